// rotated.cpp — the mass model in rotated unknowns; see mass/rotated.hpp.
#include "cdyn/mass/rotated.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "cdyn/base/error.hpp"

namespace cdyn {

namespace {

class RotatedMassModel final : public MassModel {
 public:
  RotatedMassModel(std::unique_ptr<MassModel> inner, SparseMatrix R)
      : inner_(std::move(inner)),
        R_(std::move(R)),
        Rt_(R_.transpose()),
        velocity_in_W_(inner_->velocity_is_rate()) {}

  std::string name() const override { return inner_->name(); }
  bool is_invertible() const override { return inner_->is_invertible(); }
  bool velocity_is_rate() const override { return inner_->velocity_is_rate(); }
  int n_velocity() const override { return inner_->n_velocity(); }

  // M' = Rᵀ M R.  Entries that cancel are dropped: a lumped M with equal masses m on
  // the two components of a node must stay diagonal (Paoli–Schatzman tests for it),
  // but its rotated off-diagonal entry n_x(m n_y) − n_y(m n_x) is a rounding residue
  // of a few ulps of m rather than an exact 0.  Entries below 16 ε max|M_ij| are such
  // residues: the true entries of a mass matrix are products of cell measures and
  // basis integrals, many orders of magnitude above that.
  std::optional<SparseMatrix> matrix() const override {
    const std::optional<SparseMatrix> M = inner_->matrix();
    if (!M) return std::nullopt;
    SparseMatrix Mr = Rt_ * (*M * R_);
    Mr = 0.5 * (Mr + SparseMatrix(Mr.transpose()));  // exact symmetry
    double scale = 0.0;
    for (int j = 0; j < M->outerSize(); ++j)
      for (SparseMatrix::InnerIterator it(*M, j); it; ++it) scale = std::max(scale, std::abs(it.value()));
    Mr.prune([tiny = 16 * std::numeric_limits<double>::epsilon() * scale](Eigen::Index, Eigen::Index, double v) {
      return std::abs(v) > tiny;
    });
    Mr.makeCompressed();
    return Mr;
  }

  // {A', B_s R, C_s, k}: A' is already in rotated unknowns (the problem's A); only the
  // displacement side of the inner factors turns (the saddle's velocity is internal).
  SaddleForm saddle(const SparseMatrix& A, double k) const override {
    SaddleForm f = inner_->saddle(A, k);
    f.B = SparseMatrix(f.B * R_);
    f.B.makeCompressed();
    return f;
  }

  Eigen::VectorXd momentum(const Eigen::VectorXd& V) const override {
    return Rt_ * inner_->momentum(to_inner_velocity(V));
  }

  Eigen::VectorXd velocity(const Eigen::VectorXd& Wdot) const override {
    check(Wdot);
    return from_inner_velocity(inner_->velocity(R_ * Wdot));
  }

  double kinetic_energy(const Eigen::VectorXd& V) const override {
    return inner_->kinetic_energy(to_inner_velocity(V));
  }

  Eigen::VectorXd acceleration(const Eigen::VectorXd& F) const override {
    check(F);
    return from_inner_velocity(inner_->acceleration(R_ * F));
  }

 private:
  // A classical model's velocity is a W^h vector and turns with the displacement
  // (V = R V'); a pair's velocity lives in H^h and does not.
  Eigen::VectorXd to_inner_velocity(const Eigen::VectorXd& V) const {
    if (!velocity_in_W_) return V;
    check(V);
    return R_ * V;
  }
  Eigen::VectorXd from_inner_velocity(const Eigen::VectorXd& V) const {
    return velocity_in_W_ ? Eigen::VectorXd(Rt_ * V) : V;
  }

  void check(const Eigen::VectorXd& x) const {
    if (x.size() != R_.cols())
      throw InputError("rotated mass: a vector of size " + std::to_string(x.size()) + " given, " +
                       std::to_string(R_.cols()) + " expected");
  }

  std::unique_ptr<MassModel> inner_;
  SparseMatrix R_, Rt_;
  bool velocity_in_W_;
};

}  // namespace

std::unique_ptr<MassModel> make_rotated_mass_model(std::unique_ptr<MassModel> inner, SparseMatrix R) {
  if (!inner) throw InputError("make_rotated_mass_model: no mass model given");
  if (R.rows() != R.cols()) throw InputError("make_rotated_mass_model: R must be square");
  R.makeCompressed();
  return std::make_unique<RotatedMassModel>(std::move(inner), std::move(R));
}

}  // namespace cdyn
