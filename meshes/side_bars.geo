// Two separate bars side by side for the bodies tests (tests/test_bodies.py), meshes/side_bars.msh: "bar_a" is
// [0, L] x [0, W] with Na cells along x, "bar_b" is [0, L] x [2W, 3W] with Nb cells, two
// components of one mesh that share no node, plane strain, M cells across. Their ends x = 0 are
// the physical curve "left" (a contact boundary), their ends x = L "right". The defaults give
// bar_b cells twice as long as bar_a's: with its wave speed twice bar_a's, c dt / h is the same.
DefineConstant[ L = 1, Na = 50, Nb = 25, M = 2, W = 0.02 ];
Point(1) = {0, 0, 0}; Point(2) = {L, 0, 0}; Point(3) = {L, W, 0}; Point(4) = {0, W, 0};
Point(5) = {0, 2 * W, 0}; Point(6) = {L, 2 * W, 0}; Point(7) = {L, 3 * W, 0}; Point(8) = {0, 3 * W, 0};
Line(1) = {1, 2}; Line(2) = {2, 3}; Line(3) = {3, 4}; Line(4) = {4, 1};
Line(5) = {5, 6}; Line(6) = {6, 7}; Line(7) = {7, 8}; Line(8) = {8, 5};
Curve Loop(1) = {1, 2, 3, 4};
Curve Loop(2) = {5, 6, 7, 8};
Plane Surface(1) = {1};
Plane Surface(2) = {2};
Transfinite Curve{1, 3} = Na + 1;
Transfinite Curve{5, 7} = Nb + 1;
Transfinite Curve{2, 4, 6, 8} = M + 1;
Transfinite Surface{1} = {1, 2, 3, 4} Alternate;
Transfinite Surface{2} = {5, 6, 7, 8} Alternate;
Physical Surface("bar_a") = {1};
Physical Surface("bar_b") = {2};
Physical Curve("left") = {4, 8};         // x = 0, both bars
Physical Curve("right") = {2, 6};        // x = L, both bars
Physical Curve("sides") = {1, 3, 5, 7};
Mesh.MshFileVersion = 4.1;
