// Two unit squares side by side, one of quadrilaterals, one of triangles: a
// mixed mesh, refused by tests/bad_input/mesh_mixed.prm.
// Mesh with: gmsh -2 mixed_square.geo
Point(1) = {0, 0, 0, 0.5};
Point(2) = {1, 0, 0, 0.5};
Point(3) = {1, 1, 0, 0.5};
Point(4) = {0, 1, 0, 0.5};
Point(5) = {2, 0, 0, 0.5};
Point(6) = {2, 1, 0, 0.5};
Line(1) = {1, 2};
Line(2) = {2, 3};
Line(3) = {3, 4};
Line(4) = {4, 1};
Line(5) = {2, 5};
Line(6) = {5, 6};
Line(7) = {6, 3};
Curve Loop(1) = {1, 2, 3, 4};
Plane Surface(1) = {1};
Curve Loop(2) = {5, 6, 7, -2};
Plane Surface(2) = {2};
Transfinite Curve{1, 2, 3, 4} = 3;
Transfinite Surface{1};
Recombine Surface{1};
Physical Curve(1) = {1, 5};
Physical Curve(2) = {3, 4, 6, 7};
Physical Surface(1) = {1, 2};
Mesh.MshFileVersion = 2.2;
