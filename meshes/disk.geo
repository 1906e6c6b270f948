// Elastic disk of radius R centred at (0, R + G) above the plane y = 0 (showcase D1).
// Physical names: body (surface), contact (lower half circle), upper (upper half circle).
// Parameters: R radius, G initial gap, H mesh size.
DefineConstant[ R = 1, G = 0.01, H = 0.1 ];
cy = R + G;
Point(1) = {0, cy, 0, H};
Point(2) = {R, cy, 0, H}; Point(3) = {0, cy + R, 0, H};
Point(4) = {-R, cy, 0, H}; Point(5) = {0, cy - R, 0, H};
Circle(1) = {2, 1, 3}; Circle(2) = {3, 1, 4}; Circle(3) = {4, 1, 5}; Circle(4) = {5, 1, 2};
Curve Loop(1) = {1, 2, 3, 4};
Plane Surface(1) = {1};
Physical Surface("body") = {1};
Physical Curve("contact") = {3, 4};
Physical Curve("upper") = {1, 2};
Mesh.MshFileVersion = 4.1;
