scale(65536) import("drawing.svg", center = true);
