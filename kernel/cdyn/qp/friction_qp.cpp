// friction_qp.cpp — the residual, thresholds, statuses and work of the frictional step
// problem (qp/friction_qp.hpp).
#include "cdyn/qp/friction_qp.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "cdyn/base/error.hpp"
#include "cdyn/qp/kkt.hpp"

namespace cdyn {

namespace {

// |d| over the node's tangential unknowns (the Euclidean norm: isotropic friction).
double slip_norm(const FrictionContact& c, const Eigen::VectorXd& X, const Eigen::VectorXd& Xref) {
  double sum = 0.0;
  for (int t : c.tangential) sum += (X[t] - Xref[t]) * (X[t] - Xref[t]);
  return std::sqrt(sum);
}

}  // namespace

bool in_space(const FrictionConditions& f) {
  return std::any_of(f.contacts.begin(), f.contacts.end(), [](const FrictionContact& c) { return c.tangential.size() > 1; });
}

void slip_sets(const FrictionConditions& f, const Eigen::VectorXd& X, const Eigen::VectorXd& reaction,
               const Eigen::VectorXd& s, const Eigen::VectorXd& D, std::vector<char>& stick,
               Eigen::VectorXd& direction, std::vector<double>* slip_length) {
  stick.assign(f.contacts.size(), 1);
  direction = Eigen::VectorXd::Zero(X.size());
  if (slip_length) slip_length->assign(f.contacts.size(), 0.0);
  for (std::size_t k = 0; k < f.contacts.size(); ++k) {
    const std::vector<int>& t = f.contacts[k].tangential;
    double Dk = std::numeric_limits<double>::infinity(), norm = 0.0;
    for (int j : t) Dk = std::min(Dk, D[j]);
    std::vector<double> y;
    for (int j : t) {
      y.push_back(X[j] - f.reference[j] - reaction[j] / Dk);
      norm += y.back() * y.back();
    }
    norm = std::sqrt(norm);
    if (norm <= s[k] / Dk) continue;
    stick[k] = 0;
    if (slip_length) (*slip_length)[k] = norm - s[k] / Dk;
    for (std::size_t j = 0; j < t.size(); ++j) direction[t[j]] = y[j] / norm;
  }
}

Eigen::VectorXd friction_thresholds(const FrictionConditions& f, const Eigen::VectorXd& reaction) {
  const int m = static_cast<int>(f.contacts.size());
  Eigen::VectorXd s(m);
  for (int k = 0; k < m; ++k) {
    const FrictionContact& c = f.contacts[k];
    s[k] = c.coulomb ? c.mu * std::max(reaction[c.normal], 0.0) : c.threshold;
  }
  return s;
}

double friction_residual(const BoundQP& qp, const FrictionConditions& f, const Eigen::VectorXd& X, const Eigen::VectorXd& reaction,
                         const Eigen::VectorXd& threshold, const Eigen::VectorXd& D) {
  if (qp.size() == 0) return 0.0;
  Eigen::VectorXd F = natural_residual(qp, X, reaction, D);
  for (std::size_t k = 0; k < f.contacts.size(); ++k) {
    const FrictionContact& c = f.contacts[k];
    // y = d − λ_T/D on the node's tangential unknowns, D the smallest of their
    // diagonals (one number per node, so that the shrink acts on the vector y).
    double Dk = std::numeric_limits<double>::infinity();
    for (int t : c.tangential) Dk = std::min(Dk, D[t]);
    double y_norm = 0.0;
    for (int t : c.tangential) {
      const double y = X[t] - f.reference[t] - reaction[t] / Dk;
      y_norm += y * y;
    }
    y_norm = std::sqrt(y_norm);
    const double keep = y_norm > 0.0 ? std::max(0.0, 1.0 - threshold[k] / Dk / y_norm) : 0.0;
    for (int t : c.tangential) {
      const double d = X[t] - f.reference[t];
      F[t] = d - keep * (d - reaction[t] / Dk);
    }
  }
  const double norm = F.lpNorm<Eigen::Infinity>();
  if (!std::isfinite(norm)) return std::numeric_limits<double>::infinity();
  const double scale = std::max(X.lpNorm<Eigen::Infinity>(), qp.r.cwiseQuotient(D).lpNorm<Eigen::Infinity>());
  return scale > 0 ? norm / scale : norm;
}

std::vector<ContactStatus> contact_status(const BoundQP& qp, const FrictionConditions& f, const Eigen::VectorXd& X,
                                          const Eigen::VectorXd& reaction) {
  std::vector<ContactStatus> status;
  for (const FrictionContact& c : f.contacts) {
    const int n = c.normal;
    const bool at_bound = X[n] <= qp.lower[n] || X[n] >= qp.upper[n];
    if (!at_bound && reaction[n] <= 0.0)
      status.push_back(ContactStatus::Open);
    else
      status.push_back(slip_norm(c, X, f.reference) == 0.0 ? ContactStatus::Stick : ContactStatus::Slip);
  }
  return status;
}

double friction_work(const FrictionConditions& f, const Eigen::VectorXd& X, const Eigen::VectorXd& threshold,
                     const std::vector<char>& counted) {
  double w = 0.0;
  for (std::size_t k = 0; k < f.contacts.size(); ++k) {
    if (!counted.empty() && !counted[k]) continue;
    if (const double d = slip_norm(f.contacts[k], X, f.reference); d > 0.0) w += threshold[k] * d;  // (s may be ∞ where d = 0)
  }
  return w;
}

void check_friction_qp(const BoundQP& qp, const FrictionConditions& f) {
  const int n = qp.size();
  if (f.reference.size() != n)
    throw InputError("friction: the reference X̂ has " + std::to_string(f.reference.size()) + " entries, not " +
                     std::to_string(n));
  std::vector<char> used(n, 0);
  auto claim = [&](int i) {
    if (i < 0 || i >= n) throw InputError("friction: unknown " + std::to_string(i) + " is out of range");
    if (used[i]) throw InputError("friction: unknown " + std::to_string(i) + " belongs to two contacts");
    used[i] = 1;
  };
  for (const FrictionContact& c : f.contacts) {
    claim(c.normal);
    if (c.tangential.empty()) throw InputError("friction: a contact without tangential unknown");
    for (int t : c.tangential) {
      claim(t);
      if (std::isfinite(qp.lower[t]) || std::isfinite(qp.upper[t]))
        throw InputError("friction: the tangential unknown " + std::to_string(t) + " has a bound");
    }
    if (!(c.mu >= 0.0) || !std::isfinite(c.mu)) throw InputError("mu", "the friction coefficient must be ≥ 0");
    if (!(c.threshold >= 0.0)) throw InputError("threshold", "the Tresca threshold must be ≥ 0");
  }
}

}  // namespace cdyn
