rotate_extrude(angle = 120) translate([5, 0]) square([2, 4]);
