// A unit square of 2 x 2 second-order (9-node) quadrilaterals: deal.II's
// reader takes first-order cells only (tests/bad_input/mesh_second_order.prm).
// Mesh with: gmsh -2 quad9_square.geo
Point(1) = {0, 0, 0, 1};
Point(2) = {1, 0, 0, 1};
Point(3) = {1, 1, 0, 1};
Point(4) = {0, 1, 0, 1};
Line(1) = {1, 2};
Line(2) = {2, 3};
Line(3) = {3, 4};
Line(4) = {4, 1};
Curve Loop(1) = {1, 2, 3, 4};
Plane Surface(1) = {1};
Transfinite Curve{1, 2, 3, 4} = 3;
Transfinite Surface{1};
Recombine Surface{1};
Physical Curve(1) = {1};
Physical Curve(2) = {2, 3, 4};
Physical Surface(1) = {1};
Mesh.ElementOrder = 2;
Mesh.MshFileVersion = 2.2;
