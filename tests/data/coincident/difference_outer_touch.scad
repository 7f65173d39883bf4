// The subtrahend only touches the box's face x = 20 from outside: the result is the box, face x = 20 intact.
difference() {
    cube(20);
    translate([20, 5, 5]) cube([10, 10, 10]);
}
