// bind_schemes.cpp — the time schemes in Python (schemes/), stepped one step at a time:
// a State (t, U on the free dofs of W^h, V in H^h, the last reaction Gᵀλ), step(state)
// advancing it by dt in place, and the discrete energy J = ½VᵀCV + ½UᵀAU − LᵀU of the
// seed's Theorem 2 in the form each scheme's identity is written for.
//
// Copies: reading state.U or state.V gives a copy (a snapshot: the next step does not
// change an array already read); assigning one copies it in.
#include "cdyn/schemes/time_scheme.hpp"
#include "cdyn_python.hpp"

namespace cdyn::python {

void bind_schemes(py::module_& m) {
  py::class_<State>(m, "State", "t, U (free dofs of W^h), V (H^h) and the last step's reaction Gᵀλ")
      .def(py::init([](const Eigen::VectorXd& U, const Eigen::VectorXd& V, double t) {
             State s;
             s.t = t;
             s.U = U;
             s.V = V;
             s.reaction = Eigen::VectorXd::Zero(U.size());
             return s;
           }),
           "U"_a, "V"_a, "t"_a = 0.0)
      .def_readwrite("t", &State::t)
      .def_property(
          "U", [](const State& s) { return Eigen::VectorXd(s.U); }, [](State& s, const Eigen::VectorXd& U) { s.U = U; })
      .def_property(
          "V", [](const State& s) { return Eigen::VectorXd(s.V); }, [](State& s, const Eigen::VectorXd& V) { s.V = V; })
      .def_property(
          "reaction", [](const State& s) { return Eigen::VectorXd(s.reaction); },
          [](State& s, const Eigen::VectorXd& r) { s.reaction = r; })
      .def("copy", [](const State& s) { return State(s); })
      .def("__repr__", [](const State& s) {
        return "<cdyn.State t = " + std::to_string(s.t) + ", " + std::to_string(s.U.size()) + " U, " +
               std::to_string(s.V.size()) + " V>";
      });

  py::class_<Energy>(m, "Energy", "J split in its kinetic and potential parts")
      .def_readonly("kinetic", &Energy::kinetic)
      .def_readonly("potential", &Energy::potential)
      .def_property_readonly("total", &Energy::total)
      .def("__repr__", [](const Energy& E) {
        return "<cdyn.Energy kinetic = " + std::to_string(E.kinetic) + ", potential = " + std::to_string(E.potential) +
               ">";
      });

  py::class_<StepStats>(m, "StepStats", "What one step cost and found")
      .def_readonly("qp_iterations", &StepStats::qp_iterations)
      .def_readonly("qp_seconds", &StepStats::qp_seconds)
      .def_readonly("active", &StepStats::active)
      .def_readonly("kkt_residual", &StepStats::kkt_residual)
      .def_readonly("converged", &StepStats::converged)
      .def_readonly("reconstruction_kkt", &StepStats::reconstruction_kkt)
      .def_readonly("reconstruction_seconds", &StepStats::reconstruction_seconds,
                    "the full-step reconstruction's seconds (eq. 14), a part of the step besides qp_seconds")
      .def_readonly("reconstruction_iterations", &StepStats::reconstruction_iterations)
      .def_readonly("energy_iterations", &StepStats::energy_iterations)
      .def_readonly("dissipated", &StepStats::dissipated, "the Rayleigh damping's work over the step, W_d ≥ 0");

  py::class_<SchemeParameters>(m, "SchemeParameters",
                               "The parameters of the schemes that have some, e.g. SchemeParameters(restitution=0.5)")
      .def(init_from_keywords<SchemeParameters>())
      .def_readwrite("beta", &SchemeParameters::beta)
      .def_readwrite("gamma", &SchemeParameters::gamma)
      .def_readwrite("restitution", &SchemeParameters::restitution)
      .def_readwrite("condense", &SchemeParameters::condense)
      .def_readwrite("reconstruct", &SchemeParameters::reconstruct)
      .def_readwrite("tol", &SchemeParameters::tol)
      .def_readwrite("energy_tol", &SchemeParameters::energy_tol)
      // Rayleigh damping D = αM + βA (docs/schemes.md): damping_alpha, damping_beta
      .def_property(
          "damping_alpha", [](const SchemeParameters& p) { return p.damping.alpha; },
          [](SchemeParameters& p, double a) { p.damping.alpha = a; })
      .def_property(
          "damping_beta", [](const SchemeParameters& p) { return p.damping.beta; },
          [](SchemeParameters& p, double b) { p.damping.beta = b; });

  py::class_<TimeScheme>(m, "TimeScheme", "One step of a scheme: a step QP and an explicit update (docs/schemes.md)")
      .def_property_readonly("name", &TimeScheme::name)
      .def("step", &TimeScheme::step, "state"_a, "advances the state from t to t + dt, in place")
      .def("energy", &TimeScheme::energy, "state"_a, "J of the state (the scheme's form of it)")
      .def("initialize", &TimeScheme::initialize, "state"_a,
           "makes U⁰'s massless part the static solution of eq. (14) where the scheme reconstructs (once, before "
           "the first step)")
      .def_property_readonly("full_steps", [](const TimeScheme& s) { return to_string(s.full_steps()); });
  m.def("time_scheme", &make_time_scheme, "name"_a, "problem"_a, "solver"_a, "dt"_a,
        "parameters"_a = SchemeParameters(), py::keep_alive<0, 2>(), py::keep_alive<0, 3>(),
        "a scheme by name (time_scheme_names()); it keeps the problem and the solver alive");
  m.def("time_scheme_names", &time_scheme_names);
  m.def("recommended_scheme", &recommended_scheme, "problem"_a);
  m.def("initial_velocity", &initial_velocity, "problem"_a, "Udot0"_a, "V⁰ from C V⁰ = B U̇⁰ (seed eq. 11)");
}

}  // namespace cdyn::python
