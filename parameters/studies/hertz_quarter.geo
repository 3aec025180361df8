// The Hertz indentation's block (parameters/hertz_indentation.prm) as
// tetrahedra graded toward the point of contact by Gmsh, for
// parameters/studies/hertz.sh: one quarter, x, y in [0, 200 mm], z in
// [-200 mm, 0], the contact at the origin. The target edge length is h0
// within r0 of the origin and grows by g per unit of distance beyond, up to
// hmax: h(r) = min(hmax, max(h0, h0 + g (r - r0))). Boundary ids as the
// scene's box: 0 at x = 0, 1 at x = 200 mm, 2 at y = 0, 3 at y = 200 mm,
// 4 at the bottom, 5 at the top (the contact face). Lengths in metres.
//   gmsh -3 -format msh2 -setnumber h0 8.33e-5 -setnumber g 0.1 \
//     hertz_quarter.geo -o block.msh
SetFactory("OpenCASCADE");
DefineConstant[ h0 = {1.25e-4, Name "h0"}, r0 = {2e-3, Name "r0"},
                g = {0.2, Name "g"}, hmax = {0.04, Name "hmax"} ];
Box(1) = {0, 0, -0.2, 0.2, 0.2, 0.2};
e = 1e-6;
Physical Surface(0) = Surface In BoundingBox{-e, -e, -0.2 - e, e, 0.2 + e, e};
Physical Surface(1) = Surface In BoundingBox{0.2 - e, -e, -0.2 - e, 0.2 + e, 0.2 + e, e};
Physical Surface(2) = Surface In BoundingBox{-e, -e, -0.2 - e, 0.2 + e, e, e};
Physical Surface(3) = Surface In BoundingBox{-e, 0.2 - e, -0.2 - e, 0.2 + e, 0.2 + e, e};
Physical Surface(4) = Surface In BoundingBox{-e, -e, -0.2 - e, 0.2 + e, 0.2 + e, -0.2 + e};
Physical Surface(5) = Surface In BoundingBox{-e, -e, -e, 0.2 + e, 0.2 + e, e};
Physical Volume(0) = {1};
Field[1] = MathEval;
Field[1].F = Sprintf("Min(%g, Max(%g, %g + %g * (Sqrt(x*x + y*y + z*z) - %g)))",
                     hmax, h0, h0, g, r0);
Background Field = 1;
Mesh.MeshSizeExtendFromBoundary = 0;
Mesh.MeshSizeFromPoints = 0;
Mesh.MeshSizeFromCurvature = 0;
Mesh.Algorithm3D = 10; // HXT
