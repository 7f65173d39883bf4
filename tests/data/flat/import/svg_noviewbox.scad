scale(65536) import("noviewbox.svg");
