// test_convergence.cpp — observed convergence rates on a manufactured Poisson problem.
//
//   −Δu = f in Ω, u = g on ∂Ω, with u = sin(πx) sin(πy) + x²y on the unit square
// (non-zero boundary data, so the Dirichlet lifting is exercised), and
// u = sin(2x) + x on [0, 1.5] in 1D.
// Theory (Ciarlet): ‖u − u_h‖_L2 = O(h^{k+1}), |u − u_h|_H1 = O(h^k) for P_k; P1+ has the
// rates of P1.  The rate observed between the two finest meshes is asserted within
// ±0.15 of the theoretical one (docs/verification.md; pre-asymptotic effects at these
// sizes are below 0.05 — see the printed rates).
#include <gtest/gtest.h>

#include <Eigen/SparseCholesky>
#include <cmath>
#include <cstdio>
#include <numbers>

#include "cdyn/fe/assembly.hpp"
#include "cdyn/fe/dirichlet.hpp"
#include "cdyn/fe/norms.hpp"

using namespace cdyn;
using std::numbers::pi;

namespace {

struct Problem {
  Field u, f;
  GradientField grad;
};

const Problem kSquare{
    [](double x, double y, double) { return std::sin(pi * x) * std::sin(pi * y) + x * x * y; },
    [](double x, double y, double) { return 2 * pi * pi * std::sin(pi * x) * std::sin(pi * y) - 2 * y; },
    [](double x, double y, double) {
      return std::array<double, 2>{pi * std::cos(pi * x) * std::sin(pi * y) + 2 * x * y,
                                   pi * std::sin(pi * x) * std::cos(pi * y) + x * x};
    }};

const Problem kInterval{[](double x, double, double) { return std::sin(2 * x) + x; },
                        [](double x, double, double) { return 4 * std::sin(2 * x); },
                        [](double x, double, double) { return std::array<double, 2>{2 * std::cos(2 * x) + 1, 0.0}; }};

struct Errors {
  double h, l2, h1;
};

// Solve A_ff U_f = L_f − (A U_D)_f with g = u on the whole boundary.
Errors solve(const Mesh& m, Element e, const Problem& p) {
  const FESpace W(m, e);
  const SparseMatrix A = assemble_laplace(W);
  const Eigen::VectorXd L = assemble_load(W, p.f);
  std::vector<int> parts(m.part_names.size());
  for (std::size_t k = 0; k < parts.size(); ++k) parts[k] = static_cast<int>(k);
  const DirichletLift bc(W, parts);
  const Eigen::VectorXd UD = bc.lifting(W, {p.u});
  Eigen::SimplicialLDLT<SparseMatrix> solver(bc.restrict(A));
  const Eigen::VectorXd U = bc.extend(solver.solve(bc.restrict(Eigen::VectorXd(L - A * UD))), UD);
  return {m.h_max(), l2_error(W, U, p.u), h1_seminorm_error(W, U, p.grad)};
}

void check_rates(Element e, int dim, const std::vector<int>& ns, double l2_rate, double h1_rate) {
  std::vector<Errors> err;
  for (int n : ns) err.push_back(dim == 2 ? solve(unit_square_mesh(n), e, kSquare) : solve(interval_mesh(n, 1.5), e, kInterval));
  for (std::size_t k = 1; k < err.size(); ++k) {
    const double r = std::log(err[k - 1].h / err[k].h);
    const double rl2 = std::log(err[k - 1].l2 / err[k].l2) / r, rh1 = std::log(err[k - 1].h1 / err[k].h1) / r;
    std::printf("%s %dD n=%d: L2 %.3e (rate %.3f)  H1 %.3e (rate %.3f)\n", to_string(e).c_str(), dim, ns[k],
                err[k].l2, rl2, err[k].h1, rh1);
    if (k + 1 == err.size()) {
      EXPECT_NEAR(rl2, l2_rate, 0.15) << to_string(e) << " " << dim << "D L2";
      EXPECT_NEAR(rh1, h1_rate, 0.15) << to_string(e) << " " << dim << "D H1";
    }
  }
}

}  // namespace

TEST(Convergence, P1Square) { check_rates(Element::P1, 2, {8, 16, 32}, 2.0, 1.0); }
TEST(Convergence, P1BubbleSquare) { check_rates(Element::P1Bubble, 2, {8, 16, 32}, 2.0, 1.0); }
TEST(Convergence, P2Square) { check_rates(Element::P2, 2, {4, 8, 16}, 3.0, 2.0); }
TEST(Convergence, P1Interval) { check_rates(Element::P1, 1, {8, 16, 32}, 2.0, 1.0); }
TEST(Convergence, P2Interval) { check_rates(Element::P2, 1, {4, 8, 16}, 3.0, 2.0); }
