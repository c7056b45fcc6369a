// mixed.cpp — M = Bᵀ C⁻¹ B for the pairs W^h/H^h (seed eq. 11), and the blocks B, C.
#include "cdyn/mass/mixed.hpp"

#include <Eigen/CholmodSupport>
#include <memory>
#include <cmath>

#include "cdyn/base/error.hpp"
#include "cdyn/linalg/least_squares.hpp"
#include "cdyn/linalg/parallel.hpp"
#include "cdyn/linalg/sparse_cholesky.hpp"
#include "cdyn/linalg/threads.hpp"

namespace cdyn {

namespace {

void check_size(const Eigen::VectorXd& x, Eigen::Index n, const char* what) {
  if (x.size() != n)
    throw InputError(std::string("mass model: ") + what + " has " + std::to_string(x.size()) + " entries, expected " +
                     std::to_string(n));
}

class MixedMassModel final : public MassModel {
 public:
  MixedMassModel(std::string name, MixedBlocks blocks, bool diagonal_C)
      : name_(std::move(name)), B_(std::move(blocks.B)), C_(std::move(blocks.C)), diagonal_(diagonal_C) {
    B_.makeCompressed();
    Bt_ = transposed(B_);
    if (diagonal_) {
      // H^h = P0: C = diag(ρ|T|) (one entry per cell and component).
      Cdiag_ = C_.diagonal();
      if (C_.nonZeros() != C_.rows() || (Cdiag_.array() <= 0.0).any())
        throw NumericalError("mass model " + name_ + ": C is not a positive diagonal matrix");
      // M = Bᵀ C⁻¹ B, symmetrized exactly (the two triangles of a sparse product are
      // summed in different orders).
      // C⁻¹B by scaling B's values row by row: O(nnz).  (Eigen's diagonal × sparse
      // product assigns by insertion here and was quadratic: 60 s at n = 320.)
      SparseMatrix CinvB = B_;
      CinvB.makeCompressed();
      for (int j = 0; j < CinvB.outerSize(); ++j)
        for (SparseMatrix::InnerIterator it(CinvB, j); it; ++it) it.valueRef() /= Cdiag_[it.row()];
      SparseMatrix M = SparseMatrix(B_.transpose()) * CinvB;
      M = 0.5 * (M + SparseMatrix(M.transpose()));
      M.makeCompressed();
      M_ = std::move(M);
    } else {
      // H^h = W^h (P1/P1): B = C, and the velocity C⁻¹ B Ẇ is Ẇ itself (no solve, and
      // no factor of C: in 3D it fills — 312 MB at 10⁵ unknowns, and at 10⁶ it took a
      // run's peak from 8.45 to 12.7 GB and 170 s of its set-up).  The other continuous
      // H^h factorize C when a velocity is first asked for (velocity()).
      C_.makeCompressed();
      identity_ = same_matrix(B_, C_);
    }
  }

  std::string name() const override { return name_; }
  int n_velocity() const override { return static_cast<int>(B_.rows()); }
  // V is a vector of H^h, its own space, even for H^h = W^h (where V = U̇ numerically,
  // but a rotation of W^h's unknowns does not turn it: mass/rotated.hpp).
  bool velocity_is_rate() const override { return false; }

  // Ker M = Ker B: none when N_H < N_W; otherwise B must have full column rank, which an
  // explicit M shows by a Cholesky factorization and B = C (H^h = W^h) by construction;
  // for the other continuous H^h the rank comes from a rank-revealing sparse QR.
  bool is_invertible() const override {
    if (!invertible_) {
      if (B_.rows() < B_.cols())
        invertible_ = false;
      else if (identity_)
        invertible_ = true;
      else if (M_) {
        SparseCholesky chol;
        chol.analyze(*M_);
        invertible_ = chol.factorize(*M_) < 0;
      } else {
        invertible_ = full_column_rank(B_);
      }
    }
    return *invertible_;
  }
  std::optional<SparseMatrix> matrix() const override { return M_; }
  SaddleForm saddle(const SparseMatrix& A, double k) const override { return SaddleForm{A, B_, C_, k}; }

  Eigen::VectorXd momentum(const Eigen::VectorXd& V) const override {
    check_size(V, B_.rows(), "V");
    return transpose_times(B_, V);
  }

  Eigen::VectorXd velocity(const Eigen::VectorXd& Wdot) const override {
    check_size(Wdot, B_.cols(), "the displacement rate");
    if (identity_) return Wdot;
    const Eigen::VectorXd rhs = transpose_times(Bt_, Wdot);  // B Ẇ, gathered from Bᵀ's columns
    if (diagonal_) return evaluated(rhs.cwiseQuotient(Cdiag_));
    if (!cholC_) {
      cholC_ = std::make_unique<Eigen::CholmodDecomposition<SparseMatrix, Eigen::Lower>>();
      within_thread_count([&] { cholC_->compute(C_); });
      if (cholC_->info() != Eigen::Success)
        throw NumericalError("mass model " + name_ + ": the Cholesky factorization of C failed");
    }
    Eigen::VectorXd V = cholC_->solve(rhs);
    return V;
  }

  double kinetic_energy(const Eigen::VectorXd& V) const override {
    check_size(V, C_.rows(), "V");
    return 0.5 * dot(V, symmetric_times(C_, V));
  }

  // H^h = P0: a = M⁺F, A = C⁻¹ B a (Ker M = Ker B, so the part of a that the least
  // squares solution leaves free does not reach A).  Continuous H^h: M is not formed;
  // then A minimizes ‖Bᵀ A − F‖ directly (B is surjective for these pairs, so A is
  // unique and is a rate: C⁻¹ B is onto H^h).
  Eigen::VectorXd acceleration(const Eigen::VectorXd& F) const override {
    check_size(F, B_.cols(), "the force");
    if (M_) return velocity(least_squares(*M_, F));
    return least_squares(SparseMatrix(B_.transpose()), F);
  }

 private:
  std::string name_;
  SparseMatrix B_, C_;
  SparseMatrix Bt_;  // Bᵀ in compressed columns: B x as a gather, threaded (linalg/parallel.hpp)
  bool diagonal_;
  bool identity_ = false;  // B = C
  Eigen::VectorXd Cdiag_;
  std::optional<SparseMatrix> M_;
  mutable std::unique_ptr<Eigen::CholmodDecomposition<SparseMatrix, Eigen::Lower>> cholC_;  // C's, made on first use
  mutable std::optional<bool> invertible_;  // is_invertible(), computed on the first call
};

}  // namespace

MixedBlocks mixed_blocks(const FESpace& W, const DirichletLift& bc, Element He, const CellCoefficient& rho,
                         bool velocity_dirichlet) {
  if (!W.has_vertex_dofs()) throw InputError("pair", "the displacement space W^h must be continuous (not P0)");
  if (bc.n_full() != W.n_dofs()) throw InputError("mixed_blocks: the Dirichlet partition does not belong to W^h");
  const FESpace H(W.mesh(), He, W.components());
  // B_ij = ∫ ρ ψ_i φ_j, C_ij = ∫ ρ ψ_i ψ_j (seed eq. 10 with the density inside; a uniform
  // ρ multiplies the sums, which commutes with the extraction of the free rows below
  // entry by entry, so the blocks are those of ρ · submatrix as before).
  const SparseMatrix Bfull = assemble_mass(H, W, rho);
  const SparseMatrix Cfull = assemble_mass(H, H, rho);

  // The Dirichlet conditions of W^h carried to a continuous H^h: the velocity of a
  // fixed vertex is the rate of constant data, zero.
  MixedBlocks out;
  out.n_velocity_full = H.n_dofs();
  std::vector<char> fixed(H.n_dofs(), 0);
  if (velocity_dirichlet && is_continuous(He) && !bc.fixed_dofs().empty()) {
    if (He == W.element()) {
      for (int d : bc.fixed_dofs()) fixed[d] = 1;  // same space, same numbering
    } else if (He == Element::P1 || He == Element::P1Bubble) {
      for (int v = 0; v < W.mesh().n_vertices(); ++v)  // scalar dof v of H^h is vertex v
        for (int k = 0; k < W.components(); ++k)
          if (bc.free_index(W.vertex_dof(v, k)) < 0) fixed[H.dof(v, k)] = 1;
    } else {
      throw InputError("pair", to_string(W.element()) + "/" + to_string(He) +
                                   ": a P2 velocity space needs W^h = P2 (its boundary edge dofs come from W^h)");
    }
  }
  std::vector<int> row_index(H.n_dofs(), -1);
  int nh = 0;
  for (int i = 0; i < H.n_dofs(); ++i) {
    if (fixed[i])
      out.velocity_fixed.push_back(i);
    else
      row_index[i] = nh++;
  }
  std::vector<int> col_index(W.n_dofs());
  for (int j = 0; j < W.n_dofs(); ++j) col_index[j] = bc.free_index(j);
  out.B = submatrix(Bfull, row_index, nh, col_index, bc.n_free());
  out.C = submatrix(Cfull, row_index, nh, row_index, nh);
  return out;
}

std::unique_ptr<MassModel> make_mixed_mass_model(const FESpace& W, const DirichletLift& bc, Element H,
                                                 const CellCoefficient& rho) {
  MixedBlocks blocks = mixed_blocks(W, bc, H, rho, true);
  return std::make_unique<MixedMassModel>(to_string(W.element()) + "/" + to_string(H), std::move(blocks),
                                          H == Element::P0);
}

}  // namespace cdyn
