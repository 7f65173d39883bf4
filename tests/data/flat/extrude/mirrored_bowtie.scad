linear_extrude(height = 1) scale([1, -1]) translate([1, 1]) polygon([[0, 0], [4, 3], [4, 0], [0, 3]]);
