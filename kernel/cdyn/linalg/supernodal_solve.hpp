// supernodal_solve.hpp — the forward and back solves L z = y, Lᵀ w = z with a supernodal
// Cholesky factor (CHOLMOD's layout), on several threads by subtrees of its elimination
// tree, with the same bits whatever the thread count.
//
// A supernode's column k of L has its rows among the ancestors of k in the elimination
// tree, so the unknowns of two disjoint subtrees never meet until their common
// ancestors.  The tree is cut into subtrees T_1 … T_m, each whole, and the rest R (the
// ancestors where they meet, the separators near the root in a nested-dissection-like
// order).  Forward: every T_i is swept by one thread, its updates to its own rows made
// at once and those to rows of R left; then one thread sweeps all supernodes in order,
// solving R's and making the T_i's updates to R.  A row of R thus receives its updates
// in the order of the supernodes, as in one sweep; a row of T_i receives T_i's only.
// Back: R first, in reverse order by one thread, then each T_i by its thread (it reads
// only its ancestors, all final).  Each entry's operations are those of one sweep in
// the same order, so the result does not depend on the cut or on the thread count, bit
// for bit (the rule of linalg/parallel.hpp).  CHOLMOD's own solve is one sweep on one
// thread (only the BLAS under it threads the large dense blocks); this is what lets a
// second core take half the tree.
//
// The dense blocks are plain loops: on a factor whose supernodes are narrow (a 2D mesh's)
// they beat CHOLMOD's BLAS calls (one thread, solves interleaved with CHOLMOD's: 9-point
// grids of 10⁵ and 4·10⁵ unknowns 1.28 and 1.21 times faster), on one whose entries sit
// mostly in wide supernodes (a 3D mesh's separators) the tuned BLAS is nearly twice as
// fast (27-point grids of 1.6·10⁴ and 6.9·10⁴: 0.56 and 0.53 times its speed).  Calling
// the BLAS from the sweeps for the wide ones was tried: it matched CHOLMOD in 3D, but a
// BLAS on more threads than one (OpenBLAS's default, a thread per core) threads each
// mid-sized dgemv from inside the sweeps' own threads: the solves 10 times slower, a
// step 3 times, on two cores.  So suits() sends a factor with most entries in wide
// supernodes to CHOLMOD's solve, a property of the factor and not of the thread count.
#pragma once

#include <vector>

namespace cdyn {

// A view of a supernodal factor L (CHOLMOD: super, pi, px, s, x; int indices).
// Supernode j holds columns super[j] … super[j+1] − 1; its rows are s[pi[j]] … s[pi[j+1] − 1]
// (the first ones its own columns), its values the column-major block at x + px[j] with
// pi[j+1] − pi[j] rows.
struct SupernodalFactor {
  int n = 0;
  int nsuper = 0;
  const int* super = nullptr;
  const int* pi = nullptr;
  const int* px = nullptr;
  const int* s = nullptr;
  const double* x = nullptr;
};

class SupernodalSolve {
 public:
  // Whether these sweeps suit L: at most half its entries in supernodes of 32 columns or
  // more (else CHOLMOD's solve, whose BLAS is faster on wide blocks).
  static bool suits(const SupernodalFactor& L);
  // The cut of L's tree for `threads` threads (1: one sweep), from L's pattern alone.
  SupernodalSolve(const SupernodalFactor& L, int threads);
  // x ← L⁻ᵀ L⁻¹ x, x in L's (permuted) order.  L must have the pattern it was cut from.
  void solve(const SupernodalFactor& L, double* x) const;
  // Its two halves, x ← L⁻¹ x and x ← L⁻ᵀ x (solve() is the one, then the other).
  void forward(const SupernodalFactor& L, double* x) const;
  void backward(const SupernodalFactor& L, double* x) const;
  int threads() const { return threads_; }  // as cut for (the groups may be fewer)
  // The fraction of L's entries swept by one thread (R's): what bounds the speed-up.
  double serial_fraction() const { return serial_fraction_; }
  // R's fraction plus the most loaded thread's: the sweep's estimated time against one
  // thread's, so 1 / span_fraction() is the speed-up the cut allows.
  double span_fraction() const { return span_fraction_; }

 private:
  struct Range {
    int first, last;  // the supernodes of one subtree T_i (contiguous in postorder)
  };
  std::vector<std::vector<Range>> groups_;  // the subtrees of each thread
  std::vector<int> tail_;       // tail_[j]: the first row position of supernode j in R
  std::vector<long> tail_start_;  // where supernode j's products for R's rows are kept
  long tail_entries_ = 0;
  mutable std::vector<double> tails_;  // those products, made by the subtrees' threads
  std::vector<char> in_tree_;   // supernode in some T_i
  int threads_ = 1;
  int max_rows_ = 0;            // the tallest supernode (workspace)
  double serial_fraction_ = 1.0;
  double span_fraction_ = 1.0;
};

// The forward solve of a unit vector, z = L⁻¹ e_k, on k's path alone: a column's rows
// lie among its ancestors in the elimination tree, so z is nonzero only on the supernodes
// from k's to the root (on a mesh, a few separators on the way up) and costs their
// entries alone: on the membrane's condensed P1+/P0 matrix at n = 160 (25 281 unknowns),
// 2.5e5 flops, a seventh of the forward sweep's.
// What a solve with a few rows and columns of the factorized matrix eliminated needs,
// one such column each (qp/pdas/capacitance_solve.hpp).
class SupernodalPaths {
 public:
  explicit SupernodalPaths(const SupernodalFactor& L);
  // z's entries on k's path: rows (of L, increasing) and values; returns the flops.
  double unit_forward(const SupernodalFactor& L, int k, std::vector<int>& rows, std::vector<double>& values) const;

 private:
  std::vector<int> of_column_;  // the supernode of each column
  std::vector<int> parent_;     // each supernode's parent in the tree (−1: a root)
  mutable std::vector<double> z_, E_;  // zero between calls; a supernode's updates below
};

}  // namespace cdyn
