// Two pockets touching at x = 10 (a wall of zero thickness): their shared face coincides and the wall must vanish (one open pocket).
difference() {
    cube([20, 20, 10]);
    translate([2, 2, 2]) cube([8, 16, 10]);
    translate([10, 2, 2]) cube([8, 16, 10]);
}
