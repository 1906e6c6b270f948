// Block W x H on the floor y = 0, pushed from the left by a moving plate (case block_push; plane
// strain). The floor and the plate are obstacle options, not part of the mesh.
// Physical names: body (surface), contact (base y = 0 and left face x = 0: the faces the floor and
// the plate touch), top (y = H), right (x = W).
// Parameters: W, H, NX x NY cells (structured triangles).
DefineConstant[ W = 1, H = 0.5, NX = 20, NY = 10 ];
Point(1) = {0, 0, 0}; Point(2) = {W, 0, 0}; Point(3) = {W, H, 0}; Point(4) = {0, H, 0};
Line(1) = {1, 2}; Line(2) = {2, 3}; Line(3) = {3, 4}; Line(4) = {4, 1};
Curve Loop(1) = {1, 2, 3, 4};
Plane Surface(1) = {1};
Transfinite Curve{1, 3} = NX + 1;
Transfinite Curve{2, 4} = NY + 1;
Transfinite Surface{1} = {1, 2, 3, 4};
Physical Surface("body") = {1};
Physical Curve("contact") = {1, 4};
Physical Curve("top") = {3};
Physical Curve("right") = {2};
Mesh.MshFileVersion = 4.1;
