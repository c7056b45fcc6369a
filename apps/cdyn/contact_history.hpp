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

  // The total normal contact force Σ F_N(a) of the state (U_full all dofs of W^h,
  // reaction_xy the reaction in Cartesian free components, empty before step 1); writes
  // the rows when `write` is true.
  double record(int step, double t, const Eigen::VectorXd& U_full, const Eigen::VectorXd& reaction_xy, bool write);

  // Gives the file its name (it is written under a temporary one until then: a run
  // that dies leaves no contact.csv that looks complete, atomic_file.hpp).
  void close() { csv_.commit(); }
  JournalMark checkpoint() { return csv_.checkpoint(); }

 private:
  const Mesh& mesh_;
  ContactPressure contact_;
  CsvOutput csv_;
};

// summary.json's "impact" entry.
nlohmann::ordered_json impact_json(const ImpactMonitor::Summary& s, int dim);

}  // namespace cdyn::app
