// Two elastic bars meeting end to end across a small gap, plane strain (case two_bars, issue 20:
// two-body contact). With nu = 0 the motion is 1D: thrown at each other at +-v0 they touch, stay
// in contact 2L/c with the contact stress rho c v0, and leave with their velocities swapped.
// Bar A is [0, L] x [0, W] (N_A cells along x, M_A rows across), bar B is [L + G, 2L + G] x [0, W]
// (N_B cells along x, M_B rows across). Both have the width W = L/N_A and, as meshes/bar.geo, cells
// about h x h/2 (transfinite, alternating diagonals): A h_A x h_A/2 with M_A = 2 rows; B, with
// M_B = 3 rows, h_B x 0.42 h_B. The meshes do NOT match at the interface, along x (h_A = 0.0125
// against h_B = 0.01) nor across it: A's end nodes are at y = 0, W/2, W, B's at y = 0, W/3, 2W/3,
// W. Both bars have the same width so that their impedances rho c W are equal and the 1D solution
// holds (the interface at rest during contact).
// CONF = 1 makes B's mesh A's mesh translated by L + G (N_B = N_A, M_B = M_A): conforming nodes face
// to face across the gap.
// Physical names: bar_a, bar_b (surfaces); a_right (A's end facing B, x = L), b_left (B's end
// facing A, x = L + G), a_left (x = 0), b_right (x = 2L + G), sides (y = 0 and y = W of both bars).
// Parameters (gmsh -setnumber): L, G gap, N_A, N_B, M_A, M_B, W, CONF.
DefineConstant[ L = 1, G = 0.005, N_A = 80, N_B = 100, M_A = 2, M_B = 3, CONF = 0 ];
DefineConstant[ W = L / N_A ];
nb = N_B; mb = M_B;
If (CONF)
  nb = N_A; mb = M_A;
EndIf
x0 = L + G;
// bar A
Point(1) = {0, 0, 0}; Point(2) = {L, 0, 0}; Point(3) = {L, W, 0}; Point(4) = {0, W, 0};
Line(1) = {1, 2}; Line(2) = {2, 3}; Line(3) = {3, 4}; Line(4) = {4, 1};
Curve Loop(1) = {1, 2, 3, 4};
Plane Surface(1) = {1};
Transfinite Curve{1, 3} = N_A + 1;
Transfinite Curve{2, 4} = M_A + 1;
Transfinite Surface{1} = {1, 2, 3, 4} Alternate;
// bar B
Point(5) = {x0, 0, 0}; Point(6) = {x0 + L, 0, 0}; Point(7) = {x0 + L, W, 0}; Point(8) = {x0, W, 0};
Line(5) = {5, 6}; Line(6) = {6, 7}; Line(7) = {7, 8}; Line(8) = {8, 5};
Curve Loop(2) = {5, 6, 7, 8};
Plane Surface(2) = {2};
Transfinite Curve{5, 7} = nb + 1;
Transfinite Curve{6, 8} = mb + 1;
Transfinite Surface{2} = {5, 6, 7, 8} Alternate;
Physical Surface("bar_a") = {1};
Physical Surface("bar_b") = {2};
Physical Curve("a_right") = {2};
Physical Curve("b_left") = {8};
Physical Curve("a_left") = {4};
Physical Curve("b_right") = {6};
Physical Curve("sides") = {1, 3, 5, 7};
Mesh.MshFileVersion = 4.1;
