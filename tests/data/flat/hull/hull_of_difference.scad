hull() { difference() { sphere(5); translate([0, 0, 3]) cube(10, center = true); } translate([8, 0, 0]) cube(2, center = true); }
