#!/usr/bin/env python3
"""Writes the DXF inputs of this folder as plain group-code pairs."""


def dxf(path, sections):
    lines = []
    for name, entities in sections:
        lines += ['  0', 'SECTION', '  2', name]
        for entity in entities:
            for code, value in entity:
                lines += ['%3d' % code, str(value)]
        lines += ['  0', 'ENDSEC']
    lines += ['  0', 'EOF']
    open(path, 'w').write('\n'.join(lines) + '\n')


def line(x1, y1, x2, y2, layer='0'):
    return [(0, 'LINE'), (8, layer), (10, x1), (20, y1), (30, 0), (11, x2), (21, y2), (31, 0)]


def lwpolyline(points, closed, layer='0', bulges=None):
    e = [(0, 'LWPOLYLINE'), (8, layer), (90, len(points)), (70, 1 if closed else 0)]
    for i, (x, y) in enumerate(points):
        e += [(10, x), (20, y)]
        if bulges and i in bulges:
            e += [(42, bulges[i])]
    return e


def circle(x, y, r, layer='0'):
    return [(0, 'CIRCLE'), (8, layer), (10, x), (20, y), (30, 0), (40, r)]


def arc(x, y, r, start, end, layer='0'):
    return [(0, 'ARC'), (8, layer), (10, x), (20, y), (30, 0), (40, r), (50, start), (51, end)]


def ellipse(x, y, mx, my, ratio, start, end, layer='0'):
    return [(0, 'ELLIPSE'), (8, layer), (10, x), (20, y), (30, 0), (11, mx), (21, my), (31, 0),
            (40, ratio), (41, start), (42, end)]


def insert(block, x, y, sx=None, sy=None, rot=None, layer='0'):
    e = [(0, 'INSERT'), (8, layer), (2, block), (10, x), (20, y), (30, 0)]
    if sx is not None:
        e += [(41, sx)]
    if sy is not None:
        e += [(42, sy)]
    if rot is not None:
        e += [(50, rot)]
    return e


# An outer rectangle of LINEs (out of order, one reversed, one corner a hair
# off: the 2^-10 grid joins it), holes of every kind, an open polyline beside
# it, a layer of its own, and entities 2021.01 ignores (POLYLINE, SPLINE, TEXT).
shapes = [
    line(12, -10, 12, 10),
    line(-12, 10, -12, -10),
    line(-12, -10, 12, -10),
    line(-12, 10, 12.0003, 10),
    circle(-6, 2, 3),
    lwpolyline([(2, 2), (8, 2), (5, 7)], True, bulges={0: 0.5}),
    arc(6, -5, 2.5, 270, 90),
    line(6, -2.5, 6, -7.5),
    ellipse(-6, -6, 2.5, 1, 0.5, 0, 6.283185307179586),
    lwpolyline([(13, -5), (14.5, 0), (13, 5)], False),
    lwpolyline([(-14.5, 11), (-13, 11), (-13, 12.5), (-14.5, 12.5)], True, layer='marks'),
    arc(0, 12.5, 1.5, 0, 180, layer='marks'),
    line(-1.5, 12.5, 1.5, 12.5, layer='marks'),
    [(0, 'POLYLINE'), (8, '0'), (66, 1), (70, 1), (0, 'VERTEX'), (8, '0'), (10, 9), (20, 11),
     (0, 'VERTEX'), (8, '0'), (10, 11), (20, 11), (0, 'VERTEX'), (8, '0'), (10, 10), (20, 13),
     (0, 'SEQEND')],
    [(0, 'SPLINE'), (8, '0'), (70, 8), (71, 3), (72, 8), (73, 4),
     (40, 0), (40, 0), (40, 0), (40, 0), (40, 1), (40, 1), (40, 1), (40, 1),
     (10, -9), (20, -12), (10, -7), (20, -14), (10, -5), (20, -12), (10, -9), (20, -12)],
    [(0, 'TEXT'), (8, '0'), (10, 0), (20, -14), (40, 1), (1, 'ignored')],
]
dxf('shapes.dxf', [('HEADER', []), ('ENTITIES', shapes)])

# A block of a square with a round hole, inserted plainly, scaled and rotated,
# and once on another layer; an empty *Model_Space block as CAD programs write.
peg = [lwpolyline([(0, 0), (2, 0), (2, 1.5), (0, 1.5)], True), circle(1, 0.75, 0.5)]
blocks = [
    [(0, 'BLOCK'), (8, '0'), (2, '*Model_Space'), (70, 0), (10, 0), (20, 0)], [(0, 'ENDBLK'), (8, '0')],
    [(0, 'BLOCK'), (8, '0'), (2, 'PEG'), (70, 0), (10, 0), (20, 0)], *peg, [(0, 'ENDBLK'), (8, '0')],
]
inserts = [
    insert('PEG', 0, 0),
    insert('PEG', 5, 3, 2, 1.5, 30),
    insert('PEG', -6, -4, rot=90),
    insert('PEG', -10, 6, 1.25, 1.25, layer='other'),
    line(-3, -9, 3, -9), line(3, -9, 0, -6), line(0, -6, -3, -9),
]
dxf('blocks.dxf', [('BLOCKS', blocks), ('ENTITIES', inserts)])

# Sections without entities.
dxf('empty.dxf', [('HEADER', []), ('ENTITIES', [])])

# A tangle: random segments between the points of a 7 x 7 lattice (shared
# ends, T and X junctions, dangling open chains, three or more segments at a
# point), a block drawn at the same points and inserted in place (its points
# coincide with the entities'), and arcs that end on the lattice. Tests how
# segments are joined into paths, quirks included. No two segments overlap
# along a line: Clipper 6.4.2 (strata) and 6.2.1 (OpenSCAD 2021.01) clean up
# such overlaps differently.
import random
rng = random.Random(2021)
lattice = [(-12 + 4 * i, -12 + 4 * j) for i in range(7) for j in range(7)]
used = []


def overlaps(a, b):
    """Whether segment a-b runs along a segment already used (or has no length)."""
    if a == b:
        return True
    for c, d in used:
        cross1 = (b[0] - a[0]) * (c[1] - a[1]) - (b[1] - a[1]) * (c[0] - a[0])
        cross2 = (b[0] - a[0]) * (d[1] - a[1]) - (b[1] - a[1]) * (d[0] - a[0])
        if cross1 or cross2:
            continue
        axis = 0 if a[0] != b[0] else 1
        lo1, hi1 = sorted((a[axis], b[axis]))
        lo2, hi2 = sorted((c[axis], d[axis]))
        if min(hi1, hi2) > max(lo1, lo2):
            return True
    return False


def pick(chain):
    for _ in range(1000):
        b = rng.choice(lattice)
        if not overlaps(chain[-1], b) and all(not overlaps(chain[i], chain[i + 1]) or True for i in range(len(chain) - 1)):
            return b
    return None


knot_segments = [((-4, -4), (4, -4)), ((4, -4), (4, 4)), ((4, 4), (-4, -4)), ((8, 8), (12, 8))]
used += knot_segments
tangle = []
for k in range(60):
    a = rng.choice(lattice)
    chain = [a]
    for _ in range(1 if k % 2 else 2):
        b = pick(chain)
        if b is None:
            break
        used.append((chain[-1], b))
        chain.append(b)
    if len(chain) == 2:
        tangle.append(line(chain[0][0], chain[0][1], chain[1][0], chain[1][1]))
    elif len(chain) == 3:
        tangle.append(lwpolyline(chain, False))
tangle.append(arc(0, 0, 4, 0, 90))
tangle.append(arc(-8, -8, 4, 180, 90))
tangle.append(insert('KNOT', 0, 0))
knot = [(0, 'BLOCK'), (8, '0'), (2, 'KNOT'), (70, 0), (10, 0), (20, 0)]
knot_lines = [line(a[0], a[1], b[0], b[1]) for a, b in knot_segments]
dxf('tangle.dxf', [('BLOCKS', [knot, *knot_lines, [(0, 'ENDBLK'), (8, '0')]]), ('ENTITIES', tangle)])

# 2021.01 files the segments of a block in its grid under the number the next
# entity segment will get (0 here, as BLOCKS come first). An entity chain whose
# two ends meet such stale entries counts as closed, loses its first point and
# vanishes; the same chain elsewhere stays a triangle.
unused = [(0, 'BLOCK'), (8, '0'), (2, 'UNUSED'), (70, 0), (10, 0), (20, 0)]
stale = [
    lwpolyline([(-10, -10), (-5, -10), (-7, -6)], True),
    lwpolyline([(0, 0), (3, 3), (6, 0)], False),
    lwpolyline([(0, 5), (3, 8), (6, 5)], False),
]
dxf('stale.dxf', [('BLOCKS', [unused, line(0, 0, 6, 0), [(0, 'ENDBLK'), (8, '0')]]), ('ENTITIES', stale)])
