// A resized sphere as one part of a hull.
hull() { translate([2, 0, 0]) resize([4, 2, 2]) sphere(1, $fn = 12); translate([10, 1, 1]) rotate([10, 20, 30]) cube(1); }
