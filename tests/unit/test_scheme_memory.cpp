// test_scheme_memory.cpp — a scheme goes on from its memory (schemes/scheme_memory.hpp)
// as the run that wrote it does: the restart of `cdyn run --resume`.
//
// Every scheme integrates the membrane with contact for K steps, hands out its memory
// and restores it (what a run does at a checkpoint); a new solver and scheme made alike
// restore the same memory from a copy of the state (what a resumed run does).  Both go
// on for the rest of the steps and must agree bit for bit: U, V and the reaction
// compared with ==, not to a tolerance — the warm start is all that carries over, and
// the solver's caches are cleared on both sides.  With damping too.
#include <gtest/gtest.h>

#include "cdyn/base/error.hpp"
#include "cdyn/problems/scalar_wave.hpp"
#include "scheme_fixtures.hpp"

using namespace cdyn;
using namespace cdyn::testing;

namespace {

struct Case {
  const char* scheme;
  Method method;
  RayleighDamping damping;
};

}  // namespace

TEST(SchemeMemory, ARestoredSchemeRepeatsTheRunBitForBit) {
  const Mesh mesh = unit_square_mesh(6);
  const Case cases[] = {
      {"backward_euler", {Element::P1Bubble, "P0"}, {}},     {"midpoint", {Element::P1Bubble, "P0"}, {}},
      {"midpoint_end", {Element::P1Bubble, "P0"}, {}},       {"discrete_gradient", {Element::P1Bubble, "P0"}, {}},
      {"discrete_gradient", {Element::P1Bubble, "P0"}, {0.8, 0.004}},
      {"midpoint", {Element::P2, "P1"}, {0.8, 0.004}},       {"newmark", {Element::P1, "P1"}, {}},
      {"paoli_schatzman", {Element::P1, "lumped"}, {}},      {"paoli_schatzman", {Element::P1, "consistent"}, {}},
      {"energy_conserving", {Element::P1, "consistent"}, {}},
  };
  const int K = 40, N = 120;
  for (const Case& c : cases) {
    const std::string what = std::string(c.scheme) + " " + label(c.method);
    const ConstrainedProblem p = membrane(mesh, c.method, true);
    SchemeParameters prm;
    prm.damping = c.damping;
    auto solver = make_step_solver("pdas");
    auto scheme = make_time_scheme(c.scheme, p, *solver, 0.01, prm);
    State s = initial_state(p);
    scheme->initialize(s);
    int active = 0;
    for (int n = 0; n < K; ++n) active += scheme->step(s).active > 0;
    const SchemeMemory m = scheme->memory();
    scheme->restore(m);  // the checkpointing run

    auto solver2 = make_step_solver("pdas");  // the resumed run
    auto scheme2 = make_time_scheme(c.scheme, p, *solver2, 0.01, prm);
    State s2 = s;
    scheme2->restore(m);
    for (int n = K; n < N; ++n) {
      const StepStats a = scheme->step(s), b = scheme2->step(s2);
      active += a.active > 0;
      ASSERT_TRUE(s.U == s2.U && s.V == s2.V && s.reaction == s2.reaction && s.t == s2.t)
          << what << ": the restored scheme differs at step " << n + 1;
      ASSERT_EQ(a.qp_iterations, b.qp_iterations) << what << " step " << n + 1;
      ASSERT_EQ(a.dissipated, b.dissipated) << what << " step " << n + 1;
    }
    EXPECT_EQ(scheme->energy(s).total(), scheme2->energy(s2).total()) << what;
    EXPECT_GT(active, 10) << what << ": no contact to carry over";
  }
}

TEST(SchemeMemory, AMemoryOfAnotherSchemeIsRefused) {
  const Mesh mesh = unit_square_mesh(4);
  const ConstrainedProblem p = membrane(mesh, {Element::P1Bubble, "P0"}, true);
  auto solver = make_step_solver("pdas");
  auto euler = make_time_scheme("backward_euler", p, *solver, 0.01);
  auto gradient = make_time_scheme("discrete_gradient", p, *solver, 0.01);
  try {
    gradient->restore(euler->memory());  // no Ψ(qⁿ) in it
    ADD_FAILURE() << "restored";
  } catch (const InputError& e) {
    EXPECT_EQ(e.parameter(), "memory") << e.what();
  }
}
