// bind_fe.cpp — the finite element stage in Python (fe/): the reference elements, the
// spaces W^h and H^h (seed eq. 9), the Dirichlet lift, and the assembly of the seed's
// A, B, C and L (eq. 10) as scipy.sparse matrices and numpy vectors.
//
// Copies: none for the assembled matrices and vectors (the kernel returns them by value;
// they are moved into Python's keeping).  Arguments going into the kernel are copied into
// Eigen's storage (a scipy matrix or numpy vector given to restrict(), extend(), ...).
#include "cdyn/fe/assembly.hpp"
#include "cdyn/fe/dirichlet.hpp"
#include "cdyn/fe/fe_space.hpp"
#include "cdyn/fe/norms.hpp"
#include "cdyn_python.hpp"

namespace cdyn::python {

namespace {

CellCoefficient coefficient(const py::object& value) {
  if (PyNumber_Check(value.ptr())) return value.cast<double>();
  return CellCoefficient(value.cast<std::vector<double>>());  // one value per cell
}

}  // namespace

void bind_fe(py::module_& m) {
  py::enum_<Element>(m, "Element", "The reference elements; where one is asked for, its name 'P0', 'P1', 'P1+', 'P2' will do")
      .value("P0", Element::P0)
      .value("P1", Element::P1)
      .value("P1Bubble", Element::P1Bubble, "P1+: P1 and one bubble per cell (27λ0λ1λ2 on triangles)")
      .value("P2", Element::P2)
      .def(py::init(&element_from_string), "name"_a)
      .def("__str__", [](Element e) { return to_string(e); });

  py::class_<FESpace>(m, "FESpace", "A finite element space on a mesh: its dof map (fe/fe_space.hpp)")
      .def(py::init([](const Mesh& mesh, const py::object& element, int components) {
             return FESpace(mesh, to_element(element), components);
           }),
           "mesh"_a, "element"_a, "components"_a = 1, py::keep_alive<1, 2>() /* the space keeps a pointer to its mesh */)
      .def_property_readonly("mesh", &FESpace::mesh, py::return_value_policy::reference_internal)
      .def_property_readonly("element", &FESpace::element)
      .def_property_readonly("components", &FESpace::components)
      .def_property_readonly("n_dofs", &FESpace::n_dofs)
      .def_property_readonly("n_scalar_dofs", &FESpace::n_scalar_dofs)
      .def_property_readonly("local_dofs", &FESpace::local_dofs)
      .def_property_readonly("degree", &FESpace::degree)
      .def(
          "cell_dofs", [](const FESpace& W, int c) { auto d = W.cell_dofs(c); return std::vector<int>(d.begin(), d.end()); },
          "c"_a, "the scalar dofs of cell c, vertex dofs first")
      .def("dof", &FESpace::dof, "s"_a, "k"_a = 0, "the dof of scalar dof s, component k")
      .def("vertex_dof", &FESpace::vertex_dof, "v"_a, "k"_a = 0)
      .def_property_readonly(
          "dof_points",
          [](py::object self) {
            const FESpace& W = self.cast<const FESpace&>();
            return struct_view(&W.dof_points().data()->x, W.n_scalar_dofs(), 3, sizeof(Point), self);
          },
          "the nodal point of each scalar dof (a view)")
      .def(
          "boundary_scalar_dofs",
          [](const FESpace& W, const py::object& parts) { return W.boundary_scalar_dofs(part_indices(W.mesh(), parts)); },
          "parts"_a)
      .def(
          "interpolate",
          [](const FESpace& W, const py::object& f, double t) { return W.interpolate(to_fields(f, "f"), t); },
          "f"_a, "t"_a = 0.0, "the nodal interpolant of a field (one per component)")
      .def(
          "value_in_cell",
          [](const FESpace& W, const Eigen::VectorXd& U, int c, const RefPoint& xi, int k) {
            return W.value_in_cell(U, c, xi, k);
          },
          "U"_a, "c"_a, "xi"_a, "k"_a = 0)
      .def("__repr__", [](const FESpace& W) {
        const std::string power = W.components() > 1 ? "^" + std::to_string(W.components()) : "";
        return "<cdyn.FESpace " + to_string(W.element()) + power + ", " + std::to_string(W.n_dofs()) + " dofs>";
      });

  py::class_<DirichletLift>(m, "DirichletLift", "Free and fixed dofs of W^h: U = P U_f + U_D (fe/dirichlet.hpp)")
      .def(py::init([](const FESpace& W, const py::object& parts, std::vector<int> components) {
             return DirichletLift(W, part_indices(W.mesh(), parts), std::move(components));
           }),
           "W"_a, "parts"_a, "components"_a = std::vector<int>{})
      .def_property_readonly("n_full", &DirichletLift::n_full)
      .def_property_readonly("n_free", &DirichletLift::n_free)
      .def_property_readonly("free_dofs", &DirichletLift::free_dofs)
      .def_property_readonly("fixed_dofs", &DirichletLift::fixed_dofs)
      .def("free_index", &DirichletLift::free_index, "i"_a, "the index of dof i among the free dofs, or -1")
      .def(
          "lifting",
          [](const DirichletLift& bc, const FESpace& W, const py::object& g, double t) {
            return bc.lifting(W, to_fields(g, "g"), t);
          },
          "W"_a, "g"_a, "t"_a = 0.0, "U_D: the data on the fixed dofs, 0 elsewhere")
      .def("restrict", py::overload_cast<const Eigen::VectorXd&>(&DirichletLift::restrict, py::const_), "U"_a,
           "the free entries of a full vector")
      .def("extend", &DirichletLift::extend, "Uf"_a, "UD"_a, "P U_f + U_D")
      .def(
          "restrict_matrix",
          [](const DirichletLift& bc, const SparseMatrix& A) { return bc.restrict(A); }, "A"_a,
          "A_ff: the free rows and columns")
      .def(
          "restrict_columns",
          &DirichletLift::restrict_columns, "B"_a,
          "B P: the free columns");

  m.def(
      "assemble_laplace", &assemble_laplace, "W"_a,
      "A_ij = ∫∇φ_i·∇φ_j (seed eq. 10)");
  m.def(
      "assemble_mass",
      [](const FESpace& rows, const FESpace& cols, const py::object& rho) {
        return assemble_mass(rows, cols, coefficient(rho));
      },
      "rows"_a, "cols"_a, "rho"_a = 1.0, "B_ij = ∫ρ ψ_i φ_j (rows H^h, columns W^h); C = assemble_mass(H, H)");
  m.def(
      "assemble_elasticity",
      [](const FESpace& W, const py::object& lambda, const py::object& mu) {
        return assemble_elasticity(W, coefficient(lambda), coefficient(mu));
      },
      "W"_a, "lam"_a, "mu"_a, "plane strain: A_ij = ∫λ div φ_i div φ_j + 2μ ε(φ_i):ε(φ_j)");
  m.def(
      "assemble_load",
      [](const FESpace& W, const py::object& f, double t) { return assemble_load(W, to_fields(f, "f"), t); }, "W"_a,
      "f"_a, "t"_a = 0.0, "L_i = ∫f φ_i (one field per component)");
  m.def(
      "assemble_boundary_load",
      [](const FESpace& W, const py::object& parts, const py::object& g, double t) {
        return assemble_boundary_load(W, part_indices(W.mesh(), parts), to_fields(g, "g"), t);
      },
      "W"_a, "parts"_a, "g"_a, "t"_a = 0.0, "L_i = ∫_Γ g φ_i ds over the given parts");
  m.def(
      "l2_error",
      [](const FESpace& W, const Eigen::VectorXd& U, const py::object& u, double t) {
        return l2_error(W, U, to_field(u, "u"), t);
      },
      "W"_a, "U"_a, "u"_a, "t"_a = 0.0, "‖u_h − u‖_L2 of the field U of W against u(x, y, t)");
}

}  // namespace cdyn::python
