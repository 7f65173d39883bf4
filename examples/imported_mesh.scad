// An imported mesh (meshes/twisted_star.stl, non-convex) on a base plate,
// bored through its axis and cut by a sphere at the top.
difference() {
    union() {
        translate([0, 0, 4]) color("MediumPurple") import("meshes/twisted_star.stl");
        color("LightGray") translate([0, 0, 2]) cube([36, 36, 4], center = true);
    }
    translate([0, 0, -1]) cylinder(r = 3, h = 50, $fn = 32);
    translate([0, 0, 46]) sphere(r = 10, $fn = 48);
}
