// format.hpp — numbers in messages: six significant digits, as printf's %g.
#pragma once

#include <sstream>
#include <string>

namespace cdyn {

inline std::string to_text(double v) {
  std::ostringstream s;
  s.precision(6);
  s << v;
  return s.str();
}

}  // namespace cdyn
