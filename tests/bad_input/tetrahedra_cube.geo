// A unit cube meshed with linear tetrahedra (Gmsh's default in 3D), which
// Signorini refuses (tests/bad_input/mesh_tetrahedra.prm).
// Mesh with: gmsh -3 tetrahedra_cube.geo
Point(1) = {0, 0, 0, 2};
Point(2) = {1, 0, 0, 2};
Point(3) = {1, 1, 0, 2};
Point(4) = {0, 1, 0, 2};
Line(1) = {1, 2};
Line(2) = {2, 3};
Line(3) = {3, 4};
Line(4) = {4, 1};
Curve Loop(1) = {1, 2, 3, 4};
Plane Surface(1) = {1};
out[] = Extrude {0, 0, 1} { Surface{1}; };
Physical Surface(1) = {1, out[0]};
Physical Surface(2) = {out[2], out[3], out[4], out[5]};
Physical Volume(1) = {out[1]};
Mesh.MshFileVersion = 2.2;
