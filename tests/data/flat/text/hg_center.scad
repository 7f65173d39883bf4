// text("Hg", size=7, spacing=1.3, halign="center", valign="center");
// scaled by 2^16 and shifted by [42165, -3677]: see README.md
multmatrix([[65536, 0, 0, 42165], [0, 65536, 0, -3677], [0, 0, 1, 0], [0, 0, 0, 1]])
    text("Hg", size=7, spacing=1.3, halign="center", valign="center");
