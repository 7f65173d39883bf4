// text("e", size=20, $fa=5, $fs=0.5);
// scaled by 2^16 and shifted by [-504417, -480857]: see README.md
multmatrix([[65536, 0, 0, -504417], [0, 65536, 0, -480857], [0, 0, 1, 0], [0, 0, 0, 1]])
    text("e", size=20, $fa=5, $fs=0.5);
