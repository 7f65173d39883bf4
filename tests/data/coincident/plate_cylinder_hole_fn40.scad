// As plate_cylinder_hole with $fn = 40: both end caps of the 40-sided cylinder are flush with the plate's faces.
difference() {
    cube([20, 20, 4]);
    translate([10, 10, 0]) cylinder(r = 4, h = 4, $fn = 40);
}
