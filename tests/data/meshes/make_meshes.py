#!/usr/bin/env python3
"""Writes the small mesh files the geometry import tests read.

Run from this folder; the outputs are checked in, so this is only needed to
change them. Every solid is outward oriented (counter-clockwise from outside)
unless its name says otherwise.
"""

# Unit cube [0,1]^3: corners and outward quads, counter-clockwise from outside.
CUBE_V = [(0, 0, 0), (1, 0, 0), (1, 1, 0), (0, 1, 0),
          (0, 0, 1), (1, 0, 1), (1, 1, 1), (0, 1, 1)]
CUBE_Q = [(0, 3, 2, 1),  # z = 0
          (4, 5, 6, 7),  # z = 1
          (0, 1, 5, 4),  # y = 0
          (1, 2, 6, 5),  # x = 1
          (2, 3, 7, 6),  # y = 1
          (3, 0, 4, 7)]  # x = 0


def tris(quads):
    return [t for q in quads for t in ((q[0], q[1], q[2]), (q[0], q[2], q[3]))]


def normal(a, b, c):
    u = [b[i] - a[i] for i in range(3)]
    v = [c[i] - a[i] for i in range(3)]
    return (u[1] * v[2] - u[2] * v[1], u[2] * v[0] - u[0] * v[2], u[0] * v[1] - u[1] * v[0])


def write_off(name, verts, faces):
    with open(name, "w") as f:
        f.write("OFF\n%d %d 0\n" % (len(verts), len(faces)))
        for v in verts:
            f.write("%g %g %g\n" % v)
        for face in faces:
            f.write("%d %s\n" % (len(face), " ".join(map(str, face))))


def write_off_openscad(name, verts, faces):
    """OFF as OpenSCAD 2021.01 writes it: the counts on the keyword's line."""
    with open(name, "w") as f:
        f.write("OFF %d %d 0\n" % (len(verts), len(faces)))
        for v in verts:
            f.write("%g %g %g \n" % v)
        for face in faces:
            f.write("%d %s\n" % (len(face), " ".join(map(str, face))))


def write_obj(name, verts, faces):
    with open(name, "w") as f:
        f.write("# strata test mesh\n")
        for v in verts:
            f.write("v %g %g %g\n" % v)
        for face in faces:
            f.write("f %s\n" % " ".join(str(i + 1) for i in face))


def write_ply(name, verts, faces):
    with open(name, "w") as f:
        f.write("ply\nformat ascii 1.0\nelement vertex %d\n" % len(verts))
        f.write("property float x\nproperty float y\nproperty float z\n")
        f.write("element face %d\nproperty list uchar int vertex_indices\nend_header\n" % len(faces))
        for v in verts:
            f.write("%g %g %g\n" % v)
        for face in faces:
            f.write("%d %s\n" % (len(face), " ".join(map(str, face))))


def write_stl_ascii(name, verts, triangles):
    with open(name, "w") as f:
        f.write("solid cube\n")
        for t in triangles:
            a, b, c = (verts[i] for i in t)
            f.write("  facet normal %g %g %g\n    outer loop\n" % normal(a, b, c))
            for p in (a, b, c):
                f.write("      vertex %g %g %g\n" % p)
            f.write("    endloop\n  endfacet\n")
        f.write("endsolid cube\n")


# A regular-ish tetrahedron with corners on the axes.
TET_V = [(0, 0, 0), (2, 0, 0), (0, 2, 0), (0, 0, 2)]
TET_F = [(0, 2, 1), (0, 1, 3), (0, 3, 2), (1, 2, 3)]

# An L-shaped prism, height 2: the L (area 3) is a non-convex hexagon.
L_2D = [(0, 0), (2, 0), (2, 1), (1, 1), (1, 2), (0, 2)]
L_V = [(x, y, 0) for x, y in L_2D] + [(x, y, 2) for x, y in L_2D]
L_F = [tuple(reversed(range(6))), tuple(range(6, 12))] + \
      [(i, (i + 1) % 6, (i + 1) % 6 + 6, i + 6) for i in range(6)]

# Two unit cubes sharing only the edge x = 1, y = 1: a non-manifold edge.
TWO_V = CUBE_V + [(x + 1, y + 1, z) for x, y, z in CUBE_V]
TWO_F = CUBE_Q + [tuple(i + 8 for i in q) for q in CUBE_Q]
# Weld the shared edge: the second cube's corners 0 and 4 are the first's 2 and 6.
TWO_F = [tuple({8: 2, 12: 6}.get(i, i) for i in q) for q in TWO_F]

if __name__ == "__main__":
    write_stl_ascii("cube_ascii.stl", CUBE_V, tris(CUBE_Q))
    write_off("cube.off", CUBE_V, CUBE_Q)
    write_off_openscad("cube_openscad.off", CUBE_V, CUBE_Q)
    write_obj("cube.obj", CUBE_V, CUBE_Q)
    write_ply("tetrahedron.ply", TET_V, TET_F)
    write_obj("l_prism.obj", L_V, L_F)
    write_off("open_box.off", CUBE_V, CUBE_Q[:5])
    write_off("two_cubes_sharing_edge.off", TWO_V, TWO_F)
    with open("garbage.off", "w") as f:
        f.write("OFF\nthis is not a mesh\n")
