// A minkowski() of one non-convex child: the child itself, as OpenSCAD returns a lone child untouched.
minkowski() { rotate_extrude(angle = 270, $fn = 8) translate([15, 0]) polygon([[0, 0], [3, 0], [3, 4], [1.5, 1.5], [0, 4]]); }
