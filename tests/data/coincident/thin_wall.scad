// Two pockets leave a wall 0.01 thick between x = 10 and x = 10.01: nothing coincides, the thin wall is real geometry and must survive.
difference() {
    cube([20, 20, 10]);
    translate([2, 2, 2]) cube([8, 16, 10]);
    translate([10.01, 2, 2]) cube([7.99, 16, 10]);
}
