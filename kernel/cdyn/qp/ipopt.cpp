// ipopt.cpp — the step QP through Ipopt's TNLP interface; see qp/ipopt.hpp.
#include "cdyn/qp/ipopt.hpp"

#include <coin/IpIpoptApplication.hpp>
#include <coin/IpSolveStatistics.hpp>

#include <algorithm>
#include <chrono>
#include <cmath>

#include "cdyn/base/error.hpp"
#include "cdyn/qp/ipopt_program.hpp"
#include "cdyn/qp/pdas/pdas.hpp"

namespace cdyn {

namespace {

using Ipopt::Index;
using Ipopt::Number;

// The QP as an Ipopt nonlinear program (variables X, or (U, Z) in saddle form).
class BoundQPProgram : public IpoptProgram {
 public:
  BoundQPProgram(const BoundQP& qp, const Eigen::VectorXd& x0) : IpoptProgram(qp.size()), qp_(qp), x0_(x0) {
    n_ = qp.size();
    if (qp.saddle) {
      const SaddleForm& f = *qp.saddle;
      m_ = static_cast<int>(f.C.rows());
      lower_triangle(f.A, 0, 1.0, h_rows_, h_cols_, h_vals_);
      lower_triangle(f.C, n_, f.c, h_rows_, h_cols_, h_vals_);
      // Jacobian of g(U, Z) = C Z − B U, row by row as (constraint, variable, value)
      for (int j = 0; j < n_; ++j)
        for (SparseMatrix::InnerIterator it(f.B, j); it; ++it) {
          j_rows_.push_back(static_cast<Index>(it.row()));
          j_cols_.push_back(j);
          j_vals_.push_back(-it.value());
        }
      for (int j = 0; j < m_; ++j)
        for (SparseMatrix::InnerIterator it(f.C, j); it; ++it) {
          j_rows_.push_back(static_cast<Index>(it.row()));
          j_cols_.push_back(n_ + j);
          j_vals_.push_back(it.value());
        }
    } else {
      lower_triangle(qp.S, 0, 1.0, h_rows_, h_cols_, h_vals_);
    }
  }

  bool get_nlp_info(Index& n, Index& m, Index& nnz_jac_g, Index& nnz_h_lag, IndexStyleEnum& style) override {
    n = n_ + m_;
    m = m_;
    nnz_jac_g = static_cast<Index>(j_vals_.size());
    nnz_h_lag = static_cast<Index>(h_vals_.size());
    style = C_STYLE;
    return true;
  }

  bool get_bounds_info(Index n, Number* x_l, Number* x_u, Index m, Number* g_l, Number* g_u) override {
    for (Index i = 0; i < n; ++i) {
      x_l[i] = i < n_ ? std::max(qp_.lower[i], -kIpoptInfinity) : -kIpoptInfinity;
      x_u[i] = i < n_ ? std::min(qp_.upper[i], kIpoptInfinity) : kIpoptInfinity;
    }
    for (Index k = 0; k < m; ++k) g_l[k] = g_u[k] = 0.0;
    return true;
  }

  bool get_starting_point(Index n, bool init_x, Number* x, bool init_z, Number*, Number*, Index, bool init_lambda,
                          Number*) override {
    if (!init_x || init_z || init_lambda) return false;
    for (Index i = 0; i < n; ++i) x[i] = i < n_ ? x0_[i] : 0.0;
    return true;
  }

  bool eval_f(Index, const Number* x, bool, Number& f) override {
    const Eigen::Map<const Eigen::VectorXd> U(x, n_);
    if (!qp_.saddle) {
      f = 0.5 * U.dot(qp_.S * U) - qp_.r.dot(U);
      return true;
    }
    const SaddleForm& s = *qp_.saddle;
    const Eigen::Map<const Eigen::VectorXd> Z(x + n_, m_);
    f = 0.5 * U.dot(s.A * U) + 0.5 * s.c * Z.dot(s.C * Z) - qp_.r.dot(U);
    return true;
  }

  bool eval_grad_f(Index, const Number* x, bool, Number* grad) override {
    const Eigen::Map<const Eigen::VectorXd> U(x, n_);
    Eigen::Map<Eigen::VectorXd> gU(grad, n_);
    if (!qp_.saddle) {
      gU = qp_.S * U - qp_.r;
      return true;
    }
    const SaddleForm& s = *qp_.saddle;
    const Eigen::Map<const Eigen::VectorXd> Z(x + n_, m_);
    Eigen::Map<Eigen::VectorXd> gZ(grad + n_, m_);
    gU = s.A * U - qp_.r;
    gZ = s.c * (s.C * Z);
    return true;
  }

  bool eval_g(Index, const Number* x, bool, Index, Number* g) override {
    if (m_ == 0) return true;
    const SaddleForm& s = *qp_.saddle;
    const Eigen::Map<const Eigen::VectorXd> U(x, n_);
    const Eigen::Map<const Eigen::VectorXd> Z(x + n_, m_);
    Eigen::Map<Eigen::VectorXd>(g, m_) = s.C * Z - s.B * U;
    return true;
  }

  bool eval_jac_g(Index, const Number*, bool, Index, Index nele, Index* rows, Index* cols, Number* values) override {
    if (values == nullptr) {
      std::copy(j_rows_.begin(), j_rows_.end(), rows);
      std::copy(j_cols_.begin(), j_cols_.end(), cols);
    } else {
      std::copy(j_vals_.begin(), j_vals_.begin() + nele, values);
    }
    return true;
  }

  bool eval_h(Index, const Number*, bool, Number obj_factor, Index, const Number*, bool, Index nele, Index* rows,
              Index* cols, Number* values) override {
    if (values == nullptr) {
      std::copy(h_rows_.begin(), h_rows_.end(), rows);
      std::copy(h_cols_.begin(), h_cols_.end(), cols);
    } else {
      for (Index k = 0; k < nele; ++k) values[k] = obj_factor * h_vals_[k];  // constraints are linear
    }
    return true;
  }

 private:
  const BoundQP& qp_;
  Eigen::VectorXd x0_;
  int n_ = 0, m_ = 0;
  std::vector<Index> h_rows_, h_cols_, j_rows_, j_cols_;
  std::vector<double> h_vals_, j_vals_;
};

std::string status_name(Ipopt::ApplicationReturnStatus s) {
  switch (s) {
    case Ipopt::Solve_Succeeded: return "Solve_Succeeded";
    case Ipopt::Solved_To_Acceptable_Level: return "Solved_To_Acceptable_Level";
    case Ipopt::Infeasible_Problem_Detected: return "Infeasible_Problem_Detected";
    case Ipopt::Search_Direction_Becomes_Too_Small: return "Search_Direction_Becomes_Too_Small";
    case Ipopt::Diverging_Iterates: return "Diverging_Iterates";
    case Ipopt::Maximum_Iterations_Exceeded: return "Maximum_Iterations_Exceeded";
    case Ipopt::Restoration_Failed: return "Restoration_Failed";
    case Ipopt::Error_In_Step_Computation: return "Error_In_Step_Computation";
    case Ipopt::Maximum_CpuTime_Exceeded: return "Maximum_CpuTime_Exceeded";
    default: return "Ipopt status " + std::to_string(static_cast<int>(s));
  }
}

}  // namespace

IpoptSolver::IpoptSolver(const QPOptions& options) : options_(options) {
  if (options_.max_iterations == 0) options_.max_iterations = 3000;
  QPOptions crossover = options_;
  crossover.max_iterations = 3;
  crossover.throw_on_failure = false;
  crossover_ = std::make_unique<PDASSolver>(crossover);
}

IpoptSolver::~IpoptSolver() = default;

void IpoptSolver::clear() { crossover_->clear(); }

QPResult IpoptSolver::solve(const BoundQP& qp, const QPResult* warm_start) {
  const auto start = std::chrono::steady_clock::now();
  const bool new_matrices = checked_.check(qp, /*positive_definite=*/true, "ipopt");
  const int n = qp.size();
  form_.set(qp, !new_matrices);
  QPResult result;
  std::string detail;
  if (n == 0) {
    result.X.resize(0);
  } else {
    Eigen::VectorXd x0 = Eigen::VectorXd::Zero(n);
    if (warm_start && warm_start->X.size() == n) x0 = warm_start->X;
    for (int i = 0; i < n; ++i) x0[i] = std::clamp(x0[i], qp.lower[i], qp.upper[i]);

    Ipopt::SmartPtr<Ipopt::IpoptApplication> app = new Ipopt::IpoptApplication();
    auto& o = *app->Options();
    o.SetIntegerValue("print_level", 0);
    o.SetStringValue("sb", "yes");
    o.SetNumericValue("bound_relax_factor", 0.0);
    o.SetNumericValue("tol", 1e-3 * options_.tol);
    o.SetIntegerValue("max_iter", options_.max_iterations);
    o.SetStringValue("hessian_constant", "yes");
    o.SetStringValue("jac_c_constant", "yes");
    o.SetStringValue("jac_d_constant", "yes");
    o.SetStringValue("mu_strategy", "adaptive");
    // Ipopt's default floor μ ≥ 1e-11 leaves the iterate at a distance ≈ μ/λ_i from an
    // active bound: for the obstacle of tests/unit/test_qp_obstacle.cpp (λ ≈ 1e-3) that is
    // a KKT residual of 1e-8.  Let μ go to 1e-10 × tol.
    o.SetNumericValue("mu_min", 1e-10 * options_.tol);
    o.SetStringValue("linear_solver", "mumps");
    if (app->Initialize("") != Ipopt::Solve_Succeeded) throw NumericalError("ipopt: initialization failed");

    Ipopt::SmartPtr<BoundQPProgram> program = new BoundQPProgram(qp, x0);
    const Ipopt::ApplicationReturnStatus status = app->OptimizeTNLP(Ipopt::SmartPtr<Ipopt::TNLP>(GetRawPtr(program)));
    if (Ipopt::IsValid(app->Statistics())) result.iterations = app->Statistics()->IterationCount();
    if (program->X_.size() == n) {
      result.X = program->X_;
    } else {
      result.X = x0;
    }
    if (status != Ipopt::Solve_Succeeded) detail = status_name(status);
  }
  finish_result(qp, form_, options_.tol, result);
  last_ = Statistics{result.iterations, result.kkt_residual, 0};
  if (!result.converged && options_.ipopt_crossover && n > 0) {
    // crossover: from the active set Ipopt identified, at most 3 PDAS steps (exact solves)
    const QPResult polished = crossover_->solve(qp, &result);
    if (polished.kkt_residual < result.kkt_residual) {
      result = polished;
      result.iterations = last_.ipopt_iterations + polished.iterations;
      last_.crossover_solves = polished.iterations;
      if (result.converged) detail.clear();
    }
  }
  result.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  report_failure("ipopt", options_, result, detail);
  return result;
}

}  // namespace cdyn
