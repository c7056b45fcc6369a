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

  // Whether Ker B has a local basis (mass/massless_modes.hpp) that moves every
  // constrained unknown; not for P2/P1, P1+/P1.
  bool available() const { return available_; }
  // Whether it has anything to do: false when Ker B = {0} (then U is already unique).
  bool needed() const { return available_ && modes_.Z.cols() > 0; }

  // The solution W of (14) for the massful part of U at time t; the QP's KKT residual
  // goes to *kkt when given.  Returns U itself when Ker B = {0}.  Requires available().
  Eigen::VectorXd operator()(const Eigen::VectorXd& U, double t, double* kkt = nullptr);

  // Its warm start into a scheme's memory, and back (clearing its solver's caches:
  // schemes/scheme_memory.hpp).
  void store(SchemeMemory& m) const;
  void restore(const SchemeMemory& m);

 private:
  bool available_ = false;
  const ConstrainedProblem& p_;
  MasslessModes modes_;
  SparseMatrix Zt_;  // Zᵀ in compressed columns: Z d as a gather, threaded (linalg/parallel.hpp)
  BoundQP qp_;
  std::unique_ptr<StepSolver> solver_;
  QPResult last_;
  bool has_last_ = false;
};

}  // namespace cdyn
