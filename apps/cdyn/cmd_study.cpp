// cmd_study.cpp — `cdyn study`: speed against error (docs/outputs.md, "cdyn study").
//
// Runs a scene once per combination of the --vary values (their Cartesian product,
// the last --vary changing fastest), each run a `cdyn run --quiet` into
// DIR/run_NNN/ with the values as --set overrides (no plots; no field files unless
// --fields), then reads each run's summary.json and history.csv and writes
// DIR/study.csv (one row per run) and DIR/work_precision.png (error against wall
// time, one curve per method, the refinements of a method along it).
//
// The error of a run is the measure --error names (study_error.hpp): exact, energy,
// or a probe's history against the finest run's.  A run that fails numerically gets
// kind "failed" and empty numbers; bad input in any run stops the study (exit status
// 2), naming the run and the key.  Ctrl-C stops the study after the run in progress
// (interrupt.hpp): study.csv holds the runs done, the interrupted one marked
// partial, and the exit status is 130.
#include <charconv>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <limits>
#include <nlohmann/json.hpp>
#include <optional>
#include <sstream>

#include "cdyn/base/error.hpp"
#include "commands.hpp"
#include "embedded_scripts.hpp"
#include "interrupt.hpp"
#include "python_script.hpp"
#include "scene.hpp"
#include "scene_spec.hpp"
#include "study_error.hpp"

namespace cdyn::app {

namespace {

namespace fs = std::filesystem;
constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

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
struct RunResult : RunRecord {
  std::vector<std::string> values;   // of the varied keys
  std::vector<std::string> sets;     // the --set overrides of the run
  std::string failure;               // NumericalError message
};

double number(const nlohmann::json& j, const char* key) {
  return j.contains(key) && j[key].is_number() ? j[key].get<double>() : kNaN;
}

// "run_001 (time.dt=-0.1)": a run and its values, for messages.
std::string run_label(const RunResult& r) {
  std::string values;
  for (std::size_t i = r.sets.size() - r.values.size(); i < r.sets.size(); ++i)
    values += (values.empty() ? "" : " ") + r.sets[i];
  return r.name + " (" + values + ")";
}

void run_one(const StudyOptions& opt, const fs::path& dir, const ErrorMeasure& measure, RunResult& r) {
  RunOptions run{opt.scene, dir.string(), r.sets, true, false, opt.scene_text, ""};
  try {
    cmd_run(run);  // 130 when interrupted: summary.json says partial
  } catch (const NumericalError& e) {
    r.failure = e.what();
    return;
  } catch (const InputError& e) {
    throw InputError(run_label(r) + ": " + e.what());
  }
  std::ifstream in(dir / "summary.json");
  r.summary = nlohmann::json::parse(in);
  r.partial = r.summary.value("partial", false);
  read_history((dir / "history.csv").string(), measure, r);
  r.ok = true;
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

void write_study_csv(const fs::path& path, const std::vector<Variation>& varies, const std::vector<RunResult>& runs,
                     const ErrorMeasure& measure) {
  static const char* kNumbers[] = {"n_dofs", "n_steps", "dt", "h", "wall_s", "s_per_step", "qp_iters_mean", "E_rel_drift"};
  std::ofstream csv(path);
  for (const Variation& v : varies) csv << csv_field(v.key) << ",";
  for (const char* k : kNumbers) csv << k << ",";
  csv << "E_rel_error_T,error,error_kind,error_measure,partial,run\n";
  for (const RunResult& r : runs) {
    for (const std::string& value : r.values) csv << csv_field(value) << ",";
    for (const char* k : kNumbers) csv << csv_number(r.ok ? number(r.summary, k) : kNaN) << ",";
    // |J(T) − J0| against the run's energy scale (summary.json's E_scale: never 0 when J moves)
    const double scale = r.ok ? number(r.summary, "E_scale") : kNaN;
    const double E_error_T =
        r.ok && scale > 0 ? std::abs(number(r.summary, "E_final") - number(r.summary, "E0")) / scale : kNaN;
    csv << csv_number(E_error_T) << "," << csv_number(r.error) << "," << r.error_kind << "," << measure.name() << ","
        << (r.partial ? "true" : "false") << "," << r.name << "\n";
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
  Scene base = Scene::load(opt.scene, opt.scene_text);
  // Plots of each run cost a python start each, field files hundreds of megabytes over
  // a study: off unless asked for (--fields, or a --set turning them on).
  std::vector<std::string> common = {"output.plots=false"};
  if (!opt.fields) common.push_back("output.fields=false");
  for (const std::string& a : command_line_paths(opt.sets)) {
    base.set(a);
    common.push_back(a);
  }
  const fs::path dir = opt.out.empty() ? fs::path("out") / (base.name() + "-study") : fs::path(opt.out);

  std::vector<RunResult> runs;
  std::optional<ErrorMeasure> measure;
  for (const auto& values : product(varies)) {
    RunResult r;
    char name[32];
    std::snprintf(name, sizeof name, "run_%03zu", runs.size());
    r.name = name;
    r.values = values;
    r.sets = common;
    std::vector<std::string> varied;
    for (std::size_t k = 0; k < varies.size(); ++k) varied.push_back(varies[k].key + "=" + values[k]);
    varied = command_line_paths(varied);
    Scene check = base;
    for (std::size_t k = 0; k < varies.size(); ++k) {
      try {
        check.set(varied[k]);
      } catch (const InputError& e) {
        throw InputError("--vary " + varies[k].key + ": " + e.what());
      }
      r.sets.push_back(varied[k]);
    }
    // Every key of every run read and checked here (what needs the mesh is checked
    // when the run builds it), and the error measure resolved on each.
    SceneSpec spec;
    try {
      spec = read_scene(check);
    } catch (const InputError& e) {
      throw InputError(run_label(r) + ": " + e.what());
    }
    const ErrorMeasure m = error_measure(opt.error, spec);
    if (measure && m.name() != measure->name())
      throw InputError("--error " + opt.error + ": means " + measure->name() + " for run_000 but " + m.name() + " for " +
                       r.name + " (give --error)");
    measure = m;
    runs.push_back(std::move(r));
  }

  std::error_code ec;
  fs::create_directories(dir, ec);
  if (ec) throw InputError(dir.string() + ": cannot create the output directory (" + ec.message() + ")");
  fs::remove(dir / "study.csv", ec);  // written last: its presence means the study ended (or was interrupted)
  fs::remove(dir / "work_precision.png", ec);

  std::printf("cdyn study %s: %zu runs into %s, error: %s\n", base.name().c_str(), runs.size(), dir.string().c_str(),
              measure->name().c_str());
  std::fflush(stdout);
  // Ctrl-C: the run in progress stops (its own guard, nested), then the study.
  InterruptGuard guard;
  std::size_t done = 0;
  for (RunResult& r : runs) {
    if (interrupted()) break;
    run_one(opt, dir / r.name, *measure, r);
    ++done;
    std::string values;
    for (std::size_t k = 0; k < varies.size(); ++k) values += " " + varies[k].key + "=" + r.values[k];
    if (!r.ok)
      std::printf("  %s%s: failed (%s)\n", r.name.c_str(), values.c_str(), r.failure.c_str());
    else if (r.partial)
      std::printf("  %s%s: interrupted after %d steps\n", r.name.c_str(), values.c_str(),
                  r.summary["n_steps"].get<int>());
    else
      std::printf("  %s%s: %.3g s\n", r.name.c_str(), values.c_str(), number(r.summary, "wall_s"));
    if (r.ok)
      for (const auto& w : r.summary.value("warnings", nlohmann::json::array()))
        std::printf("    warning: %s\n", w.get<std::string>().c_str());
    std::fflush(stdout);
  }
  const bool stopped = done < runs.size() || interrupted();
  const std::size_t asked = runs.size();
  runs.resize(done);  // the runs not started are left out

  std::vector<RunRecord*> records;
  for (RunResult& r : runs) records.push_back(&r);
  measure_errors(*measure, records);
  write_study_csv(dir / "study.csv", varies, runs, *measure);
  const std::string note = stopped ? "interrupted" : run_python_script(kPlotStudyScript, {dir.string()});
  std::printf("\n");
  print_table(varies, runs);
  std::printf("  Results in %s (study.csv%s)\n", dir.string().c_str(), note.empty() ? ", work_precision.png" : "");
  if (!note.empty() && !stopped && !interrupted())
    std::printf("  Note: no work-precision plot (%s).\n", note.c_str());
  if (stopped || interrupted()) {  // (a Ctrl-C during the plot too)
    const std::string last = runs.empty() ? "" : runs.back().name;
    if (!runs.empty() && runs.back().partial)
      std::fprintf(stderr, "cdyn: study interrupted during %s (run %zu of %zu); study.csv in %s holds the runs done, %s partial\n",
                   last.c_str(), done, asked, dir.string().c_str(), last.c_str());
    else
      std::fprintf(stderr, "cdyn: study interrupted after %zu of %zu runs; study.csv in %s holds them\n", done, asked,
                   dir.string().c_str());
    return 130;
  }
  return 0;
}

}  // namespace cdyn::app
