// simulation.cpp — scene keys → kernel structures.
#include "simulation.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <regex>

#include "cdyn/problems/elastic_contact.hpp"
#include "cdyn/base/error.hpp"
#include "expression.hpp"
#include "cdyn/gmsh_mesh.hpp"
#include "cdyn/problems/oscillator.hpp"
#include "cdyn/problems/scalar_wave.hpp"

namespace cdyn::app {

namespace {

Field expression(const Scene& s, const std::string& key, const std::string& fallback) {
  return parse_expression(s.string(key, fallback), key);
}

// Whether an expression mentions the variable t (then the load is re-assembled each step).
bool depends_on_time(const std::string& text) { return std::regex_search(text, std::regex(R"((^|[^A-Za-z0-9_])t($|[^A-Za-z0-9_]))")); }

// "all" or a list of part names → part indices.
std::vector<int> parts(const Mesh& mesh, const Scene& s, const std::string& key) {
  std::vector<int> out;
  for (const std::string& name : s.strings(key)) {
    if (name == "all") {
      for (std::size_t p = 0; p < mesh.part_names.size(); ++p) out.push_back(static_cast<int>(p));
      // untagged boundary facets (part −1) are included too
      out.push_back(-1);
      continue;
    }
    try {
      out.push_back(mesh.part_index(name));
    } catch (const InputError& e) {
      throw InputError(key + ": " + e.what());
    }
  }
  return out;
}

// method.pair "W/H" or method.mass "consistent|lumped|redistributed" → (W element, mass spec).
std::pair<Element, std::string> method(const Scene& s, Element default_w) {
  if (s.has("method.pair") && s.has("method.mass")) throw InputError("method: give either pair or mass, not both");
  if (s.has("method.mass")) {
    const std::string m = s.string("method.mass");
    if (m != "consistent" && m != "lumped" && m != "redistributed")
      throw InputError("method.mass: unknown mass model '" + m + "' (consistent, lumped, redistributed)");
    return {default_w, m};
  }
  const std::string pair = s.string("method.pair", "P1+/P0");
  const auto slash = pair.find('/');
  if (slash == std::string::npos) throw InputError("method.pair: expected W/H, e.g. P1+/P0 (got '" + pair + "')");
  try {
    const Element W = element_from_string(pair.substr(0, slash));
    const Element H = element_from_string(pair.substr(slash + 1));
    if (W == Element::P0) throw InputError("the displacement space must be continuous");
    if (H == Element::P2) throw InputError("P2 velocities are not among the pairs (P0 or P1)");
    return {W, to_string(H)};
  } catch (const InputError& e) {
    throw InputError("method.pair: " + std::string(e.what()));
  }
}

}  // namespace

Mesh make_mesh(const Scene& s) {
  const std::string kind = s.string("mesh.kind");
  if (kind == "interval") return interval_mesh(s.integer("mesh.n"), s.number("mesh.length", 1.0));
  if (kind == "unit_square") return unit_square_mesh(s.integer("mesh.n"));
  if (kind == "gmsh") {
    // A relative mesh.file is relative to the scene file's directory (as an #include
    // is to its file), so a scene runs from anywhere; for the embedded scene, to the
    // current directory.  (`--set mesh.file=` values arrive absolute: cmd_run.cpp.)
    std::string file = s.string("mesh.file");
    const auto slash = s.source().find_last_of('/');
    if (!file.empty() && file.front() != '/' && slash != std::string::npos) file = s.source().substr(0, slash + 1) + file;
    return read_mesh(file);
  }
  throw InputError("mesh.kind: unknown kind '" + kind + "' (interval, unit_square, gmsh)");
}

namespace {

// The one-dof oscillator (oscillator.hpp): physics.m, physics.k, physics.f = F(t).
ConstrainedProblem oscillator(const Mesh& mesh, const Scene& s) {
  if (s.has("method.pair") || (s.has("method.mass") && s.string("method.mass") != "lumped"))
    throw InputError("method: the oscillator has one dof and the mass m (no pair or mass model to choose)");
  OscillatorData o;
  o.m = s.number("physics.m", 1.0);
  o.k = s.number("physics.k", 1.0);
  const std::string F = s.string("physics.f", "0");
  o.F = parse_expression(F, "physics.f");
  o.load_is_constant = !depends_on_time(F);
  o.obstacle = s.boolean("obstacle.enabled", true);
  o.g = expression(s, "obstacle.g", "0")(0.0, 0.0, 0.0);
  return build_oscillator(mesh, o);
}

// The membrane (unit square or gmsh) and the bar (interval).
ScalarWaveData scalar_wave(const Mesh& mesh, const Scene& s, const std::string& model) {
  if (model == "bar" && mesh.dim != 1) throw InputError("physics.model: the bar needs a 1D mesh (mesh.kind = interval)");
  ScalarWaveData d;
  const auto [W, velocity] = method(s, Element::P1);
  d.displacement = W;
  d.velocity = velocity;
  d.rho = s.number("physics.rho", 1.0);
  d.kappa = model == "bar" ? s.number("physics.E", 1.0) : s.number("physics.tension", 1.0);
  const std::string f = s.string("physics.f", "0");
  d.f = parse_expression(f, "physics.f");
  d.load_is_constant = !depends_on_time(f);
  d.dirichlet_parts = parts(mesh, s, "dirichlet.parts");
  d.dirichlet_value = expression(s, "dirichlet.value", "0");
  const std::string where = s.string("obstacle.where", "vertices");
  d.obstacle_on_all_vertices = where == "vertices";
  if (!d.obstacle_on_all_vertices) d.obstacle_parts = parts(mesh, s, "obstacle.where");
  d.obstacle = s.boolean("obstacle.enabled", true);
  d.obstacle_g = expression(s, "obstacle.g", "0");
  return d;
}

// Keys that belong to other models: naming one is a mistake (it would be ignored).
void reject_keys(const Scene& s, const std::vector<std::string>& keys, const std::string& model) {
  for (const std::string& key : keys)
    if (s.has(key)) throw InputError(key + ": not a key of physics.model = " + model);
}
const std::vector<std::string> kElasticityOnly = {"physics.nu",      "physics.lambda",   "physics.mu",
                                                  "physics.gravity", "dirichlet.components", "neumann.parts",
                                                  "neumann.traction", "obstacle.point", "obstacle.normal"};
const std::vector<std::string> kScalarOnly = {"physics.tension", "physics.m", "physics.k", "obstacle.g"};

// A vector datum of elasticity: two expressions [x component, y component] in x, y, t.
// `time_dependent` is set when either mentions t.
std::array<Field, 2> vector_expression(const Scene& s, const std::string& key, bool* time_dependent = nullptr) {
  const std::vector<std::string> text = s.strings(key, {"0", "0"});
  if (text.size() != 2)
    throw InputError(key + ": expected two expressions [x component, y component] (got " + std::to_string(text.size()) + ")");
  if (time_dependent) *time_dependent = *time_dependent || depends_on_time(text[0]) || depends_on_time(text[1]);
  return {parse_expression(text[0], key), parse_expression(text[1], key)};
}

Point point(const Scene& s, const std::string& key, Point fallback) {
  if (!s.has(key)) return fallback;
  const std::vector<double> c = s.numbers(key);
  if (c.size() != 2 || !std::isfinite(c[0]) || !std::isfinite(c[1]))
    throw InputError(key + ": expected two finite numbers [x, y]");
  return {c[0], c[1]};
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
    return lame_parameters(s.number("physics.E"), s.number("physics.nu"));
  }
  if (!s.has("physics.lambda")) throw InputError("physics.lambda: missing (physics.mu is given)");
  if (!s.has("physics.mu")) throw InputError("physics.mu: missing (physics.lambda is given)");
  return {s.number("physics.lambda"), s.number("physics.mu")};  // checked by build_elastic_contact
}

// dirichlet.components: ["x"], ["y"] or both (default).
std::vector<int> components(const Scene& s) {
  std::vector<int> out;
  for (const std::string& c : s.strings("dirichlet.components")) {
    if (c != "x" && c != "y") throw InputError("dirichlet.components: expected \"x\" or \"y\" (got '" + c + "')");
    out.push_back(c == "x" ? 0 : 1);
  }
  std::sort(out.begin(), out.end());
  out.erase(std::unique(out.begin(), out.end()), out.end());
  if (!out.empty() && !s.has("dirichlet.parts")) throw InputError("dirichlet.components: given without dirichlet.parts");
  return out;
}

// Plane-strain elasticity with frictionless contact against a rigid plane
// (elastic_contact.hpp): physics.E/nu or lambda/mu, rho, f = [f_x, f_y] plus ρ·gravity,
// dirichlet.*, neumann.*, obstacle.where (Γ_C), obstacle.point, obstacle.normal.
ElasticContactData elasticity(const Mesh& mesh, const Scene& s) {
  if (mesh.dim != 2) throw InputError("physics.model: elasticity needs a 2D mesh (plane strain)");
  ElasticContactData d;
  const auto [W, velocity] = method(s, Element::P1);
  d.displacement = W;
  d.velocity = velocity;
  const Lame l = material(s);
  d.lambda = l.lambda;
  d.mu = l.mu;
  d.rho = s.number("physics.rho", 1.0);
  bool time_dependent = false;
  const std::array<Field, 2> f = vector_expression(s, "physics.f", &time_dependent);
  const Point g = point(s, "physics.gravity", {0.0, 0.0});
  const double rho = d.rho;
  // f + ρ g: the body force per unit volume (gravity given as an acceleration).
  d.f = {[f, g, rho](double x, double y, double t) { return f[0](x, y, t) + rho * g.x; },
         [f, g, rho](double x, double y, double t) { return f[1](x, y, t) + rho * g.y; }};
  d.dirichlet_parts = parts(mesh, s, "dirichlet.parts");
  d.dirichlet_components = components(s);
  d.dirichlet_value = vector_expression(s, "dirichlet.value");
  d.neumann_parts = parts(mesh, s, "neumann.parts");
  if (s.has("neumann.traction") && d.neumann_parts.empty())
    throw InputError("neumann.traction: given without neumann.parts");
  d.traction = vector_expression(s, "neumann.traction", &time_dependent);
  d.load_is_constant = !time_dependent;
  d.obstacle = s.boolean("obstacle.enabled", true);
  if (s.strings("obstacle.where", {"vertices"}) == std::vector<std::string>{"vertices"})
    throw InputError("obstacle.where: elasticity needs the contact boundary Γ_C (a part name)");
  d.contact_parts = parts(mesh, s, "obstacle.where");
  d.obstacle_point = point(s, "obstacle.point", {0.0, 0.0});
  d.obstacle_normal = point(s, "obstacle.normal", {0.0, 1.0});
  return d;
}

// The vertices whose dofs carry a constraint (dof → vertex through vertex_dof).
std::vector<int> constrained_vertices(const Mesh& mesh, const ConstrainedProblem& p) {
  const FESpace& W = *p.W;
  std::vector<int> vertex_of(W.n_dofs(), -1);
  for (int v = 0; v < mesh.n_vertices(); ++v)
    for (int k = 0; k < W.components(); ++k) vertex_of[W.vertex_dof(v, k)] = v;
  std::vector<int> out;
  for (int i : p.constrained) out.push_back(vertex_of[p.bc->free_dofs()[i]]);
  std::sort(out.begin(), out.end());
  out.erase(std::unique(out.begin(), out.end()), out.end());
  return out;
}

// The initial data: two expressions per datum for elasticity, one for the scalar models.
Eigen::VectorXd initial_field(const Scene& s, const ConstrainedProblem& p, const std::string& key) {
  const FESpace& W = *p.W;
  if (W.components() == 1) return p.unknowns(W.interpolate(expression(s, key, "0"), 0.0));
  const std::array<Field, 2> f = vector_expression(s, key);
  return p.unknowns(W.interpolate(std::vector<Field>(f.begin(), f.end()), 0.0));
}

}  // namespace

Simulation make_simulation(const Scene& s) {
  Simulation sim;
  sim.scene_name = s.name();

  // Physics: the scalar problems (oscillator, bar, membrane) and plane elasticity.
  sim.model = s.string("physics.model");
  if (sim.model != "membrane" && sim.model != "bar" && sim.model != "oscillator" && sim.model != "elasticity")
    throw InputError("physics.model: unknown model '" + sim.model + "' (oscillator, bar, membrane, elasticity)");
  reject_keys(s, sim.model == "elasticity" ? kScalarOnly : kElasticityOnly, sim.model);
  if (sim.model == "elasticity") {
    sim.mesh = std::make_unique<Mesh>(make_mesh(s));
    const ElasticContactData d = elasticity(*sim.mesh, s);
    sim.pair = s.has("method.mass") ? d.velocity : to_string(d.displacement) + "/" + d.velocity;
    sim.problem = build_elastic_contact(*sim.mesh, d);
    sim.dirichlet_parts = d.dirichlet_parts;
    sim.dirichlet_components = d.dirichlet_components;
    sim.components = 2;
    sim.has_plane = d.obstacle;
    sim.plane_point = d.obstacle_point;
    const double norm = std::hypot(d.obstacle_normal.x, d.obstacle_normal.y);  // > 0: checked by the builder
    sim.plane_normal = {d.obstacle_normal.x / norm, d.obstacle_normal.y / norm};
    sim.contact_parts = d.contact_parts;
  } else if (sim.model == "oscillator") {
    if (!s.keys("mesh").empty()) throw InputError("mesh: the oscillator has no mesh (remove the [mesh] table)");
    sim.mesh = std::make_unique<Mesh>(oscillator_mesh());
    sim.pair = "m (one dof)";
    sim.problem = oscillator(*sim.mesh, s);
    sim.dirichlet_parts = {sim.mesh->part_index("right")};
  } else {
    sim.mesh = std::make_unique<Mesh>(make_mesh(s));
    ScalarWaveData d = scalar_wave(*sim.mesh, s, sim.model);
    sim.pair = s.has("method.mass") ? d.velocity : to_string(d.displacement) + "/" + d.velocity;
    sim.problem = build_scalar_wave(*sim.mesh, d);
    sim.dirichlet_parts = d.dirichlet_parts;
  }
  const Mesh& mesh = *sim.mesh;
  sim.constrained_vertices = constrained_vertices(mesh, sim.problem);
  ConstrainedProblem& p = sim.problem;

  // Time and solver.
  sim.dt = s.number("time.dt");
  sim.T = s.number("time.T");
  if (!(sim.dt > 0.0) || !std::isfinite(sim.dt)) throw InputError("time.dt: must be positive");
  if (!(sim.T > 0.0) || !std::isfinite(sim.T)) throw InputError("time.T: must be positive");
  if (sim.T < sim.dt) throw InputError("time.T: shorter than one step (T = " + std::to_string(sim.T) + " < dt = " + std::to_string(sim.dt) + ")");
  const double steps = std::ceil(sim.T / sim.dt - 1e-9);  // T/dt may overflow int (fuzz regression)
  if (!(steps <= std::numeric_limits<int>::max()))
    throw InputError("time.T: T/dt = " + std::to_string(steps) + " steps is more than a run can take (at most 2147483647)");
  sim.n_steps = static_cast<int>(steps);
  sim.output_every = s.integer("output.every", 1);
  if (sim.output_every < 1) throw InputError("output.every: must be at least 1");
  sim.contact_every = s.integer("output.contact_every", 1);
  if (sim.contact_every < 1) throw InputError("output.contact_every: must be at least 1");
  if (sim.model != "elasticity" && s.has("output.contact_every"))
    throw InputError("output.contact_every: only elasticity runs write contact.csv");
  sim.scheme_name = s.string("time.scheme", "midpoint");
  sim.solver_name = s.string("solver.name", "pdas");
  QPOptions options;
  sim.tol = options.tol = s.number("solver.tol", 1e-10);
  if (!(options.tol > 0.0)) throw InputError("solver.tol: must be positive");
  options.max_iterations = s.integer("solver.max_iterations", 0);
  options.pdas_cg_iterations = s.integer("solver.cg_iterations", options.pdas_cg_iterations);
  if (options.pdas_cg_iterations < 0) throw InputError("solver.cg_iterations: must be 0 (no CG) or more");
  try {
    sim.solver = make_step_solver(sim.solver_name, options);
  } catch (const InputError& e) {
    throw InputError("solver.name: " + std::string(e.what()));
  }
  SchemeParameters parameters;
  parameters.beta = s.number("time.beta", parameters.beta);
  parameters.gamma = s.number("time.gamma", parameters.gamma);
  parameters.restitution = s.number("time.restitution", parameters.restitution);
  parameters.condense = s.boolean("solver.condense", parameters.condense);
  sim.scheme = make_time_scheme(sim.scheme_name, p, *sim.solver, sim.dt, parameters);

  // Initial state: U⁰ must lie in K̄^h; V⁰ from C V⁰ = B U̇⁰.
  // (p.unknowns: the rotated components at the contact nodes of an inclined plane.)
  sim.initial.U = initial_field(s, p, "initial.u");
  const double violation = p.max_violation(sim.initial.U);
  if (violation > 1e-12)
    throw InputError("initial.u: the initial state violates the obstacle (by " + std::to_string(violation) + ")");
  sim.initial.V = initial_velocity(p, initial_field(s, p, "initial.v"));
  sim.initial.reaction = Eigen::VectorXd::Zero(p.n_free());

  // Probes (the oscillator's one dof is probed as "mass" unless the scene names others).
  auto add_probe = [&](const std::string& name, const std::vector<double>& c, const std::string& key) {
    if (static_cast<int>(c.size()) != mesh.dim) throw InputError(key + ": expected " + std::to_string(mesh.dim) + " coordinates");
    Probe pr{name, {c[0], mesh.dim == 2 ? c[1] : 0.0}, {}, -1};
    pr.where = locate(mesh, pr.at);
    if (pr.where.cell < 0) throw InputError(key + ": the point lies outside the mesh");
    pr.vertex = nearest_vertex(mesh, pr.at);
    sim.probes.push_back(pr);
  };
  for (const std::string& name : s.keys("output.probes")) add_probe(name, s.numbers("output.probes." + name), "output.probes." + name);
  if (sim.model == "oscillator" && sim.probes.empty()) add_probe("mass", {0.0}, "output.probes");
  return sim;
}

}  // namespace cdyn::app
