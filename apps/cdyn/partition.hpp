// partition.hpp — a run on subdomains (solver.partition, docs/distributed.md,
// "Subdomains"): every rank builds the scene's problem on the sub-mesh of its own cells
// (mesh/sub_mesh.hpp) and steps the scheme on it, the ranks' step QPs summed and solved
// together (qp/petsc/backend.hpp's subdomain solver).
//
// What a run reports is then a sum or a maximum over the ranks.  Sums over cells — the
// energies ½VᵀCV and ½UᵀAU − LᵀU, the momentum, the damping's work, the load's work —
// are the ranks' sums added.  Sums over vertices — the active set, the contact force,
// a moving obstacle's work — count a vertex that several subdomains hold once, by its
// owner, the lowest rank holding it.  The penetration and the violation are maxima.  A
// probe is evaluated by the rank holding its cell, its multiplier by the owner of its
// vertex.  contact.csv and the field files are gathered on the first rank, which alone
// writes.  In a serial run every function here is the identity.
#pragma once

#include <Eigen/Core>
#include <string>
#include <vector>

#include "cdyn/fields_output.hpp"
#include "cdyn/mesh/sub_mesh.hpp"
#include "cdyn/post/contact_pressure.hpp"
#include "cdyn/schemes/time_scheme.hpp"

namespace cdyn::app {

struct Simulation;

// A problem's sizes and its mesh's largest cell diameter, for the summary.
struct ProblemSizes {
  int dofs = 0, free = 0, velocity = 0, constraints = 0;
  double h = 0.0;
};

struct Partition {
  Mesh whole;   // the scene's mesh (every rank reads it)
  SubMesh sub;  // this rank's cells (Simulation::mesh, the problem's, is a copy of sub.mesh)
  std::vector<int> local_cell, local_vertex;  // of each of the whole mesh's: this rank's, −1
  std::vector<char> owns_vertex;    // of this rank's vertices, those it owns
  int whole_dofs = 0, whole_free = 0;  // the whole problem's dofs and free unknowns
  int interface_vertices = 0;          // the vertices several ranks hold (what products exchange)
  // On the first rank: the whole mesh's constrained vertices (sorted) and the normal of
  // the constraint at each (elasticity), for condition (12) on the whole mesh.
  std::vector<int> constrained_vertices;
  std::vector<Point> normals;
  std::vector<int> in_whole;        // the whole problem's free unknown of each of this rank's
  std::vector<char> owns_unknown;   // of this rank's free unknowns, those it owns
};

// This rank's cells of `whole` — its slab across x (`how` = "slabs", mesh/sub_mesh.hpp's
// slab_cells), its part of the cells' dual graph by PT-Scotch ("graph"), or `cells` if
// given (a resumed run's, InputError
// unless the ranks' lists deal out every cell once) — and the maps between the two
// meshes; the ownership is number_unknowns's, once the problem is built.  Collective.
Partition make_partition(Mesh whole, const std::string& how, const std::vector<int>* cells = nullptr);

// The whole problem's free unknown of each of sim.problem's (sim.partition set), who
// owns it, the whole problem's numbers of dofs and free unknowns, and on the first rank
// its constrained vertices (collective; after sim.constrained_vertices).
void number_unknowns(Simulation& sim);

// The whole problem's sizes (on subdomains, after number_unknowns; collective).
ProblemSizes whole_sizes(const Simulation& sim);

// The reductions over the ranks (identities in a serial run); collective.
double summed(const Simulation& sim, double x);
double largest(const Simulation& sim, double x);
Energy summed(const Simulation& sim, const Energy& E);
void summed(const Simulation& sim, std::vector<double>& x);
bool on_any_rank(const Simulation& sim, bool b);

// A vector on sim.problem's free unknowns with the unknowns other ranks own set to 0:
// its sum over unknowns added over the ranks counts each of the whole problem's once.
Eigen::VectorXd owned_part(const Simulation& sim, const Eigen::VectorXd& x);

// A point's coordinates each summed over the ranks.
Point summed(const Simulation& sim, const Point& x);

// Whether this process writes the run's files: the first rank of a run on subdomains.
bool writes_files(const Simulation& sim);

// w(a) = ∫_{Γ_C} φ_a ds of each of contact.vertices() (built on sim.problem) over the
// whole Γ_C: on subdomains the sum of the ranks' shares, the facets being each one
// rank's (collective).
std::vector<double> whole_contact_weights(const Simulation& sim, const ContactPressure& contact);

// Tresca's nodal thresholds s_a = ∫_{Γ_C} s φ_a of sim.problem's friction nodes over the
// whole Γ_C, as whole_contact_weights: each rank integrated over its own facets
// (collective on subdomains; nothing in a serial run).
void whole_friction_thresholds(Simulation& sim);

// The field arrays of this rank's vertices and cells placed on the whole mesh, on the
// first rank (nothing on the others): a vertex's values from its owner, a cell's from
// its rank (collective).
ExtraFields gathered_on_first_rank(const Simulation& sim, const ExtraFields& local);

}  // namespace cdyn::app
