// gmsh_fixtures.hpp — what the gmsh front-end tests share (test_gmsh_mesh.cpp,
// test_gmsh_mesh_3d.cpp): a scratch directory per test, small files written into it,
// the measure of boundary facets, and the check of a refused file.
#pragma once

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <string>

#include "cdyn/base/error.hpp"
#include "cdyn/gmsh_mesh.hpp"

namespace cdyn::testing {

// A fresh scratch directory per test (named after it): CTest may run the tests in parallel.
inline std::filesystem::path scratch_dir() {
  const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
  const std::filesystem::path dir = std::filesystem::path(CDYN_BINARY_DIR) / "test_gmsh_mesh_tmp" /
                                    (std::string(info->test_suite_name()) + "." + info->name());
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  return dir;
}

// The measure of a boundary facet: 0 for a point (1D), the length of an edge (2D), the
// area of a triangle (3D); and the sum over the facets of part `part` (−1: untagged).
inline double facet_measure(const Mesh& m, const BoundaryFacet& f) {
  if (m.dim == 1) return 0.0;
  const Point& a = m.vertices[f.vertices[0]];
  const Point& b = m.vertices[f.vertices[1]];
  if (m.dim == 2) return std::hypot(b.x - a.x, b.y - a.y);
  const Point& c = m.vertices[f.vertices[2]];
  const double u[3] = {b.x - a.x, b.y - a.y, b.z - a.z}, w[3] = {c.x - a.x, c.y - a.y, c.z - a.z};
  return 0.5 * std::hypot(u[1] * w[2] - u[2] * w[1], u[2] * w[0] - u[0] * w[2], u[0] * w[1] - u[1] * w[0]);
}

inline double part_measure(const Mesh& m, int part) {
  double s = 0.0;
  for (const auto& f : m.boundary)
    if (f.part == part) s += facet_measure(m, f);
  return s;
}

inline std::string write_text(const std::filesystem::path& path, const std::string& text) {
  std::ofstream(path) << text;
  return path.string();
}

// Expects read_mesh(path) to throw InputError with a one-line message naming `path`
// and containing `expected` (if non-empty).
inline void expect_input_error(const std::string& path, const std::string& expected = "") {
  try {
    (void)cdyn::read_mesh(path);
    ADD_FAILURE() << path << ": no InputError thrown";
  } catch (const cdyn::InputError& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find(path), std::string::npos) << what;
    EXPECT_EQ(what.find('\n'), std::string::npos) << what;
    if (!expected.empty()) {
      EXPECT_NE(what.find(expected), std::string::npos) << what;
    }
    std::cout << "  [message] " << what << "\n";
  }
}

}  // namespace cdyn::testing
