// A rigid box with rounded edges and corners (3D) for -obstacle_NAME_type mesh: the surface of the
// box of the type box obstacle of options/ball_box.opts (corner at (-1.6, -1.6, -2), sides 2, every
// edge rounded with radius 0.5), meshed with triangles of size H. OpenCASCADE orients a solid's
// faces outward, to the body. tests/test_meshed_obstacles.py compares the two.
// Parameters: H mesh size.
SetFactory("OpenCASCADE");
DefineConstant[ H = 0.1 ];
Box(1) = {-1.6, -1.6, -2, 2, 2, 2};
f() = Fillet{1}{Curve{:}}{0.5};
Physical Surface("surface") = Surface{:};
Mesh.MeshSizeMax = H;
Mesh.MshFileVersion = 4.1;
