// pocket_flush_top rotated by odd angles: the flush top faces coincide in a plane that is not axis-aligned.
rotate([23, 37, 11]) difference() {
    cube(20);
    translate([4, 4, 10]) cube([6, 6, 10]);
}
