// full_step.hpp — the massless part of a full-step state, from the static problem the
// seed writes as eq. (14).
//
// Under condition (12) the semi-discrete problem's massless displacements F = Ker B are
// not integrated in time: at every t they minimize the potential energy over the fibre
// of the massful part (Theorem 1, eqs. (13)–(15)),
//     U(t) = argmin { ½ WᵀAW − L(t)ᵀW :  B W = B U(t),  W ∈ K̄^h }.               (14)
// A scheme that constrains the half step (midpoint) or extrapolates U^{n+1} =
// 2U^{n+½} − Uⁿ leaves the Ker B part of U^{n+1} to the extrapolation, which can put a
// full-step state below the obstacle.  Since the next step reads Uⁿ only through
// B Uⁿ (M Uⁿ = BᵀC⁻¹B Uⁿ and B(U^{n+1} − Uⁿ)), replacing it by the solution W of (14)
// changes no massful quantity: the dynamics are the same, and the state, the probes,
// the energy J = ½VᵀCV + Ψ and the violation describe a physical displacement.
//
// With the local basis of Ker B (mass/massless_modes.hpp), W = U + Z d and (14) is the
// bound-constrained QP on d
//     min ½ dᵀ(ZᵀAZ)d − (Zᵀ(L − AU))ᵀd,   lower − U ≤ d ≤ upper − U on the pinned unknowns,
// whose matrix ZᵀAZ is fixed for a run (its factorization is kept) and whose solve is
// warm-started from the last step: one more step QP per step, usually one
// forward/back solve.  For P1+/P0 it lives on the vertex values (the bubbles keep the
// cell means B W = B U).
//
// P2/P1 and P1+/P1 have no such basis (their Ker B is not spanned by cell-local
// functions).  There (14) is solved in W = U + D by the method of multipliers
// (Hestenes 1969, Powell 1969; Bertsekas, "Constrained optimization and Lagrange
// multiplier methods", 1982, ch. 2), the constraint B D = 0 penalized in the C⁻¹ norm
// of the mass: each iteration is the bound-constrained QP
//     min ½ Dᵀ(A + ρ Bᵀ C⁻¹ B) D − (L − AU + Bᵀμ)ᵀ D,   lower − U ≤ D ≤ upper − U,
// whose matrix is a step matrix A + ρ M in saddle form (qp/bound_qp.hpp), followed by
// μ ← μ − ρ C⁻¹ B D (C⁻¹B and Bᵀ by the mass model's velocity() and momentum()).  On a
// fixed active set the error in μ contracts by 1/(1 + ρ θ) per iteration, θ the
// generalized eigenvalues of (B A⁻¹ Bᵀ, C), all ≥ 1/ω²_max (ω_max the highest free
// frequency): ρ = 10³ ω²_max makes every iteration gain three digits.
// The multiplier is warm-started from the last call, the saddle matrix is factorized
// once per active set; measured cost in docs/schemes.md.
#pragma once

#include <memory>
#include <optional>

#include "cdyn/mass/massless_modes.hpp"
#include "cdyn/problems/constrained_problem.hpp"
#include "cdyn/qp/step_solver.hpp"
#include "cdyn/schemes/scheme_memory.hpp"

namespace cdyn {

class FullStepReconstruction {
 public:
  // The reconstruction of p's full steps, solved to `tol` (kkt_residual).
  FullStepReconstruction(const ConstrainedProblem& p, double tol);

  // How (14) is solved: by the local basis of Ker B (mass/massless_modes.hpp), which
  // must move every constrained unknown; by multipliers where Ker B has no local basis
  // (P2/P1, P1+/P1); or not at all (a local basis that leaves a constrained unknown
  // with mass: condition (12) fails in local form).
  enum class Method { None, LocalBasis, Multipliers };
  // How the local basis's QP is solved by pdas (the multipliers' saddle form keeps its LU):
  //   Mixed   the factor of ZᵀAZ, and CG while the active set moves (pdas's default);
  //   CgOnly  CG alone, no factor (the step's solver.linear = "cg": in 3D the factor of
  //           ZᵀAZ fills, 280 MB of a 1 GB run at 300k unknowns);
  //   Direct  the factor and its row updates only, every solve exact to round-off: for a
  //           scheme that reconstructs nearly the same state several times a step with
  //           the active set of the last (discrete_gradient's energy iteration), where a
  //           solve with the factor brought to that set costs less than CG's pair.
  enum class Solves { Mixed, CgOnly, Direct };
  // `multipliers`: use the method of multipliers even where a local basis exists (to
  // compare the two).
  // step: the scheme's step solver, when it must make this QP's solver too (a share's:
  // StepSolver::make_companion; the QP's unknowns, d, are the pinned ones); else nullptr.
  FullStepReconstruction(const ConstrainedProblem& p, double tol, bool multipliers, Solves solves = Solves::Mixed,
                         const StepSolver* step = nullptr);

  Method method() const { return method_; }
  bool available() const { return method_ != Method::None; }
  // Whether it has anything to do: false when Ker B = {0} (then U is already unique).
  bool needed() const { return method_ == Method::Multipliers || (available() && modes_.Z.cols() > 0); }

  // The solution W of (14) for the massful part of U at time t; the QP's KKT residual
  // (by multipliers: the larger of it and the fibre's residual |C⁻¹B(W − U)|∞ / |W|∞)
  // goes to *kkt when given.  Returns U itself when Ker B = {0}.  Requires available().
  // NumericalError when the multipliers do not bring B W to B U: (14) has no solution.
  Eigen::VectorXd operator()(const Eigen::VectorXd& U, double t, double* kkt = nullptr);

  // The local basis's QP at the last call: its solution, reaction, right-hand side and
  // held unknowns (empty y by multipliers, or before a call).
  struct Point {
    Eigen::VectorXd y, reaction, r;
    std::vector<int> active;
  };
  Point last_point() const;
  // (14) for U = U_a + θ (U_b − U_a), U_a and U_b the inputs of two points: the QP's
  // right-hand side and bounds are affine in U, hence on an active set its solution and
  // reaction too, and the interpolate of two points solved on the same set solves it
  // wherever it keeps that set and passes the solvers' own test (kkt_residual ≤ tol).
  // Returns W (its KKT residual to *kkt, the interpolated point to *at), or nothing when
  // the test fails or (14) is solved by multipliers.
  std::optional<Eigen::VectorXd> on_line(const Point& a, const Point& b, double theta, const Eigen::VectorXd& U,
                                         double t, double* kkt = nullptr, Point* at = nullptr);

  // Method of multipliers iterations (step QPs) of the last call.
  int iterations() const { return iterations_; }
  // What the last call (of operator() or on_line) cost: its seconds, and the
  // iterations of its QP solves (all of them by multipliers; none on a line).
  struct Cost {
    double seconds = 0.0;
    int qp_iterations = 0;
  };
  const Cost& last_cost() const { return cost_; }

  // Its warm start into a scheme's memory, and back (clearing its solver's caches:
  // schemes/scheme_memory.hpp).
  void store(SchemeMemory& m) const;
  void restore(const SchemeMemory& m);

 private:
  // The saddle-form QP of the multipliers (made on the first call: deciding the method
  // needs only B, so that asking needed() costs no copy of A).
  void prepare_multipliers();
  // The QP's bounds lower − U ≤ d ≤ upper − U at K̄^h(t), d_k moving unknowns[k].
  void set_bounds(const Eigen::VectorXd& U, const std::vector<int>& unknowns, double t);
  Eigen::VectorXd by_local_basis(const Eigen::VectorXd& U, double t, double* kkt);
  Eigen::VectorXd by_multipliers(const Eigen::VectorXd& U, double t, double* kkt);

  Method method_ = Method::None;
  const ConstrainedProblem& p_;
  double tol_;
  MasslessModes modes_;
  Eigen::VectorXd D_;  // scaling_diagonal of the QP, diag(ZᵀAZ): the PDAS rule's (qp/kkt.hpp)
  SparseMatrix Zt_;  // Zᵀ in compressed columns: Z d as a gather, threaded (linalg/parallel.hpp)
  BoundQP qp_;
  std::unique_ptr<StepSolver> solver_;
  QPResult last_;
  bool has_last_ = false;
  Eigen::VectorXd SX_;  // S X at the last solution: the warm start's reaction for a new r
  // The method of multipliers: ρ and the multiplier μ of B D = 0 (C⁻¹B and Bᵀ are the
  // mass model's velocity() and momentum()).
  double rho_ = 0.0;
  Eigen::VectorXd mu_;
  std::vector<int> all_unknowns_;
  Eigen::VectorXd A_diagonal_;
  int iterations_ = 0;
  Cost cost_;
};

}  // namespace cdyn
