minkowski() {
    difference() { cube(10); translate([3, 3, 3]) cube(10); }
    rotate([10, 20, 30]) cylinder(r = 1, h = 1, $fn = 6);
}
