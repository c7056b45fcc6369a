// run_summary.cpp — summary.json and the final paragraph of `cdyn run`.
#include "run_summary.hpp"

#include <cstdio>
#include <cstring>

#include "cdyn/qp/petsc/backend.hpp"
#include "commands.hpp"
#include "exact_solution.hpp"

namespace cdyn::app {

nlohmann::ordered_json run_summary(const RunOutcome& r) {
  const Simulation& sim = r.sim;
  const RunTotals& totals = r.totals;
  nlohmann::ordered_json j;
  j["scene"] = sim.scene_name;
  j["model"] = sim.model;
  j["dim"] = sim.mesh->dim;
  j["pair"] = sim.pair;
  j["scheme"] = sim.scheme_name;
  j["full_steps"] = to_string(sim.scheme->full_steps());
  j["solver"] = sim.solver_name;
  j["solver_tol"] = sim.tol;
  // how pdas solved its reduced systems (solver.linear, "auto" resolved)
  j["solver_linear"] = sim.spec.solver.name != "pdas" || sim.spec.solver.backend != "native" ? "-"
                       : sim.spec.solver.options.pdas_cg_only                                 ? "cg"
                                                                                              : "factor";
  // how the native pdas solved the full-step reconstruction's QP (eq. 14; on rank 0 with
  // the petsc back end), "-" without one
  // (on subdomains the step's solver solves it, on the ranks: "-")
  j["reconstruction_linear"] = sim.scheme->full_steps() != FullSteps::Reconstructed || sim.partition ? "-"
                               : sim.spec.time.parameters.reconstruct_by_cg                        ? "cg"
                                                                                                   : "factor";
  // the back end and its processes (docs/distributed.md): rank 0 and the ranks serving it
  j["backend"] = sim.spec.solver.backend;
  j["ranks"] = petsc::size();
  j["partition"] = sim.spec.solver.partition;  // "none", or the subdomains' ("slabs", "graph": each rank its cells)
  if (sim.partition) j["interface_vertices"] = sim.partition->interface_vertices;
  j["threads"] = sim.threads;
  j["blas_threads"] = sim.blas_threads > 0 ? nlohmann::ordered_json(sim.blas_threads) : nlohmann::ordered_json();
  j["n_dofs"] = sim.whole.dofs;
  j["n_free"] = sim.whole.free;
  j["n_velocity"] = sim.whole.velocity;
  j["n_constraints"] = sim.whole.constraints;
  j["n_steps"] = r.steps_done;
  j["partial"] = r.partial;  // interrupted (Ctrl-C/SIGTERM) after n_steps of n_steps_asked
  j["n_steps_asked"] = sim.n_steps;
  j["resumed_at"] = r.resumed_at >= 0 ? nlohmann::ordered_json(r.resumed_at) : nlohmann::ordered_json();
  j["dt"] = sim.dt;
  j["T"] = r.state.t;
  j["h"] = sim.whole.h;
  j["E0"] = r.E0;
  j["E_final"] = r.E_final;
  j["E_rel_drift"] = r.drift.rel();
  j["E_abs_drift"] = r.drift.abs();
  j["E_scale"] = r.drift.scale();
  const RayleighDamping& damping = sim.spec.time.parameters.damping;
  j["damping"] = damping.active() ? nlohmann::ordered_json{{"alpha", damping.alpha}, {"beta", damping.beta}}
                                  : nlohmann::ordered_json();
  if (sim.data_in_t) j["data_work"] = totals.data_work;  // the drift is then of J + W_d − J0 − data_work
  j["dissipated_work"] = totals.dissipated;  // W_d(T): J(T) + W_d(T) = J0 for a conservative scheme
  if (sim.with_friction) j["friction_work"] = totals.friction_work;  // W_f(T): in the drift with W_d
  j["max_violation"] = totals.max_violation;
  j["max_active"] = totals.max_active;
  j["setup_s"] = sim.setup_seconds;  // this process's (a resumed run's own)
  j["wall_s"] = totals.wall_seconds;
  const int per = std::max(r.steps_done, 1);
  j["s_per_step"] = totals.wall_seconds / per;
  j["qp_s_per_step"] = totals.qp_seconds / per;
  j["qp_iters_mean"] = totals.qp_iterations / per;
  if (totals.energy_iterations > 0) j["energy_iters_mean"] = totals.energy_iterations / per;  // discrete_gradient
  if (sim.scheme->full_steps() == FullSteps::Reconstructed) {
    j["reconstruction_s_per_step"] = totals.reconstruction_seconds / per;  // (part of s_per_step, not of qp_s_per_step)
    j["reconstruction_iters_mean"] = totals.reconstruction_iterations / per;
    j["reconstruction_kkt_max"] = totals.max_reconstruction_kkt;
  }
  j["kkt_residual_max"] = totals.max_kkt;
  j["fields_s"] = totals.fields_seconds;
  if (r.u_exact) j["error_exact"] = l2_error_at(sim, *r.u_exact, r.state);  // ‖u_h(T) − u(T)‖_L2
  if (sim.has_obstacle) {
    j["impact"] = r.history.impact();
    j["max_penetration"] = r.history.max_penetration();  // the whole boundary against every obstacle
  }
  if (!sim.spec.output.wellposed) {
    j["wellposed"] = {{"beta", nullptr}, {"satisfied", nullptr}, {"not_computed", "output.wellposed = false"}};
  } else {  // (on subdomains by the first rank, on the whole mesh)
    j["wellposed"] = wellposedness_summary(sim);
  }
  const SceneSpec::Units& units = sim.spec.units;
  j["units"] = units.length.empty() ? nlohmann::ordered_json()
                                    : nlohmann::ordered_json{{"length", units.length}, {"force", units.force}, {"time", units.time}};
  j["warnings"] = r.warnings;
  j["written"] = written_bytes(r.out);  // before summary.json and the plots, which are made from it
  return j;
}

void print_run_paragraph(const RunOutcome& r, const nlohmann::ordered_json& j, const std::string& plot_note) {
  const Simulation& sim = r.sim;
  const EnergyDrift& drift = r.drift;
  const std::string label = r.partial ? "INTERRUPTED after step " + std::to_string(r.steps_done) + " of " +
                                            std::to_string(sim.n_steps) + " (partial results)"
                                      : "";
  char energy[400];
  const bool damped = sim.spec.time.parameters.damping.active();
  const bool worked = sim.data_in_t;  // J balanced against the data's work W
  // the balance: J + W_d = J0 + W (W_d the damping's work, W the data's)
  const std::string balance = std::string(damped ? "J + W_d - J0" : "J - J0") + (worked ? " - W" : "");
  if (drift.scale_is_J0())
    std::snprintf(energy, sizeof energy, "max |%s|/|J0| = %.3e", balance.c_str(), drift.rel());
  else  // J0 = 0 (a start from rest) or small against the energies exchanged
    std::snprintf(energy, sizeof energy, "max |%s| = %.3e = %.3e E_scale (E_scale = max(E_kin + |E_pot|)/2 = %.4g)",
                  balance.c_str(), drift.abs(), drift.rel(), drift.scale());
  if (worked)
    std::snprintf(energy + std::strlen(energy), sizeof energy - std::strlen(energy),
                  " with W = %.6g the work of the data in t", r.totals.data_work);
  if (damped)
    std::snprintf(energy + std::strlen(energy), sizeof energy - std::strlen(energy), "; damping dissipated W_d = %.6g",
                  r.totals.dissipated);
  if (sim.with_friction)
    std::snprintf(energy + std::strlen(energy), sizeof energy - std::strlen(energy), "; friction took W_f = %.6g",
                  r.totals.friction_work);
  const int per = std::max(r.steps_done, 1);
  const double wall = r.totals.wall_seconds;
  std::string solver = sim.solver_name;
  if (sim.spec.solver.backend != "native")
    solver += " on " + sim.spec.solver.backend + " (" + std::to_string(petsc::size()) + " rank" +
              (petsc::size() == 1 ? ")" : "s)");
  std::printf(
      "cdyn run %s: %s, %s, %s, solver %s.%s%s\n  %d dofs (%d free, %d constrained), %d steps of dt = %g to T = %g in "
      "%.3f s on %d thread%s (%.3g s/step, %.2f QP iterations per step).\n  Energy J0 = %.10g, J(T) = %.10g, %s; max constraint "
      "violation %.2e.\n  Condition (12): %s.\n",
      sim.scene_name.c_str(), sim.model.c_str(), sim.pair.c_str(), sim.scheme_name.c_str(), solver.c_str(),
      r.partial ? "\n  " : "", label.c_str(), sim.whole.dofs, sim.whole.free, sim.whole.constraints,
      r.steps_done, sim.dt, r.state.t, wall, sim.threads, sim.threads == 1 ? "" : "s", wall / per,
      r.totals.qp_iterations / per, r.E0, r.E_final, energy,
      r.totals.max_violation, wellposedness_line(j["wellposed"]).c_str());
  if (r.resumed_at >= 0) std::printf("  Resumed from the checkpoint of step %d.\n", r.resumed_at);
  std::string written;
  for (const auto& [name, bytes] : j["written"].items())
    if (name != "total") written += (written.empty() ? "" : ", ") + name + " " + human_bytes(bytes.get<std::uintmax_t>());
  if (const std::uintmax_t plots = bytes_of(r.out / "plots"); plots > 0) written += ", plots " + human_bytes(plots);
  std::printf("  Results in %s (%s).\n", r.out.string().c_str(), written.c_str());
  const std::size_t n_warnings = r.warnings.size();
  if (n_warnings) std::printf("  %zu warning%s (above, and in summary.json).\n", n_warnings, n_warnings > 1 ? "s" : "");
  if (!plot_note.empty()) std::printf("  Note: no plots (%s).\n", plot_note.c_str());
}

}  // namespace cdyn::app
