// text("Mono#1", size=4, font="Liberation Mono", halign="right", valign="bottom");
// scaled by 2^16 and shifted by [634884, -121730]: see README.md
multmatrix([[65536, 0, 0, 634884], [0, 65536, 0, -121730], [0, 0, 1, 0], [0, 0, 0, 1]])
    text("Mono#1", size=4, font="Liberation Mono", halign="right", valign="bottom");
