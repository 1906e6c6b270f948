// A rigid step (2D) for -obstacle_NAME_type mesh (options/disk_step.opts): the top y = 0 for x < X,
// its edge rounded with radius R, the wall x = X down to the floor y = -D. The lines run right to
// left, so that their normals (the right of each line's direction) point up and out of the step,
// to the body. A sharp edge would poke between the body's contact nodes: round it over a few h_c'.
// Parameters: X the wall's position, D its height, R the edge's radius, H mesh size (R/8 on the edge).
DefineConstant[ X = 0.3, D = 0.4, R = 0.2, H = 0.05 ];
Point(1) = {3, -D, 0, H}; Point(2) = {X, -D, 0, H}; Point(3) = {X, -R, 0, R / 8};
Point(4) = {X - R, -R, 0, R / 8}; Point(5) = {X - R, 0, 0, R / 8}; Point(6) = {-3, 0, 0, H};
Line(1) = {1, 2}; Line(2) = {2, 3}; Circle(3) = {3, 4, 5}; Line(4) = {5, 6};
Mesh.MshFileVersion = 4.1;
