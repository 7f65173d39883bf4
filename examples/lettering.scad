// A name plate: a rounded plate (an offset square) with raised text and a
// countersunk hole, and a star-shaped hole cut with a twist. Shows
// linear_extrude, text, offset and 2D booleans inside the CSG.
$fn = 48;
difference() {
    union() {
        color([0.35, 0.55, 0.8]) linear_extrude(height = 3) offset(r = 3) square([64, 22], center = true);
        color([0.95, 0.8, 0.3]) translate([3, 0, 3])
            linear_extrude(height = 2) text("strata", size = 12, halign = "center", valign = "center");
    }
    translate([-27, 0, -1]) cylinder(h = 5, r = 2.2);
    translate([-27, 0, 2]) cylinder(h = 1.01, r1 = 2.2, r2 = 3.2);
    translate([29, 0, -1]) linear_extrude(height = 5, twist = 60, slices = 6)
        polygon([for (i = [0 : 9]) (i % 2 == 0 ? 4 : 2) * [cos(36 * i), sin(36 * i)]]);
}
