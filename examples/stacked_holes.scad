// A block drilled by three tunnels of overlapping spheres, one along each axis,
// and bitten at one corner. Looking into a tunnel, many sphere surfaces lie one
// behind another on the same view ray: the case that image-space CSG with one
// depth layer per operand gets wrong.
difference() {
    color("SteelBlue") cube(40, center = true);
    for (i = [-3 : 3]) {
        translate([9 * i, -8, 6]) sphere(r = 5.5, $fn = 32);
        translate([8, 9 * i, -7]) sphere(r = 5, $fn = 32);
        translate([-9, 9, 9 * i]) sphere(r = 6, $fn = 32);
    }
    translate([20, 20, 20]) sphere(r = 12, $fn = 48);
}
