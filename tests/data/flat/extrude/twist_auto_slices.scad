linear_extrude(height = 10, twist = -120) square([4, 2]);
