translate([3, 0, 1]) resize([0, 0, 12], auto = [true, false, false]) rotate([0, 0, 20]) cylinder(h = 4, r1 = 3, r2 = 1);
