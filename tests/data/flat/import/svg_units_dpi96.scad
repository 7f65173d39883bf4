scale(65536) import("units.svg", dpi = 96);
