linear_extrude(height = 1) projection() { rotate([30, 20, 0]) cube(6, center = true); translate([5, 0, 0]) rotate([0, 40, 0]) cylinder(h = 10, r = 2, center = true); }
