// Plate 60 x 60 mm with a central hole of radius 5 mm (gmsh; quadratic quadrilaterals, CPS8),
// graded from 1 mm at the hole to 5 mm at the edges.
a = 5; W = 30;
Point(1) = {-W, -W, 0, 5}; Point(2) = {W, -W, 0, 5}; Point(3) = {W, W, 0, 5}; Point(4) = {-W, W, 0, 5};
Point(5) = {0, 0, 0, 1.0};
Point(6) = {a, 0, 0, 1.0}; Point(7) = {0, a, 0, 1.0}; Point(8) = {-a, 0, 0, 1.0}; Point(9) = {0, -a, 0, 1.0};
Line(1) = {1, 2}; Line(2) = {2, 3}; Line(3) = {3, 4}; Line(4) = {4, 1};
Circle(5) = {6, 5, 7}; Circle(6) = {7, 5, 8}; Circle(7) = {8, 5, 9}; Circle(8) = {9, 5, 6};
Curve Loop(1) = {1, 2, 3, 4};
Curve Loop(2) = {5, 6, 7, 8};
Plane Surface(1) = {1, 2};
Mesh.ElementOrder = 2;
Mesh.SecondOrderIncomplete = 1;
Mesh.RecombineAll = 1;
