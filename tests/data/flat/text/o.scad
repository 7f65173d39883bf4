// text("o");
// scaled by 2^16 and shifted by [-253096, -240429]: see README.md
multmatrix([[65536, 0, 0, -253096], [0, 65536, 0, -240429], [0, 0, 1, 0], [0, 0, 0, 1]])
    text("o");
