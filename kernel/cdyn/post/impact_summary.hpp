// impact_summary.hpp — the first impact of a run against an obstacle, observed step by
// step: first and last step with an active constraint, the contact duration, the peak
// total contact force, the energy and momentum just before and just after, and the
// impulse, centroid and width of the force history with their half-sine equivalents.
//
// The contact starts within the first step with an active constraint and ends within
// the one after the last, so the duration t_last − t_first + dt is good to ± dt.  The
// smooth functionals of the force history F(t) (one value per step, the step's mean
// force, placed at the step's midpoint t − dt/2): the impulse I = ∫F dt, the centroid
// t̄ = ∫F t dt / I and the width σ = (∫F (t − t̄)² dt / I)^½.  A half-sine pulse
// F̂ sin(π(t − t0)/T) has σ = T (1/12 − 1/(2π²))^½ and I = 2F̂T/π, hence the half-sine
// equivalents T_hs = σ / (1/12 − 1/(2π²))^½ and F_hs = πI / (2T_hs): they converge under
// refinement where the raw duration and peak jump with the waves (docs/experiments.md,
// "The falling disk"), and I equals the change of momentum (an identity of the scheme).
#pragma once

#include <optional>

#include "cdyn/mesh/mesh.hpp"

namespace cdyn {

class ImpactMonitor {
 public:
  struct Snapshot {
    int step = -1;
    double t = 0, E = 0, E_kin = 0;
    Point P;  // linear momentum
  };
  struct Summary {
    bool contact = false;  // the rest is meaningful only with contact
    double t_first = 0, t_last = 0, duration = 0;
    int contact_steps = 0;
    double peak_force = 0, t_peak_force = 0;
    double impulse = 0, t_force_centroid = 0, force_width = 0, half_sine_duration = 0, half_sine_peak_force = 0;
    std::optional<Snapshot> before, after;  // after: empty while still in contact
  };

  // What it has observed so far (a restart carries it over).
  struct Memory {
    Snapshot previous, before, after;
    int first = -1, last = -1, contact_steps = 0;
    double t_first = 0, t_last = 0, peak = 0, t_peak = 0;
    double force_sum = 0, force_tau = 0, force_tau2 = 0;  // Σ F, Σ F τ, Σ F τ², τ = t − t_first
  };

  ImpactMonitor() = default;
  explicit ImpactMonitor(const Memory& m) : m_(m) {}
  // One step: its state, how many constraints are active, the total contact force.
  void observe(const Snapshot& now, int active, double contact_force);
  Summary summary(double dt) const;
  const Memory& memory() const { return m_; }

 private:
  Memory m_;
};

}  // namespace cdyn
