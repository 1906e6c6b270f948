// Strip of two glued halves for the bodies tests (tests/test_bodies.py): [0, L1] x [0, W] is the
// physical group "left_half", [L1, L1 + L2] x [0, W] "right_half", one connected mesh (the line
// x = L1 is shared), plane strain. N1 and N2 cells along x, M across, cells as in meshes/bar.geo.
// The defaults give the right half cells twice as long as the left's: with its wave speed twice
// the left's (tests/test_bodies.py), c dt / h is the same in both halves.
DefineConstant[ L1 = 0.5, L2 = 1.0, N1 = 40, N2 = 40, M = 2 ];
DefineConstant[ W = L1 / N1 ];
Point(1) = {0, 0, 0}; Point(2) = {L1, 0, 0}; Point(3) = {L1, W, 0}; Point(4) = {0, W, 0};
Point(5) = {L1 + L2, 0, 0}; Point(6) = {L1 + L2, W, 0};
Line(1) = {1, 2}; Line(2) = {2, 3}; Line(3) = {3, 4}; Line(4) = {4, 1};
Line(5) = {2, 5}; Line(6) = {5, 6}; Line(7) = {6, 3};
Curve Loop(1) = {1, 2, 3, 4};
Curve Loop(2) = {5, 6, 7, -2};
Plane Surface(1) = {1};
Plane Surface(2) = {2};
Transfinite Curve{1, 3} = N1 + 1;
Transfinite Curve{5, 7} = N2 + 1;
Transfinite Curve{2, 4, 6} = M + 1;
Transfinite Surface{1} = {1, 2, 3, 4} Alternate;
Transfinite Surface{2} = {2, 5, 6, 3} Alternate;
Physical Surface("left_half") = {1};
Physical Surface("right_half") = {2};
Physical Surface("strip") = {1, 2};     // the whole mesh, for a single body
Physical Curve("left") = {4};            // x = 0
Physical Curve("right") = {6};           // x = L1 + L2
Physical Curve("sides") = {1, 3, 5, 7};
Mesh.MshFileVersion = 4.1;
