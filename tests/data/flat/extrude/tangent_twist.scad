linear_extrude(height = 10, twist = 360, $fn = 24) translate([2, 0]) circle(2);
