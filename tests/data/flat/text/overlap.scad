// text("OOO", size=6, spacing=0.5);
// scaled by 2^16 and shifted by [-419675, -187988]: see README.md
multmatrix([[65536, 0, 0, -419675], [0, 65536, 0, -187988], [0, 0, 1, 0], [0, 0, 0, 1]])
    text("OOO", size=6, spacing=0.5);
