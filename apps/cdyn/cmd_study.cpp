// cmd_study.cpp — `cdyn study`: speed against error (docs/outputs.md, "cdyn study").
//
// Runs a scene once per combination of the --vary values (their Cartesian product,
// the last --vary changing fastest), each run a `cdyn run --quiet` into
// DIR/run_NNN/ with the values as --set overrides, then reads each run's
// summary.json and history.csv and writes DIR/study.csv (one row per run) and
// DIR/work_precision.png (error against wall time, one curve per method).
//
// The error of a run (docs/outputs.md):
//   - "exact":  the run's summary.json has a numeric error_exact (the scene knows
//               its analytic solution);
//   - "finest": else, against the finest run (smallest dt, then smallest h), at the
//               final time: |u@P − u@P_finest| / max(|u@P_finest|, tiny) for the
//               first probe P, or |J − J_finest| / |J_finest| when there is no probe.
//               The finest run is the reference: its error is empty (kind
//               "reference") and it is not plotted.
// A run that fails numerically gets kind "failed" and empty numbers; bad input in
// any run stops the study (exit status 2), naming the run and the key.
#include <charconv>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <limits>
#include <nlohmann/json.hpp>
#include <sstream>

#include "cdyn/base/error.hpp"
#include "commands.hpp"
#include "embedded_scripts.hpp"
#include "python_script.hpp"
#include "scene.hpp"

namespace cdyn::app {

namespace {

namespace fs = std::filesystem;
constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
constexpr double kTiny = 1e-300;  // guards the relative error against u_finest = 0

struct Variation {
  std::string key;
  std::vector<std::string> values;
};

// "v1,v2,..." split at the commas outside brackets, parentheses and quotes, so that
// arrays ([0.5, 0.5]) and expressions (min(x, y)) can be values.
std::vector<std::string> split_values(const std::string& list) {
  std::vector<std::string> out(1);
  int depth = 0;
  char quote = 0;
  for (char c : list) {
    if (quote) {
      if (c == quote) quote = 0;
    } else if (c == '"' || c == '\'') {
      quote = c;
    } else if (c == '[' || c == '(' || c == '{') {
      ++depth;
    } else if (c == ']' || c == ')' || c == '}') {
      --depth;
    } else if (c == ',' && depth == 0) {
      out.emplace_back();
      continue;
    }
    out.back() += c;
  }
  return out;
}

Variation parse_vary(const std::string& arg) {
  const auto eq = arg.find('=');
  if (eq == std::string::npos || eq == 0 || eq + 1 == arg.size())
    throw InputError("--vary " + arg + ": expected key=v1,v2,...");
  Variation v{arg.substr(0, eq), split_values(arg.substr(eq + 1))};
  for (const auto& value : v.values)
    if (value.empty()) throw InputError("--vary " + v.key + ": an empty value in '" + arg.substr(eq + 1) + "'");
  return v;
}

// Every combination of the values, the last variation changing fastest.
std::vector<std::vector<std::string>> product(const std::vector<Variation>& varies) {
  std::vector<std::vector<std::string>> out = {{}};
  for (const Variation& v : varies) {
    std::vector<std::vector<std::string>> next;
    for (const auto& head : out)
      for (const auto& value : v.values) {
        next.push_back(head);
        next.back().push_back(value);
      }
    out = std::move(next);
  }
  return out;
}

// What a study keeps of one run.
struct RunResult {
  std::string name;                  // run_NNN
  std::vector<std::string> values;   // of the varied keys
  std::vector<std::string> sets;     // the --set overrides of the run
  bool ok = false;
  std::string failure;               // NumericalError message
  nlohmann::json summary;
  std::string probe;                 // first probe's name ("" if none)
  double u_probe = kNaN;             // u@probe at the final time
  double error = kNaN;
  std::string error_kind;
};

double number(const nlohmann::json& j, const char* key) {
  return j.contains(key) && j[key].is_number() ? j[key].get<double>() : kNaN;
}

// The first probe's name and u at the last row of history.csv.
void read_first_probe(const fs::path& history, RunResult& r) {
  std::ifstream in(history);
  std::string header, line, last;
  std::getline(in, header);
  while (std::getline(in, line))
    if (!line.empty()) last = line;
  std::vector<std::string> names, values;
  for (std::stringstream h(header); std::getline(h, line, ',');) names.push_back(line);
  for (std::stringstream v(last); std::getline(v, line, ',');) values.push_back(line);
  for (std::size_t c = 0; c < names.size() && c < values.size(); ++c)
    if (names[c].rfind("u@", 0) == 0) {
      r.probe = names[c].substr(2);
      r.u_probe = std::stod(values[c]);
      return;
    }
}

void run_one(const StudyOptions& opt, const fs::path& dir, RunResult& r) {
  RunOptions run{opt.scene, dir.string(), r.sets, true};
  try {
    cmd_run(run);
  } catch (const NumericalError& e) {
    r.failure = e.what();
    return;
  } catch (const InputError& e) {
    std::string values;
    for (std::size_t i = r.sets.size() - r.values.size(); i < r.sets.size(); ++i) values += (values.empty() ? "" : " ") + r.sets[i];
    throw InputError(r.name + " (" + values + "): " + e.what());
  }
  std::ifstream in(dir / "summary.json");
  r.summary = nlohmann::json::parse(in);
  read_first_probe(dir / "history.csv", r);
  r.ok = true;
}

// The errors of all runs (see the header): exact where known, else against the finest.
void measure_errors(std::vector<RunResult>& runs) {
  const RunResult* finest = nullptr;
  for (const RunResult& r : runs) {
    if (!r.ok) continue;
    const double dt = number(r.summary, "dt"), h = number(r.summary, "h");
    if (!finest || dt < number(finest->summary, "dt") ||
        (dt == number(finest->summary, "dt") && h < number(finest->summary, "h")))
      finest = &r;
  }
  for (RunResult& r : runs) {
    if (!r.ok) {
      r.error_kind = "failed";
    } else if (const double exact = number(r.summary, "error_exact"); !std::isnan(exact)) {
      r.error = exact;
      r.error_kind = "exact";
    } else if (&r == finest) {
      r.error_kind = "reference";
    } else if (!finest->probe.empty() && r.probe == finest->probe) {
      r.error = std::abs(r.u_probe - finest->u_probe) / std::max(std::abs(finest->u_probe), kTiny);
      r.error_kind = "finest";
    } else {
      const double J = number(r.summary, "E_final"), J_ref = number(finest->summary, "E_final");
      r.error = std::abs(J - J_ref) / std::abs(J_ref);
      r.error_kind = "finest";
    }
    // Errors against the finest run compare final states: they must be at one time.
    if (r.error_kind == "finest") {
      const double T = number(r.summary, "T"), T_ref = number(finest->summary, "T");
      if (std::abs(T - T_ref) > 1e-9 * std::abs(T_ref))
        std::printf("  note: %s ends at T = %.10g, the finest run at T = %.10g (choose dt that divide time.T)\n",
                    r.name.c_str(), T, T_ref);
    }
  }
}

// A CSV field: quoted when it holds a comma or a quote (expression values may).
std::string csv_field(const std::string& s) {
  if (s.find_first_of(",\"\n") == std::string::npos) return s;
  std::string out = "\"";
  for (char c : s) out += c == '"' ? std::string("\"\"") : std::string(1, c);
  return out + "\"";
}

// The shortest text that reads back as the same double ("" for NaN: no value).
std::string csv_number(double x) {
  if (std::isnan(x)) return "";
  char buf[32];
  const auto end = std::to_chars(buf, buf + sizeof buf, x).ptr;
  return std::string(buf, end);
}

void write_study_csv(const fs::path& path, const std::vector<Variation>& varies, const std::vector<RunResult>& runs) {
  static const char* kNumbers[] = {"n_dofs", "n_steps", "dt", "h", "wall_s", "s_per_step", "qp_iters_mean", "E_rel_drift"};
  std::ofstream csv(path);
  for (const Variation& v : varies) csv << csv_field(v.key) << ",";
  for (const char* k : kNumbers) csv << k << ",";
  csv << "E_rel_error_T,error,error_kind,run\n";
  for (const RunResult& r : runs) {
    for (const std::string& value : r.values) csv << csv_field(value) << ",";
    for (const char* k : kNumbers) csv << csv_number(r.ok ? number(r.summary, k) : kNaN) << ",";
    const double E_error_T = r.ok ? std::abs(number(r.summary, "E_final") - number(r.summary, "E0")) /
                                        std::abs(number(r.summary, "E0"))
                                  : kNaN;
    csv << csv_number(E_error_T) << "," << csv_number(r.error) << "," << r.error_kind << "," << r.name << "\n";
  }
  if (!csv) throw InputError(path.string() + ": cannot write");
}

void print_table(const std::vector<Variation>& varies, const std::vector<RunResult>& runs) {
  std::printf("  %-8s", "run");
  for (const Variation& v : varies) std::printf(" %14s", v.key.c_str());
  std::printf(" %8s %6s %10s %10s %10s  %s\n", "n_dofs", "steps", "wall_s", "s/step", "error", "kind");
  for (const RunResult& r : runs) {
    std::printf("  %-8s", r.name.c_str());
    for (const std::string& value : r.values) std::printf(" %14s", value.c_str());
    if (!r.ok) {
      std::printf("  failed: %s\n", r.failure.c_str());
      continue;
    }
    char error[16] = "-";
    if (!std::isnan(r.error)) std::snprintf(error, sizeof error, "%.3e", r.error);
    std::printf(" %8d %6d %10.4g %10.3g %10s  %s\n", r.summary["n_dofs"].get<int>(), r.summary["n_steps"].get<int>(),
                number(r.summary, "wall_s"), number(r.summary, "s_per_step"), error, r.error_kind.c_str());
  }
}

}  // namespace

int cmd_study(const StudyOptions& opt) {
  // Check everything before the first run: the scene, the keys, every combination.
  std::vector<Variation> varies;
  for (const std::string& arg : opt.varies) {
    varies.push_back(parse_vary(arg));
    for (std::size_t i = 0; i + 1 < varies.size(); ++i)
      if (varies[i].key == varies.back().key) throw InputError("--vary " + varies.back().key + ": given twice");
  }
  Scene base = Scene::load(opt.scene);
  // Plots of each run cost a python start each: off unless a --set turns them on.
  std::vector<std::string> common = {"output.plots=false"};
  for (const std::string& a : command_line_paths(opt.sets)) {
    base.set(a);
    common.push_back(a);
  }
  const fs::path dir = opt.out.empty() ? fs::path("out") / (base.name() + "-study") : fs::path(opt.out);

  std::vector<RunResult> runs;
  for (const auto& values : product(varies)) {
    RunResult r;
    char name[32];
    std::snprintf(name, sizeof name, "run_%03zu", runs.size());
    r.name = name;
    r.values = values;
    r.sets = common;
    Scene check = base;
    for (std::size_t k = 0; k < varies.size(); ++k) {
      const std::string a = varies[k].key + "=" + values[k];
      try {
        check.set(a);
      } catch (const InputError& e) {
        throw InputError("--vary " + varies[k].key + ": " + e.what());
      }
      r.sets.push_back(a);
    }
    r.sets = command_line_paths(r.sets);
    runs.push_back(std::move(r));
  }

  std::error_code ec;
  fs::create_directories(dir, ec);
  if (ec) throw InputError(dir.string() + ": cannot create the output directory (" + ec.message() + ")");
  fs::remove(dir / "study.csv", ec);  // written last: its presence means the study finished
  fs::remove(dir / "work_precision.png", ec);

  std::printf("cdyn study %s: %zu runs into %s\n", base.name().c_str(), runs.size(), dir.string().c_str());
  for (RunResult& r : runs) {
    run_one(opt, dir / r.name, r);
    std::string values;
    for (std::size_t k = 0; k < varies.size(); ++k) values += " " + varies[k].key + "=" + r.values[k];
    if (r.ok)
      std::printf("  %s%s: %.3g s\n", r.name.c_str(), values.c_str(), number(r.summary, "wall_s"));
    else
      std::printf("  %s%s: failed (%s)\n", r.name.c_str(), values.c_str(), r.failure.c_str());
    std::fflush(stdout);
  }

  measure_errors(runs);
  write_study_csv(dir / "study.csv", varies, runs);
  const std::string note = run_python_script(kPlotStudyScript, {dir.string()});
  std::printf("\n");
  print_table(varies, runs);
  std::printf("  Results in %s (study.csv%s)\n", dir.string().c_str(), note.empty() ? ", work_precision.png" : "");
  if (!note.empty()) std::printf("  Note: no work-precision plot (%s).\n", note.c_str());
  return 0;
}

}  // namespace cdyn::app
