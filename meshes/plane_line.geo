// A rigid line y = 0 (2D) as a mesh of segments, for -obstacle_NAME_type mesh: from x = 3 to x = -3,
// so that its normal (the right of its direction) points up, to the body. tests/test_meshed_obstacles.py
// checks that it gives the plane's run.
// Parameters: H mesh size.
DefineConstant[ H = 0.5 ];
Point(1) = {3, 0, 0, H}; Point(2) = {-3, 0, 0, H};
Line(1) = {1, 2};
Mesh.MshFileVersion = 4.1;
