// checkpoint.cpp — a run's checkpoint as named records and back; see checkpoint.hpp.
#include "checkpoint.hpp"

#include "cdyn/base/error.hpp"
#include "cdyn/checkpoint_file.hpp"
#include "cdyn/checksum.hpp"

namespace cdyn::app {

namespace {

std::vector<double> values(const Eigen::VectorXd& v) { return {v.data(), v.data() + v.size()}; }

// Records "prefix.*" of one scheme memory.
void put_memory(CheckpointRecords& r, const SchemeMemory& m) {
  for (const auto& [name, v] : m.vectors) r.numbers["scheme.vector." + name] = values(v);
  for (const auto& [name, x] : m.numbers) r.numbers["scheme.number." + name] = {x};
  for (const auto& [name, v] : m.indices) r.integers["scheme.indices." + name] = {v.begin(), v.end()};
}

SchemeMemory get_memory(const CheckpointRecords& r) {
  SchemeMemory m;
  auto under = [](const std::string& name, const std::string& prefix, std::string& rest) {
    if (name.rfind(prefix, 0) != 0) return false;
    rest = name.substr(prefix.size());
    return true;
  };
  std::string rest;
  for (const auto& [name, v] : r.numbers) {
    if (under(name, "scheme.vector.", rest)) m.vectors[rest] = Eigen::Map<const Eigen::VectorXd>(v.data(), v.size());
    if (under(name, "scheme.number.", rest) && v.size() == 1) m.numbers[rest] = v[0];
  }
  for (const auto& [name, v] : r.integers)
    if (under(name, "scheme.indices.", rest)) m.indices[rest] = {v.begin(), v.end()};
  return m;
}

void put_snapshot(std::vector<double>& out, const ImpactMonitor::Snapshot& s) {
  out.insert(out.end(), {double(s.step), s.t, s.E, s.E_kin, s.P.x, s.P.y, s.P.z});
}

ImpactMonitor::Snapshot get_snapshot(const double*& at) {
  ImpactMonitor::Snapshot s;
  s.step = static_cast<int>(at[0]);
  s.t = at[1], s.E = at[2], s.E_kin = at[3], s.P = {at[4], at[5], at[6]};
  at += 7;
  return s;
}

// The ImpactMonitor's memory as numbers (its steps are integers well below 2⁵³).
std::vector<double> impact_values(const ImpactMonitor::Memory& m) {
  std::vector<double> out;
  for (const auto* s : {&m.previous, &m.before, &m.after}) put_snapshot(out, *s);
  out.insert(out.end(), {double(m.first), double(m.last), double(m.contact_steps), m.t_first, m.t_last, m.peak,
                         m.t_peak, m.force_sum, m.force_tau, m.force_tau2});
  return out;
}

ImpactMonitor::Memory impact_memory(const std::vector<double>& v) {
  ImpactMonitor::Memory m;
  const double* at = v.data();
  m.previous = get_snapshot(at);
  m.before = get_snapshot(at);
  m.after = get_snapshot(at);
  m.first = static_cast<int>(at[0]), m.last = static_cast<int>(at[1]), m.contact_steps = static_cast<int>(at[2]);
  m.t_first = at[3], m.t_last = at[4], m.peak = at[5], m.t_peak = at[6];
  m.force_sum = at[7], m.force_tau = at[8], m.force_tau2 = at[9];
  return m;
}

std::vector<double> totals_values(const RunTotals& t) {
  return {t.qp_iterations, t.qp_seconds,           t.energy_iterations, t.max_kkt,      t.max_reconstruction_kkt,
          t.max_violation, double(t.max_active), t.dissipated,        t.wall_seconds, t.fields_seconds,
          t.data_work,     t.friction_work,        t.reconstruction_seconds, t.reconstruction_iterations};
}

RunTotals totals(const std::vector<double>& v) {
  RunTotals t;
  t.qp_iterations = v[0], t.qp_seconds = v[1], t.energy_iterations = v[2], t.max_kkt = v[3];
  t.max_reconstruction_kkt = v[4], t.max_violation = v[5], t.max_active = static_cast<int>(v[6]);
  t.dissipated = v[7], t.wall_seconds = v[8], t.fields_seconds = v[9], t.data_work = v[10];
  t.friction_work = v[11];
  t.reconstruction_seconds = v[12], t.reconstruction_iterations = v[13];
  return t;
}

// The record `name` of r, of `size` values (0: any); InputError naming the file otherwise.
const std::vector<double>& numbers(const CheckpointRecords& r, const std::string& name, std::size_t size,
                                   const std::filesystem::path& file) {
  const auto it = r.numbers.find(name);
  if (it == r.numbers.end() || (size && it->second.size() != size))
    throw InputError(file.string() + ": not a valid checkpoint: record '" + name + "' missing or of the wrong size");
  return it->second;
}

}  // namespace

std::string scene_fingerprint(const std::string& scene_text) { return hex(fnv1a(scene_text)); }

std::filesystem::path checkpoint_file(const std::filesystem::path& out, int rank) {
  return checkpoint_dir(out) / (rank == 0 ? std::string("state.bin") : "state.rank" + std::to_string(rank) + ".bin");
}

void write_checkpoint(const std::filesystem::path& out, const RunCheckpoint& c, int rank) {
  CheckpointRecords r;
  r.texts["scene"] = c.scene_hash;
  r.integers["step"] = {c.step};
  r.numbers["t"] = {c.state.t};
  r.numbers["U"] = values(c.state.U);
  r.numbers["V"] = values(c.state.V);
  r.numbers["reaction"] = values(c.state.reaction);
  put_memory(r, c.scheme);
  r.numbers["E_initial"] = {c.E_initial.kinetic, c.E_initial.potential};
  r.numbers["drift"] = {c.drift_abs, c.drift_half_sum};
  r.numbers["totals"] = totals_values(c.totals);
  r.integers["journal.history"] = {std::int64_t(c.history.history.length), std::int64_t(c.history.history.hash)};
  r.integers["journal.contact"] = {std::int64_t(c.history.contact.length), std::int64_t(c.history.contact.hash)};
  r.numbers["impact"] = impact_values(c.history.impact);
  r.numbers["max_penetration"] = {c.history.max_penetration};
  r.numbers["rate"] = values(c.rate);
  for (const auto& [step, t] : c.frames) {
    r.integers["frames.step"].push_back(step);
    r.numbers["frames.t"].push_back(t);
  }
  if (!c.cells.empty()) r.integers["cells"] = {c.cells.begin(), c.cells.end()};
  std::filesystem::create_directories(checkpoint_dir(out));
  write_checkpoint_file(checkpoint_file(out, rank), r);
}

RunCheckpoint read_checkpoint(const std::filesystem::path& out, const std::string& scene_text, int rank) {
  const std::filesystem::path file = checkpoint_file(out, rank);
  if (!std::filesystem::exists(file))
    throw InputError(file.string() + ": no checkpoint to resume from (the run had output.checkpoint_every = 0, "
                                     "or it completed)");
  const CheckpointRecords r = read_checkpoint_file(file);
  RunCheckpoint c;
  const auto scene = r.texts.find("scene");
  c.scene_hash = scene == r.texts.end() ? "" : scene->second;
  if (c.scene_hash != scene_fingerprint(scene_text))
    throw InputError(file.string() + ": written for another scene (" + (out / "scene.toml").string() +
                     " has changed since)");
  auto integers = [&](const std::string& name, std::size_t size) -> const std::vector<std::int64_t>& {
    const auto it = r.integers.find(name);
    if (it == r.integers.end() || it->second.size() != size)
      throw InputError(file.string() + ": not a valid checkpoint: record '" + name + "' missing or of the wrong size");
    return it->second;
  };
  auto vector = [&](const std::string& name) {
    const std::vector<double>& v = numbers(r, name, 0, file);
    return Eigen::VectorXd(Eigen::Map<const Eigen::VectorXd>(v.data(), v.size()));
  };
  c.step = static_cast<int>(integers("step", 1)[0]);
  c.state.t = numbers(r, "t", 1, file)[0];
  c.state.U = vector("U");
  c.state.V = vector("V");
  c.state.reaction = vector("reaction");
  c.scheme = get_memory(r);
  const std::vector<double>& E = numbers(r, "E_initial", 2, file);
  c.E_initial = {E[0], E[1]};
  const std::vector<double>& drift = numbers(r, "drift", 2, file);
  c.drift_abs = drift[0], c.drift_half_sum = drift[1];
  c.totals = totals(numbers(r, "totals", 14, file));
  for (auto [name, mark] :
       {std::pair{"journal.history", &c.history.history}, std::pair{"journal.contact", &c.history.contact}}) {
    const std::vector<std::int64_t>& m = integers(name, 2);
    *mark = {std::uint64_t(m[0]), std::uint64_t(m[1])};
  }
  c.history.impact = impact_memory(numbers(r, "impact", 31, file));
  c.history.max_penetration = numbers(r, "max_penetration", 1, file)[0];
  c.rate = vector("rate");
  const auto steps = r.integers.find("frames.step");
  const auto times = r.numbers.find("frames.t");
  if (steps != r.integers.end() && times != r.numbers.end() && steps->second.size() == times->second.size())
    for (std::size_t k = 0; k < steps->second.size(); ++k)
      c.frames.emplace_back(static_cast<int>(steps->second[k]), times->second[k]);
  if (const auto cells = r.integers.find("cells"); cells != r.integers.end())
    c.cells.assign(cells->second.begin(), cells->second.end());
  return c;
}

}  // namespace cdyn::app
