surface("rgb.png");
