surface("grey_alpha.png", center = true);
