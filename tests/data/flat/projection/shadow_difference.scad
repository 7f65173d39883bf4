linear_extrude(height = 1) projection() difference() { rotate([30, 0, 0]) cube(6, center = true); rotate([30, 0, 0]) cylinder(h = 10, r = 1.5, center = true); }
