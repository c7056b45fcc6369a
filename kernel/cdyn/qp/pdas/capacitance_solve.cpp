// capacitance_solve.cpp — S̃ y = b for a few held unknowns by S's factor and the
// capacitance matrix K = E_Aᵀ S⁻¹ E_A; see capacitance_solve.hpp.
#include "cdyn/qp/pdas/capacitance_solve.hpp"

#include <algorithm>

#include "cdyn/linalg/sparse_cholesky.hpp"

namespace cdyn {

namespace {

// Σ a_r b_r over the rows two columns share: their paths meet and go on to the root
// together, so the shared rows are a suffix of both lists (walked from the end).
double shared_dot(const std::vector<int>& ra, const std::vector<double>& va, const std::vector<int>& rb,
                  const std::vector<double>& vb) {
  double sum = 0.0;
  for (auto p = ra.size(), q = rb.size(); p > 0 && q > 0 && ra[p - 1] == rb[q - 1]; --p, --q)
    sum += va[p - 1] * vb[q - 1];
  return sum;
}

}  // namespace

void CapacitanceSolve::clear() {
  columns_.clear();
  stored_ = 0;
  held_.clear();
  held_columns_.clear();
  ready_ = false;
}

int CapacitanceSolve::missing(const std::vector<int>& held) const {
  int count = 0;
  for (int i : held) count += columns_.count(i) == 0;
  return count;
}

const CapacitanceSolve::Column& CapacitanceSolve::column(const SparseCholesky& chol, int i, double& flops) {
  auto [it, made] = columns_.try_emplace(i);
  if (made) {
    const double f = chol.unit_forward(i, it->second.rows, it->second.values);
    flops += f;
    column_flops_ += f;
    column_length_ += static_cast<double>(it->second.rows.size());
    stored_ += static_cast<double>(it->second.rows.size());
    ++columns_made_;
  }
  return it->second;
}

void CapacitanceSolve::measure(const SparseCholesky& chol, int i) {
  double flops = 0.0;
  column(chol, i, flops);
}

double CapacitanceSolve::hold(const SparseCholesky& chol, const std::vector<int>& held, bool& ok) {
  ok = ready_ && held == held_;
  if (ok) return 0.0;  // (K as it is)
  double flops = 0.0;
  // The columns are kept while they take less memory than the factor itself; past that,
  // only those of this set (a contact zone that has wandered over the whole mesh).
  if (stored_ + missing(held) * mean_column_length() > chol.solve_flops() / 4.0) {
    std::unordered_map<int, Column> kept;
    stored_ = 0;
    for (int i : held)
      if (auto it = columns_.find(i); it != columns_.end()) {
        stored_ += static_cast<double>(it->second.rows.size());
        kept.emplace(i, std::move(it->second));
      }
    columns_.swap(kept);
  }
  held_ = held;
  held_columns_.clear();
  for (int i : held) held_columns_.push_back(&column(chol, i, flops));
  const int h = static_cast<int>(held.size());
  Eigen::MatrixXd K(h, h);
  for (int a = 0; a < h; ++a)
    for (int b = 0; b <= a; ++b) {
      const Column& ca = *held_columns_[a];
      const Column& cb = *held_columns_[b];
      K(a, b) = K(b, a) = shared_dot(ca.rows, ca.values, cb.rows, cb.values);
      flops += 2.0 * static_cast<double>(std::min(ca.rows.size(), cb.rows.size()));
    }
  K_.compute(K);
  flops += double(h) * h * h / 3.0;
  ok = ready_ = K_.info() == Eigen::Success;
  return flops;
}

// mu_ = Wᵀ v over the held set's columns.
void CapacitanceSolve::held_products(const Eigen::VectorXd& v) const {
  const int h = static_cast<int>(held_.size());
  mu_.resize(h);
  for (int a = 0; a < h; ++a) {
    const Column& c = *held_columns_[a];
    double sum = 0.0;
    for (std::size_t p = 0; p < c.rows.size(); ++p) sum += c.values[p] * v[c.rows[p]];
    mu_[a] = sum;
  }
}

// v_ += W mu_.
void CapacitanceSolve::add_held_columns() const {
  for (std::size_t a = 0; a < held_columns_.size(); ++a) {
    const Column& c = *held_columns_[a];
    for (std::size_t p = 0; p < c.rows.size(); ++p) v_[c.rows[p]] += c.values[p] * mu_[a];
  }
}

void CapacitanceSolve::solve(const SparseCholesky& chol, const Eigen::VectorXd& b, Eigen::VectorXd& y) const {
  v_ = b;
  for (int i : held_) v_[i] = 0.0;
  chol.forward(v_);  // v = L⁻¹ P b̂
  held_products(v_);
  K_.solveInPlace(mu_);
  mu_ = -mu_;
  add_held_columns();  // v − W μ
  chol.backward(v_);   // ŷ = Pᵀ L⁻ᵀ (v − W μ): ŷ_A = 0 up to round-off
  y = v_;
  for (int i : held_) y[i] = b[i];
}

void CapacitanceSolve::set_rhs(const SparseCholesky& chol, const Eigen::VectorXd& r) {
  v0_ = r;
  chol.forward(v0_);
}

void CapacitanceSolve::solve_held(const SparseCholesky& chol, const Eigen::VectorXd& g, Eigen::VectorXd& x) const {
  held_products(v0_);
  for (std::size_t a = 0; a < held_.size(); ++a) mu_[a] = g[held_[a]] - mu_[a];  // ν's g_A − Wᵀ v₀
  K_.solveInPlace(mu_);
  v_ = v0_;
  add_held_columns();  // v₀ + W ν
  chol.backward(v_);   // x = Pᵀ L⁻ᵀ (v₀ + W ν): x_A = g_A up to round-off
  x = v_;
  for (int i : held_) x[i] = g[i];
}

}  // namespace cdyn
