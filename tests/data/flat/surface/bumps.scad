surface(file = "bumps.dat");
