// text("AVAT", size=8);
// scaled by 2^16 and shifted by [-847035, -250473]: see README.md
multmatrix([[65536, 0, 0, -847035], [0, 65536, 0, -250473], [0, 0, 1, 0], [0, 0, 0, 1]])
    text("AVAT", size=8);
