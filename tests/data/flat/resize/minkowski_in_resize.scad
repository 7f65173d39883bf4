// A placed minkowski sum inside a placed resize.
translate([2, 2, 0]) resize([10, 8, 6]) translate([7, 0, 0]) minkowski() { cube([4, 2, 2]); cylinder(r = 1, h = 1, $fn = 6); }
