// An elastic ball dropped on an elastic block, 3D (case ball_block, issue 20: two-body contact).
// The block is [-W, W] x [-W, W] x [-D, 0]; the ball, of radius R, is centred at (0, 0, R + G):
// a gap G between its lowest point and the block's top, on the z axis.
// The ball is built as meshes/ball.geo builds its ball (lower and upper hemispheres joined by
// BooleanFragments, mesh size H on their points); the block has the mesh size HB.
// Physical names: ball, block (volumes); ball_contact (the ball's lower hemisphere), ball_upper,
// block_top (z = 0), block_bottom (z = -D), block_sides (the four vertical faces).
// Parameters (gmsh -setnumber): R, G, H (ball), W half-width, D depth, HB (block).
SetFactory("OpenCASCADE");
DefineConstant[ R = 0.5, G = 0.01, H = 0.15, W = 1, D = 0.5 ];
DefineConstant[ HB = H ];
cz = R + G;
eps = 1e-6;
// the ball, as in ball.geo
Sphere(1) = {0, 0, cz, R, -Pi/2, 0, 2*Pi};
Sphere(2) = {0, 0, cz, R, 0, Pi/2, 2*Pi};
BooleanFragments{ Volume{1}; Delete; }{ Volume{2}; Delete; }
ball[] = Volume{:};
below[] = Surface In BoundingBox{-2*R, -2*R, cz - 2*R, 2*R, 2*R, cz + eps};
above[] = Surface In BoundingBox{-2*R, -2*R, cz - eps, 2*R, 2*R, cz + 2*R};
equator[] = Surface In BoundingBox{-2*R, -2*R, cz - eps, 2*R, 2*R, cz + eps};
below[] -= equator[];
above[] -= equator[];
MeshSize{ PointsOf{ Volume{ball[]}; } } = H;
// the block, a separate volume (not fragmented with the ball: they do not touch)
block = newv;
Box(block) = {-W, -W, -D, 2*W, 2*W, D};
top[] = Surface In BoundingBox{-W - eps, -W - eps, -eps, W + eps, W + eps, eps};
bottom[] = Surface In BoundingBox{-W - eps, -W - eps, -D - eps, W + eps, W + eps, -D + eps};
sides[] = Abs(Boundary{ Volume{block}; });
sides[] -= top[];
sides[] -= bottom[];
MeshSize{ PointsOf{ Volume{block}; } } = HB;
Physical Volume("ball") = ball[];
Physical Volume("block") = {block};
Physical Surface("ball_contact") = below[];
Physical Surface("ball_upper") = above[];
Physical Surface("block_top") = top[];
Physical Surface("block_bottom") = bottom[];
Physical Surface("block_sides") = sides[];
Mesh.MeshSizeMax = Max(H, HB);
Mesh.MshFileVersion = 4.1;
