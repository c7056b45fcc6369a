// run_report.hpp — what a run's report adds up (summary.json and the final paragraph,
// docs/outputs.md): the drift of the energy against a scale that cannot vanish, the
// totals over the steps, and how much the run wrote.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <string>

#include "cdyn/schemes/time_scheme.hpp"

namespace cdyn::app {

// max over t of |J − J0| and the energy scale it is measured against,
//     E_scale = max(|J0|, ½ max over t of (E_kin + |E_pot|)).
// With E_kin, E_pot ≥ 0 and J within a factor 2 of J0 (every conservative run from a
// state with energy) E_scale = |J0|, and rel() is DESIGN.md §5's max |J − J0|/|J0|.
// From rest (J0 = 0: a drop, a load applied from t > 0) the kinetic and potential
// energies mirror each other, E_kin ≈ −E_pot, and E_scale is the energy they exchange.
// It vanishes only when E_kin = E_pot = 0 at every step, where J ≡ 0: rel() is then 0.
//
// With data in t the energy is balanced against the work W the data did on the body
// (problems/data_work.hpp), and with Rayleigh damping against the work W_d ≥ 0 the
// damping has taken (docs/schemes.md): the drift is then max |J + W_d − J0 − W|, the
// energy the scheme made or lost on its own.
class EnergyDrift {
 public:
  explicit EnergyDrift(const Energy& E0) : J0_(E0.total()) { observe(E0); }
  // One carried over from a checkpoint (its J0(), abs() and half_sum()).
  EnergyDrift(double J0, double abs, double half_sum) : J0_(J0), abs_(abs), half_sum_(half_sum) {}
  void observe(const Energy& E, double work = 0.0, double dissipated = 0.0) {
    abs_ = std::max(abs_, std::abs(E.total() + dissipated - J0_ - work));
    half_sum_ = std::max(half_sum_, 0.5 * (std::abs(E.kinetic) + std::abs(E.potential)));
  }
  double abs() const { return abs_; }
  double scale() const { return std::max(std::abs(J0_), half_sum_); }
  double rel() const { return scale() > 0.0 ? abs_ / scale() : 0.0; }
  bool scale_is_J0() const { return scale() == std::abs(J0_); }
  double J0() const { return J0_; }
  double half_sum() const { return half_sum_; }

 private:
  double J0_, abs_ = 0.0, half_sum_ = 0.0;
};

// What summary.json adds up over the steps (docs/outputs.md), carried over by a
// checkpoint.
struct RunTotals {
  double qp_iterations = 0, qp_seconds = 0, energy_iterations = 0;
  double reconstruction_seconds = 0, reconstruction_iterations = 0;  // the full-step reconstruction's (eq. 14)
  double max_kkt = 0, max_reconstruction_kkt = 0, max_violation = 0;
  int max_active = 0;
  double dissipated = 0;       // W_d, the work of the Rayleigh damping from t = 0
  double data_work = 0;        // W, the work of the data in t from t = 0 (problems/data_work.hpp)
  double friction_work = 0;    // W_f, the work the friction forces took from t = 0 (≥ 0)
  double wall_seconds = 0;     // the time loop, without the field files: of the steps before this process
  double fields_seconds = 0;   // the field files

  void add(const StepStats& st, double violation) {
    qp_iterations += st.qp_iterations;
    qp_seconds += st.qp_seconds;
    energy_iterations += st.energy_iterations;
    reconstruction_seconds += st.reconstruction_seconds;
    reconstruction_iterations += st.reconstruction_iterations;
    max_kkt = std::max(max_kkt, st.kkt_residual);
    max_reconstruction_kkt = std::max(max_reconstruction_kkt, st.reconstruction_kkt);
    max_violation = std::max(max_violation, violation);
    max_active = std::max(max_active, st.active);
    dissipated += st.dissipated;
    friction_work += st.friction_work;
  }
};

// Bytes of a file, or of every file under a folder (0 when absent).
std::uintmax_t bytes_of(const std::filesystem::path& p);

// summary.json's "written": bytes of scene.toml, history.csv, contact.csv, the field
// series (fields.pvd + fields/) and the checkpoint of the run directory, those present,
// and their total.
nlohmann::ordered_json written_bytes(const std::filesystem::path& out);

// "1.23 MB", "512 B".
std::string human_bytes(std::uintmax_t bytes);

}  // namespace cdyn::app
