// cdyn_python.hpp — what the binding files of the Python module share: one bind_*
// function per stage of the data flow (docs/kernel_map.md), numpy and scipy views of
// the kernel's arrays, and Python values turned into the kernel's data (fields, parts).
//
// Arrays cross the boundary without a copy where the layout allows (docs/python.md,
// "Copies"): a matrix or vector the kernel keeps (a problem's A, its bounds, a mesh's
// vertices) is lent to Python as a read-only view whose base is the Python object that
// owns it, so the view keeps that object alive; a matrix or vector the kernel returns
// by value is moved into a Python-owned holder and viewed from there.
#pragma once

#include <pybind11/eigen.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <string>
#include <vector>

#include "cdyn/base/sparse.hpp"
#include "cdyn/fe/element.hpp"
#include "cdyn/fe/field.hpp"
#include "cdyn/mesh/mesh.hpp"

namespace cdyn::python {

namespace py = pybind11;
using namespace pybind11::literals;

// A scipy.sparse.csc_matrix over the compressed arrays of S (data, indices, indptr:
// Eigen's column-major layout is scipy's CSC), read-only, kept alive by `owner`, the
// Python object that owns S.  An uncompressed S (never made by the kernel) is copied.
py::object csc_view(const SparseMatrix& S, py::handle owner);

// The same for a matrix that Python alone will own: S is moved into a holder that the
// arrays keep alive (no copy of its entries); writable.
py::object csc_owned(SparseMatrix&& S);

// A copy of a scipy.sparse matrix (any format, any index type; duplicates summed) in the
// kernel's storage.  TypeError for anything that is not a scipy.sparse matrix.
SparseMatrix sparse_from(py::handle matrix);

// A read-only numpy view of `rows` records of `cols` values of type T, the first at
// `data`, `row_stride` bytes apart (an array of structs seen as a 2D array), kept alive
// by `owner`.
template <class T>
py::array struct_view(const T* data, py::ssize_t rows, py::ssize_t cols, py::ssize_t row_stride, py::handle owner) {
  py::array a(py::dtype::of<T>(), {rows, cols}, {row_stride, static_cast<py::ssize_t>(sizeof(T))}, data, owner);
  a.attr("setflags")("write"_a = false);
  return a;
}

// An element from Element.P1 or its name ("P0", "P1", "P1+", "P2"; InputError otherwise).
Element to_element(const py::object& element);

// A datum of the kernel from a Python value: a number (a constant), a string (an
// expression in x, y, z, t, as in scene files, parsed by muParser) or a callable
// f(x, y, t) (called from the kernel with the GIL held).  `name` names it in errors.
Field to_field(const py::object& value, const std::string& name);
// One field per component: a single value, or a list of values.
std::vector<Field> to_fields(const py::object& value, const std::string& name);
// Whether a datum depends on t as far as its value tells: a string that mentions t;
// numbers never, callables by default not (the caller says so).
bool mentions_time(const py::object& value);

// A struct of options (QPOptions, SchemeParameters) from keyword arguments, each
// setting the field of its name (bound with def_readwrite) on the C++ defaults:
// QPOptions(tol=1e-12).  An unknown name is a TypeError naming it.
template <class T>
auto init_from_keywords() {
  return py::init([](const py::kwargs& fields) {
    py::object o = py::cast(T());
    for (const auto& [name, value] : fields) {
      if (!py::hasattr(o, name)) throw py::type_error("unknown option '" + py::str(name).cast<std::string>() + "'");
      py::setattr(o, name, value);
    }
    return o.cast<T>();
  });
}

// Boundary parts given by name or by index ("all": every part and the untagged facets).
std::vector<int> part_indices(const Mesh& mesh, const py::object& parts);

// The stages, in data-flow order.
void bind_mesh(py::module_& m);      // mesh/, meshing: Mesh, built-in meshes, read_mesh
void bind_fe(py::module_& m);        // fe/: Element, FESpace, DirichletLift, assembly
void bind_mass(py::module_& m);      // mass/, problems/, wellposedness/
void bind_qp(py::module_& m);        // qp/: BoundQP, step solvers
void bind_schemes(py::module_& m);   // schemes/: State, TimeScheme
void bind_runs(py::module_& m);      // apps/: scenes, run, study, wellposed, Simulation

}  // namespace cdyn::python

namespace pybind11::detail {

// The kernel's SparseMatrix as scipy.sparse.csc_matrix, instead of pybind11's own Eigen
// caster (which copies every matrix going out and needs writable arrays coming in): a
// matrix returned by value is moved into Python's keeping, one the kernel keeps (a member
// read through a property: policy reference_internal) is a read-only view of it, and a
// matrix coming in is copied into Eigen's storage (sparse_from).
template <>
struct type_caster<cdyn::SparseMatrix> {
  PYBIND11_TYPE_CASTER(cdyn::SparseMatrix, const_name("scipy.sparse.csc_matrix"));

  bool load(handle src, bool) {
    if (!src || !module_::import("scipy.sparse").attr("issparse")(src).cast<bool>()) return false;
    value = cdyn::python::sparse_from(src);
    return true;
  }
  static handle cast(cdyn::SparseMatrix&& S, return_value_policy, handle) {
    return cdyn::python::csc_owned(std::move(S)).release();
  }
  static handle cast(const cdyn::SparseMatrix& S, return_value_policy policy, handle parent) {
    if (policy == return_value_policy::reference_internal && parent) return cdyn::python::csc_view(S, parent).release();
    return cdyn::python::csc_owned(cdyn::SparseMatrix(S)).release();
  }
};

}  // namespace pybind11::detail
