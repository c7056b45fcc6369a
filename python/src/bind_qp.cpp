// bind_qp.cpp — the step QP in Python (qp/): min ½ XᵀSX − rᵀX over lower ≤ X ≤ upper,
// with S given explicitly or by its saddle form {A, B, C, c} (S = A + c Bᵀ C⁻¹ B, seed
// eq. 11), and the step solvers of this build (pdas, pgs, ipopt, nlopt: step_solver_names()).
//
// Copies: S, r and the bounds are copied into the BoundQP when it is made (the kernel's
// BoundQP owns Eigen storage); its S reads back as a view.  A QPResult's vectors are
// copies (the result is a value).
#include <limits>

#include "cdyn/qp/kkt.hpp"
#include "cdyn/qp/step_solver.hpp"
#include "cdyn_python.hpp"

namespace cdyn::python {

namespace {

Eigen::VectorXd bound_or(const std::optional<Eigen::VectorXd>& b, Eigen::Index n, double value) {
  return b ? *b : Eigen::VectorXd::Constant(n, value);
}

}  // namespace

void bind_qp(py::module_& m) {
  const double inf = std::numeric_limits<double>::infinity();

  py::class_<SaddleForm>(m, "SaddleForm", "S = A + c Bᵀ C⁻¹ B given by its blocks (base/sparse.hpp)")
      .def(py::init([](SparseMatrix A, SparseMatrix B, SparseMatrix C, double c) {
             return SaddleForm{std::move(A), std::move(B), std::move(C), c};
           }),
           "A"_a, "B"_a, "C"_a, "c"_a = 1.0)
      .def_readonly("A", &SaddleForm::A)
      .def_readonly("B", &SaddleForm::B)
      .def_readonly("C", &SaddleForm::C)
      .def_readonly("c", &SaddleForm::c);

  py::class_<BoundQP>(m, "BoundQP", "min ½ XᵀSX − rᵀX subject to lower ≤ X ≤ upper (qp/bound_qp.hpp)")
      .def(py::init([inf](std::optional<SparseMatrix> S, const Eigen::VectorXd& r,
                          const std::optional<Eigen::VectorXd>& lower, const std::optional<Eigen::VectorXd>& upper,
                          std::optional<SaddleForm> saddle) {
             BoundQP qp;
             if (S) qp.S = std::move(*S);
             qp.saddle = std::move(saddle);
             qp.r = r;
             qp.lower = bound_or(lower, r.size(), -inf);
             qp.upper = bound_or(upper, r.size(), inf);
             return qp;
           }),
           "S"_a = py::none(), "r"_a, "lower"_a = py::none(), "upper"_a = py::none(), "saddle"_a = py::none(),
           "give S (scipy.sparse, symmetric positive definite) or saddle; bounds default to ∓inf")
      .def_readonly("S", &BoundQP::S)
      .def_readonly("saddle", &BoundQP::saddle)
      .def_readwrite("r", &BoundQP::r)
      .def_readwrite("lower", &BoundQP::lower)
      .def_readwrite("upper", &BoundQP::upper)
      .def_property_readonly("size", &BoundQP::size);

  py::class_<QPOptions>(m, "QPOptions", "The step solvers' options (qp/bound_qp.hpp), e.g. QPOptions(tol=1e-12)")
      .def(init_from_keywords<QPOptions>())
      .def_readwrite("tol", &QPOptions::tol)
      .def_readwrite("max_iterations", &QPOptions::max_iterations)
      .def_readwrite("throw_on_failure", &QPOptions::throw_on_failure)
      .def_readwrite("pdas_update_limit", &QPOptions::pdas_update_limit)
      .def_readwrite("pdas_cg_iterations", &QPOptions::pdas_cg_iterations)
      .def_readwrite("pgs_omega", &QPOptions::pgs_omega)
      .def_readwrite("pgs_check_every", &QPOptions::pgs_check_every)
      .def_readwrite("ipopt_crossover", &QPOptions::ipopt_crossover)
      .def_readwrite("nlopt_algorithm", &QPOptions::nlopt_algorithm)
      .def_readwrite("nlopt_polish_rounds", &QPOptions::nlopt_polish_rounds);

  py::class_<QPResult>(m, "QPResult", "A solution X with its reaction λ = S X − r and what it cost")
      .def_readonly("X", &QPResult::X)
      .def_readonly("reaction", &QPResult::reaction)
      .def_readonly("active", &QPResult::active)
      .def_readonly("iterations", &QPResult::iterations)
      .def_readonly("kkt_residual", &QPResult::kkt_residual)
      .def_readonly("seconds", &QPResult::seconds)
      .def_readonly("converged", &QPResult::converged);

  py::class_<StepSolver>(m, "StepSolver", "A step QP solver; keeps factorizations of S between solves")
      .def_property_readonly("name", &StepSolver::name)
      .def(
          "solve",
          [](StepSolver& solver, const BoundQP& qp, const QPResult* warm_start) { return solver.solve(qp, warm_start); },
          "qp"_a, "warm_start"_a = nullptr, "the solution, to the solver's tol on kkt_residual");
  m.def("step_solver", &make_step_solver, "name"_a, "options"_a = QPOptions(), "a solver by name: step_solver_names()");
  m.def("step_solver_names", &step_solver_names, "the step solvers of this build");
  m.def(
      "kkt_residual", [](const BoundQP& qp, const Eigen::VectorXd& X) { return kkt_residual(qp, X); }, "qp"_a, "X"_a,
      "how far X is from the KKT conditions of the QP, as every solver measures it (qp/kkt.hpp)");
}

}  // namespace cdyn::python
