// Elastic disk of radius R centred at (0, R + G), its whole circle a contact boundary (case
// disk_rail: the disk rolls inside a circular rail whose lowest point is at y = 0; the rail is an
// obstacle option, not part of the mesh). Rolling brings every point of the circle to the rail.
// Physical names: body (surface), contact (the whole circle).
// Parameters: R radius, G initial gap above y = 0, H mesh size.
DefineConstant[ R = 1, G = 0.01, H = 0.1 ];
cy = R + G;
Point(1) = {0, cy, 0, H};
Point(2) = {R, cy, 0, H}; Point(3) = {0, cy + R, 0, H};
Point(4) = {-R, cy, 0, H}; Point(5) = {0, cy - R, 0, H};
Circle(1) = {2, 1, 3}; Circle(2) = {3, 1, 4}; Circle(3) = {4, 1, 5}; Circle(4) = {5, 1, 2};
Curve Loop(1) = {1, 2, 3, 4};
Plane Surface(1) = {1};
Physical Surface("body") = {1};
Physical Curve("contact") = {1, 2, 3, 4};
Mesh.MshFileVersion = 4.1;
