// scene_spec.hpp — a scene read and validated once into a typed description.
//
// Every key of docs/scenes.md is read here, in one place, with its default, its type
// and the checks that need no mesh (ranges, keys that belong to another model, keys
// that conflict); what needs the mesh (part names, probe points, the bar's 1D mesh) is
// checked when the simulation is built from this description (simulation.hpp).  An
// error names the key: "time.dt: must be positive".
#pragma once

#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "cdyn/base/error.hpp"
#include "cdyn/fe/field.hpp"
#include "cdyn/mass/mass_spec.hpp"
#include "cdyn/problems/elastic_contact.hpp"
#include "cdyn/qp/bound_qp.hpp"
#include "cdyn/schemes/time_scheme.hpp"
#include "scene.hpp"

namespace cdyn::app {

// A datum given as an expression: the key it came from, its text, the field.
struct Expression {
  std::string key, text;
  Field field;
  bool depends_on_time = false;
};

struct SceneSpec {
  std::string name, source;  // the scene's name; its file ("" or "default" for the embedded one)

  struct Mesh {
    std::string kind;          // interval | unit_square | unit_cube | gmsh | none (the oscillator)
    int dim = 0;               // 1, 2, 3 as the kind fixes it; 0 for a gmsh file (known once read)
    int n = 0;                 // cells per side (interval, unit_square, unit_cube)
    double length = 1.0;       // interval
    std::string file;          // gmsh: .geo or .msh, resolved against the scene's directory
    std::vector<std::pair<std::string, double>> set;  // mesh.set: gmsh parameters of a .geo (-setnumber)
  } mesh;

  struct Physics {
    std::string model;           // oscillator | bar | membrane | elasticity
    double rho = 1.0;            // density
    double stiffness = 1.0;      // bar: E; membrane: the tension
    Lame lame;                   // elasticity
    double m = 1.0, k = 1.0;     // oscillator
    // Elasticity's vectors have one entry per coordinate of the mesh (2 or 3); an
    // absent one is empty (zero).  simulation.cpp matches them with the mesh.
    std::vector<Expression> f;   // the load: one expression (scalar models) or a vector
    std::vector<double> gravity; // elasticity: an acceleration, added as ρ g
    struct Material {            // elasticity: [materials.NAME], NAME a region of the mesh
      std::string name;
      double rho = 1.0;
      Lame lame;
    };
    std::vector<Material> materials;
  } physics;

  struct Method {
    MassSpec mass;               // the pair or classical mass (W = P1 for the classical ones)
    std::string key;             // the key it came from: method.pair or method.mass
  } method;

  struct Dirichlet {
    std::vector<std::string> parts;   // part names, or "all"
    std::vector<int> components;      // elasticity: the fixed components (empty: all)
    std::vector<Expression> value;
  } dirichlet;

  struct Neumann {
    std::vector<std::string> parts;
    std::vector<Expression> traction;
  } neumann;

  // Elasticity: one rigid obstacle (problems/rigid_obstacle.hpp), a plane through p(t)
  // with normal n, or a surface given by its gap function φ(x, y, z, t).
  struct Rigid {
    std::string key;                  // "obstacle" or "obstacles[k]", for messages
    std::string name;
    std::vector<std::string> where;   // Γ_C: part names, or "boundary" (every boundary facet)
    std::vector<Expression> point;    // p(t), one expression per coordinate (plane; empty: the origin)
    std::vector<double> normal;       // n (plane; empty: the default, e_y in the plane, e_z in space)
    std::optional<Expression> gap;    // φ(x, y, z, t) (a curved obstacle), instead of point/normal
    // Friction (problems/friction.hpp): the obstacle's own keys (friction, mu,
    // threshold), else the scene's [contact] table; mu and threshold in x, y, z.
    std::string friction = "none";    // none | tresca | coulomb
    std::optional<Expression> mu, threshold;
    std::string friction_key, mu_key, threshold_key;  // where each came from, for messages
  };

  struct Obstacle {
    bool enabled = true;
    std::vector<std::string> where;   // scalar models: "vertices" or part names
    Expression g;                      // scalar models: the lower bound u ≥ g(x, y, t)
    std::vector<Rigid> rigid;         // elasticity: [obstacle] and the tables of [[obstacles]]
  } obstacle;

  struct Initial {
    std::vector<Expression> u, v;     // one per component
  } initial;

  struct Time {
    std::string scheme = "auto";  // auto: the kernel's recommended_scheme() for the problem
    double dt = 0.0, T = 0.0;
    int n_steps = 0;
    SchemeParameters parameters;
  } time;

  struct Solver {
    std::string name = "pdas";
    QPOptions options;
    int threads = 0;  // solver.threads: the kernel's loops (0: the environment's count, OMP_NUM_THREADS)
    // solver.backend: "native" (the kernel's solvers, one process) or "petsc" (the step QP
    // on the ranks of mpirun, qp/petsc/petsc_step_solver.hpp); solver.pc: the
    // preconditioner of its Krylov solves (empty: the solver's default)
    std::string backend = "native", pc;
    // solver.partition: "none" (rank 0 holds the whole problem, the other ranks a share of
    // each step QP's rows), "slabs" or "graph" (each rank builds and steps the problem on
    // its own cells: a slab across x, or its part of PT-Scotch's partition; partition.hpp)
    std::string partition = "none";
    // solver.linear = "auto": the CG path or the factor chosen per problem at set-up
    // (simulation.cpp, cg_path_pays)
    bool linear_auto = false;
  } solver;

  // `units`: the names of the units of length, force and time the scene's numbers are
  // in ("mm, N, s"), for the plots' axes and summary.json; empty when not given.
  struct Units {
    std::string length, force, time;
  } units;

  struct Output {
    int every = 1, contact_every = 1;  // default: about 100 to 200 frames per run
    bool fields = true, plots = true;
    bool stress = true;        // elasticity: σ, ε, von Mises in the field files
    bool wellposed = true;     // condition (12) in summary.json (its factorizations fill much more in 3D)
    int checkpoint_every = 0;  // steps between two checkpoints (0: none; checkpoint.hpp)
    std::vector<std::pair<std::string, std::vector<double>>> probes;  // name, coordinates
  } output;

  std::string exact_solution;  // exact.solution, or empty

  // What the scene asks that is accepted but probably not meant (e.g. a T that is no
  // multiple of dt): printed and listed in summary.json's "warnings".
  std::vector<std::string> warnings;

};

// Reads and checks every key of the scene.  InputError naming the key.
SceneSpec read_scene(const Scene& scene);

// The scene key that a kernel parameter name comes from ("dt" → "time.dt", "rho" →
// "physics.rho", "pair" → method.pair or method.mass, ...), for the kernel's
// InputError::parameter(); empty when the parameter is not a scene key.
// (message: the kernel's, which names the obstacle an obstacle's parameter belongs to)
std::string scene_key(const std::string& parameter, const SceneSpec& spec, const std::string& message = "");

// Runs f; a kernel InputError naming a parameter is given the scene key instead
// ("dt: must be positive" → "time.dt: must be positive").
template <class F>
auto with_scene_keys(const SceneSpec& spec, F&& f) -> decltype(f()) {
  try {
    return f();
  } catch (const InputError& e) {
    const std::string key = e.parameter().empty() ? "" : scene_key(e.parameter(), spec, e.message());
    if (key.empty()) throw;
    throw InputError(key + ": " + e.message());
  }
}

}  // namespace cdyn::app
