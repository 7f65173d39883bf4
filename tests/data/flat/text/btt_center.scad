// text("Hi", size=6, direction="btt", halign="center", valign="center");
// scaled by 2^16 and shifted by [144308, -9573]: see README.md
multmatrix([[65536, 0, 0, 144308], [0, 65536, 0, -9573], [0, 0, 1, 0], [0, 0, 0, 1]])
    text("Hi", size=6, direction="btt", halign="center", valign="center");
