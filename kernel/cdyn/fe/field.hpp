// field.hpp — a scalar datum of space and time, f(x, t): the seed's loads f and g
// (eqs. 1, 3), initial states u₀, u₁ (eq. 5), Dirichlet values (eq. 4) and obstacles
// (the α of eq. 16) before they are interpolated or integrated.
//
// A Field is called with a point (x, y, z) and a time t.  It can be made from any
// callable of the point and t, or, for code written for 1D/2D problems, from a callable
// of (x, y, t) (then z is not seen) or of (x, y, z, t):
//     Field f = [](double x, double y, double t) { return -0.6; };
//     Field g = [](const Point& p, double t) { return p.z - 1 + t; };
#pragma once

#include <functional>
#include <type_traits>
#include <utility>

#include "cdyn/mesh/mesh.hpp"

namespace cdyn {

class Field {
 public:
  Field() = default;

  template <class F>
    requires std::is_invocable_r_v<double, F&, const Point&, double>
  Field(F f) : f_(std::move(f)) {}

  template <class F>
    requires(std::is_invocable_r_v<double, F&, double, double, double, double> &&
             !std::is_invocable_r_v<double, F&, const Point&, double>)
  Field(F f) : f_([f = std::move(f)](const Point& p, double t) mutable { return f(p.x, p.y, p.z, t); }) {}

  template <class F>
    requires(std::is_invocable_r_v<double, F&, double, double, double> &&
             !std::is_invocable_r_v<double, F&, double, double, double, double> &&
             !std::is_invocable_r_v<double, F&, const Point&, double>)
  Field(F f) : f_([f = std::move(f)](const Point& p, double t) mutable { return f(p.x, p.y, t); }) {}

  // The value at p (no (x, y, t) shorthand: in 3D it would silently drop z).
  double operator()(const Point& p, double t) const { return f_(p, t); }

  explicit operator bool() const { return static_cast<bool>(f_); }

  // Whether the value may vary with the point (true unless the field was marked
  // uniform: an expression without x, y, z, e.g. a load "-0.6 + 3*sin(60*t)").  The
  // assembly evaluates a uniform field once per time instead of at every quadrature
  // point (fe/assembly.cpp): the same integrals, one evaluation of the expression.
  bool depends_on_space() const { return depends_on_space_; }
  Field& uniform_in_space() {
    depends_on_space_ = false;
    return *this;
  }

 private:
  std::function<double(const Point&, double)> f_;
  bool depends_on_space_ = true;
};

}  // namespace cdyn
