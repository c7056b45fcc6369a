// fe/norms.hpp — errors of a finite element function against an exact solution.
//
//   ‖u − u_h‖_L2 = (∫ (u − u_h)²)^½,   |u − u_h|_H1 = (∫ |∇u − ∇u_h|²)^½,
// integrated cell by cell with a rule of degree 2·deg + 4, well above the
// polynomial part, so that the quadrature error does not pollute measured rates.
#pragma once

#include <Eigen/Core>
#include <array>
#include <functional>

#include "cdyn/fe/fe_space.hpp"

namespace cdyn {

// Gradient of a scalar field, (∂x u, ∂y u)(x, y, t).
using GradientField = std::function<std::array<double, 2>(double x, double y, double t)>;

// ‖u(·, t) − u_h‖_L2(Ω), u_h = Σ U_i φ_i the finite element function of the full
// coefficient vector U on W (Dirichlet values included).
double l2_error(const FESpace& W, const Eigen::VectorXd& U, const Field& u, double t = 0.0);
// |u(·, t) − u_h|_H1(Ω) = ‖∇u − ∇u_h‖_L2, from the exact gradient (1D and 2D meshes).
double h1_seminorm_error(const FESpace& W, const Eigen::VectorXd& U, const GradientField& grad_u, double t = 0.0);

}  // namespace cdyn
