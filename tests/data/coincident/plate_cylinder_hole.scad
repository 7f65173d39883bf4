// A cylinder exactly as tall as the plate is thick: both its end caps are flush with the plate's faces (default $fn: 13 sides).
difference() {
    cube([20, 20, 4]);
    translate([10, 10, 0]) cylinder(r = 4, h = 4);
}
