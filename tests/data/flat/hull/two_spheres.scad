hull() { sphere(5); translate([12, 3, 4]) sphere(3, $fn = 20); }
