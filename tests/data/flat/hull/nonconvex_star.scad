minkowski() {
    linear_extrude(height = 2) polygon([for (i = [0:9]) (i % 2 == 0 ? 5 : 2) * [cos(36 * i), sin(36 * i)]]);
    sphere(0.5, $fn = 8);
}
