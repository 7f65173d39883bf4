linear_extrude(height = 1) minkowski() { difference() { square(10); translate([3, 3]) square(4); } circle(1, $fn = 12); }
