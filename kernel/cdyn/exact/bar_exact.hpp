// exact/bar_exact.hpp — exact solutions of two 1D elastic bar impact problems, the
// analytic references of the `bar` model (derivations: docs/bar_impact.md).
//
// They are the seed's problem (1)–(6) in one dimension (σ = E u_x, Γ_C the end x = 0,
// the contact condition (6) with u_N = −u(0,t) + g).
// Both solve the wave equation with a Signorini condition at the left end,
//
//     ρ u_tt − E u_xx = 0  in (0, L),       c = √(E/ρ),
//     u(0,t) ≥ g,   R(t) ≥ 0,   R(t) (u(0,t) − g) = 0,    R(t) = −E u_x(0,t),
//
// R the force the obstacle exerts on the bar (in the +x direction; the bar is pushed
// away from the obstacle, so the end is in compression, u_x(0,t) ≤ 0, while in
// contact).  The seed's multiplier is λ = −R = E u_x(0,t) ≤ 0, and cdyn's QP reaction at
// the contact vertex is a discrete R.
//
// The solutions are piecewise linear in x and t: the velocity v = u_t and the strain
// ε = u_x are piecewise constant, separated by fronts x = x₀ ± c t.  At a front the
// functions below return one of the two one-sided values.
#pragma once

namespace cdyn {

// (a) The clamped bar of data/scenes/bar.toml (Doyen–Ern–Piperno's 1D test up to
// notation; docs/bar_impact.md §3):
// u(L,t) = 0, obstacle g = 0 at x = 0, u(x,0) = δ (1 − x/L), u_t(x,0) = 0.
// The compressed bar is released at t = 0, its end reaches the obstacle at t = L/c,
// stays in contact with the constant force R = E δ/L until t = 2L/c, then leaves; at
// t = 3L/c it is back in its initial state: the solution is periodic, of period 3L/c.
struct ClampedBarImpact {
  double E = 1.0, rho = 1.0, L = 1.0;
  double delta = 0.5;  // the initial displacement of the contact end (data/scenes/bar.toml: ½)

  double wave_speed() const;                              // c = √(E/ρ)
  double period() const { return 3.0 * L / wave_speed(); }
  double contact_begins() const { return L / wave_speed(); }      // first impact
  double contact_ends() const { return 2.0 * L / wave_speed(); }  // first release

  double displacement(double x, double t) const;  // u(x, t)
  double velocity(double x, double t) const;      // u_t(x, t)
  double strain(double x, double t) const;        // u_x(x, t)
  double contact_force(double t) const;           // R(t) = −E u_x(0, t)
  double contact_impulse(double t) const;         // ∫₀ᵗ R ds (t ≥ 0): E δ/c per period

  // ½∫ρ u_t² and ½∫E u_x², each piecewise linear in t; their sum is E δ²/(2L).
  double kinetic_energy(double t) const;
  double elastic_energy(double t) const;
  double energy(double t) const { return kinetic_energy(t) + elastic_energy(t); }
};

// (b) The falling free bar: no Dirichlet condition (both ends free), u(x,0) = 0,
// u_t(x,0) = −v₀, no body force, obstacle at the gap d below the contact end:
// u(0,t) ≥ −d.  Free flight until t₀ = d/v₀; contact for 2L/c with the constant force
// R = ρ c v₀ (the bar's impedance times the impact speed); at t₀ + 2L/c the bar leaves
// with the velocity +v₀ and no elastic energy left: the energy ½ρL v₀² is conserved.
struct FallingBar {
  double E = 1.0, rho = 1.0, L = 1.0;
  double v0 = 0.3;  // impact speed (the initial velocity is −v₀)
  double d = 0.1;   // initial gap: the obstacle is g = −d

  double wave_speed() const;                               // c = √(E/ρ)
  double contact_begins() const { return d / v0; }         // t₀
  double contact_ends() const { return d / v0 + 2.0 * L / wave_speed(); }

  double displacement(double x, double t) const;
  double velocity(double x, double t) const;
  double strain(double x, double t) const;
  double contact_force(double t) const;  // R(t) = −E u_x(0, t)
  double contact_impulse(double t) const;  // ∫₀ᵗ R ds: 2ρL v₀ once the bar has left

  double kinetic_energy(double t) const;
  double elastic_energy(double t) const;
  double energy(double t) const { return kinetic_energy(t) + elastic_energy(t); }
};

}  // namespace cdyn
