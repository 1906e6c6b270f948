// An elastic cube of side a dropped into a 90-degree V-groove, 3D (case cube_groove). The groove is
// two rigid planes through the x axis, z = -y (normal (0, 1, 1)/sqrt2) and z = y (normal
// (0, -1, 1)/sqrt2); they are obstacle options (options/cube_groove.opts), not part of the mesh.
// The cube, x in [-a/2, a/2], is turned by 45 degrees about the x axis: its lower edge lies along
// x, parallel to the groove's bottom line (the x axis) at the height G above it, and its two lower
// faces are parallel to the walls, each at the distance G/sqrt2 from its wall. In the (y, z) plane
// its section is the square of corners (0, G), (a/sqrt2, G + a/sqrt2), (0, G + a sqrt2),
// (-a/sqrt2, G + a/sqrt2).
// Physical names: cube (volume); contact (the two lower faces, those facing the walls); top (the
// other four: the two upper faces and the ends x = -a/2, x = a/2).
// Parameters (gmsh -setnumber): a side, G height of the lower edge above the groove line, H mesh
// size.
SetFactory("OpenCASCADE");
DefineConstant[ a = 0.5, G = 0.01, H = 0.1 ];
s = a / Sqrt(2);
eps = 1e-6;
Box(1) = {-a/2, -a/2, -a/2, a, a, a};
Rotate{ {1, 0, 0}, {0, 0, 0}, Pi/4 } { Volume{1}; }
Translate{ 0, 0, G + s } { Volume{1}; }
// the lower faces lie in G <= z <= G + s; the upper faces and the ends reach above
contact[] = Surface In BoundingBox{-a/2 - eps, -s - eps, G - eps, a/2 + eps, s + eps, G + s + eps};
top[] = Abs(Boundary{ Volume{1}; });
top[] -= contact[];
Physical Volume("cube") = {1};
Physical Surface("contact") = contact[];
Physical Surface("top") = top[];
MeshSize{ PointsOf{ Volume{1}; } } = H;
Mesh.MeshSizeMax = H;
Mesh.MshFileVersion = 4.1;
