// fe/assembly.cpp — cell-by-cell assembly of A, B, C and L.
//
// Every routine follows the same three steps: tabulate the reference basis at the
// quadrature points once, then for each cell map the gradients with J⁻ᵀ and the
// weights with |det J|, and scatter the local matrix into triplets.
#include "cdyn/fe/assembly.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <vector>

#include "cdyn/mesh/cell_geometry.hpp"
#include "cdyn/base/error.hpp"
#include "cdyn/fe/quadrature.hpp"

namespace cdyn {

namespace {

using Grad = std::array<double, 3>;  // a reference or physical gradient

// Reference basis values and gradients at every quadrature point.
struct Tabulation {
  int n = 0;                                  // local dofs
  std::vector<std::vector<double>> value;     // [q][k]
  std::vector<std::vector<Grad>> gradient;    // [q][k]
  Tabulation(const FESpace& V, const QuadratureRule& q) : n(V.local_dofs()) {
    for (const auto& xi : q.points) {
      value.emplace_back(n);
      gradient.emplace_back(n);
      shape_values(V.element(), V.dim(), xi, value.back().data());
      shape_gradients(V.element(), V.dim(), xi, gradient.back().data());
    }
  }
};

// Whether the stiffness couples the local shape functions i and j at all.  With P1+ on
// straight-sided cells the P1 functions and the bubble b are orthogonal in energy: ∇φ_i
// is constant on K, so ∫_K ∇φ_i·∇b = ∇φ_i·∫_K ∇b = ∇φ_i·∮_∂K b n = 0 (b vanishes on
// ∂K), and ∫ div·div and ∫ ε:ε are sums of such integrals.  The quadrature leaves
// round-off there (below 1e-15 of the diagonal); not storing it leaves A 43 % of the
// entries (membrane, n = 40: 14 641 of 33 841), which every product with A reads.
bool stiffness_couples(const FESpace& W, int i, int j) {
  if (W.element() != Element::P1Bubble) return true;
  const int bubble = W.dim() + 1;  // the local bubble follows the dim + 1 vertices
  return (i == bubble) == (j == bubble);
}

SparseMatrix from_triplets(int rows, int cols, const std::vector<Eigen::Triplet<double>>& t) {
  SparseMatrix M(rows, cols);
  M.setFromTriplets(t.begin(), t.end());
  M.makeCompressed();
  return M;
}

// The cells' entries (i, j, value), summed into a sparse matrix by batches of kBatch:
// setFromTriplets holds every entry at once and an unsorted matrix of as many besides,
// 12 × 12 entries a tetrahedron for 3D elasticity — 284M entries at 10⁶ unknowns, where
// a run peaked at 8.45 GB with one setFromTriplets and at 5.63 GB by batches
// (docs/performance.md, "Three dimensions").  A mesh with fewer entries (every mesh of
// the tests) is summed by one setFromTriplets as before, bit for bit; a larger one
// batch by batch, the partial matrices added (the same sums in another order:
// round-off).
class TripletSum {
 public:
  TripletSum(int rows, int cols, std::size_t expected) : rows_(rows), cols_(cols) {
    t_.reserve(std::min(expected, kBatch));
  }
  void add(int i, int j, double value) {
    t_.emplace_back(i, j, value);
    if (t_.size() == kBatch) flush();
  }
  SparseMatrix finish() {
    if (!batched_) return from_triplets(rows_, cols_, t_);
    flush();
    sum_.makeCompressed();
    return std::move(sum_);
  }

 private:
  static constexpr std::size_t kBatch = std::size_t{1} << 24;  // 16.8M entries, 268 MB
  void flush() {
    SparseMatrix part = from_triplets(rows_, cols_, t_);
    t_.clear();
    if (!batched_) {
      sum_ = std::move(part);
      batched_ = true;
    } else {
      sum_ += part;
    }
  }
  int rows_, cols_;
  std::vector<Eigen::Triplet<double>> t_;
  SparseMatrix sum_;
  bool batched_ = false;
};

}  // namespace

namespace {

// The mass of (R, W), each cell's local matrix scaled by weight(c) (nullptr: 1).
SparseMatrix weighted_mass(const FESpace& R, const FESpace& W, const CellCoefficient* weight) {
  if (&R.mesh() != &W.mesh()) throw InputError("assemble_mass: the two spaces must share one mesh");
  if (R.components() != W.components()) throw InputError("assemble_mass: the spaces differ in components");
  const QuadratureRule q = cell_quadrature(W.dim(), R.degree() + W.degree());
  const Tabulation tr(R, q), tw(W, q);
  const int nc = R.components();
  TripletSum t(R.n_dofs(), W.n_dofs(), static_cast<std::size_t>(W.mesh().n_cells()) * tr.n * tw.n * nc);
  std::vector<double> local(tr.n * tw.n);
  for (int c = 0; c < W.mesh().n_cells(); ++c) {
    const double detJ = CellGeometry(W.mesh(), c).det;
    std::fill(local.begin(), local.end(), 0.0);
    for (int p = 0; p < q.size(); ++p)
      for (int i = 0; i < tr.n; ++i)
        for (int j = 0; j < tw.n; ++j) local[i * tw.n + j] += q.weights[p] * detJ * tr.value[p][i] * tw.value[p][j];
    if (weight)
      for (double& m : local) m *= (*weight)[c];
    const auto ri = R.cell_dofs(c), wj = W.cell_dofs(c);
    for (int i = 0; i < tr.n; ++i)
      for (int j = 0; j < tw.n; ++j)
        for (int k = 0; k < nc; ++k) t.add(R.dof(ri[i], k), W.dof(wj[j], k), local[i * tw.n + j]);
  }
  return t.finish();
}

// A per-cell coefficient must have one value per cell of the mesh.
void check_cells(const CellCoefficient& a, const Mesh& mesh, const char* what) {
  if (!a.is_uniform() && static_cast<int>(a.per_cell().size()) != mesh.n_cells())
    throw InputError(std::string(what) + ": " + std::to_string(a.per_cell().size()) + " cell values for a mesh of " +
                     std::to_string(mesh.n_cells()) + " cells");
}

}  // namespace

SparseMatrix assemble_mass(const FESpace& R, const FESpace& W) { return weighted_mass(R, W, nullptr); }

SparseMatrix assemble_mass(const FESpace& R, const FESpace& W, const CellCoefficient& rho) {
  check_cells(rho, W.mesh(), "assemble_mass");
  // Uniform: ρ times the unweighted sums, the order of the products of every
  // single-material result (so that they stay bit for bit what they were).
  if (rho.is_uniform()) return rho.value() * weighted_mass(R, W, nullptr);
  return weighted_mass(R, W, &rho);
}

SparseMatrix assemble_laplace(const FESpace& W) {
  if (W.components() != 1) throw InputError("assemble_laplace: a scalar space is expected");
  const QuadratureRule q = cell_quadrature(W.dim(), 2 * (W.degree() - 1));
  const Tabulation tw(W, q);
  TripletSum t(W.n_dofs(), W.n_dofs(), static_cast<std::size_t>(W.mesh().n_cells()) * tw.n * tw.n);
  std::vector<Grad> g(tw.n);
  std::vector<double> local(tw.n * tw.n);
  for (int c = 0; c < W.mesh().n_cells(); ++c) {
    const CellGeometry K(W.mesh(), c);
    std::fill(local.begin(), local.end(), 0.0);
    for (int p = 0; p < q.size(); ++p) {
      for (int i = 0; i < tw.n; ++i) g[i] = K.gradient(tw.gradient[p][i]);
      const double w = q.weights[p] * K.det;
      for (int i = 0; i < tw.n; ++i)
        for (int j = 0; j < tw.n; ++j) local[i * tw.n + j] += w * (g[i][0] * g[j][0] + g[i][1] * g[j][1] + g[i][2] * g[j][2]);
    }
    const auto d = W.cell_dofs(c);
    for (int i = 0; i < tw.n; ++i)
      for (int j = 0; j < tw.n; ++j)
        if (stiffness_couples(W, i, j)) t.add(d[i], d[j], local[i * tw.n + j]);
  }
  return t.finish();
}

SparseMatrix assemble_elasticity(const FESpace& W, const CellCoefficient& lambda_c, const CellCoefficient& mu_c) {
  const int nc = W.dim();  // components: 2 (plane strain) or 3
  if (nc < 2 || W.components() != nc)
    throw InputError("assemble_elasticity: a 2-component space on a 2D mesh or a 3-component one on a 3D mesh is expected");
  check_cells(lambda_c, W.mesh(), "assemble_elasticity: lambda");
  check_cells(mu_c, W.mesh(), "assemble_elasticity: mu");
  const QuadratureRule q = cell_quadrature(nc, 2 * (W.degree() - 1));
  const Tabulation tw(W, q);
  const int n = tw.n, m = nc * n;  // local vector dofs: (scalar i, component k) -> nc·i + k
  constexpr int kMaxLocal = 10;    // P2 on a tetrahedron
  if (n > kMaxLocal) throw InputError("assemble_elasticity: more than 10 local dofs per cell");
  // The local matrix of cell c into local[0 .. m·m).
  auto cell_matrix = [&](int c, double* local) {
    const CellGeometry K(W.mesh(), c);
    const double lambda = lambda_c[c], mu = mu_c[c];  // the cell's material (one for all cells: uniform)
    std::array<Grad, kMaxLocal> g;
    std::fill(local, local + m * m, 0.0);
    for (int p = 0; p < q.size(); ++p) {
      for (int i = 0; i < n; ++i) g[i] = K.gradient(tw.gradient[p][i]);
      const double w = q.weights[p] * K.det;
      // For φ = ψ e_k: div φ = ∂_k ψ and ε(φ)_ab = ½(δ_ak ∂_b ψ + δ_bk ∂_a ψ), so
      // ε(ψ_i e_k) : ε(ψ_j e_l) = ½ (δ_kl ∇ψ_i·∇ψ_j + ∂_l ψ_i ∂_k ψ_j).
      for (int i = 0; i < n; ++i)
        for (int j = 0; j < n; ++j) {
          double gg = g[i][0] * g[j][0] + g[i][1] * g[j][1];
          if (nc == 3) gg += g[i][2] * g[j][2];
          for (int k = 0; k < nc; ++k)
            for (int l = 0; l < nc; ++l) {
              const double eps = 0.5 * ((k == l ? gg : 0.0) + g[i][l] * g[j][k]);
              local[(nc * i + k) * m + nc * j + l] += w * (lambda * g[i][k] * g[j][l] + 2.0 * mu * eps);
            }
        }
    }
  };
  // The local matrices of a chunk of cells on every thread (each cell's arithmetic as on
  // one thread), then their entries into the triplets in cell order: the same triplets,
  // bit for bit, whatever the thread count (linalg/parallel.hpp, rule 1).  The cells'
  // quadrature is most of the assembly (3D P1+: 24 points, 225 entries a cell).
  // (a parallel region costs microseconds: a chunk of fewer than kParallelCells cells stays
  // on one thread)
  const int n_cells = W.mesh().n_cells();
  constexpr int kChunk = 4096, kParallelCells = 256;
  std::vector<double> locals(static_cast<std::size_t>(std::min(n_cells, kChunk)) * m * m);
  TripletSum t(W.n_dofs(), W.n_dofs(), static_cast<std::size_t>(n_cells) * m * m);
  for (int c0 = 0; c0 < n_cells; c0 += kChunk) {
    const int c1 = std::min(n_cells, c0 + kChunk);
#pragma omp parallel for schedule(static) if (c1 - c0 >= kParallelCells)
    for (int c = c0; c < c1; ++c) cell_matrix(c, &locals[static_cast<std::size_t>(c - c0) * m * m]);
    for (int c = c0; c < c1; ++c) {
      const double* local = &locals[static_cast<std::size_t>(c - c0) * m * m];
      const auto d = W.cell_dofs(c);
      for (int i = 0; i < n; ++i)
        for (int j = 0; j < n; ++j)
          if (stiffness_couples(W, i, j))
            for (int k = 0; k < nc; ++k)
              for (int l = 0; l < nc; ++l)
                t.add(W.dof(d[i], k), W.dof(d[j], l), local[(nc * i + k) * m + nc * j + l]);
    }
  }
  return t.finish();
}

namespace {

// L_i = ∫ w f·φ_i, w = weight(c) on cell c (nullptr: no weight, not even a product by 1).
Eigen::VectorXd weighted_load(const FESpace& W, const CellCoefficient* weight, const std::vector<Field>& f, double t) {
  if (static_cast<int>(f.size()) != W.components()) throw InputError("assemble_load: one field per component expected");
  const QuadratureRule q = cell_quadrature(W.dim(), 2 * W.degree() + 2);
  const Tabulation tw(W, q);
  Eigen::VectorXd L = Eigen::VectorXd::Zero(W.n_dofs());
  // A component uniform in space is evaluated once (its value at the origin).
  std::vector<double> uniform_value(f.size(), 0.0);
  bool any_varies = false;
  for (std::size_t k = 0; k < f.size(); ++k) {
    if (f[k].depends_on_space())
      any_varies = true;
    else
      uniform_value[k] = f[k](Point{}, t);
  }
  for (int c = 0; c < W.mesh().n_cells(); ++c) {
    const CellGeometry K(W.mesh(), c);
    const auto d = W.cell_dofs(c);
    for (int p = 0; p < q.size(); ++p) {
      const Point x = any_varies ? K.map(q.points[p]) : Point{};
      for (int k = 0; k < W.components(); ++k) {
        double fw = (f[k].depends_on_space() ? f[k](x, t) : uniform_value[k]) * q.weights[p] * K.det;
        if (weight) fw *= (*weight)[c];
        for (int i = 0; i < tw.n; ++i) L[W.dof(d[i], k)] += fw * tw.value[p][i];
      }
    }
  }
  return L;
}

}  // namespace

Eigen::VectorXd assemble_load(const FESpace& W, const std::vector<Field>& f, double t) {
  return weighted_load(W, nullptr, f, t);
}

std::function<Eigen::VectorXd(double)> load_in_time(const FESpace& W, std::vector<Field> f, bool depends_on_time) {
  const bool uniform = std::none_of(f.begin(), f.end(), [](const Field& fk) { return fk.depends_on_space(); });
  if (!depends_on_time || !uniform || f.size() != static_cast<std::size_t>(W.components()))
    return [&W, f = std::move(f)](double t) { return assemble_load(W, f, t); };
  std::vector<Eigen::VectorXd> unit;  // ∫ φ_{i,k}: the load of f_k = 1 alone
  for (std::size_t k = 0; k < f.size(); ++k) {
    std::vector<Field> e(f.size(), Field([](const Point&, double) { return 0.0; }).uniform_in_space());
    e[k] = Field([](const Point&, double) { return 1.0; }).uniform_in_space();
    unit.push_back(assemble_load(W, e));
  }
  return [f = std::move(f), unit = std::move(unit)](double t) {
    Eigen::VectorXd L = Eigen::VectorXd::Zero(unit[0].size());
    for (std::size_t k = 0; k < f.size(); ++k) L += f[k](Point{}, t) * unit[k];
    return L;
  };
}

Eigen::VectorXd assemble_load(const FESpace& W, const CellCoefficient& w, const std::vector<Field>& f, double t) {
  check_cells(w, W.mesh(), "assemble_load");
  return weighted_load(W, &w, f, t);
}

Eigen::VectorXd assemble_load(const FESpace& W, const Field& f, double t) {
  return assemble_load(W, std::vector<Field>{f}, t);
}

}  // namespace cdyn
