// linalg/parallel.hpp — the products and sums of a time step that run on several
// threads, written so that their results do not depend on the number of threads, bit
// for bit (the thread count: linalg/threads.hpp).
//
// Two rules make that so.
//  1. Every entry of a result is computed by one thread, with the operations in the
//     order they have on one thread.  A product with a sparse matrix is therefore a
//     gather, one dot product per entry of the result over a compressed column: y = Mᵀx
//     reads column i of M for y_i, and no two threads write the same entry.  S x for a
//     symmetric S is Sᵀx (its columns are its rows); B x for a rectangular B is (Bᵀ)ᵀx
//     with Bᵀ kept in compressed columns beside B (transposed()).  Eigen's own M x on
//     column storage is a scatter, y_i += M_ij x_j column after column, which threads
//     could only split with a copy of y each and a sum of the copies.  The gather adds
//     y_i's terms in the same order (j increasing): (Bᵀ)ᵀx is Eigen's B x bit for bit,
//     and Sᵀx is S x when S is symmetric to the last bit, as the kernel's mass and step
//     matrices are made (mass/mixed.cpp, qp/condensation.cpp).
//  2. A sum over a vector (a dot product, a norm) is cut into blocks of kBlock entries —
//     a length that does not depend on the thread count — each block summed by one
//     thread, and the block sums added in order by one thread.
// Loops with less than kParallelWork entries to read stay on one thread, since a
// parallel region costs microseconds; by the two rules that changes no result either.
// The sparse triangular solves of a supernodal Cholesky factor follow the same rule by
// another route: each unknown waits for the ones before it, but two disjoint subtrees of
// the elimination tree do not wait for each other (linalg/supernodal_solve.hpp).
#pragma once

#include <Eigen/Core>
#include <algorithm>
#include <functional>
#include <vector>

#include "cdyn/base/sparse.hpp"

namespace cdyn {

// The block length of rule 2 (8 KiB of doubles: a block is worth a thread's start).
constexpr int kBlock = 1024;
// Below this many entries read, a loop runs on one thread.  Eigen's threshold for its
// own threaded sparse products, found on 2D and 3D Poisson matrices.
constexpr long kParallelWork = 20000;

// The number of blocks of kBlock entries (the last one shorter) that cover n entries.
inline int block_count(long n) { return static_cast<int>((n + kBlock - 1) / kBlock); }

// y = Mᵀ x (x of M.rows() entries, y of M.cols()): one dot product per column of M.
void transpose_times(const SparseMatrix& M, const double* x, double* y);
Eigen::VectorXd transpose_times(const SparseMatrix& M, const Eigen::VectorXd& x);

// S x for a symmetric S stored whole (both triangles): Sᵀx.
Eigen::VectorXd symmetric_times(const SparseMatrix& S, const Eigen::VectorXd& x);

// xᵀy, summed by blocks (rule 2).
double dot(long n, const double* x, const double* y);
double dot(const Eigen::VectorXd& x, const Eigen::VectorXd& y);

// f(begin, end) on the blocks [k kBlock, min(n, (k + 1) kBlock)) of n entries, the blocks
// shared among the threads (one thread below kParallelWork entries).
void for_each_block(long n, const std::function<void(long, long)>& f);

// An entry-by-entry expression of vectors (sums, scalings, quotients; no products),
// evaluated by blocks shared among the threads: each entry is computed as Eigen computes
// it, so the same bits on any number of threads.  (The schemes' vector updates, one pass
// each over the unknowns, ran on the main thread alone while the other one waited.)
template <class Expression>
Eigen::VectorXd evaluated(const Eigen::MatrixBase<Expression>& e) {
  Eigen::VectorXd out(e.size());
  for_each_block(e.size(), [&](long begin, long end) { out.segment(begin, end - begin) = e.segment(begin, end - begin); });
  return out;
}

// The i < n with p(i), in increasing order, by blocks of kBlock shared among the threads:
// each block counts its indices, then writes them from its offset, so the list is the
// same on any number of threads.
template <class Predicate>
std::vector<int> indices_where(int n, Predicate p) {
  const int blocks = block_count(n);
  const bool threaded = 4L * n >= kParallelWork;
  std::vector<int> offset(blocks + 1, 0);
#pragma omp parallel for schedule(static) if (threaded)
  for (int b = 0; b < blocks; ++b) {
    const int end = std::min(n, (b + 1) * kBlock);
    int count = 0;
    for (int i = b * kBlock; i < end; ++i) count += p(i) ? 1 : 0;
    offset[b + 1] = count;
  }
  for (int b = 0; b < blocks; ++b) offset[b + 1] += offset[b];
  std::vector<int> list(offset[blocks]);
#pragma omp parallel for schedule(static) if (threaded)
  for (int b = 0; b < blocks; ++b) {
    const int end = std::min(n, (b + 1) * kBlock);
    int k = offset[b];
    for (int i = b * kBlock; i < end; ++i)
      if (p(i)) list[k++] = i;
  }
  return list;
}

// max_i |x_i| / scale_i (|x_i| without a scale), NaN if an entry is NaN: a maximum is
// the same in any order, so the entries are shared among the threads.
double max_abs(const Eigen::VectorXd& x, const Eigen::VectorXd* scale = nullptr);

// Mᵀ in compressed columns: what B x is computed from (rule 1).
SparseMatrix transposed(const SparseMatrix& M);

}  // namespace cdyn
