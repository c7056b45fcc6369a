// rigid_obstacle.hpp — a rigid obstacle given by its signed gap function, for the nodal
// Signorini condition of seed eq. (6).
//
// The body must stay where φ(x, t) ≥ 0: φ > 0 outside the obstacle, φ = 0 on its
// surface.  A plane through p(t) with unit normal n (pointing from the obstacle into the
// body's side) is φ(x, t) = (x − p(t))·n; a rigid cylinder of radius R centred at c is
// φ(x) = |x − c| − R (the body outside it) or R − |x − c| (the body inside a bowl).  The
// condition is nodal and linearized at each contact vertex a, as the seed's small-strain
// setting writes it (u_N ≤ gap):
//     φ(a + u(a), t) ≈ φ(a, t) + ∇φ(a, 0)·u(a) ≥ 0
//       ⇔  n(a)·u(a) ≥ g(a, t) := −φ(a, t) / |∇φ(a, 0)|,   n(a) = ∇φ(a, 0)/|∇φ(a, 0)|,
// the membrane's lower bound u ≥ g with e_y replaced by the obstacle's outward normal at
// a, taken at t = 0 (the node-local rotation of problems/nodal_rotation.hpp is fixed for
// a run: an obstacle that moves keeps its normals; one that turns is approximated).  For a
// plane the linearization is exact.  The distance of a point x to the obstacle is
// d(x, t) = φ(x, t)/|∇φ(a, 0)| near a (exact for a plane), what contact.csv's gap reports.
#pragma once

#include <functional>
#include <string>
#include <vector>

#include "cdyn/fe/field.hpp"
#include "cdyn/mesh/mesh.hpp"
#include "cdyn/problems/friction.hpp"

namespace cdyn {

struct RigidObstacle {
  std::string name;                  // for messages ("obstacle 1", a scene's name)
  Field gap;                         // φ(x, t)
  bool moves = false;                // φ depends on t (the bounds are updated every step)
  std::vector<int> contact_parts;    // Γ_C: the boundary parts that may touch it (indices into part_names; -1 untagged)
  Point origin;                      // a point of reference: the plane's p (contact.csv's s is measured from it)

  // ∇φ(x, 0) when the caller knows it and φ is a distance (|∇φ| = 1: a plane); else
  // central differences of φ at x with a step of 1e-6 of the mesh size (the normal only
  // defines the direction the constraint acts in).
  std::function<Point(const Point&)> gradient;

  // Friction between the body and this obstacle (problems/friction.hpp): none by default.
  FrictionSpec friction;

  // The plane through p with normal n (normalized; InputError "normal" if zero).
  static RigidObstacle plane(Point p, Point n, std::vector<int> contact_parts);
  // The plane through p(t) with normal n: a plane that moves (a translation).
  static RigidObstacle moving_plane(std::function<Point(double)> p, Point n, std::vector<int> contact_parts);
};

// The unit outward normal n(x) = ∇φ(x, 0)/|∇φ(x, 0)| and |∇φ(x, 0)| (1 for a given
// gradient); central differences with step h in the first `dim` coordinates otherwise
// (the mesh's dimension).  InputError naming the obstacle where ∇φ vanishes.
struct ObstacleNormal {
  Point n;
  double scale = 1.0;
};
ObstacleNormal obstacle_normal(const RigidObstacle& o, const Point& x, double h, int dim);

}  // namespace cdyn
