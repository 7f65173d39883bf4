// text("fig", size=9, font="Liberation Sans:style=Bold Italic", valign="top", halign="right");
// scaled by 2^16 and shifted by [475026, 368082]: see README.md
multmatrix([[65536, 0, 0, 475026], [0, 65536, 0, 368082], [0, 0, 1, 0], [0, 0, 0, 1]])
    text("fig", size=9, font="Liberation Sans:style=Bold Italic", valign="top", halign="right");
