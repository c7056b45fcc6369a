// step_solver.cpp — choosing a step QP solver by name.
#include "cdyn/qp/step_solver.hpp"

#include <cmath>

#include "cdyn/base/error.hpp"
#include "cdyn/base/format.hpp"
#include "cdyn/qp/pdas/pdas.hpp"
#include "cdyn/qp/pgs.hpp"
#ifdef CDYN_WITH_IPOPT
#include "cdyn/qp/ipopt.hpp"
#endif
#ifdef CDYN_WITH_NLOPT
#include "cdyn/qp/nlopt.hpp"
#endif

namespace cdyn {

std::vector<std::string> step_solver_names() {
  std::vector<std::string> names{"pdas", "pgs"};
#ifdef CDYN_WITH_IPOPT
  names.push_back("ipopt");
#endif
#ifdef CDYN_WITH_NLOPT
  names.push_back("nlopt");
#endif
  return names;
}

std::unique_ptr<StepSolver> make_step_solver(const std::string& name, const QPOptions& options) {
  if (!(options.tol > 0) || !std::isfinite(options.tol))
    throw InputError("tol", "must be a positive number (got " + to_text(options.tol) + ")");
  if (options.max_iterations < 0)
    throw InputError("max_iterations", "must be >= 0 (got " + std::to_string(options.max_iterations) + ")");
  if (name == "pdas") return std::make_unique<PDASSolver>(options);
  if (name == "pgs") return std::make_unique<PGSSolver>(options);
#ifdef CDYN_WITH_IPOPT
  if (name == "ipopt") return std::make_unique<IpoptSolver>(options);
#endif
#ifdef CDYN_WITH_NLOPT
  if (name == "nlopt") return std::make_unique<NLoptSolver>(options);
#endif
  std::string known;
  for (const auto& n : step_solver_names()) known += (known.empty() ? "" : ", ") + n;
  if (name == "ipopt" || name == "nlopt")
    throw InputError("solver", "this cdyn was built without " + name + " (CDYN_WITH_" +
                                   (name == "ipopt" ? std::string("IPOPT") : std::string("NLOPT")) +
                                   "=OFF; available: " + known + ")");
  throw InputError("solver", "'" + name + "' is not a step solver (available: " + known + ")");
}

}  // namespace cdyn
