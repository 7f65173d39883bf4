rotate_extrude(angle = -90, $fn = 12) polygon([[0, 0], [3, 0], [3, 5], [1, 6], [0, 6]]);
