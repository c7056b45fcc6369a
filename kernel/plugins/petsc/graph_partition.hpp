// kernel/plugins/petsc/graph_partition.hpp — a graph dealt out to the ranks by PT-Scotch,
// through PETSc's MatPartitioning: the cells of a run on subdomains (the dual graph of
// mesh/sub_mesh.hpp's cell_graph), each rank's part with few cut edges, the parts about
// equal in size.
#pragma once

#include <vector>

namespace cdyn::petsc {

// The rank of each vertex of the graph whose vertex v has the neighbours
// neighbour[offset[v]] … neighbour[offset[v + 1] − 1] (no v itself), given whole on
// every rank; the same answer on every rank, and at every run (PT-Scotch on one thread).
// Collective; all 0 on one rank.
std::vector<int> partition_graph(const std::vector<int>& offset, const std::vector<int>& neighbour);

}  // namespace cdyn::petsc
