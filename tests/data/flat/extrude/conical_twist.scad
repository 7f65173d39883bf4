linear_extrude(height = 6, scale = 0.3, twist = 200) circle(4, $fn = 7);
