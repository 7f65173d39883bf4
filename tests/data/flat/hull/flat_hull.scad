linear_extrude(height = 2) hull() { circle(3); translate([10, 0]) square(2); translate([4, 6]) circle(1, $fn = 6); }
