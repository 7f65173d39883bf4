scale(65536) import("stale.dxf");
