// gmsh_mesh.hpp — the gmsh front end: a .geo or .msh file becomes a cdyn::Mesh.
//
// A .geo file is meshed through the gmsh C++ API; a .msh file (format 2.2 or 4.1,
// what gmsh and FreeFEM exchange) is read through the same API.  Physical groups
// carry the names the rest of cdyn uses:
//   - groups of the top dimension (physical volumes in 3D, surfaces in 2D, curves in
//     1D) select the cells and become regions (Mesh::cell_region, Mesh::region_names);
//   - groups of one dimension lower (surfaces in 3D, curves in 2D, points in 1D) become
//     the named boundary parts (Mesh::part_names), e.g. "dirichlet", "contact".
// Only first-order simplices are accepted: 4-node tetrahedra (3D), 3-node triangles
// (2D, in the plane z = 0) and 2-node lines (1D, along the x axis).  docs/meshing.md
// has the details.
//
// Parameters.  A .geo is usually written with its mesh size (and other numbers) as
// parameters, DefineConstant[h = {0.1, Name "..."}], which `gmsh -setnumber h 0.05`
// overrides from outside.  read_mesh takes such values, so that a refinement study needs
// no hand-written .msh: each (name, value) is defined before the .geo is parsed, and
// DefineConstant keeps a value already defined.  (gmsh 4.8's API has no parser::
// setNumber, and its -setnumber argument to gmsh::initialize outlives the session, so
// the values go through a small .geo of definitions read just before the file.)  Refused
// (InputError whose parameter() is "setnumber.<name>"): parameters with a .msh, a name
// that is not an identifier or that the .geo (and the files it Includes) never
// mentions, a value that is not finite, and a name the .geo assigns itself (h = 0.1;
// after the definitions, which would silently ignore the value given).
//
// Every failure (missing file, syntax error, meshing error, unsupported element,
// empty mesh) is thrown as cdyn::InputError with a one-line message that starts with
// the file name.  gmsh keeps global state, so these functions must not be called
// from two threads at once.
#pragma once

#include <string>
#include <utility>
#include <vector>

#include "cdyn/mesh/mesh.hpp"

namespace cdyn {

// (name, value) pairs given to a .geo as `gmsh -setnumber name value` would.
using GeoParameters = std::vector<std::pair<std::string, double>>;

// Reads `path` (.geo: meshed in its own dimension; .msh: read as is) into a Mesh:
// vertices numbered 0..nv-1 in increasing gmsh node tag order (only nodes used by a
// cell), triangles counter-clockwise, tetrahedra positively oriented, boundary facets
// (triangles in 3D) tagged with their physical group (untagged boundary facets get
// part -1), checked with Mesh::check.
// `parameters` (.geo only): see above.
Mesh read_mesh(const std::string& path, const GeoParameters& parameters = {});

// Meshes a .geo (or opens a .msh) and writes the mesh to `out_path` (must end in
// .msh) in msh format `version`, 2.2 (what FreeFEM's gmshload reads) or 4.1.  The
// mesh is validated as read_mesh does before it is written, so that what is written
// can be read back.  gmsh writes only the elements of physical groups, so a model that
// has physical groups but none of its own dimension gets one, named "domain", holding
// all its cells (read back, it is a region).
void write_msh(const std::string& geo_or_msh, const std::string& out_path, double version,
               const GeoParameters& parameters = {});

// Both are done by the plugin libcdyn_gmsh.so (gmsh's libraries are loaded only by a run
// that reads a mesh), opened on the first call from, in this order: the file named by
// the environment variable CDYN_GMSH_PLUGIN; the paths given to add_gmsh_plugin_path; the
// program's PREFIX/lib/cdyn/ (an installed cdyn); the build tree; the configured
// install prefix.  A program built against an installed cdyn (find_package(cdyn)) gets
// its plugin's path from the CMake package, as CDYN_GMSH_PLUGIN_PATH, added by the
// inline variable below.  Not found: InputError naming the plugin.
void add_gmsh_plugin_path(const std::string& path);
// The plugin file opened ("" before the first read_mesh or write_msh).
std::string gmsh_plugin_file();
#ifdef CDYN_GMSH_PLUGIN_PATH
inline const bool gmsh_plugin_path_added = (add_gmsh_plugin_path(CDYN_GMSH_PLUGIN_PATH), true);
#endif

}  // namespace cdyn
