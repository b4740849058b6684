// Two bodies for prm/gmsh_hertz_2d.prm: the B2 Hertz scene (half model)
// meshed by Gmsh with unstructured quadrilaterals graded towards the
// contact point. Lengths in metres.
//   body 1 (physical surface 1): quarter disc, centre (0, 0.1), R = 0.1
//   body 2 (physical surface 2): block [0, 0.1] x [-0.1, 0]
// Physical lines (they become deal.II boundary ids):
//   10 curved face of the disc (slave)     23 top of the block (master)
//   11 flat top of the disc (load)         20 symmetry side of the block
//   12 symmetry side of the disc           21 right side of the block
//                                          22 bottom of the block
// The two bodies touch at the origin but use separate points there, so the
// mesh has two distinct nodes at (0, 0) and the interface is two boundaries.
// Regenerate: gmsh -2 -format msh22 hertz_two_bodies.geo -o hertz_two_bodies.msh

R = 0.1;
h_contact = 8e-4;  // size before the split into quads (halved by it)
h_far = 1.6e-2;    // same, far from the contact

// Quarter disc
Point(1) = {0, R, 0};      // centre
Point(2) = {0, 0, 0};      // lowest point, first contact
Point(3) = {R, R, 0};
Circle(1) = {2, 1, 3};     // curved face
Line(2) = {3, 1};          // flat top
Line(3) = {1, 2};          // symmetry side
Curve Loop(1) = {1, 2, 3};
Plane Surface(1) = {1};

// Block
Point(11) = {0, 0, 0};     // its own node at the contact point
Point(12) = {0, -R, 0};
Point(13) = {R, -R, 0};
Point(14) = {R, 0, 0};
Line(11) = {11, 12};       // symmetry side
Line(12) = {12, 13};       // bottom
Line(13) = {13, 14};       // right side
Line(14) = {14, 11};       // top
Curve Loop(2) = {11, 12, 13, 14};
Plane Surface(2) = {2};

// Grading: h_contact within 10 mm of the contact point, growing to h_far
// at 60 mm.
Field[1] = Distance;
Field[1].PointsList = {2, 11};
Field[2] = Threshold;
Field[2].InField = 1;
Field[2].SizeMin = h_contact;
Field[2].SizeMax = h_far;
Field[2].DistMin = 0.01;
Field[2].DistMax = 0.06;
Background Field = 2;
Mesh.MeshSizeExtendFromBoundary = 0;
Mesh.MeshSizeFromPoints = 0;
Mesh.MeshSizeFromCurvature = 0;

// Quadrilaterals only (deal.II): recombine, then split into quads.
Mesh.Algorithm = 6;
Mesh.RecombineAll = 1;
Mesh.RecombinationAlgorithm = 1;
Mesh.SubdivisionAlgorithm = 1;
Mesh.MshFileVersion = 2.2;

Physical Surface(1) = {1};
Physical Surface(2) = {2};
Physical Curve(10) = {1};
Physical Curve(11) = {2};
Physical Curve(12) = {3};
Physical Curve(20) = {11};
Physical Curve(21) = {13};
Physical Curve(22) = {12};
Physical Curve(23) = {14};
