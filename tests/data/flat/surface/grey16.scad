surface("grey16.png", center = true);
