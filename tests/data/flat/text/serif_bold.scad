// text("Rag", font="Liberation Serif:style=Bold");
// scaled by 2^16 and shifted by [-774058, -197545]: see README.md
multmatrix([[65536, 0, 0, -774058], [0, 65536, 0, -197545], [0, 0, 1, 0], [0, 0, 0, 1]])
    text("Rag", font="Liberation Serif:style=Bold");
