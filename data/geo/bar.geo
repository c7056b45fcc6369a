// bar.geo — the 1D bar [0, 2] (dimensionless units), meshed with intervals.
//
// A 1D model read through gmsh: cdyn takes the x coordinate of the nodes.  It is the
// gmsh counterpart of the built-in `interval` mesh (mesh.kind = "interval").
//
// Physical groups:
//   point "left"   x = 0
//   point "right"  x = 2
//   curve "bar"    the bar
//
// Mesh size h (default 0.25, i.e. 8 intervals): gmsh -1 -setnumber h 0.1 bar.geo

DefineConstant[ h = {0.25, Name "Parameters/mesh size h"} ];

Point(1) = {0, 0, 0, h};
Point(2) = {2, 0, 0, h};
Line(1) = {1, 2};

Physical Point("left") = {1};
Physical Point("right") = {2};
Physical Curve("bar") = {1};
