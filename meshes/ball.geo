// Elastic ball of radius R centred at (0, 0, R + G) above the plane z = 0 (showcase D2; with
// G = 0.45, the V-groove case ball_vgroove).
// Physical names: body (volume), contact (lower hemisphere), upper (upper hemisphere).
// Parameters: R radius, G initial gap, H mesh size.
SetFactory("OpenCASCADE");
DefineConstant[ R = 1, G = 0.01, H = 0.25 ];
cz = R + G;
Sphere(1) = {0, 0, cz, R, -Pi/2, 0, 2*Pi};
Sphere(2) = {0, 0, cz, R, 0, Pi/2, 2*Pi};
BooleanFragments{ Volume{1}; Delete; }{ Volume{2}; Delete; }
eps = 1e-6;
below[] = Surface In BoundingBox{-2*R, -2*R, cz - 2*R, 2*R, 2*R, cz + eps};
above[] = Surface In BoundingBox{-2*R, -2*R, cz - eps, 2*R, 2*R, cz + 2*R};
equator[] = Surface In BoundingBox{-2*R, -2*R, cz - eps, 2*R, 2*R, cz + eps};
below[] -= equator[];
above[] -= equator[];
Physical Volume("body") = Volume{:};
Physical Surface("contact") = below[];
Physical Surface("upper") = above[];
MeshSize{ PointsOf{ Volume{:}; } } = H;
Mesh.MeshSizeMax = H;
Mesh.MshFileVersion = 4.1;
