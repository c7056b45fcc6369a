// test_mass_model.cpp — the mass operators M = Bᵀ C⁻¹ B of the seed's pairs and the
// classical mass models (mass/mass_model.hpp), and Theorem 2 (energy conservation of the
// unconstrained semi-discrete problem) for each of them.
//
// Every expected number comes from mathematics:
//  - 1_hᵀ M 1_h = ρ|Ω| per component: the L² projection of a constant on any H^h
//    containing the constants is itself, so 1ᵀBᵀC⁻¹B1 = ∫ρ·1·1; the classical models
//    keep it by construction (lumping: row sums; redistribution: T 1_h = 1_h);
//  - P1/P1: B = C = M_ff, so Bᵀ C⁻¹ B = M_ff;
//  - redistribution: T P = P for affine P gives Pᵀ M_red Q = Pᵀ M_ff Q;
//  - Theorem 2: J is constant along the exact solution, computed modally.
// Tolerances: everything is an exact identity evaluated in floating point on matrices
// of at most a few hundred rows, with condition numbers of mass matrices (≤ 1e3);
// the worst round-off measured is printed by each test and is ≤ 3e-15 relative;
// the tolerances (1e-13 for identities, 1e-12 for the moments, docs/semi_discretization.md §4, 1e-11
// for the energy, which goes through two dense eigen-decompositions) leave ~10–100×.
#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include "cdyn/base/error.hpp"
#include "cdyn/mass/mass_model.hpp"
#include "cdyn/mass/redistribution.hpp"
#include "mass_fixtures.hpp"

using namespace cdyn;
using namespace cdyn::testing;  // mass_fixtures.hpp
using Eigen::MatrixXd;
using Eigen::VectorXd;

namespace {

std::vector<int> parts(const Mesh& m, const std::vector<std::string>& names) {
  std::vector<int> p;
  for (const auto& n : names) p.push_back(m.part_index(n));
  return p;
}

// A named configuration: mesh, W element, components, Dirichlet parts, contact parts.
struct Config {
  std::string label;
  Mesh mesh;
  Element W;
  int components;
  std::vector<std::string> dirichlet, contact;
};

std::vector<Config> configs_without_dirichlet() {
  std::vector<Config> s;
  for (Element e : {Element::P1, Element::P1Bubble, Element::P2}) {
    s.push_back({"square", unit_square_mesh(4, 1.5, 1.0), e, 1, {}, {"bottom"}});
    s.push_back({"interval", interval_mesh(6, 2.5), e, 1, {}, {"left"}});
    s.push_back({"square-vector", unit_square_mesh(3, 1.5, 1.0), e, 2, {}, {"bottom"}});
    s.push_back({"cube", unit_cube_mesh(2), e, 1, {}, {"bottom"}});
    s.push_back({"cube-vector", unit_cube_mesh(2), e, 3, {}, {"bottom"}});
  }
  return s;
}

std::vector<std::string> specs_for(Element W, int dim) {
  std::vector<std::string> s = {"P0", "P1", "consistent", "redistributed"};
  if (!(W == Element::P2 && dim >= 2)) s.push_back("lumped");  // P2's vertex row sums: 0 in 2D, < 0 in 3D
  return s;
}

}  // namespace

// M symmetric positive semi-definite and 1_hᵀ M 1_h = ρ|Ω| for every pair and model,
// scalar and vector, in 1D, 2D and 3D (no Dirichlet elimination, so the constant is free).
TEST(MassModel, SymmetricPsdAndTotalMass) {
  const double rho = 2.5;
  double worst_sym = 0, worst_neg = 0, worst_mass = 0;
  for (const Config& s : configs_without_dirichlet()) {
    const FESpace W(s.mesh, s.W, s.components);
    const DirichletLift bc(W, {});
    const MatrixXd P = affine_fields(W, bc);
    for (const std::string& spec : specs_for(s.W, s.mesh.dim)) {
      SCOPED_TRACE(s.label + " " + to_string(s.W) + " " + spec);
      const auto model = make_mass_model(W, bc, spec, rho, contact_dofs(W, bc, s.contact));
      const MatrixXd M = dense_mass(*model, bc.n_free());
      const double norm = M.norm();
      const double sym = (M - M.transpose()).norm() / norm;
      const double lmin = Eigen::SelfAdjointEigenSolver<MatrixXd>(0.5 * (M + M.transpose())).eigenvalues()[0];
      worst_sym = std::max(worst_sym, sym);
      worst_neg = std::max(worst_neg, -lmin / norm);
      EXPECT_LE(sym, 1e-14);
      EXPECT_GE(lmin, -1e-13 * norm);
      const int nf = s.mesh.dim + 1;
      for (int k = 0; k < s.components; ++k) {
        const VectorXd one = P.col(k * nf);  // the constant 1 in component k
        const double mass = one.dot(M * one);
        worst_mass = std::max(worst_mass, std::abs(mass - rho * s.mesh.measure()) / (rho * s.mesh.measure()));
        EXPECT_NEAR(mass, rho * s.mesh.measure(), 1e-13 * rho * s.mesh.measure());
      }
    }
  }
  std::printf("[mass] worst: asymmetry %.1e, negative eigenvalue %.1e, total-mass error %.1e (relative)\n",
              worst_sym, worst_neg, worst_mass);
}

// P1/P1 is the standard Galerkin method: M = M_ff (with the velocity's Dirichlet dofs
// removed as the displacement's; without removal it is M_ff too, C⁻¹ B = injection).
TEST(MassModel, P1OverP1IsTheConsistentMass) {
  struct Case {
    Mesh mesh;
    int components;
    std::vector<std::string> dirichlet;
  };
  const std::vector<Case> cases = {{unit_square_mesh(5), 1, {}},
                                   {unit_square_mesh(5), 1, {"bottom", "left"}},
                                   {unit_square_mesh(5), 1, {"bottom", "right", "top", "left"}},
                                   {interval_mesh(9, 2.0), 1, {"right"}},
                                   {unit_square_mesh(4), 2, {"left"}}};
  double worst = 0;
  for (const Case& c : cases) {
    const FESpace W(c.mesh, Element::P1, c.components);
    const DirichletLift bc(W, parts(c.mesh, c.dirichlet));
    const auto pair = make_mass_model(W, bc, "P1/P1", 1.7);
    const auto cons = make_mass_model(W, bc, "consistent", 1.7);
    EXPECT_FALSE(pair->matrix().has_value());  // continuous H: saddle form only
    const MatrixXd Mp = dense_mass(*pair, bc.n_free()), Mc = MatrixXd(*cons->matrix());
    const double err = (Mp - Mc).norm() / Mc.norm();
    worst = std::max(worst, err);
    EXPECT_LE(err, 1e-13);
    EXPECT_EQ(pair->n_velocity(), bc.n_free());  // H's fixed dofs are W's
    const MixedBlocks full = mixed_blocks(W, bc, Element::P1, 1.7, false);
    const MatrixXd Mfull = MatrixXd(full.B).transpose() * MatrixXd(full.C).llt().solve(MatrixXd(full.B));
    EXPECT_LE((Mfull - Mc).norm() / Mc.norm(), 1e-13);
  }
  std::printf("[mass] P1/P1 against the consistent mass: %.1e relative\n", worst);
}

// The operators of the interface agree with each other: saddle form, momentum,
// velocity, kinetic energy; ρ scales M but not V; the P0 pairs have a sparse M.
TEST(MassModel, OperatorsAreConsistent) {
  const Mesh mesh = unit_square_mesh(4);
  const std::vector<std::string> all = {"bottom", "right", "top", "left"};
  for (Element e : {Element::P1, Element::P1Bubble, Element::P2}) {
    const FESpace W(mesh, e);
    const DirichletLift bc(W, parts(mesh, {"left", "top"}));
    const SparseMatrix A = bc.restrict(assemble_laplace(W));
    const int n = bc.n_free();
    for (const std::string spec : {"P0", "P1", "consistent", "lumped", "redistributed"}) {
      if (e == Element::P2 && spec == "lumped") continue;
      SCOPED_TRACE(to_string(e) + " " + spec);
      const auto c = contact_dofs(W, bc, {"bottom"});
      const auto m1 = make_mass_model(W, bc, spec, 1.0, c);
      const auto m3 = make_mass_model(W, bc, spec, 3.0, c);
      const MatrixXd M = dense_mass(*m1, n);
      EXPECT_EQ(m1->matrix().has_value(), spec != "P1");
      // S = A + k M from the saddle blocks.
      const double k = 7.0;
      const SaddleForm s = m1->saddle(A, k);
      const MatrixXd Bs(s.B), Cs(s.C);
      const MatrixXd S = MatrixXd(s.A) + s.c * Bs.transpose() * Cs.llt().solve(Bs);
      EXPECT_LE((S - (MatrixXd(A) + k * M)).norm(), 1e-13 * S.norm());
      // V independent of ρ, kinetic energy ½ U̇ᵀ M U̇ proportional to ρ.
      const VectorXd Ud = VectorXd::LinSpaced(n, -1.0, 2.0).array().sin();
      const VectorXd V1 = m1->velocity(Ud), V3 = m3->velocity(Ud);
      EXPECT_LE((V1 - V3).norm(), 1e-14 * V1.norm());
      const double ke = 0.5 * Ud.dot(M * Ud);
      EXPECT_NEAR(m1->kinetic_energy(V1), ke, 1e-13 * ke);
      EXPECT_NEAR(m3->kinetic_energy(V3), 3.0 * ke, 3e-13 * ke);
      EXPECT_LE((m1->momentum(V1) - M * Ud).norm(), 1e-13 * (M * Ud).norm());
    }
  }
  // A continuous velocity space loses the fixed vertices: N_H = interior vertices.
  const FESpace W(mesh, Element::P1Bubble);
  const DirichletLift bc(W, parts(mesh, all));
  EXPECT_EQ(make_mass_model(W, bc, "P1+/P1", 1.0)->n_velocity(), 9);
  EXPECT_EQ(make_mass_model(W, bc, "P0", 1.0)->n_velocity(), 32);
  EXPECT_EQ(make_mass_model(W, bc, "P1+/P0", 1.0)->name(), "P1+/P0");
}

TEST(MassModel, BadInputIsAnInputError) {
  const Mesh mesh = unit_square_mesh(3);
  const FESpace W(mesh, Element::P1Bubble), W2(mesh, Element::P2), W0(mesh, Element::P0);
  const DirichletLift bc(W, {}), bc2(W2, {}), bc0(W0, {});
  EXPECT_THROW(make_mass_model(W, bc, "P3", 1.0), InputError);
  EXPECT_THROW(make_mass_model(W, bc, "nonsense", 1.0), InputError);
  EXPECT_THROW(make_mass_model(W, bc, "P2/P0", 1.0), InputError);  // W is P1+
  const DirichletLift clamped(W, {mesh.part_index("left")});
  EXPECT_THROW(make_mass_model(W, clamped, "P1+/P2", 1.0), InputError);  // P2 velocity: its edge dofs on Γ_D need W = P2
  EXPECT_THROW(make_mass_model(W, bc, "P0", 0.0), InputError);
  EXPECT_THROW(make_mass_model(W, bc, "P0", -1.0), InputError);
  EXPECT_THROW(make_mass_model(W2, bc2, "lumped", 1.0), InputError);  // 2D P2: zero vertex mass
  EXPECT_THROW(make_mass_model(W0, bc0, "P0", 1.0), InputError);
  EXPECT_THROW(make_mass_model(W, bc, "redistributed", 1.0), InputError);  // no contact dofs
  std::vector<int> every_vertex;
  for (int v = 0; v < mesh.n_vertices(); ++v) every_vertex.push_back(v);
  EXPECT_THROW(make_mass_model(W, bc, "redistributed", 1.0, every_vertex), InputError);  // no donors
  EXPECT_THROW(make_mass_model(W, bc, "redistributed", 1.0, {mesh.n_vertices()}), InputError);  // a bubble dof
  EXPECT_NO_THROW(make_mass_model(W2, bc2, "P2/P2", 1.0));
}

// Mass redistribution: zero contact rows and columns, moments of order ≤ 2 of the
// consistent mass kept, Ker M = the contact directions exactly.
TEST(MassModel, RedistributionKeepsMomentsAndRemovesContactInertia) {
  struct Case {
    std::string label;
    Mesh mesh;
    Element W;
    int components;
    std::vector<std::string> dirichlet, contact;
    std::vector<int> contact_components;  // empty: all
  };
  const std::vector<Case> cases = {
      {"1D bar, contact at x = 0, clamped at x = 1", interval_mesh(10), Element::P1, 1, {"right"}, {"left"}, {}},
      {"1D bar, P2", interval_mesh(10), Element::P2, 1, {"right"}, {"left"}, {}},
      {"membrane, contact on bottom", unit_square_mesh(6), Element::P1, 1, {}, {"bottom"}, {}},
      {"membrane, contact on bottom, top clamped", unit_square_mesh(6), Element::P1, 1, {"top"}, {"bottom"}, {}},
      {"membrane P1+, contact on bottom and left", unit_square_mesh(5), Element::P1Bubble, 1, {"top"},
       {"bottom", "left"}, {}},
      {"membrane P2, contact on bottom", unit_square_mesh(5), Element::P2, 1, {"right"}, {"bottom"}, {}},
      {"elasticity, contact on bottom (both components)", unit_square_mesh(5, 2.0, 1.0), Element::P1, 2, {"top"},
       {"bottom"}, {}},
      {"elasticity, contact on bottom (u_y only)", unit_square_mesh(5, 2.0, 1.0), Element::P1, 2, {"top"},
       {"bottom"}, {1}},
      {"elasticity, no Dirichlet", unit_square_mesh(4), Element::P1, 2, {}, {"bottom"}, {}},
  };
  for (const Case& c : cases) {
    SCOPED_TRACE(c.label);
    const FESpace W(c.mesh, c.W, c.components);
    const DirichletLift bc(W, parts(c.mesh, c.dirichlet));
    const std::vector<int> contact = contact_dofs(W, bc, c.contact, c.contact_components);
    const auto red = make_mass_model(W, bc, "redistributed", 1.3, contact);
    const auto cons = make_mass_model(W, bc, "consistent", 1.3);
    const SparseMatrix Ms = *red->matrix();  // matrix() returns by value
    const MatrixXd M(Ms), Mc(*cons->matrix());

    // Rows and columns of the contact dofs vanish: structurally, so exactly.
    for (int i : contact) {
      EXPECT_EQ(M.row(i).cwiseAbs().maxCoeff(), 0.0);
      EXPECT_EQ(M.col(i).cwiseAbs().maxCoeff(), 0.0);
    }
    // Moments PᵀMQ of the affine fields (1, x, y per component): mass, centre of mass
    // (xᵀM1, yᵀM1) and second moments (xᵀMx, yᵀMy, xᵀMy), each entry relative to its
    // Cauchy–Schwarz scale sqrt(PᵀMP · QᵀMQ).
    const MatrixXd P = affine_fields(W, bc);
    const MatrixXd mom = P.transpose() * M * P, mom_c = P.transpose() * Mc * P;
    double worst = 0.0;
    for (int a = 0; a < P.cols(); ++a)
      for (int b = 0; b < P.cols(); ++b) {
        const double scale = std::sqrt(mom_c(a, a) * mom_c(b, b));
        worst = std::max(worst, std::abs(mom(a, b) - mom_c(a, b)) / scale);
      }
    EXPECT_LE(worst, 1e-12);
    // Positive semi-definite with kernel exactly span{e_c}: as many eigenvalues below
    // 1e-12 λ_max (round-off level for an exact zero) as contact dofs, the others well
    // above it.
    const Eigen::SelfAdjointEigenSolver<MatrixXd> eig(M);
    const VectorXd lam = eig.eigenvalues();
    const double lmax = lam[lam.size() - 1];
    const int nc = static_cast<int>(contact.size());
    EXPECT_GE(lam[0], -1e-14 * lmax);
    if (nc > 0) {
      EXPECT_LE(lam[nc - 1], 1e-14 * lmax);
    }
    EXPECT_GT(lam[nc], 1e-6 * lmax);
    // ... and that kernel is the contact directions: its eigenvectors live on them.
    double outside = 0.0;
    std::vector<char> is_contact(bc.n_free(), 0);
    for (int i : contact) is_contact[i] = 1;
    for (int j = 0; j < nc; ++j)
      for (int i = 0; i < bc.n_free(); ++i)
        if (!is_contact[i]) outside = std::max(outside, std::abs(eig.eigenvectors()(i, j)));
    EXPECT_LE(outside, 1e-10);
    std::printf("[redistribution] %-50s contact dofs %3d  moment error %.1e  smallest nonzero eigenvalue %.1e "
                "(relative)\n",
                c.label.c_str(), nc, worst, lam[nc] / lmax);
  }
}

// ----- Theorem 2: energy conservation of the exact semi-discrete solution -----------
//
// M Ü + A U = L with M = Bᵀ C⁻¹ B possibly singular.  Split U = Y a + Z b with Z an
// orthonormal basis of Ker M and Y of its complement (eigenvectors of M).  Projected on
// Z the equation has no inertia: Zᵀ A (Y a + Z b) = Zᵀ L, the static equation
//     b = (ZᵀAZ)⁻¹ Zᵀ (L − A Y a)                                       (Ker-M part)
// (ZᵀAZ is invertible since A is positive definite).  Projected on Y:
//     M̃ ä + Ã a = L̃,   M̃ = YᵀMY (diagonal, positive),
//     Ã = YᵀAY − YᵀAZ (ZᵀAZ)⁻¹ ZᵀAY,   L̃ = YᵀL − YᵀAZ (ZᵀAZ)⁻¹ ZᵀL,
// a linear oscillator solved exactly with the modes Ã φ = ω² M̃ φ, φᵀM̃φ = 1:
//     a(t) = a* + Σ φ (ξ cos ωt + η sin ωt / ω),   a* = Ã⁻¹ L̃.
// Then U̇ = (Y − Z (ZᵀAZ)⁻¹ ZᵀAY) ȧ, V = C⁻¹ B U̇ (the model's velocity()), and
//     J = ½ VᵀCV + ½ UᵀAU − LᵀU
// must be the same at every t (seed, Theorem 2, with no constraint active).
namespace {

double energy_drift(const MassModel& model, const MatrixXd& A, const VectorXd& L, const char* label) {
  const int n = static_cast<int>(A.rows());
  const MatrixXd M = dense_mass(model, n);
  const Eigen::SelfAdjointEigenSolver<MatrixXd> eig(0.5 * (M + M.transpose()));
  const VectorXd lam = eig.eigenvalues();
  int k = 0;  // dim Ker M: eigenvalues at round-off level (≤ 1e-12 λ_max; the nonzero
  while (k < n && lam[k] <= 1e-12 * lam[n - 1]) ++k;  // ones are ≥ 1e-4 λ_max here)
  const MatrixXd Z = eig.eigenvectors().leftCols(k), Y = eig.eigenvectors().rightCols(n - k);
  const VectorXd mt = lam.tail(n - k);
  MatrixXd K = MatrixXd::Zero(k, n - k);  // b = K a + b0
  VectorXd b0 = VectorXd::Zero(k);
  if (k > 0) {
    const Eigen::LLT<MatrixXd> azz(Z.transpose() * A * Z);
    K = -azz.solve(Z.transpose() * A * Y);
    b0 = azz.solve(Z.transpose() * L);
  }
  const MatrixXd E = Y + Z * K;  // U = E a + Z b0
  MatrixXd At = E.transpose() * A * E;
  At = 0.5 * (At + At.transpose());
  const VectorXd Lt = E.transpose() * (L - A * Z * b0);
  const Eigen::GeneralizedSelfAdjointEigenSolver<MatrixXd> modes(At, mt.asDiagonal().toDenseMatrix());
  const MatrixXd Phi = modes.eigenvectors();  // Φᵀ M̃ Φ = I
  const VectorXd omega = modes.eigenvalues().cwiseSqrt();
  const VectorXd astar = At.llt().solve(Lt);
  // Initial state: a(0), ȧ(0) fixed pseudo-random (the Ker-M part follows from them).
  const VectorXd a0 = astar + VectorXd::LinSpaced(n - k, 0.3, -0.7).array().cos().matrix();
  const VectorXd ad0 = VectorXd::LinSpaced(n - k, -1.1, 0.9).array().sin().matrix();
  const VectorXd xi = Phi.transpose() * (mt.asDiagonal() * (a0 - astar));
  const VectorXd eta = Phi.transpose() * (mt.asDiagonal() * ad0);
  double J0 = 0.0, drift = 0.0, scale = 0.0, ke_mismatch = 0.0;
  for (double t : {0.0, 0.37, 1.3, 5.1, 17.0, 123.4}) {
    const VectorXd c = (omega * t).array().cos(), s = (omega * t).array().sin();
    const VectorXd a = astar + Phi * (xi.cwiseProduct(c) + eta.cwiseProduct(s).cwiseQuotient(omega));
    const VectorXd ad = Phi * (-xi.cwiseProduct(omega).cwiseProduct(s) + eta.cwiseProduct(c));
    const VectorXd U = E * a + Z * b0, Ud = E * ad;
    const VectorXd V = model.velocity(Ud);
    const double ke = model.kinetic_energy(V), pe = 0.5 * U.dot(A * U), work = L.dot(U);
    ke_mismatch = std::max(ke_mismatch, std::abs(ke - 0.5 * Ud.dot(M * Ud)) / std::max(ke, 1e-300));
    const double J = ke + pe - work;
    scale = std::max(scale, ke + pe + std::abs(work));
    if (t == 0.0) J0 = J;
    drift = std::max(drift, std::abs(J - J0));
  }
  drift /= scale;
  std::printf("[theorem 2] %-36s N_W %3d  dim Ker M %3d  max |J(t) - J(0)| / scale = %.1e  (½VᵀCV vs ½U̇ᵀMU̇: %.1e)\n",
              label, n, k, drift, ke_mismatch);
  EXPECT_LE(ke_mismatch, 1e-12);
  return drift;
}

}  // namespace

TEST(MassModel, Theorem2EnergyIsConservedByTheExactSolution) {
  const std::vector<std::string> specs = {"P1/P1", "P1/P0", "P1+/P0", "P1+/P1", "P2/P1", "P2/P0"};
  const std::vector<std::string> classical = {"consistent", "lumped", "redistributed"};
  // Scalar: the membrane (unit square, clamped on left and bottom, load 1 + xy,
  // contact part for the redistribution: top) and the bar (clamped at x = 1).
  struct Scalar {
    std::string label;
    Mesh mesh;
    std::vector<std::string> dirichlet, contact;
  };
  const std::vector<Scalar> scalar = {{"membrane", unit_square_mesh(3), {"left", "bottom"}, {"top"}},
                                      {"bar", interval_mesh(6), {"right"}, {"left"}}};
  const Field f = [](double x, double y, double) { return 1.0 + x * y; };
  for (const Scalar& s : scalar) {
    auto run = [&](Element We, const std::string& spec) {
      const FESpace W(s.mesh, We);
      const DirichletLift bc(W, parts(s.mesh, s.dirichlet));
      const MatrixXd A = MatrixXd(bc.restrict(assemble_laplace(W)));
      const VectorXd L = bc.restrict(assemble_load(W, f));
      const auto model = make_mass_model(W, bc, spec, 1.4, contact_dofs(W, bc, s.contact));
      const std::string label = s.label + " " + (!cdyn::MassSpec::parse(spec).is_pair() ? to_string(We) + " " : "") + spec;
      EXPECT_LE(energy_drift(*model, A, L, label.c_str()), 1e-11) << label;
    };
    for (const auto& p : specs) run(element_from_string(p.substr(0, p.find('/'))), p);
    for (const auto& m : classical) run(Element::P1, m);
    run(Element::P1Bubble, "redistributed");
  }
  // Plane elasticity (λ = 1, μ = 0.5), clamped on the left, contact on the bottom.
  const Mesh mesh = unit_square_mesh(2);
  for (const std::string spec : {"P1/P0", "P1+/P0", "P1+/P1", "P2/P1", "redistributed"}) {
    const Element We = spec == "redistributed" ? Element::P1 : element_from_string(spec.substr(0, spec.find('/')));
    const FESpace W(mesh, We, 2);
    const DirichletLift bc(W, parts(mesh, {"left"}));
    const MatrixXd A = MatrixXd(bc.restrict(assemble_elasticity(W, 1.0, 0.5)));
    const VectorXd L = bc.restrict(assemble_load(W, std::vector<Field>{f, f}));
    const auto model = make_mass_model(W, bc, spec, 1.0, contact_dofs(W, bc, {"bottom"}));
    const std::string label = "elasticity " + spec;
    EXPECT_LE(energy_drift(*model, A, L, label.c_str()), 1e-11) << label;
  }
}
