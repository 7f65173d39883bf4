// The pocket's top face (z = 20) lies in the same plane as the cube's top face.
difference() {
    cube(20);
    translate([4, 4, 10]) cube([6, 6, 10]);
}
