// mass_spec.hpp — which inertia a problem has: one of the seed's pairs W^h/H^h
// (M = Bᵀ C⁻¹ B, eq. 11) or a classical mass model on W^h (consistent, lumped,
// redistributed; docs/semi_discretization.md).  The text forms "P1+/P0" and
// "consistent" are parsed here and nowhere else.
#pragma once

#include <string>

#include "cdyn/fe/element.hpp"

namespace cdyn {

struct MassSpec {
  enum class Model { Pair, Consistent, Lumped, Redistributed };

  Model model = Model::Pair;
  Element W = Element::P1Bubble;  // the displacement space W^h (for every model)
  Element H = Element::P0;        // the velocity space H^h (Model::Pair only)

  static MassSpec pair(Element W, Element H) { return {Model::Pair, W, H}; }

  // "P1+/P0" (a pair), "P0" (the velocity space alone: the pair W/P0), or "consistent",
  // "lumped", "redistributed" (on W).  InputError with parameter "pair" for anything
  // else, for P0 displacements and for P2 velocities with W ≠ P2.
  static MassSpec parse(const std::string& text, Element W = Element::P1);

  bool is_pair() const { return model == Model::Pair; }
  // "P1+/P0", "consistent", ...
  std::string name() const;
};

}  // namespace cdyn
