// study_error.cpp — the error measures of `cdyn study` (study_error.hpp).
#include "study_error.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <sstream>

#include "cdyn/base/error.hpp"

namespace cdyn::app {

namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
constexpr double kTiny = 1e-300;  // guards the relative error against a probe that never moves

double number(const nlohmann::json& j, const char* key) {
  return j.contains(key) && j[key].is_number() ? j[key].get<double>() : kNaN;
}

std::string joined(const std::vector<std::string>& names) {
  std::string out;
  for (const std::string& n : names) out += (out.empty() ? "" : ", ") + n;
  return out.empty() ? "none" : out;
}

// The probes of a run's history, in the scene's order (the oscillator's one dof is
// probed as "mass" when the scene names none, simulation.cpp).
std::vector<std::string> probe_names(const SceneSpec& spec) {
  std::vector<std::string> out;
  for (const auto& [name, at] : spec.output.probes) out.push_back(name);
  if (out.empty() && spec.physics.model == "oscillator") out.push_back("mass");
  return out;
}

// |c(row)|: the Euclidean norm over the measure's columns.
double norm_at(const std::vector<std::vector<double>>& c, std::size_t row) {
  double s = 0.0;
  for (const auto& column : c) s += column[row] * column[row];
  return std::sqrt(s);
}

// max over the run's rows with t ≤ the reference's end of |c(t) − c_ref(t)| /
// max_t |c_ref(t)|, c_ref linear between the reference's rows.
double history_error(const RunRecord& r, const RunRecord& ref) {
  double amplitude = 0.0;
  for (std::size_t i = 0; i < ref.t.size(); ++i) amplitude = std::max(amplitude, norm_at(ref.c, i));
  const double end = ref.t.back(), slack = 1e-9 * std::max(std::abs(end), 1.0);  // t = n·dt carries round-off
  double worst = 0.0;
  for (std::size_t i = 0; i < r.t.size() && r.t[i] <= end + slack; ++i) {
    const double t = std::min(r.t[i], end);
    const auto up = std::upper_bound(ref.t.begin(), ref.t.end(), t);
    const std::size_t k = up == ref.t.begin() ? 0 : std::min<std::size_t>(up - ref.t.begin() - 1, ref.t.size() - 1);
    const std::size_t k1 = std::min(k + 1, ref.t.size() - 1);
    const double w = k1 == k ? 0.0 : (t - ref.t[k]) / (ref.t[k1] - ref.t[k]);
    double s = 0.0;
    for (std::size_t col = 0; col < r.c.size(); ++col) {
      const double d = r.c[col][i] - ((1.0 - w) * ref.c[col][k] + w * ref.c[col][k1]);
      s += d * d;
    }
    worst = std::max(worst, std::sqrt(s));
  }
  return worst / std::max(amplitude, kTiny);
}

}  // namespace

std::string ErrorMeasure::name() const {
  if (kind == Kind::Exact) return "exact";
  if (kind == Kind::Energy) return "energy";
  std::string column = columns.front().substr(0, columns.front().find('@'));
  if (columns.size() == 2) column = column.substr(0, 1);  // (ux, uy) → u
  return "probe:" + probe + ":" + column;
}

ErrorMeasure error_measure(const std::string& text, const SceneSpec& spec) {
  const std::vector<std::string> probes = probe_names(spec);
  ErrorMeasure m;
  if (text == "auto") {
    if (!spec.exact_solution.empty()) return error_measure("exact", spec);
    if (!probes.empty()) return error_measure("probe:" + probes.front(), spec);
    return error_measure("energy", spec);
  }
  if (text == "exact") {
    if (spec.exact_solution.empty())
      throw InputError("--error exact: the scene names no exact solution (exact.solution)");
    m.kind = ErrorMeasure::Kind::Exact;
    return m;
  }
  if (text == "energy") return m;
  if (text.rfind("probe:", 0) != 0 || text.size() == 6)
    throw InputError("--error " + text + ": expected auto, exact, energy or probe:NAME[:COLUMN]");
  m.kind = ErrorMeasure::Kind::Probe;
  const std::string rest = text.substr(6);
  const auto colon = rest.find(':');
  m.probe = rest.substr(0, colon);
  const std::string column = colon == std::string::npos ? "u" : rest.substr(colon + 1);
  if (std::find(probes.begin(), probes.end(), m.probe) == probes.end())
    throw InputError("--error " + text + ": no probe '" + m.probe + "' in output.probes (" + joined(probes) + ")");
  const bool vector = spec.physics.model == "elasticity";
  const std::vector<std::string> allowed =
      vector ? std::vector<std::string>{"u", "v", "ux", "uy", "uz", "vx", "vy", "vz", "lambda"}
             : std::vector<std::string>{"u", "v", "lambda"};
  if (std::find(allowed.begin(), allowed.end(), column) == allowed.end())
    throw InputError("--error " + text + ": no column '" + column + "' (" + joined(allowed) + ")");
  const std::string at = "@" + m.probe;
  if (vector && (column == "u" || column == "v"))
    m.columns = {column + "x" + at, column + "y" + at};
  else
    m.columns = {column + at};
  return m;
}

void read_history(const std::string& history_csv, const ErrorMeasure& m, RunRecord& r) {
  if (m.kind != ErrorMeasure::Kind::Probe) return;
  std::ifstream in(history_csv);
  std::string header, line, cell;
  std::getline(in, header);
  std::vector<std::string> names;
  for (std::stringstream h(header); std::getline(h, cell, ',');) names.push_back(cell);
  auto index = [&](const std::string& column) {
    const auto it = std::find(names.begin(), names.end(), column);
    if (it == names.end()) throw InputError("--error " + m.name() + ": " + history_csv + " has no column " + column);
    return static_cast<std::size_t>(it - names.begin());
  };
  const std::size_t it = index("t");
  std::vector<std::size_t> ic;
  for (const std::string& c : m.columns) ic.push_back(index(c));
  // u or v of a body in space: (ux, uy) and uz, which only the history's header tells
  if (m.columns.size() == 2) {
    const std::string z = m.columns[0].substr(0, 1) + "z" + m.columns[0].substr(2);
    if (const auto at = std::find(names.begin(), names.end(), z); at != names.end())
      ic.push_back(static_cast<std::size_t>(at - names.begin()));
  }
  r.t.clear();
  r.c.assign(ic.size(), {});
  std::vector<std::string> values;
  while (std::getline(in, line)) {
    if (line.empty()) continue;
    values.clear();
    for (std::stringstream v(line); std::getline(v, cell, ',');) values.push_back(cell);
    r.t.push_back(std::stod(values.at(it)));
    for (std::size_t k = 0; k < ic.size(); ++k) r.c[k].push_back(std::stod(values.at(ic[k])));
  }
}

int measure_errors(const ErrorMeasure& m, std::vector<RunRecord*>& runs) {
  int finest = -1;
  if (m.kind == ErrorMeasure::Kind::Probe) {
    for (std::size_t i = 0; i < runs.size(); ++i) {
      const RunRecord& r = *runs[i];
      if (!r.ok || r.partial || r.t.empty()) continue;
      const double dt = number(r.summary, "dt"), h = number(r.summary, "h");
      if (finest < 0) {
        finest = static_cast<int>(i);
        continue;
      }
      const double dt_f = number(runs[finest]->summary, "dt"), h_f = number(runs[finest]->summary, "h");
      if (dt < dt_f || (dt == dt_f && h < h_f)) finest = static_cast<int>(i);
    }
  }
  for (std::size_t i = 0; i < runs.size(); ++i) {
    RunRecord& r = *runs[i];
    r.error = kNaN;
    if (!r.ok) {
      r.error_kind = "failed";
    } else if (r.partial) {
      r.error_kind = "partial";  // stopped before T: not comparable
    } else if (m.kind == ErrorMeasure::Kind::Exact) {
      r.error = number(r.summary, "error_exact");
      r.error_kind = "exact";
    } else if (m.kind == ErrorMeasure::Kind::Energy) {
      r.error = number(r.summary, "E_rel_drift");
      r.error_kind = "energy";
    } else if (static_cast<int>(i) == finest) {
      r.error_kind = "reference";
    } else {
      const RunRecord& ref = *runs[finest];
      r.error = history_error(r, ref);
      r.error_kind = "finest";
      // The histories are compared on [0, T] of the finest run: a run ending elsewhere is
      // compared on part of its history only.
      const double T = number(r.summary, "T"), T_ref = number(ref.summary, "T");
      if (std::abs(T - T_ref) > 1e-9 * std::abs(T_ref))
        std::printf("  note: %s ends at T = %.10g, the finest run at T = %.10g (choose dt that divide time.T)\n",
                    r.name.c_str(), T, T_ref);
    }
  }
  return finest;
}

}  // namespace cdyn::app
