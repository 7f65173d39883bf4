// Two blocks touching (not overlapping): they share the whole face x = 10.
union() {
    cube(10);
    translate([10, 0, 0]) cube(10);
}
