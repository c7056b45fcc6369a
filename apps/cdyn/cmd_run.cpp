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
#include <sstream>

#include "cdyn/atomic_file.hpp"
#include "cdyn/base/error.hpp"
#include "cdyn/fields_output.hpp"
#include "cdyn/post/contact_force.hpp"
#include "cdyn/problems/data_work.hpp"
#include "cdyn/qp/petsc/backend.hpp"
#include "checkpoint.hpp"
#include "commands.hpp"
#include "derived_fields.hpp"
#include "embedded_scripts.hpp"
#include "diagnostics.hpp"
#include "exact_solution.hpp"
#include "interrupt.hpp"
#include "python_script.hpp"
#include "run_history.hpp"
#include "run_report.hpp"
#include "run_summary.hpp"
#include "simulation.hpp"

namespace cdyn::app {

namespace {

using Clock = std::chrono::steady_clock;

double seconds_since(Clock::time_point t0) { return std::chrono::duration<double>(Clock::now() - t0).count(); }

// A one-line progress report on a terminal, rewritten in place (elapsed: the seconds
// of the `done` steps this process has made).
void progress(int step, int n, double t, double drift, int active, double elapsed, int done) {
  const double eta = done > 0 ? elapsed * (n - step) / done : 0.0;
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

// The scene as run, to be written next to the results: its name given (the stem of its
// file otherwise, and scene.toml's would be "scene"), a relative mesh.file made absolute
// (by the rule of make_mesh: relative to the scene file's directory, or to the current
// directory for the embedded scene), so that `cdyn run DIR/scene.toml` reruns it from
// anywhere, and `cdyn run --resume DIR` with the same name.
Scene scene_as_run(Scene scene, const std::string& scene_file) {
  if (!scene.has("name")) scene.set("name=" + toml_string(scene.name()));
  if (scene.string("mesh.kind", "") != "gmsh") return scene;  // else mesh.file is unused
  std::filesystem::path file = scene.string("mesh.file");
  if (file.is_relative() && !scene_file.empty()) file = std::filesystem::path(scene_file).parent_path() / file;
  scene.set("mesh.file=" + toml_string(std::filesystem::absolute(file).lexically_normal().string()));
  return scene;
}

// An earlier run's files in the same directory go first: a directory holds one run.
// A resumed run keeps the run's field files and checkpoint (and rewrites history.csv
// and contact.csv from the checkpoint's journals).
void remove_previous_outputs(const std::filesystem::path& out, bool resuming) {
  std::error_code ec;
  remove_stale_temporaries(out);  // of a run that was killed
  std::filesystem::remove(out / "summary.json", ec);
  std::filesystem::remove(out / "history.csv", ec);
  std::filesystem::remove(out / "contact.csv", ec);
  for (const char* png : {"energy.png", "probes.png", "contact.png", "contact_pressure.png", "friction.png"}) std::filesystem::remove(out / "plots" / png, ec);
  if (resuming) return;
  remove_fields(out);
  std::filesystem::remove_all(checkpoint_dir(out), ec);
}

// The whole of a text file; InputError naming it if it cannot be read.
std::string read_text(const std::filesystem::path& file, const std::string& what) {
  std::ifstream in(file, std::ios::binary);
  if (!in) throw InputError(file.string() + ": " + what);
  std::stringstream text;
  text << in.rdbuf();
  return text.str();
}

// How a run starts: its scene, its directory and, for --resume, its checkpoint.
struct Start {
  Scene scene;
  std::string scene_text;  // scene.toml as written (or to be written)
  std::filesystem::path out;
  std::optional<RunCheckpoint> checkpoint;
};

Start fresh_start(const RunOptions& opt) {
  Scene scene = Scene::load(opt.scene, opt.scene_text);
  for (const auto& a : command_line_paths(opt.sets)) scene.set(a);
  Start start{scene, scene_as_run(scene, opt.scene).dump(), opt.out, std::nullopt};
  if (start.out.empty()) start.out = std::filesystem::path("out") / scene.name();
  return start;
}

// `--resume DIR`: the scene is DIR/scene.toml as the run wrote it, and the checkpoint
// must have been written for it (checkpoint.hpp).
Start resumed_start(const RunOptions& opt, int rank) {
  if (!opt.scene.empty() || !opt.scene_text.empty() || !opt.sets.empty() || !opt.out.empty())
    throw InputError("--resume: the run's scene is DIR/scene.toml and its outputs go to DIR: give no SCENE, --set "
                     "or --out with it");
  const std::filesystem::path out = opt.resume;
  const std::filesystem::path file = out / "scene.toml";
  std::string text = read_text(file, "no such file (--resume takes the directory of a run)");
  RunCheckpoint checkpoint = read_checkpoint(out, text, rank);
  Scene scene = Scene::from_string(text, file.string());
  return {std::move(scene), std::move(text), out, std::move(checkpoint)};
}

// A checkpoint's state must be one of this problem (a scene.toml that matches its
// fingerprint builds the same problem; this guards the file's own consistency).
// On subdomains (each rank its cells from its checkpoint) every rank's checkpoint must
// be of the same step, and the run on as many ranks as the stopped one.
void check_sizes(const RunCheckpoint& c, const Simulation& sim, const std::filesystem::path& out, int rank) {
  const ConstrainedProblem& p = sim.problem;
  const std::string file = checkpoint_file(out, rank).string();
  if (sim.partition && c.cells != sim.partition->sub.cell)
    throw InputError(file + ": written by a run on another number of ranks (resume on as many as the stopped run "
                            "had)");
  if (c.state.U.size() != p.n_free() || c.state.V.size() != p.mass->n_velocity() ||
      c.state.reaction.size() != p.n_free() || c.rate.size() != p.W->n_dofs() || c.step < 0 || c.step > sim.n_steps)
    throw InputError(file + ": not a valid checkpoint of this run's problem");
  if (largest(sim, c.step) != -largest(sim, -c.step))
    throw InputError(file + ": the ranks' checkpoints are of different steps (the run was stopped while writing "
                            "them)");
}

// An InputError met by some ranks only (a rank's checkpoint file) stops every rank of a
// run on subdomains: the others would wait in the next collective call.
template <class F>
void agreed(const RunOptions& opt, F f) {
  if (!opt.every_rank) return f();
  std::optional<InputError> error;
  try {
    f();
  } catch (const InputError& e) {
    error = e;
  }
  if (petsc::max_over_ranks(error ? 1.0 : 0.0) > 0)
    throw error ? *error
                : InputError("--resume: another rank's checkpoint is missing or not valid (resume on as many ranks as "
                             "the stopped run had)");
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

bool runs_on_subdomains(const RunOptions& opt) {
  try {
    const Scene scene = opt.resume.empty() ? fresh_start(opt).scene
                                           : Scene::from_string(read_text(std::filesystem::path(opt.resume) / "scene.toml",
                                                                          "no such file"),
                                                                "scene.toml");
    return scene.string("solver.partition", "none") != "none";
  } catch (const std::exception&) {
    return false;
  }
}

int cmd_run(const RunOptions& opt) {
  // (on subdomains each rank reads its own checkpoint file)
  const int rank = opt.every_rank ? petsc::rank() : 0;
  std::optional<Start> started;
  agreed(opt, [&] { started = opt.resume.empty() ? fresh_start(opt) : resumed_start(opt, rank); });
  Start& start = *started;
  const std::optional<RunCheckpoint>& resume = start.checkpoint;
  Simulation sim = make_simulation(start.scene, resume && opt.every_rank ? &resume->cells : nullptr);
  if (resume) agreed(opt, [&] { check_sizes(*resume, sim, start.out, rank); });
  const auto u_exact = exact_displacement(sim);
  const ConstrainedProblem& p = sim.problem;
  // On subdomains every rank runs this function, the first alone writing and reporting;
  // what the ranks record is summed over them (partition.hpp).
  const bool writes = writes_files(sim);
  std::vector<std::string> warnings = run_warnings(sim);
  if (opt.warnings && writes)
    for (const std::string& w : warnings) std::fprintf(stderr, "cdyn: warning: %s\n", w.c_str());

  const std::filesystem::path& out = start.out;
  std::error_code ec;
  if (writes) {
    std::filesystem::create_directories(out, ec);
    if (ec) throw InputError(out.string() + ": cannot create the output directory (" + ec.message() + ")");
    remove_previous_outputs(out, resume.has_value());
    if (!resume) write_file_atomically(out / "scene.toml", start.scene_text);
  }
  const int checkpoint_every = sim.spec.output.checkpoint_every;
  // (the journals of the files rank 0 writes; on subdomains every rank writes its state)
  const std::filesystem::path journals = checkpoint_every > 0 && writes ? checkpoint_dir(out) : std::filesystem::path();
  if (!journals.empty()) std::filesystem::create_directories(journals);
  History history(sim, out, journals, resume ? std::optional(resume->history) : std::nullopt);

  // The state and everything summed over the steps: from t = 0, or from the checkpoint.
  State s = resume ? resume->state : sim.initial;
  if (resume) sim.scheme->restore(resume->scheme);
  const Energy E_initial = resume ? resume->E_initial : summed(sim, sim.scheme->energy(s));
  const double E0 = E_initial.total();
  EnergyDrift drift = resume ? EnergyDrift(E0, resume->drift_abs, resume->drift_half_sum) : EnergyDrift(E_initial);
  RunTotals totals = resume ? resume->totals : RunTotals{};
  if (!resume) totals.max_violation = largest(sim, p.max_violation(s.U));
  double E_final = summed(sim, sim.scheme->energy(s)).total();
  Eigen::VectorXd rate = resume ? resume->rate : Eigen::VectorXd::Zero(p.W->n_dofs());
  Eigen::VectorXd force_xy = reaction_xy(p, s.reaction);  // the last step's reaction in (x, y), for every output

  // The work of the data in t (a load L(t), a moving obstacle) since t = 0: the scheme's
  // own balance when it keeps one exactly (discrete_gradient), else the midpoint
  // quadrature of problems/data_work.hpp; J is balanced against it (and against the
  // damping's work W_d).  (On subdomains the reaction's work on the unknowns each rank owns.)
  auto add_data_work = [&](const StepStats& st, double t_before, const Eigen::VectorXd& U_before) {
    if (!sim.data_in_t) return;
    totals.data_work +=
        st.external_work
            ? *st.external_work
            : summed(sim, data_increment(p, t_before, s.t).work(p, 0.5 * (U_before + s.U), owned_part(sim, s.reaction)));
  };
  auto record = [&](int step, const StepStats& st, double step_seconds, const Energy& E) {
    E_final = E.total();
    // J + W_d + W_f − J0 − W: friction and damping take energy, the data give it
    drift.observe(E, totals.data_work, totals.dissipated + totals.friction_work);
    force_xy = reaction_xy(p, s.reaction);
    history.record(step, s, st, step_seconds, E, {totals.dissipated, totals.data_work, totals.friction_work}, rate,
                   force_xy);
  };
  // The field series: step 0, every output.every steps and the last step.  Its cost
  // is measured apart and left out of wall_s, which is the cost of the method.
  // On subdomains every rank makes its arrays and the first writes them on the whole mesh.
  const bool with_fields = sim.spec.output.fields;
  std::optional<FieldsWriter> fields;
  if (with_fields && writes) fields.emplace(out, sim.partition ? sim.partition->whole : *sim.mesh);
  if (fields && resume) fields->continue_series(resume->frames, resume->step);
  const DerivedFields derived(sim);  // σ, ε, von Mises, contact pressure, regions
  double fields_seconds = 0.0;       // in this process
  auto write_fields = [&](int step) {
    const auto tf = Clock::now();
    const Eigen::VectorXd U_full = p.full(s.U);
    ExtraFields arrays = derived(U_full, force_xy, &s);
    const std::vector<FieldArray> state = state_arrays(*sim.mesh, p, U_full, rate, force_xy);
    arrays.point.insert(arrays.point.begin(), state.begin(), state.end());
    if (sim.partition) {  // the ranks' arrays on the whole mesh, the vertex stress completed there
      arrays = gathered_on_first_rank(sim, arrays);
      if (fields) derived.add_vertex_stress(sim.partition->whole, arrays);
    }
    if (fields) fields->write(step, s.t, arrays);
    fields_seconds += seconds_since(tf);
  };
  const auto t0 = Clock::now();
  // The totals with this process's time added (the checkpoint's, or summary.json's).
  auto totals_now = [&] {
    RunTotals t = totals;
    t.fields_seconds += fields_seconds;
    t.wall_seconds += seconds_since(t0) - fields_seconds;
    return t;
  };
  // A checkpoint at step n: the journals first, then state.bin (checkpoint.hpp); then
  // the scheme restores its own memory, as a run resumed from here will.
  int last_checkpoint = resume ? resume->step : -1;
  auto checkpoint = [&](int n) {
    RunCheckpoint c{scene_fingerprint(start.scene_text), n, s, sim.scheme->memory(), E_initial, drift.abs(),
                    drift.half_sum(), totals_now(), history.checkpoint(), rate, {}, {}};
    if (fields)
      for (const FieldsWriter::Frame& f : fields->frames()) c.frames.emplace_back(f.step, f.t);
    if (sim.partition) c.cells = sim.partition->sub.cell;
    write_checkpoint(out, c, rank);
    sim.scheme->restore(c.scheme);
    last_checkpoint = n;
  };
  if (!resume) {
    record(0, StepStats{}, 0.0, E_initial);
    if (with_fields) write_fields(0);
  }

  const bool show_progress = !opt.quiet && writes && isatty(STDERR_FILENO);
  const int first = resume ? resume->step + 1 : 1;
  int steps_done = first - 1;
  // Ctrl-C stops the loop after the step in progress (interrupt.hpp); the guard stays
  // through the plots, whose interruption leaves the data files complete.
  InterruptGuard guard;
  // (on subdomains the ranks stop together: any rank's Ctrl-C stops them all)
  for (int n = first; n <= sim.n_steps && !on_any_rank(sim, interrupted()); ++n) {
    const Eigen::VectorXd U_old = s.U;
    const double t_old = s.t;
    StepStats st;
    double step_seconds = 0.0;  // the scheme's step: the QP and everything around it
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
      const auto ts = Clock::now();
      st = sim.scheme->step(s);
      step_seconds = seconds_since(ts);
      if (on_any_rank(sim, !s.U.allFinite() || !s.V.allFinite()))
        throw NumericalError("the solution is not finite (NaN or Inf)");
      E = summed(sim, sim.scheme->energy(s));
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
    if (sim.spec.time.parameters.damping.active()) st.dissipated = summed(sim, st.dissipated);
    if (sim.with_friction) st.friction_work = summed(sim, st.friction_work);  // (each rank its contacts')
    totals.add(st, largest(sim, p.max_violation(s.U, s.t)));
    add_data_work(st, t_old, U_old);
    record(n, st, step_seconds, E);
    steps_done = n;
    if (with_fields && (n % sim.output_every == 0 || n == sim.n_steps)) write_fields(n);
    if (checkpoint_every > 0 && n % checkpoint_every == 0 && n < sim.n_steps) checkpoint(n);
    if (show_progress && (n % 10 == 0 || n == sim.n_steps))
      progress(n, sim.n_steps, s.t, drift.rel(), st.active, seconds_since(t0), n - first + 1);
  }
  const bool partial = steps_done < sim.n_steps;
  // Interrupted: a checkpoint of the last step, so that --resume loses nothing (before
  // the last state's field file, which is no frame of the series).  Complete: nothing
  // left to resume.
  if (partial && checkpoint_every > 0 && steps_done > last_checkpoint) checkpoint(steps_done);
  if (partial && with_fields && steps_done % sim.output_every != 0) write_fields(steps_done);  // the last state computed
  if (!partial && writes) std::filesystem::remove_all(checkpoint_dir(out), ec);
  totals = totals_now();
  if (show_progress) std::fprintf(stderr, "\n");
  history.close();
  if (fields) fields->finish();

  if (sim.has_obstacle) {
    const std::string w = penetration_warning(sim, history.max_penetration(), totals.max_violation);
    if (!w.empty()) {
      warnings.push_back(w);
      if (opt.warnings) std::fprintf(stderr, "cdyn: warning: %s\n", w.c_str());
    }
  }
  const RunOutcome outcome{sim, out, s, steps_done, partial, resume ? resume->step : -1, E0, E_final, drift, totals,
                           history, warnings, u_exact};
  if (!writes) return partial ? 130 : 0;  // (the first rank reports)
  const nlohmann::ordered_json summary = run_summary(outcome);
  write_file_atomically(out / "summary.json", summary.dump(2) + "\n");

  std::string plot_note;
  if (sim.spec.output.plots && !partial && !interrupted()) plot_note = run_python_script(kPlotRunScript, {out.string()});
  const bool plots_interrupted = !partial && interrupted();
  if (!opt.quiet) print_run_paragraph(outcome, summary, plots_interrupted ? "" : plot_note);
  if (partial) {
    std::fprintf(stderr,
                 "cdyn: interrupted after step %d of %d; the results so far are in %s (summary.json: partial = true%s)\n",
                 steps_done, sim.n_steps, out.string().c_str(),
                 checkpoint_every > 0 ? "; cdyn run --resume continues it" : "");
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
