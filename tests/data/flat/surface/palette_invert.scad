surface("palette.png", invert = true);
