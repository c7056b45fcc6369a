// cmd_run.cpp — `cdyn run`: integrate a scene in time and write its results
// (docs/outputs.md): history.csv (one row per step), summary.json,
// scene.toml (the scene as run), fields.pvd + fields/*.vtu (output.fields),
// contact.csv (elasticity: the contact force and pressure along Γ_C) and plots/*.png
// (output.plots).
//
// Every step records the discrete energy J = ½VᵀCV + ½UᵀAU − LᵀU split into its
// kinetic and potential parts, the active constraints, the QP iterations and time,
// and the probes (u, v and the seed's multiplier λ ≤ 0 at named points).  A NaN or an
// infinity born in the time loop (in the state, the energy or the data of a step QP)
// or a QP failure stops the run with the step number (exit status 3), after closing
// the history and the field series up to the last good step so that the blow-up can
// be looked at; summary.json is written after the time loop, so a directory without
// it is an unfinished run.  Every file is written under a temporary name and renamed
// when complete (atomic_file.hpp); Ctrl-C stops the loop cleanly: the files hold the
// steps computed, summary.json says "partial": true, the exit status is 130.  The
// plots come last, made from the finished files by the embedded scripts/plot_run.py
// (a Ctrl-C there stops the plots only: the data files are complete; exit 130).
#include <unistd.h>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <nlohmann/json.hpp>
#include <optional>

#include "cdyn/atomic_file.hpp"
#include "cdyn/base/error.hpp"
#include "cdyn/fields_output.hpp"
#include "cdyn/post/contact_force.hpp"
#include "cdyn/post/contact_pressure.hpp"
#include "cdyn/post/linear_momentum.hpp"
#include "commands.hpp"
#include "contact_history.hpp"
#include "derived_fields.hpp"
#include "embedded_scripts.hpp"
#include "diagnostics.hpp"
#include "exact_solution.hpp"
#include "interrupt.hpp"
#include "python_script.hpp"
#include "run_report.hpp"
#include "simulation.hpp"

namespace cdyn::app {

namespace {

using Clock = std::chrono::steady_clock;

double seconds_since(Clock::time_point t0) { return std::chrono::duration<double>(Clock::now() - t0).count(); }

// The probe columns of history.csv: u, v and λ for a scalar field; for elasticity the
// two components of u and v and the seed's normal multiplier λ_N ≤ 0.
std::vector<std::string> probe_columns(const Simulation& sim, const Probe& pr) {
  if (sim.components == 1) return {"u@" + pr.name, "v@" + pr.name, "lambda@" + pr.name};
  return {"ux@" + pr.name, "uy@" + pr.name, "vx@" + pr.name, "vy@" + pr.name, "lambda@" + pr.name};
}

// The probe values of the current state, in the order of probe_columns: u (full
// field), v (displacement rate over the last step) at the point, and λ at the vertex
// nearest to it (scalar: the seed's multiplier; elasticity: λ_N = −F·n).
std::vector<double> probe(const Simulation& sim, const Probe& pr, const Eigen::VectorXd& U_full,
                          const Eigen::VectorXd& rate_full, const Eigen::VectorXd& reaction_xy) {
  const FESpace& W = *sim.problem.W;
  std::vector<double> out;
  for (const Eigen::VectorXd* field : {&U_full, &rate_full})
    for (int k = 0; k < sim.components; ++k) out.push_back(W.value_in_cell(*field, pr.where.cell, pr.where.xi, k));
  const Point lambda = vertex_multiplier(sim.problem, reaction_xy, pr.vertex);
  if (sim.components == 1) {
    out.push_back(lambda.x);
    return out;
  }
  Point n;  // the normal of the obstacle that constrains the vertex (λ = 0 elsewhere)
  for (const auto& c : sim.problem.contact_nodes)
    if (c.vertex == pr.vertex) n = c.normal;
  out.push_back(lambda.x * n.x + lambda.y * n.y + 0.0);  // λ_N = λ·n (+ 0.0: no −0)
  return out;
}

// A one-line progress report on a terminal, rewritten in place.
void progress(int step, int n, double t, double drift, int active, double elapsed) {
  const double eta = step > 0 ? elapsed * (n - step) / step : 0.0;
  std::fprintf(stderr, "\r  step %d/%d  t = %.4g  |J - J0|/E_scale = %.2e  active %d  ETA %.0f s   ", step, n, t, drift,
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
  remove_stale_temporaries(out);  // of a run that was killed
  std::filesystem::remove(out / "summary.json", ec);
  std::filesystem::remove(out / "history.csv", ec);
  std::filesystem::remove(out / "contact.csv", ec);
  remove_fields(out);
  for (const char* png : {"energy.png", "probes.png", "contact.png", "contact_pressure.png"}) std::filesystem::remove(out / "plots" / png, ec);
}

// history.csv (one row per step) and, for elasticity against a plane, contact.csv
// (every output.contact_every steps), the per-step contact force and momentum columns and the
// impact summary.
class History {
 public:
  History(const Simulation& sim, const std::filesystem::path& out)
      : sim_(sim), damped_(sim.spec.time.parameters.damping.active()), file_(out / "history.csv"), csv_(file_.stream()) {
    csv_.precision(17);
    csv_ << "step,t,E_kin,E_pot,E_total,active,qp_iters,solve_s";
    if (damped_) csv_ << ",dissipated";
    if (sim.components == 2) {
      momentum_.emplace(sim.problem);
      csv_ << ",contact_force,px,py";
      if (sim.has_obstacle) {
        contact_.emplace(sim, out / "contact.csv");
        penetration_.emplace(sim.problem);
        csv_ << ",penetration";
      }
    }
    for (const auto& pr : sim.probes)
      for (const std::string& c : probe_columns(sim, pr)) csv_ << "," << c;
    csv_ << "\n";
  }

  // reaction_xy: the step's reaction in (x, y) (post/contact_force.hpp); dissipated: the
  // damping's work W_d from t = 0.
  void record(int step, const State& s, const StepStats& st, const Energy& E, double dissipated,
              const Eigen::VectorXd& rate, const Eigen::VectorXd& reaction_xy) {
    csv_ << step << "," << s.t << "," << E.kinetic << "," << E.potential << "," << E.total() << "," << st.active << ","
         << st.qp_iterations << "," << st.qp_seconds;
    if (damped_) csv_ << "," << dissipated;
    const ConstrainedProblem& p = sim_.problem;
    const Eigen::VectorXd U_full = p.full(s.U);
    if (momentum_) {
      const bool write = step % sim_.contact_every == 0 || step == sim_.n_steps;
      const double force = contact_ ? contact_->record(step, s.t, U_full, reaction_xy, write) : 0.0;
      const Point P = (*momentum_)(s.V);
      csv_ << "," << force << "," << P.x << "," << P.y;
      impact_.observe({step, s.t, E.total(), E.kinetic, P}, st.active, force);
      if (penetration_) {
        const double depth = (*penetration_)(U_full, s.t);
        max_penetration_ = std::max(max_penetration_, depth);
        csv_ << "," << depth;
      }
    }
    for (const auto& pr : sim_.probes)
      for (double v : probe(sim_, pr, U_full, rate, reaction_xy)) csv_ << "," << v;
    csv_ << "\n";
  }

  // The files get their names only here (atomic_file.hpp): at the end of the run, at
  // an interruption or at a numerical failure, never half-written by a killed process.
  void close() {
    file_.commit();
    if (contact_) contact_->close();
  }

  // summary.json's "impact" (elasticity against rigid obstacles), else null.
  nlohmann::ordered_json impact() const { return contact_ ? impact_json(impact_.summary(sim_.dt)) : nlohmann::ordered_json(); }
  // The largest penetration of the whole boundary into the obstacles so far.
  double max_penetration() const { return max_penetration_; }

 private:
  const Simulation& sim_;
  bool damped_;  // the column `dissipated`
  AtomicFile file_;
  std::ostream& csv_;
  std::optional<LinearMomentum> momentum_;
  std::optional<ContactHistory> contact_;
  std::optional<BoundaryPenetration> penetration_;
  double max_penetration_ = 0.0;
  ImpactMonitor impact_;
};

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
  Simulation sim = make_simulation(scene);
  const bool write_fields = sim.spec.output.fields;
  const bool make_plots = sim.spec.output.plots;
  const auto u_exact = exact_displacement(sim);
  const ConstrainedProblem& p = sim.problem;
  const std::vector<std::string> warnings = run_warnings(sim);
  if (opt.warnings)
    for (const std::string& w : warnings) std::fprintf(stderr, "cdyn: warning: %s\n", w.c_str());

  const std::filesystem::path out = opt.out.empty() ? std::filesystem::path("out") / sim.scene_name : std::filesystem::path(opt.out);
  std::error_code ec;
  std::filesystem::create_directories(out, ec);
  if (ec) throw InputError(out.string() + ": cannot create the output directory (" + ec.message() + ")");
  remove_previous_outputs(out);
  write_file_atomically(out / "scene.toml", scene_as_run(scene, opt.scene).dump());
  History history(sim, out);

  const bool show_progress = !opt.quiet && isatty(STDERR_FILENO);
  State s = sim.initial;
  const Energy E_initial = sim.scheme->energy(s);
  const double E0 = E_initial.total();
  EnergyDrift drift(E_initial);
  double max_violation = p.max_violation(s.U), qp_iters = 0.0, qp_seconds = 0.0, E_final = E0;
  double energy_iters = 0.0, max_reconstruction_kkt = 0.0;
  double dissipated = 0.0;  // W_d, the work of the Rayleigh damping from t = 0
  int max_active = 0;
  double max_kkt = 0.0;  // the largest step-QP KKT residual (≤ solver.tol: the steps are solved)
  Eigen::VectorXd rate = Eigen::VectorXd::Zero(p.W->n_dofs());
  Eigen::VectorXd force_xy;  // the last step's reaction in (x, y), for every output

  auto record = [&](int step, const StepStats& st, const Energy& E) {
    E_final = E.total();
    dissipated += st.dissipated;
    drift.observe(E, dissipated);
    force_xy = reaction_xy(p, s.reaction);
    history.record(step, s, st, E, dissipated, rate, force_xy);
  };
  // The field series: step 0, every output.every steps and the last step.  Its cost
  // is measured apart and left out of wall_s, which is the cost of the method.
  std::optional<FieldsWriter> fields;
  if (write_fields) fields.emplace(out, *sim.mesh, p);
  const DerivedFields derived(sim);  // σ, ε, von Mises, contact pressure, regions
  double fields_seconds = 0.0;
  auto write_fields_at = [&](int step) {
    if (!fields || (step % sim.output_every != 0 && step != sim.n_steps)) return;
    const auto tf = Clock::now();
    const Eigen::VectorXd U_full = p.full(s.U);
    fields->write(step, s.t, U_full, rate, force_xy, derived(U_full, force_xy));
    fields_seconds += seconds_since(tf);
  };
  const auto t0 = Clock::now();
  record(0, StepStats{}, E_initial);
  write_fields_at(0);

  int steps_done = 0;
  // Ctrl-C stops the loop after the step in progress (interrupt.hpp); the guard stays
  // through the plots, whose interruption leaves the data files complete.
  InterruptGuard guard;
  for (int n = 1; n <= sim.n_steps && !interrupted(); ++n) {
    const Eigen::VectorXd U_old = s.U;
    StepStats st;
    Energy E;
    // Everything non-finite born here is a numerical failure, not bad input: the data
    // were checked before the loop, so a step QP refusing an infinite r (its input
    // check throws InputError) means the run blew up.
    auto fail = [&](const std::string& what) {
      history.close();  // the history and the field series up to the last good step, for a look at them
      if (fields) fields->finish();
      char at[64];
      std::snprintf(at, sizeof at, "step %d (t = %.6g): ", n, n * sim.dt);  // (s.t: before or after the step)
      throw NumericalError(at + what + "; steps 0 to " + std::to_string(n - 1) + " are in " +
                           (out / "history.csv").string());
    };
    try {
      st = sim.scheme->step(s);
      if (!s.U.allFinite() || !s.V.allFinite()) throw NumericalError("the solution is not finite (NaN or Inf)");
      E = sim.scheme->energy(s);
      if (!std::isfinite(E.total())) throw NumericalError("the energy is not finite (the solution blew up)");
    } catch (const NumericalError& e) {
      fail(e.what());
    } catch (const InputError& e) {
      fail(std::string("non-finite data in the step's QP (") + e.what() +
           "): the solution blew up, or a datum is not finite at this time");
    }
    // the rate in (x, y) (global(): the unknowns are rotated components at the contact
    // nodes of an inclined plane); on the fixed dofs it stays 0 (U_D is constant in time)
    const Eigen::VectorXd du = p.global(s.U - U_old) / sim.dt;
    for (int j = 0; j < p.n_free(); ++j) rate[p.bc->free_dofs()[j]] = du[j];
    qp_iters += st.qp_iterations;
    energy_iters += st.energy_iterations;
    max_reconstruction_kkt = std::max(max_reconstruction_kkt, st.reconstruction_kkt);
    qp_seconds += st.qp_seconds;
    max_active = std::max(max_active, st.active);
    max_kkt = std::max(max_kkt, st.kkt_residual);
    max_violation = std::max(max_violation, p.max_violation(s.U, s.t));
    record(n, st, E);
    steps_done = n;
    write_fields_at(n);
    if (show_progress && (n % 10 == 0 || n == sim.n_steps))
      progress(n, sim.n_steps, s.t, drift.rel(), st.active, seconds_since(t0));
  }
  const bool partial = steps_done < sim.n_steps;
  if (partial && fields && steps_done % sim.output_every != 0) {  // the last state computed
    const auto tf = Clock::now();
    const Eigen::VectorXd U_full = p.full(s.U);
    fields->write(steps_done, s.t, U_full, rate, force_xy, derived(U_full, force_xy));
    fields_seconds += seconds_since(tf);
  }
  const double wall = seconds_since(t0) - fields_seconds;
  if (show_progress) std::fprintf(stderr, "\n");
  history.close();
  if (fields) fields->finish();

  nlohmann::ordered_json j;
  j["scene"] = sim.scene_name;
  j["model"] = sim.model;
  j["pair"] = sim.pair;
  j["scheme"] = sim.scheme_name;
  j["full_steps"] = to_string(sim.scheme->full_steps());
  j["solver"] = sim.solver_name;
  j["solver_tol"] = sim.tol;
  j["n_dofs"] = p.W->n_dofs();
  j["n_free"] = p.n_free();
  j["n_velocity"] = p.mass->n_velocity();
  j["n_constraints"] = p.constrained.size();
  j["n_steps"] = steps_done;
  j["partial"] = partial;  // interrupted (Ctrl-C/SIGTERM) after n_steps of n_steps_asked
  j["n_steps_asked"] = sim.n_steps;
  j["dt"] = sim.dt;
  j["T"] = s.t;
  j["h"] = sim.mesh->h_max();
  j["E0"] = E0;
  j["E_final"] = E_final;
  j["E_rel_drift"] = drift.rel();
  j["E_abs_drift"] = drift.abs();
  j["E_scale"] = drift.scale();
  const RayleighDamping& damping = sim.spec.time.parameters.damping;
  j["damping"] = damping.active() ? nlohmann::ordered_json{{"alpha", damping.alpha}, {"beta", damping.beta}}
                                  : nlohmann::ordered_json();
  j["dissipated_work"] = dissipated;  // W_d(T): J(T) + W_d(T) = J0 for a conservative scheme
  j["max_violation"] = max_violation;
  j["max_active"] = max_active;
  j["wall_s"] = wall;
  const int per = std::max(steps_done, 1);
  j["s_per_step"] = wall / per;
  j["qp_s_per_step"] = qp_seconds / per;
  j["qp_iters_mean"] = qp_iters / per;
  if (energy_iters > 0) j["energy_iters_mean"] = energy_iters / per;  // discrete_gradient: step QPs per step
  if (sim.scheme->full_steps() == FullSteps::Reconstructed) j["reconstruction_kkt_max"] = max_reconstruction_kkt;
  j["kkt_residual_max"] = max_kkt;
  j["fields_s"] = fields_seconds;
  if (u_exact) j["error_exact"] = l2_error_at(sim, *u_exact, s);  // ‖u_h(T) − u(T)‖_L2
  if (sim.has_obstacle) {
    j["impact"] = history.impact();
    j["max_penetration"] = history.max_penetration();  // the whole boundary against every obstacle
  }
  j["wellposed"] = wellposedness_summary(sim);
  const SceneSpec::Units& units = sim.spec.units;
  j["units"] = units.length.empty() ? nlohmann::ordered_json()
                                    : nlohmann::ordered_json{{"length", units.length}, {"force", units.force}, {"time", units.time}};
  j["warnings"] = warnings;
  j["written"] = written_bytes(out);  // before summary.json and the plots, which are made from it
  write_file_atomically(out / "summary.json", j.dump(2) + "\n");

  std::string plot_note;
  if (make_plots && !partial && !interrupted()) plot_note = run_python_script(kPlotRunScript, {out.string()});
  const bool plots_interrupted = !partial && interrupted();

  if (!opt.quiet) {
    const std::string label = partial ? "INTERRUPTED after step " + std::to_string(steps_done) + " of " +
                                             std::to_string(sim.n_steps) + " (partial results)"
                                       : "";
    char energy[300];
    const char* J = damping.active() ? "J + W_d" : "J";  // with damping, the balance J + W_d = J0
    if (drift.scale_is_J0())
      std::snprintf(energy, sizeof energy, "max |%s - J0|/|J0| = %.3e", J, drift.rel());
    else  // J0 = 0 (a start from rest) or small against the energies exchanged
      std::snprintf(energy, sizeof energy, "max |%s - J0| = %.3e = %.3e E_scale (E_scale = max(E_kin + |E_pot|)/2 = %.4g)",
                    J, drift.abs(), drift.rel(), drift.scale());
    if (damping.active())
      std::snprintf(energy + std::strlen(energy), sizeof energy - std::strlen(energy), "; damping dissipated W_d = %.6g",
                    dissipated);
    std::printf(
        "cdyn run %s: %s, %s, %s, solver %s.%s%s\n  %d dofs (%d free, %d constrained), %d steps of dt = %g to T = %g in "
        "%.3f s (%.3g s/step, %.2f QP iterations per step).\n  Energy J0 = %.10g, J(T) = %.10g, %s; max constraint "
        "violation %.2e.\n  Condition (12): %s.\n",
        sim.scene_name.c_str(), sim.model.c_str(), sim.pair.c_str(), sim.scheme_name.c_str(), sim.solver_name.c_str(),
        partial ? "\n  " : "", label.c_str(), p.W->n_dofs(), p.n_free(), static_cast<int>(p.constrained.size()),
        steps_done, sim.dt, s.t, wall, wall / per, qp_iters / per, E0, E_final, energy, max_violation,
        wellposedness_line(j["wellposed"]).c_str());
    std::string written;
    for (const auto& [name, bytes] : j["written"].items())
      if (name != "total") written += (written.empty() ? "" : ", ") + name + " " + human_bytes(bytes.get<std::uintmax_t>());
    if (const std::uintmax_t plots = bytes_of(out / "plots"); plots > 0) written += ", plots " + human_bytes(plots);
    std::printf("  Results in %s (%s).\n", out.string().c_str(), written.c_str());
    if (!warnings.empty()) std::printf("  %zu warning%s (above, and in summary.json).\n", warnings.size(), warnings.size() > 1 ? "s" : "");
    if (!plot_note.empty() && !plots_interrupted) std::printf("  Note: no plots (%s).\n", plot_note.c_str());
  }
  if (partial) {
    std::fprintf(stderr, "cdyn: interrupted after step %d of %d; the results so far are in %s (summary.json: partial = true)\n",
                 steps_done, sim.n_steps, out.string().c_str());
    return 130;  // the shell's status for a run ended by SIGINT
  }
  if (plots_interrupted) {
    std::fprintf(stderr, "cdyn: interrupted after the time loop; the data files in %s are complete (no plots)\n",
                 out.string().c_str());
    return 130;
  }
  return 0;
}

}  // namespace cdyn::app
