linear_extrude(height = 3, twist = 30, slices = 3) offset(r = 0.75, $fn = 20) difference() { square([8, 5]); translate([4, 2.5]) circle(1.5); }
