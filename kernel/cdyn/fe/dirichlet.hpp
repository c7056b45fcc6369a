// fe/dirichlet.hpp — Dirichlet conditions by lifting and elimination.
//
// The seed's u = 0 on Γ_D (eq. 4; the model problem's u = 0.05, its experiments' u = 0.02
// on ∂Ω): W^h is the affine space of finite element functions with those values.
// The dofs of W^h split into free dofs f and fixed dofs d (those on the Dirichlet
// boundary parts).  A full coefficient vector is
//     U = P U_f + U_D,
// P the injection of the free dofs and U_D the lifting: the interpolated Dirichlet
// data on the fixed dofs, zero elsewhere.  The linear system A U = L then reads
//     A_ff U_f = L_f − (A U_D)_f,
// and the full field (needed for the energy J = ½UᵀAU − LᵀU of the whole body, for
// outputs and probes) is recovered by extend().  The full A and L are kept by the
// caller; this class only knows which dofs are which.
#pragma once

#include <Eigen/Core>
#include <vector>

#include "cdyn/fe/assembly.hpp"

namespace cdyn {

// The entries of S whose row and column both survive: row_index / col_index map an
// old row / column to its new index, or to −1 to drop it (n_rows × n_cols result).
SparseMatrix submatrix(const SparseMatrix& S, const std::vector<int>& row_index, int n_rows,
                       const std::vector<int>& col_index, int n_cols);

class DirichletLift {
 public:
  // Fixes every component of the dofs on the named parts (indices into
  // mesh.part_names); `components` restricts it to some components (e.g. {1} for a
  // roller that fixes only u_y).  No parts: nothing fixed.
  DirichletLift(const FESpace& W, const std::vector<int>& parts, std::vector<int> components = {});

  int n_full() const { return static_cast<int>(free_index_.size()); }
  int n_free() const { return static_cast<int>(free_.size()); }
  const std::vector<int>& free_dofs() const { return free_; }
  const std::vector<int>& fixed_dofs() const { return fixed_; }
  // Index of full dof i among the free dofs, or −1 if it is fixed.
  int free_index(int i) const { return free_index_[i]; }

  // U_D: the Dirichlet data g(x, y, t) interpolated on the fixed dofs, zero elsewhere
  // (one field per component of W).
  Eigen::VectorXd lifting(const FESpace& W, const std::vector<Field>& g, double t = 0.0) const;

  // X_f: the free entries of a full vector.
  Eigen::VectorXd restrict(const Eigen::VectorXd& U) const;
  // P X_f + U_D.
  Eigen::VectorXd extend(const Eigen::VectorXd& Uf, const Eigen::VectorXd& UD) const;

  // A_ff: the free rows and free columns of a square matrix on W^h.
  SparseMatrix restrict(const SparseMatrix& A) const;
  // B P: the free columns of a matrix whose columns are W^h dofs (e.g. B, rows H^h).
  SparseMatrix restrict_columns(const SparseMatrix& B) const;

 private:
  std::vector<int> free_, fixed_, free_index_;
};

}  // namespace cdyn
