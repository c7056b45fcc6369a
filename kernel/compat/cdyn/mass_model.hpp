// mass_model.hpp — forwarding header: the flat include path of cdyn 0.1 before the kernel was
// laid out by stage (docs/kernel_map.md).  Kept for one release; include the new path.
#pragma once

#include "cdyn/mass/mass_model.hpp"


namespace cdyn {

// The former name test of the classical models (now MassSpec::is_pair()).
inline bool is_classical_mass_model(const std::string& spec) {
  return spec == "consistent" || spec == "lumped" || spec == "redistributed";
}

}  // namespace cdyn
