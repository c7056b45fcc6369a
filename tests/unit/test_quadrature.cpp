// test_quadrature.cpp — the rules integrate monomials exactly up to their degree.
//
// Exact values: ∫₀¹ ξ^a dξ = 1/(a+1);  ∫_T̂ ξ^a η^b = a! b! / (a+b+2)!  (the reference
// triangle (0,0),(1,0),(0,1)).  Tolerance 1e-14: the rules are exact, so only
// round-off (a few ulps times the number of points) remains.
#include <gtest/gtest.h>

#include <cmath>

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
