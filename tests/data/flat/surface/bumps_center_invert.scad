// invert only applies to images: this is bumps.dat centred.
surface(file = "bumps.dat", center = true, invert = true);
