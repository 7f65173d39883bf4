// text("Fb", font="NoSuchFont Foo");
// scaled by 2^16 and shifted by [-564288, -339319]: see README.md
multmatrix([[65536, 0, 0, -564288], [0, 65536, 0, -339319], [0, 0, 1, 0], [0, 0, 0, 1]])
    text("Fb", font="NoSuchFont Foo");
