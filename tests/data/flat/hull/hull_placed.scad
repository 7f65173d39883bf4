// A hull under transforms, its parts under transforms of their own.
translate([3, 4, 5]) rotate([30, 0, 15]) scale([2, 1, 1])
    hull() {
        translate([4, 0, 0]) rotate([0, 45, 0]) cube(2, center = true);
        sphere(1, $fn = 10);
    }
