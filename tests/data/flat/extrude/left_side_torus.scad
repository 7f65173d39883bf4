rotate_extrude() translate([-6, 0]) circle(1.5);
