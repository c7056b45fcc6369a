// impact_summary.cpp — the first impact of a run; see impact_summary.hpp.
#include "cdyn/post/impact_summary.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

namespace cdyn {

void ImpactMonitor::observe(const Snapshot& now, int active, double contact_force) {
  if (active > 0) {
    if (m_.first < 0) {
      m_.first = now.step;
      m_.t_first = now.t;
      m_.before = m_.previous;
    }
    m_.last = now.step;
    m_.t_last = now.t;
    ++m_.contact_steps;
    m_.after = Snapshot{};  // not released yet
    // The force's moments about t_first (t − t_first is small: no cancellation in σ²).
    const double tau = now.t - m_.t_first;
    m_.force_sum += contact_force;
    m_.force_tau += contact_force * tau;
    m_.force_tau2 += contact_force * tau * tau;
  } else if (m_.first >= 0 && m_.after.step < 0) {
    m_.after = now;
  }
  if (contact_force > m_.peak) {
    m_.peak = contact_force;
    m_.t_peak = now.t;
  }
  m_.previous = now;
}

ImpactMonitor::Summary ImpactMonitor::summary(double dt) const {
  Summary s;
  if (m_.first < 0) return s;
  s.contact = true;
  s.t_first = m_.t_first;
  s.t_last = m_.t_last;
  s.duration = m_.t_last - m_.t_first + dt;
  s.contact_steps = m_.contact_steps;
  s.peak_force = m_.peak;
  s.t_peak_force = m_.t_peak;
  s.impulse = m_.force_sum * dt;
  const double tau_bar = m_.force_sum > 0.0 ? m_.force_tau / m_.force_sum : 0.0;
  s.force_width = m_.force_sum > 0.0 ? std::sqrt(std::max(0.0, m_.force_tau2 / m_.force_sum - tau_bar * tau_bar)) : 0.0;
  s.t_force_centroid = m_.t_first + tau_bar - 0.5 * dt;
  const double half_sine_ratio = std::sqrt(1.0 / 12.0 - 1.0 / (2.0 * std::numbers::pi * std::numbers::pi));
  s.half_sine_duration = s.force_width / half_sine_ratio;
  s.half_sine_peak_force =
      s.half_sine_duration > 0.0 ? std::numbers::pi * s.impulse / (2.0 * s.half_sine_duration) : 0.0;
  if (m_.before.step >= 0) s.before = m_.before;
  if (m_.after.step >= 0) s.after = m_.after;
  return s;
}

}  // namespace cdyn
