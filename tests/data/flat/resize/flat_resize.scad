linear_extrude(height = 2) resize([20, 0], auto = true) union() { circle(3); translate([4, 0]) square(3); }
