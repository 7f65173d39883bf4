// text("ÅÇøé", size=6);
// scaled by 2^16 and shifted by [-673590, -180388]: see README.md
multmatrix([[65536, 0, 0, -673590], [0, 65536, 0, -180388], [0, 0, 1, 0], [0, 0, 0, 1]])
    text("ÅÇøé", size=6);
