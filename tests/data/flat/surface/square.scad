surface("square.dat", center = true);
