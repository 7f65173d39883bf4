linear_extrude(height = 2) offset(delta = 1.5, chamfer = true) polygon([for (i = [0 : 9]) (i % 2 == 0 ? 5 : 2) * [cos(36 * i), sin(36 * i)]]);
