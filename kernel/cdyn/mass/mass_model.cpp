// mass_model.cpp — make_mass_model: a scene's `method.pair` / `method.mass` to a model.
#include "cdyn/mass/mass_model.hpp"

#include <algorithm>
#include <cmath>

#include "cdyn/base/error.hpp"
#include "cdyn/mass/classical.hpp"
#include "cdyn/mass/mixed.hpp"

namespace cdyn {

std::vector<std::string> classical_mass_models() { return {"consistent", "lumped", "redistributed"}; }

bool is_classical_mass_model(const std::string& spec) {
  const auto names = classical_mass_models();
  return std::find(names.begin(), names.end(), spec) != names.end();
}

std::unique_ptr<MassModel> make_mass_model(const FESpace& W, const DirichletLift& bc, const std::string& spec,
                                           double rho, const std::vector<int>& contact_free_dofs) {
  if (!(rho > 0.0) || !std::isfinite(rho))
    throw InputError("physics.rho: the density must be positive and finite (got " + std::to_string(rho) + ")");
  if (is_classical_mass_model(spec)) return make_classical_mass_model(W, bc, spec, rho, contact_free_dofs);

  // A pair "W/H" or only its velocity element "H".
  std::string velocity = spec;
  if (const auto slash = spec.find('/'); slash != std::string::npos) {
    const Element w = element_from_string(spec.substr(0, slash));
    if (w != W.element())
      throw InputError("method.pair '" + spec + "': the displacement space is " + to_string(W.element()) + ", not " +
                       to_string(w));
    velocity = spec.substr(slash + 1);
  }
  Element H;
  try {
    H = element_from_string(velocity);
  } catch (const InputError&) {
    throw InputError("method: unknown mass model or velocity space '" + spec +
                     "' (a pair such as P1+/P0, or consistent, lumped, redistributed)");
  }
  return make_mixed_mass_model(W, bc, H, rho);
}

}  // namespace cdyn
