// Rubber block W x H on the plane y = 0, pressed by a pressure on its top (issue 50: the static start
// in finite strain, options/rubber_block_press.opts). Plane strain.
// Physical names: body (surface), base (y = 0: the contact face), top, sides, and pin (the top
// middle point, held in x: the frictionless plane does not hold the block's horizontal translation).
// Parameters: W, H, NX x NY cells (structured triangles).
DefineConstant[ W = 1, H = 0.5, NX = 16, NY = 8 ];
Point(1) = {0, 0, 0}; Point(2) = {W, 0, 0}; Point(3) = {W, H, 0}; Point(4) = {0, H, 0};
Point(5) = {W / 2, H, 0};
Line(1) = {1, 2}; Line(2) = {2, 3}; Line(3) = {3, 5}; Line(4) = {4, 1}; Line(5) = {5, 4};
Curve Loop(1) = {1, 2, 3, 5, 4};
Plane Surface(1) = {1};
Transfinite Curve{1} = NX + 1;
Transfinite Curve{3, 5} = NX / 2 + 1;
Transfinite Curve{2, 4} = NY + 1;
Transfinite Surface{1} = {1, 2, 3, 4};
Physical Surface("body") = {1};
Physical Curve("base") = {1};
Physical Curve("top") = {3, 5};
Physical Curve("sides") = {2, 4};
Physical Point("pin") = {5};
Mesh.MshFileVersion = 4.1;
