// bind_mass.cpp — inertia, problems and condition (12) in Python: the mass models
// (mass/: M = Bᵀ C⁻¹ B of a pair, seed eq. 11, or a classical mass), the constrained
// problem M Ü + A U = L + Gᵀλ, G U ≤ α (problems/, seed eq. 16) of the membrane, the bar
// and the one-dof oscillator, and β = σ_min(G Z) (wellposedness/, condition (12)).
//
// Copies: a problem's A, A_full, bounds and Dirichlet lifting are views of the problem's
// own storage (they keep the problem alive).  M, B and C of a mass model are copies made
// by the kernel's interface (MassModel::matrix() and saddle() return them by value);
// mixed_blocks() and G are assembled on demand.  load(t) is a copy (the kernel keeps one
// cached vector that its next call overwrites).
#include <cmath>
#include <limits>
#include <optional>

#include "cdyn/base/error.hpp"
#include "cdyn/mass/mass_model.hpp"
#include "cdyn/problems/oscillator.hpp"
#include "cdyn/problems/scalar_wave.hpp"
#include "cdyn/wellposedness/condition12.hpp"
#include "cdyn_python.hpp"

namespace cdyn::python {

namespace {

// G and α of the seed's eq. 16 for a problem whose constraints are bounds on single
// unknowns: a lower bound X_i ≥ l_i is the row −e_i with α = −l_i, an upper bound
// X_i ≤ u_i the row e_i with α = u_i (in the order of the constrained unknowns).
std::pair<SparseMatrix, Eigen::VectorXd> constraint_rows(const ConstrainedProblem& p, double t) {
  Eigen::VectorXd lower, upper;
  p.bounds(t, lower, upper);
  std::vector<Eigen::Triplet<double>> entries;
  std::vector<double> alpha;
  for (int i : p.constrained) {
    if (std::isfinite(lower[i])) {
      entries.emplace_back(static_cast<int>(alpha.size()), i, -1.0);
      alpha.push_back(-lower[i]);
    }
    if (std::isfinite(upper[i])) {
      entries.emplace_back(static_cast<int>(alpha.size()), i, 1.0);
      alpha.push_back(upper[i]);
    }
  }
  SparseMatrix G(static_cast<int>(alpha.size()), p.n_free());
  G.setFromTriplets(entries.begin(), entries.end());
  return {std::move(G), Eigen::Map<Eigen::VectorXd>(alpha.data(), static_cast<Eigen::Index>(alpha.size()))};
}

Condition12Method condition12_method(const std::string& name) {
  if (name == "automatic") return Condition12Method::automatic;
  if (name == "dense") return Condition12Method::dense;
  if (name == "sparse") return Condition12Method::sparse;
  throw InputError("method", "unknown method '" + name + "' (automatic, dense, sparse)");
}

}  // namespace

void bind_mass(py::module_& m) {
  py::class_<MassModel>(m, "MassModel", "The inertia on the free dofs of W^h (mass/mass_model.hpp)")
      .def_property_readonly("name", &MassModel::name)
      .def_property_readonly("is_invertible", &MassModel::is_invertible)
      .def_property_readonly("velocity_is_rate", &MassModel::velocity_is_rate)
      .def_property_readonly("n_velocity", &MassModel::n_velocity, "N_H")
      .def_property_readonly(
          "M",
          &MassModel::matrix,
          "M = Bᵀ C⁻¹ B (a copy), or None when C⁻¹ is dense (a continuous H^h)")
      .def_property_readonly(
          "B", [](const MassModel& mass) { return mass.saddle(SparseMatrix(), 1.0).B; },
          "B (N_H × n_free; for a classical mass the factor B_s of its saddle form), a copy")
      .def_property_readonly(
          "C", [](const MassModel& mass) { return mass.saddle(SparseMatrix(), 1.0).C; },
          "C (N_H × N_H), a copy")
      .def("momentum", &MassModel::momentum, "V"_a, "Bᵀ V")
      .def("velocity", &MassModel::velocity, "Wdot"_a, "C⁻¹ B Ẇ")
      .def("kinetic_energy", &MassModel::kinetic_energy, "V"_a, "½ Vᵀ C V")
      .def("acceleration", &MassModel::acceleration, "F"_a);

  m.def(
      "make_mass_model",
      [](const FESpace& W, const DirichletLift& bc, const std::string& spec, double rho,
         const std::vector<int>& contact_free_dofs) { return make_mass_model(W, bc, spec, rho, contact_free_dofs); },
      "W"_a, "bc"_a, "spec"_a, "rho"_a = 1.0, "contact_free_dofs"_a = std::vector<int>{},
      "the mass model 'P1+/P0' (a pair W/H), 'consistent', 'lumped' or 'redistributed' on W's free dofs");
  m.def(
      "mixed_blocks",
      [](const FESpace& W, const DirichletLift& bc, const py::object& H, double rho) {
        MixedBlocks b = mixed_blocks(W, bc, to_element(H), rho);
        return std::pair(std::move(b.B), std::move(b.C));
      },
      "W"_a, "bc"_a, "H"_a, "rho"_a = 1.0, "(B, C) of the pair W/H on W's free dofs, both times ρ");

  py::class_<ConstrainedProblem>(m, "ConstrainedProblem",
                                 "M Ü + A U = L(t) + Gᵀλ, G U ≤ α on the free dofs of W^h (seed eq. 16)")
      .def_property_readonly("W", [](const ConstrainedProblem& p) -> const FESpace& { return *p.W; },
                             py::return_value_policy::reference_internal)
      .def_property_readonly("bc", [](const ConstrainedProblem& p) -> const DirichletLift& { return *p.bc; },
                             py::return_value_policy::reference_internal)
      .def_property_readonly("mass", [](const ConstrainedProblem& p) -> const MassModel& { return *p.mass; },
                             py::return_value_policy::reference_internal)
      .def_property_readonly("n_free", &ConstrainedProblem::n_free)
      .def_readonly("A", &ConstrainedProblem::A, "A on the free dofs (a view)")
      .def_readonly("A_full", &ConstrainedProblem::A_full, "A on all dofs of W^h (a view)")
      .def_readonly("UD", &ConstrainedProblem::UD, "the Dirichlet lifting U_D (a view)")
      .def_readonly("lower", &ConstrainedProblem::lower, "the lower bounds at t = 0 (a view)")
      .def_readonly("upper", &ConstrainedProblem::upper, "the upper bounds at t = 0 (a view)")
      .def_readonly("constrained", &ConstrainedProblem::constrained, "the free dofs carrying a bound")
      .def(
          "load", [](const ConstrainedProblem& p, double t) { return Eigen::VectorXd(p.load(t)); }, "t"_a = 0.0,
          "(L(t) − A U_D)_f, the load on the free dofs (a copy)")
      .def(
          "full_load", [](const ConstrainedProblem& p, double t) { return Eigen::VectorXd(p.full_load(t)); },
          "t"_a = 0.0, "L(t) on all dofs (a copy)")
      .def(
          "G",
          &constraint_rows,
          "t"_a = 0.0, "(G, α) of the constraint G U ≤ α at time t: a row −e_i per lower bound, e_i per upper")
      .def("full", &ConstrainedProblem::full, "U"_a, "the full coefficient vector P U + U_D")
      .def("unknowns", &ConstrainedProblem::unknowns, "U_full"_a, "the free unknowns of a full vector")
      .def("potential_energy", &ConstrainedProblem::potential_energy, "U"_a, "t"_a = 0.0, "½ uᵀA u − Lᵀu, u = full(U)")
      .def("max_violation", &ConstrainedProblem::max_violation, "U"_a, "t"_a = 0.0)
      .def("__repr__", [](const ConstrainedProblem& p) {
        return "<cdyn.ConstrainedProblem " + p.mass->name() + ", " + std::to_string(p.n_free()) + " free dofs, " +
               std::to_string(p.constrained.size()) + " constrained>";
      });

  m.def(
      "scalar_wave",
      [](const Mesh& mesh, const std::string& mass, double rho, double kappa, const py::object& f,
         const py::object& dirichlet_parts, const py::object& dirichlet_value, bool obstacle,
         const py::object& obstacle_where, const py::object& g, std::optional<bool> load_is_constant,
         std::optional<bool> obstacle_moves) {
        ScalarWaveData d;
        d.mass = MassSpec::parse(mass, Element::P1);
        d.rho = rho;
        d.kappa = kappa;
        d.f = to_field(f, "f");
        d.load_is_constant = load_is_constant.value_or(!mentions_time(f));
        d.dirichlet_parts = part_indices(mesh, dirichlet_parts);
        d.dirichlet_value = to_field(dirichlet_value, "dirichlet_value");
        d.obstacle = obstacle;
        d.obstacle_on_all_vertices = py::isinstance<py::str>(obstacle_where) && obstacle_where.cast<std::string>() == "vertices";
        if (!d.obstacle_on_all_vertices) d.obstacle_parts = part_indices(mesh, obstacle_where);
        d.obstacle_g = to_field(g, "g");
        d.obstacle_moves = obstacle_moves.value_or(mentions_time(g));
        return build_scalar_wave(mesh, d);
      },
      "mesh"_a, "mass"_a = "P1+/P0", "rho"_a = 1.0, "kappa"_a = 1.0, "f"_a = 0.0, "dirichlet_parts"_a = py::list(),
      "dirichlet_value"_a = 0.0, "obstacle"_a = true, "obstacle_where"_a = "vertices", "g"_a = 0.0,
      "load_is_constant"_a = py::none(), "obstacle_moves"_a = py::none(), py::keep_alive<0, 1>(),
      "ρ ü − κ Δu = f, u = g_D on the Dirichlet parts, u(a) ≥ g(a) at the constrained vertices (the membrane, "
      "the bar); data as numbers, expressions or callables f(x, y, t)");
  m.def("oscillator_mesh", &oscillator_mesh, "the one-element mesh of the oscillator");
  m.def(
      "oscillator",
      [](const Mesh& mesh, double mass, double k, const py::object& F, double g, bool obstacle,
         std::optional<bool> load_is_constant) {
        OscillatorData o;
        o.m = mass;
        o.k = k;
        o.F = to_field(F, "F");
        o.load_is_constant = load_is_constant.value_or(!mentions_time(F));
        o.g = g;
        o.obstacle = obstacle;
        return build_oscillator(mesh, o);
      },
      "mesh"_a, "m"_a = 1.0, "k"_a = 1.0, "F"_a = 0.0, "g"_a = 0.0, "obstacle"_a = true,
      "load_is_constant"_a = py::none(), py::keep_alive<0, 1>(),
      "m ü + k u = F(t) + λ, u ≥ g: the seed's one-dof system, on oscillator_mesh()");

  py::class_<WellPosedness>(m, "WellPosedness", "Condition (12): β = σ_min(G Z), Z a basis of Ker B")
      .def_readonly("pair", &WellPosedness::pair)
      .def_readonly("n_W", &WellPosedness::n_W)
      .def_readonly("n_H", &WellPosedness::n_H)
      .def_readonly("dim_ker_B", &WellPosedness::dim_ker_B)
      .def_readonly("n_g", &WellPosedness::n_g)
      .def_readonly("beta", &WellPosedness::beta)
      .def_readonly("satisfied", &WellPosedness::satisfied)
      .def_readonly("method", &WellPosedness::method)
      .def("__repr__", [](const WellPosedness& w) {
        return "<cdyn.WellPosedness " + w.pair + ": beta = " + std::to_string(w.beta) +
               (w.satisfied ? ", satisfied>" : ", not satisfied>");
      });
  m.def(
      "condition12",
      [](const SparseMatrix& B, const SparseMatrix& G, const std::string& method) {
        return condition12(B, G, condition12_method(method));
      },
      "B"_a, "G"_a, "method"_a = "automatic", "β = σ_min(G Z) for B (N_H × N_W) and G (N_g × N_W)");
  m.def(
      "vertex_constraint_matrix",
      [](const FESpace& W, const DirichletLift& bc, const std::vector<int>& vertices,
         std::optional<std::array<double, 2>> normal) {
        std::optional<Point> n;
        if (normal) n = Point{(*normal)[0], (*normal)[1]};
        return vertex_constraint_matrix(W, bc, vertices, n);
      },
      "W"_a, "bc"_a, "vertices"_a, "normal"_a = py::none(), "G: one row per constrained free vertex");
  m.def(
      "condition12_on",
      [](const Mesh& mesh, const std::string& spec, const py::object& dirichlet_parts,
         const std::vector<int>& constrained_vertices, const std::string& method) {
        WellPosednessSetup setup;
        setup.dirichlet_parts = part_indices(mesh, dirichlet_parts);
        setup.constrained_vertices = constrained_vertices;
        setup.method = condition12_method(method);
        return condition12_on(mesh, MassSpec::parse(spec, Element::P1), setup);
      },
      "mesh"_a, "spec"_a, "dirichlet_parts"_a, "constrained_vertices"_a, "method"_a = "automatic",
      "condition (12) for a pair (or classical mass on P1) on a mesh, scalar constraints at the given vertices");
}

}  // namespace cdyn::python
