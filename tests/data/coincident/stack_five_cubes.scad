// Five identical cubes stacked by exactly their height: each top face coincides with the next cube's bottom face.
union() {
    for (i = [0 : 4]) translate([0, 0, 10 * i]) cube(10);
}
