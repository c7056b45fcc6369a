// simulation.hpp — from a scene's typed description (scene_spec.hpp) to everything a
// run needs: the mesh, the constrained problem, the initial state, the step solver and
// the scheme.  The kernel itself knows no scene key: an InputError it throws names its
// own parameter, which becomes the scene key here (scene_key).
#pragma once

#include <memory>
#include <string>
#include <vector>

#include "cdyn/problems/constrained_problem.hpp"
#include "cdyn/problems/elastic_contact.hpp"
#include "cdyn/mesh/mesh.hpp"
#include "cdyn/mesh/point_location.hpp"
#include "cdyn/qp/step_solver.hpp"
#include "cdyn/schemes/time_scheme.hpp"
#include "partition.hpp"
#include "scene_spec.hpp"

namespace cdyn::app {

struct Probe {
  std::string name;
  Point at;
  CellPoint where;   // cell and reference point of `at` (on subdomains: −1 where another rank's)
  int vertex = -1;   // nearest vertex, where λ lives (on subdomains: −1 where another rank owns it)
};

struct Simulation {
  SceneSpec spec;  // the scene as read and checked
  std::string scene_name, model, pair, scheme_name, solver_name;
  double dt = 0, T = 0, tol = 0;
  int n_steps = 0, output_every = 1;
  // The threads of the kernel's loops (solver.threads or OMP_NUM_THREADS) and of the BLAS
  // under CHOLMOD (the environment's; 0: a BLAS that cannot tell; linalg/threads.hpp).
  int threads = 1, blas_threads = 0;
  int contact_every = 1;  // period of contact.csv's rows (elasticity)
  // The wall time make_simulation took: the mesh, the assembly, the mass model, the step
  // matrix and the scheme's set-up (its factorizations wait for the first step).
  double setup_seconds = 0;
  std::unique_ptr<Mesh> mesh;  // the problem's: on subdomains, this rank's cells
  ConstrainedProblem problem;
  ProblemSizes whole;  // the whole problem's (a run on subdomains holds a share)
  // A run on subdomains (solver.partition): the whole mesh, the maps, the owners.
  std::unique_ptr<Partition> partition;
  State initial;
  std::unique_ptr<StepSolver> solver;
  std::unique_ptr<TimeScheme> scheme;
  std::vector<Probe> probes;
  std::vector<int> dirichlet_parts;        // for condition (12)
  std::vector<int> dirichlet_components;   // elasticity's rollers (empty: all components fixed)
  std::vector<int> constrained_vertices;   // vertices carrying a constraint (sorted)

  // Elasticity (physics.model = "elasticity"): two displacement components and rigid
  // obstacles (the problem's contact_nodes and obstacles, problems/elastic_contact.hpp).
  // The scalar models keep components = 1 and no rigid obstacle.
  int components = 1;
  bool has_obstacle = false;
  CellMaterials materials;  // elasticity: ρ, λ, μ of every cell (materials by region), for σ in the fields

  // What the outputs and the reductions over the ranks follow, alike on every rank (on
  // subdomains a rank's cells may touch no rough obstacle, no moving one, no loaded part):
  // friction nodes (problems/friction.hpp), data in t (problems/data_work.hpp), in the
  // problem of any rank.
  bool with_friction = false;
  bool data_in_t = false;
};

// Builds and checks everything (bad input throws InputError naming the key).  On
// subdomains, `cells`: this rank's cells if given (a resumed run keeps the stopped run's
// partition), else the partition's of solver.partition.
Simulation make_simulation(const SceneSpec& spec, const std::vector<int>* cells = nullptr);
inline Simulation make_simulation(const Scene& scene, const std::vector<int>* cells = nullptr) {
  return make_simulation(read_scene(scene), cells);
}

// The mesh a scene describes (mesh.kind: interval, unit_square, unit_cube, gmsh).
Mesh make_mesh(const SceneSpec& spec);

}  // namespace cdyn::app
