scale(65536) import("blocks.dxf", origin = [1, 1], scale = 0.75, $fn = 9);
