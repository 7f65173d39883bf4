// A spur gear: a disc and a hub joined with 24 teeth, then bored, keyed and
// lightened. A union inside a difference, with many small subtrahends.
teeth = 24;
difference() {
    union() {
        color("Goldenrod") cylinder(r = 26, h = 8, $fn = 96);
        color("Goldenrod") cylinder(r = 10, h = 14, $fn = 48);
        for (i = [0 : teeth - 1])
            rotate(360 * i / teeth) translate([27, 0, 4])
                color("DarkGoldenrod") cube([6, 3.5, 8], center = true);
    }
    translate([0, 0, -1]) cylinder(r = 5, h = 16, $fn = 48);      // bore
    translate([5, 0, 7]) cube([4, 3, 16], center = true);          // keyway
    for (i = [0 : 4])                                              // lightening holes
        rotate(72 * i + 36) translate([17.5, 0, -1]) cylinder(r = 5.5, h = 10, $fn = 48);
    // a chamfer ring on the rim's top edge: a cone subtracted from above
    difference() {
        translate([0, 0, 6]) cylinder(r = 40, h = 3, $fn = 96);
        translate([0, 0, 5.99]) cylinder(r1 = 30, r2 = 27, h = 3.02, $fn = 96);
    }
}
