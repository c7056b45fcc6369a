// derived_fields.hpp — the arrays a run's field files carry besides u, v and lambda
// (docs/outputs.md, "fields.pvd and fields/*.vtu"):
//   - elasticity: the strain ε, the stress σ (3 × 3, σ_zz = λ tr ε of plane strain) and
//     the von Mises stress, per cell (cell means) and at the vertices (area-weighted
//     averages of the cell values), from the kernel's post/stress.hpp with the λ, μ of
//     every cell (materials by region); output.stress = false leaves them out;
//   - elasticity against a plane: the contact pressure p(a) = F_N(a) / w(a) at the
//     constrained vertices of Γ_C (post/contact_pressure.hpp, contact.csv's `pressure`),
//     0 at every other vertex;
//   - elasticity with friction (problems/friction.hpp): the tangential force (the
//     reaction on the tangential unknown, along t = (−n_y, n_x)), the last step's slip
//     along t and the status (0 open, 1 stick, 2 slip) at the friction vertices, as
//     contact.csv has them; 0, 0 and −1 at every other vertex;
//   - elasticity on a mesh with regions (gmsh physical surfaces, where materials are
//     given): the region index of each cell.
// The scalar models get none of them: their files are those of cdyn::io alone.
// The kernel computes, cdyn::io writes; this file only names and lays out the arrays.
#pragma once

#include <Eigen/Core>
#include <optional>

#include "cdyn/fields_output.hpp"
#include "cdyn/post/contact_pressure.hpp"
#include "simulation.hpp"

namespace cdyn::app {

class DerivedFields {
 public:
  explicit DerivedFields(const Simulation& sim);

  // The arrays of the state U_full (all dofs of W^h) with the step's reaction in (x, y)
  // (post/contact_force.hpp's reaction_xy; empty: no reaction yet).
  // `state`: the friction arrays' source (its reaction, slip and status).
  // On subdomains (partition.hpp) the vertex arrays of this rank's vertices, but for
  // the vertex stress, which needs the neighbouring ranks' cells: see below.
  ExtraFields operator()(const Eigen::VectorXd& U_full, const Eigen::VectorXd& reaction_xy,
                         const State* state = nullptr) const;

  // A run on subdomains: the vertex averages of σ, ε (and von Mises of the averaged σ)
  // from the cell arrays gathered on the whole mesh, inserted after u, v and lambda, as
  // operator() places them in a serial run.
  void add_vertex_stress(const Mesh& whole, ExtraFields& gathered) const;

 private:
  const Simulation& sim_;
  std::optional<ContactPressure> contact_;
  std::vector<double> weight_;  // w(a) of contact_'s vertices over the whole Γ_C
  bool friction_ = false;       // the friction arrays (on subdomains: friction nodes on any rank)
};

}  // namespace cdyn::app
