// gmsh_mesh.cpp — read_mesh and write_msh by the gmsh plugin libcdyn_gmsh.so, opened on
// the first call (plugin/gmsh_plugin_table.hpp says why; the reading itself is
// plugin/gmsh_plugin.cpp).
#include "cdyn/gmsh_mesh.hpp"

#include <dlfcn.h>

#include <cstdlib>
#include <filesystem>
#include <string>
#include <vector>

#include "cdyn/base/error.hpp"
#include "cdyn/base/plugin.hpp"
#include "gmsh_plugin_table.hpp"

namespace cdyn {

namespace {

std::vector<std::filesystem::path>& added_paths() {
  static std::vector<std::filesystem::path> paths;
  return paths;
}

// Where the plugin may be, in the order tried (gmsh_mesh.hpp).
std::vector<std::filesystem::path> plugin_candidates() {
  std::vector<std::filesystem::path> out;
  if (const char* file = std::getenv("CDYN_GMSH_PLUGIN")) out.emplace_back(file);
  out.insert(out.end(), added_paths().begin(), added_paths().end());
  out.push_back(beside_installed_program("libcdyn_gmsh.so"));
  out.emplace_back(CDYN_GMSH_PLUGIN_BUILD);
  out.emplace_back(CDYN_GMSH_PLUGIN_INSTALLED);
  return out;
}

const GmshPluginTable* opened = nullptr;
std::filesystem::path opened_file;

const GmshPluginTable& plugin() {
  if (opened) return *opened;
  std::string tried;
  opened = open_plugin<GmshPluginTable>(plugin_candidates(), "cdyn_gmsh_plugin", kGmshPluginVersion,
                                        RTLD_NOW | RTLD_LOCAL, tried, &opened_file);
  if (opened) return *opened;
  throw InputError("mesh.file", "the gmsh plugin libcdyn_gmsh.so, which reads .geo and .msh files, was not found or "
                                "not opened (" +
                                    (tried.empty() ? std::string("set CDYN_GMSH_PLUGIN to its path") : tried) + ")");
}

}  // namespace

void add_gmsh_plugin_path(const std::string& path) { added_paths().emplace_back(path); }

std::string gmsh_plugin_file() { return opened_file.string(); }

Mesh read_mesh(const std::string& path, const GeoParameters& parameters) {
  return plugin().read_mesh(path, parameters);
}

void write_msh(const std::string& geo_or_msh, const std::string& out_path, double version,
               const GeoParameters& parameters) {
  plugin().write_msh(geo_or_msh, out_path, version, parameters);
}

}  // namespace cdyn
