linear_extrude(height = 1) projection(cut = true) rotate([90, 0, 0]) rotate_extrude() translate([4, 0]) circle(1.5);
