// text("שלום", size=6, direction="rtl", language="he", script="Hebr");
// scaled by 2^16 and shifted by [-602192, -215986]: see README.md
multmatrix([[65536, 0, 0, -602192], [0, 65536, 0, -215986], [0, 0, 1, 0], [0, 0, 0, 1]])
    text("שלום", size=6, direction="rtl", language="he", script="Hebr");
