// test_sub_mesh.cpp — sub-meshes of a partition of the cells (mesh/sub_mesh.hpp): the
// elastic contact problem built on each subdomain sums to the whole problem's,
//     A = Σ_r P_rᵀ A_r P_r,  M = Σ_r P_rᵀ M_r P_r,  L = Σ_r P_rᵀ L_r,  S_c = Σ_r P_rᵀ S_c,r P_r,
// and every subdomain has the whole problem's bounds on its unknowns (P_r lower = lower_r),
// the identities a distributed assembly rests on.  The cells are dealt out c mod 3, so
// that most subdomains touch the Dirichlet and contact parts at vertices whose facets
// another one holds; the plane is inclined (rotated unknowns at the contact nodes), the
// top side carries a traction, and gravity acts.  Round-off only: 1e-13 relative.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "cdyn/base/error.hpp"
#include "cdyn/mesh/sub_mesh.hpp"
#include "cdyn/problems/elastic_contact.hpp"
#include "cdyn/problems/subdomain.hpp"
#include "cdyn/qp/condensation.hpp"

using namespace cdyn;

namespace {

constexpr int kParts = 3;

ElasticContactData data(int dim) {
  ElasticContactData d;
  d.mass = MassSpec::pair(Element::P1Bubble, Element::P0);
  d.lambda = 0.7;
  d.gravity = {0.1, -1.0, 0.2};
  d.dirichlet_parts = {dim == 2 ? 3 : 3};   // "left" in both meshes
  d.neumann_parts = {dim == 2 ? 2 : 5};     // "top"
  d.traction = {[](double x, double, double, double) { return 0.3 * x; }, zero_field, zero_field};
  d.contact_parts = {dim == 2 ? 0 : 4};     // "bottom"
  d.obstacle_point = {0.0, -0.01, -0.01};
  d.obstacle_normal = dim == 2 ? Point{0.2, 1.0, 0.0} : Point{0.2, 0.1, 1.0};
  return d;
}

Eigen::MatrixXd place(const SparseMatrix& Ar, const std::vector<int>& P, int n) {
  Eigen::MatrixXd A = Eigen::MatrixXd::Zero(n, n);
  for (int j = 0; j < Ar.outerSize(); ++j)
    for (SparseMatrix::InnerIterator it(Ar, j); it; ++it) A(P[it.row()], P[it.col()]) += it.value();
  return A;
}

void expect_sums_to_whole(const Mesh& mesh) {
  const ElasticContactData d = data(mesh.dim);
  const ConstrainedProblem whole = build_elastic_contact(mesh, d);
  const int n = whole.n_free();
  const double k = 37.0;  // S = A + k M, k as m/dt² of a step
  const SparseMatrix S = whole.A + k * *whole.mass->matrix();
  const StaticCondensation cond(S, whole.lower, whole.upper, bubble_unknowns(whole));
  ASSERT_EQ(cond.n_condensed(), mesh.dim * mesh.n_cells());  // every bubble
  const std::vector<int>& kept = cond.kept_unknowns();
  std::vector<int> kept_of(n, -1);
  for (std::size_t i = 0; i < kept.size(); ++i) kept_of[kept[i]] = static_cast<int>(i);

  Eigen::MatrixXd A = Eigen::MatrixXd::Zero(n, n), M = A, Sc = Eigen::MatrixXd::Zero(cond.n_kept(), cond.n_kept());
  Eigen::VectorXd L = Eigen::VectorXd::Zero(n);
  int touching = 0;  // subdomains that hold part vertices through another's facets
  for (int r = 0; r < kParts; ++r) {
    std::vector<int> cells;
    for (int c = r; c < mesh.n_cells(); c += kParts) cells.push_back(c);
    const SubMesh sub = sub_mesh(mesh, cells);
    touching += !sub.mesh.parts_elsewhere.empty();
    const ConstrainedProblem part = build_elastic_contact(sub.mesh, d);
    const std::vector<int> P = unknowns_in_whole(*whole.W, *whole.bc, part, sub);
    A += place(part.A, P, n);
    M += place(*part.mass->matrix(), P, n);
    const Eigen::VectorXd Lr = part.load(0.0);
    for (int i = 0; i < part.n_free(); ++i) {
      L[P[i]] += Lr[i];
      EXPECT_EQ(part.lower[i], whole.lower[P[i]]) << "unknown " << i << " of subdomain " << r;
      EXPECT_EQ(part.upper[i], whole.upper[P[i]]);
    }
    EXPECT_EQ(std::count_if(whole.constrained.begin(), whole.constrained.end(),
                            [&](int g) { return std::find(P.begin(), P.end(), g) != P.end(); }),
              static_cast<long>(part.constrained.size()));
    // S_c,r: the kept unknowns are the same, the condensed bubbles each in one subdomain
    const StaticCondensation cond_r(part.A + k * *part.mass->matrix(), part.lower, part.upper, bubble_unknowns(part));
    std::vector<int> Pc;
    for (int i = 0; i < part.n_free(); ++i)
      if (!cond_r.condenses(i)) {
        ASSERT_FALSE(cond.condenses(P[i]));
        Pc.push_back(kept_of[P[i]]);
      } else {
        ASSERT_TRUE(cond.condenses(P[i]));
      }
    Sc += place(cond_r.S_c(), Pc, cond.n_kept());
  }
  EXPECT_GT(touching, 0) << "the partition does not test the part vertices held elsewhere";
  const Eigen::MatrixXd A_whole(whole.A), M_whole(*whole.mass->matrix()), Sc_whole(cond.S_c());
  EXPECT_LE((A - A_whole).cwiseAbs().maxCoeff(), 1e-13 * A_whole.cwiseAbs().maxCoeff());
  EXPECT_LE((M - M_whole).cwiseAbs().maxCoeff(), 1e-13 * M_whole.cwiseAbs().maxCoeff());
  EXPECT_LE((Sc - Sc_whole).cwiseAbs().maxCoeff(), 1e-13 * Sc_whole.cwiseAbs().maxCoeff());
  EXPECT_LE((L - whole.load(0.0)).cwiseAbs().maxCoeff(), 1e-13 * whole.load(0.0).cwiseAbs().maxCoeff());
}

}  // namespace

TEST(SubMesh, TheSubdomainProblemsSumToTheWholeInThePlane) { expect_sums_to_whole(unit_square_mesh(6)); }

TEST(SubMesh, TheSubdomainProblemsSumToTheWholeInSpace) { expect_sums_to_whole(unit_cube_mesh(3)); }

TEST(SubMesh, KeepsItsCellsFacetsAndTheMeshsVertexOrder) {
  const Mesh mesh = unit_square_mesh(2);  // 9 vertices, 8 triangles, 8 boundary edges
  const SubMesh sub = sub_mesh(mesh, {7, 0});
  EXPECT_EQ(sub.mesh.n_cells(), 2);
  EXPECT_TRUE(std::is_sorted(sub.vertex.begin(), sub.vertex.end()));
  for (int c = 0; c < 2; ++c)
    for (int k = 0; k < 3; ++k) EXPECT_EQ(sub.vertex[sub.mesh.cells[c][k]], mesh.cells[sub.cell[c]][k]);
  EXPECT_NEAR(sub.mesh.measure(), 0.25, 1e-15);
  // cell 0 (below the diagonal of the lower left square) holds a bottom edge, cell 7
  // (above the diagonal of the upper right one) a top edge
  ASSERT_EQ(sub.mesh.boundary.size(), 2u);
  EXPECT_EQ(mesh.part_names[sub.mesh.boundary[0].part], "bottom");
  EXPECT_EQ(mesh.part_names[sub.mesh.boundary[1].part], "top");
  EXPECT_THROW(sub_mesh(mesh, {0, 0}), InputError);
  EXPECT_THROW(sub_mesh(mesh, {8}), InputError);
}

TEST(SubMesh, SlabsPartitionTheCells) {
  const Mesh mesh = unit_cube_mesh(3);
  std::vector<int> seen(mesh.n_cells(), 0);
  for (int part = 0; part < 3; ++part) {
    const std::vector<int> cells = slab_cells(mesh, part, 3);
    EXPECT_EQ(static_cast<int>(cells.size()), mesh.n_cells() / 3);  // one layer of cubes each
    for (int c : cells) ++seen[c];
  }
  EXPECT_EQ(std::count(seen.begin(), seen.end(), 1), mesh.n_cells());
}

// The dual graph: every interior facet joins two cells, so the degrees sum to twice the
// interior facets, (d + 1)·cells − boundary facets; the neighbours are mutual, sorted,
// and share d vertices with the cell.
void expect_dual_graph(const Mesh& mesh) {
  const CellGraph g = cell_graph(mesh);
  const int d = mesh.dim;
  ASSERT_EQ(static_cast<int>(g.offset.size()), mesh.n_cells() + 1);
  EXPECT_EQ(g.offset.back(), (d + 1) * mesh.n_cells() - static_cast<int>(mesh.boundary.size()));
  for (int c = 0; c < mesh.n_cells(); ++c) {
    const auto first = g.neighbour.begin() + g.offset[c], last = g.neighbour.begin() + g.offset[c + 1];
    EXPECT_TRUE(std::is_sorted(first, last));
    for (auto it = first; it != last; ++it) {
      const int e = *it;
      EXPECT_NE(e, c);
      EXPECT_TRUE(std::binary_search(g.neighbour.begin() + g.offset[e], g.neighbour.begin() + g.offset[e + 1], c));
      int common = 0;
      for (int i = 0; i <= d; ++i)
        for (int j = 0; j <= d; ++j) common += mesh.cells[c][i] == mesh.cells[e][j];
      EXPECT_EQ(common, d);
    }
  }
}

TEST(SubMesh, TheCellsDualGraphJoinsCellsAcrossFacets) {
  expect_dual_graph(unit_square_mesh(4));  // 32 triangles, 16 boundary edges: 80 / 2 interior
  expect_dual_graph(unit_cube_mesh(2));
}
