// A minkowski sum under a translation: the translation moves the sum once.
translate([25, 25, 0]) minkowski() { cube(10); cylinder(r = 2, h = 1); }
