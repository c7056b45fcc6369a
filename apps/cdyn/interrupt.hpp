// interrupt.hpp — Ctrl-C (SIGINT) and SIGTERM as a request to stop, for `cdyn run`
// and `cdyn study` (docs/outputs.md): the handler only raises a flag, which the time
// loop and the study's loop over runs read between steps and runs; what was computed
// is then written and the command exits with status 130.
#pragma once

#include <csignal>

namespace cdyn::app {

// Whether SIGINT or SIGTERM arrived since the outermost InterruptGuard was installed.
bool interrupted();

// Catches SIGINT and SIGTERM while it lives, then puts the previous handlers back.
// Guards nest (a study's guard around the guards of its runs): only the outermost one
// clears the flag, so a Ctrl-C between two runs of a study is not forgotten.
class InterruptGuard {
 public:
  InterruptGuard();
  ~InterruptGuard();
  InterruptGuard(const InterruptGuard&) = delete;
  InterruptGuard& operator=(const InterruptGuard&) = delete;

 private:
  struct sigaction previous_int_{}, previous_term_{};
};

}  // namespace cdyn::app
