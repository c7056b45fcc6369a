// fields_output.cpp — VTK XML UnstructuredGrid files with appended raw data
// (https://docs.vtk.org/en/latest/design_documents/VTKFileFormats.html), and their
// .pvd collection.  See fields_output.hpp for what is written.
#include "cdyn/fields_output.hpp"

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <sstream>

#include "cdyn/atomic_file.hpp"
#include "cdyn/base/error.hpp"
#include "cdyn/post/contact_force.hpp"

namespace cdyn {

namespace {

constexpr std::uint8_t kVtkLine = 3, kVtkTriangle = 5, kVtkTetra = 10;

const char* byte_order() { return std::endian::native == std::endian::little ? "LittleEndian" : "BigEndian"; }

// One appended block: its size in bytes (UInt64, header_type) then the bytes.
template <class T>
void append_block(std::string& blocks, const std::vector<T>& values) {
  const std::uint64_t n = values.size() * sizeof(T);
  blocks.append(reinterpret_cast<const char*>(&n), sizeof n);
  blocks.append(reinterpret_cast<const char*>(values.data()), n);
}

std::uint64_t block_size(std::size_t n_values, std::size_t value_size) { return 8 + n_values * value_size; }

// A double with all its digits (for the pvd's time values).
std::string exact(double x) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.17g", x);
  return buf;
}

// fields/step_NNNNNN.vtu, relative to the output directory.
std::string frame_file(int step) {
  char name[32];
  std::snprintf(name, sizeof name, "step_%06d.vtu", step);
  return std::string("fields/") + name;
}

}  // namespace

void remove_fields(const std::filesystem::path& out) {
  std::error_code ec;
  std::vector<std::filesystem::path> old{out / "fields.pvd"};
  // fields.pvd's temporaries left by an interrupted run (atomic_file.hpp) — only its
  // own: the run now starting may be writing its other outputs' temporaries in `out`
  for (const auto& entry : std::filesystem::directory_iterator(out, ec))
    if (is_atomic_temporary(entry.path()) && entry.path().filename().string().rfind(".fields.pvd.", 0) == 0)
      old.push_back(entry.path());
  // fields/step_*.vtu and every temporary in fields/
  for (const auto& entry : std::filesystem::directory_iterator(out / "fields", ec)) {
    const std::string name = entry.path().filename().string();
    if ((name.rfind("step_", 0) == 0 && entry.path().extension() == ".vtu") || is_atomic_temporary(entry.path()))
      old.push_back(entry.path());
  }
  for (const auto& path : old) std::filesystem::remove(path, ec);
}

std::vector<FieldArray> state_arrays(const Mesh& mesh, const ConstrainedProblem& problem, const Eigen::VectorXd& U_full,
                                     const Eigen::VectorXd& rate_full, const Eigen::VectorXd& reaction_xy) {
  const FESpace& W = *problem.W;
  const int nv = mesh.n_vertices(), n_comp = W.components();
  const int width = n_comp == 1 ? 1 : 3;  // ParaView's vectors have 3 components

  // Vertex values: scalar dof v of P1, P1+ and P2 is vertex v (fe/fe_space.hpp).
  const std::vector<double> zeros(static_cast<std::size_t>(width) * nv, 0.0);
  FieldArray u{"u", width, zeros}, v{"v", width, zeros}, lambda{"lambda", width, zeros};
  for (int vertex = 0; vertex < nv; ++vertex)
    for (int k = 0; k < n_comp; ++k) {
      const int dof = W.vertex_dof(vertex, k), at = width * vertex + k;
      u.values[at] = U_full[dof];
      v.values[at] = rate_full[dof];
    }
  for (int vertex = 0; vertex < nv; ++vertex) {
    const Point lam = vertex_multiplier(problem, reaction_xy, vertex);
    const double c[3] = {lam.x, lam.y, lam.z};
    for (int k = 0; k < n_comp; ++k) lambda.values[width * vertex + k] = c[k];
  }
  return {std::move(u), std::move(v), std::move(lambda)};
}

FieldsWriter::FieldsWriter(const std::filesystem::path& out, const Mesh& mesh, const ConstrainedProblem& problem)
    : FieldsWriter(out, mesh) {
  problem_ = &problem;
}

FieldsWriter::FieldsWriter(const std::filesystem::path& out, const Mesh& mesh) : out_(out), mesh_(mesh) {
  std::error_code ec;
  std::filesystem::create_directories(out_ / "fields", ec);
  if (ec) throw InputError((out_ / "fields").string() + ": cannot create the directory (" + ec.message() + ")");

  // The geometry is the same in every frame: encode it once.
  const int nv = mesh.n_vertices(), nc = mesh.n_cells(), per_cell = mesh.vertices_per_cell();
  std::vector<double> points(3 * static_cast<std::size_t>(nv), 0.0);  // z = 0 below 3D
  for (int v = 0; v < nv; ++v) {
    points[3 * v] = mesh.vertices[v].x;
    points[3 * v + 1] = mesh.vertices[v].y;
    points[3 * v + 2] = mesh.vertices[v].z;
  }
  std::vector<std::int64_t> connectivity, offsets;
  for (int c = 0; c < nc; ++c) {
    for (int k = 0; k < per_cell; ++k) connectivity.push_back(mesh.cells[c][k]);
    offsets.push_back(static_cast<std::int64_t>(c + 1) * per_cell);
  }
  // (VTK's linear tetrahedron takes its vertices in the order of a positive one, as
  // the cells are stored: mesh/mesh.hpp)
  const std::vector<std::uint8_t> types(nc, mesh.dim == 3 ? kVtkTetra : mesh.dim == 2 ? kVtkTriangle : kVtkLine);
  append_block(geometry_blocks_, points);
  append_block(geometry_blocks_, connectivity);
  append_block(geometry_blocks_, offsets);
  append_block(geometry_blocks_, types);
}

void FieldsWriter::write(int step, double t, const Eigen::VectorXd& U_full, const Eigen::VectorXd& rate_full,
                         const Eigen::VectorXd& reaction_xy, const ExtraFields& extra) {
  if (!problem_) throw InputError("FieldsWriter: made without a problem, it writes given arrays only");
  ExtraFields arrays{state_arrays(mesh_, *problem_, U_full, rate_full, reaction_xy), extra.cell};
  arrays.point.insert(arrays.point.end(), extra.point.begin(), extra.point.end());
  write(step, t, arrays);
}

void FieldsWriter::write(int step, double t, const ExtraFields& arrays) {
  const int nv = mesh_.n_vertices();
  // The arrays in the order of their blocks: the point arrays (u, v, lambda first), the
  // cell arrays; then the geometry.
  struct Entry {
    const std::string* name;
    int components;
    const std::vector<double>* values;
    std::uint64_t offset;
  };
  std::vector<Entry> point_entries, cell_entries;
  auto add = [](std::vector<Entry>& to, const std::vector<FieldArray>& arrays, std::size_t tuples, const char* where) {
    for (const FieldArray& a : arrays) {
      if (a.components < 1 || a.values.size() != tuples * static_cast<std::size_t>(a.components))
        throw InputError("FieldsWriter: the " + std::string(where) + " array '" + a.name + "' has " +
                         std::to_string(a.values.size()) + " values, expected " + std::to_string(tuples) + " × " +
                         std::to_string(a.components));
      to.push_back({&a.name, a.components, &a.values, 0});
    }
  };
  add(point_entries, arrays.point, static_cast<std::size_t>(nv), "point");
  add(cell_entries, arrays.cell, static_cast<std::size_t>(mesh_.n_cells()), "cell");
  std::string blocks;
  std::uint64_t offset = 0;
  for (std::vector<Entry>* list : {&point_entries, &cell_entries})
    for (Entry& e : *list) {
      e.offset = offset;
      append_block(blocks, *e.values);
      offset += block_size(e.values->size(), 8);
    }
  const std::uint64_t at_points = offset;
  const std::uint64_t at_connectivity = at_points + block_size(3 * static_cast<std::size_t>(nv), 8);
  const std::uint64_t at_offsets = at_connectivity + block_size(static_cast<std::size_t>(mesh_.n_cells()) * mesh_.vertices_per_cell(), 8);
  const std::uint64_t at_types = at_offsets + block_size(mesh_.n_cells(), 8);

  std::ostringstream xml;
  xml << "<?xml version=\"1.0\"?>\n"
      << "<VTKFile type=\"UnstructuredGrid\" version=\"1.0\" byte_order=\"" << byte_order()
      << "\" header_type=\"UInt64\">\n"
      << "  <UnstructuredGrid>\n"
      << "    <Piece NumberOfPoints=\"" << nv << "\" NumberOfCells=\"" << mesh_.n_cells() << "\">\n"
      << "      <PointData Scalars=\"u\">\n";
  auto data_arrays = [&xml](const std::vector<Entry>& list) {
    for (const Entry& e : list)
      xml << "        <DataArray type=\"Float64\" Name=\"" << *e.name << "\" NumberOfComponents=\"" << e.components
          << "\" format=\"appended\" offset=\"" << e.offset << "\"/>\n";
  };
  data_arrays(point_entries);
  xml << "      </PointData>\n";
  if (!cell_entries.empty()) {
    xml << "      <CellData>\n";
    data_arrays(cell_entries);
    xml << "      </CellData>\n";
  }
  xml
      << "      <Points>\n"
      << "        <DataArray type=\"Float64\" Name=\"Points\" NumberOfComponents=\"3\" format=\"appended\" offset=\""
      << at_points << "\"/>\n"
      << "      </Points>\n"
      << "      <Cells>\n"
      << "        <DataArray type=\"Int64\" Name=\"connectivity\" format=\"appended\" offset=\"" << at_connectivity << "\"/>\n"
      << "        <DataArray type=\"Int64\" Name=\"offsets\" format=\"appended\" offset=\"" << at_offsets << "\"/>\n"
      << "        <DataArray type=\"UInt8\" Name=\"types\" format=\"appended\" offset=\"" << at_types << "\"/>\n"
      << "      </Cells>\n"
      << "    </Piece>\n"
      << "  </UnstructuredGrid>\n"
      << "  <AppendedData encoding=\"raw\">\n   _";

  const std::string file = frame_file(step);
  // Written under a temporary name and renamed when complete (atomic_file.hpp): an
  // interrupted run leaves no truncated step_*.vtu.
  AtomicFile vtu(out_ / file);
  std::ostream& os = vtu.stream();
  os << xml.str();
  os.write(blocks.data(), static_cast<std::streamsize>(blocks.size()));
  os.write(geometry_blocks_.data(), static_cast<std::streamsize>(geometry_blocks_.size()));
  os << "\n  </AppendedData>\n</VTKFile>\n";
  vtu.commit();
  frames_.push_back({step, t, file});
}

void FieldsWriter::continue_series(const std::vector<std::pair<int, double>>& frames, int last_step) {
  frames_.clear();
  for (const auto& [step, t] : frames) {
    const std::string file = frame_file(step);
    if (!std::filesystem::is_regular_file(out_ / file))
      throw InputError((out_ / file).string() + ": missing (a field file of the run being resumed)");
    frames_.push_back({step, t, file});
  }
  // the others: later steps, and the last state of an interrupted run (not a frame of the series)
  std::error_code ec;
  std::vector<std::filesystem::path> others;
  for (const auto& entry : std::filesystem::directory_iterator(out_ / "fields", ec)) {
    const std::string name = entry.path().filename().string();
    int step = -1;
    if (std::sscanf(name.c_str(), "step_%d.vtu", &step) != 1) continue;
    const bool listed = std::any_of(frames.begin(), frames.end(), [&](const auto& f) { return f.first == step; });
    if (!listed || step > last_step) others.push_back(entry.path());
  }
  for (const auto& path : others) std::filesystem::remove(path, ec);
}

void FieldsWriter::finish() const {
  // fields.pvd lists only files already renamed into place; it is itself atomic, so
  // a reader never sees a collection cut in the middle.
  AtomicFile file(out_ / "fields.pvd");
  std::ostream& pvd = file.stream();
  pvd << "<?xml version=\"1.0\"?>\n"
      << "<VTKFile type=\"Collection\" version=\"0.1\" byte_order=\"" << byte_order() << "\">\n"
      << "  <Collection>\n";
  for (const Frame& f : frames_)
    pvd << "    <DataSet timestep=\"" << exact(f.t) << "\" group=\"\" part=\"0\" file=\"" << f.file << "\"/>\n";
  pvd << "  </Collection>\n</VTKFile>\n";
  file.commit();
}

}  // namespace cdyn
