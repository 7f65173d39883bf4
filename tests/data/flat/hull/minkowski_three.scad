minkowski() { cube([4, 3, 2]); rotate([0, 0, 30]) cylinder(h = 1, r = 2, $fn = 8); sphere(0.5, $fn = 8); }
