// impact_summary.cpp — the first impact of a run; see impact_summary.hpp.
#include "cdyn/post/impact_summary.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

namespace cdyn {

void ImpactMonitor::observe(const Snapshot& now, int active, double contact_force) {
  if (active > 0) {
    if (first_ < 0) {
      first_ = now.step;
      t_first_ = now.t;
      before_ = previous_;
    }
    last_ = now.step;
    t_last_ = now.t;
    ++contact_steps_;
    after_ = Snapshot{};  // not released yet
    // The force's moments about t_first (t − t_first is small: no cancellation in σ²).
    const double tau = now.t - t_first_;
    force_sum_ += contact_force;
    force_tau_ += contact_force * tau;
    force_tau2_ += contact_force * tau * tau;
  } else if (first_ >= 0 && after_.step < 0) {
    after_ = now;
  }
  if (contact_force > peak_) {
    peak_ = contact_force;
    t_peak_ = now.t;
  }
  previous_ = now;
}

ImpactMonitor::Summary ImpactMonitor::summary(double dt) const {
  Summary s;
  if (first_ < 0) return s;
  s.contact = true;
  s.t_first = t_first_;
  s.t_last = t_last_;
  s.duration = t_last_ - t_first_ + dt;
  s.contact_steps = contact_steps_;
  s.peak_force = peak_;
  s.t_peak_force = t_peak_;
  s.impulse = force_sum_ * dt;
  const double tau_bar = force_sum_ > 0.0 ? force_tau_ / force_sum_ : 0.0;
  s.force_width = force_sum_ > 0.0 ? std::sqrt(std::max(0.0, force_tau2_ / force_sum_ - tau_bar * tau_bar)) : 0.0;
  s.t_force_centroid = t_first_ + tau_bar - 0.5 * dt;
  const double half_sine_ratio = std::sqrt(1.0 / 12.0 - 1.0 / (2.0 * std::numbers::pi * std::numbers::pi));
  s.half_sine_duration = s.force_width / half_sine_ratio;
  s.half_sine_peak_force =
      s.half_sine_duration > 0.0 ? std::numbers::pi * s.impulse / (2.0 * s.half_sine_duration) : 0.0;
  if (before_.step >= 0) s.before = before_;
  if (after_.step >= 0) s.after = after_;
  return s;
}

}  // namespace cdyn
