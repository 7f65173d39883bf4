// Not coincident: two cylinders, the second moved by hundredths and turned by a degree, intersected: the exact result takes the inner facet of each pair.
intersection() { cylinder(r = 10, h = 20, $fn = 48); translate([0.02, 0.01, 0]) rotate([0, 0, 1]) cylinder(r = 10, h = 20, $fn = 48); }
