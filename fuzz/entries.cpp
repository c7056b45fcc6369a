// entries.cpp — the fuzz entry functions (see entries.hpp).
#include "entries.hpp"

#include <unistd.h>

#include <array>
#include <cstdint>
#include <cstdio>
#include <stdexcept>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

#include "cdyn/base/error.hpp"
#include "expression.hpp"
#include "cdyn/gmsh_mesh.hpp"
#include "scene.hpp"
#include "simulation.hpp"

namespace cdyn::fuzz {

namespace {

// True when the scene asks for a problem beyond the caps (or for a mesh file, whose
// reader mesh_input fuzzes on its own: a scene must not make the fuzzer read files).
bool too_large(const app::Scene& s) {
  try {
    if (!s.has("mesh.kind")) return false;
    const std::string kind = s.string("mesh.kind");
    if (kind == "gmsh") return true;
    if (!s.has("mesh.n")) return false;
    const int n = s.integer("mesh.n");
    return n > (kind == "interval" ? kMaxIntervalCells : kind == "unit_cube" ? kMaxCubeCells : kMaxSquareCells);
  } catch (const InputError&) {
    return false;  // make_simulation reports the same bad key
  }
}

// What make_simulation promises of a scene it accepts (a broken promise is a finding,
// thrown as std::logic_error so that no entry catches it): at least one step, as
// many as T/dt asks for, and the mesh the scene's integer keys say.
void check_accepted(const app::Scene& scene, const app::Simulation& sim) {
  const double asked = std::ceil(sim.T / sim.dt - 1e-9);
  if (!(sim.n_steps >= 1 && sim.n_steps == asked))
  {
    char what[160];
    std::snprintf(what, sizeof what, "make_simulation accepted T = %g, dt = %g with n_steps = %d", sim.T, sim.dt,
                  sim.n_steps);
    throw std::logic_error(what);
  }
  // mesh.n as written (64-bit), read back from the scene's own dump
  const toml::table table = toml::parse(scene.dump());
  const auto n = table.at_path("mesh.n").value_exact<std::int64_t>();
  const int cells = sim.mesh->n_cells();
  const std::int64_t per_side = sim.mesh->dim == 1   ? cells
                                : sim.mesh->dim == 2 ? std::llround(std::sqrt(cells / 2.0))
                                                     : std::llround(std::cbrt(cells / 6.0));
  if (n && scene.string("mesh.kind") != "gmsh" && *n != per_side)
    throw std::logic_error("mesh.n = " + std::to_string(*n) + " gave " + std::to_string(per_side) + " cells per side");
}

}  // namespace

void scene_input(std::string_view text) {
  try {
    app::Scene scene = app::Scene::from_string(std::string(text), "fuzz.toml");
    std::istringstream lines{std::string(text)};
    for (std::string line; std::getline(lines, line);)
      if (line.rfind("#set ", 0) == 0) scene.set(line.substr(5));
    (void)scene.dump();
    if (too_large(scene)) return;
    app::Simulation sim = app::make_simulation(scene);
    check_accepted(scene, sim);
    State s = sim.initial;
    for (int n = 0; n < 2; ++n) {
      sim.scheme->step(s);
      (void)sim.scheme->energy(s);
    }
  } catch (const InputError&) {
  } catch (const NumericalError&) {
  }
}

void expression_input(std::string_view text) {
  try {
    const Field f = parse_expression(std::string(text), "fuzz");
    for (const std::array<double, 3> p : {std::array<double, 3>{0, 0, 0}, {0.5, -1, 2}, {1e300, -1e-300, NAN}})
      (void)f(Point{p[0], p[1], p[2]}, p[2]);
  } catch (const InputError&) {
  }
}

void mesh_input(std::string_view text) {
  // One file per process (libFuzzer may run several jobs side by side).
  const std::filesystem::path file =
      std::filesystem::temp_directory_path() / ("cdyn_fuzz_" + std::to_string(::getpid()) + ".msh");
  {
    std::ofstream os(file, std::ios::binary | std::ios::trunc);
    os.write(text.data(), static_cast<std::streamsize>(text.size()));
  }
  try {
    const Mesh mesh = read_mesh(file.string());
    (void)mesh.measure();
  } catch (const InputError&) {
  }
  std::error_code ec;
  std::filesystem::remove(file, ec);
}

}  // namespace cdyn::fuzz
