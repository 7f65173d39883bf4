hull() { translate([0, 0, -5]) hull() { cube(2); translate([6, 0, 0]) sphere(1); } translate([2, 7, 3]) cylinder(h = 2, r = 2); }
