resize([15, 5, 5]) hull() { sphere(2); translate([5, 0, 0]) cube(2, center = true); }
