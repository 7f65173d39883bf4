// A translucent cube in a difference (an OpenCSG product of two): its front faces only.
difference() {
  color([1, 0, 0, 0.5]) cube(10, center = true);
  translate([5, -5, 5]) cube(2, center = true);
}
