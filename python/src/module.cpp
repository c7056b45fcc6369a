// module.cpp — the compiled part of the Python module `cdyn` (cdyn._cdyn): the two
// errors of the kernel as Python exceptions, then the stages in data-flow order.
//
// cdyn::InputError becomes cdyn.InputError (a ValueError), cdyn::NumericalError
// cdyn.NumericalError (a RuntimeError), each carrying the kernel's or the command
// line's one-line message unchanged: the text `cdyn` prints after "cdyn: error: " or
// "cdyn: numerical failure: ".
#include "cdyn/base/error.hpp"
#include "cdyn/qp/petsc/backend.hpp"
#include "cdyn/version.hpp"
#include "cdyn_python.hpp"

PYBIND11_MODULE(_cdyn, m) {
  using namespace cdyn::python;
  m.doc() = "cdyn's kernel and command line (compiled part); import cdyn instead";
  m.attr("__version__") = cdyn::version;
  // (the PETSc back end ends its process without the interpreter's own ending)
  cdyn::petsc::refuse("the Python module runs on the native back end; run solver.backend = \"petsc\" with the "
                      "command line (mpirun -n P cdyn run SCENE, docs/distributed.md)");
  auto input = py::register_exception<cdyn::InputError>(m, "InputError", PyExc_ValueError);
  auto numerical = py::register_exception<cdyn::NumericalError>(m, "NumericalError", PyExc_RuntimeError);
  input.attr("__module__") = "cdyn";
  numerical.attr("__module__") = "cdyn";
  input.doc() = "Bad input: the message names the key, file or parameter (cdyn exits with status 2)";
  numerical.doc() = "The computation failed: a QP that does not converge, a blow-up (cdyn exits with status 3)";
  bind_mesh(m);
  bind_fe(m);
  bind_mass(m);
  bind_qp(m);
  bind_schemes(m);
  bind_runs(m);
}
