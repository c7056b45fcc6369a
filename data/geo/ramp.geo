// ramp.geo — the elastic disk of disk.geo above a rigid plane inclined by theta
// (units: mm): the plane goes through the origin with the unit normal
// n = (−sin theta, cos theta), i.e. it rises to the right at the angle theta.
//
// Radius R = 20 mm, centre c = (R + d) n: the disk's point nearest the plane,
// c − R n, is d = 0.5 mm above it, as in disk.geo.  The circle is split at the four
// points c ± R n, c ± R t (t = (cos theta, sin theta), along the plane), so that the
// half facing the plane is one physical curve.
//
// Physical groups:
//   curve "contact"  the half of the circle facing the plane (the candidate contact zone)
//   curve "free"     the other half (traction-free)
//   surface "disk"   the disk
//
// theta must match the scene's obstacle.normal (data/scenes/ramp.toml).
// Mesh size lc (default 2.5 mm): gmsh -2 -setnumber lc 1.25 ramp.geo

DefineConstant[ R = {20.0, Name "Parameters/radius R (mm)"} ];
DefineConstant[ d = {0.5, Name "Parameters/initial distance to the plane (mm)"} ];
DefineConstant[ theta = {30.0, Name "Parameters/inclination (degrees)"} ];
DefineConstant[ lc = {2.5, Name "Parameters/mesh size lc (mm)"} ];

a = theta * Pi / 180;
nx = -Sin(a); ny = Cos(a);   // the plane's unit normal
tx = Cos(a);  ty = Sin(a);   // the unit tangent, up the slope
cx = (R + d) * nx; cy = (R + d) * ny;

Point(1) = {cx, cy, 0, lc};                        // centre
Point(2) = {cx - R * nx, cy - R * ny, 0, lc};      // nearest the plane
Point(3) = {cx + R * tx, cy + R * ty, 0, lc};      // up the slope
Point(4) = {cx + R * nx, cy + R * ny, 0, lc};      // farthest from the plane
Point(5) = {cx - R * tx, cy - R * ty, 0, lc};      // down the slope

// Quarter arcs (gmsh circle arcs must be smaller than pi), counter-clockwise.
Circle(1) = {2, 1, 3};
Circle(2) = {3, 1, 4};
Circle(3) = {4, 1, 5};
Circle(4) = {5, 1, 2};

Curve Loop(1) = {1, 2, 3, 4};
Plane Surface(1) = {1};

Physical Curve("contact") = {4, 1};
Physical Curve("free") = {2, 3};
Physical Surface("disk") = {1};
