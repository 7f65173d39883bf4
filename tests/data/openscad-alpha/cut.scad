// A translucent subtrahend: its cut faces, once, over the background.
difference() {
  cube(10, center = true);
  color([1, 0, 0, 0.5]) translate([0, -5, 0]) sphere(4);
}
