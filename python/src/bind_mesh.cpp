// bind_mesh.cpp — the mesh stage in Python: cdyn.Mesh (geometry and topology only, as
// mesh/mesh.hpp), the built-in meshes of the scene keys mesh.kind = interval and
// unit_square, and gmsh files (.geo meshed on the fly, .msh read) through cdyn::meshing.
//
// A mesh's arrays are read-only numpy views of its own storage (no copy), which keep the
// mesh alive: vertices (N × 3, x y z), cells (n_cells × (dim + 1) vertex indices),
// boundary facets (dim vertex indices each) and the part of each facet.
#include <cstddef>
#include <map>

#include "cdyn/gmsh_mesh.hpp"
#include "cdyn/mesh/point_location.hpp"
#include "cdyn_python.hpp"

namespace cdyn::python {

void bind_mesh(py::module_& m) {
  static_assert(sizeof(Point) == 3 * sizeof(double), "Point is x, y, z: a row of an N × 3 array");
  py::class_<Mesh>(m, "Mesh", "A simplicial mesh: vertices, cells, boundary facets tagged with their part")
      .def_readonly("dim", &Mesh::dim, "1 (intervals), 2 (triangles) or 3 (tetrahedra)")
      .def_property_readonly("n_vertices", &Mesh::n_vertices)
      .def_property_readonly("n_cells", &Mesh::n_cells)
      .def_property_readonly(
          "vertices",
          [](py::object self) {
            const Mesh& mesh = self.cast<const Mesh&>();
            return struct_view(&mesh.vertices.data()->x, mesh.n_vertices(), 3, sizeof(Point), self);
          },
          "N × 3 coordinates (a view)")
      .def_property_readonly(
          "cells",
          [](py::object self) {
            const Mesh& mesh = self.cast<const Mesh&>();
            return struct_view(mesh.cells.data()->data(), mesh.n_cells(), mesh.dim + 1, sizeof(Cell), self);
          },
          "vertex indices of each cell, counter-clockwise in 2D (a view)")
      .def_property_readonly(
          "facets",
          [](py::object self) {
            const Mesh& mesh = self.cast<const Mesh&>();
            return struct_view(mesh.boundary.data()->vertices.data(), static_cast<py::ssize_t>(mesh.boundary.size()),
                               mesh.dim, sizeof(BoundaryFacet), self);
          },
          "vertex indices of each boundary facet (a view)")
      .def_property_readonly(
          "facet_parts",
          [](py::object self) {
            const Mesh& mesh = self.cast<const Mesh&>();
            return struct_view(&mesh.boundary.data()->part, static_cast<py::ssize_t>(mesh.boundary.size()), 1,
                               sizeof(BoundaryFacet), self)
                .attr("reshape")(-1);
          },
          "the part of each boundary facet, an index into part_names or -1 (a view)")
      .def_readonly("part_names", &Mesh::part_names)
      .def_readonly("region_names", &Mesh::region_names)
      .def_readonly("cell_region", &Mesh::cell_region)
      .def("part_index", &Mesh::part_index, "name"_a)
      .def(
          "part_vertices",
          [](const Mesh& mesh, const py::object& parts) { return mesh.part_vertices(part_indices(mesh, parts)); },
          "parts"_a, "the vertices on the given parts (names or indices), sorted")
      .def("cell_measure", &Mesh::cell_measure, "c"_a)
      .def("measure", &Mesh::measure, "|Ω|, the sum of the cell measures")
      .def("h_max", &Mesh::h_max, "the largest cell diameter h")
      .def(
          "locate",
          [](const Mesh& mesh, double x, double y, double z) {
            const CellPoint c = locate(mesh, {x, y, z});
            return py::make_tuple(c.cell, c.xi);
          },
          "x"_a, "y"_a = 0.0, "z"_a = 0.0, "(cell, reference coordinates) of a point; cell −1 outside")
      .def("__repr__", [](const Mesh& mesh) {
        return "<cdyn.Mesh " + std::to_string(mesh.dim) + "D, " + std::to_string(mesh.n_vertices()) + " vertices, " +
               std::to_string(mesh.n_cells()) + " cells>";
      });

  m.def("unit_square_mesh", &unit_square_mesh, "n"_a, "lx"_a = 1.0, "ly"_a = 1.0,
        "n × n squares, each cut along its lower-left to upper-right diagonal (FreeFEM's square(n, n)); parts "
        "bottom, right, top, left");
  m.def("interval_mesh", &interval_mesh, "n"_a, "length"_a = 1.0, "[0, length] in n intervals; parts left, right");
  m.def(
      "read_mesh",
      [](const std::string& path, const std::map<std::string, double>& set) {
        return read_mesh(path, GeoParameters(set.begin(), set.end()));
      },
      "path"_a, "set"_a = std::map<std::string, double>{},
      "a gmsh .geo (meshed now, with the parameters `set` as gmsh -setnumber) or .msh file; physical groups become "
      "parts and regions");
}

}  // namespace cdyn::python
