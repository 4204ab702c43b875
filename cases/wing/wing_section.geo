// NACA 0012 (chord 1, closed trailing edge) in a circular far field of radius 15
// chords: a structured quad layer on the wall, triangles outside. Planar, z = 0.
// The section of the wing case (make_wing.py extrudes it along z).
points_per_side = 50;
wall_size = 0.025;
far_size = 2.5;
far_radius = 10;

// Upper surface from the trailing edge to the leading edge, then the lower surface
// back; cosine spacing clusters points at both edges.
For i In {0:points_per_side}
  x = 0.5 * (1 + Cos(Pi * i / points_per_side));
  t = 0.6 * (0.2969 * Sqrt(x) - 0.1260 * x - 0.3516 * x^2 + 0.2843 * x^3 - 0.1036 * x^4);
  Point(i + 1) = {x, t, 0, wall_size};
EndFor
For i In {1:points_per_side - 1}
  x = 0.5 * (1 - Cos(Pi * i / points_per_side));
  t = 0.6 * (0.2969 * Sqrt(x) - 0.1260 * x - 0.3516 * x^2 + 0.2843 * x^3 - 0.1036 * x^4);
  Point(points_per_side + 1 + i) = {x, -t, 0, wall_size};
EndFor
leading_edge = points_per_side + 1;
upper_points[] = {1:leading_edge};
lower_points[] = {leading_edge:2 * points_per_side};
lower_points[] += {1};
Spline(1) = upper_points[];
Spline(2) = lower_points[];

Point(1001) = {0.25, 0, 0, far_size};
Point(1002) = {0.25 + far_radius, 0, 0, far_size};
Point(1003) = {0.25 - far_radius, 0, 0, far_size};
Circle(11) = {1002, 1001, 1003};
Circle(12) = {1003, 1001, 1002};

Curve Loop(21) = {11, 12};
Curve Loop(22) = {1, 2};
Plane Surface(31) = {21, 22};

// Viscous layer: first height 1e-3 chords, growth 1.15, 0.03 chords thick.
Field[1] = BoundaryLayer;
Field[1].EdgesList = {1, 2};
Field[1].FanNodesList = {1};
Field[1].hwall_n = 0.002;
Field[1].ratio = 1.2;
Field[1].thickness = 0.03;
Field[1].hfar = wall_size;
Field[1].Quads = 1;
BoundaryLayer Field = 1;

Physical Curve("airfoil") = {1, 2};
Physical Curve("farfield") = {11, 12};
Physical Surface("fluid") = {31};
Mesh.MshFileVersion = 2.2;
