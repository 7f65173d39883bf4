scale(65536) import("shapes.dxf", $fa = 5, $fs = 0.5);
