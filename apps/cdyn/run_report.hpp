// run_report.hpp — two quantities of a run's report (summary.json and the final
// paragraph, docs/outputs.md): the drift of the energy against a scale that cannot
// vanish, and how much the run wrote.
#pragma once

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
// With Rayleigh damping the conserved quantity is J + W_d, W_d ≥ 0 the work the damping
// has done so far (docs/schemes.md): the drift is max |J + W_d − J0|.
class EnergyDrift {
 public:
  explicit EnergyDrift(const Energy& E0) : J0_(E0.total()) { observe(E0); }
  void observe(const Energy& E, double dissipated = 0.0) {
    abs_ = std::max(abs_, std::abs(E.total() + dissipated - J0_));
    half_sum_ = std::max(half_sum_, 0.5 * (std::abs(E.kinetic) + std::abs(E.potential)));
  }
  double abs() const { return abs_; }
  double scale() const { return std::max(std::abs(J0_), half_sum_); }
  double rel() const { return scale() > 0.0 ? abs_ / scale() : 0.0; }
  bool scale_is_J0() const { return scale() == std::abs(J0_); }

 private:
  double J0_, abs_ = 0.0, half_sum_ = 0.0;
};

// Bytes of a file, or of every file under a folder (0 when absent).
std::uintmax_t bytes_of(const std::filesystem::path& p);

// summary.json's "written": bytes of scene.toml, history.csv, contact.csv and the
// field series (fields.pvd + fields/) of the run directory, those present, and their
// total.
nlohmann::ordered_json written_bytes(const std::filesystem::path& out);

// "1.23 MB", "512 B".
std::string human_bytes(std::uintmax_t bytes);

}  // namespace cdyn::app
