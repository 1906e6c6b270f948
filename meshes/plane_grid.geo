// A rigid plane z = 0 (3D) as a mesh of triangles, for -obstacle_NAME_type mesh: the square
// [-3, 3]^2 meshed with triangles of size H, whose normals point up (+z), to the body.
// tests/test_meshed_obstacles.py checks that it gives the plane's run. In 2D the line y = 0, from
// x = 3 to x = -3 (its normal, the right of its direction, points up): plane_line.msh.
// Parameters: H mesh size.
DefineConstant[ H = 0.5 ];
Point(1) = {-3, -3, 0, H}; Point(2) = {3, -3, 0, H}; Point(3) = {3, 3, 0, H}; Point(4) = {-3, 3, 0, H};
Line(1) = {1, 2}; Line(2) = {2, 3}; Line(3) = {3, 4}; Line(4) = {4, 1};
Curve Loop(1) = {1, 2, 3, 4};
Plane Surface(1) = {1};
Mesh.MshFileVersion = 4.1;
