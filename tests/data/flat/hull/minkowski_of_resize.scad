// A resized solid as an operand of a placed minkowski sum.
translate([0, 5, 0]) minkowski() { resize([4, 4, 4]) cube(1); cube(1); }
