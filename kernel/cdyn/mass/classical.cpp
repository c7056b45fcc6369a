// classical.cpp — consistent, lumped and redistributed mass matrices.
#include "cdyn/mass/classical.hpp"

#include <cmath>

#include "cdyn/base/error.hpp"
#include "cdyn/linalg/least_squares.hpp"
#include "cdyn/linalg/parallel.hpp"
#include "cdyn/mass/redistribution.hpp"

namespace cdyn {

namespace {

class ClassicalMassModel final : public MassModel {
 public:
  // M the mass on the free dofs; (Bs, Cs) its saddle factors, Bsᵀ Cs⁻¹ Bs = M.
  ClassicalMassModel(MassSpec spec, SparseMatrix M, SparseMatrix Bs, SparseMatrix Cs)
      : spec_(spec), M_(std::move(M)), Bs_(std::move(Bs)), Cs_(std::move(Cs)) {}

  std::string name() const override { return spec_.name(); }
  // Consistent and lumped are positive definite; the redistributed M has Ker M = span{e_c}.
  bool is_invertible() const override { return spec_.model != MassSpec::Model::Redistributed; }
  bool velocity_is_rate() const override { return true; }
  int n_velocity() const override { return static_cast<int>(M_.rows()); }
  std::optional<SparseMatrix> matrix() const override { return M_; }
  SaddleForm saddle(const SparseMatrix& A, double k) const override { return SaddleForm{A, Bs_, Cs_, k}; }
  Eigen::VectorXd momentum(const Eigen::VectorXd& V) const override {
    check(V);
    return symmetric_times(M_, V);
  }
  Eigen::VectorXd velocity(const Eigen::VectorXd& Wdot) const override {
    check(Wdot);
    return Wdot;
  }
  double kinetic_energy(const Eigen::VectorXd& V) const override {
    check(V);
    return 0.5 * dot(V, symmetric_times(M_, V));
  }
  // V = U̇, so A = Ü solves M Ü = F (least squares for the singular redistributed M:
  // its massless contact dofs get a basic solution, which no energy or momentum sees).
  Eigen::VectorXd acceleration(const Eigen::VectorXd& F) const override {
    check(F);
    return least_squares(M_, F);
  }

 private:
  void check(const Eigen::VectorXd& x) const {
    if (x.size() != M_.rows())
      throw InputError("mass model " + spec_.name() + ": a vector of " + std::to_string(x.size()) + " entries, expected " +
                       std::to_string(M_.rows()));
  }
  MassSpec spec_;
  SparseMatrix M_, Bs_, Cs_;
};

SparseMatrix diagonal(const Eigen::VectorXd& d) {
  SparseMatrix D(d.size(), d.size());
  D.reserve(Eigen::VectorXi::Ones(d.size()));
  for (Eigen::Index i = 0; i < d.size(); ++i) D.insert(i, i) = d[i];
  D.makeCompressed();
  return D;
}

}  // namespace

std::unique_ptr<MassModel> make_classical_mass_model(const FESpace& W, const DirichletLift& bc,
                                                     MassSpec::Model model, const CellCoefficient& rho,
                                                     const std::vector<int>& contact_free_dofs) {
  const MassSpec spec{model, W.element(), Element::P0};
  const std::string name = spec.name();
  if (!W.has_vertex_dofs()) throw InputError("mass", name + ": the displacement space must be continuous");
  const SparseMatrix Mfull = assemble_mass(W, W, rho);  // ρ ∫φ_iφ_j, ρ per cell
  const SparseMatrix Mff = bc.restrict(Mfull);  // the consistent mass on the free dofs

  if (model == MassSpec::Model::Consistent) return std::make_unique<ClassicalMassModel>(spec, Mff, Mff, Mff);

  if (model == MassSpec::Model::Lumped) {
    // Row sums against the interpolant of the constant: (M_full 1_h)_i = ρ∫φ_i for the
    // P1 and P2 nodal bases (and for the vertex rows of P1+), lumped BEFORE the Dirichlet
    // elimination so that 1ᵀM1 = ρ|Ω| per component when nothing is fixed.
    const std::vector<Field> one(W.components(), [](double, double, double) { return 1.0; });
    const Eigen::VectorXd rowsum = Mfull * W.interpolate(one);
    const Eigen::VectorXd d = bc.restrict(rowsum);
    const double scale = rowsum.cwiseAbs().maxCoeff();
    for (Eigen::Index i = 0; i < d.size(); ++i)
      if (!(d[i] > 1e-12 * scale))  // exact zeros of 2D P2 vertex rows come out at ~1e-17
        throw InputError("mass", "lumped: the row sum of free dof " + std::to_string(i) + " is " +
                                     std::to_string(d[i]) + " (row-sum lumping of " + to_string(W.element()) + " in " +
                                     std::to_string(W.dim()) + "D gives vertices no mass); use consistent or a pair");
    const SparseMatrix D = diagonal(d);
    return std::make_unique<ClassicalMassModel>(spec, D, D, D);
  }

  {  // redistributed
    if (contact_free_dofs.empty())
      throw InputError("mass", "redistributed: no contact dofs given (it removes the inertia of the contact nodes)");
    const SparseMatrix T = redistribution_operator(W, bc, contact_free_dofs);
    const SparseMatrix MT = Mff * T;
    SparseMatrix M = SparseMatrix(T.transpose()) * MT;  // M_red = Tᵀ M_ff T
    M = 0.5 * (M + SparseMatrix(M.transpose()));        // exact symmetry
    M.prune(0.0);
    M.makeCompressed();
    return std::make_unique<ClassicalMassModel>(spec, M, MT, Mff);
  }
}

}  // namespace cdyn
