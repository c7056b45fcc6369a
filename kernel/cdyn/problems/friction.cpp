// problems/friction.cpp — the names of the friction laws.
#include "cdyn/problems/friction.hpp"

#include <cmath>

#include "cdyn/base/error.hpp"

namespace cdyn {

FrictionLaw parse_friction_law(const std::string& name) {
  if (name == "none") return FrictionLaw::None;
  if (name == "tresca") return FrictionLaw::Tresca;
  if (name == "coulomb") return FrictionLaw::Coulomb;
  throw InputError("friction", "unknown friction law '" + name + "' (none, tresca, coulomb)");
}

std::string to_string(FrictionLaw law) {
  switch (law) {
    case FrictionLaw::None: return "none";
    case FrictionLaw::Tresca: return "tresca";
    case FrictionLaw::Coulomb: return "coulomb";
  }
  return "?";
}

double tangential_magnitude(const FrictionNode& node, const Eigen::VectorXd& v) {
  if (node.tangential.size() == 1) return v[node.tangential[0]];
  double sum = 0.0;
  for (int t : node.tangential) sum += v[t] * v[t];
  return std::sqrt(sum);
}

}  // namespace cdyn
