linear_extrude(height = 2) rotate(17) translate([3, 1]) scale([2, 0.5]) rotate(33) square(2, center = true);
