scale(65536) import("shapes.dxf", origin = [3, -2], scale = 0.5, $fn = 7);
