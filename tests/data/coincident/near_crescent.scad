// Not coincident: a cylinder less itself moved by a hundredth, a crescent wall thinner than a pixel's depth step at its tips.
difference() { cylinder(r = 10, h = 20, $fn = 64); translate([0.01, 0, -1]) cylinder(r = 10, h = 22, $fn = 64); }
