// Square plate [0,L] x [0,L] for the loads of README "Loads in time" (plane strain): pressures on
// its sides and concentrated forces on its corners (issue 38, items 12 and 13).
// Physical names: body (surface); left, right, bottom, top (its sides); rim (all four: a
// closed curve); tip (the corner (L, L)), ends (the corners (L, 0) and (L, L)): Physical Points.
// Parameters: L, N x N cells (structured triangles).
DefineConstant[ L = 1, N = 8 ];
Point(1) = {0, 0, 0}; Point(2) = {L, 0, 0}; Point(3) = {L, L, 0}; Point(4) = {0, L, 0};
Line(1) = {1, 2}; Line(2) = {2, 3}; Line(3) = {3, 4}; Line(4) = {4, 1};
Curve Loop(1) = {1, 2, 3, 4};
Plane Surface(1) = {1};
Transfinite Curve{1, 2, 3, 4} = N + 1;
Transfinite Surface{1} = {1, 2, 3, 4};
Physical Surface("body") = {1};
Physical Curve("bottom") = {1};
Physical Curve("right") = {2};
Physical Curve("top") = {3};
Physical Curve("left") = {4};
Physical Curve("rim") = {1, 2, 3, 4};
Physical Point("tip") = {3};
Physical Point("ends") = {2, 3};
Mesh.MshFileVersion = 4.1;
