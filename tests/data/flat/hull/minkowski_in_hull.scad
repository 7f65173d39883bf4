// A placed minkowski sum as one part of a placed hull.
translate([0, 0, 4]) rotate([10, 0, 0])
    hull() {
        translate([6, 0, 0]) minkowski() { cube(2); sphere(1, $fn = 8); }
        cube(1);
    }
