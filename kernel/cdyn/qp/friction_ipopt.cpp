// friction_ipopt.cpp — (FQP) by Ipopt on split slip variables; see qp/friction_ipopt.hpp.
#include "cdyn/qp/friction_ipopt.hpp"

#include <coin/IpIpoptApplication.hpp>
#include <coin/IpSolveStatistics.hpp>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>

#include "cdyn/base/error.hpp"
#include "cdyn/base/format.hpp"
#include "cdyn/qp/ipopt_program.hpp"
#include "cdyn/qp/kkt.hpp"

namespace cdyn {

namespace {

using Ipopt::Index;
using Ipopt::Number;

// Variables (X, p, q), X of size n, p and q one per contact; constraints
// X_T,k − p_k + q_k = X̂_T,k.  s_k = ∞ (bonded) holds p_k = q_k = 0.
class SplitSlipProgram : public IpoptProgram {
 public:
  SplitSlipProgram(const BoundQP& qp, const FrictionConditions& f, const Eigen::VectorXd& s, const Eigen::VectorXd& x0)
      : IpoptProgram(qp.size()), qp_(qp), f_(f), s_(s), x0_(x0), n_(qp.size()), m_(static_cast<int>(f.contacts.size())) {
    lower_triangle(qp.S, 0, 1.0, h_rows_, h_cols_, h_vals_);
  }

  bool get_nlp_info(Index& n, Index& m, Index& nnz_jac_g, Index& nnz_h_lag, IndexStyleEnum& style) override {
    n = n_ + 2 * m_;
    m = m_;
    nnz_jac_g = 3 * m_;
    nnz_h_lag = static_cast<Index>(h_vals_.size());
    style = C_STYLE;
    return true;
  }

  bool get_bounds_info(Index n, Number* x_l, Number* x_u, Index m, Number* g_l, Number* g_u) override {
    for (Index i = 0; i < n_; ++i) {
      x_l[i] = std::max(qp_.lower[i], -kIpoptInfinity);
      x_u[i] = std::min(qp_.upper[i], kIpoptInfinity);
    }
    for (Index i = n_; i < n; ++i) {
      const int k = (i - n_) % m_;
      x_l[i] = 0.0;
      x_u[i] = std::isinf(s_[k]) ? 0.0 : kIpoptInfinity;
    }
    for (Index k = 0; k < m; ++k) g_l[k] = g_u[k] = f_.reference[f_.contacts[k].tangential[0]];
    return true;
  }

  bool get_starting_point(Index, bool init_x, Number* x, bool init_z, Number*, Number*, Index, bool init_lambda,
                          Number*) override {
    if (!init_x || init_z || init_lambda) return false;
    for (Index i = 0; i < n_; ++i) x[i] = x0_[i];
    for (int k = 0; k < m_; ++k) {
      const int t = f_.contacts[k].tangential[0];
      const double d = x0_[t] - f_.reference[t];
      x[n_ + k] = std::max(d, 0.0);
      x[n_ + m_ + k] = std::max(-d, 0.0);
    }
    return true;
  }

  bool eval_f(Index, const Number* x, bool, Number& f) override {
    const Eigen::Map<const Eigen::VectorXd> X(x, n_);
    f = 0.5 * X.dot(qp_.S * X) - qp_.r.dot(X);
    for (int k = 0; k < m_; ++k)
      if (!std::isinf(s_[k])) f += s_[k] * (x[n_ + k] + x[n_ + m_ + k]);
    return true;
  }

  bool eval_grad_f(Index, const Number* x, bool, Number* grad) override {
    const Eigen::Map<const Eigen::VectorXd> X(x, n_);
    Eigen::Map<Eigen::VectorXd>(grad, n_) = qp_.S * X - qp_.r;
    for (int k = 0; k < m_; ++k) grad[n_ + k] = grad[n_ + m_ + k] = std::isinf(s_[k]) ? 0.0 : s_[k];
    return true;
  }

  bool eval_g(Index, const Number* x, bool, Index, Number* g) override {
    for (int k = 0; k < m_; ++k) g[k] = x[f_.contacts[k].tangential[0]] - x[n_ + k] + x[n_ + m_ + k];
    return true;
  }

  bool eval_jac_g(Index, const Number*, bool, Index, Index, Index* rows, Index* cols, Number* values) override {
    for (int k = 0; k < m_; ++k) {
      if (values == nullptr) {
        rows[3 * k] = rows[3 * k + 1] = rows[3 * k + 2] = k;
        cols[3 * k] = f_.contacts[k].tangential[0];
        cols[3 * k + 1] = n_ + k;
        cols[3 * k + 2] = n_ + m_ + k;
      } else {
        values[3 * k] = 1.0;
        values[3 * k + 1] = -1.0;
        values[3 * k + 2] = 1.0;
      }
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
  const FrictionConditions& f_;
  Eigen::VectorXd s_, x0_;
  int n_, m_;
  std::vector<Index> h_rows_, h_cols_;
  std::vector<double> h_vals_;
};

// In space, variables (X, w), w one per contact, and the constraints
//     w_k² − |X_T,k − X̂_T,k|² ≥ 0,  w_k ≥ 0
// (the second-order cone |d| ≤ w: the Euclidean norm of two tangential unknowns has no
// split into positive parts); the term s_k w_k.  s_k = ∞ (bonded) holds X_T,k = X̂_T,k
// by its bounds and leaves its constraint free.
class ConeSlipProgram : public IpoptProgram {
 public:
  ConeSlipProgram(const BoundQP& qp, const FrictionConditions& f, const Eigen::VectorXd& s, const Eigen::VectorXd& x0)
      : IpoptProgram(qp.size()),
        qp_(qp),
        f_(f),
        s_(s),
        x0_(x0),
        n_(qp.size()),
        m_(static_cast<int>(f.contacts.size())),
        diagonal_(qp.size(), -1) {
    lower_triangle(qp.S, 0, 1.0, h_rows_, h_cols_, h_vals_);
    for (std::size_t e = 0; e < h_rows_.size(); ++e)
      if (h_rows_[e] == h_cols_[e]) diagonal_[h_cols_[e]] = static_cast<Index>(e);
    for (const FrictionContact& c : f.contacts)
      for (int t : c.tangential)
        if (diagonal_[t] < 0) throw InputError("friction (ipopt): S has no diagonal entry at a tangential unknown");
  }

  bool get_nlp_info(Index& n, Index& m, Index& nnz_jac_g, Index& nnz_h_lag, IndexStyleEnum& style) override {
    n = n_ + m_;
    m = m_;
    nnz_jac_g = 0;
    for (const FrictionContact& c : f_.contacts) nnz_jac_g += 1 + static_cast<Index>(c.tangential.size());
    nnz_h_lag = static_cast<Index>(h_vals_.size()) + m_;
    style = C_STYLE;
    return true;
  }

  bool get_bounds_info(Index, Number* x_l, Number* x_u, Index m, Number* g_l, Number* g_u) override {
    for (Index i = 0; i < n_; ++i) {
      x_l[i] = std::max(qp_.lower[i], -kIpoptInfinity);
      x_u[i] = std::min(qp_.upper[i], kIpoptInfinity);
    }
    for (int k = 0; k < m_; ++k) {
      const bool bonded = std::isinf(s_[k]);
      if (bonded)
        for (int t : f_.contacts[k].tangential) x_l[t] = x_u[t] = f_.reference[t];
      x_l[n_ + k] = 0.0;
      x_u[n_ + k] = bonded ? 0.0 : kIpoptInfinity;
    }
    for (Index k = 0; k < m; ++k) {
      g_l[k] = std::isinf(s_[k]) ? -kIpoptInfinity : 0.0;
      g_u[k] = kIpoptInfinity;
    }
    return true;
  }

  bool get_starting_point(Index, bool init_x, Number* x, bool init_z, Number*, Number*, Index, bool init_lambda,
                          Number*) override {
    if (!init_x || init_z || init_lambda) return false;
    for (Index i = 0; i < n_; ++i) x[i] = x0_[i];
    for (int k = 0; k < m_; ++k) x[n_ + k] = std::isinf(s_[k]) ? 0.0 : slip(x, k);
    return true;
  }

  bool eval_f(Index, const Number* x, bool, Number& f) override {
    const Eigen::Map<const Eigen::VectorXd> X(x, n_);
    f = 0.5 * X.dot(qp_.S * X) - qp_.r.dot(X);
    for (int k = 0; k < m_; ++k)
      if (!std::isinf(s_[k])) f += s_[k] * x[n_ + k];
    return true;
  }

  bool eval_grad_f(Index, const Number* x, bool, Number* grad) override {
    const Eigen::Map<const Eigen::VectorXd> X(x, n_);
    Eigen::Map<Eigen::VectorXd>(grad, n_) = qp_.S * X - qp_.r;
    for (int k = 0; k < m_; ++k) grad[n_ + k] = std::isinf(s_[k]) ? 0.0 : s_[k];
    return true;
  }

  bool eval_g(Index, const Number* x, bool, Index, Number* g) override {
    for (int k = 0; k < m_; ++k) {
      const double d = slip(x, k);
      g[k] = x[n_ + k] * x[n_ + k] - d * d;
    }
    return true;
  }

  bool eval_jac_g(Index, const Number* x, bool, Index, Index, Index* rows, Index* cols, Number* values) override {
    Index e = 0;
    for (int k = 0; k < m_; ++k) {
      if (values == nullptr) {
        rows[e] = k, cols[e++] = n_ + k;
        for (int t : f_.contacts[k].tangential) rows[e] = k, cols[e++] = t;
      } else {
        values[e++] = 2.0 * x[n_ + k];
        for (int t : f_.contacts[k].tangential) values[e++] = -2.0 * (x[t] - f_.reference[t]);
      }
    }
    return true;
  }

  bool eval_h(Index, const Number*, bool, Number obj_factor, Index, const Number* lambda, bool, Index, Index* rows,
              Index* cols, Number* values) override {
    const Index base = static_cast<Index>(h_vals_.size());
    if (values == nullptr) {
      std::copy(h_rows_.begin(), h_rows_.end(), rows);
      std::copy(h_cols_.begin(), h_cols_.end(), cols);
      for (int k = 0; k < m_; ++k) rows[base + k] = cols[base + k] = n_ + k;
      return true;
    }
    for (Index e = 0; e < base; ++e) values[e] = obj_factor * h_vals_[e];
    for (int k = 0; k < m_; ++k) {  // ∇²g_k: 2 on w_k, −2 on each tangential unknown
      values[base + k] = 2.0 * lambda[k];
      for (int t : f_.contacts[k].tangential) values[diagonal_[t]] -= 2.0 * lambda[k];
    }
    return true;
  }

 private:
  double slip(const Number* x, int k) const {
    double sum = 0.0;
    for (int t : f_.contacts[k].tangential) sum += (x[t] - f_.reference[t]) * (x[t] - f_.reference[t]);
    return std::sqrt(sum);
  }
  const BoundQP& qp_;
  const FrictionConditions& f_;
  Eigen::VectorXd s_, x0_;
  int n_, m_;
  std::vector<Index> h_rows_, h_cols_, diagonal_;
  std::vector<double> h_vals_;
};

// The Tresca problem of the thresholds s by Ipopt, from x0; its X and iterations.
Eigen::VectorXd solve_tresca(const BoundQP& qp, const FrictionConditions& f, const Eigen::VectorXd& s,
                             const Eigen::VectorXd& x0, double tol, int& iterations) {
  Ipopt::SmartPtr<Ipopt::IpoptApplication> app = new Ipopt::IpoptApplication();
  auto& o = *app->Options();
  o.SetIntegerValue("print_level", 0);
  o.SetStringValue("sb", "yes");
  o.SetNumericValue("bound_relax_factor", 0.0);  // (docs/qp.md §3.3: exact bounds)
  o.SetNumericValue("tol", 1e-3 * tol);
  o.SetNumericValue("mu_min", 1e-10 * tol);
  o.SetIntegerValue("max_iter", 3000);
  const bool space = in_space(f);
  if (!space) {  // the split program is a QP: constant derivatives
    o.SetStringValue("hessian_constant", "yes");
    o.SetStringValue("jac_c_constant", "yes");
    o.SetStringValue("jac_d_constant", "yes");
  }
  o.SetStringValue("mu_strategy", "adaptive");
  o.SetStringValue("linear_solver", "mumps");
  if (app->Initialize("") != Ipopt::Solve_Succeeded) throw NumericalError("friction (ipopt): initialization failed");
  auto optimize = [&](auto program) {
    app->OptimizeTNLP(Ipopt::SmartPtr<Ipopt::TNLP>(GetRawPtr(program)));
    if (Ipopt::IsValid(app->Statistics())) iterations += app->Statistics()->IterationCount();
    return program->X_.size() == qp.size() ? program->X_ : x0;
  };
  if (space) return optimize(Ipopt::SmartPtr<ConeSlipProgram>(new ConeSlipProgram(qp, f, s, x0)));
  return optimize(Ipopt::SmartPtr<SplitSlipProgram>(new SplitSlipProgram(qp, f, s, x0)));
}

}  // namespace

FrictionResult solve_friction_ipopt(BoundQP& qp, const FrictionConditions& f, const FrictionOptions& options,
                                    const FrictionResult* warm_start) {
  const auto start = std::chrono::steady_clock::now();
  if (qp.saddle) throw InputError("friction (ipopt): split slip variables need the entries of S; use solver pdas");
  check_friction_qp(qp, f);
  const int m = static_cast<int>(f.contacts.size());
  const Eigen::VectorXd D = scaling_diagonal(qp);
  // In space Coulomb's fixed point is left to the crossover after two thresholds: the
  // cone's apex (w = |d| = 0 at a sticking vertex, where the constraint's gradient
  // vanishes) costs Ipopt hundreds of iterations a solve (measured: 3 400–4 100 a step
  // on the plate of incline_block_3d.toml with 50 thresholds, 15 s a step).
  const bool space = in_space(f);
  const int max_outer = options.max_iterations > 0 ? options.max_iterations : space ? 2 : 50;

  // Coulomb's thresholds start from the previous step's, or from the bonded step's λ_N
  // (s = ∞: every slip held at 0), as the semismooth Newton method does.
  Eigen::VectorXd s(m);
  bool coulomb = false;
  for (int k = 0; k < m; ++k) {
    const FrictionContact& c = f.contacts[k];
    coulomb = coulomb || c.coulomb;
    const bool warm = warm_start && warm_start->threshold.size() == m;
    s[k] = !c.coulomb ? c.threshold : warm ? warm_start->threshold[k] : std::numeric_limits<double>::infinity();
  }
  Eigen::VectorXd X = f.reference;
  if (warm_start && warm_start->qp.X.size() == qp.size()) X = warm_start->qp.X;
  for (int i = 0; i < qp.size(); ++i) X[i] = std::clamp(X[i], qp.lower[i], qp.upper[i]);

  FrictionResult result;
  int iterations = 0, outer = 0;
  for (;;) {
    ++outer;
    X = solve_tresca(qp, f, s, X, options.tol, iterations);
    const Eigen::VectorXd reaction = qp.S * X - qp.r;
    const Eigen::VectorXd s_new = friction_thresholds(f, reaction);
    result.qp.X = X;
    result.qp.reaction = reaction;
    result.threshold = s_new;
    result.residual = friction_residual(qp, f, X, reaction, s_new, D);
    // Coulomb's fixed point has settled when the thresholds stop moving (relative to
    // the largest: the interior point's own accuracy), Tresca after one solve
    const double moved = coulomb ? (s_new - s).lpNorm<Eigen::Infinity>() : 0.0;
    const double size = s_new.lpNorm<Eigen::Infinity>();
    s = s_new;
    if (result.residual <= options.tol || moved <= 1e-8 * size || outer >= max_outer) break;
  }
  // The sets of Ipopt's X, for the crossover and for the next step's warm start.
  slip_sets(f, X, result.qp.reaction, s, D, result.stick, result.direction);
  result.converged = result.residual <= options.tol;
  if (!result.converged) {
    // crossover: the semismooth Newton method from Ipopt's sets (exact solves)
    QPOptions inner_options;
    inner_options.tol = 0.1 * options.tol;
    const auto inner = make_step_solver("pdas", inner_options);
    FrictionOptions crossover = options;
    crossover.throw_on_failure = false;
    FrictionResult polished = solve_friction_ssn(qp, f, *inner, crossover, &result);
    if (polished.residual < result.residual) {
      iterations += polished.qp.iterations;
      result = std::move(polished);
    }
  }
  result.status = contact_status(qp, f, result.qp.X, result.qp.reaction);
  result.qp.iterations = iterations;
  result.qp.kkt_residual = result.residual;
  result.qp.converged = result.converged;
  result.qp.active = active_set(qp, result.qp.X, result.qp.reaction, D);
  result.qp.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  if (!result.converged && options.throw_on_failure)
    throw NumericalError("friction (ipopt, split slip variables): did not converge: residual " +
                         to_text(result.residual) + " > tol " + to_text(options.tol) + " after " +
                         std::to_string(outer) + " threshold iterations and the crossover");
  return result;
}

}  // namespace cdyn
