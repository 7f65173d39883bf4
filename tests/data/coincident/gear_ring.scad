// A ring with 12 teeth: the teeth's tops and bottoms (z = 0, z = 5) are coplanar with the ring's.
union() {
    difference() {
        cylinder(r = 15, h = 5, $fn = 48);
        translate([0, 0, -1]) cylinder(r = 10, h = 7, $fn = 48);
    }
    for (i = [0 : 11])
        rotate([0, 0, i * 30]) translate([14, -1.5, 0]) cube([4, 3, 5]);
}
