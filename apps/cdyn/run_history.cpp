// run_history.cpp — history.csv and contact.csv, row by row; see run_history.hpp.
#include "run_history.hpp"

#include <sstream>

#include "cdyn/post/contact_force.hpp"

namespace cdyn::app {

namespace {

// The probe columns of history.csv: u, v and λ for a scalar field; for elasticity the
// components of u and v (x, y and in space z) and the seed's normal multiplier λ_N ≤ 0.
std::vector<std::string> probe_columns(const Simulation& sim, const Probe& pr) {
  if (sim.components == 1) return {"u@" + pr.name, "v@" + pr.name, "lambda@" + pr.name};
  std::vector<std::string> out;
  for (const char* field : {"u", "v"})
    for (int k = 0; k < sim.components; ++k) out.push_back(field + std::string(1, "xyz"[k]) + "@" + pr.name);
  out.push_back("lambda@" + pr.name);
  return out;
}

// The probe values of the current state, in the order of probe_columns: u (full
// field), v (displacement rate over the last step) at the point, and λ at the vertex
// nearest to it (scalar: the seed's multiplier; elasticity: λ_N = −F·n).  On
// subdomains 0 for the values of a cell or vertex of another rank (partition.hpp).
std::vector<double> probe(const Simulation& sim, const Probe& pr, const Eigen::VectorXd& U_full,
                          const Eigen::VectorXd& rate_full, const Eigen::VectorXd& reaction_xy) {
  const FESpace& W = *sim.problem.W;
  std::vector<double> out;
  for (const Eigen::VectorXd* field : {&U_full, &rate_full})
    for (int k = 0; k < sim.components; ++k)
      out.push_back(pr.where.cell >= 0 ? W.value_in_cell(*field, pr.where.cell, pr.where.xi, k) : 0.0);
  if (pr.vertex < 0) {
    out.push_back(0.0);
    return out;
  }
  const Point lambda = vertex_multiplier(sim.problem, reaction_xy, pr.vertex);
  if (sim.components == 1) {
    out.push_back(lambda.x);
    return out;
  }
  Point n;  // the normal of the obstacle that constrains the vertex (λ = 0 elsewhere)
  for (const auto& c : sim.problem.contact_nodes)
    if (c.vertex == pr.vertex) n = c.normal;
  out.push_back(lambda.x * n.x + lambda.y * n.y + lambda.z * n.z + 0.0);  // λ_N = λ·n (+ 0.0: no −0)
  return out;
}

std::optional<JournalMark> mark(const std::optional<HistoryMemory>& m, JournalMark HistoryMemory::*which) {
  if (!m) return std::nullopt;
  return (*m).*which;
}

}  // namespace

History::History(const Simulation& sim, const std::filesystem::path& out, const std::filesystem::path& journal_dir,
                 const std::optional<HistoryMemory>& resume)
    : sim_(sim),
      reconstructed_(sim.scheme->full_steps() == FullSteps::Reconstructed),
      damped_(sim.spec.time.parameters.damping.active()),
      data_in_t_(sim.data_in_t),
      friction_(sim.with_friction),
      writes_(writes_files(sim)),
      csv_(writes_ ? out / "history.csv" : std::filesystem::path(),
           journal_dir.empty() ? journal_dir : journal_dir / "history.csv", mark(resume, &HistoryMemory::history)) {
  if (resume) {
    impact_ = ImpactMonitor(resume->impact);
    max_penetration_ = resume->max_penetration;
  }
  std::ostringstream csv;  // the header (a resumed run has it among the rows taken back)
  csv << "step,t,E_kin,E_pot,E_total,active,qp_iters,solve_s,step_s";
  if (reconstructed_) csv << ",reconstruction_s";
  if (damped_) csv << ",dissipated";
  if (sim.components > 1) {
    momentum_.emplace(sim.problem);
    csv << ",contact_force,px,py" << (sim.components == 3 ? ",pz" : "");
    if (sim.has_obstacle) {
      contact_.emplace(sim, writes_ ? out / "contact.csv" : std::filesystem::path(),
                       journal_dir.empty() ? journal_dir : journal_dir / "contact.csv", mark(resume, &HistoryMemory::contact));
      penetration_.emplace(sim.problem);
      csv << ",penetration";
    }
  }
  if (data_in_t_) csv << ",data_work";
  if (friction_) csv << ",friction_work";
  for (const auto& pr : sim.probes)
    for (const std::string& c : probe_columns(sim, pr)) csv << "," << c;
  csv << "\n";
  if (csv_.resumed()) return;
  csv_.rows() << csv.str();
  csv_.end_rows();
}

void History::record(int step, const State& s, const StepStats& st, double step_seconds, const Energy& E,
                     const Works& works, const Eigen::VectorXd& rate, const Eigen::VectorXd& reaction_xy) {
  std::ostream& csv = csv_.rows();
  csv << step << "," << s.t << "," << E.kinetic << "," << E.potential << "," << E.total() << "," << st.active << ","
      << st.qp_iterations << "," << st.qp_seconds << "," << step_seconds;
  if (reconstructed_) csv << "," << st.reconstruction_seconds;
  if (damped_) csv << "," << works.dissipated;
  const ConstrainedProblem& p = sim_.problem;
  const Eigen::VectorXd U_full = p.full(s.U);
  if (momentum_) {
    const bool write = step % sim_.contact_every == 0 || step == sim_.n_steps;
    const double force = contact_ ? summed(sim_, contact_->record(step, s, U_full, reaction_xy, write)) : 0.0;
    const Point P = summed(sim_, (*momentum_)(s.V));
    csv << "," << force << "," << P.x << "," << P.y;
    if (sim_.components == 3) csv << "," << P.z;
    impact_.observe({step, s.t, E.total(), E.kinetic, P}, st.active, force);
    if (penetration_) {
      const double depth = largest(sim_, (*penetration_)(U_full, s.t));
      max_penetration_ = std::max(max_penetration_, depth);
      csv << "," << depth;
    }
  }
  if (data_in_t_) csv << "," << works.data;
  if (friction_) csv << "," << works.friction;
  std::vector<double> probes;
  for (const auto& pr : sim_.probes)
    for (double v : probe(sim_, pr, U_full, rate, reaction_xy)) probes.push_back(v);
  summed(sim_, probes);
  for (double v : probes) csv << "," << v;
  csv << "\n";
  csv_.end_rows();
}

HistoryMemory History::checkpoint() {
  HistoryMemory m;
  m.history = csv_.checkpoint();
  if (contact_) m.contact = contact_->checkpoint();
  m.impact = impact_.memory();
  m.max_penetration = max_penetration_;
  return m;
}

void History::close() {
  csv_.commit();
  if (contact_) contact_->close();
}

nlohmann::ordered_json History::impact() const {
  return contact_ ? impact_json(impact_.summary(sim_.dt), sim_.mesh->dim) : nlohmann::ordered_json();
}

}  // namespace cdyn::app
