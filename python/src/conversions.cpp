// conversions.cpp — the kernel's sparse matrices as scipy.sparse views, and Python values
// as the kernel's fields and boundary parts (cdyn_python.hpp).
#include <memory>

#include "cdyn/base/error.hpp"
#include "cdyn_python.hpp"
#include "expression.hpp"

namespace cdyn::python {

namespace {

// A 1D numpy array of n values of T at p, with base `owner`.
template <class T>
py::array view1(const T* p, py::ssize_t n, py::handle owner, bool writable) {
  py::array a(py::dtype::of<T>(), {n}, {static_cast<py::ssize_t>(sizeof(T))}, p, owner);
  if (!writable) a.attr("setflags")("write"_a = false);
  return a;
}

py::object csc(const SparseMatrix& S, py::handle owner, bool writable) {
  // Eigen's compressed column storage is scipy's CSC: values, row indices (int32, the
  // StorageIndex) and the n + 1 column pointers.  copy=False: scipy keeps the arrays
  // (it checks their dtypes, which already are the ones it wants).
  const py::ssize_t nnz = S.nonZeros();
  py::array data = view1(S.valuePtr(), nnz, owner, writable);
  py::array indices = view1(S.innerIndexPtr(), nnz, owner, writable);
  py::array indptr = view1(S.outerIndexPtr(), S.outerSize() + 1, owner, writable);
  return py::module_::import("scipy.sparse")
      .attr("csc_matrix")(py::make_tuple(data, indices, indptr), "shape"_a = py::make_tuple(S.rows(), S.cols()),
                          "copy"_a = false);
}

}  // namespace

py::object csc_owned(SparseMatrix&& S) {
  S.makeCompressed();
  auto* held = new SparseMatrix(std::move(S));
  py::capsule owner(held, [](void* p) { delete static_cast<SparseMatrix*>(p); });
  return csc(*held, owner, true);
}

py::object csc_view(const SparseMatrix& S, py::handle owner) {
  if (!S.isCompressed()) return csc_owned(SparseMatrix(S));  // a copy, compressed
  return csc(S, owner, false);
}

SparseMatrix sparse_from(py::handle matrix) {
  const py::object csc = py::module_::import("scipy.sparse").attr("csc_matrix")(matrix);  // no copy if CSC
  const auto data = py::array_t<double, py::array::c_style | py::array::forcecast>(csc.attr("data"));
  const auto rows = py::array_t<long long, py::array::c_style | py::array::forcecast>(csc.attr("indices"));
  const auto start = py::array_t<long long, py::array::c_style | py::array::forcecast>(csc.attr("indptr"));
  const auto shape = csc.attr("shape").cast<std::pair<Eigen::Index, Eigen::Index>>();
  // Triplets (duplicates summed, rows sorted), whatever the order scipy keeps them in.
  std::vector<Eigen::Triplet<double>> entries;
  entries.reserve(static_cast<std::size_t>(data.size()));
  for (Eigen::Index j = 0; j < shape.second; ++j)
    for (long long k = start.at(j); k < start.at(j + 1); ++k)
      entries.emplace_back(static_cast<int>(rows.at(k)), static_cast<int>(j), data.at(k));
  SparseMatrix S(shape.first, shape.second);
  S.setFromTriplets(entries.begin(), entries.end());
  return S;
}

Element to_element(const py::object& element) {
  if (py::isinstance<py::str>(element)) return element_from_string(element.cast<std::string>());
  return element.cast<Element>();
}

Field to_field(const py::object& value, const std::string& name) {
  if (py::isinstance<py::str>(value)) return parse_expression(value.cast<std::string>(), name);
  if (PyNumber_Check(value.ptr()) && !PyCallable_Check(value.ptr())) {
    const double c = value.cast<double>();
    return Field([c](const Point&, double) { return c; });
  }
  if (!PyCallable_Check(value.ptr()))
    throw InputError(name, "expected a number, an expression (str) or a callable f(x, y, t) or f(x, y, z, t)");
  // The callable is kept (a reference) as long as the field: by the problem that holds it.
  py::function f = py::reinterpret_borrow<py::function>(value);
  // (a callable whose signature Python cannot tell, some builtins, is taken as f(x, y, t))
  int parameters = 3;
  try {
    parameters = static_cast<int>(py::len(py::module_::import("inspect").attr("signature")(f).attr("parameters")));
  } catch (const py::error_already_set&) {
  }
  if (parameters == 4)
    return Field([f](const Point& p, double t) { return f(p.x, p.y, p.z, t).cast<double>(); });
  // f(x, y, t) cannot see z: refused at the first point off the plane z = 0 (a 3D mesh)
  // rather than evaluated there as if z were 0.
  return Field([f, name](const Point& p, double t) {
    if (p.z != 0.0) throw InputError(name, "a callable f(x, y, t) cannot depend on z: on a 3D mesh give f(x, y, z, t)");
    return f(p.x, p.y, t).cast<double>();
  });
}

std::vector<Field> to_fields(const py::object& value, const std::string& name) {
  if (py::isinstance<py::list>(value) || py::isinstance<py::tuple>(value)) {
    std::vector<Field> out;
    for (const py::handle& v : value) out.push_back(to_field(py::reinterpret_borrow<py::object>(v), name));
    return out;
  }
  return {to_field(value, name)};
}

bool mentions_time(const py::object& value) {
  return py::isinstance<py::str>(value) && depends_on_time(value.cast<std::string>());
}

std::vector<int> part_indices(const Mesh& mesh, const py::object& parts) {
  std::vector<int> out;
  if (parts.is_none()) return out;
  auto add = [&](const py::handle& p) {
    if (py::isinstance<py::str>(p)) {
      const std::string name = p.cast<std::string>();
      if (name != "all") return out.push_back(mesh.part_index(name));
      for (std::size_t k = 0; k < mesh.part_names.size(); ++k) out.push_back(static_cast<int>(k));
      out.push_back(-1);  // the untagged boundary facets, as a scene's "all"
    } else {
      out.push_back(p.cast<int>());
    }
  };
  if (py::isinstance<py::str>(parts))
    add(parts);
  else
    for (const py::handle& p : parts) add(p);
  return out;
}

}  // namespace cdyn::python
