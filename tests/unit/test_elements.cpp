// test_elements.cpp — reference basis functions: partition of unity, nodal property,
// bubble placement, and gradients against central finite differences.
#include <gtest/gtest.h>

#include <cmath>

#include "cdyn/fe/element.hpp"

using namespace cdyn;

namespace {
const Element kAll[] = {Element::P0, Element::P1, Element::P1Bubble, Element::P2};
const cdyn::RefPoint kSamples[] = {{0.1, 0.2}, {0.3, 0.3}, {0.6, 0.1}, {0.05, 0.9}};
}  // namespace

TEST(Elements, LagrangeBasesAreNodal) {
  // P1 and P2 are Lagrange elements: φ_k(node_j) = δ_kj exactly.
  for (Element e : {Element::P1, Element::P2})
    for (int dim : {1, 2}) {
      const int n = local_dofs(e, dim);
      double v[6];
      for (int j = 0; j < n; ++j) {
        shape_values(e, dim, local_node(e, dim, j), v);
        for (int k = 0; k < n; ++k) EXPECT_NEAR(v[k], k == j ? 1.0 : 0.0, 1e-15) << to_string(e) << " dim " << dim;
      }
    }
}

TEST(Elements, PartitionOfUnity) {
  // Σ φ_k = 1 for P1 and P2; for P1+ the vertex functions alone sum to 1 (the bubble
  // is an addition, hierarchical basis).
  for (int dim : {1, 2})
    for (const auto& xi0 : kSamples) {
      const cdyn::RefPoint xi = dim == 1 ? cdyn::RefPoint{xi0[0], 0.0} : xi0;
      for (Element e : {Element::P1, Element::P2, Element::P1Bubble}) {
        double v[6];
        shape_values(e, dim, xi, v);
        double s = 0.0;
        for (int k = 0; k <= dim; ++k) s += v[k];
        if (e == Element::P2)
          for (int k = dim + 1; k < local_dofs(e, dim); ++k) s += v[k];
        EXPECT_NEAR(s, 1.0, 1e-15) << to_string(e);
      }
    }
}

TEST(Elements, BubbleIsOneAtCentroidAndVanishesOnTheBoundary) {
  for (int dim : {1, 2}) {
    double v[4];
    shape_values(Element::P1Bubble, dim, local_node(Element::P0, dim, 0), v);
    EXPECT_NEAR(v[dim + 1], 1.0, 1e-15);
    const cdyn::RefPoint on_boundary = dim == 1 ? cdyn::RefPoint{1.0, 0.0} : cdyn::RefPoint{0.4, 0.6};
    shape_values(Element::P1Bubble, dim, on_boundary, v);
    EXPECT_NEAR(v[dim + 1], 0.0, 1e-15);
  }
}

TEST(Elements, GradientsMatchFiniteDifferences) {
  // Central differences with step 1e-5 on polynomials of degree <= 3: error ~ h² f''' ≈ 1e-9.
  const double h = 1e-5;
  for (Element e : kAll)
    for (int dim : {1, 2})
      for (const auto& xi0 : kSamples) {
        const cdyn::RefPoint xi = dim == 1 ? cdyn::RefPoint{xi0[0], 0.0} : xi0;
        const int n = local_dofs(e, dim);
        std::array<double, 3> g[6];
        shape_gradients(e, dim, xi, g);
        for (int a = 0; a < dim; ++a) {
          auto xp = xi, xm = xi;
          xp[a] += h, xm[a] -= h;
          double vp[6], vm[6];
          shape_values(e, dim, xp, vp);
          shape_values(e, dim, xm, vm);
          for (int k = 0; k < n; ++k)
            EXPECT_NEAR(g[k][a], (vp[k] - vm[k]) / (2 * h), 1e-8) << to_string(e) << " dim " << dim << " dof " << k;
        }
      }
}

TEST(Elements, NamesRoundTrip) {
  for (Element e : kAll) EXPECT_EQ(element_from_string(to_string(e)), e);
  EXPECT_EQ(element_from_string("P1b"), Element::P1Bubble);
  EXPECT_THROW(element_from_string("Q1"), std::runtime_error);
}
