// plugin.hpp — opening one of cdyn's plugins: a shared library whose one exported
// function returns its table of functions (the PETSc back end, qp/petsc/backend.cpp; the
// gmsh reader, meshing/cdyn/gmsh_mesh.cpp).  The first candidate file that opens, exports
// the function and gives a table of this build's version is taken.
#pragma once

#include <filesystem>
#include <functional>
#include <string>
#include <vector>

namespace cdyn {

// PREFIX/lib/cdyn/`file` for a program installed as PREFIX/bin/… (empty if the
// program's path cannot be read).
std::filesystem::path beside_installed_program(const std::string& file);

// The table the exported function `symbol` of the first candidate returns, if that
// candidate opens (dlopen `flags`) and `matches` the table; else null.  `tried` gets why
// each existing candidate was refused, `opened` the file taken.
const void* open_plugin(const std::vector<std::filesystem::path>& candidates, const char* symbol, int flags,
                        const std::function<bool(const void*)>& matches, std::string& tried,
                        std::filesystem::path* opened = nullptr);

// The same for a table type with a `version` member, which must equal `version`.
template <class Table>
const Table* open_plugin(const std::vector<std::filesystem::path>& candidates, const char* symbol, int version,
                         int flags, std::string& tried, std::filesystem::path* opened = nullptr) {
  const auto matches = [version](const void* table) { return static_cast<const Table*>(table)->version == version; };
  return static_cast<const Table*>(open_plugin(candidates, symbol, flags, matches, tried, opened));
}

}  // namespace cdyn
