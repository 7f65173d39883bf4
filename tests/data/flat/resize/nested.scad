resize([8, 8, 8]) translate([2, 0, 0]) resize([3, 1, 0]) cube([1, 2, 3]);
