linear_extrude(height = 5, twist = 90, slices = 8) difference() { square(10, center = true); circle(3); }
