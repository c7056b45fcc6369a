// base/scope_timer.hpp — the wall time of a scope, added to a counter: the cost figures a
// run reports (the pdas solver's counters, the full-step reconstruction's seconds).
#pragma once

#include <chrono>

namespace cdyn {

// Adds the wall time of its scope to `seconds` (steady clock: immune to clock changes).
class ScopeTimer {
 public:
  explicit ScopeTimer(double& seconds) : seconds_(seconds), start_(std::chrono::steady_clock::now()) {}
  ~ScopeTimer() { seconds_ += std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count(); }
  ScopeTimer(const ScopeTimer&) = delete;
  ScopeTimer& operator=(const ScopeTimer&) = delete;

 private:
  double& seconds_;
  std::chrono::steady_clock::time_point start_;
};

}  // namespace cdyn
