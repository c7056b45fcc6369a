// cmd_run.cpp — `cdyn run`: integrate a scene in time and write its results
// (DESIGN.md §5, docs/outputs.md): history.csv (one row per step), summary.json,
// scene.toml (the scene as run), fields.pvd + fields/*.vtu (output.fields) and
// plots/*.png (output.plots).
//
// Every step records the discrete energy J = ½VᵀCV + ½UᵀAU − LᵀU split into its
// kinetic and potential parts, the active constraints, the QP iterations and time,
// and the probes (u, v and the seed's multiplier λ ≤ 0 at named points).  A NaN or a
// QP failure stops the run with the step number (exit status 3), after closing the
// field series so that the blow-up can be looked at; summary.json is written after
// the time loop, so a directory without it is an unfinished run.  The plots come
// last, made from the finished files by the embedded scripts/plot_run.py.
#include <unistd.h>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <nlohmann/json.hpp>
#include <optional>

#include "cdyn/error.hpp"
#include "commands.hpp"
#include "embedded_scripts.hpp"
#include "exact_solution.hpp"
#include "cdyn/fields_output.hpp"
#include "python_script.hpp"
#include "simulation.hpp"

namespace cdyn::app {

namespace {

using Clock = std::chrono::steady_clock;

double seconds_since(Clock::time_point t0) { return std::chrono::duration<double>(Clock::now() - t0).count(); }

// The probe values of the current state: u (full field), v (displacement rate over
// the last step) and λ (the seed's multiplier at the vertex nearest to the probe).
struct ProbeValues {
  double u, v, lambda;
};

ProbeValues probe(const Simulation& sim, const Probe& pr, const Eigen::VectorXd& U_full,
                  const Eigen::VectorXd& rate_full, const State& s) {
  const FESpace& W = *sim.problem.W;
  ProbeValues out{W.value_in_cell(U_full, pr.where.cell, pr.where.xi),
                  W.value_in_cell(rate_full, pr.where.cell, pr.where.xi), 0.0};
  out.lambda = vertex_multiplier(sim.problem, s.reaction, pr.vertex);
  return out;
}

// A one-line progress report on a terminal, rewritten in place.
void progress(int step, int n, double t, double drift, int active, double elapsed) {
  const double eta = step > 0 ? elapsed * (n - step) / step : 0.0;
  std::fprintf(stderr, "\r  step %d/%d  t = %.4g  |J - J0|/|J0| = %.2e  active %d  ETA %.0f s   ", step, n, t, drift,
               active, eta);
  std::fflush(stderr);
}

// A path as a TOML basic string.
std::string toml_string(const std::string& text) {
  std::string out = "\"";
  for (char c : text) {
    if (c == '"' || c == '\\') out += '\\';
    out += c;
  }
  return out + "\"";
}

// The scene as run, to be written next to the results: a relative mesh.file is made
// absolute (by the rule of make_mesh: relative to the scene file's directory, or to
// the current directory for the embedded scene), so that `cdyn run DIR/scene.toml`
// reruns it from anywhere.
Scene scene_as_run(Scene scene, const std::string& scene_file) {
  if (scene.string("mesh.kind", "") != "gmsh") return scene;  // else mesh.file is unused
  std::filesystem::path file = scene.string("mesh.file");
  if (file.is_relative() && !scene_file.empty()) file = std::filesystem::path(scene_file).parent_path() / file;
  scene.set("mesh.file=" + toml_string(std::filesystem::absolute(file).lexically_normal().string()));
  return scene;
}

// An earlier run's files in the same directory go first: a directory holds one run.
void remove_previous_outputs(const std::filesystem::path& out) {
  std::error_code ec;
  std::filesystem::remove(out / "summary.json", ec);
  remove_fields(out);
  for (const char* png : {"energy.png", "probes.png", "contact.png"}) std::filesystem::remove(out / "plots" / png, ec);
}

}  // namespace

std::vector<std::string> command_line_paths(std::vector<std::string> sets) {
  const std::string key = "mesh.file=";
  for (std::string& a : sets) {
    if (a.rfind(key, 0) != 0) continue;
    std::string value = a.substr(key.size());
    if (value.size() >= 2 && (value.front() == '"' || value.front() == '\'') && value.back() == value.front())
      value = value.substr(1, value.size() - 2);
    if (!value.empty() && std::filesystem::path(value).is_relative())
      a = key + toml_string(std::filesystem::absolute(value).lexically_normal().string());
  }
  return sets;
}

int cmd_run(const RunOptions& opt) {
  Scene scene = Scene::load(opt.scene);
  for (const auto& a : command_line_paths(opt.sets)) scene.set(a);
  const bool write_fields = scene.boolean("output.fields", true);
  const bool make_plots = scene.boolean("output.plots", true);
  Simulation sim = make_simulation(scene);
  const auto u_exact = exact_displacement(scene, sim);
  const ConstrainedProblem& p = sim.problem;

  const std::filesystem::path out = opt.out.empty() ? std::filesystem::path("out") / sim.scene_name : std::filesystem::path(opt.out);
  std::error_code ec;
  std::filesystem::create_directories(out, ec);
  if (ec) throw InputError(out.string() + ": cannot create the output directory (" + ec.message() + ")");
  remove_previous_outputs(out);
  std::ofstream(out / "scene.toml") << scene_as_run(scene, opt.scene).dump();
  std::ofstream csv(out / "history.csv");
  if (!csv) throw InputError((out / "history.csv").string() + ": cannot write");
  csv.precision(17);
  csv << "step,t,E_kin,E_pot,E_total,active,qp_iters,solve_s";
  for (const auto& pr : sim.probes) csv << ",u@" << pr.name << ",v@" << pr.name << ",lambda@" << pr.name;
  csv << "\n";

  const bool show_progress = !opt.quiet && isatty(STDERR_FILENO);
  State s = sim.initial;
  const double E0 = sim.scheme->energy(s).total();
  double max_drift = 0.0, max_violation = p.max_violation(s.U), qp_iters = 0.0, qp_seconds = 0.0, E_final = E0;
  int max_active = 0;
  Eigen::VectorXd rate = Eigen::VectorXd::Zero(p.W->n_dofs());

  auto record = [&](int step, const StepStats& st) {
    const Energy E = sim.scheme->energy(s);
    const double Ek = E.kinetic, Ep = E.potential;
    E_final = E.total();
    max_drift = std::max(max_drift, std::abs(E_final - E0) / std::abs(E0));
    csv << step << "," << s.t << "," << Ek << "," << Ep << "," << E_final << "," << st.active << "," << st.qp_iterations
        << "," << st.qp_seconds;
    const Eigen::VectorXd U_full = p.full(s.U);
    for (const auto& pr : sim.probes) {
      const ProbeValues v = probe(sim, pr, U_full, rate, s);
      csv << "," << v.u << "," << v.v << "," << v.lambda;
    }
    csv << "\n";
  };
  // The field series: step 0, every output.every steps and the last step.  Its cost
  // is measured apart and left out of wall_s, which is the cost of the method.
  std::optional<FieldsWriter> fields;
  if (write_fields) fields.emplace(out, *sim.mesh, p);
  double fields_seconds = 0.0;
  auto write_fields_at = [&](int step) {
    if (!fields || (step % sim.output_every != 0 && step != sim.n_steps)) return;
    const auto tf = Clock::now();
    fields->write(step, s.t, p.full(s.U), rate, s.reaction);
    fields_seconds += seconds_since(tf);
  };
  const auto t0 = Clock::now();
  record(0, StepStats{});
  write_fields_at(0);

  for (int n = 1; n <= sim.n_steps; ++n) {
    const Eigen::VectorXd U_old = s.U;
    StepStats st;
    try {
      st = sim.scheme->step(s);
      if (!s.U.allFinite() || !s.V.allFinite()) throw NumericalError("the solution is not finite (NaN or Inf)");
    } catch (const NumericalError& e) {
      if (fields) fields->finish();  // the series up to the failure, for a look at it
      throw NumericalError("step " + std::to_string(n) + " (t = " + std::to_string(s.t + sim.dt) + "): " + e.what());
    }
    rate.setZero();
    const Eigen::VectorXd du = (s.U - U_old) / sim.dt;
    for (int j = 0; j < p.n_free(); ++j) rate[p.bc->free_dofs()[j]] = du[j];
    qp_iters += st.qp_iterations;
    qp_seconds += st.qp_seconds;
    max_active = std::max(max_active, st.active);
    max_violation = std::max(max_violation, p.max_violation(s.U));
    record(n, st);
    write_fields_at(n);
    if (show_progress && (n % 10 == 0 || n == sim.n_steps))
      progress(n, sim.n_steps, s.t, max_drift, st.active, seconds_since(t0));
  }
  const double wall = seconds_since(t0) - fields_seconds;
  if (show_progress) std::fprintf(stderr, "\n");
  csv.close();
  if (fields) fields->finish();

  nlohmann::ordered_json j;
  j["scene"] = sim.scene_name;
  j["model"] = sim.model;
  j["pair"] = sim.pair;
  j["scheme"] = sim.scheme_name;
  j["solver"] = sim.solver_name;
  j["solver_tol"] = sim.tol;
  j["n_dofs"] = p.W->n_dofs();
  j["n_free"] = p.n_free();
  j["n_velocity"] = p.mass->n_velocity();
  j["n_constraints"] = p.constrained.size();
  j["n_steps"] = sim.n_steps;
  j["dt"] = sim.dt;
  j["T"] = s.t;
  j["h"] = sim.mesh->h_max();
  j["E0"] = E0;
  j["E_final"] = E_final;
  j["E_rel_drift"] = max_drift;
  j["max_violation"] = max_violation;
  j["max_active"] = max_active;
  j["wall_s"] = wall;
  j["s_per_step"] = wall / sim.n_steps;
  j["qp_s_per_step"] = qp_seconds / sim.n_steps;
  j["qp_iters_mean"] = qp_iters / sim.n_steps;
  j["fields_s"] = fields_seconds;
  if (u_exact) j["error_exact"] = l2_error_at(sim, *u_exact, s);  // ‖u_h(T) − u(T)‖_L2
  j["wellposed"] = wellposedness_summary(sim);
  std::ofstream(out / "summary.json") << j.dump(2) << "\n";

  std::string plot_note;
  if (make_plots) plot_note = run_python_script(kPlotRunScript, {out.string()});

  if (!opt.quiet) {
    std::printf(
        "cdyn run %s: %s, %s, %s, solver %s.\n  %d dofs (%d free, %d constrained), %d steps of dt = %g to T = %g in "
        "%.3f s (%.3g s/step, %.2f QP iterations per step).\n  Energy J0 = %.10g, J(T) = %.10g, max |J - J0|/|J0| = "
        "%.3e; max constraint violation %.2e.\n  Condition (12): %s.\n  Results in %s\n",
        sim.scene_name.c_str(), sim.model.c_str(), sim.pair.c_str(), sim.scheme_name.c_str(), sim.solver_name.c_str(),
        p.W->n_dofs(), p.n_free(), static_cast<int>(p.constrained.size()), sim.n_steps, sim.dt, s.t, wall,
        wall / sim.n_steps, qp_iters / sim.n_steps, E0, E_final, max_drift, max_violation,
        wellposedness_line(j["wellposed"]).c_str(), out.string().c_str());
    if (!plot_note.empty()) std::printf("  Note: no plots (%s).\n", plot_note.c_str());
  }
  return 0;
}

}  // namespace cdyn::app
