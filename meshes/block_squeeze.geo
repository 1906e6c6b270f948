// Block W x H squeezed between two plates, y = 0 below and y = H + gap above (case block_squeeze;
// plane strain). The plates are obstacle options, not part of the mesh.
// Physical names: body (surface), contact (base y = 0 and top y = H: the faces the plates touch),
// sides (x = 0 and x = W, free).
// Parameters: W, H, NX x NY cells (structured triangles with alternating diagonals: for an even
// NX the mesh is mirror-symmetric about x = W/2, like the squeeze).
DefineConstant[ W = 1, H = 0.5, NX = 20, NY = 10 ];
Point(1) = {0, 0, 0}; Point(2) = {W, 0, 0}; Point(3) = {W, H, 0}; Point(4) = {0, H, 0};
Line(1) = {1, 2}; Line(2) = {2, 3}; Line(3) = {3, 4}; Line(4) = {4, 1};
Curve Loop(1) = {1, 2, 3, 4};
Plane Surface(1) = {1};
Transfinite Curve{1, 3} = NX + 1;
Transfinite Curve{2, 4} = NY + 1;
Transfinite Surface{1} = {1, 2, 3, 4} Alternate;
Physical Surface("body") = {1};
Physical Curve("contact") = {1, 3};
Physical Curve("sides") = {2, 4};
Mesh.MshFileVersion = 4.1;
