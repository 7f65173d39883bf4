surface("grey4_interlaced.png");
