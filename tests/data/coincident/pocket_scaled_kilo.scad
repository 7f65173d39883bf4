// pocket_flush_top scaled by 1000: the flush top faces coincide at z = 20000 (tolerance must scale up).
scale([1000, 1000, 1000]) difference() {
    cube(20);
    translate([4, 4, 10]) cube([6, 6, 10]);
}
