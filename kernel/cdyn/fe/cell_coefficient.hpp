// fe/cell_coefficient.hpp — a coefficient that is constant on each cell: the density ρ
// and the Lamé parameters λ, μ of a body made of several materials (seed eqs. 1–2 with
// piecewise constant data, one value per mesh region).
//
// The weak forms of the seed (eq. 10) only ever see a material coefficient inside a
// cell integral, ∫_K ρ ψ_i φ_j or ∫_K λ div φ_i div φ_j + 2μ ε(φ_i):ε(φ_j), so a value
// per cell is all an assembly routine needs, and a material interface that follows
// the cell edges (a gmsh physical surface per material) is represented exactly.
//
// A CellCoefficient is either uniform (one number, the single-material body) or one
// value per cell.  A plain double converts to a uniform one, so every caller written
// for a single material still compiles and — this matters for the reference tests —
// computes with exactly the same floating-point operations as before: the assembly
// routines keep their uniform path (e.g. ρ · ∫ψ_iφ_j, the product taken after the
// sum) and use the per-cell path only when the values differ.  A per-cell vector
// whose values are all equal is made uniform on construction for that reason.
#pragma once

#include <algorithm>
#include <utility>
#include <vector>

namespace cdyn {

class CellCoefficient {
 public:
  // The uniform coefficient `value` (implicit: a number is a single material).
  CellCoefficient(double value = 1.0) : value_(value) {}  // NOLINT(google-explicit-constructor)

  // One value per cell (index = cell index of the mesh).  All equal: uniform.
  explicit CellCoefficient(std::vector<double> per_cell) {
    if (!per_cell.empty() &&
        std::all_of(per_cell.begin(), per_cell.end(), [&](double v) { return v == per_cell.front(); })) {
      value_ = per_cell.front();
    } else if (!per_cell.empty()) {
      per_cell_ = std::move(per_cell);
      value_ = per_cell_.front();
    }
  }

  bool is_uniform() const { return per_cell_.empty(); }

  // The value on every cell (uniform); for a per-cell coefficient, that of cell 0.
  double value() const { return value_; }

  // The value on cell c.
  double operator[](int c) const { return per_cell_.empty() ? value_ : per_cell_[static_cast<std::size_t>(c)]; }

  // The per-cell values (empty when uniform).
  const std::vector<double>& per_cell() const { return per_cell_; }

  double min() const { return per_cell_.empty() ? value_ : *std::min_element(per_cell_.begin(), per_cell_.end()); }
  double max() const { return per_cell_.empty() ? value_ : *std::max_element(per_cell_.begin(), per_cell_.end()); }

 private:
  double value_ = 1.0;
  std::vector<double> per_cell_;
};

}  // namespace cdyn
