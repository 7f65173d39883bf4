// A row of `count` cubes `size` wide, each with a hole through it: a module
// with a parameter and variables for -D to set
// (tests/apps/StrataRenderScadGLTest.cpp).
count = 2;
size = 4;

module holed(s) {
    difference() {
        cube(s, center = true);
        rotate([90, 0, 0]) cylinder(h = 2 * s, r = s / 4, center = true, $fn = 24);
    }
}

for (i = [0 : count - 1]) translate([i * size * 1.5, 0, 0]) holed(size);
