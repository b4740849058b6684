// One elastic hemisphere of radius R = 50 mm, meshed with hexahedra (tets
// split into hexes), graded towards the pole at the origin where the two
// hemispheres of the scene touch.
//   s = +1: upper body, centre (0, 0, R), curved face down:
//           physical volume 1, curved face 10, flat face 11 (z = R)
//   s = -1: lower body, centre (0, 0, -R), curved face up:
//           physical volume 2, curved face 20, flat face 21 (z = -R)
// Regenerate (Gmsh 4.11):
//   gmsh -3 hemisphere.geo -setnumber s 1 -o hemisphere_upper.msh
//   gmsh -3 hemisphere.geo -setnumber s -1 -o hemisphere_lower.msh
SetFactory("OpenCASCADE");
R = 0.05;
DefineConstant[ s = 1 ];
DefineConstant[ hc = 4e-3 ];   // element size at the pole (before the split)
DefineConstant[ hf = 2e-2 ];   // far from it
If (s > 0)
  Sphere(1) = {0, 0, R, R, -Pi/2, 0, 2*Pi};
Else
  Sphere(1) = {0, 0, -R, R, 0, Pi/2, 2*Pi};
EndIf
flat() = Surface In BoundingBox{-2*R, -2*R, s*R - 1e-6, 2*R, 2*R, s*R + 1e-6};
all() = Boundary{ Volume{1}; };
curved() = all();
curved() -= flat();
Field[1] = MathEval;
Field[1].F = Sprintf("%g + (%g - %g) * Min(1, Sqrt(x^2 + y^2 + z^2) / (0.8 * %g))", hc, hf, hc, R);
Background Field = 1;
Mesh.MeshSizeExtendFromBoundary = 0;
Mesh.MeshSizeFromPoints = 0;
Mesh.MeshSizeFromCurvature = 0;
Mesh.SubdivisionAlgorithm = 2;
Mesh.MshFileVersion = 2.2;
id = (s > 0) ? 1 : 2;
Physical Volume(id) = {1};
Physical Surface(10 * id) = curved();
Physical Surface(10 * id + 1) = flat();
