// Intersection of two boxes whose bottom faces lie in the same plane z = 0: the result keeps that face.
intersection() {
    cube(20);
    translate([10, 5, 0]) cube([20, 10, 8]);
}
