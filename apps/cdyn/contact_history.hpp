// contact_history.hpp — what an elasticity run writes about its contact with the rigid
// plane (docs/outputs.md): contact.csv (the normal contact force, pressure and gap at
// every constrained vertex of Γ_C) and summary.json's "impact".  The quantities
// themselves are the kernel's post-processing (cdyn/post/): ContactPressure, the
// force per vertex, LinearMomentum, ImpactMonitor.
#pragma once

#include <Eigen/Core>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <optional>

#include "cdyn/post/contact_pressure.hpp"
#include "cdyn/post/impact_summary.hpp"
#include "csv_output.hpp"
#include "simulation.hpp"

namespace cdyn::app {

// contact.csv: one row per constrained vertex of Γ_C at each recorded step.
class ContactHistory {
 public:
  // journal: its journal (csv_output.hpp), empty without checkpoints; resume: the mark a
  // checkpoint recorded, for a resumed run.
  ContactHistory(const Simulation& sim, const std::filesystem::path& file, const std::filesystem::path& journal,
                 const std::optional<JournalMark>& resume);

  // On subdomains (partition.hpp) every rank records the vertices it owns, their
  // pressures by their whole share of Γ_C; the first rank writes the rows of all, in
  // the order of a serial run.
  // The total normal contact force Σ F_N(a) of the state (U_full all dofs of W^h,
  // reaction_xy the reaction in Cartesian free components, empty before step 1); writes
  // the rows when `write` is true.
  // With friction the rows add the tangential force (the reaction on the vertex's
  // tangential unknown, along t = (−n_y, n_x)), the slip of the last step along t and
  // the status (0 open, 1 stick, 2 slip; −1 at a vertex without friction).
  double record(int step, const State& s, const Eigen::VectorXd& U_full, const Eigen::VectorXd& reaction_xy, bool write);
  // (the force on this rank's vertices, on subdomains)

  // Gives the file its name (it is written under a temporary one until then: a run
  // that dies leaves no contact.csv that looks complete, atomic_file.hpp).
  void close() { csv_.commit(); }
  JournalMark checkpoint() { return csv_.checkpoint(); }

 private:
  // The rows of a run on subdomains: this rank's gathered on the first, sorted.
  double record_share(int step, const State& s, const Eigen::VectorXd& U_full, const Eigen::VectorXd& reaction_xy,
                      bool write);

  // The friction columns of a vertex (none without friction): the tangential force, the
  // slip, the status, and in space the force's and the slip's x, y, z from these vectors
  // (tangential_xy of the reaction and the slip, made only for a written step in space).
  struct FrictionVectors {
    Eigen::VectorXd force, slip;
  };
  FrictionVectors friction_vectors(const State& s, bool write) const;
  std::vector<double> friction_columns(const State& s, int vertex, const FrictionVectors& xy) const;
  int friction_width() const { return !friction_ ? 0 : mesh_.dim == 3 ? 9 : 3; }

  const Simulation& sim_;
  const Mesh& mesh_;
  const ConstrainedProblem& problem_;
  ContactPressure contact_;
  CsvOutput csv_;
  std::vector<int> friction_of_;  // per vertex of the mesh, its friction node or −1
  bool friction_ = false;
  std::vector<double> whole_weight_;  // w(a) of contact_'s vertices over the whole Γ_C (every rank's)
};

// summary.json's "impact" entry.
nlohmann::ordered_json impact_json(const ImpactMonitor::Summary& s, int dim);

}  // namespace cdyn::app
