// exact/bar_exact.cpp — the two bar impact solutions, written region by region of the
// characteristic diagrams of docs/bar_impact.md.
#include "cdyn/exact/bar_exact.hpp"

#include <algorithm>
#include <cmath>

namespace cdyn {

namespace {

double indicator(bool b) { return b ? 1.0 : 0.0; }

}  // namespace

// ----- (a) the clamped bar --------------------------------------------------------------
//
// In the scaled variables ξ = x/L, τ = ct/L (reduced modulo the period 3) and for δ = 1,
// the solution û(ξ, τ) has three phases (docs/bar_impact.md, "The clamped bar"):
//   τ ∈ [0, 1)  release:     û = 1 − max(ξ, τ)
//   τ ∈ [1, 2)  contact:     û = −min(ξ, τ − 1) + max(0, ξ + τ − 2)
//   τ ∈ [2, 3)  free again:  û = min(τ − 2, 1 − ξ)
// and u(x, t) = δ û(x/L, ct/L), u_t = δ (c/L) û_τ, u_x = (δ/L) û_ξ.

namespace {

// ct/L reduced to [0, 3): the solution is periodic (and so defined for t < 0 too).
double reduced_time(double c, double L, double t) {
  const double tau = c * t / L;
  return tau - 3.0 * std::floor(tau / 3.0);
}

}  // namespace

double ClampedBarImpact::wave_speed() const { return std::sqrt(E / rho); }

double ClampedBarImpact::displacement(double x, double t) const {
  const double xi = x / L, tau = reduced_time(wave_speed(), L, t);
  double u;
  if (tau < 1.0)
    u = 1.0 - std::max(xi, tau);
  else if (tau < 2.0)
    u = -std::min(xi, tau - 1.0) + std::max(0.0, xi + tau - 2.0);
  else
    u = std::min(tau - 2.0, 1.0 - xi);
  return delta * u;
}

double ClampedBarImpact::velocity(double x, double t) const {
  const double xi = x / L, tau = reduced_time(wave_speed(), L, t);
  double v;  // û_τ
  if (tau < 1.0)
    v = -indicator(xi < tau);  // behind the release front the bar moves at −δc/L
  else if (tau < 2.0)
    v = -indicator(xi > tau - 1.0) + indicator(xi > 2.0 - tau);
  else
    v = indicator(xi < 3.0 - tau);
  return delta * wave_speed() / L * v;
}

double ClampedBarImpact::strain(double x, double t) const {
  const double xi = x / L, tau = reduced_time(wave_speed(), L, t);
  double e;  // û_ξ
  if (tau < 1.0)
    e = -indicator(xi > tau);  // ahead of the release front the initial compression
  else if (tau < 2.0)
    e = -indicator(xi < tau - 1.0) + indicator(xi > 2.0 - tau);
  else
    e = -indicator(xi > 3.0 - tau);
  return delta / L * e;
}

double ClampedBarImpact::contact_force(double t) const { return -E * strain(0.0, t); }

// R = E δ/L during [L/c, 2L/c) of each period: E δ/c per period.
double ClampedBarImpact::contact_impulse(double t) const {
  const double c = wave_speed(), periods = std::floor(t / period()), s = t - periods * period();
  return periods * E * delta / c + E * delta / L * std::clamp(s - L / c, 0.0, L / c);
}

// In units of E₀ = E δ²/(2L): ρ(δc/L)²/2 = E(δ/L)²/2 is the energy density of a moving
// region and of a strained one alike, so each energy is E₀ times the fraction of the
// bar that moves (resp. is strained).
double ClampedBarImpact::kinetic_energy(double t) const {
  const double tau = reduced_time(wave_speed(), L, t);
  double moving;
  if (tau < 1.0)
    moving = tau;
  else if (tau < 2.0)
    moving = std::abs(3.0 - 2.0 * tau);
  else
    moving = 3.0 - tau;
  return 0.5 * E * delta * delta / L * moving;
}

double ClampedBarImpact::elastic_energy(double t) const {
  return 0.5 * E * delta * delta / L - kinetic_energy(t);
}

// ----- (b) the falling bar --------------------------------------------------------------
//
// With s = t − t₀ the time since impact (docs/bar_impact.md, "The falling bar"):
//   s < 0           free flight:  u = −v₀ t
//   0 ≤ s ≤ 2L/c    contact:      u = −d − (v₀/c) min(x, cs, 2L − cs)
//   s > 2L/c        departure:    u = −d + v₀ (s − 2L/c)

double FallingBar::wave_speed() const { return std::sqrt(E / rho); }

double FallingBar::displacement(double x, double t) const {
  const double c = wave_speed(), s = t - contact_begins();
  if (s < 0.0) return -v0 * t;
  if (s > 2.0 * L / c) return -d + v0 * (s - 2.0 * L / c);
  return -d - v0 / c * std::min({x, c * s, 2.0 * L - c * s});
}

double FallingBar::velocity(double x, double t) const {
  const double c = wave_speed(), s = t - contact_begins();
  if (s < 0.0) return -v0;
  if (s > 2.0 * L / c) return v0;
  if (x < std::min(c * s, 2.0 * L - c * s)) return 0.0;  // stopped by the compression wave
  return c * s <= L ? -v0 : v0;  // still falling / already relieved by the free end
}

double FallingBar::strain(double x, double t) const {
  const double c = wave_speed(), s = t - contact_begins();
  if (s < 0.0 || s > 2.0 * L / c) return 0.0;
  return x < std::min(c * s, 2.0 * L - c * s) ? -v0 / c : 0.0;
}

double FallingBar::contact_force(double t) const { return -E * strain(0.0, t); }

// R = ρ c v₀ during 2L/c: the impulse 2ρL v₀ reverses the momentum −ρL v₀.
double FallingBar::contact_impulse(double t) const {
  return rho * wave_speed() * v0 * std::clamp(t - contact_begins(), 0.0, 2.0 * L / wave_speed());
}

// In units of E₀ = ½ρL v₀² (ρv₀²/2 = E(v₀/c)²/2: same density moving or strained).
double FallingBar::kinetic_energy(double t) const {
  const double c = wave_speed(), s = t - contact_begins();
  double strained = 0.0;  // the compressed length over L
  if (s >= 0.0 && s <= 2.0 * L / c) strained = std::min(c * s, 2.0 * L - c * s) / L;
  return 0.5 * rho * L * v0 * v0 * (1.0 - strained);
}

double FallingBar::elastic_energy(double t) const { return 0.5 * rho * L * v0 * v0 - kinetic_energy(t); }

}  // namespace cdyn
