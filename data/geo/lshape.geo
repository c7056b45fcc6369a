// lshape.geo — the L-shaped membrane [0,1]^2 minus [0.5,1]^2 (dimensionless units).
//
// The classic domain with a re-entrant corner at (0.5, 0.5), where the solution of
// the Laplacian is singular (r^(2/3)): it shows how the schemes behave when the
// displacement is not smooth.  Area 0.75, perimeter 4.
//
// Physical groups (what `cdyn mesh` and a scene's dirichlet.parts / obstacle.where see):
//   curve "outer"      the four sides on the boundary of the unit square (length 3)
//   curve "reentrant"  the two sides of the removed quarter (length 1)
//   surface "membrane" the domain
//
// Mesh size h (default 0.1) can be changed without editing: gmsh -2 -setnumber h 0.05 lshape.geo

DefineConstant[ h = {0.1, Name "Parameters/mesh size h"} ];

Point(1) = {0.0, 0.0, 0, h};
Point(2) = {1.0, 0.0, 0, h};
Point(3) = {1.0, 0.5, 0, h};
Point(4) = {0.5, 0.5, 0, h};   // the re-entrant corner
Point(5) = {0.5, 1.0, 0, h};
Point(6) = {0.0, 1.0, 0, h};

Line(1) = {1, 2};   // bottom
Line(2) = {2, 3};   // right
Line(3) = {3, 4};   // re-entrant, horizontal
Line(4) = {4, 5};   // re-entrant, vertical
Line(5) = {5, 6};   // top
Line(6) = {6, 1};   // left

Curve Loop(1) = {1, 2, 3, 4, 5, 6};   // counter-clockwise
Plane Surface(1) = {1};

Physical Curve("outer") = {1, 2, 5, 6};
Physical Curve("reentrant") = {3, 4};
Physical Surface("membrane") = {1};
