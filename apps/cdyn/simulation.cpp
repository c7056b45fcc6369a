// simulation.cpp — a scene's typed description → kernel structures.
#include "simulation.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>

#include "cdyn/base/error.hpp"
#include "cdyn/gmsh_mesh.hpp"
#include "cdyn/linalg/threads.hpp"
#include "cdyn/problems/data_work.hpp"
#include "cdyn/problems/elastic_contact.hpp"
#include "cdyn/problems/oscillator.hpp"
#include "cdyn/problems/scalar_wave.hpp"
#include "cdyn/qp/petsc/backend.hpp"
#include "diagnostics.hpp"

namespace cdyn::app {

namespace {

// "all" or a list of part names → part indices.
std::vector<int> parts(const Mesh& mesh, const std::vector<std::string>& names, const std::string& key) {
  std::vector<int> out;
  for (const std::string& name : names) {
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

// The one-dof oscillator (problems/oscillator.hpp): physics.m, physics.k, physics.f = F(t).
ConstrainedProblem oscillator(const Mesh& mesh, const SceneSpec& s) {
  OscillatorData o;
  o.m = s.physics.m;
  o.k = s.physics.k;
  o.F = s.physics.f[0].field;
  o.load_is_constant = !s.physics.f[0].depends_on_time;
  o.obstacle = s.obstacle.enabled;
  o.g = s.obstacle.g.field(Point{}, 0.0);
  return build_oscillator(mesh, o);
}

// The membrane (unit square or gmsh) and the bar (interval).
ScalarWaveData scalar_wave(const Mesh& mesh, const SceneSpec& s) {
  if (s.physics.model == "bar" && mesh.dim != 1)
    throw InputError("physics.model: the bar needs a 1D mesh (mesh.kind = interval)");
  ScalarWaveData d;
  d.mass = s.method.mass;
  d.rho = s.physics.rho;
  d.kappa = s.physics.stiffness;
  d.f = s.physics.f[0].field;
  d.load_is_constant = !s.physics.f[0].depends_on_time;
  d.dirichlet_parts = parts(mesh, s.dirichlet.parts, "dirichlet.parts");
  d.dirichlet_value = s.dirichlet.value[0].field;
  d.obstacle_on_all_vertices = s.obstacle.where == std::vector<std::string>{"vertices"};
  if (!d.obstacle_on_all_vertices) d.obstacle_parts = parts(mesh, s.obstacle.where, "obstacle.where");
  d.obstacle = s.obstacle.enabled;
  d.obstacle_g = s.obstacle.g.field;
  d.obstacle_moves = s.obstacle.g.depends_on_time;
  return d;
}

// One field per component of a datum: a scalar's one expression, or a vector's one per
// coordinate of the mesh (absent: zero).  InputError naming the key when a vector has
// another number of entries than the mesh has coordinates.
std::vector<Field> fields(const std::vector<Expression>& e, int components) {
  if (e.empty()) return std::vector<Field>(components, zero_field);
  if (static_cast<int>(e.size()) != components)
    throw InputError(e[0].key + ": expected " + std::to_string(components) + " entries, one per coordinate of the " +
                     std::to_string(components) + "D mesh (got " + std::to_string(e.size()) + ")");
  std::vector<Field> out;
  for (const Expression& c : e) out.push_back(c.field);
  return out;
}

bool depends_on_time(const std::vector<Expression>& e) {
  return std::any_of(e.begin(), e.end(), [](const Expression& c) { return c.depends_on_time; });
}

// A vector of numbers given for a dim-dimensional mesh (empty: `fallback`).
Point vector_point(const std::vector<double>& c, int dim, const std::string& key, Point fallback) {
  if (c.empty()) return fallback;
  if (static_cast<int>(c.size()) != dim)
    throw InputError(key + ": expected " + std::to_string(dim) + " numbers, one per coordinate of the " +
                     std::to_string(dim) + "D mesh (got " + std::to_string(c.size()) + ")");
  return {c[0], c[1], dim == 3 ? c[2] : 0.0};
}

// A rigid obstacle of the scene: a plane (moving when its point depends on t) or a
// gap function.  The default plane is y = 0 in the plane, z = 0 in space, the body above.
RigidObstacle rigid(const Mesh& mesh, const SceneSpec::Rigid& r) {
  std::vector<int> where;
  if (r.where == std::vector<std::string>{"boundary"}) {
    for (std::size_t k = 0; k < mesh.part_names.size(); ++k) where.push_back(static_cast<int>(k));
    where.push_back(-1);  // and the untagged boundary facets
  } else {
    where = parts(mesh, r.where, r.key + ".where");
  }
  RigidObstacle o;
  if (r.gap) {
    o.gap = r.gap->field;
    o.moves = r.gap->depends_on_time;
    o.contact_parts = where;
  } else {
    const int dim = mesh.dim;
    const std::vector<Field> p = fields(r.point, dim);
    const Point n = vector_point(r.normal, dim, r.key + ".normal", dim == 3 ? Point{0, 0, 1} : Point{0, 1, 0});
    auto at = [p, dim](double t) { return Point{p[0](Point{}, t), p[1](Point{}, t), dim == 3 ? p[2](Point{}, t) : 0.0}; };
    try {
      if (depends_on_time(r.point))
        o = RigidObstacle::moving_plane(at, n, where);
      else
        o = RigidObstacle::plane(at(0.0), n, where);
    } catch (const InputError& e) {
      throw InputError(r.key + "." + e.parameter() + ": " + e.message());
    }
  }
  o.name = r.name;
  o.friction.law = parse_friction_law(r.friction);
  if (r.mu) o.friction.mu = r.mu->field;
  if (r.threshold) o.friction.threshold = r.threshold->field;
  return o;
}

// The index of region `name` of the mesh (a gmsh physical surface), for the key `key`.
int region(const Mesh& mesh, const std::string& name, const std::string& key) {
  const auto it = std::find(mesh.region_names.begin(), mesh.region_names.end(), name);
  if (it != mesh.region_names.end()) return static_cast<int>(it - mesh.region_names.begin());
  std::string known;
  for (const std::string& r : mesh.region_names) known += (known.empty() ? "" : ", ") + r;
  throw InputError(key + ": the mesh has no region '" + name + "' (" +
                   (known.empty() ? "it has no regions: physical surfaces of a gmsh mesh" : "regions: " + known) + ")");
}

// Elasticity in plane strain or in space with frictionless contact against rigid
// obstacles (problems/elastic_contact.hpp): the materials (one, or one per named region),
// the body force f + ρ·gravity, Dirichlet and Neumann parts, Γ_C and the obstacles.
// Every vector has one entry per coordinate of the mesh.
ElasticContactData elasticity(const Mesh& mesh, const SceneSpec& s) {
  if (mesh.dim != 2 && mesh.dim != 3)
    throw InputError("physics.model: elasticity needs a 2D (plane strain) or 3D mesh");
  const int dim = mesh.dim;
  ElasticContactData d;
  d.mass = s.method.mass;
  d.lambda = s.physics.lame.lambda;
  d.mu = s.physics.lame.mu;
  d.rho = s.physics.rho;
  for (const auto& m : s.physics.materials)
    d.region_materials.push_back({region(mesh, m.name, "materials." + m.name), {m.rho, m.lame.lambda, m.lame.mu}});
  // f + ρ g: the body force per unit volume (gravity given as an acceleration; the
  // kernel adds ρ g with the density of each cell).
  auto to = [dim](std::array<Field, 3>& a, const std::vector<Field>& f) {
    for (int k = 0; k < dim; ++k) a[k] = f[k];
  };
  to(d.f, fields(s.physics.f, dim));
  const Point g = vector_point(s.physics.gravity, dim, "physics.gravity", Point{});
  d.gravity = {g.x, g.y, g.z};
  d.dirichlet_parts = parts(mesh, s.dirichlet.parts, "dirichlet.parts");
  d.dirichlet_components = s.dirichlet.components;
  if (dim == 2 && std::find(d.dirichlet_components.begin(), d.dirichlet_components.end(), 2) != d.dirichlet_components.end())
    throw InputError("dirichlet.components: \"z\" is not a component of a 2D body");
  to(d.dirichlet_value, fields(s.dirichlet.value, dim));
  d.neumann_parts = parts(mesh, s.neumann.parts, "neumann.parts");
  to(d.traction, fields(s.neumann.traction, dim));
  d.load_is_constant = !(depends_on_time(s.physics.f) || depends_on_time(s.neumann.traction));
  d.obstacle = s.obstacle.enabled;
  for (const SceneSpec::Rigid& r : s.obstacle.rigid) d.obstacles.push_back(rigid(mesh, r));
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

// The unknowns of an initial datum (one expression per component; p.unknowns: the
// rotated components at the contact nodes of an inclined plane).
Eigen::VectorXd initial_field(const ConstrainedProblem& p, const std::vector<Expression>& e) {
  return p.unknowns(p.W->interpolate(fields(e, p.W->components()), 0.0));
}

void build_problem(Simulation& sim, const std::vector<int>* cells) {
  const SceneSpec& s = sim.spec;
  if (s.physics.model == "oscillator") {
    sim.mesh = std::make_unique<Mesh>(oscillator_mesh());
    sim.pair = "m (one dof)";
    sim.problem = oscillator(*sim.mesh, s);
    sim.dirichlet_parts = {sim.mesh->part_index("right")};
    return;
  }
  if (s.solver.partition == "none") {
    sim.mesh = std::make_unique<Mesh>(make_mesh(s));
  } else {  // the problem on this rank's cells
    // (under mpirun the other commands run on rank 0 alone, the others serving its
    // solves: the partition's collective calls would wait for them forever)
    if (petsc::launched_in_parallel() && !petsc::every_rank_running())
      throw InputError("solver.partition: under mpirun only `cdyn run` runs on subdomains; run this command "
                       "without mpirun (one process holds every cell)");
    sim.partition = std::make_unique<Partition>(make_partition(make_mesh(s), s.solver.partition, cells));
    sim.mesh = std::make_unique<Mesh>(sim.partition->sub.mesh);
  }
  sim.pair = s.method.mass.name();
  if (s.physics.model != "elasticity") {
    const ScalarWaveData d = scalar_wave(*sim.mesh, s);
    sim.problem = build_scalar_wave(*sim.mesh, d);
    sim.dirichlet_parts = d.dirichlet_parts;
    return;
  }
  const ElasticContactData d = elasticity(*sim.mesh, s);
  sim.problem = build_elastic_contact(*sim.mesh, d);
  sim.with_friction = on_any_rank(sim, !sim.problem.friction.empty());
  whole_friction_thresholds(sim);  // (on subdomains: integrated over every rank's facets)
  sim.dirichlet_parts = d.dirichlet_parts;
  sim.dirichlet_components = d.dirichlet_components;
  sim.components = sim.mesh->dim;
  sim.has_obstacle = d.obstacle;
  sim.materials = cell_materials(*sim.mesh, d);
}

// The probes, each located in the whole mesh; on subdomains its cell is this rank's, or
// −1, and its vertex too where this rank owns it (partition.hpp).
void add_probes(Simulation& sim) {
  const Partition* part = sim.partition.get();
  const Mesh& mesh = part ? part->whole : *sim.mesh;
  auto add = [&](const std::string& name, const std::vector<double>& c, const std::string& key) {
    if (static_cast<int>(c.size()) != mesh.dim)
      throw InputError(key + ": expected " + std::to_string(mesh.dim) + " coordinates");
    Probe pr{name, {c[0], mesh.dim >= 2 ? c[1] : 0.0, mesh.dim == 3 ? c[2] : 0.0}, {}, -1};
    pr.where = locate(mesh, pr.at);
    if (pr.where.cell < 0) throw InputError(key + ": the point lies outside the mesh");
    pr.vertex = nearest_vertex(mesh, pr.at);
    if (part) {
      pr.where.cell = part->local_cell[pr.where.cell];
      pr.vertex = part->local_vertex[pr.vertex];
      if (pr.vertex >= 0 && !part->owns_vertex[pr.vertex]) pr.vertex = -1;
    }
    sim.probes.push_back(pr);
  };
  for (const auto& [name, c] : sim.spec.output.probes) add(name, c, "output.probes." + name);
  // the oscillator's one dof is probed as "mass" unless the scene names others
  if (sim.model == "oscillator" && sim.probes.empty()) add("mass", {0.0}, "output.probes");
}

}  // namespace

Mesh make_mesh(const SceneSpec& s) {
  return with_scene_keys(s, [&] {
    if (s.mesh.kind == "interval") return interval_mesh(s.mesh.n, s.mesh.length);
    if (s.mesh.kind == "unit_square") return unit_square_mesh(s.mesh.n);
    if (s.mesh.kind == "unit_cube") return unit_cube_mesh(s.mesh.n);
    return read_mesh(s.mesh.file, s.mesh.set);
  });
}

// The step solver of solver.name on solver.backend; on subdomains, of this rank's share.
std::unique_ptr<StepSolver> make_solver(const Simulation& sim) {
  const SceneSpec::Solver& v = sim.spec.solver;
  if (sim.partition) return petsc::make_petsc_subdomain_solver(sim.partition->in_whole, v.options, v.pc, v.name);
  if (v.backend == "petsc") return petsc::make_petsc_step_solver(v.name, v.options, v.pc);
  return make_step_solver(v.name, v.options);
}

// What the PETSc back end takes (docs/distributed.md): in saddle form pdas alone, and
// no snesvi with friction; and what a run under mpirun takes: that back end.
void check_backend(const Simulation& sim) {
  const SceneSpec::Solver& v = sim.spec.solver;
  if (v.backend == "native" && petsc::launched_in_parallel())
    throw InputError("solver.backend: \"native\" runs on one process; under mpirun with more than one, set "
                     "solver.backend = \"petsc\"");
  if (v.backend != "petsc") return;
  if (sim.partition && !sparse_mass(*sim.problem.mass))
    throw InputError(sim.spec.method.key + ": with " + sim.pair + " the step is in saddle form (H^h continuous), "
                     "which a run on subdomains (solver.partition) does not solve: no explicit step matrix");
  // (in saddle form the back end's pdas factorizes each reduced saddle system by MUMPS)
  if (!sparse_mass(*sim.problem.mass) && v.name != "pdas")
    throw InputError("solver.name: with " + sim.pair + " the step is in saddle form (H^h continuous), which the "
                     "petsc back end solves by pdas only (" + v.name + " needs an explicit step matrix)");
  if (!sparse_mass(*sim.problem.mass) && !v.pc.empty())
    throw InputError("solver.pc: with " + sim.pair + " the step is in saddle form (H^h continuous), solved by "
                     "MUMPS's factorization on the petsc back end: no preconditioner");
  // (measured: with friction's inner QPs SNESVI leaves its pdas finish a CG that
  // diverges at the first steps, in the plane and in space; pdas and TAO run)
  if (sim.with_friction && v.name == "snesvi")
    throw InputError("solver.name: snesvi does not solve friction's step QPs on the petsc back end (its CG "
                     "diverges); use pdas or a tao_ solver");
}

// solver.linear = "auto": the CG path where it was measured to beat the factor —
// tetrahedral meshes from about 10⁴ step-QP unknowns (P1+'s bubbles, eliminated by the
// scheme, not counted), where the factor's fill makes every row update and
// refactorization dear (docs/performance.md, "Three dimensions": CG 2–9× faster in
// contact from there) — if the step matrix is explicit and the scheme is not the
// energy-exact one (its correction needs solves below the QP tolerance); the factor
// otherwise (2D, small 3D problems, saddle forms).  The same rule picks how rank 0
// solves the full-step reconstruction's QP on the petsc back end, whose step QP is CG's.
namespace {
bool cg_path_pays(const Simulation& sim) {
  const SceneSpec& s = sim.spec;
  const ConstrainedProblem& p = sim.problem;
  const int bubbles = p.W->element() == Element::P1Bubble && s.time.parameters.condense
                          ? p.W->mesh().n_cells() * p.W->components()
                          : 0;
  return sim.mesh->dim == 3 && p.n_free() - bubbles >= 10000 && sparse_mass(*p.mass) &&
         s.time.scheme != "discrete_gradient";
}

// time.scheme = "auto": the kernel's choice (recommended_scheme), except on the CG path
// and on subdomains, whose CG solves stop at the QP tolerance, above what the
// energy-exact scheme's correction needs (it runs there when asked for): there the
// midpoint rule with its full-step reconstruction, or with friction the kernel's choice
// for it (docs/friction.md) by the mass alone.
std::string auto_scheme(const Simulation& sim) {
  if (!sim.spec.solver.options.pdas_cg_only && !sim.partition) return recommended_scheme(sim.problem);
  if (sim.with_friction)
    return sim.problem.mass->is_invertible() ? "midpoint_end" : "backward_euler";
  return "midpoint";
}
}  // namespace

Simulation make_simulation(const SceneSpec& spec, const std::vector<int>* cells) {
  const auto start = std::chrono::steady_clock::now();
  Simulation sim;
  sim.spec = spec;
  const SceneSpec& s = sim.spec;
  // The threads of the kernel's loops are the process's (the OpenMP runtime's): set for
  // every simulation, so that a run without solver.threads after one with it in the same
  // process (cdyn study, Python) gets the environment's count back.  The BLAS keeps its
  // own (OPENBLAS_NUM_THREADS), which would change the factor's round-off: with it fixed,
  // a run is the same bit for bit whatever solver.threads (linalg/threads.hpp).
  set_thread_count(s.solver.threads);
  sim.threads = thread_count();
  sim.blas_threads = blas_thread_count();
  sim.scene_name = s.name;
  sim.model = s.physics.model;
  with_scene_keys(s, [&] { build_problem(sim, cells); });
  sim.data_in_t = on_any_rank(sim, has_data_in_t(sim.problem));
  sim.constrained_vertices = constrained_vertices(*sim.mesh, sim.problem);
  ConstrainedProblem& p = sim.problem;

  sim.dt = s.time.dt;
  sim.T = s.time.T;
  sim.n_steps = s.time.n_steps;
  sim.output_every = s.output.every;
  sim.contact_every = s.output.contact_every;
  if (s.solver.linear_auto) sim.spec.solver.options.pdas_cg_only = cg_path_pays(sim);  // (refused with petsc)
  sim.scheme_name = s.time.scheme != "auto" ? s.time.scheme : auto_scheme(sim);
  // The full-step reconstruction's QP solved as the step's: by CG alone on that path.
  // On the petsc back end rank 0 solves it with the native pdas, by the same rule
  // (docs/distributed.md: there the factor of ZᵀAZ was rank 0's serial work), but not
  // for the energy-exact scheme's corrections.  (On subdomains the ranks solve it together
  // with the step's solver, its companion: this flag is not read.)
  sim.spec.time.parameters.reconstruct_by_cg =
      s.solver.options.pdas_cg_only ||
      (s.solver.backend == "petsc" && sim.scheme_name != "discrete_gradient" && cg_path_pays(sim));
  sim.solver_name = s.solver.name;
  // (without a sparse M the step QP is in saddle form: no explicit S for CG alone)
  if (s.solver.options.pdas_cg_only && !sparse_mass(*p.mass))
    throw InputError("solver.linear: the CG path needs an explicit step matrix; with " + sim.pair +
                     " the step is in saddle form (H^h continuous), solved by UMFPACK: use solver.linear = \"factor\"");
  sim.tol = s.solver.options.tol;
  check_backend(sim);
  with_scene_keys(s, [&] {
    if (sim.partition) number_unknowns(sim);
    sim.whole = whole_sizes(sim);
    sim.solver = make_solver(sim);
    sim.scheme = make_time_scheme(sim.scheme_name, p, *sim.solver, sim.dt, s.time.parameters);
  });

  // Initial state: U⁰ must lie in K̄^h; V⁰ from C V⁰ = B U̇⁰.
  sim.initial.U = initial_field(p, s.initial.u);
  const double violation = largest(sim, p.max_violation(sim.initial.U));
  if (violation > 1e-12) infeasible_initial_state(sim, violation);  // names initial.u or obstacle.normal
  sim.initial.V = initial_velocity(p, initial_field(p, s.initial.v));
  sim.initial.reaction = Eigen::VectorXd::Zero(p.n_free());
  sim.scheme->initialize(sim.initial);  // e.g. U⁰'s massless part from eq. (14)
  add_probes(sim);
  sim.setup_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return sim;
}

}  // namespace cdyn::app
