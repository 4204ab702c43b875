// A 2 x 1 x 1 block with all four cell types, meshed by Gmsh alone:
//   z in [0, 0.3]  boundary layer extruded from the floor in 3 layers: the left half
//                  of the floor is a recombined (quad) grid -> hexahedra, the right
//                  half triangles -> prisms;
//   z in [0.3, 1]  unstructured tetrahedra; Gmsh closes the quads on top of the
//                  hexahedra with pyramids.
// Regenerate: gmsh -3 -format msh41 mixed_block.geo -o mixed_block.msh
lc = 0.25;
Point(1) = {0, 0, 0, lc};
Point(2) = {1, 0, 0, lc};
Point(3) = {2, 0, 0, lc};
Point(4) = {2, 1, 0, lc};
Point(5) = {1, 1, 0, lc};
Point(6) = {0, 1, 0, lc};
Line(1) = {1, 2};
Line(2) = {2, 5};
Line(3) = {5, 6};
Line(4) = {6, 1};
Line(5) = {2, 3};
Line(6) = {3, 4};
Line(7) = {4, 5};
Curve Loop(1) = {1, 2, 3, 4};
Plane Surface(1) = {1};
Curve Loop(2) = {5, 6, 7, -2};
Plane Surface(2) = {2};
Transfinite Curve {1, 2, 3, 4} = 5;
Transfinite Surface {1};
Recombine Surface {1};

layer[] = Extrude {0, 0, 0.3} { Surface {1, 2}; Layers {3}; Recombine; };
// layer[0] top of surface 1, layer[1] its volume, layer[2..5] its sides;
// layer[6] top of surface 2, layer[7] its volume.
outer[] = Extrude {0, 0, 0.7} { Surface {layer[0], layer[6]}; };

e = 1e-6;
Physical Surface("wall") = Surface In BoundingBox {-e, -e, -e, 2 + e, 1 + e, e};
Physical Surface("top") = Surface In BoundingBox {-e, -e, 1 - e, 2 + e, 1 + e, 1 + e};
sides[] = Surface In BoundingBox {-e, -e, -e, e, 1 + e, 1 + e};
sides[] += Surface In BoundingBox {2 - e, -e, -e, 2 + e, 1 + e, 1 + e};
sides[] += Surface In BoundingBox {-e, -e, -e, 2 + e, e, 1 + e};
sides[] += Surface In BoundingBox {-e, 1 - e, -e, 2 + e, 1 + e, 1 + e};
Physical Surface("sides") = sides[];
Physical Volume("layer", 1) = {layer[1], layer[7]};
Physical Volume("outer", 2) = {outer[1], outer[7]};
