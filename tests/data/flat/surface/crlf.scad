surface("crlf.dat", center = true);
