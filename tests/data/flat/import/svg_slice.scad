scale(65536) import("slice.svg");
