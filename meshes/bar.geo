// Strip [0,L] x [0,W] of triangles for the 1D bar benchmarks B1 and B2 (plane strain, nu = 0).
// Parameters (override with gmsh -setnumber): N cells along x, M cells across, width W.
// The default W = L/N with M = 2 makes cells h x h/2. A triangulated strip is not exactly 1D: its
// transverse modes couple to the axial wave. With cells h x h/2 they sit far above the axial band,
// and the B1 contact plateau is flat to 0.13%; with h x h cells it wobbles by 1.4%.
DefineConstant[ L = 1, N = 80, M = 2 ];
DefineConstant[ W = L / N ];
Point(1) = {0, 0, 0}; Point(2) = {L, 0, 0}; Point(3) = {L, W, 0}; Point(4) = {0, W, 0};
Line(1) = {1, 2}; Line(2) = {2, 3}; Line(3) = {3, 4}; Line(4) = {4, 1};
Curve Loop(1) = {1, 2, 3, 4};
Plane Surface(1) = {1};
Transfinite Curve{1, 3} = N + 1;
Transfinite Curve{2, 4} = M + 1;
Transfinite Surface{1} = {1, 2, 3, 4} Alternate;
Physical Surface("body") = {1};
Physical Curve("left") = {4};    // x = 0: the contact end
Physical Curve("right") = {2};   // x = L
Physical Curve("sides") = {1, 3};
Mesh.MshFileVersion = 4.1;
