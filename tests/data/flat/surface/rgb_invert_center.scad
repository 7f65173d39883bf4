surface("rgb.png", invert = true, center = true);
