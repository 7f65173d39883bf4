// A tree ten levels deep: each level wraps the one before in another operation
// (difference, union, intersection, in turn). Starts from a rounded cube, the
// intersection of a cube and a sphere.
module tier(n) {
    if (n == 0) {
        intersection() {
            color("Tomato") cube(20, center = true);
            color("Orange") sphere(r = 13.5, $fn = 48);
        }
    } else if (n % 3 == 1) {
        difference() {
            tier(n - 1);
            rotate([90, 0, 40 * n]) cylinder(r = 4.5 - 0.3 * n, h = 40, center = true, $fn = 32);
        }
    } else if (n % 3 == 2) {
        union() {
            tier(n - 1);
            rotate([0, 0, 40 * n]) translate([12, 0, 6 - n])
                color("MediumSeaGreen") sphere(r = 3.5, $fn = 24);
        }
    } else {
        intersection() {
            tier(n - 1);
            rotate([0, 0, 15 * n]) cube([31 - n, 31 - n, 21], center = true);
        }
    }
}
tier(10);
