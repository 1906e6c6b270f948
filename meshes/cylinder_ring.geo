// A cylinder inside a ring, 3D (case cylinder_ring, issue 51: large sliding on a concave curved master;
// after Kratos' cylinder-in-ring contact test). The ring, axis z, inner radius RI, outer RO, length L, is
// held by its outer surface; the cylinder of radius RC and the same length, centred at (XC, YC), is
// thrown inside it. Cells of size H.
// Physical names: ring, cylinder (volumes); ring_inner (the master), ring_outer (held), cyl_side (the
// slave), and the end faces ring_ends, cyl_ends.
// Parameters (gmsh -setnumber): RI, RO, RC, L, XC, YC, H.
DefineConstant[ RI = 0.8, RO = 1.0, RC = 0.3, L = 0.2, XC = 0.3, YC = -0.1, H = 0.08 ];
SetFactory("OpenCASCADE");
eps = 1e-6;
Cylinder(1) = {0, 0, 0, 0, 0, L, RO};
Cylinder(2) = {0, 0, 0, 0, 0, L, RI};
ring() = BooleanDifference{ Volume{1}; Delete; }{ Volume{2}; Delete; };
ring_all[] = Abs(Boundary{ Volume{ring()}; });
ring_inner[] = Surface In BoundingBox{-RI - eps, -RI - eps, -eps, RI + eps, RI + eps, L + eps};
ring_ends[] = Surface In BoundingBox{-RO - eps, -RO - eps, -eps, RO + eps, RO + eps, eps};
ring_ends[] += Surface In BoundingBox{-RO - eps, -RO - eps, L - eps, RO + eps, RO + eps, L + eps};
ring_outer[] = ring_all[];
ring_outer[] -= ring_inner[];
ring_outer[] -= ring_ends[];
cyl = newv;
Cylinder(cyl) = {XC, YC, 0, 0, 0, L, RC};
cyl_all[] = Abs(Boundary{ Volume{cyl}; });
cyl_ends[] = Surface In BoundingBox{XC - RC - eps, YC - RC - eps, -eps, XC + RC + eps, YC + RC + eps, eps};
cyl_ends[] += Surface In BoundingBox{XC - RC - eps, YC - RC - eps, L - eps, XC + RC + eps, YC + RC + eps, L + eps};
cyl_side[] = cyl_all[];
cyl_side[] -= cyl_ends[];
Mesh.CharacteristicLengthMin = H;
Mesh.CharacteristicLengthMax = H;
Physical Volume("ring") = {ring()};
Physical Volume("cylinder") = {cyl};
Physical Surface("ring_inner") = {ring_inner[]};
Physical Surface("ring_outer") = {ring_outer[]};
Physical Surface("ring_ends") = {ring_ends[]};
Physical Surface("cyl_side") = {cyl_side[]};
Physical Surface("cyl_ends") = {cyl_ends[]};
Mesh.MshFileVersion = 4.1;
