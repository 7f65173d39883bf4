rotate_extrude($fn = 40) translate([5, 0]) circle(2);
