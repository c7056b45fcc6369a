// rigid_obstacle.cpp — planes and the gradient of a gap function.
#include "cdyn/problems/rigid_obstacle.hpp"

#include <cmath>

#include "cdyn/base/error.hpp"

namespace cdyn {

RigidObstacle RigidObstacle::plane(Point p, Point n, std::vector<int> contact_parts) {
  // (the two-argument hypot in the plane, bit-compatible with the 2D formulas)
  const double norm = n.z == 0.0 ? std::hypot(n.x, n.y) : std::hypot(n.x, n.y, n.z);
  if (!(norm > 0.0) || !std::isfinite(norm)) throw InputError("normal", "must be a nonzero finite vector");
  const Point u{n.x / norm, n.y / norm, n.z / norm};
  RigidObstacle o;
  o.name = "plane";
  o.gap = [p, u](const Point& x, double) { return (x.x - p.x) * u.x + (x.y - p.y) * u.y + (x.z - p.z) * u.z; };
  o.gradient = [u](const Point&) { return u; };
  o.contact_parts = std::move(contact_parts);
  o.origin = p;
  return o;
}

RigidObstacle RigidObstacle::moving_plane(std::function<Point(double)> p, Point n, std::vector<int> contact_parts) {
  RigidObstacle o = plane(p(0.0), n, std::move(contact_parts));
  const Point u = o.gradient(Point{});
  o.gap = [p, u](const Point& x, double t) {
    const Point q = p(t);
    return (x.x - q.x) * u.x + (x.y - q.y) * u.y + (x.z - q.z) * u.z;
  };
  o.moves = true;
  return o;
}

ObstacleNormal obstacle_normal(const RigidObstacle& o, const Point& x, double h, int dim) {
  if (o.gradient) return {o.gradient(x), 1.0};
  auto d = [&](Point e) {
    const Point a{x.x + h * e.x, x.y + h * e.y, x.z + h * e.z}, b{x.x - h * e.x, x.y - h * e.y, x.z - h * e.z};
    return (o.gap(a, 0.0) - o.gap(b, 0.0)) / (2 * h);
  };
  // in the mesh's own dimensions: a gap "z" has no gradient in the plane of a 2D body
  const Point G{d({1, 0, 0}), dim > 1 ? d({0, 1, 0}) : 0.0, dim > 2 ? d({0, 0, 1}) : 0.0};
  const double s = std::hypot(G.x, G.y, G.z);
  if (!(s > 0.0) || !std::isfinite(s))
    throw InputError("gap", "the gap function has no gradient at (" + std::to_string(x.x) + ", " +
                                std::to_string(x.y) + "), so no normal there (obstacle " + o.name + ")");
  return {{G.x / s, G.y / s, G.z / s}, s};
}

}  // namespace cdyn
