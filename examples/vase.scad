// A turned vase and its saucer: rotate_extrude of a profile polygon (a full
// turn, and a partial one cut open to show the wall), a twisted, tapering
// linear_extrude of a rounded star standing in it.
$fn = 64;
color([0.8, 0.45, 0.35]) difference() {
    rotate_extrude() polygon([[0, 0], [9, 0], [11, 4], [7, 16], [9, 24], [8, 24], [6, 16], [10, 4], [8, 1.2], [0, 1.2]]);
    translate([0, -30, 10]) cube([30, 30, 30]);
}
color([0.5, 0.7, 0.45]) rotate_extrude(angle = 270) translate([13, 0]) square([6, 1]);
color([0.45, 0.6, 0.85]) translate([0, 0, 1.2])
    linear_extrude(height = 30, twist = -120, scale = 0.4, slices = 24)
        offset(r = 0.6) polygon([for (i = [0 : 11]) (i % 2 == 0 ? 4 : 2.2) * [cos(30 * i), sin(30 * i)]]);
