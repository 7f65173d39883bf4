// Three blocks in an L: the corner block shares its face x = 10 with one and y = 10 with the other.
union() {
    cube(10);
    translate([10, 0, 0]) cube(10);
    translate([0, 10, 0]) cube(10);
}
