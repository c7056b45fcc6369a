// cmd_run.cpp — `cdyn run`: integrate a scene in time and write its results
// (DESIGN.md §5): history.csv (one row per step), summary.json, scene.toml.
//
// Every step records the discrete energy J = ½VᵀCV + ½UᵀAU − LᵀU split into its
// kinetic and potential parts, the active constraints, the QP iterations and time,
// and the probes (u, v and the seed's multiplier λ ≤ 0 at named points).  A NaN or a
// QP failure stops the run with the step number (exit status 3); the summary is
// written last, so a directory without summary.json is an unfinished run.
#include <unistd.h>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <nlohmann/json.hpp>

#include "cdyn/error.hpp"
#include "commands.hpp"
#include "simulation.hpp"

namespace cdyn::app {

namespace {

using Clock = std::chrono::steady_clock;

double seconds_since(Clock::time_point t0) { return std::chrono::duration<double>(Clock::now() - t0).count(); }

// The probe values of the current state: u (full field), v (displacement rate over
// the last step) and λ (the seed's multiplier at the nearest constrained vertex).
struct ProbeValues {
  double u, v, lambda;
};

ProbeValues probe(const Simulation& sim, const Probe& pr, const Eigen::VectorXd& U_full,
                  const Eigen::VectorXd& rate_full, const State& s) {
  const FESpace& W = *sim.problem.W;
  ProbeValues out{W.value_in_cell(U_full, pr.where.cell, pr.where.xi),
                  W.value_in_cell(rate_full, pr.where.cell, pr.where.xi), 0.0};
  const int i = sim.problem.bc->free_index(W.vertex_dof(pr.vertex));
  if (i >= 0 && s.reaction.size()) out.lambda = 0.0 - s.reaction[i];  // G = −I: λ = −(SX − r) (0.0 − avoids printing −0)
  return out;
}

// A one-line progress report on a terminal, rewritten in place.
void progress(int step, int n, double t, double drift, int active, double elapsed) {
  const double eta = step > 0 ? elapsed * (n - step) / step : 0.0;
  std::fprintf(stderr, "\r  step %d/%d  t = %.4g  |J - J0|/|J0| = %.2e  active %d  ETA %.0f s   ", step, n, t, drift,
               active, eta);
  std::fflush(stderr);
}

}  // namespace

int cmd_run(const RunOptions& opt) {
  Scene scene = Scene::load(opt.scene);
  for (const auto& a : opt.sets) scene.set(a);
  Simulation sim = make_simulation(scene);
  const ConstrainedProblem& p = sim.problem;

  const std::filesystem::path out = opt.out.empty() ? std::filesystem::path("out") / sim.scene_name : std::filesystem::path(opt.out);
  std::error_code ec;
  std::filesystem::create_directories(out, ec);
  if (ec) throw InputError(out.string() + ": cannot create the output directory (" + ec.message() + ")");
  std::filesystem::remove(out / "summary.json", ec);
  std::ofstream(out / "scene.toml") << scene.dump();
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
  record(0, StepStats{});

  const auto t0 = Clock::now();
  for (int n = 1; n <= sim.n_steps; ++n) {
    const Eigen::VectorXd U_old = s.U;
    StepStats st;
    try {
      st = sim.scheme->step(s);
    } catch (const NumericalError& e) {
      throw NumericalError("step " + std::to_string(n) + " (t = " + std::to_string(s.t + sim.dt) + "): " + e.what());
    }
    if (!s.U.allFinite() || !s.V.allFinite())
      throw NumericalError("step " + std::to_string(n) + ": the solution is not finite (NaN or Inf)");
    rate.setZero();
    const Eigen::VectorXd du = (s.U - U_old) / sim.dt;
    for (int j = 0; j < p.n_free(); ++j) rate[p.bc->free_dofs()[j]] = du[j];
    qp_iters += st.qp_iterations;
    qp_seconds += st.qp_seconds;
    max_active = std::max(max_active, st.active);
    max_violation = std::max(max_violation, p.max_violation(s.U));
    record(n, st);
    if (show_progress && (n % 10 == 0 || n == sim.n_steps))
      progress(n, sim.n_steps, s.t, max_drift, st.active, seconds_since(t0));
  }
  const double wall = seconds_since(t0);
  if (show_progress) std::fprintf(stderr, "\n");
  csv.close();

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
  j["wellposed"] = wellposedness_summary(sim);
  std::ofstream(out / "summary.json") << j.dump(2) << "\n";

  if (!opt.quiet) {
    std::printf(
        "cdyn run %s: %s, %s, %s, solver %s.\n  %d dofs (%d free, %d constrained), %d steps of dt = %g to T = %g in "
        "%.3f s (%.3g s/step, %.2f QP iterations per step).\n  Energy J0 = %.10g, J(T) = %.10g, max |J - J0|/|J0| = "
        "%.3e; max constraint violation %.2e.\n  Condition (12): %s.\n  Results in %s\n",
        sim.scene_name.c_str(), sim.model.c_str(), sim.pair.c_str(), sim.scheme_name.c_str(), sim.solver_name.c_str(),
        p.W->n_dofs(), p.n_free(), static_cast<int>(p.constrained.size()), sim.n_steps, sim.dt, s.t, wall,
        wall / sim.n_steps, qp_iters / sim.n_steps, E0, E_final, max_drift, max_violation,
        wellposedness_line(j["wellposed"]).c_str(), out.string().c_str());
  }
  return 0;
}

}  // namespace cdyn::app
