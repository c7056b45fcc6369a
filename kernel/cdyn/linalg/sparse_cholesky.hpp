// sparse_cholesky.hpp — a sparse Cholesky factorization P S Pᵀ = L Lᵀ of a symmetric
// positive definite matrix through CHOLMOD's C API, kept across time steps.
//
// The Eigen matrix is read in place (no copy; lower triangle used).  analyze() once per
// pattern (fill-reducing ordering, pattern of L), factorize() per new values (supernodal
// when CHOLMOD finds it worth it), and between factorizations replace_by_identity() /
// restore() change one row and column of the factorized matrix (cholmod_rowdel /
// cholmod_rowadd: a rank-2 modification of L, Davis & Hager 2005) without refactorizing:
// what an active-set method needs when a few constraints switch.  A supernodal factor
// with narrow supernodes (a 2D mesh's) is solved by the kernel's own sweeps, by subtrees
// of its elimination tree on the kernel's threads (linalg/supernodal_solve.hpp); one with
// most entries in wide supernodes (3D), and a simplicial one (small, or after row
// updates), by CHOLMOD's solve.
#pragma once

#include <Eigen/Core>
#include <memory>
#include <string>
#include <vector>

#include "cdyn/base/sparse.hpp"

namespace cdyn {

class SparseCholesky {
 public:
  SparseCholesky();
  ~SparseCholesky();
  SparseCholesky(const SparseCholesky&) = delete;
  SparseCholesky& operator=(const SparseCholesky&) = delete;

  void analyze(const SparseMatrix& S);
  // The analysis with a given fill-reducing order (ordering[k] = the unknown eliminated
  // k-th; CHOLMOD still postorders it): no minimum degree search.  For a principal
  // submatrix whose parent's ordering is known, the induced order is nearly as good.
  void analyze(const SparseMatrix& S, const std::vector<int>& ordering);
  // The analysis's order (ordering[k] = the unknown eliminated k-th).  Requires an analysis.
  std::vector<int> ordering() const;
  bool analyzed_for(const SparseMatrix& S) const;  // same pattern as the last analyze()
  // Numeric factorization of S (pattern as analysed).  Returns −1, or the unknown at
  // which S was found not positive definite (the factor is then dropped).
  int factorize(const SparseMatrix& S);
  bool factorized() const;
  Eigen::VectorXd solve(const Eigen::VectorXd& b) const;
  // Row and column i of the factorized matrix become those of the identity.
  void replace_by_identity(int i);
  // Row and column i, identity before, become column i of S restricted to the rows with
  // keep[row] != 0 (keep[i] != 0).  Returns false if the result is not positive definite.
  bool restore(int i, const SparseMatrix& S, const std::vector<char>& keep);
  // The two halves of solve() with an LLᵀ factor — the factorized matrix's own, not one
  // after row updates (CHOLMOD makes those LDLᵀ) — v ← L⁻¹ P v and v ← Pᵀ L⁻ᵀ v, and
  // the first for a unit vector on its elimination-tree path alone, z = L⁻¹ P e_i (its
  // entries there: rows of L, increasing, and values; returns the flops): what a solve
  // with a few rows and columns of the matrix eliminated is made of
  // (qp/pdas/capacitance_solve.hpp).
  bool has_halves() const;
  void forward(Eigen::VectorXd& v) const;
  void backward(Eigen::VectorXd& v) const;
  double unit_forward(int i, std::vector<int>& rows, std::vector<double>& values) const;
  // A copy of the current factor kept aside, and the factor made a copy of it again
  // later: an active-set method returns to S's own factor when the last constraint is
  // released, for the price of a copy instead of a factorization.  Row updates and
  // factorizations leave the kept copy as it is; an analysis or forget_kept() drops it.
  void keep();
  bool has_kept() const;
  void use_kept();
  void forget_kept();
  // Floating-point operations of the last replace_by_identity() or restore(), as CHOLMOD
  // counts them (cholmod_common::modfl): what an active-set method weighs against a CG solve.
  double modification_flops() const;
  // Floating-point operations of a numeric factorization of the analysed pattern
  // (cholmod_common::fl of the last analyze()).
  double factorization_flops() const;
  // Floating-point operations of a solve with the factor: a multiply and an add per entry
  // of L in each of the forward and the backward sweep, 4 lnz (lnz: the analysis's count).
  double solve_flops() const;

 private:
  void analyze_with(const SparseMatrix& S, const std::vector<int>* ordering);
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

// Checks that S is positive definite (one CHOLMOD factorization); throws NumericalError
// naming `what` and the failing leading minor.
void check_positive_definite(const SparseMatrix& S, const std::string& what = "S");

}  // namespace cdyn
