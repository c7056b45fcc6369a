// cmd_mesh.cpp — `cdyn mesh FILE.geo|FILE.msh`: what cdyn makes of a gmsh file.
//
// Prints the dimension, the vertex / cell / boundary-facet counts, the measure of the
// domain and h_max, then each physical group cdyn uses with its dimension, name and
// number of cells or facets.  Everything is counted on the cdyn::Mesh itself (not on
// the gmsh model), so the summary shows exactly what a scene using this file gets.
// --set name=value gives a parameter of a .geo, as a scene's mesh.set.name does.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include "cdyn/base/error.hpp"
#include "cdyn/gmsh_mesh.hpp"
#include "cdyn/mesh/mesh.hpp"
#include "commands.hpp"

namespace cdyn::app {

namespace {

struct GroupRow {
  int dim;
  std::string name;
  int count;
};

}  // namespace

int cmd_mesh(const std::string& file, const std::vector<std::string>& sets) {
  GeoParameters parameters;
  for (const std::string& a : sets) {
    const auto eq = a.find('=');
    double value = NAN;
    std::size_t used = 0;
    try {
      if (eq != std::string::npos) value = std::stod(a.substr(eq + 1), &used);
    } catch (const std::exception&) {
    }
    if (eq == std::string::npos || eq == 0 || used == 0 || used != a.size() - eq - 1)
      throw InputError("--set " + a + ": expected name=number, e.g. --set h=0.5");
    parameters.emplace_back(a.substr(0, eq), value);
  }
  const Mesh mesh = [&] {
    try {
      return read_mesh(file, parameters);  // throws InputError on bad input
    } catch (const InputError& e) {        // a parameter's error names its --set
      if (e.parameter().rfind("setnumber.", 0) != 0) throw;
      throw InputError("--set " + e.parameter().substr(10) + ": " + e.message());
    }
  }();

  // "1 triangle", "2 triangles", "1 tetrahedron", "2 tetrahedra"
  const int d = mesh.dim;
  auto cells_word = [d](std::size_t n) {
    if (d == 3) return std::string(n == 1 ? "tetrahedron" : "tetrahedra");
    return std::string(d == 2 ? "triangle" : "interval") + (n == 1 ? "" : "s");
  };
  auto facets_word = [d](std::size_t n) {
    return std::string(d == 3 ? "triangle" : d == 2 ? "edge" : "point") + (n == 1 ? "" : "s");
  };

  // Cells per region (physical group of the top dimension) and facets per boundary
  // part (physical group of dimension dim - 1); part -1 is the untagged boundary.
  std::vector<int> cells_in(mesh.region_names.size(), 0);
  for (int r : mesh.cell_region)
    if (r >= 0) ++cells_in[r];
  std::vector<int> facets_in(mesh.part_names.size(), 0);
  int untagged = 0;
  for (const auto& f : mesh.boundary) {
    if (f.part >= 0)
      ++facets_in[f.part];
    else
      ++untagged;
  }

  std::vector<GroupRow> rows;
  for (std::size_t r = 0; r < mesh.region_names.size(); ++r)
    rows.push_back({mesh.dim, mesh.region_names[r], cells_in[r]});
  for (std::size_t p = 0; p < mesh.part_names.size(); ++p)
    rows.push_back({mesh.dim - 1, mesh.part_names[p], facets_in[p]});

  std::printf("%s: %dD mesh\n", file.c_str(), mesh.dim);
  std::printf("  vertices         %d\n", mesh.n_vertices());
  std::printf("  cells            %d %s\n", mesh.n_cells(), cells_word(mesh.n_cells()).c_str());
  std::printf("  boundary facets  %zu %s (%d in no physical group)\n", mesh.boundary.size(),
              facets_word(mesh.boundary.size()).c_str(), untagged);
  std::printf("  %-16s %.12g\n", d == 3 ? "volume" : d == 2 ? "area" : "length", mesh.measure());
  std::printf("  h_max            %.6g\n", mesh.h_max());

  if (rows.empty()) {
    std::printf("physical groups: none\n");
    return 0;
  }
  std::size_t width = 4;
  for (const auto& row : rows) width = std::max(width, row.name.size());
  std::printf("physical groups\n");
  std::printf("  dim  %-*s  count\n", static_cast<int>(width), "name");
  for (const auto& row : rows)
    std::printf("  %-3d  %-*s  %d %s\n", row.dim, static_cast<int>(width), row.name.c_str(),
                row.count, (row.dim == mesh.dim ? cells_word(row.count) : facets_word(row.count)).c_str());
  return 0;
}

}  // namespace cdyn::app
