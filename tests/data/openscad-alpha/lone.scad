// A translucent cube alone: OpenSCAD draws its back faces, then its front faces.
color([1, 0, 0, 0.5]) cube(10, center = true);
