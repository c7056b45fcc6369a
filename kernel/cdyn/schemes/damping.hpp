// schemes/damping.hpp — Rayleigh damping D = α M + β A in the equation of motion
//
//     M Ü + D U̇ + A U = L + Gᵀλ     (seed eq. 16 with a viscous force),
//
// written in the seed's two spaces: the mass part through the velocity of H^h,
// M U̇ = Bᵀ C⁻¹ B U̇ = Bᵀ V (eq. 11), so α Bᵀ V; the stiffness part on the displacement
// rate of W^h, β A U̇, with U̇ the scheme's difference quotient (U^{n+1} − Uⁿ)/dt.  The
// force does the work
//     W_d = ∫ (α VᵀCV + β U̇ᵀAU̇) dt ≥ 0,
// so that J + W_d is what a conservative scheme conserves.  A mode of frequency ω (of
// the pair A, M) is damped with the ratio ζ = α/(2ω) + βω/2: its amplitude decays like
// exp(−ζωt).  Each scheme's step QP with damping: docs/schemes.md, "Rayleigh damping".
#pragma once

namespace cdyn {

struct RayleighDamping {
  double alpha = 0.0;  // α ≥ 0, 1/time: damps the low frequencies (and rigid motions)
  double beta = 0.0;   // β ≥ 0, time: damps the high frequencies
  bool active() const { return alpha != 0.0 || beta != 0.0; }
};

}  // namespace cdyn
