// A translucent cube before an opaque one that lies behind it: drawn first,
// it hides the opaque one where it covers it.
color([1, 0, 0, 0.5]) cube(10, center = true);
color([0, 0, 1]) translate([0, 20, 0]) cube(20, center = true);
