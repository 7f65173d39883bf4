minkowski() { cube([10, 6, 4], center = true); sphere(1.5, $fn = 16); }
