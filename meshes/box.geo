// Box W x W x H on the plane z = 0 for the 3D friction benchmark F1 (tetrahedra).
// Physical names: body (volume), base (z = 0: the contact face), top, sides.
SetFactory("OpenCASCADE");
DefineConstant[ W = 1, H = 0.5, M = 0.125 ];
Box(1) = {0, 0, 0, W, W, H};
eps = 1e-6;
base[] = Surface In BoundingBox{-eps, -eps, -eps, W + eps, W + eps, eps};
top[] = Surface In BoundingBox{-eps, -eps, H - eps, W + eps, W + eps, H + eps};
all[] = Surface{:};
sides[] = all[];
sides[] -= base[];
sides[] -= top[];
Physical Volume("body") = {1};
Physical Surface("base") = base[];
Physical Surface("top") = top[];
Physical Surface("sides") = sides[];
MeshSize{ PointsOf{ Volume{:}; } } = M;
Mesh.MeshSizeMax = M;
Mesh.MshFileVersion = 4.1;
