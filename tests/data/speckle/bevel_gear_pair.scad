// MCAD's bevel gear pair (involute_gears.scad): teeth whose sides cross the big gear's cut face.
use <MCAD/involute_gears.scad>
bevel_gear_pair(gear1_teeth=31, gear2_teeth=17, axis_angle=90);
