linear_extrude(height = 4) intersection() { circle(5); square(7, center = true); translate([1, 1]) circle(4); }
