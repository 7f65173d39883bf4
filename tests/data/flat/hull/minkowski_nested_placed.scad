// A placed minkowski sum as an operand of another, both under transforms.
translate([5, 0, -2]) rotate([0, 0, 20])
    minkowski() {
        translate([0, 3, 0]) minkowski() { cube(2); sphere(1, $fn = 6); }
        rotate([0, 0, 45]) cube(1);
    }
