// mass/mass_model.cpp — make_mass_model: a MassSpec to a model (a pair or a classical mass).
#include "cdyn/mass/mass_model.hpp"

#include <cmath>

#include "cdyn/base/error.hpp"
#include "cdyn/base/format.hpp"
#include "cdyn/mass/classical.hpp"
#include "cdyn/mass/mixed.hpp"

namespace cdyn {

std::unique_ptr<MassModel> make_mass_model(const FESpace& W, const DirichletLift& bc, const MassSpec& spec,
                                           const CellCoefficient& rho, const std::vector<int>& contact_free_dofs) {
  // (min and max: a NaN fails one of the two comparisons wherever it sits)
  if (!(rho.min() > 0.0) || !std::isfinite(rho.max()) || !(rho.max() > 0.0))
    throw InputError("rho", "the density must be positive and finite (got " +
                                to_text(rho.min() > 0.0 ? rho.max() : rho.min()) + ")");
  if (spec.W != W.element())
    throw InputError("pair", "'" + spec.name() + "': the displacement space is " + to_string(W.element()) +
                                 ", not " + to_string(spec.W));
  if (!spec.is_pair()) return make_classical_mass_model(W, bc, spec.model, rho, contact_free_dofs);
  return make_mixed_mass_model(W, bc, spec.H, rho);
}

std::unique_ptr<MassModel> make_mass_model(const FESpace& W, const DirichletLift& bc, const std::string& spec,
                                           const CellCoefficient& rho, const std::vector<int>& contact_free_dofs) {
  return make_mass_model(W, bc, MassSpec::parse(spec, W.element()), rho, contact_free_dofs);
}

std::optional<SparseMatrix> sparse_mass(const MassModel& mass) {
  std::optional<SparseMatrix> M = mass.matrix();
  if (M) return M;
  const SaddleForm f = mass.saddle(SparseMatrix(), 1.0);
  if (same_matrix(f.B, f.C)) M = f.C;
  return M;
}

}  // namespace cdyn
