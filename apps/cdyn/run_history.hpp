// run_history.hpp — what `cdyn run` records at every step (docs/outputs.md):
// history.csv (energies, cost, probes; elasticity: contact force, momentum,
// penetration), contact.csv (elasticity against rigid obstacles, every
// output.contact_every steps), and the impact summary and largest penetration of
// summary.json.  With checkpoints the rows also go to journals in the checkpoint folder,
// and a resumed run starts from them (csv_output.hpp, checkpoint.hpp).
#pragma once

#include <Eigen/Core>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <optional>

#include "cdyn/post/contact_pressure.hpp"
#include "cdyn/post/impact_summary.hpp"
#include "cdyn/post/linear_momentum.hpp"
#include "contact_history.hpp"
#include "csv_output.hpp"
#include "simulation.hpp"

namespace cdyn::app {

// What a checkpoint keeps of the records: the journals' marks and the monitors.
struct HistoryMemory {
  JournalMark history, contact;
  ImpactMonitor::Memory impact;
  double max_penetration = 0.0;
};

class History {
 public:
  // Into out/history.csv (and out/contact.csv); journal_dir: the checkpoint folder, empty
  // without checkpoints; resume: the memory of the checkpoint a resumed run starts from.
  History(const Simulation& sim, const std::filesystem::path& out, const std::filesystem::path& journal_dir,
          const std::optional<HistoryMemory>& resume = {});

  // The works from t = 0 the energy is balanced against (each a column only when there is one).
  struct Works {
    double dissipated = 0.0;  // W_d, the Rayleigh damping's
    double data = 0.0;        // W, the data in t's (problems/data_work.hpp)
    double friction = 0.0;    // W_f, the friction forces' (problems/friction.hpp)
  };

  // The row of a step.  step_seconds: the wall time of the scheme's step; rate: the
  // displacement rate over the step on all dofs; reaction_xy: the step's reaction in
  // (x, y) (post/contact_force.hpp).
  void record(int step, const State& s, const StepStats& st, double step_seconds, const Energy& E, const Works& works,
              const Eigen::VectorXd& rate, const Eigen::VectorXd& reaction_xy);

  // The rows so far into the journals; the memory for a checkpoint.
  HistoryMemory checkpoint();

  // The files get their names only here (atomic_file.hpp): at the end of the run, at
  // an interruption or at a numerical failure, never half-written by a killed process.
  void close();

  // summary.json's "impact" (elasticity against rigid obstacles), else null.
  nlohmann::ordered_json impact() const;
  // The largest penetration of the whole boundary into the obstacles so far.
  double max_penetration() const { return max_penetration_; }

 private:
  const Simulation& sim_;
  bool reconstructed_;  // the column `reconstruction_s` (the scheme reconstructs its full steps, eq. 14)
  bool damped_;    // the column `dissipated`
  bool data_in_t_;  // the column `data_work`
  bool friction_;   // the column `friction_work`, and contact.csv's friction columns
  bool writes_;    // the files: all but the first rank of a run on subdomains only take part in the sums
  CsvOutput csv_;
  std::optional<LinearMomentum> momentum_;
  std::optional<ContactHistory> contact_;
  std::optional<BoundaryPenetration> penetration_;
  double max_penetration_ = 0.0;
  ImpactMonitor impact_;
};

}  // namespace cdyn::app
