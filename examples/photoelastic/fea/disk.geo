// Disk of radius 25 mm for diametral compression (gmsh; quadratic triangles, CPS6), graded
// towards the load points (0, +-25).
R = 25;
Point(1) = {0, 0, 0};
Point(2) = {R, 0, 0};
Point(3) = {0, R, 0};
Point(4) = {-R, 0, 0};
Point(5) = {0, -R, 0};
Circle(1) = {2, 1, 3};
Circle(2) = {3, 1, 4};
Circle(3) = {4, 1, 5};
Circle(4) = {5, 1, 2};
Curve Loop(1) = {1, 2, 3, 4};
Plane Surface(1) = {1};
Field[1] = Distance;
Field[1].PointsList = {3, 5};
Field[2] = Threshold;
Field[2].InField = 1;
Field[2].SizeMin = 0.4;
Field[2].SizeMax = 3;
Field[2].DistMin = 0.5;
Field[2].DistMax = 15;
Background Field = 2;
Mesh.MeshSizeExtendFromBoundary = 0;
Mesh.MeshSizeFromPoints = 0;
Mesh.ElementOrder = 2;
