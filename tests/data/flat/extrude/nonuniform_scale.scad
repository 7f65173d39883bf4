linear_extrude(height = 8, scale = [0.5, 2]) offset(r = 1) square(4);
