// error.hpp — the two kinds of failure cdyn reports.
//
// Not part of the seed's mathematics: the kernel's contract for failures (DESIGN.md §4).
//
// InputError: the user gave something cdyn cannot use (a missing or malformed file,
// an unknown key, dt <= 0, ...).  The message names the file or key and says what is
// wrong; the command line prints it as one line and exits with status 2.
//
// NumericalError: the computation itself failed (a QP that does not converge, a NaN,
// a pair that violates condition (12) where it is required).  It is reported, never
// silently continued.
#pragma once

#include <stdexcept>
#include <string>

namespace cdyn {

struct InputError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

struct NumericalError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

}  // namespace cdyn
