// A rigid funnel (3D) for -obstacle_NAME_type mesh (options/ball_funnel.opts): the cone of half-angle
// 45 degrees about the z axis from radius R0 at z = Z0 to radius R0 + L at z = Z0 + L, a surface of
// revolution of triangles whose normals point in, to the axis and up, where the body is.
// Parameters: R0 the hole's radius, Z0 its height, L the cone's height, H mesh size.
DefineConstant[ R0 = 0.3, Z0 = -0.2, L = 2, H = 0.15 ];
Point(1) = {R0, 0, Z0, H}; Point(2) = {R0 + L, 0, Z0 + L, H};
Line(1) = {1, 2};
s[] = Extrude {{0, 0, 1}, {0, 0, 0}, Pi / 2} { Line{1}; };
For k In {1 : 3}
  s[] = Extrude {{0, 0, 1}, {0, 0, 0}, Pi / 2} { Line{s[0]}; };
EndFor
Mesh.MshFileVersion = 4.1;
