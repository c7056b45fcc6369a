// box.geo — a box [0, 2] × [0, 1] × [0, 1] meshed with tetrahedra, the 3D counterpart
// of the unit square scenes read through gmsh (cdyn mesh, tests, 3D scenes).
//
//           z
//           |  +--------------+     "top"    z = Lz
//           | /|             /|
//           |/ |            / |     "sides"  y = 0, y = Ly, x = 2
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
// Parameters: the mesh size h (default 0.25), the width Ly and the height Lz (default 1:
// the box [0, 2] × [0, 1] × [0, 1] above).  From a scene: mesh.set = { h = 0.5 }; by
// hand: gmsh -3 -setnumber h 0.5 box.geo.

DefineConstant[ h = {0.25, Name "Parameters/mesh size h"} ];
DefineConstant[ Ly = {1.0, Name "Parameters/width Ly"} ];
DefineConstant[ Lz = {1.0, Name "Parameters/height Lz"} ];
Lx = 2.0;

Point(1) = {0, 0, 0, h};
Point(2) = {Lx, 0, 0, h};
Point(3) = {Lx, Ly, 0, h};
Point(4) = {0, Ly, 0, h};
Line(1) = {1, 2};
Line(2) = {2, 3};
Line(3) = {3, 4};
Line(4) = {4, 1};
Curve Loop(1) = {1, 2, 3, 4};
Plane Surface(1) = {1};

// The bottom swept up by Lz: out[0] is the top, out[1] the volume, out[2..5] the sides
// swept from lines 1..4 (y = 0, x = Lx, y = Ly, x = 0).
out[] = Extrude {0, 0, Lz} { Surface{1}; };

Physical Volume("solid") = {out[1]};
Physical Surface("bottom") = {1};
Physical Surface("top") = {out[0]};
Physical Surface("left") = {out[5]};
Physical Surface("sides") = {out[2], out[3], out[4]};
