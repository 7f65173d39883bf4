// text("DO", size=5, font="Strata Cubic Test", $fn=20, halign="center");
// scaled by 2^16 and shifted by [-12622, -159288]: see README.md
multmatrix([[65536, 0, 0, -12622], [0, 65536, 0, -159288], [0, 0, 1, 0], [0, 0, 0, 1]])
    text("DO", size=5, font="Strata Cubic Test", $fn=20, halign="center");
