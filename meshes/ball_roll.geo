// Elastic ball of radius R resting on the plane z = 0 (centre (0, 0, R + G)), its whole sphere a
// contact boundary (case ball_roll: a ball that rolls brings every point of its sphere to the plane).
// Physical names: body (volume), surface (the whole sphere).
// Parameters: R radius, G initial gap above z = 0, H mesh size.
SetFactory("OpenCASCADE");
DefineConstant[ R = 1, G = 0, H = 0.25 ];
Sphere(1) = {0, 0, R + G, R};
Physical Volume("body") = {1};
Physical Surface("surface") = Surface{:};
MeshSize{ PointsOf{ Volume{:}; } } = H;
Mesh.MeshSizeMax = H;
Mesh.MshFileVersion = 4.1;
