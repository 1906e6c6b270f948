// A block sliding along a longer block (case block_slide, issue 40: contact pairs under large
// sliding), plane strain. The master block is [0, L] x [0, H] (NX x NY cells: NX facets of length
// L/NX on its top), the slave block [X0, X0 + W] x [H, H + HS] (MX x MY cells) on top of it, touching
// (gap 0). The meshes do not match at the interface: the slave's bottom nodes are W/MX apart, the
// master's top nodes L/NX.
// Physical names: master, slave (surfaces); master_top (the master surface of the pair),
// slave_bottom (its slave surface), master_bottom and slave_top (the loads that press the blocks
// together), master_sides, slave_sides.
// Parameters (gmsh -setnumber): L, H, NX, NY, X0, W, HS, MX, MY.
DefineConstant[ L = 2, H = 0.2, NX = 20, NY = 4, X0 = 0.3, W = 0.4, HS = 0.2, MX = 7, MY = 3 ];
// master
Point(1) = {0, 0, 0}; Point(2) = {L, 0, 0}; Point(3) = {L, H, 0}; Point(4) = {0, H, 0};
Line(1) = {1, 2}; Line(2) = {2, 3}; Line(3) = {3, 4}; Line(4) = {4, 1};
Curve Loop(1) = {1, 2, 3, 4};
Plane Surface(1) = {1};
Transfinite Curve{1, 3} = NX + 1;
Transfinite Curve{2, 4} = NY + 1;
Transfinite Surface{1} = {1, 2, 3, 4} Alternate;
// slave
Point(5) = {X0, H, 0}; Point(6) = {X0 + W, H, 0}; Point(7) = {X0 + W, H + HS, 0}; Point(8) = {X0, H + HS, 0};
Line(5) = {5, 6}; Line(6) = {6, 7}; Line(7) = {7, 8}; Line(8) = {8, 5};
Curve Loop(2) = {5, 6, 7, 8};
Plane Surface(2) = {2};
Transfinite Curve{5, 7} = MX + 1;
Transfinite Curve{6, 8} = MY + 1;
Transfinite Surface{2} = {5, 6, 7, 8} Alternate;
Physical Surface("master") = {1};
Physical Surface("slave") = {2};
Physical Curve("master_top") = {3};
Physical Curve("slave_bottom") = {5};
Physical Curve("master_bottom") = {1};
Physical Curve("slave_top") = {7};
Physical Curve("master_sides") = {2, 4};
Physical Curve("slave_sides") = {6, 8};
Mesh.MshFileVersion = 4.1;
