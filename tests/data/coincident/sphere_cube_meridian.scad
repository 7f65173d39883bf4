// With $fn = 24 (no vertex ring at z = 0) the cube's face x = 0 passes through the sphere's 24 vertices, and the edges between them, on its x = 0 great circle.
union() {
    sphere(r = 10, $fn = 24);
    translate([-15, -15, -15]) cube([15, 30, 30]);
}
