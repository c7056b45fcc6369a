// run_summary.hpp — the end of `cdyn run` (docs/outputs.md): summary.json and the
// final paragraph, from what the time loop leaves.
#pragma once

#include <filesystem>
#include <functional>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <vector>

#include "run_history.hpp"
#include "run_report.hpp"
#include "simulation.hpp"

namespace cdyn::app {

// What the time loop leaves for the report.
struct RunOutcome {
  const Simulation& sim;
  std::filesystem::path out;
  const State& state;        // the last state computed
  int steps_done = 0;
  bool partial = false;      // interrupted before T
  int resumed_at = -1;       // the checkpoint's step for a resumed run, else −1
  double E0 = 0, E_final = 0;
  const EnergyDrift& drift;
  const RunTotals& totals;   // wall_seconds and fields_seconds: the whole run's
  const History& history;
  std::vector<std::string> warnings;
  std::optional<std::function<double(double, double)>> u_exact;
};

// summary.json's content.
nlohmann::ordered_json run_summary(const RunOutcome& r);

// The final paragraph on stdout (summary: run_summary's; plot_note: why there are no plots).
void print_run_paragraph(const RunOutcome& r, const nlohmann::ordered_json& summary, const std::string& plot_note);

}  // namespace cdyn::app
