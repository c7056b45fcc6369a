// box.geo — a box [0, 2] × [0, 1] × [0, 1] meshed with tetrahedra, the 3D counterpart
// of the unit square scenes read through gmsh (cdyn mesh, tests, 3D scenes).
//
//           z
//           |  +--------------+     "top"    z = 1
//           | /|             /|
//           |/ |            / |     "sides"  y = 0, y = 1, x = 2
//           +--------------+  |
//           |  +-----------|--+     "bottom" z = 0
//           | /            | /
//           |/             |/       "left"   x = 0
//           +--------------+----- x
//
// Physical groups:
//   volume  "solid"                       all the tetrahedra
//   surface "bottom", "top", "left", "sides"  the boundary, every triangle in one part
//
// Parameter: the mesh size h (default 0.25).  From a scene: mesh.set = { h = 0.5 };
// by hand: gmsh -3 -setnumber h 0.5 box.geo.

DefineConstant[ h = {0.25, Name "Parameters/mesh size h"} ];
Lx = 2.0;

Point(1) = {0, 0, 0, h};
Point(2) = {Lx, 0, 0, h};
Point(3) = {Lx, 1, 0, h};
Point(4) = {0, 1, 0, h};
Line(1) = {1, 2};
Line(2) = {2, 3};
Line(3) = {3, 4};
Line(4) = {4, 1};
Curve Loop(1) = {1, 2, 3, 4};
Plane Surface(1) = {1};

// The bottom swept up by 1: out[0] is the top, out[1] the volume, out[2..5] the sides
// swept from lines 1..4 (y = 0, x = Lx, y = 1, x = 0).
out[] = Extrude {0, 0, 1} { Surface{1}; };

Physical Volume("solid") = {out[1]};
Physical Surface("bottom") = {1};
Physical Surface("top") = {out[0]};
Physical Surface("left") = {out[5]};
Physical Surface("sides") = {out[2], out[3], out[4]};
