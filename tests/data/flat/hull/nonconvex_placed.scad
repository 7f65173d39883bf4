// A minkowski sum of a non-convex extrusion (split into convex parts) under
// transforms outside and inside.
translate([3, 4, 5]) rotate([0, 0, 45]) scale([1, 1, 2])
    minkowski() {
        translate([1, 0, 0]) linear_extrude(2) polygon([[0, 0], [4, 0], [4, 1], [1, 1], [1, 4], [0, 4]]);
        rotate([0, 0, 10]) cube(1, center = true);
    }
