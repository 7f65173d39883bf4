hull() { rotate([10, 20, 30]) cube(6, center = true); translate([0, 0, 10]) cylinder(h = 4, r1 = 3, r2 = 0); }
