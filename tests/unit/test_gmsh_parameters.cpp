// test_gmsh_parameters.cpp — numbers given to a .geo before gmsh meshes it
// (read_mesh(path, parameters), meshing/cdyn/gmsh_mesh.hpp), what `gmsh -setnumber`
// does from the shell and what a scene's mesh.set passes.
//
// Checked: a smaller mesh size gives more vertices (about 4× for h/2 in 2D, by the
// area per vertex), the default of the .geo's DefineConstant is what no parameter
// gives, a parameterized read leaves nothing behind for the next read (gmsh's global
// state), a parameter used only in an Included file is found, and what cannot work is
// refused with InputError naming "setnumber.<name>": a .msh, a name the .geo never
// mentions, a name the .geo assigns itself (h = 0.5;), a non-identifier, a value that
// is not finite.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <limits>
#include <string>

#include "cdyn/base/error.hpp"
#include "cdyn/gmsh_mesh.hpp"

namespace fs = std::filesystem;
using cdyn::GeoParameters;
using cdyn::InputError;
using cdyn::read_mesh;

namespace {

std::string data_geo(const std::string& name) { return std::string(CDYN_SOURCE_DIR) + "/data/geo/" + name; }

fs::path scratch_dir() {
  const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
  const fs::path dir = fs::path(CDYN_BINARY_DIR) / "test_gmsh_parameters_tmp" /
                       (std::string(info->test_suite_name()) + "." + info->name());
  fs::remove_all(dir);
  fs::create_directories(dir);
  return dir;
}

std::string write_text(const fs::path& path, const std::string& text) {
  std::ofstream(path) << text;
  return path.string();
}

// The unit square with mesh size `size_expr` at its corners, physical surface "sq".
std::string square_geo(const std::string& header, const std::string& size_expr) {
  return header + "Point(1) = {0, 0, 0, " + size_expr + "}; Point(2) = {1, 0, 0, " + size_expr +
         "};\nPoint(3) = {1, 1, 0, " + size_expr + "}; Point(4) = {0, 1, 0, " + size_expr +
         "};\nLine(1) = {1, 2}; Line(2) = {2, 3}; Line(3) = {3, 4}; Line(4) = {4, 1};\n"
         "Curve Loop(1) = {1, 2, 3, 4}; Plane Surface(1) = {1};\nPhysical Surface(\"sq\") = {1};\n";
}

// The parameter an InputError of `f` names.
template <class F>
std::string refused_parameter(F&& f) {
  try {
    f();
  } catch (const InputError& e) {
    return e.parameter();
  }
  return "(accepted)";
}

}  // namespace

TEST(GmshParameters, SmallerMeshSizeGivesMoreVertices) {
  const std::string geo = data_geo("two_layer.geo");  // DefineConstant[h = {1.0, ...}]
  const int n_default = read_mesh(geo).n_vertices();
  const int n1 = read_mesh(geo, {{"h", 1.0}}).n_vertices();
  const int n2 = read_mesh(geo, {{"h", 2.0}}).n_vertices();
  const int n05 = read_mesh(geo, {{"h", 0.5}}).n_vertices();
  EXPECT_EQ(n1, n_default);  // the .geo's default is h = 1
  EXPECT_LT(n2, n1);
  EXPECT_LT(n1, n05);
  // In 2D the vertex count goes as 1/h²: about 4× per halving (measured 82, 275, 1001,
  // 3832 vertices for h = 2, 1, 0.5, 0.25: ratios 3.4, 3.6, 3.8, as the boundary
  // vertices grow as 1/h only).
  EXPECT_GT(static_cast<double>(n05) / n1, 3.0);
  EXPECT_LT(static_cast<double>(n05) / n1, 4.5);
  EXPECT_GT(static_cast<double>(n1) / n2, 3.0);
  // Regions and parts are those of the .geo whatever h.
  const cdyn::Mesh fine = read_mesh(geo, {{"h", 0.5}});
  EXPECT_EQ(fine.region_names, (std::vector<std::string>{"soft", "stiff"}));
  EXPECT_NEAR(fine.measure(), 200.0, 1e-10);
  // And the parameter of the disk, lc (a DefineConstant with a long ONELAB name).
  EXPECT_LT(read_mesh(data_geo("disk.geo")).n_vertices(), read_mesh(data_geo("disk.geo"), {{"lc", 1.25}}).n_vertices());
}

TEST(GmshParameters, NothingIsLeftForTheNextRead) {
  const std::string geo = data_geo("two_layer.geo");
  const int n_default = read_mesh(geo).n_vertices();
  read_mesh(geo, {{"h", 0.5}});
  EXPECT_EQ(read_mesh(geo).n_vertices(), n_default);
}

TEST(GmshParameters, ParameterOfAnIncludedFile) {
  const fs::path dir = scratch_dir();
  fs::create_directories(dir / "parts");
  write_text(dir / "parts" / "size.geo", "DefineConstant[ s = {0.5, Name \"Parameters/s\"} ];\n");
  const std::string geo = write_text(dir / "main.geo", square_geo("Include \"parts/size.geo\";\n", "s"));
  EXPECT_LT(read_mesh(geo).n_vertices(), read_mesh(geo, {{"s", 0.1}}).n_vertices());
}

TEST(GmshParameters, RefusedParameters) {
  const fs::path dir = scratch_dir();
  const std::string geo = data_geo("two_layer.geo");
  // a .msh is already meshed
  const std::string msh = (dir / "two_layer.msh").string();
  cdyn::write_msh(geo, msh, 4.1);
  EXPECT_EQ(refused_parameter([&] { read_mesh(msh, {{"h", 0.5}}); }), "setnumber.h");
  // a name the .geo never mentions (a typo would otherwise change nothing)
  EXPECT_EQ(refused_parameter([&] { read_mesh(geo, {{"lc", 0.5}}); }), "setnumber.lc");
  // not a variable name, given twice, not finite
  EXPECT_EQ(refused_parameter([&] { read_mesh(geo, {{"1h", 0.5}}); }), "setnumber.1h");
  EXPECT_EQ(refused_parameter([&] { read_mesh(geo, {{"h", 0.5}, {"h", 0.25}}); }), "setnumber.h");
  EXPECT_EQ(refused_parameter([&] { read_mesh(geo, {{"h", std::numeric_limits<double>::infinity()}}); }),
            "setnumber.h");
  // a plain assignment in the .geo overrides the value: refused, with the value it took
  const std::string assigned = write_text(dir / "assigned.geo", square_geo("h = 0.5;\n", "h"));
  try {
    read_mesh(assigned, {{"h", 0.1}});
    FAIL() << "a parameter the .geo assigns itself was accepted";
  } catch (const InputError& e) {
    EXPECT_EQ(e.parameter(), "setnumber.h");
    EXPECT_NE(e.message().find("DefineConstant"), std::string::npos) << e.message();
    EXPECT_NE(e.message().find("0.5"), std::string::npos) << e.message();
  }
  // the file still reads without parameters, and a good read follows the refusals
  EXPECT_GT(read_mesh(assigned).n_vertices(), 4);
  EXPECT_EQ(read_mesh(geo, {{"h", 2.0}}).region_names.size(), 2u);
}
