// A & A: every face of one operand coincides with the other's; the result is A.
intersection() {
    rotate([23, 37, 11]) cylinder(r = 5, h = 10, $fn = 12);
    rotate([23, 37, 11]) cylinder(r = 5, h = 10, $fn = 12);
}
