// beam.geo — a thin elastic beam lying flat above a rigid plane (units: mm).
//
// The rectangle [-L/2, L/2] x [yb, yb + H], L = 100 mm, H = 2 mm, its lower side 0.5 mm
// above the obstacle (the plane y = 0).  A structured mesh of nx cells along the beam
// and ny across (each cell split into two triangles): ny = 1 is the thin structure of
// docs/elasticity.md, one cell thick, where every vertex lies on the top or the bottom side.
//
// Physical groups:
//   curve "bottom"   the lower side: the contact zone
//   curve "top"      the upper side (traction-free)
//   curve "ends"     the two short sides (traction-free)
//   surface "beam"   the beam
//
// Parameters (gmsh -2 -setnumber ny 2 beam.geo): L, H, yb, nx (default 50), ny
// (default 1).  A .geo that sets ny before `Include "beam.geo";` overrides it too
// (beam_two_cells.geo), since DefineConstant keeps a value already defined.

DefineConstant[ L = {100.0, Name "Parameters/length L (mm)"} ];
DefineConstant[ H = {2.0, Name "Parameters/thickness H (mm)"} ];
DefineConstant[ yb = {0.5, Name "Parameters/height of the lower side (mm)"} ];
DefineConstant[ nx = {50, Name "Parameters/cells along the beam"} ];
DefineConstant[ ny = {1, Name "Parameters/cells across the beam"} ];

Point(1) = {-L / 2, yb, 0};
Point(2) = {L / 2, yb, 0};
Point(3) = {L / 2, yb + H, 0};
Point(4) = {-L / 2, yb + H, 0};

Line(1) = {1, 2};   // bottom
Line(2) = {2, 3};   // right end
Line(3) = {3, 4};   // top
Line(4) = {4, 1};   // left end

Curve Loop(1) = {1, 2, 3, 4};
Plane Surface(1) = {1};
Transfinite Curve{1, 3} = nx + 1;
Transfinite Curve{2, 4} = ny + 1;
Transfinite Surface{1};   // triangles: each structured cell cut along a diagonal

Physical Curve("bottom") = {1};
Physical Curve("top") = {3};
Physical Curve("ends") = {2, 4};
Physical Surface("beam") = {1};
