#!/usr/bin/env python3
"""Writes the accuracy corpus: scenes/*.csg, meshes/*, and scenes.txt.

    python3 tests/accuracy/generate.py        # from anywhere; rewrites the files beside it

The output is checked in; run this again only to change the corpus. It is
deterministic (fixed seeds, fixed number formatting), so a re-run without
edits changes nothing.

Every scene is built to break image-space CSG: stacked subtractions
along the view ray, deep trees, n-ary nodes of 50+ operands, non-convex
operands (tori, imported meshes of depth complexity >= 6, several shells in one
leaf), subtrahends through the front and the back, thin walls, near-coincident
faces, the camera inside the model, mirrored and sheared leaves, and
(the coincident family) faces of different operands in one plane on purpose:
flush pockets and holes, shared faces, identical solids, turned and scaled.

Rules kept throughout:
  * no two operands have overlapping faces in one plane (near-coincident
    faces are offset by 1e-3 of the size or more, on purpose, never less),
    except in the coincident family, where such faces are the point: both
    paths take surfaces within the coincidence tolerance along a ray as one
    place (render::coincidenceTolerance), so the result is the exact one
    (tests/data/coincident holds OpenSCAD's, for its models);
  * stack axes and camera axes are shifted off round numbers, so no pixel
    centre's ray runs exactly along a face or through a symmetric vertex.

The text is OpenSCAD's CSG export dialect (what `openscad -o x.csg x.scad`
writes): group/union/intersection/difference, multmatrix, color, cube, sphere,
cylinder, polyhedron (faces clockwise seen from outside), import.
"""

import math
import os
import random
import struct

HERE = os.path.dirname(os.path.abspath(__file__))
SCENES = os.path.join(HERE, "scenes")
MESHES = os.path.join(HERE, "meshes")


# ----------------------------------------------------------------------------
# numbers and matrices (4x4, row-major lists, applied to column vectors)

def num(x, digits=10):
    x = float(x)
    if x == 0.0:
        return "0"
    return "%.*g" % (digits, x)


def identity():
    return [[1.0 if i == j else 0.0 for j in range(4)] for i in range(4)]


def matmul(a, b):
    return [[sum(a[i][k] * b[k][j] for k in range(4)) for j in range(4)] for i in range(4)]


def chain(*ms):
    out = identity()
    for m in ms:
        out = matmul(out, m)
    return out


def translate(x, y, z):
    m = identity()
    m[0][3], m[1][3], m[2][3] = x, y, z
    return m


def scale(x, y, z):
    m = identity()
    m[0][0], m[1][1], m[2][2] = x, y, z
    return m


def rotate(axis, degrees):
    ax, ay, az = axis
    n = math.sqrt(ax * ax + ay * ay + az * az)
    ax, ay, az = ax / n, ay / n, az / n
    c, s = math.cos(math.radians(degrees)), math.sin(math.radians(degrees))
    t = 1.0 - c
    m = identity()
    m[0][:3] = [t * ax * ax + c, t * ax * ay - s * az, t * ax * az + s * ay]
    m[1][:3] = [t * ax * ay + s * az, t * ay * ay + c, t * ay * az - s * ax]
    m[2][:3] = [t * ax * az - s * ay, t * ay * az + s * ax, t * az * az + c]
    return m


def shear(xy=0.0, xz=0.0, yx=0.0, yz=0.0, zx=0.0, zy=0.0):
    """x' = x + xy*y + xz*z, and so on."""
    m = identity()
    m[0][1], m[0][2] = xy, xz
    m[1][0], m[1][2] = yx, yz
    m[2][0], m[2][1] = zx, zy
    return m


def apply(m, p):
    return tuple(m[i][0] * p[0] + m[i][1] * p[1] + m[i][2] * p[2] + m[i][3] for i in range(3))


def det3(m):
    return (m[0][0] * (m[1][1] * m[2][2] - m[1][2] * m[2][1])
            - m[0][1] * (m[1][0] * m[2][2] - m[1][2] * m[2][0])
            + m[0][2] * (m[1][0] * m[2][1] - m[1][1] * m[2][0]))


# ----------------------------------------------------------------------------
# the CSG text

class Node:
    """A CSG node; children is None for a primitive (written `head;`)."""

    def __init__(self, head, children=None):
        self.head = head
        self.children = None if children is None else list(children)

    def text(self, indent=0):
        pad = "\t" * indent
        if self.children is None:
            return pad + self.head + ";\n"
        out = pad + self.head + " {\n"
        for c in self.children:
            out += c.text(indent + 1)
        return out + pad + "}\n"

    def depth(self):
        """Boolean nodes on the longest path to a primitive (multmatrix and color do not count)."""
        if self.children is None:
            return 0
        own = 1 if self.head.startswith(("union", "intersection", "difference")) else 0
        return own + max((c.depth() for c in self.children), default=0)


def union(*c):
    return Node("union()", c)


def group(*c):
    return Node("group()", c)


def intersection(*c):
    return Node("intersection()", c)


def difference(*c):
    return Node("difference()", c)


def mm(m, *c):
    rows = ", ".join("[" + ", ".join(num(v) for v in row) + "]" for row in m)
    return Node("multmatrix([" + rows + "])", c)


def color(rgb, *c):
    return Node("color([%s, %s, %s, 1])" % tuple(num(v) for v in rgb), c)


def cube(size, center=True):
    return Node("cube(size = [%s, %s, %s], center = %s)" % (num(size[0]), num(size[1]), num(size[2]),
                                                          "true" if center else "false"))


def sphere(r, fn=24):
    return Node("sphere($fn = %d, $fa = 12, $fs = 2, r = %s)" % (fn, num(r)))


def cylinder(h, r1, r2=None, fn=24, center=True):
    r2 = r1 if r2 is None else r2
    return Node("cylinder($fn = %d, $fa = 12, $fs = 2, h = %s, r1 = %s, r2 = %s, center = %s)" %
                (fn, num(h), num(r1), num(r2), "true" if center else "false"))


def polyhedron(points, triangles):
    """triangles: counter-clockwise seen from outside (written clockwise, as OpenSCAD does)."""
    assert signed_volume(points, triangles) > 0.0, "polyhedron is inside out"
    pts = ", ".join("[%s, %s, %s]" % tuple(num(v, 8) for v in p) for p in points)
    fcs = ", ".join("[%d, %d, %d]" % (t[2], t[1], t[0]) for t in triangles)
    return Node("polyhedron(points = [%s], faces = [%s], convexity = 10)" % (pts, fcs))


def imported(path):
    return Node('import(file = "%s", layer = "", origin = [0, 0], scale = 1, convexity = 10, '
                '$fn = 0, $fa = 12, $fs = 2, timestamp = 0)' % path)


def at(x, y, z, *c):
    return mm(translate(x, y, z), *c)


# Flat (2D) shapes and the extrusions that make solids of them, as OpenSCAD
# 2021.01 exports them.
FRAG = "$fn = %d, $fa = 12, $fs = 2"


def square(size, center=False):
    return Node("square(size = [%s, %s], center = %s)" % (num(size[0]), num(size[1]), "true" if center else "false"))


def circle(r, fn=0):
    return Node("circle(%s, r = %s)" % (FRAG % fn, num(r)))


def polygon(points, paths=None):
    pts = ", ".join("[%s, %s]" % (num(p[0], 8), num(p[1], 8)) for p in points)
    pth = "undef" if paths is None else "[" + ", ".join("[" + ", ".join(str(i) for i in p) + "]" for p in paths) + "]"
    return Node("polygon(points = [%s], paths = %s, convexity = 1)" % (pts, pth))


def text(string, size, halign="left", valign="baseline"):
    return Node('text(text = "%s", size = %s, spacing = 1, font = "", direction = "ltr", language = "en", '
                'script = "Latn", halign = "%s", valign = "%s", $fn = 0, $fa = 12, $fs = 2)'
                % (string, num(size), halign, valign))


def offset_r(r, *c, fn=0):
    return Node("offset(r = %s, %s)" % (num(r), FRAG % fn), c)


def linear_extrude(height, *c, center=False, twist=None, slices=None, scale=(1, 1), fn=0):
    args = ["height = %s" % num(height), "center = %s" % ("true" if center else "false"), "convexity = 2"]
    if twist is not None:
        args.append("twist = %s" % num(twist))
    if slices is not None:
        args.append("slices = %d" % slices)
    args.append("scale = [%s, %s]" % (num(scale[0]), num(scale[1])))
    if slices is None:
        args.append(FRAG % fn)
    return Node("linear_extrude(%s)" % ", ".join(args), c)


def resize(size, *c, auto=(0, 0, 0)):
    return Node("resize(newsize = [%s], auto = [%s], convexity = 0)" % (",".join(num(v) for v in size),
                                                                         ",".join(str(int(a)) for a in auto)), c)


def projection(cut, *c):
    return Node("projection(cut = %s, convexity = 0)" % ("true" if cut else "false"), c)


def hull(*c):
    return Node("hull()", c)


def minkowski(*c):
    return Node("minkowski(convexity = 0)", c)


def rotate_extrude(*c, angle=360, fn=0):
    return Node("rotate_extrude(angle = %s, convexity = 2, %s)" % (num(angle), FRAG % fn), c)


# ----------------------------------------------------------------------------
# meshes made here

def signed_volume(points, triangles):
    v = 0.0
    for a, b, c in triangles:
        pa, pb, pc = points[a], points[b], points[c]
        v += (pa[0] * (pb[1] * pc[2] - pb[2] * pc[1])
              - pa[1] * (pb[0] * pc[2] - pb[2] * pc[0])
              + pa[2] * (pb[0] * pc[1] - pb[1] * pc[0]))
    return v / 6.0


def uv_sphere(n=24, rings=12):
    """A unit sphere with flat polar caps, like OpenSCAD's: (points, ccw triangles)."""
    pts, tris = [], []
    for i in range(rings):
        phi = math.pi * (i + 0.5) / rings
        for k in range(n):
            th = 2.0 * math.pi * k / n
            pts.append((math.sin(phi) * math.cos(th), math.sin(phi) * math.sin(th), math.cos(phi)))
    idx = lambda i, k: i * n + (k % n)
    for i in range(rings - 1):
        for k in range(n):
            a, b, c, d = idx(i, k), idx(i + 1, k), idx(i + 1, k + 1), idx(i, k + 1)
            tris.append((a, b, c))
            tris.append((a, c, d))
    for k in range(1, n - 1):  # top cap (z > 0), seen from +z counter-clockwise
        tris.append((idx(0, 0), idx(0, k), idx(0, k + 1)))
    for k in range(1, n - 1):  # bottom cap, reversed
        tris.append((idx(rings - 1, 0), idx(rings - 1, k + 1), idx(rings - 1, k)))
    return pts, tris


def torus_mesh(R, r, nu=32, nv=16):
    """A torus around the z axis: (points, ccw triangles). Quads are planar."""
    pts, tris = [], []
    for i in range(nu):
        u = 2.0 * math.pi * i / nu
        for j in range(nv):
            v = 2.0 * math.pi * j / nv
            pts.append(((R + r * math.cos(v)) * math.cos(u), (R + r * math.cos(v)) * math.sin(u),
                        r * math.sin(v)))
    idx = lambda i, j: (i % nu) * nv + (j % nv)
    for i in range(nu):
        for j in range(nv):
            a, b, c, d = idx(i, j), idx(i + 1, j), idx(i + 1, j + 1), idx(i, j + 1)
            tris.append((a, b, c))
            tris.append((a, c, d))
    return pts, tris


def merge_meshes(parts):
    pts, tris = [], []
    for p, t in parts:
        base = len(pts)
        pts.extend(p)
        tris.extend((a + base, b + base, c + base) for a, b, c in t)
    return pts, tris


def transform_mesh(m, mesh):
    p, t = mesh
    p = [apply(m, q) for q in p]
    if det3(m) < 0:
        t = [(a, c, b) for a, b, c in t]
    return p, t


def torus(R, r, m=None, nu=32, nv=16):
    p, t = torus_mesh(R, r, nu, nv)
    if m is not None:
        p, t = transform_mesh(m, (p, t))
    return polyhedron(p, t)


def shells(centres_radii, n=24, rings=12):
    """One leaf made of several disjoint ellipsoid shells: a non-convex operand.
    centres_radii: ((cx, cy, cz), (rx, ry, rz)) per shell."""
    unit = uv_sphere(n, rings)
    parts = []
    for (cx, cy, cz), (rx, ry, rz) in centres_radii:
        parts.append(transform_mesh(chain(translate(cx, cy, cz), scale(rx, ry, rz)), unit))
    p, t = merge_meshes(parts)
    return polyhedron(p, t)


def ear_clip(poly):
    """Triangulates a simple counter-clockwise polygon (list of (x, y))."""
    idx = list(range(len(poly)))
    out = []

    def cross(o, a, b):
        return (a[0] - o[0]) * (b[1] - o[1]) - (a[1] - o[1]) * (b[0] - o[0])

    def inside(p, a, b, c):
        return cross(a, b, p) >= 0 and cross(b, c, p) >= 0 and cross(c, a, p) >= 0

    while len(idx) > 3:
        for k in range(len(idx)):
            i0, i1, i2 = idx[k - 1], idx[k], idx[(k + 1) % len(idx)]
            a, b, c = poly[i0], poly[i1], poly[i2]
            if cross(a, b, c) <= 0:
                continue
            if any(inside(poly[j], a, b, c) for j in idx if j not in (i0, i1, i2)):
                continue
            out.append((i0, i1, i2))
            idx.pop(k)
            break
        else:
            raise RuntimeError("ear clipping failed")
    out.append(tuple(idx))
    return out


def prism(poly, height):
    """The polygon (ccw in xy) extruded from z = 0 to z = height: (points, ccw triangles)."""
    n = len(poly)
    pts = [(x, y, 0.0) for x, y in poly] + [(x, y, height) for x, y in poly]
    tris = []
    for a, b, c in ear_clip(poly):
        tris.append((a, c, b))              # bottom, seen from -z
        tris.append((a + n, b + n, c + n))  # top
    for k in range(n):
        a, b = k, (k + 1) % n
        tris.append((a, b, b + n))
        tris.append((a, b + n, a + n))
    return pts, tris


def comb_polygon(teeth=5, tooth=1.2, gap=1.6, length=9.0, spine=2.0):
    """A comb, counter-clockwise: a spine along x (y in [0, spine]) and `teeth`
    teeth pointing +y, the first at the right end, the last at the left.
    Centred on the origin."""
    width = teeth * tooth + (teeth - 1) * gap
    top = spine + length
    poly = [(0.0, 0.0), (width, 0.0)]
    for k in range(teeth):
        right = width - k * (tooth + gap)
        left = right - tooth
        if k > 0:
            poly.append((right, spine))
        poly.append((right, top))
        poly.append((left, top))
        if k + 1 < teeth:
            poly.append((left, spine))
    assert abs(poly[-1][0]) < 1e-12  # the last tooth's left side runs down to (0, 0)
    return [(px - width / 2.0, py - top / 2.0) for px, py in poly]


def coil_mesh(Rc=6.0, a=1.1, turns=3.0, pitch=4.2, segments_per_turn=28, m=10):
    """A helical tube with flat end caps: depth complexity 4 x turns from the side."""
    steps = int(turns * segments_per_turn)
    pts, tris = [], []
    height = turns * pitch
    for s in range(steps + 1):
        th = 2.0 * math.pi * turns * s / steps
        z = height * s / steps - height / 2.0
        c = (Rc * math.cos(th), Rc * math.sin(th), z)
        # tangent, the radial direction (orthogonal to it) and the binormal
        tx, ty, tz = -Rc * math.sin(th) * 2 * math.pi * turns, Rc * math.cos(th) * 2 * math.pi * turns, height
        tl = math.sqrt(tx * tx + ty * ty + tz * tz)
        tx, ty, tz = tx / tl, ty / tl, tz / tl
        nx, ny, nz = math.cos(th), math.sin(th), 0.0
        bx, by, bz = ty * nz - tz * ny, tz * nx - tx * nz, tx * ny - ty * nx
        for k in range(m):
            v = 2.0 * math.pi * k / m
            pts.append((c[0] + a * (math.cos(v) * nx + math.sin(v) * bx),
                        c[1] + a * (math.cos(v) * ny + math.sin(v) * by),
                        c[2] + a * (math.cos(v) * nz + math.sin(v) * bz)))
    idx = lambda s, k: s * m + (k % m)
    for s in range(steps):
        for k in range(m):
            a0, b0, c0, d0 = idx(s, k), idx(s + 1, k), idx(s + 1, k + 1), idx(s, k + 1)
            tris.append((a0, b0, c0))
            tris.append((a0, c0, d0))
    for k in range(1, m - 1):
        tris.append((idx(0, 0), idx(0, k), idx(0, k + 1)))
        tris.append((idx(steps, 0), idx(steps, k + 1), idx(steps, k)))
    if signed_volume(pts, tris) < 0:
        tris = [(x, z, y) for x, y, z in tris]
    return pts, tris


def write_ascii_stl(path, mesh, name):
    p, t = mesh
    assert signed_volume(p, t) > 0
    with open(path, "w") as f:
        f.write("solid %s\n" % name)
        for a, b, c in t:
            pa, pb, pc = p[a], p[b], p[c]
            u = [pb[i] - pa[i] for i in range(3)]
            v = [pc[i] - pa[i] for i in range(3)]
            n = [u[1] * v[2] - u[2] * v[1], u[2] * v[0] - u[0] * v[2], u[0] * v[1] - u[1] * v[0]]
            ln = math.sqrt(sum(x * x for x in n)) or 1.0
            f.write("  facet normal %s %s %s\n    outer loop\n" % tuple("%.6e" % (x / ln) for x in n))
            for q in (pa, pb, pc):
                f.write("      vertex %s %s %s\n" % tuple("%.7e" % struct.unpack("f", struct.pack("f", x))[0]
                                                         for x in q))
            f.write("    endloop\n  endfacet\n")
        f.write("endsolid %s\n" % name)


def write_off(path, mesh):
    p, t = mesh
    assert signed_volume(p, t) > 0
    with open(path, "w") as f:
        f.write("OFF\n%d %d 0\n" % (len(p), len(t)))
        for q in p:
            f.write("%.7g %.7g %.7g\n" % q)
        for a, b, c in t:
            f.write("3 %d %d %d\n" % (a, b, c))


# ----------------------------------------------------------------------------
# cameras and the manifest

class Shot:
    def __init__(self, eye, center, projection="p", size=(96, 96), fov=None, flags=()):
        self.eye, self.center, self.projection = eye, center, projection
        self.size, self.fov, self.flags = size, fov, list(flags)


def orbit(center, azimuth, elevation, distance, **kw):
    """A camera looking at `center` from the given direction (degrees; azimuth from +x toward +y)."""
    az, el = math.radians(azimuth), math.radians(elevation)
    d = (math.cos(el) * math.cos(az), math.cos(el) * math.sin(az), math.sin(el))
    eye = tuple(center[i] + distance * d[i] for i in range(3))
    return Shot(eye, center, **kw)


SCENE_LIST = []


def scene(name, family, root, shots, note):
    SCENE_LIST.append((name, family, root, shots, note))


PALETTE = [(0.85, 0.55, 0.25), (0.3, 0.6, 0.85), (0.55, 0.8, 0.4), (0.8, 0.35, 0.45), (0.65, 0.5, 0.85),
           (0.9, 0.8, 0.3)]


# ----------------------------------------------------------------------------
# the scenes

# Stacks of plates on one axis, each plate holed by its own subtrahend; the
# holes shrink with depth, so every plate shows as a ring seen down the axis:
#
#    eye
#     :        ====   ====     plate 0, hole radius R0
#     :      ======   ======   plate 1, R1 < R0
#     :    ========   ======== ...
#     v    ==================  base plate, no hole
#
# The ellipsoids (rz = 1.2) are 3 apart: disjoint, so K of them can also be one
# polyhedron leaf of K shells (depth complexity 2K: the non-convex stack).
AX, AY = 0.137, -0.211  # the stack axis, off round numbers
# Cameras look straight along the stack from a little beside its axis: on the
# axis, the spheres' meridian edges would run exactly through pixel centres
# (the image's diagonals), rays through an edge whose facet is a tie.
CX, CY = AX + 0.0371, AY - 0.0233
PLATE_GAP, PLATE_T, SHELL_RZ = 3.0, 0.6, 1.2


def hole_radii(k_count, r_max=9.0, r_min=1.6):
    if k_count == 1:
        return [r_max]
    return [r_max - (r_max - r_min) * k / (k_count - 1) for k in range(k_count)]


def plates(k_count, width=22.0):
    out = []
    for k in range(k_count + 1):  # the last one is the base
        out.append(color(PALETTE[k % len(PALETTE)], at(AX, AY, -PLATE_GAP * k, cube((width, width, PLATE_T)))))
    return union(*out)


def alternating_radii(k_count):
    """Big and small holes in turn: a ray through a big hole meets the next
    plate, so the gap between two shells of one leaf holds visible material."""
    big = hole_radii((k_count + 1) // 2, 9.0, 6.0)
    small = hole_radii(k_count // 2, 4.5, 1.6) if k_count >= 2 else []
    return [big[k // 2] if k % 2 == 0 else small[k // 2] for k in range(k_count)]


def stack_shots(k_count, flags=(), size=(96, 96)):
    depth = PLATE_GAP * k_count
    top = 3.0
    return [
        Shot((CX, CY, top + 40.0 + depth * 0.2), (CX, CY, -depth / 2.0), "p", size, flags=flags),
        Shot((CX, CY, top + 30.0), (CX, CY, 0.0), "o", size, fov=30, flags=flags),
        orbit((AX, AY, -depth / 2.0), 33.0, 62.0, 70.0 + depth, size=size, flags=flags),
    ]


for k_count in (2, 4, 8, 16):
    radii = hole_radii(k_count)
    subs = [at(AX, AY, -PLATE_GAP * k, mm(scale(r, r, SHELL_RZ), sphere(1.0, 32))) for k, r in enumerate(radii)]
    size = (128, 128) if k_count == 16 else (96, 96)
    scene("stack_convex_%d" % k_count, "stack", difference(plates(k_count), *subs),
          stack_shots(k_count, size=size)[:2] if k_count != 4 else stack_shots(k_count, size=size),
          "%d plates, each holed by its own ellipsoid leaf (convex), on one axis" % k_count)

for k_count in (3, 8, 16):
    radii = alternating_radii(k_count)
    leaf = shells([((AX, AY, -PLATE_GAP * k), (r, r, SHELL_RZ)) for k, r in enumerate(radii)])
    size = (128, 128) if k_count == 16 else (96, 96)
    shots = stack_shots(k_count, flags=("nonconvex-stack",), size=size)
    scene("stack_shells_%d" % k_count, "stack", difference(plates(k_count), color(PALETTE[3], leaf)),
          shots if k_count == 8 else shots[:2],
          "%d plates holed by ONE leaf of %d disjoint ellipsoid shells, big and small holes in turn "
          "(depth complexity %d)" %
          (k_count, k_count, 2 * k_count))

# The same plates holed by rotated square prisms (cubes), each its own leaf.
cube_subs = []
for k, r in enumerate(hole_radii(6, 8.0, 2.0)):
    cube_subs.append(at(AX, AY, -PLATE_GAP * k, mm(rotate((0, 0, 1), 7.0 + 17.0 * k), cube((r * 1.6, r * 1.6, 2.0)))))
scene("stack_cubes_6", "stack", difference(plates(6), *cube_subs), stack_shots(6),
      "6 plates, each holed by its own rotated cube")

# The paper's failure (Goldfeather / Rossignac & Wu): a slab minus three
# spheres lined up on the view ray, the spheres ONE leaf. The first breaks the
# top face, the last the bottom face; slab material lies between them.
paper_spheres = [((AX, AY, 5.5), (2.5, 2.5, 2.5)), ((AX, AY, 0.0), (2.4, 2.4, 2.4)),
                 ((AX, AY, -5.5), (2.5, 2.5, 2.5))]
scene("stack_paper_3", "stack",
      difference(color(PALETTE[1], cube((20, 20, 12))), color(PALETTE[0], shells(paper_spheres))),
      [Shot((CX, CY, 60.0), (CX, CY, 0.0), "p", flags=("nonconvex-stack",)),
       Shot((CX, CY, -50.0), (CX, CY, 0.0), "o", fov=30, flags=("nonconvex-stack",)),
       orbit((AX, AY, 0.0), -40.0, 71.0, 60.0, flags=("nonconvex-stack",))],
      "a slab minus one leaf of three spheres on the view axis, breaking the top and bottom faces")

# The same three spheres as three leaves under a union node: the tree, not the
# leaf, is non-convex; one layer per operand is enough.
scene("stack_union_subtrahend", "stack",
      difference(color(PALETTE[1], cube((20, 20, 12))),
                 union(*[at(c[0], c[1], c[2], sphere(r[0], 24)) for c, r in paper_spheres])),
      [Shot((CX, CY, 60.0), (CX, CY, 0.0), "p"), orbit((AX, AY, 0.0), -40.0, 71.0, 60.0, projection="o", fov=30)],
      "a slab minus a union of three sphere leaves on the view axis")

# Two tori, each seen across its ring (four crossings per ray through the hole),
# stacked on the view axis; the top one breaks the slab's top face.
scene("stack_tori_2", "stack",
      difference(color(PALETTE[2], at(0, 0, -3.4, cube((22, 22, 17.8)))),
                 color(PALETTE[4], torus(3.0, 1.0, chain(translate(AX, AY, 2.5), rotate((0, 1, 0), 90)))),
                 color(PALETTE[4], torus(3.0, 1.0, chain(translate(AX, AY, -6.0), rotate((1, 0, 0), 90))))),
      [Shot((CX, CY, 60.0), (CX, CY, 0.0), "p", flags=("nonconvex-stack",)),
       Shot((CX, CY, 40.0), (CX, CY, 0.0), "o", fov=20, flags=("nonconvex-stack",))],
      "a slab minus two tori stacked on the view axis, each crossed four times by the central rays")

# A comb (depth complexity 10 through its teeth) as one subtrahend, its first
# tooth breaking the block's front face.
scene("stack_comb", "stack",
      difference(color(PALETTE[5], at(0.05, -0.25, 0, cube((17, 12.5, 16)))),
                 color(PALETTE[0], mm(chain(translate(0.2, 0.31, -1.0), rotate((0, 0, 1), 90), rotate((1, 0, 0), 90),
                                            translate(0, 0, -3.0)),
                                      imported("../meshes/comb.stl")))),
      [Shot((0.23, 58.0, 0.4), (0.23, 0.0, 0.4), "p", flags=("nonconvex-stack",)),
       Shot((0.23, 30.0, 0.4), (0.23, 0.0, 0.4), "o", fov=30, flags=("nonconvex-stack",))],
      "a block minus an imported comb whose 5 teeth line up on the view ray")

# Deep trees. Each level wraps the tree so far in one operation with a fresh
# operand (or a small subtree), so the result stays a solid with something of
# every level visible.
def deep_tree(seed, levels):
    rnd = random.Random(seed)

    def prim(size):
        kind = rnd.choice(("sphere", "cube", "cylinder"))
        rot = rotate((rnd.uniform(-1, 1), rnd.uniform(-1, 1), rnd.uniform(0.2, 1)), rnd.uniform(0, 90))
        if kind == "sphere":
            p = sphere(size * 0.6, 24)
        elif kind == "cube":
            p = cube((size, size * 0.8, size * 0.9))
        else:
            p = cylinder(size * 1.2, size * 0.45, fn=20)
        return mm(rot, p)

    def placed(size, spread):
        return at(rnd.uniform(-spread, spread), rnd.uniform(-spread, spread), rnd.uniform(-spread, spread),
                  color(rnd.choice(PALETTE), prim(size)))

    tree = color(PALETTE[1], mm(rotate((0.3, 0.2, 1), 11.0), cube((12.3, 11.1, 10.7))))
    ops = ["difference", "union", "intersection"]
    for level in range(levels):
        op = ops[level % 3] if level < 3 else rnd.choice(ops)
        if op == "difference":
            subs = [placed(rnd.uniform(3.0, 5.0), 7.0) for _ in range(rnd.randint(1, 2))]
            if rnd.random() < 0.5:
                subs.append(intersection(placed(6.0, 5.0), placed(6.0, 5.0)))
            tree = difference(tree, *subs)
        elif op == "union":
            extra = [placed(rnd.uniform(2.5, 4.5), 8.0) for _ in range(rnd.randint(1, 2))]
            if rnd.random() < 0.5:
                extra.append(difference(placed(5.0, 7.0), placed(3.0, 7.0)))
            tree = union(tree, *extra)
        else:
            big = at(rnd.uniform(-1, 1), rnd.uniform(-1, 1), rnd.uniform(-1, 1),
                     mm(rotate((rnd.uniform(-1, 1), 1, rnd.uniform(-1, 1)), rnd.uniform(0, 60)),
                        sphere(rnd.uniform(9.0, 10.5), 32) if rnd.random() < 0.5 else cube((17.1, 16.3, 15.9))))
            tree = intersection(tree, big)
    return tree


for seed, levels in ((7, 9), (11, 13)):
    t = deep_tree(seed, levels)
    scene("deep_tree_%d" % levels, "deep", t,
          [orbit((0, 0, 0), 35.0, 30.0, 60.0), orbit((0, 0, 0), 215.0, -20.0, 48.0, projection="o", fov=30)],
          "a tree of depth %d mixing union, intersection and difference (seed %d)" % (t.depth(), seed))

# One solid repeated: the same sphere intersected with a chain at every
# third level (the renderer peels identical leaves once and folds the inner
# intersections away), a copy subtracted from its original inside a union
# (nothing), and a copy of another colour (a solid of its own).
rnd = random.Random(9)
bound = lambda: sphere(9.5, 32)
chain_tree = cube((12, 12, 12))
for level in range(1, 13):
    piece = at(rnd.uniform(-6, 6), rnd.uniform(-6, 6), rnd.uniform(-6, 6),
               sphere(rnd.uniform(1.5, 3.0), 16) if level % 2 else cube((3, 3, 3)))
    chain_tree = difference(chain_tree, piece) if level % 3 == 1 else union(chain_tree, piece)
    if level % 3 == 0:
        chain_tree = intersection(chain_tree, bound())
scene("repeated_solid_chain", "deep",
      union(chain_tree,
            at(0, 0, 13, difference(cube((4, 4, 4)), cube((4, 4, 4)))),
            at(0, 0, -13, difference(cube((5, 5, 5)), color(PALETTE[2], cube((5, 5, 5))), sphere(2.8, 24)))),
      [orbit((0, 0, 0), 35.0, 30.0, 70.0), orbit((0, 0, 0), 200.0, -25.0, 60.0, projection="o", fov=35)],
      "one sphere intersected at every third level of a chain, and a cube minus its own copy")

# n-ary nodes.
rnd = random.Random(3)
balls = [at(rnd.uniform(-8, 8), rnd.uniform(-8, 8), rnd.uniform(-8, 8),
            color(rnd.choice(PALETTE), sphere(rnd.uniform(1.8, 3.4), 16))) for _ in range(64)]
scene("nary_union_64", "nary", union(*balls),
      [orbit((0, 0, 0), 20.0, 25.0, 75.0), orbit((0, 0, 0), 120.0, 60.0, 75.0, projection="o", fov=30)],
      "a union of 64 spheres")

rnd = random.Random(4)
cubes = [mm(chain(translate(rnd.uniform(-0.3, 0.3), rnd.uniform(-0.3, 0.3), rnd.uniform(-0.3, 0.3)),
                  rotate((rnd.uniform(-1, 1), rnd.uniform(-1, 1), rnd.uniform(-1, 1)), rnd.uniform(0, 180))),
            cube((16, 16, 16))) for _ in range(60)]
scene("nary_intersection_60", "nary", color(PALETTE[4], intersection(*cubes)),
      [orbit((0, 0, 0), 30.0, 20.0, 70.0), orbit((0, 0, 0), 80.0, -50.0, 70.0)],
      "an intersection of 60 randomly rotated cubes: a polytope of many faces")

rnd = random.Random(5)
big_balls = []
for _ in range(52):
    z = rnd.uniform(-1, 1)
    a = rnd.uniform(0, 2 * math.pi)
    s = math.sqrt(1 - z * z)
    big_balls.append(at(4.0 * s * math.cos(a), 4.0 * s * math.sin(a), 4.0 * z, sphere(10.0, 32)))
scene("nary_intersection_spheres_52", "nary", color(PALETTE[2], intersection(*big_balls)),
      [orbit((0, 0, 0), 10.0, 35.0, 55.0), orbit((0, 0, 0), 190.0, 10.0, 55.0, projection="o", fov=25)],
      "an intersection of 52 spheres of radius 10 whose centres lie 4 from the origin")

rnd = random.Random(6)
holes = [at(rnd.uniform(-10.5, 10.5), rnd.uniform(-10.5, 10.5), rnd.uniform(-10.5, 10.5),
            sphere(rnd.uniform(1.2, 3.0), 16)) for _ in range(64)]
scene("nary_cheese_64", "nary", difference(color(PALETTE[5], cube((20, 20, 20))), *holes),
      [orbit((0, 0, 0), 30.0, 35.0, 85.0), orbit((0, 0, 0), -60.0, -25.0, 85.0, projection="o", fov=25)],
      "a cube minus 64 spheres (the benchmark's cheese)")

# Non-convex operands.
scene("torus_chain", "nonconvex",
      union(color(PALETTE[0], torus(5.0, 1.3, translate(-5.1, 0.03, 0.0))),
            color(PALETTE[1], torus(5.0, 1.3, chain(translate(0.02, 0.0, 0.05), rotate((1, 0, 0), 90)))),
            color(PALETTE[2], torus(5.0, 1.3, translate(5.07, -0.04, 0.0)))),
      [orbit((0, 0, 0), 70.0, 40.0, 80.0), orbit((0, 0, 0), 0.5, 89.3, 60.0, projection="o", fov=30)],
      "three interlocked tori")

scene("torus_cuts", "nonconvex",
      union(difference(color(PALETTE[5], at(-6.0, 0, 0, cube((9.5, 9.5, 9.5)))),
                       torus(4.6, 1.1, chain(translate(-6.0, 0.1, 0.2), rotate((1, 0, 0), 20)))),
            intersection(color(PALETTE[4], torus(3.5, 1.6, chain(translate(6.0, 0.0, 0.0), rotate((0, 1, 0), 30)))),
                         at(6.0, 0.0, 1.1, mm(rotate((1, 1, 0), 40), cube((8.3, 8.3, 8.3)))))),
      [orbit((0, 0, 0), -85.0, 15.0, 70.0), orbit((0, 0, 0), 60.0, 50.0, 70.0, projection="o", fov=30)],
      "a cube minus a torus through its front and back faces; a torus intersected with a cube")

scene("coil_cut", "nonconvex",
      difference(union(color(PALETTE[2], imported("../meshes/coil.off")),
                       color(PALETTE[0], cylinder(16.0, 2.0, fn=24))),
                 at(0.1, -6.0, 0.3, mm(rotate((0, 0, 1), 8), cube((9.7, 12.0, 20.0))))),
      [orbit((0, 0, 0), -100.0, 8.0, 52.0, flags=("nonconvex-stack",)),
       orbit((0, 0, 0), -60.0, 40.0, 40.0, projection="o", fov=28)],
      "an imported coil (12 surfaces along a side ray) and a core, a quarter cut away")

scene("comb_ball", "nonconvex",
      union(intersection(color(PALETTE[0], mm(translate(0.0, 0.0, -3.0), imported("../meshes/comb.stl"))),
                         at(0.1, 0.2, 0.0, sphere(6.3, 32))),
            color(PALETTE[3], mm(rotate((0, 1, 0), 90), cylinder(18.0, 0.8, fn=16)))),
      [orbit((0, 0, 0), -75.0, 30.0, 60.0), Shot((-30.0, 0.13, 0.21), (0.0, 0.13, 0.21), "p", flags=("nonconvex-stack",))],
      "an imported comb intersected with a sphere, a rod through all its teeth")

scene("twisted_star", "nonconvex",
      difference(color(PALETTE[4], mm(translate(0, 0, -20), imported("../../../examples/meshes/twisted_star.stl"))),
                 at(0.21, -0.13, 14.0, sphere(9.0, 32)),
                 mm(rotate((1, 0, 0), 90), cylinder(40.0, 2.5, fn=20))),
      [orbit((0, 0, 0), 30.0, 25.0, 130.0), orbit((0, 0, 0), 95.0, 70.0, 110.0, projection="o", fov=30)],
      "the examples' twisted star (six surfaces along a ray) minus a sphere and a rod")

# Subtrahends through the front and the back.
scene("through_front_back", "through",
      union(difference(color(PALETTE[1], cube((16, 16, 8))),
                       at(0.11, -0.07, 0, mm(rotate((1, 0.2, 0), 12), cylinder(20.0, 3.2, fn=24))),
                       at(5.3, 4.9, 0, mm(rotate((0.3, 1, 0), 5), cube((3.1, 2.7, 12.0))))),
            color(PALETTE[0], at(0.3, 0.2, -9.0, cube((10, 10, 1.0))))),
      [Shot((0.4, -0.3, 60.0), (0.4, -0.3, 0.0), "p"), orbit((0, 0, 0), 50.0, 55.0, 60.0)],
      "a block pierced front to back by a tilted cylinder and a prism, a floor behind it")

scene("through_back_only", "through",
      difference(color(PALETTE[5], cube((14, 14, 14))),
                 at(0.2, 0.3, -8.5, sphere(4.0, 32)),
                 at(-3.1, 2.9, 7.9, sphere(2.5, 24))),
      [orbit((0, 0, 0), 20.0, 70.0, 60.0), orbit((0, 0, 0), 20.0, -70.0, 60.0, projection="o", fov=30)],
      "a cube minus a sphere that breaks only its back face, and a small one through the front")

# Thin walls (0.02 of 20).
scene("thin_box", "thin",
      difference(color(PALETTE[1], cube((20, 20, 20))), cube((19.96, 19.96, 19.96)),
                 at(-0.13, -10.0, 0.2, mm(rotate((1, 0, 0), 90), cylinder(6.0, 6.0, fn=32))),
                 at(10.0, 3.0, 4.0, sphere(5.0, 24))),
      [orbit((0, 0, 0), -70.0, 25.0, 75.0), orbit((0, 0, 0), -10.0, 10.0, 75.0, projection="o", fov=30)],
      "a hollow cube with walls 0.02 thick, windows cut into it")

scene("thin_fins", "thin",
      intersection(union(*[color(PALETTE[k % 6], at(0, 0, -9.0 + 1.5 * k + 0.013, mm(rotate((1, 0.3, 0), 4), cube((30, 30, 0.06)))))
                           for k in range(13)]),
                   sphere(10.0, 32)),
      [orbit((0, 0, 0), 25.0, 30.0, 60.0), orbit((0, 0, 0), 25.0, 3.0, 60.0, projection="o", fov=30)],
      "13 fins 0.06 thick, intersected with a sphere")

# Near-coincident faces: offsets of 1e-3 of the size (10), never zero.
scene("near_union", "near",
      union(color(PALETTE[0], cube((10, 10, 10))),
            color(PALETTE[1], at(4.03, 3.07, 0.01, cube((10, 10, 10)))),
            color(PALETTE[2], at(-3.01, 6.11, -0.01, cube((10, 10.02, 10))))),
      [orbit((1, 2, 0), 30.0, 50.0, 70.0), Shot((1.1, 2.3, 40.0), (1.1, 2.3, 0.0), "o", fov=35)],
      "a union of cubes whose faces lie 0.01 (1e-3 of their size) above and below each other")

scene("near_difference", "near",
      union(difference(color(PALETTE[3], at(-6.0, 0, 0, cube((10, 10, 10)))),
                       at(-6.02, 0.03, -0.01, cube((9.98, 9.97, 10.0)))),
            difference(color(PALETTE[4], at(6.0, 0, 0, cube((10, 10, 10)))),
                       at(6.3, 0.2, 0.01, cube((7.0, 7.0, 10.0))))),
      [orbit((0, 0, 0), -60.0, 40.0, 80.0), orbit((0, 0, 0), -60.0, -40.0, 80.0, projection="o", fov=30)],
      "cubes minus cubes 0.01 inside or outside their faces: skins and through-cuts")

scene("near_intersection", "near",
      intersection(color(PALETTE[2], sphere(8.0, 32)),
                   at(0.008, -0.006, 0.01, sphere(8.0, 32)),
                   at(0.0, 0.0, 7.99, cube((20, 20, 16)))),
      [orbit((0, 0, 0), 40.0, 35.0, 60.0), orbit((0, 0, 0), 40.0, 85.0, 60.0, projection="o", fov=30)],
      "two spheres 0.01 apart intersected, and a cube face 0.01 below the centre")

# The camera inside the model.
scene("nearplane_ortho", "inside",
      difference(color(PALETTE[1], cube((20, 20, 20))),
                 at(0.3, -0.2, -4.0, sphere(5.0, 24)), at(5.1, 5.3, 3.0, sphere(3.0, 24)),
                 at(-6.0, -5.0, 6.0, mm(rotate((1, 0, 0), 20), cylinder(30.0, 2.0, fn=16)))),
      [Shot((0.13, 0.07, 2.1), (0.13, 0.07, -8.0), "o", fov=60),
       Shot((2.1, -0.3, 0.17), (-8.0, -0.3, 0.17), "o", fov=60)],
      "an orthographic view whose ray origins lie inside a cube with cavities: the first exit shows")

scene("eye_in_subtrahend", "inside",
      union(difference(color(PALETTE[5], cube((16, 16, 16))), at(0.1, -8.0, 0.3, sphere(6.0, 32)),
                       at(3.0, 2.0, -2.0, sphere(2.5, 24))),
            color(PALETTE[1], at(11.3, -15.0, 0.2, mm(rotate((0, 0, 1), 20), cube((3.0, 3.0, 14.0)))))),
      [Shot((0.12, -7.0, 0.29), (10.0, -9.5, 0.3), "p", fov=80),
       Shot((1.0, -9.5, 1.2), (-10.0, -5.0, -6.0), "p", fov=60)],
      "the eye inside a subtracted sphere that bites the cube's front face, looking out and in")

scene("eye_in_result", "inside",
      difference(color(PALETTE[2], cube((24, 24, 24))), at(4.0, 5.0, 0.0, sphere(2.5, 24)),
                 at(-3.0, 6.0, 3.0, mm(rotate((1, 0, 0), 80), cylinder(30.0, 1.5, fn=16))),
                 at(1.0, 9.0, -4.0, cube((4.3, 3.1, 5.2)))),
      [Shot((0.11, -3.0, 0.23), (0.11, 5.0, 0.23), "p", fov=70),
       Shot((0.11, -3.0, 0.23), (5.0, 5.0, -3.0), "p", fov=50)],
      "the eye inside the result: every ray sees its first exit")

# Mirrored and sheared leaves.
wedge_pts = [(0, 0, 0), (6, 0, 0), (0, 4, 0), (0, 0, 3), (1.5, 0.3, 7)]  # not symmetric
wedge_tris = [(0, 2, 1), (0, 1, 3), (0, 3, 2), (1, 2, 4), (1, 4, 3), (2, 3, 4)]
if signed_volume(wedge_pts, wedge_tris) < 0:
    wedge_tris = [(a, c, b) for a, b, c in wedge_tris]
wedge = polyhedron(wedge_pts, wedge_tris)
mirror_x = scale(-1, 1, 1)
scene("mirrored", "transform",
      difference(union(color(PALETTE[0], at(0.6, 0, 0, wedge)),
                       color(PALETTE[1], mm(chain(translate(-0.6, 0, 0), mirror_x), wedge)),
                       color(PALETTE[2], mm(chain(translate(0, -3.0, 0), scale(1, -1, 1)),
                                            cylinder(5.0, 3.0, 1.0, fn=24, center=False)))),
                 mm(chain(translate(0.1, 1.0, 3.0), scale(-1.5, 1, -1)), at(1.0, 0.5, 0.0, sphere(1.6, 24)))),
      [orbit((0, 0, 2), 60.0, 25.0, 34.0), orbit((0, 0, 2), -120.0, -30.0, 30.0, projection="o", fov=30)],
      "a chiral wedge and its mirror image, a mirrored cone, minus a mirrored ellipsoid")

scene("sheared", "transform",
      union(difference(color(PALETTE[4], mm(shear(xz=0.6, yx=0.2), cube((8, 8, 8)))),
                       mm(chain(translate(2.0, 0.5, 3.5), shear(xy=0.5, zx=-0.3)), sphere(3.0, 24))),
            color(PALETTE[5], at(9.0, 0, 0, mm(shear(zx=0.7, yz=-0.4), cylinder(8.0, 2.5, fn=24))))),
      [orbit((3, 0, 0), 40.0, 30.0, 60.0), orbit((3, 0, 0), 140.0, 60.0, 60.0, projection="o", fov=30)],
      "a sheared cube minus a sheared sphere; a sheared cylinder")

mirror_shear = chain(translate(0.1, -0.2, 0.3), scale(1, 1, -1), shear(xy=0.4, zx=0.3), rotate((1, 0, 0), 70))
scene("mirrored_sheared_torus", "transform",
      difference(color(PALETTE[1], cube((14, 14, 6))),
                 torus(4.5, 1.2, mirror_shear),
                 mm(chain(translate(4.0, 4.0, 0), scale(-1, 1, 1), shear(xz=0.5)), cylinder(10.0, 1.5, fn=16))),
      [Shot((0.3, 0.1, 50.0), (0.3, 0.1, 0.0), "p"), orbit((0, 0, 0), -35.0, 35.0, 55.0, projection="o", fov=35)],
      "a slab minus a mirrored, sheared torus (through front and back) and a mirrored, sheared rod")


# Solids made from flat shapes: extrusions (twisted, scaled, revolved) of
# booleans, offsets and text, inside the CSG like any other leaf.
scene("flat_twist_cut", "flat",
      difference(color(PALETTE[0], linear_extrude(12.0, difference(square((10, 10), center=True), circle(3.0)),
                                                  center=True, twist=90, slices=8)),
                 at(4.0, 3.5, 4.5, sphere(3.5, 32))),
      [orbit((0, 0, 0), 35.0, 40.0, 45.0), orbit((0, 0, 0), 35.0, 80.0, 45.0, projection="o", fov=30)],
      "a square with a round hole extruded with a twist of 90 in 8 slices, a sphere cut from its corner")

vase = [(0.0, 0.0), (6.0, 0.0), (7.5, 3.0), (5.0, 9.0), (6.5, 14.0), (5.5, 14.0), (4.0, 9.0), (6.3, 3.2),
        (5.2, 1.0), (0.0, 1.0)]
scene("flat_revolved", "flat",
      union(difference(color(PALETTE[1], rotate_extrude(polygon(vase), fn=48)),
                       at(0, -10.0, 7.0, cube((20, 20, 20)))),
            color(PALETTE[2], at(0, 0, 3.0, rotate_extrude(mm(translate(9.0, 0, 0), circle(1.2, fn=16)),
                                                           angle=230, fn=40)))),
      [orbit((0, 0, 5), -60.0, 30.0, 55.0), orbit((0, 0, 5), 30.0, 60.0, 55.0, projection="o", fov=35)],
      "a revolved vase profile cut open, and a partial torus of 230 degrees around it")

scene("flat_text_block", "flat",
      difference(color(PALETTE[3], cube((34, 22, 8))),
                 at(0, 0, -6.0, linear_extrude(12.0, text("Sg", 14.0, halign="center", valign="center"))),
                 at(0, 0, 4.03, linear_extrude(4.0, offset_r(1.5, square((28, 16), center=True)), center=True))),
      [Shot((0.3, -0.2, 60.0), (0.3, -0.2, 0.0), "p", size=(128, 96)),
       orbit((0, 0, 0), -110.0, 55.0, 70.0, projection="o", fov=35, size=(128, 96))],
      "text cut through a block, under a pocket of rounded corners (an offset square)")

ring = [(-6, -6), (6, -6), (6, 6), (-6, 6), (-2.5, -2.5), (-2.5, 2.5), (2.5, 2.5), (2.5, -2.5)]
scene("flat_scaled_offset", "flat",
      difference(color(PALETTE[4], linear_extrude(10.0, offset_r(1.5, polygon(ring, [[0, 1, 2, 3], [4, 5, 6, 7]]), fn=24),
                                                  twist=-45, scale=(0.5, 1.3))),
                 at(0, 0, 5.0, mm(rotate((1, 0, 0), 90), cylinder(30.0, 1.8, fn=24)))),
      [orbit((0, 0, 5), 50.0, 35.0, 50.0), orbit((0, 0, 5), 50.0, -60.0, 50.0, projection="o", fov=35)],
      "a rounded square ring (an offset polygon with a hole) extruded with twist and a scale of [0.5, 1.3], pierced")


# hull() and minkowski() of convex solids: one convex leaf each (a minkowski
# of a union, a union of them).
scene("hull_die", "hull",
      difference(color(PALETTE[5], hull(*[at(x, y, z, sphere(1.6, 24)) for x in (-4.2, 4.2) for y in (-4.2, 4.2)
                                          for z in (-4.2, 4.2)])),
                 *[at(dx, -5.9, dz, sphere(1.1, 20)) for dx, dz in ((-2.5, 2.5), (0, 0), (2.5, -2.5))],
                 *[at(5.9, dy, dz, sphere(1.1, 20)) for dy, dz in ((-2.5, -2.5), (2.5, 2.5))]),
      [orbit((0, 0, 0), -55.0, 30.0, 40.0), orbit((0, 0, 0), 20.0, -25.0, 40.0, projection="o", fov=35)],
      "OpenSCAD's die: a hull of eight spheres minus dots on two faces")

scene("minkowski_rounded", "hull",
      union(color(PALETTE[1], minkowski(union(cube((8, 4, 3)), at(3.0, 3.0, 0.4, cube((2, 6, 3.6)))),
                                        sphere(1.0, 16))),
            difference(color(PALETTE[2], at(-9.0, 0, 0, minkowski(cylinder(3.0, 2.5, fn=24), mm(rotate((1, 1, 0), 30),
                                                                                              cube((2, 2, 2)))))),
                       at(-9.0, 0, 2.3, sphere(2.0, 24)))),
      [orbit((-2, 1, 0), 40.0, 35.0, 45.0), orbit((-2, 1, 0), -140.0, 50.0, 45.0, projection="o", fov=35)],
      "a Minkowski sum of a union of two boxes and a sphere (a union of two hulls), and one of a cylinder and a turned cube, bitten")


# minkowski() of non-convex solids: split into convex parts, summed and joined
# exactly on the CPU into one leaf.
STAR = [((5.0 if i % 2 == 0 else 2.2) * math.cos(math.radians(36 * i)),
         (5.0 if i % 2 == 0 else 2.2) * math.sin(math.radians(36 * i))) for i in range(10)]

scene("minkowski_nonconvex", "hull",
      union(difference(color(PALETTE[3], minkowski(linear_extrude(2.0, polygon(STAR)), sphere(0.8, 12))),
                       at(0, 0, 1.0, cylinder(6.0, 1.2, fn=24))),
            color(PALETTE[0], at(-4.0, 9.0, -1.0,
                                 minkowski(difference(cube((8, 6, 3)), at(2.5, 2.0, -1.0, cube((8, 8, 5)))),
                                           mm(rotate((0, 0, 1), 30), cube((1.5, 1.5, 1.5))))))),
      [orbit((0, 3, 0), 35.0, 45.0, 50.0), orbit((0, 3, 0), -110.0, -30.0, 50.0, projection="o", fov=35)],
      "a star extrusion plus a sphere, bored, and an L-shaped difference plus a turned cube: Minkowski sums of non-convex solids")


scene("resized", "hull",
      difference(color(PALETTE[3], resize((18.0, 11.0, 7.0), sphere(5.0, 32))),
                 at(0, 0, 2.0, resize((14.0, 0, 0), union(cube((4, 4, 6)), at(4.0, 0, 0, cylinder(6.0, 2.0, fn=24))),
                                      auto=(1, 1, 0)))),
      [orbit((0, 0, 0), 30.0, 40.0, 45.0), orbit((0, 0, 0), 120.0, 70.0, 45.0, projection="o", fov=35)],
      "a sphere resized to an ellipsoid, minus a resized union of a box and a cylinder (resize with auto axes)")


scene("flat_projected", "flat",
      union(difference(color(PALETTE[0], cube((20, 14, 4))),
                       at(0, 0, -1.0, linear_extrude(8.0, projection(True, difference(sphere(6.0, 32),
                                                                                        cylinder(20.0, 2.0, fn=24))),
                                                     center=True))),
            color(PALETTE[1], at(0, 12.0, -2.0, linear_extrude(3.0, projection(False, mm(rotate((1, 0.5, 0), 50),
                                                                                          cube((8, 3, 2)))))))),
      [orbit((0, 4, 0), -60.0, 45.0, 55.0), orbit((0, 4, 0), 20.0, 75.0, 55.0, projection="o", fov=35)],
      "a slab holed by the section of a bored sphere (projection cut), and the extruded shadow of a turned box")


scene("exact_results", "hull",
      union(color(PALETTE[4], hull(difference(sphere(5.0, 32), at(0, 0, 4.0, cube((12, 12, 8)))),
                                   at(7.0, 0, -2.0, cube((2, 2, 2))))),
            color(PALETTE[0], at(0, 11.0, 0, resize((8.0, 0, 0), intersection(sphere(4.0, 24), at(2.0, 0, 0, cube((6, 6, 6)))),
                                                    auto=(1, 1, 1))))),
      [orbit((1, 5, 0), 35.0, 40.0, 50.0), orbit((1, 5, 0), -120.0, -35.0, 50.0, projection="o", fov=35)],
      "a hull of a sphere cut flat and a cube, and a resized intersection: exact results of a difference and an intersection")


# Coincident faces, on purpose: the models of tests/data/coincident (OpenSCAD's
# exact results of them are there), where faces of different operands lie in
# one plane, share edges or are the same. Both paths must treat surfaces within
# the coincidence tolerance along a ray as one place
# (render::coincidenceTolerance): a flush pocket opens cleanly, shared faces vanish,
# A - A is empty. No color(): the scheme's face and cut-face colours show, so a
# surface shown with the wrong cut bit is a shading disagreement. Each model
# also comes rotated by odd angles (the coincident planes no longer axis
# aligned, their copies a float rounding apart) and scaled by 1e-3 and 1e3
# (the tolerance must scale with the view).

def sdeg(d):
    """sin and cos of d degrees, exact where they are at multiples of 30 (as OpenSCAD's sin_degrees)."""
    h = math.sqrt(3.0) / 2.0
    table = {0: (0.0, 1.0), 30: (0.5, h), 60: (h, 0.5), 90: (1.0, 0.0), 120: (h, -0.5), 150: (0.5, -h),
             180: (0.0, -1.0), 210: (-0.5, -h), 240: (-h, -0.5), 270: (-1.0, 0.0), 300: (-h, 0.5), 330: (-0.5, h)}
    if d % 30 == 0:
        return table[d % 360]
    return math.sin(math.radians(d)), math.cos(math.radians(d))


def rot_axis(axis, d):
    s_, c_ = sdeg(d)
    m = identity()
    i, j = {"x": (1, 2), "y": (2, 0), "z": (0, 1)}[axis]
    m[i][i], m[i][j], m[j][i], m[j][j] = c_, -s_, s_, c_
    return m


def rotate_xyz(ax, ay, az):
    """OpenSCAD's rotate([ax, ay, az]): about x, then y, then z."""
    return chain(rot_axis("z", az), rot_axis("y", ay), rot_axis("x", ax))


def box(x, y, z, sx, sy, sz):
    """OpenSCAD's translate([x, y, z]) cube([sx, sy, sz]) (corner at the origin)."""
    return at(x, y, z, cube((sx, sy, sz), center=False))


def pocket_flush_top():
    return difference(cube((20, 20, 20), center=False), box(4, 4, 10, 6, 6, 10))


def through_holes():
    # A square hole and a 13-sided round one ($fn = 0: $fa and $fs pick 13),
    # each exactly as tall as its plate: both ends flush.
    return union(difference(cube((20, 20, 10), center=False), box(6, 6, 0, 8, 8, 10)),
                 at(24, 0, 0, difference(cube((20, 20, 4), center=False),
                                         at(10, 10, 0, cylinder(4, 4, fn=0, center=False)))))


def flush_slot():
    return difference(cube((30, 20, 10), center=False), box(12, 0, 4, 6, 10, 10))


def side_pockets():
    # A pocket opening in the side x = 20; two pockets touching at x = 34 (a
    # wall of no thickness, which vanishes).
    return union(difference(cube((20, 20, 20), center=False), box(10, 5, 5, 10, 10, 10)),
                 at(24, 0, 0, difference(cube((20, 20, 10), center=False), box(2, 2, 2, 8, 16, 10),
                                         box(10, 2, 2, 8, 16, 10))))


def shared_face_unions():
    # Three blocks in an L (two shared faces) and five cubes stacked by their
    # height (four shared faces).
    return union(cube((10, 10, 10), center=False), box(10, 0, 0, 10, 10, 10), box(0, 10, 0, 10, 10, 10),
                 *[box(24, 0, 10 * i, 10, 10, 10) for i in range(5)])


def gear_ring():
    teeth = [mm(rot_axis("z", 30 * i), box(14, -1.5, 0, 4, 3, 5)) for i in range(12)]
    return union(difference(cylinder(5, 15, fn=48, center=False),
                            at(0, 0, -1, cylinder(7, 10, fn=48, center=False))),
                 group(*teeth))


def shared_face_intersection():
    return intersection(cube((20, 20, 20), center=False), box(10, 5, 0, 20, 10, 8))


def identical_solids():
    # A | A, A & A and A - A of one turned 12-sided cylinder: every face of one
    # operand is a face of the other. The last is empty.
    def a():
        return mm(rotate_xyz(23, 37, 11), cylinder(10, 5, fn=12, center=False))
    return union(union(a(), a()), at(16, 0, 0, intersection(a(), a())), at(32, 0, 0, difference(a(), a())))


def sphere_cube_equator():
    # $fn = 26 puts a ring of the sphere's vertices at z = 0, in the cube's top.
    return union(sphere(10, 26), box(-15, -15, -15, 30, 30, 15))


def corners(lo, hi):
    return [(x, y, z) for x in (lo[0], hi[0]) for y in (lo[1], hi[1]) for z in (lo[2], hi[2])]


COINCIDENT = [
    # name, model, its bounds (before the variant's transform), what coincides
    ("flush_pocket", pocket_flush_top, ((0, 0, 0), (20, 20, 20)),
     "a cube minus a pocket whose top lies in the cube's top face"),
    ("through_holes", through_holes, ((0, 0, 0), (44, 20, 10)),
     "a square and a 13-sided hole as tall as their plates: both ends flush"),
    ("flush_slot", flush_slot, ((0, 0, 0), (30, 20, 14)),
     "a slot whose front face lies in the block's front face"),
    ("side_pockets", side_pockets, ((0, 0, 0), (44, 20, 20)),
     "a pocket flush with a side face; two pockets touching (a wall of no thickness vanishes)"),
    ("shared_unions", shared_face_unions, ((0, 0, 0), (34, 20, 50)),
     "three blocks in an L and five stacked cubes: unions of shared faces"),
    ("gear_ring", gear_ring, ((-18, -18, -1), (18, 18, 6)),
     "a ring with 12 teeth whose tops and bottoms lie in the ring's"),
    ("shared_intersection", shared_face_intersection, ((0, 0, 0), (30, 20, 20)),
     "two boxes intersected whose bottoms lie in one plane"),
    ("identical_solids", identical_solids, ((-8, -8, -6), (40, 8, 12)),
     "A | A, A & A and A - A of one turned cylinder (the last is empty)"),
    ("sphere_cube_equator", sphere_cube_equator, ((-15, -15, -15), (15, 15, 10)),
     "a sphere on a cube whose top runs through the sphere's equator vertices"),
]

# The variants: the model as written, turned by odd angles, and turned another
# way and scaled by 1e-3 and by 1e3.
VARIANTS = [
    ("", identity(), ""),
    ("_turned", rotate_xyz(23, 37, 11), ", turned by [23, 37, 11]"),
    ("_milli", chain(scale(1e-3, 1e-3, 1e-3), rotate_xyz(-31, 13, 47)), ", turned by [-31, 13, 47] and scaled by 1e-3"),
    ("_kilo", chain(scale(1e3, 1e3, 1e3), rotate_xyz(17, -29, 71)), ", turned by [17, -29, 71] and scaled by 1e3"),
]

for k, (name, make, (lo, hi), note) in enumerate(COINCIDENT):
    for v, (suffix, m, how) in enumerate(VARIANTS):
        pts = [apply(m, c) for c in corners(lo, hi)]
        c = tuple((min(p[i] for p in pts) + max(p[i] for p in pts)) / 2.0 for i in range(3))
        diag = math.sqrt(sum((max(p[i] for p in pts) - min(p[i] for p in pts)) ** 2 for i in range(3)))
        # Odd angles, different for every scene and variant; one view from below.
        az = -58.3 + 47.9 * k + 83.1 * v
        el = (27.7, 41.3, -22.9, 34.1)[(k + v) % 4]
        big = (200, 150) if (k, v) in ((0, 0), (4, 0)) else (128, 96) if (k + v) % 3 == 2 else (96, 96)
        if v == 0:
            shots = [orbit(c, az, el, 2.1 * diag, size=big),
                     orbit(c, az + 131.7, 52.9 - el, 2.1 * diag, projection="o", fov=40)]
        elif v == 2:
            shots = [orbit(c, az, el, 2.1 * diag, projection="o", fov=40, size=big)]
        else:
            shots = [orbit(c, az, el, 2.1 * diag, size=big)]
        root = make() if v == 0 else mm(m, make())
        scene("coincident_" + name + suffix, "coincident", root, shots, note + how)


# ----------------------------------------------------------------------------

def main():
    os.makedirs(SCENES, exist_ok=True)
    os.makedirs(MESHES, exist_ok=True)
    comb = prism(comb_polygon(), 6.0)
    write_ascii_stl(os.path.join(MESHES, "comb.stl"), comb, "comb")
    write_off(os.path.join(MESHES, "coil.off"), coil_mesh())

    for f in os.listdir(SCENES):
        if f.endswith(".csg"):
            os.remove(os.path.join(SCENES, f))
    lines = ["# The accuracy corpus: one line per scene and camera. Written by generate.py; do not edit.",
             "# scene family projection WxH eye_x,eye_y,eye_z,center_x,center_y,center_z [fov=DEG] [flags]",
             "# flags: nonconvex-stack = a non-convex operand stacked on the view ray: must FAIL the bounds with one peel layer"]
    notes = ["# What each scene is for (docs/accuracy.md shows this column)."]
    for name, family, root, shots, note in SCENE_LIST:
        with open(os.path.join(SCENES, name + ".csg"), "w") as f:
            f.write("// %s\n// Written by tests/accuracy/generate.py.\n" % note)
            f.write(group(root).text())
        notes.append("%s\t%s" % (name, note))
        for s in shots:
            cam = ",".join(num(round(v, 6)) for v in tuple(s.eye) + tuple(s.center))
            extra = []
            if s.fov is not None:
                extra.append("fov=%s" % num(s.fov))
            extra.extend(s.flags)
            lines.append(" ".join([name + ".csg", family, s.projection, "%dx%d" % s.size, cam] + extra))
    with open(os.path.join(HERE, "scenes.txt"), "w") as f:
        f.write("\n".join(lines) + "\n")
    with open(os.path.join(HERE, "notes.txt"), "w") as f:
        f.write("\n".join(notes) + "\n")
    print("%d scenes, %d cameras" % (len(SCENE_LIST), len(lines) - 3))


if __name__ == "__main__":
    main()
