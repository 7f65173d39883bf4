// With $fn = 26 the sphere has a vertex ring at z = 0: the cube's top face z = 0 contains the sphere's equator vertices and edges.
union() {
    sphere(r = 10, $fn = 26);
    translate([-15, -15, -15]) cube([30, 30, 15]);
}
