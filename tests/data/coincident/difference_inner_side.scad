// The subtrahend lies inside the box against its side x = 20 (shares that face plane from inside): a pocket opens in the side.
difference() {
    cube(20);
    translate([10, 5, 5]) cube([10, 10, 10]);
}
