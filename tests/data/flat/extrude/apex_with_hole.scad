linear_extrude(height = 3, center = true, scale = 0) polygon(points = [[-5, -5], [5, -5], [5, 5], [-5, 5], [-2, -2], [2, -2], [2, 2], [-2, 2]], paths = [[0, 1, 2, 3], [4, 5, 6, 7]]);
