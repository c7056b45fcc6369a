// base/error.hpp — the two kinds of failure cdyn reports.
//
// Not part of the seed's mathematics: the kernel's contract for failures.
//
// InputError: the caller gave something the kernel cannot use (dt <= 0, an unknown
// scheme, a mesh that cannot carry a pair, ...).  The message says what is wrong in the
// kernel's own vocabulary; when it concerns one named quantity, `parameter()` gives that
// name ("dt", "rho", "pair", ...), so that a front end can name its own key for it (the
// command line turns "dt" into "time.dt", docs/scenes.md) and exit with status 2.
//
// NumericalError: the computation itself failed (a QP that does not converge, a NaN,
// a pair that violates condition (12) where it is required).  It is reported, never
// silently continued.
#pragma once

#include <stdexcept>
#include <string>

namespace cdyn {

struct InputError : std::runtime_error {
  explicit InputError(const std::string& message) : std::runtime_error(message), message_(message) {}
  // what() is "parameter: message".
  InputError(const std::string& parameter, const std::string& message)
      : std::runtime_error(parameter + ": " + message), parameter_(parameter), message_(message) {}

  // The quantity the error concerns (empty when the message names it itself), and the
  // message without it.
  const std::string& parameter() const { return parameter_; }
  const std::string& message() const { return message_; }

 private:
  std::string parameter_;
  std::string message_;
};

struct NumericalError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

}  // namespace cdyn
