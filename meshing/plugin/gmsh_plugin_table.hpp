// gmsh_plugin_table.hpp — what the gmsh plugin (libcdyn_gmsh.so) gives the program that
// opens it (cdyn/gmsh_mesh.cpp): one table of functions, those of cdyn/gmsh_mesh.hpp.
//
// Why a plugin.  libgmsh brings 91 shared libraries (OpenCASCADE, FLTK, ...) whose
// loading and static constructors cost every process that links it 0.11 s at start
// (an empty program linked with -lgmsh, this machine), more than the whole of a small
// run of cdyn; only a .geo or .msh mesh needs it.  Opened on the first mesh read, gmsh
// costs only the runs that read one.
#pragma once

#include "cdyn/gmsh_mesh.hpp"

namespace cdyn {

struct GmshPluginTable {
  int version;  // kGmshPluginVersion of the plugin's build
  Mesh (*read_mesh)(const std::string& path, const GeoParameters& parameters);
  void (*write_msh)(const std::string& geo_or_msh, const std::string& out_path, double version,
                    const GeoParameters& parameters);
};

constexpr int kGmshPluginVersion = 1;

}  // namespace cdyn

// The plugin's one exported symbol.
extern "C" const cdyn::GmshPluginTable* cdyn_gmsh_plugin();
