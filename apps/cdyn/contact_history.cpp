// contact_history.cpp — contact.csv and the impact summary of an elasticity run.
#include "contact_history.hpp"

#include <algorithm>
#include <numeric>
#include <tuple>

#include "cdyn/post/contact_force.hpp"
#include "cdyn/qp/petsc/backend.hpp"

namespace cdyn::app {

namespace {

// A row's columns from the vertex to the pressure (the friction columns follow).
void write_row(std::ostream& csv, int step, double t, int vertex, const Point& a, int dim, double s, double gap,
               double force, double pressure) {
  csv << step << "," << t << "," << vertex << "," << a.x << "," << a.y << ",";
  if (dim == 3) csv << a.z << ",";
  csv << s << "," << gap << "," << force << "," << pressure;
}

}  // namespace

ContactHistory::ContactHistory(const Simulation& sim, const std::filesystem::path& file,
                               const std::filesystem::path& journal, const std::optional<JournalMark>& resume)
    : sim_(sim), mesh_(*sim.mesh), problem_(sim.problem), contact_(sim.problem), csv_(file, journal, resume) {
  friction_ = sim.with_friction;  // (on subdomains rank 0 writes the header for all)
  whole_weight_ = whole_contact_weights(sim, contact_);
  friction_of_.assign(mesh_.n_vertices(), -1);
  for (std::size_t k = 0; k < problem_.friction.size(); ++k)
    friction_of_[problem_.contact_nodes[problem_.friction[k].node].vertex] = static_cast<int>(k);
  if (csv_.resumed()) return;
  csv_.rows() << (mesh_.dim == 3 ? "step,t,vertex,x,y,z,s,gap,force,pressure" : "step,t,vertex,x,y,s,gap,force,pressure")
              << (!friction_         ? "\n"
                  : mesh_.dim == 3 ? ",tangential_force,slip,status,tangential_force_x,tangential_force_y,"
                                     "tangential_force_z,slip_x,slip_y,slip_z\n"
                                   : ",tangential_force,slip,status\n");
  csv_.end_rows();
}

double ContactHistory::record(int step, const State& s, const Eigen::VectorXd& U_full,
                              const Eigen::VectorXd& reaction_xy, bool write) {
  if (sim_.partition) return record_share(step, s, U_full, reaction_xy, write);
  const double t = s.t;
  double total = 0.0;
  std::ostream& csv = csv_.rows();
  const FrictionVectors xy = friction_vectors(s, write);
  const std::vector<ContactPressure::Vertex>& vertices = contact_.vertices();
  for (std::size_t i = 0; i < vertices.size(); ++i) {
    const ContactPressure::Vertex& c = vertices[i];
    const double force = contact_.normal_force(reaction_xy, c);
    total += force;
    if (!write) continue;
    write_row(csv, step, t, c.vertex, mesh_.vertices[c.vertex], mesh_.dim, c.s, contact_.gap(U_full, c, t), force,
              whole_weight_[i] > 0.0 ? force / whole_weight_[i] : 0.0);
    for (double x : friction_columns(s, c.vertex, xy)) csv << "," << x;
    csv << "\n";
  }
  if (write) csv_.end_rows();
  return total;
}

ContactHistory::FrictionVectors ContactHistory::friction_vectors(const State& s, bool write) const {
  if (!write || !friction_ || mesh_.dim != 3) return {};
  return {tangential_xy(problem_, s.reaction), tangential_xy(problem_, s.slip)};
}

std::vector<double> ContactHistory::friction_columns(const State& s, int vertex, const FrictionVectors& xy) const {
  if (!friction_) return {};
  const int k = friction_of_[vertex];
  std::vector<double> out(friction_width(), 0.0);
  if (k < 0) {
    out[2] = -1;
  } else if (s.slip.size() > 0) {  // (zeros before the first step)
    const FrictionNode& node = problem_.friction[k];
    // (in space a length: |·| also where a roller leaves one tangential unknown)
    const auto length = [&](double x) { return mesh_.dim == 3 ? std::abs(x) : x; };
    out[0] = s.reaction.size() ? length(tangential_magnitude(node, s.reaction)) : 0.0;
    out[1] = length(tangential_magnitude(node, s.slip));
    out[2] = s.contact_status[k];
    if (mesh_.dim == 3) {
      const Point F = vertex_force(problem_, xy.force, vertex), D = vertex_force(problem_, xy.slip, vertex);
      const double v[] = {F.x, F.y, F.z, D.x, D.y, D.z};
      std::copy(v, v + 6, out.begin() + 3);
    }
  }
  return out;
}

double ContactHistory::record_share(int step, const State& s, const Eigen::VectorXd& U_full,
                                    const Eigen::VectorXd& reaction_xy, bool write) {
  const Partition& part = *sim_.partition;
  // obstacle, s, vertex, x, y, z, gap, force, pressure, then the friction columns
  const int kColumns = 9 + friction_width();
  std::vector<double> mine;
  double total = 0.0;
  const FrictionVectors xy = friction_vectors(s, write);
  const std::vector<ContactPressure::Vertex>& vertices = contact_.vertices();
  for (std::size_t i = 0; i < vertices.size(); ++i) {
    const ContactPressure::Vertex& c = vertices[i];
    if (!part.owns_vertex[c.vertex]) continue;
    const double force = contact_.normal_force(reaction_xy, c);
    total += force;
    if (!write) continue;
    const Point& a = mesh_.vertices[c.vertex];
    const double w = whole_weight_[i];
    mine.insert(mine.end(), {static_cast<double>(contact_.node(c).obstacle), c.s,
                             static_cast<double>(part.sub.vertex[c.vertex]), a.x, a.y, a.z,
                             contact_.gap(U_full, c, s.t), force, w > 0.0 ? force / w : 0.0});
    for (double x : friction_columns(s, c.vertex, xy)) mine.push_back(x);
  }
  if (!write) return total;
  const std::vector<double> all = petsc::gather_on_first_rank(mine);
  // a serial run's order (ContactPressure's: by obstacle, s, vertex)
  std::vector<int> order(all.size() / kColumns);
  std::iota(order.begin(), order.end(), 0);
  auto key = [&](int k) { return std::tie(all[k * kColumns], all[k * kColumns + 1], all[k * kColumns + 2]); };
  std::sort(order.begin(), order.end(), [&](int a, int b) { return key(a) < key(b); });
  std::ostream& csv = csv_.rows();
  for (int k : order) {
    const double* r = &all[k * kColumns];
    write_row(csv, step, s.t, static_cast<int>(r[2]), Point{r[3], r[4], r[5]}, mesh_.dim, r[1], r[6], r[7], r[8]);
    for (int j = 9; j < kColumns; ++j) csv << "," << r[j];
    csv << "\n";
  }
  csv_.end_rows();
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
