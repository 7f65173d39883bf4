// text("a b");
// scaled by 2^16 and shifted by [-623978, -325314]: see README.md
multmatrix([[65536, 0, 0, -623978], [0, 65536, 0, -325314], [0, 0, 1, 0], [0, 0, 0, 1]])
    text("a b");
