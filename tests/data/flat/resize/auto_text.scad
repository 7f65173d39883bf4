resize([40, 0, 0], auto = true) linear_extrude(height = 2) text("Resize", size = 8);
