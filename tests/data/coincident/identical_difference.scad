// A - A: every face of the subtrahend coincides with the minuend's; the result is empty.
difference() {
    rotate([23, 37, 11]) cylinder(r = 5, h = 10, $fn = 12);
    rotate([23, 37, 11]) cylinder(r = 5, h = 10, $fn = 12);
}
