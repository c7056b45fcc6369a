// expression.hpp — data given as text expressions in x, y, z and t.
//
// Loads, initial states, Dirichlet values and obstacles are written in scenes as
// expressions such as "-0.6" or "0.02*sin(pi*x)*(t<0.5)", parsed by muParser (its
// built-in functions sin, cos, exp, sqrt, abs, min, max, the ternary ?:, ...; the
// constant pi is predefined as _pi by muParser and added here as pi).  They give the
// seed's data: f and g of eqs. 1 and 3, u₀ and u₁ of eq. 5, the obstacle α of eq. 16.
#pragma once

#include <string>

#include "cdyn/fe/field.hpp"

namespace cdyn {

// Parses `text` once and returns the field (x, y, z, t) -> value.  A syntax error or an
// unknown variable throws InputError naming `key` (the scene key the text came from).
Field parse_expression(const std::string& text, const std::string& key);

// Whether the text mentions the variable t (a datum that changes in time).
bool depends_on_time(const std::string& text);

}  // namespace cdyn
