// Cantilever [0,L] x [0,H] clamped at x = 0, its tip half's underside the contact face (issue 38:
// stiffness damping of the massless contact dofs). Plane strain, structured triangles.
// Physical names: body (surface), clamp (x = 0), contact (y = 0, x >= L/2), free (the rest).
// Parameters: L, H, NX x NY cells (NX even).
DefineConstant[ L = 1, H = 0.1, NX = 20, NY = 2 ];
Point(1) = {0, 0, 0}; Point(2) = {L / 2, 0, 0}; Point(3) = {L, 0, 0}; Point(4) = {L, H, 0}; Point(5) = {0, H, 0};
Line(1) = {1, 2}; Line(2) = {2, 3}; Line(3) = {3, 4}; Line(4) = {4, 5}; Line(5) = {5, 1};
Curve Loop(1) = {1, 2, 3, 4, 5};
Plane Surface(1) = {1};
Transfinite Curve{1, 2} = NX / 2 + 1;
Transfinite Curve{4} = NX + 1;
Transfinite Curve{3, 5} = NY + 1;
Transfinite Surface{1} = {1, 3, 4, 5};
Physical Surface("body") = {1};
Physical Curve("clamp") = {5};
Physical Curve("contact") = {2};
Physical Curve("free") = {1, 3, 4};
Mesh.MshFileVersion = 4.1;
