// gmsh_plugin.cpp — .geo and .msh files to cdyn::Mesh through the gmsh C++ API (4.8):
// the plugin libcdyn_gmsh.so, opened by cdyn/gmsh_mesh.cpp on the first mesh read
// (gmsh_plugin_table.hpp says why a plugin).
//
// How gmsh 4.8 reports trouble, found by experiment, and why the code is written so:
//  - With the API's default General.AbortOnError = 2, a syntax error in a .geo or
//    .msh throws a std::string (not a std::exception) out of gmsh's parser and leaves
//    the parser's global state broken: every later gmsh::open in the same process
//    then fails, even after finalize() and initialize().  We therefore set
//    AbortOnError = 0: gmsh logs the error, recovers, and carries on; we read its
//    logger after each call and turn the first "Error: " line into an InputError.
//  - gmsh::open on a missing file neither throws nor logs an error (the model is
//    just empty), so the file is checked before gmsh sees it.
//  - General.Terminal = 0 keeps gmsh from printing: its messages go to the logger only,
//    and the user sees the one line of our InputError.
//  - The ONELAB database outlives finalize(): a DefineConstant[h = ...] read from one
//    .geo would silently give its value to the same parameter name in the next .geo
//    opened by the process.  Each session therefore starts by clearing it.
//  - `-setnumber h 0.05` passed to gmsh::initialize does reach DefineConstant, but it
//    is kept in a process-wide table that finalize() does not clear: every later .geo
//    of the process would get h = 0.05.  And 4.8 has no gmsh::parser::setNumber.  So
//    parameters are defined by a .geo of definitions that gmsh::open reads first (open
//    starts a fresh model and a fresh table of variables, which also makes every
//    session independent of the previous ones) before the file is merged into it.  A
//    plain assignment h = 0.1; in the file overrides such a definition (gmsh -setnumber
//    behaves the same): the value each parameter has after the file is read back
//    through ONELAB (SetNumber) and compared.
#include <gmsh.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cctype>
#include <cerrno>
#include <cstdio>
#include <cstdlib>
#include <cmath>
#include <cstddef>
#include <filesystem>
#include <fstream>
#include <regex>
#include <set>
#include <sstream>
#include <unordered_map>
#include <utility>
#include <vector>

#include "cdyn/base/error.hpp"
#include "gmsh_plugin_table.hpp"

namespace cdyn {
namespace {

namespace fs = std::filesystem;

// The message of one gmsh log line, made fit for a one-line InputError that already
// starts with the file name: drop the "Error: " level, drop gmsh's own "'file', "
// prefix, and turn any line break into a space.
std::string clean_gmsh_message(std::string msg, const std::string& file) {
  const std::string level = "Error: ";
  if (msg.compare(0, level.size(), level) == 0) msg.erase(0, level.size());
  const std::string name = fs::path(file).filename().string();
  if (!msg.empty() && msg[0] == '\'') {
    const auto close = msg.find("', ");
    if (close != std::string::npos && msg.substr(0, close).ends_with(name))
      msg.erase(0, close + 3);
  }
  for (char& c : msg)
    if (c == '\n' || c == '\r') c = ' ';
  return msg;
}

// One gmsh session per read or write: initialize() on construction, finalize() on
// destruction, so that every way out (including an exception) leaves gmsh clean for
// the next call.  gmsh is global state: one session at a time.
class GmshSession {
 public:
  GmshSession() {
    gmsh::initialize(0, nullptr, /*readConfigFiles=*/false);
    gmsh::option::setNumber("General.Terminal", 0);
    gmsh::option::setNumber("General.AbortOnError", 0);
    gmsh::logger::start();
    gmsh::onelab::clear();
  }
  ~GmshSession() {
    try {
      gmsh::logger::stop();
      gmsh::finalize();
    } catch (...) {  // a destructor must not throw; there is nothing left to clean
    }
  }
  GmshSession(const GmshSession&) = delete;
  GmshSession& operator=(const GmshSession&) = delete;

  // Runs one gmsh call `f`.  Whatever it throws or logs as an error becomes
  // InputError("<file>: <doing>: <gmsh's first error>").
  template <class F>
  void call(const std::string& file, const std::string& doing, F&& f) {
    std::string failure;
    try {
      f();
    } catch (const std::string& s) {  // gmsh 4.8 throws plain strings
      failure = s;
    } catch (const std::exception& e) {
      failure = e.what();
    } catch (...) {
      failure = "unknown gmsh failure";
    }
    std::vector<std::string> log;
    gmsh::logger::get(log);
    int more = 0;  // errors logged besides the one reported
    for (std::size_t i = seen_; i < log.size(); ++i) {
      if (log[i].rfind("Error", 0) != 0) continue;
      if (failure.empty())
        failure = log[i];  // the first error is the cause; later ones are consequences
      else
        ++more;
    }
    seen_ = log.size();
    if (failure.empty()) return;
    std::string msg = file + ": " + doing + ": " + clean_gmsh_message(failure, file);
    if (more > 0) msg += " (and " + std::to_string(more) + " more gmsh errors)";
    throw InputError(msg);
  }

 private:
  std::size_t seen_ = 0;  // log lines already examined
};

std::string lowercase(std::string s) {
  for (char& c : s) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return s;
}

bool is_geo(const std::string& path) { return lowercase(fs::path(path).extension().string()) == ".geo"; }
bool is_msh(const std::string& path) { return lowercase(fs::path(path).extension().string()) == ".msh"; }

// gmsh 4.8's .msh reader trusts its input: some malformed files (found by fuzzing,
// tests/robustness/regressions/mesh/) make it dereference a null pointer instead of
// reporting an error.  So a .msh is first opened by a forked child process: if the
// child does not come back cleanly (killed by a signal, or stopped by a sanitizer's
// report), the file is refused with one line and this process, whose gmsh state the
// child could not touch, never reads it.  The cost is one extra read of the file.
// (.geo files are gmsh's own language, parsed with error reporting: not probed.)
void refuse_if_reader_crashes(const std::string& path) {
  std::fflush(nullptr);  // the child must not write this process's buffered output again
  const pid_t child = fork();
  if (child < 0) return;  // no process to probe with: read it as before
  if (child == 0) {
    try {
      gmsh::open(path);
    } catch (...) {  // an error gmsh reports: the parent's read reports it properly
    }
    _exit(0);
  }
  int status = 0;
  while (waitpid(child, &status, 0) < 0)
    if (errno != EINTR) return;
  if (WIFEXITED(status) && WEXITSTATUS(status) == 0) return;
  throw InputError(path + ": invalid .msh file: gmsh's reader crashed on it (" +
                   (WIFSIGNALED(status) ? "signal " + std::to_string(WTERMSIG(status))
                                        : "exit status " + std::to_string(WEXITSTATUS(status))) +
                   ")");
}

// The text of a .geo and of the files it Includes (recursively, relative to the
// including file's directory as gmsh resolves them; unreadable ones are skipped: gmsh
// reports them when it parses).
std::string geo_text_with_includes(const fs::path& file, std::set<fs::path>& seen) {
  std::error_code ec;
  const fs::path canonical = fs::weakly_canonical(file, ec);
  if (!seen.insert(ec ? file : canonical).second) return "";
  std::ifstream in(file);
  std::stringstream buffer;
  buffer << in.rdbuf();
  std::string text = buffer.str();
  static const std::regex include(R"re(Include\s*"([^"]+)")re");
  std::string all = text;
  for (std::sregex_iterator it(text.begin(), text.end(), include), end; it != end; ++it) {
    const fs::path inc = (*it)[1].str();
    all += "\n" + geo_text_with_includes(inc.is_absolute() ? inc : file.parent_path() / inc, seen);
  }
  return all;
}

bool mentions_word(const std::string& text, const std::string& word) {
  auto is_ident = [](char c) { return std::isalnum(static_cast<unsigned char>(c)) || c == '_'; };
  for (std::size_t at = text.find(word); at != std::string::npos; at = text.find(word, at + 1))
    if ((at == 0 || !is_ident(text[at - 1])) && (at + word.size() == text.size() || !is_ident(text[at + word.size()])))
      return true;
  return false;
}

// A private temporary directory, removed with everything in it on destruction.
class TemporaryDirectory {
 public:
  TemporaryDirectory() {
    std::string pattern = (fs::temp_directory_path() / "cdyn-geo-XXXXXX").string();
    if (!mkdtemp(pattern.data())) throw InputError("cannot create a temporary directory for the .geo parameters");
    path_ = pattern;
  }
  ~TemporaryDirectory() {
    std::error_code ec;
    fs::remove_all(path_, ec);
  }
  TemporaryDirectory(const TemporaryDirectory&) = delete;
  TemporaryDirectory& operator=(const TemporaryDirectory&) = delete;
  const fs::path& path() const { return path_; }

 private:
  fs::path path_;
};

std::string exact_number(double v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.17g", v);
  return buf;
}

// The checks on parameters that need no gmsh (see gmsh_mesh.hpp).
void check_parameters(const std::string& path, const GeoParameters& parameters) {
  static const std::regex identifier("[A-Za-z_][A-Za-z0-9_]*");
  std::set<fs::path> seen;
  const std::string text = geo_text_with_includes(path, seen);
  std::set<std::string> names;
  for (const auto& [name, value] : parameters) {
    const std::string key = "setnumber." + name;
    if (!std::regex_match(name, identifier))
      throw InputError(key, path + ": '" + name + "' is not a .geo variable name");
    if (!names.insert(name).second) throw InputError(key, path + ": given twice");
    if (!std::isfinite(value)) throw InputError(key, path + ": the value must be a finite number");
    if (!mentions_word(text, name))
      throw InputError(key, path + ": the .geo (and the files it includes) never mentions '" + name +
                                "', so the value would change nothing");
  }
}

// Opens `path` in the session and, for a .geo, meshes it in its own dimension.
// Returns that dimension (1, 2 or 3).
int load(GmshSession& session, const std::string& path, const GeoParameters& parameters) {
  if (!is_geo(path) && !is_msh(path))
    throw InputError(path + ": unknown mesh file type '" + fs::path(path).extension().string() +
                     "' (expected .geo or .msh)");
  std::error_code ec;
  if (!fs::exists(path, ec)) throw InputError(path + ": no such file");
  if (!fs::is_regular_file(path, ec)) throw InputError(path + ": not a regular file");
  if (!std::ifstream(path)) throw InputError(path + ": cannot be opened for reading");

  const bool geo = is_geo(path);
  if (!geo && !parameters.empty())
    throw InputError("setnumber." + parameters.front().first,
                     path + ": parameters need a .geo file (a .msh is already meshed)");
  if (!geo) refuse_if_reader_crashes(path);
  if (parameters.empty()) {
    session.call(path, geo ? "invalid .geo file" : "invalid .msh file", [&] { gmsh::open(path); });
  } else {
    check_parameters(path, parameters);
    // definitions.geo (name = value; ...), then the file, then readback.geo, which puts
    // the value each name has after the file into ONELAB for the comparison below.
    const TemporaryDirectory tmp;
    const fs::path definitions = tmp.path() / "definitions.geo", readback = tmp.path() / "readback.geo";
    {
      std::ofstream d(definitions), r(readback);
      for (const auto& [name, value] : parameters) {
        d << name << " = " << exact_number(value) << ";\n";
        r << "SetNumber(\"cdyn/setnumber/" << name << "\", " << name << ");\n";
      }
      if (!d || !r) throw InputError(path + ": cannot write the .geo parameters to " + tmp.path().string());
    }
    session.call(path, "invalid .geo file", [&] {
      gmsh::open(definitions.string());
      gmsh::merge(path);
    });
    session.call(path, "reading the parameters back", [&] { gmsh::merge(readback.string()); });
    for (const auto& [name, value] : parameters) {
      std::vector<double> now;
      gmsh::onelab::getNumber("cdyn/setnumber/" + name, now);
      if (now.size() != 1 || now[0] != value)
        throw InputError("setnumber." + name,
                         path + ": the .geo assigns '" + name + "' itself (" + name + " = " +
                             (now.empty() ? std::string("?") : exact_number(now[0])) +
                             " after reading it), so the value given is ignored; declare it with DefineConstant[" +
                             name + " = ...]");
    }
  }

  const int dim = gmsh::model::getDimension();
  if (dim < 1)
    throw InputError(path + (geo ? ": the geometry has no curve, surface or volume to mesh"
                                 : ": the file holds no mesh elements"));
  if (geo) session.call(path, "meshing failed", [&] { gmsh::model::mesh::generate(dim); });
  return dim;
}

// The name of a physical group, or "group<tag>" when the file gives it none.
std::string group_name(int dim, int tag) {
  std::string name;
  gmsh::model::getPhysicalName(dim, tag, name);
  return name.empty() ? "group" + std::to_string(tag) : name;
}

// Index of `name` in `names`, appended if new: two physical groups with the same name
// (possible in a .msh) are one part.
int name_index(std::vector<std::string>& names, const std::string& name) {
  const auto it = std::find(names.begin(), names.end(), name);
  if (it != names.end()) return static_cast<int>(it - names.begin());
  names.push_back(name);
  return static_cast<int>(names.size()) - 1;
}

// The node tags of the elements of dimension `dim` on model entity `entity`, dim + 1
// per element.  Only first-order simplices are accepted: cdyn's spaces are built on
// straight tetrahedra, triangles and intervals, so a 6-node triangle, a quadrangle or
// a hexahedron is refused here rather than misread later.
std::vector<std::size_t> simplex_nodes(const std::string& path, int dim, int entity) {
  std::vector<int> types;
  std::vector<std::vector<std::size_t>> element_tags, node_tags;
  gmsh::model::mesh::getElements(types, element_tags, node_tags, dim, entity);
  std::vector<std::size_t> nodes;
  for (std::size_t b = 0; b < types.size(); ++b) {
    std::string name;
    int element_dim = 0, order = 0, n_nodes = 0, n_primary = 0;
    std::vector<double> local_coords;
    gmsh::model::mesh::getElementProperties(types[b], name, element_dim, order, n_nodes,
                                            local_coords, n_primary);
    if (order > 1)
      throw InputError(path + ": '" + name + "' elements are of order " + std::to_string(order) +
                       "; cdyn reads first-order elements only (Mesh.ElementOrder = 1)");
    if (n_nodes != dim + 1)
      throw InputError(path + ": '" + name + "' elements are not supported; cdyn reads " +
                       (dim == 3   ? "4-node tetrahedra"
                        : dim == 2 ? "3-node triangles"
                        : dim == 1 ? "2-node lines"
                                   : "points") +
                       " only");
    nodes.insert(nodes.end(), node_tags[b].begin(), node_tags[b].end());
  }
  return nodes;
}

// The mesh of the model now open in the session, of dimension `dim`.
Mesh extract(const std::string& path, int dim) {
  Mesh mesh;
  mesh.dim = dim;
  const int nv = dim + 1;  // vertices per cell

  // 1. Cells.  Physical groups of the top dimension, if any, say which entities are
  //    the domain and name its regions; without them every entity of that dimension
  //    is.  An entity in two groups gives its cells once (to the first group).
  std::vector<std::size_t> cell_nodes;  // nv gmsh node tags per cell
  std::vector<int> cell_region;
  std::set<int> taken;
  auto take = [&](int entity, int region) {
    if (!taken.insert(entity).second) return;
    const auto nodes = simplex_nodes(path, dim, entity);
    cell_nodes.insert(cell_nodes.end(), nodes.begin(), nodes.end());
    cell_region.insert(cell_region.end(), nodes.size() / nv, region);
  };
  gmsh::vectorpair regions;
  gmsh::model::getPhysicalGroups(regions, dim);
  if (!regions.empty()) {
    for (const auto& [d, tag] : regions) {
      const int region = name_index(mesh.region_names, group_name(d, tag));
      std::vector<int> entities;
      gmsh::model::getEntitiesForPhysicalGroup(d, tag, entities);
      for (int e : entities) take(e, region);
    }
  } else {
    gmsh::vectorpair entities;
    gmsh::model::getEntities(entities, dim);
    for (const auto& [d, e] : entities) take(e, -1);
  }
  if (cell_nodes.empty())
    throw InputError(path + ": the mesh has no " +
                     (dim == 3 ? "tetrahedra" : dim == 2 ? "triangles" : "line elements"));

  // 2. Vertices: the nodes used by cells, numbered 0..nv-1 in increasing tag order
  //    (nodes of unused points, such as a circle's centre, are left out).
  std::vector<std::size_t> used = cell_nodes;
  std::sort(used.begin(), used.end());
  used.erase(std::unique(used.begin(), used.end()), used.end());
  std::unordered_map<std::size_t, int> vertex_of_node;
  for (std::size_t i = 0; i < used.size(); ++i) vertex_of_node[used[i]] = static_cast<int>(i);

  std::vector<std::size_t> node_tags;
  std::vector<double> xyz, parametric;
  gmsh::model::mesh::getNodes(node_tags, xyz, parametric, -1, -1, /*includeBoundary=*/true,
                              /*returnParametricCoord=*/false);
  mesh.vertices.resize(used.size());
  std::vector<bool> found(used.size(), false);
  double extent = 1.0, off_plane = 0.0;  // largest |coordinate|, largest out-of-plane one
  for (std::size_t k = 0; k < node_tags.size(); ++k) {
    const auto it = vertex_of_node.find(node_tags[k]);
    if (it == vertex_of_node.end()) continue;
    const double x = xyz[3 * k], y = xyz[3 * k + 1], z = xyz[3 * k + 2];
    // A 2D mesh must lie in the plane z = 0, a 1D mesh on the x axis: cdyn keeps
    // (x, y) in 2D and x in 1D, and silently dropping a coordinate would distort it.
    extent = std::max({extent, std::abs(x), std::abs(y), std::abs(z)});
    if (dim < 3) off_plane = std::max(off_plane, dim == 2 ? std::abs(z) : std::max(std::abs(y), std::abs(z)));
    mesh.vertices[it->second] = {x, dim >= 2 ? y : 0.0, dim == 3 ? z : 0.0};
    found[it->second] = true;
  }
  if (std::find(found.begin(), found.end(), false) != found.end())
    throw InputError(path + ": an element refers to a node that is not in the file");
  if (off_plane > 1e-10 * extent)
    throw InputError(path + (dim == 2 ? ": the 2D mesh does not lie in the plane z = 0"
                                      : ": the 1D mesh does not lie on the x axis (y = z = 0)"));

  // 3. Cells in cdyn numbering, oriented: counter-clockwise triangles, positively
  //    oriented tetrahedra (positive Jacobian), intervals left to right.  gmsh's .geo
  //    meshes are already so for a surface whose normal is +z and for gmsh's
  //    tetrahedra, but a .msh or a reversed surface need not be; swapping the last two
  //    vertices reverses the orientation.
  const std::size_t n_cells = cell_nodes.size() / nv;
  mesh.cells.resize(n_cells, {-1, -1, -1});
  for (std::size_t c = 0; c < n_cells; ++c) {
    auto& t = mesh.cells[c];
    for (int i = 0; i < nv; ++i) t[i] = vertex_of_node.at(cell_nodes[c * nv + i]);
    if (mesh.cell_measure(static_cast<int>(c)) < 0.0) std::swap(t[nv - 2], t[nv - 1]);
  }
  if (!mesh.region_names.empty()) mesh.cell_region = std::move(cell_region);

  // 4. Boundary facets: each physical group of dimension dim - 1 (surfaces in 3D,
  //    curves in 2D, points in 1D) becomes the boundary part of its name.
  gmsh::vectorpair parts;
  gmsh::model::getPhysicalGroups(parts, dim - 1);
  for (const auto& [d, tag] : parts) {
    const std::string name = group_name(d, tag);
    const int part = name_index(mesh.part_names, name);
    std::vector<int> entities;
    gmsh::model::getEntitiesForPhysicalGroup(d, tag, entities);
    for (int e : entities) {
      const auto nodes = simplex_nodes(path, d, e);
      for (std::size_t f = 0; f < nodes.size() / dim; ++f) {
        BoundaryFacet facet;
        facet.part = part;
        for (int i = 0; i < dim; ++i) {
          const auto it = vertex_of_node.find(nodes[f * dim + i]);
          if (it == vertex_of_node.end())
            throw InputError(path + ": physical " + (d == 2 ? "surface '" : d == 1 ? "curve '" : "point '") + name +
                             "' is not on the meshed domain (a node of it belongs to no cell)");
          facet.vertices[i] = it->second;
        }
        mesh.boundary.push_back(facet);
      }
    }
  }

  // 5. The rest of the topological boundary, untagged (part -1); then the checks
  //    every reader runs (no cells, inverted or degenerate cells).
  mesh.complete_boundary();
  mesh.check(path);
  return mesh;
}

std::string format_number(double v) {
  std::ostringstream s;
  s << v;
  return s.str();
}

// cdyn/gmsh_mesh.hpp's read_mesh and write_msh.
Mesh read_file(const std::string& path, const GeoParameters& parameters) {
  GmshSession session;
  const int dim = load(session, path, parameters);
  return extract(path, dim);
}

void write_file(const std::string& geo_or_msh, const std::string& out_path, double version,
                const GeoParameters& parameters) {
  if (version != 2.2 && version != 4.1)
    throw InputError(out_path + ": msh version " + format_number(version) +
                     " is not supported (use 2.2 or 4.1)");
  if (!is_msh(out_path)) throw InputError(out_path + ": the output file name must end in .msh");

  GmshSession session;
  const int dim = load(session, geo_or_msh, parameters);
  extract(geo_or_msh, dim);  // refuse now what read_mesh would refuse when reading it back

  // gmsh saves only the elements of physical groups when the model has any, so a
  // model with physical curves but no physical surface would lose its triangles.
  // Mesh.SaveAll is no cure: in msh 2.2 it writes every physical tag as 0, losing the
  // boundary parts.  So the cells get a physical group of their own, "domain".
  gmsh::vectorpair all_groups, top_groups;
  gmsh::model::getPhysicalGroups(all_groups);
  gmsh::model::getPhysicalGroups(top_groups, dim);
  if (!all_groups.empty() && top_groups.empty()) {
    gmsh::vectorpair entities;
    gmsh::model::getEntities(entities, dim);
    std::vector<int> tags;
    for (const auto& [d, tag] : entities) tags.push_back(tag);
    const int group = gmsh::model::addPhysicalGroup(dim, tags);
    gmsh::model::setPhysicalName(dim, group, "domain");
  }
  gmsh::option::setNumber("Mesh.SaveAll", 0);  // even if the .geo asked for it
  gmsh::option::setNumber("Mesh.MshFileVersion", version);
  gmsh::option::setNumber("Mesh.Binary", 0);  // text: FreeFEM's gmshload reads ASCII 2.2
  session.call(out_path, "cannot write the mesh", [&] { gmsh::write(out_path); });
}

const GmshPluginTable table{kGmshPluginVersion, read_file, write_file};

}  // namespace
}  // namespace cdyn

extern "C" const cdyn::GmshPluginTable* cdyn_gmsh_plugin() { return &cdyn::table; }
