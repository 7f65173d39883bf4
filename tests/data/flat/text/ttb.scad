// text("ABC", size=5, direction="ttb");
// scaled by 2^16 and shifted by [-3547, 624211]: see README.md
multmatrix([[65536, 0, 0, -3547], [0, 65536, 0, 624211], [0, 0, 1, 0], [0, 0, 0, 1]])
    text("ABC", size=5, direction="ttb");
