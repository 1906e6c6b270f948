// Elastic ball of radius R centred at (0, 0, R + G), its whole sphere a contact boundary (case
// ball_bowl: the ball rolls inside a spherical bowl whose lowest point is at z = 0; the bowl is an
// obstacle option, not part of the mesh). Rolling brings every point of the sphere to the bowl.
// Physical names: body (volume), contact (the whole sphere).
// Parameters: R radius, G initial gap above z = 0, H mesh size.
SetFactory("OpenCASCADE");
DefineConstant[ R = 1, G = 0.01, H = 0.25 ];
Sphere(1) = {0, 0, R + G, R};
Physical Volume("body") = {1};
Physical Surface("contact") = Surface{:};
MeshSize{ PointsOf{ Volume{:}; } } = H;
Mesh.MeshSizeMax = H;
Mesh.MshFileVersion = 4.1;
