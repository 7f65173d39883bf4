// A square through hole exactly as tall as the block: its bottom (z = 0) and top (z = 10) are flush with the block's.
difference() {
    cube([20, 20, 10]);
    translate([6, 6, 0]) cube([8, 8, 10]);
}
