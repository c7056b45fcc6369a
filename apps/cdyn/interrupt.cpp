// interrupt.cpp — the stop flag of interrupt.hpp.
#include "interrupt.hpp"

namespace cdyn::app {

namespace {

volatile std::sig_atomic_t flag = 0;
int depth = 0;  // guards alive (nesting)

extern "C" void on_interrupt(int) { flag = 1; }

}  // namespace

bool interrupted() { return flag != 0; }

InterruptGuard::InterruptGuard() {
  if (depth++ == 0) flag = 0;
  struct sigaction action{};
  action.sa_handler = on_interrupt;
  sigemptyset(&action.sa_mask);
  action.sa_flags = SA_RESTART;  // a write or a waitpid in progress goes on
  sigaction(SIGINT, &action, &previous_int_);
  sigaction(SIGTERM, &action, &previous_term_);
}

InterruptGuard::~InterruptGuard() {
  sigaction(SIGINT, &previous_int_, nullptr);
  sigaction(SIGTERM, &previous_term_, nullptr);
  --depth;
}

}  // namespace cdyn::app
