// contact_history.cpp — contact.csv and the impact summary of an elasticity run.
#include "contact_history.hpp"

namespace cdyn::app {

ContactHistory::ContactHistory(const Simulation& sim, const std::filesystem::path& file,
                               const std::filesystem::path& journal, const std::optional<JournalMark>& resume)
    : mesh_(*sim.mesh), contact_(sim.problem), csv_(file, journal, resume) {
  if (csv_.resumed()) return;
  csv_.rows() << (mesh_.dim == 3 ? "step,t,vertex,x,y,z,s,gap,force,pressure\n"
                                  : "step,t,vertex,x,y,s,gap,force,pressure\n");
  csv_.end_rows();
}

double ContactHistory::record(int step, double t, const Eigen::VectorXd& U_full, const Eigen::VectorXd& reaction_xy,
                              bool write) {
  double total = 0.0;
  std::ostream& csv = csv_.rows();
  for (const ContactPressure::Vertex& c : contact_.vertices()) {
    const double force = contact_.normal_force(reaction_xy, c);
    total += force;
    if (!write) continue;
    const Point& a = mesh_.vertices[c.vertex];
    csv << step << "," << t << "," << c.vertex << "," << a.x << "," << a.y << ",";
    if (mesh_.dim == 3) csv << a.z << ",";
    csv << c.s << ","
        << contact_.gap(U_full, c, t) << "," << force << "," << (c.weight > 0.0 ? force / c.weight : 0.0) << "\n";
  }
  if (write) csv_.end_rows();
  return total;
}

namespace {

nlohmann::ordered_json snapshot_json(const std::optional<ImpactMonitor::Snapshot>& s, int dim) {
  if (!s) return nullptr;
  nlohmann::ordered_json j;
  j["step"] = s->step;
  j["t"] = s->t;
  j["E"] = s->E;
  j["E_kin"] = s->E_kin;
  j["momentum"] = dim == 3 ? nlohmann::ordered_json{s->P.x, s->P.y, s->P.z} : nlohmann::ordered_json{s->P.x, s->P.y};
  return j;
}

}  // namespace

nlohmann::ordered_json impact_json(const ImpactMonitor::Summary& s, int dim) {
  nlohmann::ordered_json j;
  j["contact"] = s.contact;
  if (!s.contact) return j;
  j["t_first_contact"] = s.t_first;
  j["t_last_contact"] = s.t_last;
  j["contact_duration"] = s.duration;
  j["contact_steps"] = s.contact_steps;
  j["peak_force"] = s.peak_force;
  j["t_peak_force"] = s.t_peak_force;
  j["impulse"] = s.impulse;
  j["t_force_centroid"] = s.t_force_centroid;
  j["force_width"] = s.force_width;
  j["half_sine_duration"] = s.half_sine_duration;
  j["half_sine_peak_force"] = s.half_sine_peak_force;
  j["before"] = snapshot_json(s.before, dim);
  j["after"] = snapshot_json(s.after, dim);
  return j;
}

}  // namespace cdyn::app
