surface("palette8.png", invert = true);
