scale(65536) import("shapes.dxf");
