scale(65536) import("quirks.svg");
