// test_reference_matrices.cpp — cdyn's A and M = Bᵀ C⁻¹ B against FreeFEM's and GetFEM's, through
// invariants that do not depend on the basis (reference_scripts/matrices.edp): FreeFEM's
// P1b is cdyn's P1+ in a nodal basis, so entries differ while
//   1ᵀM1 (no Dirichlet condition; the measure of Ω),
//   tr(A_ff⁻¹ M_ff) = Σ 1/ω_k²  and  tr((A_ff⁻¹ M_ff)²) = Σ 1/ω_k⁴  (u = 0 on ∂Ω)
// agree for the same space.  Pairs P1/P1, P1+/P0 (P1b/P0), P2/P1 at n = 4 and 10; in 3D
// against GetFEM on the Kuhn cube (unit_cube_mesh) at n = 2 and 3, where P1+ is GetFEM's
// FEM_PK_WITH_CUBIC_BUBBLE(3,1), P1 plus the quartic bubble.
// Both sides integrate exactly and solve directly: the tolerance 1e-10 relative covers
// the round-off of dense solves with A's condition number (≈ 1e3 at n = 10); FreeFEM's
// tgv = 1e30 on the Dirichlet rows perturbs its numbers by ~1e-30.  The stored CSVs are
// read, or the live ones of the `reference` label when CDYN_REFERENCE_DIR is set.
#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <cstdlib>
#include <fstream>
#include <map>
#include <sstream>
#include <vector>

#include "cdyn/problems/scalar_wave.hpp"

using namespace cdyn;

namespace {

struct Invariants {
  double mass = 0, trace1 = 0, trace2 = 0;
};

std::map<std::string, Invariants> read_reference(const std::string& program, int n) {
  const char* live = std::getenv("CDYN_REFERENCE_DIR");
  const std::string dir = live ? std::string(live) : std::string(CDYN_SOURCE_DIR) + "/data/reference";
  const std::string path = dir + "/" + program + "_n" + std::to_string(n) + ".csv";
  std::ifstream in(path);
  if (!in) throw std::runtime_error("cannot open " + path);
  std::map<std::string, Invariants> out;
  std::string line;
  std::getline(in, line);  // pair,n,ndof,mass,trace1,trace2
  while (std::getline(in, line)) {
    std::stringstream s(line);
    std::string pair, field;
    std::getline(s, pair, ',');
    std::vector<double> v;
    while (std::getline(s, field, ',')) v.push_back(std::stod(field));
    out[pair] = {v[2], v[3], v[4]};
  }
  return out;
}

ConstrainedProblem problem(const Mesh& mesh, Element W, const std::string& H, bool dirichlet) {
  ScalarWaveData d;
  d.mass = cdyn::MassSpec::parse(H, W);
  d.f = [](double, double, double) { return 0.0; };
  if (dirichlet)
    for (int part = 0; part < static_cast<int>(mesh.part_names.size()); ++part) d.dirichlet_parts.push_back(part);
  d.dirichlet_value = [](double, double, double) { return 0.0; };
  d.obstacle = false;
  d.obstacle_g = [](double, double, double) { return 0.0; };
  return build_scalar_wave(mesh, d);
}

// M as a dense matrix, column by column through the mass model's own operators.
Eigen::MatrixXd dense_mass(const ConstrainedProblem& p) {
  const int n = p.n_free();
  Eigen::MatrixXd M(n, n);
  for (int j = 0; j < n; ++j) M.col(j) = p.mass->momentum(p.mass->velocity(Eigen::VectorXd::Unit(n, j)));
  return M;
}

Invariants cdyn_invariants(const Mesh& mesh, Element W, const std::string& H) {
  Invariants out;
  const ConstrainedProblem all = problem(mesh, W, H, false);
  const Eigen::VectorXd one = all.W->interpolate([](double, double, double) { return 1.0; });
  out.mass = 2.0 * all.mass->kinetic_energy(all.mass->velocity(one));
  const ConstrainedProblem p = problem(mesh, W, H, true);
  const Eigen::MatrixXd Y = Eigen::MatrixXd(p.A).ldlt().solve(dense_mass(p));
  out.trace1 = Y.trace();
  out.trace2 = (Y * Y).trace();
  return out;
}

}  // namespace

// program: "matrices" (FreeFEM, reference_scripts/matrices.edp) or "getfem_matrices"
// (GetFEM, reference_scripts/getfem_matrices.py, whose P1+ is FEM_PK_WITH_CUBIC_BUBBLE).
// dim 3: the unit cube (GetFEM only, "getfem_matrices_3d").
void check_against(const std::string& program, int dim = 2) {
  for (int n : dim == 2 ? std::vector<int>{4, 10} : std::vector<int>{2, 3}) {
    const auto ff = read_reference(program, n);
    const Mesh mesh = dim == 2 ? unit_square_mesh(n) : unit_cube_mesh(n);
    const std::tuple<std::string, Element, std::string> pairs[] = {
        {"P1/P1", Element::P1, "P1"}, {"P1b/P0", Element::P1Bubble, "P0"}, {"P2/P1", Element::P2, "P1"}};
    for (const auto& [name, W, H] : pairs) {
      ASSERT_TRUE(ff.count(name)) << name;
      const Invariants r = ff.at(name), c = cdyn_invariants(mesh, W, H);
      std::printf("%s n = %d %s: 1'M1 %.3e, tr(A^-1 M) %.3e, tr((A^-1 M)^2) %.3e relative difference\n", program.c_str(), n, name.c_str(),
                  std::abs(c.mass - r.mass) / r.mass, std::abs(c.trace1 - r.trace1) / r.trace1,
                  std::abs(c.trace2 - r.trace2) / r.trace2);
      EXPECT_NEAR(c.mass, r.mass, 1e-12 * r.mass) << name << " n = " << n;
      EXPECT_NEAR(c.trace1, r.trace1, 1e-10 * r.trace1) << name << " n = " << n;
      EXPECT_NEAR(c.trace2, r.trace2, 1e-10 * r.trace2) << name << " n = " << n;
    }
  }
}

TEST(ReferenceMatrices, InvariantsAgreeWithFreeFEM) { check_against("matrices"); }
TEST(ReferenceMatrices, InvariantsAgreeWithGetFEM) { check_against("getfem_matrices"); }
TEST(ReferenceMatrices, InvariantsAgreeWithGetFEMOnTetrahedra) { check_against("getfem_matrices_3d", 3); }
