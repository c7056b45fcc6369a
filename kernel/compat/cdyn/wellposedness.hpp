// wellposedness.hpp — forwarding header: the flat include path of cdyn 0.1 before the kernel was
// laid out by stage (docs/kernel_map.md).  Kept for one release; include the new path.
#pragma once

#include "cdyn/wellposedness/condition12.hpp"


namespace cdyn {

// The former names: one row of the `cdyn wellposed` table, and the seed's pairs.
inline WellPosedness wellposedness_row(const Mesh& mesh, const std::string& spec, const WellPosednessSetup& setup,
                                       Element classical_W = Element::P1) {
  return condition12_on(mesh, MassSpec::parse(spec, classical_W), setup);
}
inline std::vector<std::string> seed_pairs() { return {"P1/P1", "P1/P0", "P1+/P0", "P1+/P1", "P2/P1"}; }

}  // namespace cdyn
