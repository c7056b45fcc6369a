// mass_spec.cpp — the one parser of pair and mass-model names.
#include "cdyn/mass/mass_spec.hpp"

#include "cdyn/base/error.hpp"

namespace cdyn {

MassSpec MassSpec::parse(const std::string& text, Element W) {
  if (text == "consistent") return {Model::Consistent, W, Element::P0};
  if (text == "lumped") return {Model::Lumped, W, Element::P0};
  if (text == "redistributed") return {Model::Redistributed, W, Element::P0};
  MassSpec s;
  s.W = W;
  std::string velocity = text;
  try {
    if (const auto slash = text.find('/'); slash != std::string::npos) {
      s.W = element_from_string(text.substr(0, slash));
      velocity = text.substr(slash + 1);
    }
    s.H = element_from_string(velocity);
  } catch (const InputError&) {
    throw InputError("pair", "unknown pair or mass model '" + text +
                                 "' (a pair W/H such as P1+/P0, or consistent, lumped, redistributed)");
  }
  if (s.W == Element::P0) throw InputError("pair", "'" + text + "': the displacement space must be continuous");
  if (s.H == Element::P2 && s.W != Element::P2)
    throw InputError("pair", "'" + text + "': a P2 velocity space needs W^h = P2 (its boundary edge dofs come from W^h)");
  return s;
}

std::string MassSpec::name() const {
  switch (model) {
    case Model::Consistent: return "consistent";
    case Model::Lumped: return "lumped";
    case Model::Redistributed: return "redistributed";
    case Model::Pair: break;
  }
  return to_string(W) + "/" + to_string(H);
}

}  // namespace cdyn
