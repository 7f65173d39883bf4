// text("SO", size=5, font="Strata Cubic Test", $fn=48);
// scaled by 2^16 and shifted by [-278756, -152011]: see README.md
multmatrix([[65536, 0, 0, -278756], [0, 65536, 0, -152011], [0, 0, 1, 0], [0, 0, 0, 1]])
    text("SO", size=5, font="Strata Cubic Test", $fn=48);
