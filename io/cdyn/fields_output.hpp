// fields_output.hpp — the fields of a run for ParaView: fields.pvd + fields/*.vtu.
//
// Every output.every steps (and at step 0 and the last step) one VTK XML
// UnstructuredGrid file holds the mesh (VTK_TETRA cells in 3D, triangles in 2D,
// VTK_LINE cells in 1D, the points of 1D and 2D meshes at z = 0) and three point fields
// at its vertices:
//   u       the displacement, full field (Dirichlet values included);
//   v       the displacement rate over the last step, (Uⁿ − Uⁿ⁻¹)/dt (0 at step 0);
//   lambda  the seed's multiplier λ ≤ 0 at the constrained vertices (−reaction of
//           the step's QP, G = −I; post/contact_force.hpp's vertex_multiplier), 0
//           elsewhere.
// Vector-valued spaces give 3-component u, v, lambda (the missing ones 0; lambda
// = λ_N n for contact against a rigid plane of normal n).  A caller may add named
// arrays of its own, at the vertices (point data) or per cell (cell data): the
// command line adds the stress and strain of elasticity runs (post/stress.hpp) and the
// contact pressure.  This file writes them; it computes nothing.
// Only vertex values are written: a P1+ bubble vanishes at the vertices and a P2
// edge dof is not a vertex value, so the files show the P1 interpolant of the field
// (docs/outputs.md).  fields.pvd lists the files with their times, so ParaView
// opens the whole series at once.
//
// Format: binary, appended raw data (UInt64 block headers, the machine's byte
// order), the most compact form ParaView and meshio read without a decoder
// step; the XML header stays readable text.
#pragma once

#include <Eigen/Core>
#include <filesystem>
#include <string>
#include <vector>


#include "cdyn/problems/constrained_problem.hpp"
#include "cdyn/mesh/mesh.hpp"

namespace cdyn {

// A named array written next to u, v and lambda: `components` values per vertex
// (point data) or per cell (cell data), tuple after tuple.  9 components are read by
// ParaView as a 3 × 3 tensor (row by row).
struct FieldArray {
  std::string name;
  int components = 1;
  std::vector<double> values;
};
struct ExtraFields {
  std::vector<FieldArray> point, cell;
};

// u, v and lambda at the vertices of `mesh` (the mesh of problem.W) — the arrays every
// file begins with: U_full and rate_full on all dofs of W^h, reaction_xy the step's
// reaction on its free dofs in (x, y) components (empty: none yet).
std::vector<FieldArray> state_arrays(const Mesh& mesh, const ConstrainedProblem& problem, const Eigen::VectorXd& U_full,
                                     const Eigen::VectorXd& rate_full, const Eigen::VectorXd& reaction_xy);

// Removes the fields of an earlier run in `out` (fields.pvd, fields/step_*.vtu), so
// that a directory never mixes two runs' files.
void remove_fields(const std::filesystem::path& out);

class FieldsWriter {
 public:
  // Writes into out/fields/ (created) and out/fields.pvd.
  FieldsWriter(const std::filesystem::path& out, const Mesh& mesh, const ConstrainedProblem& problem);
  // The same for arrays made elsewhere (the write below taking all of them): a run on
  // subdomains writes its ranks' arrays gathered on the whole mesh.
  FieldsWriter(const std::filesystem::path& out, const Mesh& mesh);

  // Writes fields/step_NNNNNN.vtu for the state at `step`: U_full and rate_full are
  // coefficient vectors on all dofs of W^h, reaction_xy the step's reaction on its free
  // dofs in (x, y) components (post/contact_force.hpp's reaction_xy; empty: none yet).
  // `extra`: more arrays (InputError if one has not n_vertices (n_cells) tuples).
  void write(int step, double t, const Eigen::VectorXd& U_full, const Eigen::VectorXd& rate_full,
             const Eigen::VectorXd& reaction_xy, const ExtraFields& extra = {});
  // The same with every array given (state_arrays' first among the point arrays).
  void write(int step, double t, const ExtraFields& arrays);

  // Writes fields.pvd, the time series of the files written so far.
  void finish() const;

  struct Frame {
    int step;
    double t;
    std::string file;  // relative to the output directory
  };
  const std::vector<Frame>& frames() const { return frames_; }

  // Takes over the series of a run resumed at step `last_step` (docs/outputs.md,
  // "Restart"): the frames (step, t) it had written up to there, whose files must exist
  // (InputError naming a missing one), and removes every other step file: those the
  // stopped run wrote after its checkpoint, and the last state of an interrupted run.
  void continue_series(const std::vector<std::pair<int, double>>& frames, int last_step);

 private:
  std::filesystem::path out_;
  const Mesh& mesh_;
  const ConstrainedProblem* problem_ = nullptr;  // for the write from a state
  std::string geometry_blocks_;  // points, connectivity, offsets, types: the same every frame
  std::vector<Frame> frames_;
};

}  // namespace cdyn
