// text("ODS", size=6, font="Strata Cubic Test");
// scaled by 2^16 and shifted by [-545825, -184977]: see README.md
multmatrix([[65536, 0, 0, -545825], [0, 65536, 0, -184977], [0, 0, 1, 0], [0, 0, 0, 1]])
    text("ODS", size=6, font="Strata Cubic Test");
