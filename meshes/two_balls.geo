// Two elastic balls of radius R thrown at each other along x, 3D (case two_balls, issue 20:
// two-body contact). Ball A is centred at (-(R + G/2), 0, 0), ball B at (R + G/2, 0, 0): a gap G
// between them on the x axis, the plane x = 0 halfway.
// Each ball is built as meshes/ball.geo builds its ball (two hemispheres joined by
// BooleanFragments, mesh size H on their points, the same family as meshes/ball.msh), then turned
// about the y axis so that the split is across x: ball.geo's lower (contact) hemisphere becomes A's
// hemisphere facing +x (turned by -90 degrees) and B's facing -x (turned by +90 degrees; B is A
// turned by 180 degrees about the y axis). Ball A is built first, with the same entity tags as
// alone, so that ONLY_A = 1 (ball A alone: the reference run of one ball against the rigid plane
// x = 0, options/ball_plane_x.opts) meshes it exactly as here: the same nodes and cells.
// Physical names: ball_a, ball_b (volumes); a_near (A's hemisphere facing B, x > -(R + G/2)),
// a_far (its other hemisphere), b_near (B's hemisphere facing A, x < R + G/2), b_far. With
// ONLY_A = 1: ball_a, a_near, a_far.
// Parameters (gmsh -setnumber): R radius, G gap, H mesh size, ONLY_A.
SetFactory("OpenCASCADE");
DefineConstant[ R = 1, G = 0.01, H = 0.25, ONLY_A = 0 ];
cx = R + G/2;
eps = 1e-6;

// ball A: ball.geo's hemispheres at the origin, the lower one turned to +x, then moved to -cx
Sphere(1) = {0, 0, 0, R, -Pi/2, 0, 2*Pi};
Sphere(2) = {0, 0, 0, R, 0, Pi/2, 2*Pi};
BooleanFragments{ Volume{1}; Delete; }{ Volume{2}; Delete; }
ballA[] = Volume{:};
Rotate{ {0, 1, 0}, {0, 0, 0}, -Pi/2 } { Volume{ballA[]}; }
Translate{ -cx, 0, 0 } { Volume{ballA[]}; }
a_near[] = Surface In BoundingBox{-cx - eps, -2*R, -2*R, -cx + 2*R, 2*R, 2*R};
a_far[] = Surface In BoundingBox{-cx - 2*R, -2*R, -2*R, -cx + eps, 2*R, 2*R};
a_eq[] = Surface In BoundingBox{-cx - eps, -2*R, -2*R, -cx + eps, 2*R, 2*R};
a_near[] -= a_eq[];
a_far[] -= a_eq[];
Physical Volume("ball_a") = ballA[];
Physical Surface("a_near") = a_near[];
Physical Surface("a_far") = a_far[];
MeshSize{ PointsOf{ Volume{ballA[]}; } } = H;

If (!ONLY_A)
  // ball B: the same, its lower hemisphere turned to -x, then moved to +cx
  Sphere(3) = {0, 0, 0, R, -Pi/2, 0, 2*Pi};
  Sphere(4) = {0, 0, 0, R, 0, Pi/2, 2*Pi};
  BooleanFragments{ Volume{3}; Delete; }{ Volume{4}; Delete; }
  ballB[] = Volume{:};
  ballB[] -= ballA[];
  Rotate{ {0, 1, 0}, {0, 0, 0}, Pi/2 } { Volume{ballB[]}; }
  Translate{ cx, 0, 0 } { Volume{ballB[]}; }
  b_near[] = Surface In BoundingBox{cx - 2*R, -2*R, -2*R, cx + eps, 2*R, 2*R};
  b_far[] = Surface In BoundingBox{cx - eps, -2*R, -2*R, cx + 2*R, 2*R, 2*R};
  b_eq[] = Surface In BoundingBox{cx - eps, -2*R, -2*R, cx + eps, 2*R, 2*R};
  b_near[] -= b_eq[];
  b_far[] -= b_eq[];
  Physical Volume("ball_b") = ballB[];
  Physical Surface("b_near") = b_near[];
  Physical Surface("b_far") = b_far[];
  MeshSize{ PointsOf{ Volume{ballB[]}; } } = H;
EndIf
Mesh.MeshSizeMax = H;
// No random perturbation in the 3D Delaunay: with gmsh's default (1e-12) ball A's interior was
// meshed differently with ball B present (74 of its 444 nodes off by up to 7e-16, other cells);
// without it ball A is the same, node for node and cell for cell, with ONLY_A = 1 (checked for
// H = 0.25, 0.2, 0.15, 0.1 with gmsh 4.8.4).
Mesh.RandomFactor3D = 0;
Mesh.MshFileVersion = 4.1;
