resize([12, 0, 0], auto = true) intersection() { sphere(4); translate([2, 0, 0]) cube(6, center = true); }
