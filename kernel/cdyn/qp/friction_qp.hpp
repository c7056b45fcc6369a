// friction_qp.hpp — the step problem of nodal contact with friction, and its residual.
//
// With Tresca friction (a given threshold s_i per contact node) the step of an implicit
// scheme is the convex problem
//
//     min_X  ½ XᵀSX − rᵀX + Σ_i s_i |X_T,i − X̂_T,i|    subject to  lower ≤ X ≤ upper,   (FQP)
//
// X_T,i the tangential unknowns of contact node i (one in the plane, two in space:
// problems/nodal_rotation.hpp) and X̂_T,i their values at the start of the step, so
// that X_T − X̂_T is the slip of the step, the slip velocity times dt (the seed: a nodal
// friction condition written on the velocity, "stable when a central difference scheme
// is also used").  The normal unknown carries the Signorini bound as in qp/bound_qp.hpp.
// Coulomb friction takes s_i = μ_i λ_N,i, λ_N,i ≥ 0 the node's normal reaction: a
// quasi-variational problem, solved as a fixed point on the threshold.
//
// KKT conditions.  With the reaction λ = S X − r, the bound conditions of
// qp/bound_qp.hpp hold on every unknown that is not tangential, and on the tangential
// ones λ_T ∈ −s ∂|·|(X_T − X̂_T):  |λ_T| ≤ s, and λ_T = −s (X_T − X̂_T)/|X_T − X̂_T|
// where the node slips.  In the proximal form (Alart–Curnier; Hüeber, Stadler,
// Wohlmuth, SIAM J. Sci. Comput. 30 (2008)) the tangential condition is
//
//     d = shrink(d − λ_T/D, s/D),   d = X_T − X̂_T,   shrink(y, τ) = max(0, 1 − τ/|y|) y,
//
// D = diag(S) as in qp/kkt.hpp.  friction_residual() is therefore qp/kkt.hpp's natural
// residual with the tangential entries replaced by d − shrink(d − λ_T/D, s/D): one
// number for stationarity, feasibility, complementarity and the friction law, in units
// of X, and the same measure for every solver (qp/friction_solvers.hpp).  With s = 0
// it is the frictionless residual; with s → ∞ the tangential entries are d (bonded).
#pragma once

#include <vector>

#include <Eigen/Core>

#include "cdyn/qp/bound_qp.hpp"

namespace cdyn {

// One contact node of (FQP): its normal unknown (bounded), its tangential unknowns
// (unbounded), and the friction law: Tresca with the threshold s, or Coulomb with the
// coefficient μ (s = μ λ_N).
struct FrictionContact {
  int normal = -1;
  std::vector<int> tangential;
  bool coulomb = false;
  double mu = 0.0;         // Coulomb
  double threshold = 0.0;  // Tresca: s ≥ 0 (a force: the nodal share of a traction bound)
};

// The friction terms of (FQP), beside its BoundQP (S, r and the bounds; no bound on a
// tangential unknown).
struct FrictionConditions {
  std::vector<FrictionContact> contacts;
  Eigen::VectorXd reference;           // X̂: the unknowns at the start of the step (size n; tangential entries used)
};

// What a contact node does at a solution: its normal bound inactive (open), or active
// and sticking (X_T = X̂_T, |λ_T| ≤ s), or slipping (|λ_T| = s).
enum class ContactStatus { Open = 0, Stick = 1, Slip = 2 };

struct FrictionResult {
  QPResult qp;                         // X, λ = S X − r (the tangential force included), iterations, seconds
  std::vector<ContactStatus> status;   // per contact
  Eigen::VectorXd threshold;           // s_i the solution satisfies (Coulomb: μ λ_N)
  double residual = 0.0;               // friction_residual
  bool converged = false;
  int fallbacks = 0;                   // semismooth Newton: projected Gauss–Seidel solves after a cycle
  // The tangential sets of the solution, a warm start for the next step: per contact,
  // sticking or not, and the slip direction σ = y/|y| on the tangential unknowns of the
  // slipping ones (0 elsewhere; size n).
  std::vector<char> stick;
  Eigen::VectorXd direction;
};

// Whether a contact has two tangential unknowns (a problem in space).
bool in_space(const FrictionConditions& f);

// The tangential sets of (X, λ) by the semismooth Newton method's rule (Hüeber, Stadler,
// Wohlmuth 2008): per contact y = d − λ_T/D_k, d = X_T − X̂_T and D_k the smallest of D
// on its tangential unknowns; sticking where |y| ≤ s_k/D_k, else slipping along
// σ = y/|y|.  stick has one entry per contact, direction σ on the tangential unknowns of
// the slipping ones (0 elsewhere, size n); slip_length, when given, the length of the
// slip the rule predicts, |shrink(y, s_k/D_k)| = |y| − s_k/D_k (0 where sticking).
void slip_sets(const FrictionConditions& f, const Eigen::VectorXd& X, const Eigen::VectorXd& reaction,
               const Eigen::VectorXd& s, const Eigen::VectorXd& D, std::vector<char>& stick,
               Eigen::VectorXd& direction, std::vector<double>* slip_length = nullptr);

// The threshold of each contact: s, or μ max(λ_N, 0) from the reaction λ.
Eigen::VectorXd friction_thresholds(const FrictionConditions& f, const Eigen::VectorXd& reaction);

// ‖F(X)‖_∞ / max(‖X‖_∞, ‖D⁻¹r‖_∞) with F the natural residual above, thresholds s.
double friction_residual(const BoundQP& qp, const FrictionConditions& f, const Eigen::VectorXd& X, const Eigen::VectorXd& reaction,
                         const Eigen::VectorXd& threshold, const Eigen::VectorXd& D);

// Status of each contact at (X, λ): open when λ_N ≤ 0 and the normal bound is not
// reached, stick when every |X_T − X̂_T| is 0, slip otherwise.
std::vector<ContactStatus> contact_status(const BoundQP& qp, const FrictionConditions& f, const Eigen::VectorXd& X,
                                          const Eigen::VectorXd& reaction);

// Σ_i s_i |X_T,i − X̂_T,i|: the work the friction forces take over the step's slip (≥ 0),
// over the contacts `counted` marks (all when empty: a share of the QP counts those its
// rank owns, StepSolver::owns).
double friction_work(const FrictionConditions& f, const Eigen::VectorXd& X, const Eigen::VectorXd& threshold,
                     const std::vector<char>& counted = {});

// InputError for an index out of range or used twice, a tangential unknown with a
// bound, a negative threshold or μ, or a reference of the wrong size.
void check_friction_qp(const BoundQP& qp, const FrictionConditions& f);

}  // namespace cdyn
