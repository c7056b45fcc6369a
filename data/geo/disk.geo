// disk.geo — an elastic disk falling on a rigid plane (units: mm).
//
// Radius R = 20 mm, centre (0, 20.5): the lowest point is 0.5 mm above the obstacle,
// the plane y = 0.  This is the usual 2D test of frictionless Signorini contact in
// elastodynamics (impact of a disk): contact can only happen on the lower half.
// Area pi R^2 (the mesh is an inscribed polygon, slightly smaller).
//
// Physical groups:
//   curve "contact"  the lower half of the circle (y <= 20.5): the candidate contact zone
//   curve "free"     the upper half (traction-free)
//   surface "disk"   the disk
//
// Mesh size lc (default 2.5 mm): gmsh -2 -setnumber lc 1.25 disk.geo

DefineConstant[ R = {20.0, Name "Parameters/radius R (mm)"} ];
DefineConstant[ yc = {20.5, Name "Parameters/centre height (mm)"} ];
DefineConstant[ lc = {2.5, Name "Parameters/mesh size lc (mm)"} ];

Point(1) = {0, yc, 0, lc};        // centre
Point(2) = {0, yc - R, 0, lc};    // bottom
Point(3) = {R, yc, 0, lc};        // right
Point(4) = {0, yc + R, 0, lc};    // top
Point(5) = {-R, yc, 0, lc};       // left

// Quarter arcs (gmsh circle arcs must be smaller than pi), counter-clockwise.
Circle(1) = {2, 1, 3};   // bottom -> right
Circle(2) = {3, 1, 4};   // right -> top
Circle(3) = {4, 1, 5};   // top -> left
Circle(4) = {5, 1, 2};   // left -> bottom

Curve Loop(1) = {1, 2, 3, 4};
Plane Surface(1) = {1};

Physical Curve("contact") = {4, 1};
Physical Curve("free") = {2, 3};
Physical Surface("disk") = {1};
