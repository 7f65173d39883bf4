// Rotation, translation and scale outside the sum and inside each operand.
translate([5, -3, 2]) rotate([20, 35, 10]) scale([1.5, 1, 0.5])
    minkowski() {
        translate([1, 2, 3]) rotate([0, 0, 30]) cube([4, 3, 2]);
        translate([0, 0, -1]) scale([1, 2, 1]) sphere(1, $fn = 8);
    }
