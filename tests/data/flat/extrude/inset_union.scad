linear_extrude(height = 2) offset(delta = -0.5) union() { square(3); translate([2, 2]) square(3); }
