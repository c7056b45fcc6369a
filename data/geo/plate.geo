// plate.geo — a flat elastic plate resting on a rigid plane (units: m).
//
// The rectangle [0, L] x [0, H], L = 0.4 m, H = 0.05 m, its lower side on the obstacle
// (the plane y = 0), a structured mesh of nx × ny cells, each split into two triangles.
// Flat, so that the moment of a weight tilted by θ varies the contact pressure along the
// base by only ±3 tan θ H/L (±14 % at θ = 20°): the base sticks or slips as a whole,
// as the block of the textbook inclined plane.
//
// Physical groups:
//   curve "bottom"   the lower side: the contact zone
//   curve "top"      the upper side (traction-free)
//   curve "ends"     the two short sides (traction-free)
//   surface "plate"  the plate
//
// Parameters (gmsh -2 -setnumber nx 64 plate.geo): L, H, nx (default 32), ny (default 4).

DefineConstant[ L = {0.4, Name "Parameters/length L (m)"} ];
DefineConstant[ H = {0.05, Name "Parameters/thickness H (m)"} ];
DefineConstant[ nx = {32, Name "Parameters/cells along the plate"} ];
DefineConstant[ ny = {4, Name "Parameters/cells across the plate"} ];

Point(1) = {0, 0, 0};
Point(2) = {L, 0, 0};
Point(3) = {L, H, 0};
Point(4) = {0, H, 0};

Line(1) = {1, 2};   // bottom
Line(2) = {2, 3};   // right end
Line(3) = {3, 4};   // top
Line(4) = {4, 1};   // left end

Curve Loop(1) = {1, 2, 3, 4};
Plane Surface(1) = {1};
Transfinite Curve{1, 3} = nx + 1;
Transfinite Curve{2, 4} = ny + 1;
Transfinite Surface{1};

Physical Curve("bottom") = {1};
Physical Curve("top") = {3};
Physical Curve("ends") = {2, 4};
Physical Surface("plate") = {1};
