// text("S", size=4, $fn=40);
// scaled by 2^16 and shifted by [-121327, -125326]: see README.md
multmatrix([[65536, 0, 0, -121327], [0, 65536, 0, -125326], [0, 0, 1, 0], [0, 0, 0, 1]])
    text("S", size=4, $fn=40);
