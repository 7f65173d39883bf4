surface("trailing.dat");
