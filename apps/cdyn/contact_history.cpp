// contact_history.cpp — contact forces, pressures, momentum and the impact summary of
// an elasticity run (see contact_history.hpp for the definitions).
#include "contact_history.hpp"

#include <algorithm>
#include <cmath>
#include <map>
#include <numbers>

#include "cdyn/problems/elastic_contact.hpp"
#include "cdyn/base/error.hpp"

namespace cdyn::app {

Point vertex_force(const ConstrainedProblem& p, const Eigen::VectorXd& reaction_xy, int vertex) {
  double F[2] = {0.0, 0.0};
  if (reaction_xy.size() == 0) return {0.0, 0.0};
  for (int k : {0, 1}) {
    const int i = p.bc->free_index(p.W->vertex_dof(vertex, k));
    if (i >= 0) F[k] = reaction_xy[i];
  }
  return {F[0], F[1]};
}

double normal_multiplier(const Simulation& sim, const Eigen::VectorXd& reaction_xy, int vertex) {
  if (!std::binary_search(sim.constrained_vertices.begin(), sim.constrained_vertices.end(), vertex)) return 0.0;
  const Point F = vertex_force(sim.problem, reaction_xy, vertex);
  return 0.0 - (F.x * sim.plane_normal.x + F.y * sim.plane_normal.y);  // 0.0 − : no printed −0
}

LinearMomentum::LinearMomentum(const Simulation& sim) : p_(sim.problem) {
  const Field one = [](double, double, double) { return 1.0; }, zero = zero_field;
  T_[0] = p_.bc->restrict(p_.W->interpolate(std::vector<Field>{one, zero}));
  T_[1] = p_.bc->restrict(p_.W->interpolate(std::vector<Field>{zero, one}));
}

Point LinearMomentum::operator()(const Eigen::VectorXd& V) const {
  const Eigen::VectorXd BtV = p_.global(p_.mass->momentum(V));  // Cartesian free components
  return {BtV.dot(T_[0]), BtV.dot(T_[1])};
}

ContactHistory::ContactHistory(const Simulation& sim, const std::filesystem::path& file)
    : sim_(sim), file_(file), csv_(file_.stream()) {
  csv_.precision(17);
  csv_ << "step,t,vertex,x,y,s,gap,force,pressure\n";
  // w(a): half of each Γ_C edge to each of its two vertices.
  const Mesh& mesh = *sim.mesh;
  std::map<int, double> weight;
  for (const BoundaryFacet& f : mesh.boundary) {
    if (std::find(sim.contact_parts.begin(), sim.contact_parts.end(), f.part) == sim.contact_parts.end()) continue;
    const Point &a = mesh.vertices[f.vertices[0]], &b = mesh.vertices[f.vertices[1]];
    const double half = 0.5 * std::hypot(b.x - a.x, b.y - a.y);
    weight[f.vertices[0]] += half;
    weight[f.vertices[1]] += half;
  }
  const Point n = sim.plane_normal, p = sim.plane_point;
  for (int v : sim.constrained_vertices) {
    const Point& a = mesh.vertices[v];
    vertices_.push_back({v, -(a.x - p.x) * n.y + (a.y - p.y) * n.x, weight[v]});
  }
  std::sort(vertices_.begin(), vertices_.end(), [](const Vertex& a, const Vertex& b) { return a.s < b.s; });
}

double ContactHistory::record(int step, double t, const Eigen::VectorXd& U_full, const Eigen::VectorXd& reaction_xy,
                              bool write) {
  const Mesh& mesh = *sim_.mesh;
  const FESpace& W = *sim_.problem.W;
  const Point n = sim_.plane_normal, p = sim_.plane_point;
  double total = 0.0;
  for (const Vertex& c : vertices_) {
    const Point F = vertex_force(sim_.problem, reaction_xy, c.vertex);
    const double force = F.x * n.x + F.y * n.y;
    total += force;
    if (!write) continue;
    const Point& a = mesh.vertices[c.vertex];
    // (a + u(a) − p)·n ≥ 0: the distance to the plane, negative if it penetrates.
    const double gap = (a.x + U_full[W.vertex_dof(c.vertex, 0)] - p.x) * n.x +
                       (a.y + U_full[W.vertex_dof(c.vertex, 1)] - p.y) * n.y;
    csv_ << step << "," << t << "," << c.vertex << "," << a.x << "," << a.y << "," << c.s << "," << gap << ","
         << force << "," << (c.weight > 0.0 ? force / c.weight : 0.0) << "\n";
  }
  return total;
}

void ImpactMonitor::observe(const Snapshot& now, int active, double contact_force) {
  if (active > 0) {
    if (first_ < 0) {
      first_ = now.step;
      t_first_ = now.t;
      before_ = previous_;
    }
    last_ = now.step;
    t_last_ = now.t;
    ++contact_steps_;
    after_ = Snapshot{};  // not released yet
    // The force's moments about t_first (t − t_first is small: no cancellation in σ²).
    const double tau = now.t - t_first_;
    force_sum_ += contact_force;
    force_tau_ += contact_force * tau;
    force_tau2_ += contact_force * tau * tau;
  } else if (first_ >= 0 && after_.step < 0) {
    after_ = now;
  }
  if (contact_force > peak_) {
    peak_ = contact_force;
    t_peak_ = now.t;
  }
  previous_ = now;
}

namespace {

nlohmann::ordered_json snapshot_json(const ImpactMonitor::Snapshot& s) {
  if (s.step < 0) return nullptr;
  nlohmann::ordered_json j;
  j["step"] = s.step;
  j["t"] = s.t;
  j["E"] = s.E;
  j["E_kin"] = s.E_kin;
  j["momentum"] = {s.P.x, s.P.y};
  return j;
}

}  // namespace

nlohmann::ordered_json ImpactMonitor::summary(double dt) const {
  nlohmann::ordered_json j;
  if (first_ < 0) {
    j["contact"] = false;
    return j;
  }
  j["contact"] = true;
  j["t_first_contact"] = t_first_;
  j["t_last_contact"] = t_last_;
  j["contact_duration"] = t_last_ - t_first_ + dt;
  j["contact_steps"] = contact_steps_;
  j["peak_force"] = peak_;
  j["t_peak_force"] = t_peak_;
  // The smooth functionals of the force history F(t) (one value per step, the step's
  // mean force, placed at the step's midpoint t − dt/2): the impulse I = ∫F dt, the
  // centroid t̄ = ∫F t dt / I and the width σ = (∫F (t − t̄)² dt / I)^½.  A half-sine
  // pulse F̂ sin(π(t − t0)/T) has σ = T (1/12 − 1/(2π²))^½ and I = 2F̂T/π, hence the
  // half-sine equivalents T_hs = σ / (1/12 − 1/(2π²))^½ and F_hs = πI / (2T_hs): they
  // converge under refinement where the raw duration and peak jump with the waves
  // (docs/experiments.md, "The falling disk").
  const double impulse = force_sum_ * dt;
  const double tau_bar = force_sum_ > 0.0 ? force_tau_ / force_sum_ : 0.0;
  const double sigma = force_sum_ > 0.0 ? std::sqrt(std::max(0.0, force_tau2_ / force_sum_ - tau_bar * tau_bar)) : 0.0;
  const double half_sine_ratio = std::sqrt(1.0 / 12.0 - 1.0 / (2.0 * std::numbers::pi * std::numbers::pi));
  const double T_hs = sigma / half_sine_ratio;
  j["impulse"] = impulse;
  j["t_force_centroid"] = t_first_ + tau_bar - 0.5 * dt;
  j["force_width"] = sigma;
  j["half_sine_duration"] = T_hs;
  j["half_sine_peak_force"] = T_hs > 0.0 ? std::numbers::pi * impulse / (2.0 * T_hs) : 0.0;
  j["before"] = snapshot_json(before_);
  j["after"] = snapshot_json(after_);
  return j;
}

}  // namespace cdyn::app
