// test_quadrature.cpp — the rules integrate monomials exactly up to their degree.
//
// Exact values: ∫₀¹ ξ^a dξ = 1/(a+1);  ∫_T̂ ξ^a η^b = a! b! / (a+b+2)!  (the reference
// triangle (0,0),(1,0),(0,1)).  Tolerance 1e-14: the rules are exact, so only
// round-off (a few ulps times the number of points) remains.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <limits>

#include "cdyn/fe/quadrature.hpp"

using cdyn::cell_quadrature;

namespace {
double factorial(int n) { return std::tgamma(n + 1.0); }
}  // namespace

TEST(Quadrature, IntervalIsExactUpToItsDegree) {
  for (int degree = 0; degree <= 15; ++degree) {
    const auto q = cell_quadrature(1, degree);
    for (int a = 0; a <= degree; ++a) {
      double s = 0.0;
      for (int p = 0; p < q.size(); ++p) s += q.weights[p] * std::pow(q.points[p][0], a);
      EXPECT_NEAR(s, 1.0 / (a + 1), 1e-14) << "degree " << degree << " monomial " << a;
    }
  }
}

TEST(Quadrature, TriangleIsExactUpToItsDegree) {
  for (int degree = 0; degree <= 12; ++degree) {
    const auto q = cell_quadrature(2, degree);
    for (int a = 0; a <= degree; ++a)
      for (int b = 0; a + b <= degree; ++b) {
        double s = 0.0;
        for (int p = 0; p < q.size(); ++p) s += q.weights[p] * std::pow(q.points[p][0], a) * std::pow(q.points[p][1], b);
        EXPECT_NEAR(s, factorial(a) * factorial(b) / factorial(a + b + 2), 1e-14)
            << "degree " << degree << " monomial x^" << a << " y^" << b;
      }
  }
}

TEST(Quadrature, DegreeSixIsNotExactForDegreeEight) {
  // A rule is not accidentally of higher degree than asked for the bubble products:
  // this guards the exactness test above against a rule that ignores its argument.
  const auto q = cell_quadrature(2, 1);
  double s = 0.0;
  for (int p = 0; p < q.size(); ++p) s += q.weights[p] * std::pow(q.points[p][0], 8);
  EXPECT_GT(std::abs(s - factorial(8) / factorial(10)), 1e-6);
}

namespace {

// ∫_T λ^a = a0! a1! a2! a3! 3! / (|a| + 3)! · |T| over a tetrahedron T, λ its barycentric
// coordinates (the Dirichlet integral).
double barycentric_monomial_integral(const std::array<int, 4>& a, double volume) {
  return factorial(a[0]) * factorial(a[1]) * factorial(a[2]) * factorial(a[3]) * factorial(3) /
         factorial(a[0] + a[1] + a[2] + a[3] + 3) * volume;
}

// Σ_p w_p λ(x_p)^a for the reference rule q, λ = (1 − ξ − η − ζ, ξ, η, ζ), and the
// scale of its round-off, Σ_p |w_p| λ(x_p)^a.
struct Sum {
  double value = 0.0, scale = 0.0;
};
Sum integrate(const cdyn::QuadratureRule& q, const std::array<int, 4>& a) {
  Sum s;
  for (int p = 0; p < q.size(); ++p) {
    const auto& x = q.points[p];
    const double l[4] = {1.0 - x[0] - x[1] - x[2], x[0], x[1], x[2]};
    const double f = std::pow(l[0], a[0]) * std::pow(l[1], a[1]) * std::pow(l[2], a[2]) * std::pow(l[3], a[3]);
    s.value += q.weights[p] * f;
    s.scale += std::abs(q.weights[p]) * f;
  }
  return s;
}

}  // namespace

// The Grundmann–Möller rules (fe/quadrature.hpp) against the closed form, for every
// barycentric monomial up to the rule's degree.  Some weights are negative, so the sum
// cancels: its round-off is a few ε times Σ_p |w_p| λ(x_p)^a, not times the integral
// (Σ_p |w_p| is 25 |T| at degree 9, 116 |T| at degree 13), and relative to a small
// integral such as ∫ λ0 λ3⁷ it can reach 3.3e-14 (degree 8).  Measured: |error| at
// most 7.9 ε of that scale (degrees 0..12); 50 ε leaves room for another compiler's
// rounding and still fails any wrong weight or point by ten decades.
TEST(Quadrature, TetrahedronIsExactUpToItsDegree) {
  const double eps = std::numeric_limits<double>::epsilon();
  double worst_scaled = 0.0, worst_relative = 0.0;
  for (int degree = 0; degree <= 12; ++degree) {
    const auto q = cell_quadrature(3, degree);
    double sum = 0.0;
    for (int p = 0; p < q.size(); ++p) {
      sum += q.weights[p];
      const auto& x = q.points[p];
      EXPECT_GT(std::min({x[0], x[1], x[2], 1.0 - x[0] - x[1] - x[2]}), 0.0) << "a point outside the cell";
    }
    EXPECT_NEAR(sum, 1.0 / 6.0, 50 * eps * 116.0 / 6.0);
    for (int a0 = 0; a0 <= degree; ++a0)
      for (int a1 = 0; a0 + a1 <= degree; ++a1)
        for (int a2 = 0; a0 + a1 + a2 <= degree; ++a2)
          for (int a3 = 0; a0 + a1 + a2 + a3 <= degree; ++a3) {
            const std::array<int, 4> a{a0, a1, a2, a3};
            const double exact = barycentric_monomial_integral(a, 1.0 / 6.0);
            const Sum s = integrate(q, a);
            const double scaled = std::abs(s.value - exact) / (eps * s.scale);
            worst_scaled = std::max(worst_scaled, scaled);
            EXPECT_LE(scaled, 50.0) << "degree " << degree << " monomial " << a0 << a1 << a2 << a3;
            if (degree <= 9) worst_relative = std::max(worst_relative, std::abs(s.value - exact) / exact);
          }
  }
  // The bubble's mass, ∫ (256 λ0λ1λ2λ3)² = 256² · 2⁴ 3! / 11! |T|, with the degree-8 rule:
  // measured 7.7e-15 relative (the cancellation above), bounded by 4e-14.
  const double bubble = integrate(cell_quadrature(3, 8), {2, 2, 2, 2}).value;
  const double bubble_exact = barycentric_monomial_integral({2, 2, 2, 2}, 1.0 / 6.0);
  EXPECT_NEAR(bubble, bubble_exact, 4e-14 * bubble_exact);
  std::printf("  tetrahedron rules, degrees 0..12: largest error %.2g eps of sum |w f|; up to degree 9 %.2e relative "
              "(the bubble's mass %.1e)\n",
              worst_scaled, worst_relative, std::abs(bubble - bubble_exact) / bubble_exact);
}

TEST(Quadrature, TetrahedronRuleSizesAndDegree) {
  // C(s + 4, 4) points for degree 2s + 1; degree 8 (the bubble's mass) takes s = 4.
  EXPECT_EQ(cell_quadrature(3, 0).size(), 1);
  EXPECT_EQ(cell_quadrature(3, 3).size(), 5);
  EXPECT_EQ(cell_quadrature(3, 8).size(), 70);
  // ... and is not exact beyond 2s + 1 = 9: the guard against a rule that ignores its
  // argument (λ0^10 is integrated with an error of 2.4e-4 relative).
  const std::array<int, 4> a{10, 0, 0, 0};
  EXPECT_GT(std::abs(integrate(cell_quadrature(3, 8), a).value / barycentric_monomial_integral(a, 1.0 / 6.0) - 1.0), 1e-6);
}
