// step_solver.hpp — what a step QP solver is, and choosing one by name.
//
// The solvers (one file each under qp/): pdas (primal-dual active set,
// Hintermüller–Ito–Kunisch 2002, the default; qp/pdas/), pgs (projected Gauss–Seidel /
// SOR), ipopt (interior point, optional at build time: CDYN_WITH_IPOPT), nlopt (L-BFGS
// with bounds, small problems; CDYN_WITH_NLOPT).  A solver sees only S (or its saddle
// form), r and the bounds (qp/bound_qp.hpp): never a scheme or a mesh.
#pragma once

#include <memory>
#include <string>
#include <vector>

#include "cdyn/qp/bound_qp.hpp"

namespace cdyn {

// One object lives across all time steps; it may cache analyses and factorizations
// of S (keyed by S's pattern and values, so a changed S is always noticed).
class StepSolver {
 public:
  virtual ~StepSolver() = default;
  virtual std::string name() const = 0;
  // Throws InputError for inconsistent data (sizes, lower > upper, NaN/Inf, a form the
  // solver does not take) and NumericalError when S is not positive definite or the
  // solver does not reach tol.  `warm_start`: a previous result (its X and active set).
  virtual QPResult solve(const BoundQP& qp, const QPResult* warm_start = nullptr) = 0;
  // Forgets what it has cached (analyses, factorizations and their updates, the CG
  // statistics that steer pdas): the next solve computes what a solver just made would,
  // bit for bit, from the same QP and warm start.  A run resumed from a checkpoint
  // starts with a new solver; the run that wrote the checkpoint clears its own there,
  // so that both go on alike (schemes/scheme_memory.hpp).
  virtual void clear() {}
  // The next solve is the last one's time step again, with another right-hand side (a
  // scheme's iteration within a step, as the discrete gradient's energy correction): a
  // solver that learns from the sequence of steps (pdas's settled active sets) does not
  // count it as a step of its own.  to_round_off: the scheme needs more of it than the
  // tolerance (an energy correction stalled on the solves' errors): a solver with a
  // factorization solves by it (pdas: its factor brought to the active set, not CG).
  virtual void next_in_same_step(bool /*to_round_off*/) {}
  // A solver of one subdomain's share of the step QP (the ranks' shares summed:
  // qp/petsc/backend.hpp) sees a matrix whose pattern is not the whole S's: the
  // scheme's condensation then takes the cells' bubbles only (qp/condensation.hpp).
  virtual bool solves_a_share() const { return false; }
  // The QP's unknowns among the problem's free unknowns (the kept ones of the scheme's
  // condensation, in order; all of them without), told by the scheme whenever it builds
  // its QP: a share's solver places them in the whole problem through them.
  virtual void set_unknowns(const std::vector<int>& /*free_unknowns*/) {}
  // For another QP a scheme solves on some of the problem's free unknowns (the full-step
  // reconstruction of eq. (14)), with these options: a share's solver makes one of its
  // kind (the ranks solve that QP together too; set_unknowns then names them); any
  // other returns nothing, and the scheme makes its own.
  virtual std::unique_ptr<StepSolver> make_companion(const QPOptions& /*options*/) const { return nullptr; }
  // How many unknowns of the whole problem these of its QP (an active set) are: a
  // share's solver counts those its rank owns and sums over the ranks (collective), so
  // that a vertex two subdomains hold is counted once; any other, their number.
  virtual int count_in_whole(const std::vector<int>& unknowns) const { return static_cast<int>(unknowns.size()); }
  // What a method around the solver (friction's semismooth Newton, qp/friction_ssn.cpp;
  // the discrete gradient's energy iteration) needs of the whole problem when the solver
  // takes a share: whether this rank counts the unknown in sums over the whole (the
  // lowest rank holding it); a vector of sums over cells (r, diag S) summed over the
  // ranks holding each unknown; a number's sum and its largest value over the ranks.
  // All but the first are collective.  Any other solver: true, x, x and x.
  virtual bool owns(int /*unknown*/) const { return true; }
  virtual Eigen::VectorXd summed(const Eigen::VectorXd& x) const { return x; }
  virtual double total(double x) const { return x; }
  virtual double largest(double x) const { return x; }
};

// name: one of step_solver_names(); anything else is an InputError.
std::unique_ptr<StepSolver> make_step_solver(const std::string& name, const QPOptions& options = {});

// The solvers this build has: "pdas", "pgs", and "ipopt", "nlopt" when built with them.
std::vector<std::string> step_solver_names();

}  // namespace cdyn
