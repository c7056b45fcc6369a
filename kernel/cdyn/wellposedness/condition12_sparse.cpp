// condition12_sparse.cpp — β of condition (12) by certified shift-and-invert Lanczos on
// the Gram form of G P Gᵀ.
#include "cdyn/wellposedness/condition12_sparse.hpp"

#include <cmath>
#include <limits>
#include <random>
#include <string>

#include "cdyn/base/error.hpp"
#include "cdyn/wellposedness/condition12.hpp"
#include "cdyn/wellposedness/lanczos.hpp"
#include "cdyn/wellposedness/row_basis.hpp"
#include "cdyn/wellposedness/shifted_gram.hpp"

namespace cdyn {

namespace {

// Lanczos steps per shift.  Once the shift sits within a tenth of the gap below β², a
// run converges in ~10 steps; the first shift (σ₀ < 0, far from a clustered β²) only
// needs a rough estimate to move to.
constexpr int kStepsPerShift = 40;
constexpr int kMaxShifts = 12;         // factorizations, failed ones included
constexpr double kFirstShift = 1e-2;   // σ₀ = −kFirstShift · max_i |G_i|²
// Relative accuracy asked of β² (so ~5e-13 on β): the eigenvalue of T = (GPGᵀ − σ)⁻¹ to
// residual r gives β² to r (β² − σ)², see converged() below.
constexpr double kEigenTolerance = 1e-12;

}  // namespace

WellPosedness condition12_sparse(const SparseMatrix& B_in, const SparseMatrix& G) {
  const int nW = static_cast<int>(B_in.cols()), nH = static_cast<int>(B_in.rows()), ng = static_cast<int>(G.rows());
  if (G.cols() != nW)
    throw InputError("condition (12): G has " + std::to_string(G.cols()) + " columns, B has " + std::to_string(nW));
  WellPosedness r;
  r.method = "sparse";
  r.n_W = nW;
  r.n_H = nH;
  r.n_g = ng;

  const SparseMatrix B = rows_scaled_to_unit_max(B_in);
  const RowBasis basis = row_basis(B);
  r.dim_ker_B = nW - basis.rank;
  if (ng == 0) {
    r.beta = std::numeric_limits<double>::infinity();
    r.satisfied = true;
    return r;
  }
  if (r.dim_ker_B < ng) {
    r.beta = 0.0;  // rank(G Z) ≤ dim Ker B < N_g
    return r;
  }
  SparseMatrix Br = B;
  if (static_cast<int>(basis.rows.size()) < nH) {  // drop the dependent rows: same kernel
    SparseMatrix select(basis.rank, nH);
    std::vector<Eigen::Triplet<double>> t;
    for (int k = 0; k < basis.rank; ++k) t.emplace_back(k, basis.rows[k], 1.0);
    select.setFromTriplets(t.begin(), t.end());
    Br = select * B;
  }

  // The scale of G P Gᵀ's spectrum: the largest diagonal entry of G Gᵀ (1 for the
  // vertex constraints of vertex_constraint_matrix).
  const double scale = (SparseMatrix(G.cwiseProduct(G)) * Eigen::VectorXd::Ones(nW)).maxCoeff();
  if (!(scale > 0.0)) {  // G = 0: G Z = 0
    r.beta = 0.0;
    return r;
  }
  ShiftedGram gram(Br, G);
  double sigma = -kFirstShift * scale;
  if (!gram.factorize(sigma))
    throw NumericalError("condition (12): the Gram matrix [B; G][B; G]ᵀ + σ₀E is not positive definite although B "
                         "has independent rows (the rank test of B was wrong)");

  // A fixed pseudo-random start: deterministic, and with a component along every
  // eigenvector in practice (a structured start like (1, ..., 1) can miss one by symmetry).
  Eigen::VectorXd start(ng);
  std::mt19937 rng(12);
  std::uniform_real_distribution<double> uniform(-1.0, 1.0);
  for (int i = 0; i < ng; ++i) start[i] = uniform(rng);

  const auto T = [&](const Eigen::VectorXd& q) { return gram.solve(q); };
  LanczosPair pair;
  for (;;) {
    // The Ritz value τ of T approximates 1/(β² − σ), so θ = σ + 1/τ ≥ β² (Ritz values lie
    // inside the spectrum), and a residual r moves θ by about r (θ − σ)².
    const double shift = sigma;
    const auto converged = [&](const LanczosPair& p) {
      const double theta = shift + 1.0 / p.value;
      const double gap = theta - shift;
      return p.residual / p.value * gap <= kEigenTolerance * std::max(theta, gap);
    };
    pair = lanczos_largest(T, start, kStepsPerShift, converged);
    const double theta = sigma + 1.0 / pair.value;
    if (converged(pair)) break;
    if (gram.factorizations() >= kMaxShifts)
      throw NumericalError("condition (12): the eigensolver did not converge in " + std::to_string(kMaxShifts) +
                           " shifts");
    // Next shift: the lower end of the Ritz value's inclusion interval (an eigenvalue of
    // T lies within r of τ), but at least halfway from σ to θ, so that every shift
    // gains.  A failed factorization means β² is below it: back off toward σ.
    double next = std::max(sigma + 1.0 / (pair.value + pair.residual), sigma + 0.5 * (theta - sigma));
    while (!gram.factorize(next)) {
      if (gram.factorizations() >= kMaxShifts)
        throw NumericalError("condition (12): no certified shift found in " + std::to_string(kMaxShifts) +
                             " factorizations");
      next = sigma + 0.25 * (next - sigma);
    }
    sigma = next;
    start = pair.vector;
  }
  // β unsquared: one more inverse-iteration step, Q = T y and W = P Gᵀ Q.
  Eigen::VectorXd W;
  const Eigen::VectorXd Q = gram.solve(pair.vector, &W);
  r.beta = W.norm() / Q.norm();
  r.satisfied = r.beta > kBetaTolerance;
  r.factorizations = gram.factorizations();
  r.solves = gram.solves();
  return r;
}

}  // namespace cdyn
