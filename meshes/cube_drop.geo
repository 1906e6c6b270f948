// A coarse cube of side L whose whole skin is contact boundary, its base at height G above the plane
// z = 0 (issue 38: the redistributed mass on a coarse mesh, tests/test_mass_coarse_mesh.py).
// Physical names: body (volume), skin (all six faces), base (z = G: the face that can touch the plane).
// Parameters: L side, G initial gap, H mesh size (0.2: 240 nodes, 37 of them inside; 0.25: 144 and
// 12; 0.5: 45 and 1).
SetFactory("OpenCASCADE");
DefineConstant[ L = 1, G = 0.05, H = 0.2 ];
Box(1) = {-L/2, -L/2, G, L, L, L};
eps = 1e-6;
base[] = Surface In BoundingBox{-L, -L, G - eps, L, L, G + eps};
Physical Volume("body") = {1};
Physical Surface("skin") = Surface{:};
Physical Surface("base") = base[];
MeshSize{ PointsOf{ Volume{:}; } } = H;
Mesh.MeshSizeMax = H;
Mesh.MshFileVersion = 4.1;
