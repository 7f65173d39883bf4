// Source of meshes/twisted_star.stl: a six-pointed star extruded with a twist,
// a non-convex solid (up to six surfaces along one ray). Written by
//   cd examples/meshes && openscad --export-format binstl -o twisted_star.stl twisted_star.scad
linear_extrude(height = 40, twist = 120, slices = 24)
    polygon([for (i = [0 : 11]) (i % 2 == 0 ? 14 : 6) * [cos(30 * i), sin(30 * i)]]);
