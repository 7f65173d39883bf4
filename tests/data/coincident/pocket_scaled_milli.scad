// pocket_flush_top scaled by 0.001: the flush top faces coincide at z = 0.02 (tolerance must scale down).
scale([0.001, 0.001, 0.001]) difference() {
    cube(20);
    translate([4, 4, 10]) cube([6, 6, 10]);
}
