linear_extrude(height = 1) projection() sphere(5);
