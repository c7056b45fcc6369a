// condition12.cpp — β = σ_min(G Z) of condition (12) by dense orthogonal factorizations,
// and the choice between that and the sparse method.
#include "cdyn/wellposedness/condition12.hpp"

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <limits>

#include "cdyn/base/error.hpp"
#include "cdyn/mass/mass_model.hpp"
#include "cdyn/wellposedness/condition12_sparse.hpp"
#include "cdyn/wellposedness/row_basis.hpp"

namespace cdyn {

WellPosedness condition12(const SparseMatrix& B, const SparseMatrix& G, Condition12Method method, int dense_limit) {
  if (method == Condition12Method::automatic)
    method = std::max(B.rows(), B.cols()) <= kCondition12DenseUpTo ? Condition12Method::dense
                                                                    : Condition12Method::sparse;
  return method == Condition12Method::dense ? condition12_dense(B, G, dense_limit) : condition12_sparse(B, G);
}

WellPosedness condition12_dense(const SparseMatrix& B, const SparseMatrix& G, int dense_limit) {
  const int nW = static_cast<int>(B.cols()), nH = static_cast<int>(B.rows()), ng = static_cast<int>(G.rows());
  if (G.cols() != nW)
    throw InputError("condition (12): G has " + std::to_string(G.cols()) + " columns, B has " + std::to_string(nW));
  if (nW > dense_limit || nH > dense_limit)
    throw InputError("condition (12): " + std::to_string(nW) + " displacement and " + std::to_string(nH) +
                     " velocity dofs exceed the dense limit of " + std::to_string(dense_limit) +
                     " of this check (dense QR of B); use a coarser mesh");
  WellPosedness r;
  r.method = "dense";
  r.n_W = nW;
  r.n_H = nH;
  r.n_g = ng;

  const Eigen::MatrixXd Bt = Eigen::MatrixXd(rows_scaled_to_unit_max(B)).transpose();  // (D B)ᵀ, N_W × N_H
  int rank = 0;
  Eigen::MatrixXd ZtGt;  // Zᵀ Gᵀ, (N_W − r) × N_g
  if (nH > 0) {
    Eigen::ColPivHouseholderQR<Eigen::MatrixXd> qr(Bt);
    qr.setThreshold(kRankTolerance);
    rank = static_cast<int>(qr.rank());
    if (ng > 0) {
      Eigen::MatrixXd X = Eigen::MatrixXd(G).transpose();  // N_W × N_g
      X = qr.householderQ().adjoint() * X;                 // Qᵀ Gᵀ = [Q_rᵀ Gᵀ; Zᵀ Gᵀ]
      ZtGt = X.bottomRows(nW - rank);
    }
  } else {
    ZtGt = Eigen::MatrixXd(G).transpose();  // no velocity space: Ker B = everything
  }
  r.dim_ker_B = nW - rank;
  if (ng == 0) {
    r.beta = std::numeric_limits<double>::infinity();  // inf over an empty set
  } else if (r.dim_ker_B < ng) {
    r.beta = 0.0;  // rank(G Z) ≤ dim Ker B < N_g: G cannot be onto R^{N_g}
  } else {
    // Singular values only.  BDCSVD: its error is absolute, O(ε‖G Z‖) with ‖G Z‖ ≤ 1,
    // and it returns exact zeros where its deflation meets them (JacobiSVD, 3–5× slower
    // here, gives 3e-16 .. 4e-16 on the same exactly deficient cases).
    Eigen::BDCSVD<Eigen::MatrixXd> svd(ZtGt);
    r.beta = svd.singularValues()[ng - 1];  // the N_g-th = σ_min(G Z), descending order
  }
  r.satisfied = r.beta > kBetaTolerance;
  return r;
}

SparseMatrix vertex_constraint_matrix(const FESpace& W, const DirichletLift& bc, const std::vector<int>& vertices,
                                      std::optional<Point> normal, const std::vector<Point>& normals) {
  if (!W.has_vertex_dofs()) throw InputError("pair", "the displacement space must be continuous");
  if (W.components() > 1 && !normal && normals.size() != vertices.size())
    throw InputError("constraints: a vector-valued space needs the contact normal");
  std::vector<Eigen::Triplet<double>> t;
  int row = 0;
  for (std::size_t j = 0; j < vertices.size(); ++j) {
    const int v = vertices[j];
    const Point n = normals.empty() ? (normal ? *normal : Point{}) : normals[j];
    if (v < 0 || v >= W.mesh().n_vertices()) throw InputError("constraints: no vertex " + std::to_string(v));
    bool any = false;
    for (int k = 0; k < W.components(); ++k) {
      const int f = bc.free_index(W.vertex_dof(v, k));
      if (f < 0) continue;
      const double c = W.components() == 1 ? -1.0 : (k == 0 ? n.x : k == 1 ? n.y : n.z);
      if (c != 0.0) {
        t.emplace_back(row, f, c);
        any = true;
      }
    }
    if (any) ++row;
  }
  SparseMatrix G(row, bc.n_free());
  G.setFromTriplets(t.begin(), t.end());
  G.makeCompressed();
  return G;
}

WellPosedness condition12_on(const Mesh& mesh, const MassSpec& spec, const WellPosednessSetup& setup) {
  const FESpace W(mesh, spec.W, setup.components);
  const DirichletLift bc(W, setup.dirichlet_parts);
  const SparseMatrix G = vertex_constraint_matrix(W, bc, setup.constrained_vertices, setup.normal, setup.normals);

  SparseMatrix B;
  if (!spec.is_pair()) {
    std::vector<int> contact;
    for (int v : setup.constrained_vertices)
      for (int k = 0; k < W.components(); ++k)
        if (const int f = bc.free_index(W.vertex_dof(v, k)); f >= 0) contact.push_back(f);
    const auto model = make_mass_model(W, bc, spec, 1.0, contact);
    B = *model->matrix();  // Ker B = Ker M
  } else {
    B = mixed_blocks(W, bc, spec.H, 1.0).B;
  }
  WellPosedness r = condition12(B, G, setup.method, setup.dense_limit);
  r.pair = spec.name();
  return r;
}

}  // namespace cdyn
