// linalg/symmetric_gauss_seidel.hpp — the symmetric Gauss–Seidel preconditioner of linalg/masked_cg.hpp
// in a multicolour ordering, applied by Eisenstat's trick.
//
// Scaling and splitting.  With D = diag(S), Ŝ = D^{-1/2} S D^{-1/2} has a unit diagonal
// and splits as Ŝ = L̂ + L̂ᵀ − I, L̂ unit lower triangular.  Symmetric Gauss–Seidel is the
// preconditioner L̂ L̂ᵀ of Ŝ, used symmetrically: CG runs on
//     Â = L̂⁻¹ Ŝ L̂⁻ᵀ,   x̂ = L̂ᵀ D^{1/2} y,   r̂ = L̂⁻¹ D^{-1/2} r   (r = b − S y).
// Eisenstat's trick (S. C. Eisenstat, "Efficient implementation of a class of
// preconditioned conjugate gradient methods", SIAM J. Sci. Stat. Comput. 2 (1981) 1–4):
// since Ŝ = L̂ + L̂ᵀ − I,
//     Â v = t + L̂⁻¹ (v − t),   t = L̂⁻ᵀ v,
// one backward and one forward sweep and no product with S: an iteration reads S once,
// like a Jacobi-preconditioned one, and CG moves y by D^{-1/2} t.
//
// Ordering.  "Lower" is with respect to a greedy colouring of S's graph (no two coupled
// unknowns share a colour; 4 colours for the P1 vertices of a triangle mesh), colours in
// turn.  The rows of one colour depend only on earlier colours, so a sweep has no chain
// of dependent rows (in the natural order every row i waits for row i − 1), and L̂ and
// L̂ᵀ are stored apart, each row's entries to earlier and to later colours, so that the
// two sweeps together read each entry of S once (Saad, Iterative Methods for Sparse
// Linear Systems, 2nd ed., §12.4).  On the condensed P1+/P0 membrane matrix (n = 160,
// 7 000 held vertices) CG reduces the residual by 1e-12 in 17 iterations with this
// preconditioner, against 40 with Jacobi's and 14 with the natural ordering's sweeps.
//
// Threads.  The rows of one colour are shared among the threads, the colours taken in
// turn; each row is computed by one thread as on one thread, so the sweeps' results do not
// depend on the thread count (linalg/parallel.hpp).
//
// Held rows.  Every operation takes a held set A (the active set of a PDAS iterate): the
// rows of A are skipped and set to 0, so everything acts on S_II (I = the complement of
// A) without forming it — the entries to columns of A meet zeros.
#pragma once

#include <vector>

#include "cdyn/base/sparse.hpp"

namespace cdyn {

class SymmetricGaussSeidel {
 public:
  // S: symmetric, full storage, compressed, positive diagonal.
  explicit SymmetricGaussSeidel(const SparseMatrix& S);

  int size() const { return static_cast<int>(sqrt_diagonal_.size()); }
  int colours() const { return static_cast<int>(colour_start_.size()) - 1; }
  const std::vector<int>& colour() const { return colour_; }  // the colour of each unknown
  const Eigen::VectorXd& sqrt_diagonal() const { return sqrt_diagonal_; }  // D^{1/2}

  // q = Â v and t = L̂⁻ᵀ v (w: work vector); returns vᵀq.
  double apply(const std::vector<char>& held, const double* v, double* t, double* w, double* q) const;

  // The free rows of a held set in sweep order, by colour: for sweeps that visit those
  // rows only, when most rows are held (their t, w, q are 0 and stay so).  From the free
  // rows listed in increasing order: O(|I|), with no pass over the held rows.
  struct FreeRows {
    std::vector<int> position;      // k: rows_[k] free, increasing within each colour
    std::vector<int> colour_start;  // position[colour_start[c] .. colour_start[c+1]) have colour c
  };
  FreeRows free_rows(const std::vector<int>& free) const;
  // apply() on the free rows alone: q_I = (Â v)_I and t_I = (L̂⁻ᵀ v)_I, with t, w, q 0
  // on the held rows on entry (left so).
  void apply(const FreeRows& free, const double* v, double* t, double* w, double* q) const;
  // CG's first residuals from a guess y, by one pass over Ŝ's two triangles instead of a
  // product with S and a forward sweep: with g = D^{-1/2} b and ŷ = D^{1/2} y (0 on A),
  //     r = b − S̃y = D^{1/2} (g − Ŝŷ),   r̂ = L̂⁻¹ D^{-1/2} r = L̂⁻¹ (g − (L̂ᵀ − I) ŷ) − ŷ,
  // since Ŝ = L̂ + L̂ᵀ − I: a row gathers ŷ over both triangles and u = L̂⁻¹ (g − (L̂ᵀ − I)ŷ)
  // over the lower one, colour by colour (Eisenstat's trick applied to the residual).
  // r, r̂ and u (work) are 0 on A.
  void first_residual(const std::vector<char>& held, const double* b, const double* y_hat, double* u, double* r_hat,
                      double* r) const;
  // out = L̂ in (in_A = 0 assumed).
  void multiply_lower(const std::vector<char>& held, const double* in, double* out) const;
  // first_residual() on the free rows alone, with u, r̂ and r 0 on the held rows on entry
  // (left so) and ŷ 0 there.
  void first_residual(const FreeRows& free, const double* b, const double* y_hat, double* u, double* r_hat,
                      double* r) const;
  // multiply_lower() on the free rows alone: out_I, with in 0 on the held rows; the held
  // rows of out are not written.
  void multiply_lower(const FreeRows& free, const double* in, double* out) const;

 private:
  bool threaded() const;  // whether a sweep is long enough for threads (linalg/parallel.hpp)
  void first_residual_row(int k, const double* b, const double* y_hat, double* u, double* r_hat, double* r) const;

  // One strict triangle of Ŝ: for each row in sweep order (rows_), its entries to
  // earlier colours (lower_) or to later ones (upper_), compressed.
  struct Triangle {
    std::vector<int> start, column;
    std::vector<double> value;
  };
  Eigen::VectorXd sqrt_diagonal_;
  std::vector<int> colour_;
  std::vector<int> rows_;          // the unknowns sorted by colour
  std::vector<int> position_;      // position_[rows_[k]] = k
  std::vector<int> colour_start_;  // rows_[colour_start_[c] .. colour_start_[c+1]) have colour c
  Triangle lower_, upper_;
};

}  // namespace cdyn
