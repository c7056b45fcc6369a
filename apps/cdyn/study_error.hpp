// study_error.hpp — the error of each run of a `cdyn study` (`--error MEASURE`,
// docs/outputs.md, "The error of a run").
//
//   exact              the run's error_exact (‖u_h(T) − u(T)‖_L2; the scene names its
//                      analytic solution, exact.solution);
//   energy             the run's own energy drift E_rel_drift (no reference needed);
//   probe:NAME[:COL]   the probe's history against the finest run's (the successful,
//                      complete run with the smallest dt, then the smallest h):
//                      max over the run's steps of |c(t) − c_ref(t)| / max_t |c_ref(t)|,
//                      c_ref interpolated linearly in t; COL is u (default), v or lambda,
//                      and for elasticity u and v are the vectors (ux, uy), (vx, vy),
//                      ux, uy, vx, vy a component;
//   auto (default)     exact if the scene names an exact solution, else probe:P with P
//                      the scene's first probe (as written), else energy.
#pragma once

#include <limits>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "scene_spec.hpp"

namespace cdyn::app {

struct ErrorMeasure {
  enum class Kind { Exact, Energy, Probe } kind = Kind::Energy;
  std::string probe;                  // Probe: the probe's name
  std::vector<std::string> columns;   // Probe: its history.csv columns (one, or two for a vector)
  std::string name() const;           // "exact", "energy", "probe:centre:u"
};

// The measure `text` asks for on a scene (auto resolved); InputError naming --error
// when it does not apply (no exact solution, no such probe or column).
ErrorMeasure error_measure(const std::string& text, const SceneSpec& spec);

// What the error needs of one run.
struct RunRecord {
  std::string name;                      // run_NNN
  bool ok = false, partial = false;
  nlohmann::json summary;
  std::vector<double> t;                 // history.csv's t
  std::vector<std::vector<double>> c;    // the measure's columns, c[k][row]
  double error = std::numeric_limits<double>::quiet_NaN();
  std::string error_kind;                // exact, finest, reference, energy, failed, partial
};

// Reads the measure's columns of DIR/history.csv into r (InputError when missing).
void read_history(const std::string& history_csv, const ErrorMeasure& m, RunRecord& r);

// Sets error and error_kind of every run.  Returns the index of the reference (the
// finest run) for a probe measure, else -1.
int measure_errors(const ErrorMeasure& m, std::vector<RunRecord*>& runs);

}  // namespace cdyn::app
