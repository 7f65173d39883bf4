hull() { linear_extrude(height = 3, twist = 30) square(4, center = true); translate([8, 0, 0]) rotate_extrude($fn = 16) translate([2, 0]) circle(1, $fn = 8); }
