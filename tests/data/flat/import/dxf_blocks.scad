scale(65536) import("blocks.dxf");
