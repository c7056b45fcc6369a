// scene_spec.cpp — every scene key read, defaulted and checked, in one place.
#include "scene_spec.hpp"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdio>
#include <limits>
#include <map>
#include <thread>

#include "cdyn/base/error.hpp"
#include "cdyn/qp/petsc/backend.hpp"
#include "expression.hpp"

namespace cdyn::app {

namespace {

// The names of a vector's entries, for messages: "[x, y]", "[x, y, z]", or both.
std::string entries(int components) {
  return components == 2 ? "[x, y]" : components == 3 ? "[x, y, z]" : "[x, y] or [x, y, z]";
}

Expression expression(const Scene& s, const std::string& key, const std::string& fallback) {
  const std::string text = s.string(key, fallback);
  return {key, text, parse_expression(text, key), depends_on_time(text)};
}

// A datum with one expression per component: a string (one component) or a list of
// one per coordinate (components = 2 or 3; 0: a gmsh mesh not read yet, 2 or 3
// accepted and matched with the mesh by simulation.cpp).  An absent vector datum is
// empty: zero in every component.
std::vector<Expression> expressions(const Scene& s, const std::string& key, int components) {
  if (components == 1) return {expression(s, key, "0")};
  if (!s.has(key)) return {};
  const std::vector<std::string> text = s.strings(key);
  const int n = static_cast<int>(text.size());
  if (components == 0 ? n != 2 && n != 3 : n != components)
    throw InputError(key + ": expected one expression per component " + entries(components) + " (got " +
                     std::to_string(n) + ")");
  std::vector<Expression> out;
  for (const std::string& t : text) out.push_back({key, t, parse_expression(t, key), depends_on_time(t)});
  return out;
}

// A vector of numbers, one per coordinate (components as for expressions()); empty
// when the key is absent.
std::vector<double> numbers(const Scene& s, const std::string& key, int components) {
  if (!s.has(key)) return {};
  const std::vector<double> c = s.numbers(key);
  const int n = static_cast<int>(c.size());
  bool finite = true;
  for (double x : c) finite = finite && std::isfinite(x);
  if ((components == 0 ? n != 2 && n != 3 : n != components) || !finite)
    throw InputError(key + ": expected finite numbers " + entries(components));
  return c;
}

// The friction of an obstacle (problems/friction.hpp): its table's keys `friction`, `mu`,
// `threshold`, else those of [contact].  A key the law would ignore is refused: μ
// without Coulomb, a threshold without Tresca; μ and the threshold may vary along Γ_C
// but not in time (they are taken at t = 0).
void read_friction(const Scene& s, const std::string& key, SceneSpec::Rigid& r) {
  auto pick = [&](const std::string& name) { return s.has(key + "." + name) ? key + "." + name : "contact." + name; };
  r.friction_key = pick("friction");
  r.mu_key = pick("mu");
  r.threshold_key = pick("threshold");
  r.friction = s.string(r.friction_key, "none");
  if (r.friction != "none" && r.friction != "tresca" && r.friction != "coulomb")
    throw InputError(r.friction_key + ": unknown friction law '" + r.friction + "' (none, tresca, coulomb)");
  const bool coulomb = r.friction == "coulomb", tresca = r.friction == "tresca";
  if (s.has(r.mu_key) && !coulomb)
    throw InputError(r.mu_key + ": a friction coefficient needs " + r.friction_key + " = \"coulomb\" (it is " + r.friction + ")");
  if (s.has(r.threshold_key) && !tresca)
    throw InputError(r.threshold_key + ": a threshold needs " + r.friction_key + " = \"tresca\" (it is " + r.friction + ")");
  if (coulomb && !s.has(r.mu_key)) throw InputError(r.mu_key + ": Coulomb friction needs the coefficient mu");
  if (tresca && !s.has(r.threshold_key)) throw InputError(r.threshold_key + ": Tresca friction needs the threshold");
  if (coulomb) r.mu = expression(s, r.mu_key, "0");
  if (tresca) r.threshold = expression(s, r.threshold_key, "0");
  for (const auto* e : {&r.mu, &r.threshold})
    if (*e && (*e)->depends_on_time)
      throw InputError((*e)->key + ": may vary along the contact boundary, not in time (taken at t = 0)");
}

// One rigid obstacle of elasticity from the table `key` ("obstacle" or "obstacles[k]");
// dim as for expressions().
SceneSpec::Rigid rigid_obstacle(const Scene& s, const std::string& key, int dim) {
  SceneSpec::Rigid r;
  r.key = key;
  read_friction(s, key, r);
  r.name = s.string(key + ".name", key);
  r.where = s.strings(key + ".where", {"vertices"});
  if (r.where == std::vector<std::string>{"vertices"})
    throw InputError(key + ".where: elasticity needs the contact boundary Γ_C (a part name, or \"boundary\")");
  if (s.has(key + ".gap")) {
    if (s.has(key + ".point") || s.has(key + ".normal"))
      throw InputError(key + ".gap: give a gap function or a plane (point, normal), not both");
    r.gap = expression(s, key + ".gap", "0");
    return r;
  }
  r.point = expressions(s, key + ".point", dim);
  for (const Expression& e : r.point)
    if (!std::isfinite(e.field(Point{}, 0.0)))
      throw InputError(key + ".point: expected finite numbers " + entries(dim) + " (or expressions in t)");
  r.normal = numbers(s, key + ".normal", dim);
  return r;
}

// Keys that belong to other models: naming one is a mistake (it would be ignored).
void reject_keys(const Scene& s, const std::vector<std::string>& keys, const std::string& model) {
  for (const std::string& key : keys)
    if (s.has(key)) throw InputError(key + ": not a key of physics.model = " + model);
}
const std::vector<std::string> kElasticityOnly = {"contact.friction", "contact.mu", "contact.threshold",
                                                  "obstacle.friction", "obstacle.mu", "obstacle.threshold","physics.nu",      "physics.lambda",   "physics.mu",
                                                  "physics.gravity", "dirichlet.components", "neumann.parts",
                                                  "neumann.traction", "obstacle.point", "obstacle.normal",
                                                  "obstacle.gap", "obstacles"};
const std::vector<std::string> kScalarOnly = {"physics.tension", "physics.m", "physics.k", "obstacle.g"};
// The oscillator is m, k, F(t) and g: the continuum's keys would be ignored.
const std::vector<std::string> kNotOscillator = {"physics.rho", "physics.E", "physics.tension", "dirichlet.parts",
                                                 "dirichlet.value", "obstacle.where"};

void read_mesh_keys(const Scene& s, SceneSpec& spec) {
  SceneSpec::Mesh& m = spec.mesh;
  if (spec.physics.model == "oscillator") {
    if (!s.keys("mesh").empty()) throw InputError("mesh: the oscillator has no mesh (remove the [mesh] table)");
    m.kind = "none";
    return;
  }
  m.kind = s.string("mesh.kind");
  if (m.kind != "interval" && m.kind != "unit_square" && m.kind != "unit_cube" && m.kind != "gmsh")
    throw InputError("mesh.kind: unknown kind '" + m.kind + "' (interval, unit_square, unit_cube, gmsh)");
  if (spec.physics.model == "elasticity" && m.kind == "interval")
    throw InputError("physics.model: elasticity needs a 2D (plane strain) or 3D mesh");
  m.dim = m.kind == "interval" ? 1 : m.kind == "unit_square" ? 2 : m.kind == "unit_cube" ? 3 : 0;
  // A key of another kind would be ignored: refused (a --set of mesh.kind drops them,
  // scene.cpp).
  if (m.kind == "gmsh") {
    for (const char* key : {"mesh.n", "mesh.length"})
      if (s.has(key))
        throw InputError(std::string(key) + ": not a key of mesh.kind = gmsh (the mesh is the file's, mesh.file)");
  } else if (s.has("mesh.file")) {
    throw InputError("mesh.file: not a key of mesh.kind = " + m.kind + " (a built-in mesh; a file needs mesh.kind = gmsh)");
  }
  if ((m.kind == "unit_square" || m.kind == "unit_cube") && s.has("mesh.length"))
    throw InputError("mesh.length: not a key of mesh.kind = " + m.kind + " (its sides are 1)");
  if (m.kind == "gmsh") {
    // A relative mesh.file is relative to the scene file's directory (as an #include
    // is to its file), so a scene runs from anywhere; for the embedded scene, to the
    // current directory.  (`--set mesh.file=` values arrive absolute: cmd_run.cpp.)
    m.file = s.string("mesh.file");
    const auto slash = spec.source.find_last_of('/');
    if (!m.file.empty() && m.file.front() != '/' && slash != std::string::npos)
      m.file = spec.source.substr(0, slash + 1) + m.file;
    // mesh.set: numbers given to the .geo before gmsh meshes it (gmsh -setnumber).
    const std::vector<std::string> names = s.keys("mesh.set");
    const auto dot = m.file.find_last_of('.');
    std::string extension = dot == std::string::npos ? "" : m.file.substr(dot);
    for (char& c : extension) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
    if (!names.empty() && extension != ".geo")
      throw InputError("mesh.set: gmsh parameters need a .geo mesh.file (" + m.file + " is already meshed)");
    for (const std::string& name : names) {
      const double value = s.number("mesh.set." + name);
      if (!std::isfinite(value)) throw InputError("mesh.set." + name + ": must be a finite number");
      m.set.emplace_back(name, value);
    }
    return;
  }
  if (s.has("mesh.set")) throw InputError("mesh.set: gmsh parameters need mesh.kind = \"gmsh\" and a .geo file");
  m.n = s.integer("mesh.n");
  if (m.kind == "interval") m.length = s.number("mesh.length", 1.0);
}

// method.pair "W/H" or method.mass "consistent|lumped|redistributed" (on P1).
void read_method(const Scene& s, SceneSpec& spec) {
  if (s.has("method.pair") && s.has("method.mass")) throw InputError("method: give either pair or mass, not both");
  SceneSpec::Method& m = spec.method;
  if (s.has("method.mass")) {
    m.key = "method.mass";
    const std::string name = s.string("method.mass");
    m.mass = MassSpec::parse(name, Element::P1);
    if (m.mass.is_pair())
      throw InputError("method.mass: unknown mass model '" + name + "' (consistent, lumped, redistributed)");
    return;
  }
  m.key = "method.pair";
  const std::string pair = s.string("method.pair", "P1+/P0");
  if (pair.find('/') == std::string::npos)
    throw InputError("method.pair: expected W/H, e.g. P1+/P0 (got '" + pair + "')");
  try {
    m.mass = MassSpec::parse(pair);
  } catch (const InputError& e) {
    throw InputError("method.pair: " + e.message());
  }
  if (m.mass.H == Element::P2) throw InputError("method.pair: P2 velocities are not among the pairs (P0 or P1)");
}

// The Lamé parameters from exactly one of the pairs (E, nu) and (lambda, mu).
Lame material(const Scene& s) {
  const bool young = s.has("physics.E") || s.has("physics.nu");
  const bool lame = s.has("physics.lambda") || s.has("physics.mu");
  if (young && lame) throw InputError("physics.lambda: give E and nu, or lambda and mu, not both");
  if (!young && !lame) throw InputError("physics.E: elasticity needs E and nu, or lambda and mu");
  if (young) {
    if (!s.has("physics.E")) throw InputError("physics.E: missing (physics.nu is given)");
    if (!s.has("physics.nu")) throw InputError("physics.nu: missing (physics.E is given)");
    const double E = s.number("physics.E"), nu = s.number("physics.nu");
    try {
      return lame_parameters(E, nu);
    } catch (const InputError& e) {
      throw InputError("physics." + e.parameter() + ": " + e.message());
    }
  }
  if (!s.has("physics.lambda")) throw InputError("physics.lambda: missing (physics.mu is given)");
  if (!s.has("physics.mu")) throw InputError("physics.mu: missing (physics.lambda is given)");
  return {s.number("physics.lambda"), s.number("physics.mu")};  // checked by build_elastic_contact
}

// [materials.NAME]: the material of the mesh region NAME (a gmsh physical surface);
// each gives E and nu, or lambda and mu, or neither (the region keeps physics' pair),
// and rho or not (physics.rho).  Regions are matched with the mesh in simulation.cpp.
void read_materials(const Scene& s, SceneSpec& spec) {
  for (const std::string& name : s.keys("materials")) {
    const std::string key = "materials." + name;
    if (s.keys(key).empty()) throw InputError(key + ": empty (give E and nu, or lambda and mu, and/or rho)");
    SceneSpec::Physics::Material m{name, s.number(key + ".rho", spec.physics.rho), spec.physics.lame};
    if (!(m.rho > 0.0) || !std::isfinite(m.rho)) throw InputError(key + ".rho: must be positive");
    const bool young = s.has(key + ".E") || s.has(key + ".nu");
    const bool lame = s.has(key + ".lambda") || s.has(key + ".mu");
    if (young && lame) throw InputError(key + ".lambda: give E and nu, or lambda and mu, not both");
    if (young) {
      if (!s.has(key + ".E")) throw InputError(key + ".E: missing (" + key + ".nu is given)");
      if (!s.has(key + ".nu")) throw InputError(key + ".nu: missing (" + key + ".E is given)");
      try {
        m.lame = lame_parameters(s.number(key + ".E"), s.number(key + ".nu"));
      } catch (const InputError& e) {
        throw InputError(key + "." + e.parameter() + ": " + e.message());
      }
    } else if (lame) {
      if (!s.has(key + ".lambda")) throw InputError(key + ".lambda: missing (" + key + ".mu is given)");
      if (!s.has(key + ".mu")) throw InputError(key + ".mu: missing (" + key + ".lambda is given)");
      m.lame = {s.number(key + ".lambda"), s.number(key + ".mu")};
      if (!(m.lame.mu > 0.0) || !std::isfinite(m.lame.mu))
        throw InputError(key + ".mu: the shear modulus must be positive");
      if (!(m.lame.lambda + m.lame.mu > 0.0) || !std::isfinite(m.lame.lambda))
        throw InputError(key + ".lambda: needs λ + μ > 0 (plane strain) or 3λ + 2μ > 0 (space)");
    }
    spec.physics.materials.push_back(m);
  }
}

void read_physics(const Scene& s, SceneSpec& spec) {
  SceneSpec::Physics& p = spec.physics;
  p.rho = s.number("physics.rho", 1.0);
  if (p.model == "oscillator") {
    if (s.has("method.pair") || (s.has("method.mass") && s.string("method.mass") != "lumped"))
      throw InputError("method: the oscillator has one dof and the mass m (no pair or mass model to choose)");
    p.m = s.number("physics.m", 1.0);
    p.k = s.number("physics.k", 1.0);
    p.f = {expression(s, "physics.f", "0")};
    return;
  }
  if (p.model == "elasticity") {
    p.lame = material(s);
    p.f = expressions(s, "physics.f", spec.mesh.dim);
    p.gravity = numbers(s, "physics.gravity", spec.mesh.dim);
    read_materials(s, spec);
    return;
  }
  p.stiffness = p.model == "bar" ? s.number("physics.E", 1.0) : s.number("physics.tension", 1.0);
  p.f = {expression(s, "physics.f", "0")};
}

// dirichlet.components: some of "x", "y" and (in space) "z"; all by default.
std::vector<int> components(const Scene& s, int dim) {
  std::vector<int> out;
  for (const std::string& c : s.strings("dirichlet.components")) {
    if (c != "x" && c != "y" && (c != "z" || dim == 2))
      throw InputError("dirichlet.components: expected " + std::string(dim == 2 ? "\"x\" or \"y\"" : "\"x\", \"y\" or \"z\"") +
                       " (got '" + c + "')");
    out.push_back(c == "x" ? 0 : c == "y" ? 1 : 2);
  }
  std::sort(out.begin(), out.end());
  out.erase(std::unique(out.begin(), out.end()), out.end());
  if (!out.empty() && !s.has("dirichlet.parts")) throw InputError("dirichlet.components: given without dirichlet.parts");
  return out;
}

void read_boundary(const Scene& s, SceneSpec& spec) {
  const bool vector = spec.physics.model == "elasticity";
  const int nc = vector ? spec.mesh.dim : 1;  // (0: a gmsh mesh, 2 or 3)
  spec.dirichlet.parts = s.strings("dirichlet.parts");
  spec.dirichlet.value = expressions(s, "dirichlet.value", nc);
  if (vector) {
    spec.dirichlet.components = components(s, nc);
    spec.neumann.parts = s.strings("neumann.parts");
    if (s.has("neumann.traction") && spec.neumann.parts.empty())
      throw InputError("neumann.traction: given without neumann.parts");
    spec.neumann.traction = expressions(s, "neumann.traction", nc);
  }
  SceneSpec::Obstacle& o = spec.obstacle;
  o.enabled = s.boolean("obstacle.enabled", true);
  o.where = s.strings("obstacle.where", {"vertices"});
  if (vector) {
    if (s.has("obstacle.where") || !s.has("obstacles"))
      o.rigid.push_back(rigid_obstacle(s, "obstacle", nc));
    else
      for (const char* key : {"obstacle.friction", "obstacle.mu", "obstacle.threshold"})
        if (s.has(key)) throw InputError(std::string(key) + ": [obstacle] has no where: the [[obstacles]] take their own");
    for (std::size_t k = 0; k < s.count("obstacles"); ++k)
      o.rigid.push_back(rigid_obstacle(s, "obstacles[" + std::to_string(k) + "]", nc));
    if (!o.enabled)
      for (const SceneSpec::Rigid& r : o.rigid)
        if (r.friction != "none")
          throw InputError(r.friction_key + ": friction needs the obstacle (obstacle.enabled = false)");
  } else {
    o.g = expression(s, "obstacle.g", "0");
    if (spec.physics.model == "oscillator" && o.g.depends_on_time)
      throw InputError("obstacle.g: the oscillator's obstacle is a number (g may not depend on t)");
  }
  // Prescribed motion of the boundary is not modelled: the velocity of a fixed dof is
  // taken as 0 (the inertia of the data, M_fd Ü_D, does not enter; docs/scenes.md).
  for (const Expression& e : spec.dirichlet.value)
    if (e.depends_on_time)
      throw InputError("dirichlet.value: data that vary in time are not supported (the inertia of a prescribed "
                       "motion is not modelled); move the body with a moving obstacle or a traction instead");
  spec.initial.u = expressions(s, "initial.u", nc);
  spec.initial.v = expressions(s, "initial.v", nc);
}

// solver.backend and solver.pc (docs/distributed.md).  The keys of the native pdas's
// linear solves have no meaning on the PETSc back end, whose pdas solves by CG with
// solver.pc: refused there, as solver.pc is on the native back end.
void read_backend(const Scene& s, SceneSpec::Solver& v) {
  v.backend = s.string("solver.backend", "native");
  if (v.backend != "native" && v.backend != "petsc")
    throw InputError("solver.backend: expected \"native\" or \"petsc\" (got '" + v.backend + "')");
  if (v.backend == "petsc" && !petsc::built())
    throw InputError("solver.backend: this cdyn was built without PETSc (CDYN_WITH_PETSC=OFF)");
  v.pc = s.string("solver.pc", "");
  if (v.backend == "native" && s.has("solver.pc"))
    throw InputError("solver.pc: the preconditioner of the petsc back end (set solver.backend = \"petsc\")");
  v.partition = s.string("solver.partition", "none");
  if (v.partition != "none" && v.partition != "slabs" && v.partition != "graph")
    throw InputError("solver.partition: expected \"none\", \"slabs\" or \"graph\" (got '" + v.partition + "')");
  if (v.partition != "none" && v.backend != "petsc")
    throw InputError("solver.partition: the subdomains' step QPs are summed and solved on the petsc back end "
                     "(set solver.backend = \"petsc\")");
  if (v.backend == "petsc")
    for (const char* key : {"solver.linear", "solver.cg_iterations", "solver.free_block"})
      if (s.has(key))
        throw InputError(std::string(key) + ": a setting of the native pdas; the petsc back end solves by CG with "
                                            "solver.pc");
}

void read_time_and_solver(const Scene& s, SceneSpec& spec) {
  SceneSpec::Time& t = spec.time;
  t.dt = s.number("time.dt");
  t.T = s.number("time.T");
  if (!(t.dt > 0.0) || !std::isfinite(t.dt)) throw InputError("time.dt: must be positive");
  if (!(t.T > 0.0) || !std::isfinite(t.T)) throw InputError("time.T: must be positive");
  if (t.T < t.dt)
    throw InputError("time.T: shorter than one step (T = " + std::to_string(t.T) + " < dt = " + std::to_string(t.dt) + ")");
  const double steps = std::ceil(t.T / t.dt - 1e-9);  // T/dt may overflow int (fuzz regression)
  if (!(steps <= std::numeric_limits<int>::max()))
    throw InputError("time.T: T/dt = " + std::to_string(steps) +
                     " steps is more than a run can take (at most 2147483647)");
  t.n_steps = static_cast<int>(steps);
  // The last step ends at n_steps·dt: past T when T is no multiple of dt.
  if (steps - t.T / t.dt > 1e-6) {
    char text[200];
    std::snprintf(text, sizeof text, "time.T = %g is not a multiple of time.dt = %g: %d steps, to t = %.10g", t.T, t.dt,
                  t.n_steps, t.n_steps * t.dt);
    spec.warnings.push_back(text);
  }
  t.scheme = s.string("time.scheme", "auto");  // auto: recommended_scheme() of the problem
  t.parameters.beta = s.number("time.beta", t.parameters.beta);
  t.parameters.gamma = s.number("time.gamma", t.parameters.gamma);
  t.parameters.restitution = s.number("time.restitution", t.parameters.restitution);
  t.parameters.condense = s.boolean("solver.condense", t.parameters.condense);
  t.parameters.reconstruct = s.boolean("time.reconstruct", t.parameters.reconstruct);
  t.parameters.energy_tol = s.number("time.energy_tol", t.parameters.energy_tol);
  if (!(t.parameters.energy_tol > 0.0)) throw InputError("time.energy_tol: must be positive");
  // Rayleigh damping D = αM + βA (docs/schemes.md; the schemes without it refuse it,
  // naming the key through scene_key)
  RayleighDamping& d = t.parameters.damping;
  d.alpha = s.number("damping.alpha", 0.0);
  d.beta = s.number("damping.beta", 0.0);
  for (const auto& [key, value] : {std::pair{"damping.alpha", d.alpha}, std::pair{"damping.beta", d.beta}})
    if (!(value >= 0.0) || !std::isfinite(value)) throw InputError(std::string(key) + ": must be a finite number ≥ 0");

  SceneSpec::Solver& v = spec.solver;
  v.name = s.string("solver.name", "pdas");
  v.options.tol = s.number("solver.tol", 1e-10);
  if (!(v.options.tol > 0.0)) throw InputError("solver.tol: must be positive");
  t.parameters.tol = v.options.tol;  // the full-step reconstruction's QP, as tight as the step's
  v.options.max_iterations = s.integer("solver.max_iterations", 0);
  v.options.pdas_cg_iterations = s.integer("solver.cg_iterations", v.options.pdas_cg_iterations);
  if (v.options.pdas_cg_iterations < 0) throw InputError("solver.cg_iterations: must be 0 (no CG) or more");
  v.options.pdas_free_block = s.number("solver.free_block", v.options.pdas_free_block);
  if (!(v.options.pdas_free_block >= 0.0 && v.options.pdas_free_block <= 1.0))
    throw InputError("solver.free_block: a fraction of the unknowns, in [0, 1]");
  // solver.linear: how pdas solves its reduced systems, a kept Cholesky factor (with
  // CG while the active set moves) or CG alone (docs/performance.md, 3D)
  const std::string linear = s.string("solver.linear", "factor");
  if (linear != "factor" && linear != "cg" && linear != "auto")
    throw InputError("solver.linear: expected \"factor\", \"cg\" or \"auto\" (got '" + linear + "')");
  if (linear != "factor" && v.name != "pdas")
    throw InputError("solver.linear: the CG path is pdas's (solver.name = " + v.name + ")");
  v.options.pdas_cg_only = linear == "cg";
  v.linear_auto = linear == "auto";
  read_backend(s, v);
  v.threads = s.integer("solver.threads", 0);
  if (v.threads < 0)
    throw InputError("solver.threads: must be 0 (the environment's count, OMP_NUM_THREADS) or a number of threads ≥ 1");
  // more threads than cores: accepted (the results are the same), but slower than one per core
  if (const unsigned cores = std::thread::hardware_concurrency(); cores > 0 && unsigned(v.threads) > cores)
    spec.warnings.push_back("solver.threads = " + std::to_string(v.threads) + " is more than the " +
                            std::to_string(cores) + " cores of this machine: the threads will share them");
}

// units = "length, force, time", e.g. "mm, N, s".
SceneSpec::Units units(const Scene& s) {
  if (!s.has("units")) return {};
  std::vector<std::string> names(1);
  for (char c : s.string("units")) {
    if (c == ',')
      names.emplace_back();
    else if (c != ' ')
      names.back() += c;
  }
  if (names.size() != 3 || names[0].empty() || names[1].empty() || names[2].empty())
    throw InputError("units: expected the units of length, force and time, e.g. \"mm, N, s\"");
  return {names[0], names[1], names[2]};
}

void read_output(const Scene& s, SceneSpec& spec) {
  SceneSpec::Output& o = spec.output;
  // By default about 100 to 200 field files and contact.csv frames a run, whatever its
  // length (every = floor(n_steps / 100)): enough to watch, not a file per step.
  const int every = std::max(1, spec.time.n_steps / 100);
  o.every = s.integer("output.every", every);
  if (o.every < 1) throw InputError("output.every: must be at least 1");
  o.contact_every = s.integer("output.contact_every", every);
  if (o.contact_every < 1) throw InputError("output.contact_every: must be at least 1");
  o.fields = s.boolean("output.fields", true);
  o.plots = s.boolean("output.plots", true);
  o.stress = s.boolean("output.stress", true);
  o.wellposed = s.boolean("output.wellposed", true);
  o.checkpoint_every = s.integer("output.checkpoint_every", 0);
  if (o.checkpoint_every < 0) throw InputError("output.checkpoint_every: must be 0 (no checkpoints) or more");
  for (const std::string& name : s.keys("output.probes"))
    o.probes.emplace_back(name, s.numbers("output.probes." + name));
  spec.exact_solution = s.string("exact.solution", "");
  spec.units = units(s);
}

// What a run on subdomains (solver.partition) does not do yet: refused by key rather
// than done on one rank's cells only (docs/distributed.md, "Subdomains").
void check_partition(const SceneSpec& spec) {
  if (spec.solver.partition == "none") return;
  const std::string why = " on subdomains (solver.partition = \"" + spec.solver.partition + "\")";
  if (spec.physics.model != "membrane" && spec.physics.model != "elasticity")
    throw InputError("solver.partition: a run" + why + " takes a membrane or an elastic body (physics.model = \"" +
                     spec.physics.model + "\")");
}

}  // namespace

SceneSpec read_scene(const Scene& s) {
  SceneSpec spec;
  spec.name = s.name();
  spec.source = s.source();
  SceneSpec::Physics& p = spec.physics;
  p.model = s.string("physics.model");
  if (p.model != "membrane" && p.model != "bar" && p.model != "oscillator" && p.model != "elasticity")
    throw InputError("physics.model: unknown model '" + p.model + "' (oscillator, bar, membrane, elasticity)");
  reject_keys(s, p.model == "elasticity" ? kScalarOnly : kElasticityOnly, p.model);
  if (p.model == "oscillator") reject_keys(s, kNotOscillator, p.model);
  if (p.model != "elasticity" && !s.keys("materials").empty())
    throw InputError("materials: materials by region are for physics.model = elasticity");
  if (p.model != "elasticity" && s.has("output.contact_every"))
    throw InputError("output.contact_every: only elasticity runs write contact.csv");
  if (p.model != "elasticity" && s.has("output.stress"))
    throw InputError("output.stress: only elasticity runs have a stress to write");
  read_mesh_keys(s, spec);
  read_physics(s, spec);
  if (p.model == "oscillator") {
    spec.method.mass = {MassSpec::Model::Lumped, Element::P1, Element::P0};
    spec.method.key = "method.mass";
  } else {
    read_method(s, spec);
  }
  read_boundary(s, spec);
  read_time_and_solver(s, spec);
  read_output(s, spec);
  check_partition(spec);
  return spec;
}

std::string scene_key(const std::string& parameter, const SceneSpec& spec, const std::string& message) {
  static const std::map<std::string, std::string> fixed = {
      {"n", "mesh.n"},           {"length", "mesh.length"},         {"rho", "physics.rho"},
      {"E", "physics.E"},        {"nu", "physics.nu"},              {"lambda", "physics.lambda"},
      {"mu", "physics.mu"},      {"m", "physics.m"},                {"k", "physics.k"},
      {"normal", "obstacle.normal"}, {"contact", "obstacle.where"}, {"dt", "time.dt"},
      {"beta", "time.beta"},     {"gamma", "time.gamma"},           {"restitution", "time.restitution"},
      {"scheme", "time.scheme"}, {"tol", "solver.tol"},             {"max_iterations", "solver.max_iterations"},
      {"solver", "solver.name"}, {"mesh", "mesh.kind"},         {"linear", "solver.linear"},
      {"pc", "solver.pc"},       {"solver.backend", "solver.backend"}};
  if (const auto it = fixed.find(parameter); it != fixed.end()) return it->second;
  // gmsh parameters of the .geo (meshing/cdyn/gmsh_mesh.hpp)
  if (parameter.rfind("setnumber.", 0) == 0) return "mesh.set." + parameter.substr(10);
  if (parameter == "kappa") return spec.physics.model == "bar" ? "physics.E" : "physics.tension";
  if (parameter == "pair" || parameter == "mass") return spec.method.key;
  if (parameter == "damping") return spec.time.parameters.damping.alpha != 0.0 ? "damping.alpha" : "damping.beta";
  // friction: the key of the obstacle the message names, else of the first with friction
  if (parameter == "friction" || parameter == "friction_mu" || parameter == "friction_threshold") {
    const SceneSpec::Rigid* found = nullptr;
    for (const SceneSpec::Rigid& r : spec.obstacle.rigid) {
      if (r.friction == "none") continue;
      if (!found || message.find("(" + r.name + ")") != std::string::npos) found = &r;
    }
    if (found)
      return parameter == "friction" ? found->friction_key : parameter == "friction_mu" ? found->mu_key : found->threshold_key;
  }
  if (parameter == "gap")  // "... (obstacle NAME)" names the obstacle
    for (const SceneSpec::Rigid& r : spec.obstacle.rigid)
      if (message.find("(obstacle " + r.name + ")") != std::string::npos) return r.key + ".gap";
  return "";
}

}  // namespace cdyn::app
