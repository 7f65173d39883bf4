linear_extrude(height = 1) projection(cut = true) rotate([20, 35, 10]) cube([8, 6, 4], center = true);
