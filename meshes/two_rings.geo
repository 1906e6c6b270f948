// Two elastic rings, plane strain (case two_rings, issue 51: large sliding on curved masters; after
// COMSOL's ring impact model). Ring A, centred at the origin, and ring B, centred at (XB, YB), both of
// outer radius R and inner radius RI; B is offset across the line of A's motion (along +x) so that the
// impact is oblique. Cells of size H (about (R - RI) / H cells through the wall).
// Physical names: ring_a, ring_b (surfaces); a_outer, b_outer, a_inner, b_inner (circles).
// Parameters (gmsh -setnumber): R, RI, XB, YB, H.
DefineConstant[ R = 0.1, RI = 0.08, XB = 0.21, YB = 0.05, H = 0.005 ];
Mesh.CharacteristicLengthMin = H;
Mesh.CharacteristicLengthMax = H;
SetFactory("OpenCASCADE");
Circle(1) = {0, 0, 0, R};
Circle(2) = {0, 0, 0, RI};
Circle(3) = {XB, YB, 0, R};
Circle(4) = {XB, YB, 0, RI};
Curve Loop(1) = {1}; Curve Loop(2) = {2};
Curve Loop(3) = {3}; Curve Loop(4) = {4};
Plane Surface(1) = {1, 2};
Plane Surface(2) = {3, 4};
Physical Surface("ring_a") = {1};
Physical Surface("ring_b") = {2};
Physical Curve("a_outer") = {1};
Physical Curve("a_inner") = {2};
Physical Curve("b_outer") = {3};
Physical Curve("b_inner") = {4};
Mesh.MshFileVersion = 4.1;
