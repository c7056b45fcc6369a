// two_layer.geo — a column of two materials on a rigid plane (units: mm), for
// data/scenes/two_layer.toml: a soft layer below a stiff one.
//
//   y = 20  +---------+   top      (loaded)
//           |  stiff  |
//   y = 10  +---------+   the interface, a line of the mesh: each triangle lies in
//           |  soft   |   one material
//   y = 0   +---------+   bottom   (on the plane y = 0: the contact zone)
//           x = 0     x = 10
//
// Physical groups:
//   curve "bottom"   y = 0 (Γ_C)
//   curve "top"      y = 20 (the pressure)
//   curve "sides"    x = 0 and x = 10 (rollers)
//   surface "soft"   the lower layer, surface "stiff" the upper one
//
// Parameter: the mesh size h (default 1 mm).  From a scene: mesh.set = { h = 0.5 };
// by hand: gmsh -2 -setnumber h 0.5 two_layer.geo.

DefineConstant[ h = {1.0, Name "Parameters/mesh size h (mm)"} ];
width = 10.0;
h1 = 10.0;    // thickness of the soft layer
h2 = 10.0;    // thickness of the stiff layer

Point(1) = {0, 0, 0, h};
Point(2) = {width, 0, 0, h};
Point(3) = {width, h1, 0, h};
Point(4) = {0, h1, 0, h};
Point(5) = {width, h1 + h2, 0, h};
Point(6) = {0, h1 + h2, 0, h};

Line(1) = {1, 2};   // bottom
Line(2) = {2, 3};   // right side, soft
Line(3) = {3, 4};   // the interface
Line(4) = {4, 1};   // left side, soft
Line(5) = {3, 5};   // right side, stiff
Line(6) = {5, 6};   // top
Line(7) = {6, 4};   // left side, stiff

Curve Loop(1) = {1, 2, 3, 4};
Plane Surface(1) = {1};
Curve Loop(2) = {-3, 5, 6, 7};
Plane Surface(2) = {2};

Physical Curve("bottom") = {1};
Physical Curve("top") = {6};
Physical Curve("sides") = {2, 4, 5, 7};
Physical Surface("soft") = {1};
Physical Surface("stiff") = {2};
