scale(65536) import("tangle.dxf");
