// half_disk.geo — the lower half of a cylinder of radius R resting on a rigid plane
// (units: mm), for the Hertz check of the contact operator (data/scenes/hertz.toml).
//
// The half disk below the diameter y = R, centre (0, R): its lowest point (0, 0)
// touches the plane y = 0 with zero gap.  The mesh is graded: size lc_c at the lowest
// point, lc at the ends of the diameter, so that the contact zone of half-width
// a ≈ 0.15 R has some ten vertices on each side.
//
// Physical groups:
//   curve "contact"   the half circle (the candidate contact zone)
//   curve "top"       the diameter, where the load is applied
//   surface "cylinder"
//
// Parameters: R (20 mm), lc (2 mm), lc_c (0.2 mm).

DefineConstant[ R = {20.0, Name "Parameters/radius R (mm)"} ];
DefineConstant[ lc = {2.0, Name "Parameters/mesh size far from the contact (mm)"} ];
DefineConstant[ lc_c = {0.2, Name "Parameters/mesh size at the contact point (mm)"} ];

Point(1) = {0, R, 0, lc};      // centre
Point(2) = {0, 0, 0, lc_c};    // lowest point, on the plane
Point(3) = {R, R, 0, lc};      // right end of the diameter
Point(4) = {-R, R, 0, lc};     // left end

Circle(1) = {2, 1, 3};   // lowest point -> right
Line(2) = {3, 4};        // the diameter, right -> left
Circle(3) = {4, 1, 2};   // left -> lowest point

Curve Loop(1) = {1, 2, 3};
Plane Surface(1) = {1};

Physical Curve("contact") = {3, 1};
Physical Curve("top") = {2};
Physical Surface("cylinder") = {1};
