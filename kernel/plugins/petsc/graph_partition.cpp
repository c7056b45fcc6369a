// kernel/plugins/petsc/graph_partition.cpp — PT-Scotch's parts of a graph; see
// kernel/plugins/petsc/graph_partition.hpp.
#include "graph_partition.hpp"

#include <petscmat.h>

#include <algorithm>
#include <cstdlib>

#include "distributed_qp.hpp"

namespace cdyn::petsc {

namespace {

// The first of the graph's n vertices in rank k's block of rows (p ranks).
int block_start(int n, int k, int p) { return static_cast<int>(static_cast<long long>(n) * k / p); }

}  // namespace

std::vector<int> partition_graph(const std::vector<int>& offset, const std::vector<int>& neighbour) {
  const MPI_Comm world = PETSC_COMM_WORLD;
  const int n = static_cast<int>(offset.size()) - 1;
  int me = 0, p = 1;
  MPI_Comm_rank(world, &me), MPI_Comm_size(world, &p);
  if (p == 1) return std::vector<int>(n, 0);
  // this rank's block of rows of the adjacency matrix (MatCreateMPIAdj takes the arrays
  // over: allocated by PETSc, freed with the matrix)
  const int begin = block_start(n, me, p), end = block_start(n, me + 1, p), m = end - begin;
  PetscInt *i = nullptr, *j = nullptr;
  check(PetscMalloc1(m + 1, &i), "PetscMalloc1");
  check(PetscMalloc1(offset[end] - offset[begin], &j), "PetscMalloc1");
  for (int r = 0; r <= m; ++r) i[r] = offset[begin + r] - offset[begin];
  std::copy(neighbour.begin() + offset[begin], neighbour.begin() + offset[end], j);
  Owned<Mat, MatDestroy> adjacency;
  check(MatCreateMPIAdj(world, m, n, i, j, nullptr, adjacency.out()), "MatCreateMPIAdj");
  Owned<MatPartitioning, MatPartitioningDestroy> part;
  Owned<IS, ISDestroy> rank_of;
  check(MatPartitioningCreate(world, part.out()), "MatPartitioningCreate");
  check(MatPartitioningSetAdjacency(part, adjacency), "MatPartitioningSetAdjacency");
  check(MatPartitioningSetType(part, MATPARTITIONINGPTSCOTCH), "MatPartitioningSetType");
  check(MatPartitioningSetFromOptions(part), "MatPartitioningSetFromOptions");
  // PT-Scotch on one thread a process unless the user says otherwise: its threads make
  // the parts change from run to run, and with them the numbers of two runs of a scene
  // (measured on the cube at 16³ on four ranks: 564, 572, 564, 565 interface vertices in
  // four runs; on one thread 606 in each)
  setenv("SCOTCH_PTHREAD_NUMBER", "1", /*overwrite=*/0);
  check(MatPartitioningApply(part, rank_of.out()), "MatPartitioningApply");
  const PetscInt* mine = nullptr;
  check(ISGetIndices(rank_of, &mine), "ISGetIndices");
  const std::vector<int> local(mine, mine + m);
  check(ISRestoreIndices(rank_of, &mine), "ISRestoreIndices");
  // every rank's block, on every rank
  std::vector<int> counts(p), first(p);
  for (int k = 0; k < p; ++k) first[k] = block_start(n, k, p), counts[k] = block_start(n, k + 1, p) - first[k];
  std::vector<int> all(n);
  MPI_Allgatherv(local.data(), m, MPI_INT, all.data(), counts.data(), first.data(), MPI_INT, world);
  return all;
}

}  // namespace cdyn::petsc
