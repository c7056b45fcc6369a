// sphere.geo — a ball of radius R = 1 resting on its lowest point, the origin, meshed
// with tetrahedra that are finer near that point: the Hertz impact scene
// (data/scenes/sphere_hertz.toml).
//
// Physical groups:
//   volume  "ball"     all the tetrahedra
//   surface "surface"  its boundary
//
// Parameters: the mesh size h away from the contact (default 0.25) and hc within 0.2
// of the lowest point (default 0.04), growing to h over a further 0.6.  From a scene:
// mesh.set = { h = 0.3, hc = 0.05 }; by hand: gmsh -3 -setnumber hc 0.05 sphere.geo.
SetFactory("OpenCASCADE");
DefineConstant[ h = {0.25, Name "Parameters/mesh size h"} ];
DefineConstant[ hc = {0.04, Name "Parameters/mesh size at the contact point hc"} ];
R = 1.0;
Sphere(1) = {0, 0, R, R};
Physical Volume("ball") = {1};
Physical Surface("surface") = {1};

Field[1] = Ball;
Field[1].Radius = 0.2;
Field[1].Thickness = 0.6;
Field[1].VIn = hc;
Field[1].VOut = h;
Field[1].XCenter = 0;
Field[1].YCenter = 0;
Field[1].ZCenter = 0;
Background Field = 1;
Mesh.MeshSizeExtendFromBoundary = 0;
Mesh.MeshSizeFromPoints = 0;
Mesh.MeshSizeFromCurvature = 0;
