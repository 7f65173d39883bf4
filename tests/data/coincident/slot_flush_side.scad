// A slot cut in from the front: its front face (y = 0) lies in the block's front face (it overshoots the top).
difference() {
    cube([30, 20, 10]);
    translate([12, 0, 4]) cube([6, 10, 10]);
}
