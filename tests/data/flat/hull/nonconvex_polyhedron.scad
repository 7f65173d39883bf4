// An L-shaped prism, written as a polyhedron, summed with a cube and a cone.
minkowski() {
    polyhedron(points = [[0, 0, 0], [6, 0, 0], [6, 2, 0], [2, 2, 0], [2, 5, 0], [0, 5, 0],
                         [0, 0, 3], [6, 0, 3], [6, 2, 3], [2, 2, 3], [2, 5, 3], [0, 5, 3]],
               faces = [[5, 4, 3, 2, 1, 0], [6, 7, 8, 9, 10, 11],
                        [0, 1, 7, 6], [1, 2, 8, 7], [2, 3, 9, 8], [3, 4, 10, 9], [4, 5, 11, 10], [5, 0, 6, 11]]);
    cube([1, 0.5, 0.25], center = true);
    cylinder(r1 = 0.5, r2 = 0, h = 1, $fn = 5);
}
