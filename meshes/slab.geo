// Slab W x W x H on the plane z = 0, structured: NX x NX x NZ hexahedra, each split into 6
// tetrahedra (no Recombine), so the base holds (NX + 1)^2 contact nodes exactly.
// Physical names: body (volume), base (z = 0: the contact face), top (z = H: the press), sides.
DefineConstant[ W = 1, H = 0.035, NX = 144, NZ = 5 ];
Point(1) = {0, 0, 0}; Point(2) = {W, 0, 0}; Point(3) = {W, W, 0}; Point(4) = {0, W, 0};
Line(1) = {1, 2}; Line(2) = {2, 3}; Line(3) = {3, 4}; Line(4) = {4, 1};
Curve Loop(1) = {1, 2, 3, 4};
Plane Surface(1) = {1};
Transfinite Curve{1, 2, 3, 4} = NX + 1;
Transfinite Surface{1};
ext[] = Extrude{0, 0, H} { Surface{1}; Layers{NZ}; };
// ext[0]: the top surface, ext[1]: the volume, ext[2..5]: the sides
Physical Volume("body") = {ext[1]};
Physical Surface("base") = {1};
Physical Surface("top") = {ext[0]};
Physical Surface("sides") = {ext[2], ext[3], ext[4], ext[5]};
Mesh.MshFileVersion = 4.1;
