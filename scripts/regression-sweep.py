#!/usr/bin/env python3
"""The comparisons of scripts/regression-sweep.sh (see its header).

  regression-sweep.py camera EXACT.stl
      prints "TX,TY,TZ,55,0,25,DIST DIAG": OpenSCAD's default view (gimbal
      form, --viewall --autocenter) fitted to the mesh's box, and the box's
      diagonal.
  regression-sweep.py compare DIR W,H CAMERA DIAG
      reads DIR/{strata,exact}-{depth,normal}.exr, prints one line of
      "key=value" figures and writes DIR/diff.png.
  regression-sweep.py table OUT
      the Markdown table, the skip list and the failures from OUT/*/result.
  regression-sweep.py side OUT N
      the N files with the most differing non-edge pixels, those whose
      difference has a known cause (a node strata leaves out, a part
      OpenSCAD's CGAL dropped with an ERROR) after the others; for the shell
      to put their strata | exact | diff strips together.
  regression-sweep.py recompare OUT W,H
      compare again every compared model of OUT, from the AOVs kept there.

A pixel's verdict, first that fails: coverage (hit in one image only), depth
(view depth apart by more than 1e-4 of the exact box's diagonal), normal
(more than 1 degree apart). The exact image alone says which pixels are edge
pixels, as the accuracy suite does (tests/accuracy/Compare.h): a pixel beside
an edge of it (a neighbour missed where the pixel hits or the other way
round, a crease of more than 30 degrees, a depth step of more than half a
pixel footprint plus the depth tolerance) is an edge pixel whatever its
verdict; a pixel beside a facet boundary only (a neighbour's normal more
than 1 degree off: every pixel between two facets of a sphere) is one when
it differs only in its normal, by at most 30 degrees (it went to the next
facet); any other difference there counts, since coverage and depth are
continuous across facets. A lone pixel: covered, its 8 neighbours covered,
and its normal more than 1 degree from each of theirs, in strata's image but
not in the exact one.

Needs python3 with numpy (Debian's python3-numpy); the EXR reader is its
own (scanline files, no, ZIPS or ZIP compression: what strata writes).
"""
import math
import os
import re
import struct
import sys
import zlib

import numpy as np

DEPTH_TOL = 1e-4       # of the exact box's diagonal
NORMAL_TOL_DEG = 1.0
CREASE_DEG = 30.0     # a larger turn between neighbours is an edge
STEP_PIXELS = 0.5     # an off-plane step of more pixel footprints is an edge
FOV_DEG = 22.5
ROTATION = (55.0, 0.0, 25.0)


# ---------------------------------------------------------------- EXR input
def read_exr(path):
    """{channel: HxW float32 array} of a scanline OpenEXR file of float or half channels."""
    data = open(path, 'rb').read()
    if struct.unpack_from('<I', data, 0)[0] != 20000630:
        raise ValueError(path + ': not an OpenEXR file')
    pos = 8
    attrs = {}
    while data[pos] != 0:
        end = data.index(b'\0', pos)
        name = data[pos:end].decode()
        tend = data.index(b'\0', end + 1)
        size = struct.unpack_from('<i', data, tend + 1)[0]
        attrs[name] = data[tend + 5:tend + 5 + size]
        pos = tend + 5 + size
    pos += 1
    channels = []
    c = attrs['channels']
    p = 0
    while c[p] != 0:
        end = c.index(b'\0', p)
        ptype = struct.unpack_from('<i', c, end + 1)[0]
        channels.append((c[p:end].decode(), ptype))
        p = end + 1 + 16
    xmin, ymin, xmax, ymax = struct.unpack('<4i', attrs['dataWindow'])
    w, h = xmax - xmin + 1, ymax - ymin + 1
    comp = attrs['compression'][0]
    lines = {0: 1, 2: 1, 3: 16}.get(comp)
    if lines is None:
        raise ValueError('%s: compression %d is not read here' % (path, comp))
    bpp = [4 if t in (1, 2) else 2 for _, t in channels]
    dtypes = ['<u4' if t == 0 else '<f2' if t == 1 else '<f4' for _, t in channels]
    chunks = (h + lines - 1) // lines
    offsets = struct.unpack_from('<%dQ' % chunks, data, pos)
    out = {name: np.zeros((h, w), np.float32) for name, _ in channels}
    for off in offsets:
        y, size = struct.unpack_from('<ii', data, off)
        raw = data[off + 8:off + 8 + size]
        n = min(lines, ymax + 1 - y)
        want = n * w * sum(bpp)
        if comp != 0 and size < want:
            t = np.frombuffer(zlib.decompress(raw), np.uint8).astype(np.int32)
            t = (np.cumsum(t - 128 * (np.arange(t.size) > 0)) + 0) & 0xFF  # undo the predictor
            t = t.astype(np.uint8)
            half = (t.size + 1) // 2
            raw = np.empty(t.size, np.uint8)
            raw[0::2] = t[:half]
            raw[1::2] = t[half:]
            raw = raw.tobytes()
        q = 0
        for row in range(n):
            for (name, _), b, dt in zip(channels, bpp, dtypes):
                out[name][y - ymin + row] = np.frombuffer(raw, dt, w, q).astype(np.float32)
                q += w * b
    return out


# --------------------------------------------------------------- PNG output
def write_png(path, rgba):
    h, w, _ = rgba.shape
    raw = b''.join(b'\0' + rgba[j].tobytes() for j in range(h))

    def chunk(kind, body):
        return struct.pack('>I', len(body)) + kind + body + struct.pack('>I', zlib.crc32(kind + body) & 0xffffffff)
    with open(path, 'wb') as f:
        f.write(b'\x89PNG\r\n\x1a\n' + chunk(b'IHDR', struct.pack('>IIBBBBB', w, h, 8, 6, 0, 0, 0))
                + chunk(b'IDAT', zlib.compress(raw, 6)) + chunk(b'IEND', b''))


# ------------------------------------------------------------------- camera
def stl_vertices(path):
    data = open(path, 'rb').read()
    # ASCII: 'solid NAME' then facets, or straight 'endsolid' when empty.
    if data[:5] == b'solid' and (b'facet' in data[:2000] or b'endsolid' in data.split()[1:3]):
        v = re.findall(rb'vertex\s+(\S+)\s+(\S+)\s+(\S+)', data)
        return np.array(v, dtype=np.float64).reshape(-1, 3)
    n = struct.unpack_from('<I', data, 80)[0]
    rec = np.frombuffer(data, np.dtype([('n', '<3f4'), ('v', '<9f4'), ('a', '<u2')]), n, 84)
    return rec['v'].reshape(-1, 3).astype(np.float64)


def rot(v, axis, deg):
    c, s = math.cos(math.radians(deg)), math.sin(math.radians(deg))
    x, y, z = v
    if axis == 0:
        return (x, c * y - s * z, s * y + c * z)
    if axis == 1:
        return (c * x + s * z, y, -s * x + c * z)
    return (c * x - s * y, s * x + c * y, z)


def gimbal(numbers):
    """Eye and centre of strata's gimbal camera (engine/camera/Camera.cpp, placeGimbal)."""
    t = np.array(numbers[:3])
    o = (0.0, -numbers[6], 0.0)
    o = rot(o, 0, numbers[3] - 90.0)
    o = rot(o, 1, numbers[4])
    o = rot(o, 2, numbers[5])
    return t + np.array(o), t


def cmd_camera(stl):
    v = stl_vertices(stl)
    if not len(v):
        sys.exit('no triangles (an empty result)')
    lo, hi = v.min(0), v.max(0)
    diag = float(np.linalg.norm(hi - lo))
    c = (lo + hi) / 2
    dist = (diag / 2) / math.sin(math.radians(FOV_DEG) / 2) if diag > 0 else 140.0
    print('%.9g,%.9g,%.9g,%g,%g,%g,%.9g %.9g' % (c[0], c[1], c[2], *ROTATION, dist, diag))


# ------------------------------------------------------------------ compare
def neighbours(a, fill):
    """The 8 shifted copies of a (HxW[xC]), padded with fill: list of (dy, dx, shifted)."""
    pad = [(1, 1), (1, 1)] + [(0, 0)] * (a.ndim - 2)
    p = np.pad(a, pad, constant_values=fill)
    h, w = a.shape[:2]
    return [(dy, dx, p[1 + dy:1 + dy + h, 1 + dx:1 + dx + w])
            for dy in (-1, 0, 1) for dx in (-1, 0, 1) if dy or dx]


def cmd_compare(d, size, camera, diag):
    w, h = map(int, size.split(','))
    diag = float(diag)
    nums = [float(x) for x in camera.split(',')]
    eye, centre = gimbal(nums)
    f = centre - eye
    f /= np.linalg.norm(f)
    r = np.cross(f, (0, 0, 1))
    r = r / np.linalg.norm(r) if np.linalg.norm(r) > 1e-12 else np.array((0.0, 1.0, 0.0))
    u = np.cross(r, f)
    t = math.tan(math.radians(FOV_DEG) / 2)
    x = 2 * (np.arange(w) + 0.5) / w - 1
    y = 1 - 2 * (np.arange(h) + 0.5) / h
    X, Y = np.meshgrid(x, y)
    dirs = f + (X * t * w / h)[..., None] * r + (Y * t)[..., None] * u
    dirs /= np.linalg.norm(dirs, axis=2)[..., None]
    cos_f = dirs @ f

    def load(who):
        z = read_exr(os.path.join(d, who + '-depth.exr'))['Z'].astype(np.float64)
        nn = read_exr(os.path.join(d, who + '-normal.exr'))
        n = np.stack([nn['R'], nn['G'], nn['B']], axis=2).astype(np.float64)
        hit = np.isfinite(z)
        zz = np.where(hit, z, 0.0)
        pts = eye + dirs * (zz / cos_f)[..., None]
        ln = np.linalg.norm(n, axis=2)
        n = np.where(hit[..., None] & (ln[..., None] > 0), n / np.maximum(ln, 1e-30)[..., None], 0.0)
        return hit, zz, n, pts

    hs, zs, ns, ps = load('strata')
    he, ze, ne, pe = load('exact')
    cos_tol = math.cos(math.radians(NORMAL_TOL_DEG))
    tol = DEPTH_TOL * diag

    # What separates a pixel of the exact image from each neighbour (as
    # tests/accuracy/Compare.cpp): an edge (a silhouette, a crease of more
    # than 30 degrees, a depth step: either point off the other's tangent
    # plane by more than half a pixel footprint plus the depth tolerance), or
    # else a facet boundary (normals more than 1 degree apart).
    cos_crease = math.cos(math.radians(CREASE_DEG))
    foot = 2 * t / h
    edge = np.zeros((h, w), bool)
    facet = np.zeros((h, w), bool)
    inside = np.ones((h, w), bool)
    for (dy, dx, hq), (_, _, nq), (_, _, pq), (_, _, zq), (_, _, vq) in zip(
            neighbours(he, False), neighbours(ne, 0.0), neighbours(pe, 0.0), neighbours(ze, 0.0),
            neighbours(inside, False)):
        c = np.einsum('ijk,ijk->ij', nq, ne)
        off = np.maximum(np.abs(np.einsum('ijk,ijk->ij', pq - pe, ne)), np.abs(np.einsum('ijk,ijk->ij', pe - pq, nq)))
        step = off > STEP_PIXELS * foot * np.maximum(ze, zq) + tol
        both_hit = he & hq
        edge |= vq & ((hq != he) | (both_hit & ((c < cos_crease) | step)))
        facet |= vq & both_hit & (c < cos_tol)
    facet &= ~edge

    cov = hs != he
    both = hs & he
    dep = both & (np.abs(zs - ze) > tol)
    nor = both & ~dep & (np.einsum('ijk,ijk->ij', ns, ne) < cos_tol)
    bad = cov | dep | nor

    def lone(hit, n):
        out = hit.copy()
        for (_, _, hq), (_, _, nq) in zip(neighbours(hit, False), neighbours(n, 0.0)):
            out &= hq & (np.einsum('ijk,ijk->ij', nq, n) < cos_tol)
        return out
    lone_px = lone(hs, ns) & ~lone(he, ne)

    # Beside a facet boundary only a normal-only difference of at most 30
    # degrees is an edge pixel's (the pixel went to the next facet); coverage
    # and depth are continuous there, so any other difference counts.
    swap = facet & nor & (np.einsum('ijk,ijk->ij', ns, ne) >= cos_crease)
    excused = edge | swap
    ne_ = ~excused
    fig = dict(covered_exact=int(he.sum()), covered_strata=int(hs.sum()),
               edge_pixels=int((edge & (hs | he)).sum()), facet_pixels=int(facet.sum()),
               coverage=int((cov & ne_).sum()), depth=int((dep & ne_).sum()), normal=int((nor & ne_).sum()),
               edge_diff=int((bad & excused).sum()), lone=int(lone_px.sum()))
    fig['nonedge'] = fig['coverage'] + fig['depth'] + fig['normal']
    print(' '.join('%s=%d' % kv for kv in fig.items()))

    # diff.png: the exact image in grey (|n.view|), non-edge differences in
    # colour (coverage red, depth blue, normal green), differing edge pixels
    # yellow, lone pixels magenta.
    shade = np.abs(np.einsum('ijk,ijk->ij', ne, -dirs))
    img = np.zeros((h, w, 4), np.uint8)
    img[..., 3] = 255
    g = np.where(he, 60 + 120 * shade, 255).astype(np.uint8)
    img[..., 0] = img[..., 1] = img[..., 2] = g
    img[hs & ~he] = (230, 230, 230, 255)
    img[bad & excused] = (230, 200, 0, 255)
    img[cov & ne_] = (230, 0, 0, 255)
    img[dep & ne_] = (0, 60, 255, 255)
    img[nor & ne_] = (0, 190, 0, 255)
    img[lone_px] = (255, 0, 255, 255)
    write_png(os.path.join(d, 'diff.png'), img)


# -------------------------------------------------------------------- table
def results(out):
    rows = []
    for name in sorted(os.listdir(out)):
        p = os.path.join(out, name, 'result')
        if not os.path.isfile(p):
            continue
        r = {}
        for line in open(p):
            if '=' in line:
                k, v = line.rstrip('\n').split('=', 1)
                r[k] = v
        r['dir'] = name
        rows.append(r)
    return rows


def notes(out, r):
    """What the logs say that bears on a row: strata's warnings (a node left
    out or ignored), and OpenSCAD's errors and ignored children (the exact
    result then lacks a part, whatever strata draws)."""
    said = []
    d = os.path.join(out, r['dir'])
    seen = set()
    for line in open_lines(os.path.join(d, 'strata.log')):
        if ' warning: ' in line:
            w = line.split(' warning: ', 1)[1].split(' (further')[0].split('; its subtree')[0]
            if w not in seen:
                seen.add(w)
                said.append('strata: ' + w)
    for line in open_lines(os.path.join(d, 'openscad.log')):
        if line.startswith('ERROR:') or 'Ignoring 2D child' in line or 'Ignoring 3D child' in line:
            w = re.sub(r' in file [^,]*, line \d+', '', line[:120])
            if w not in seen:
                seen.add(w)
                said.append('OpenSCAD: ' + w)
    return '; '.join(said).replace('|', '\\|')


def open_lines(path):
    try:
        with open(path, errors='replace') as f:
            return [l.rstrip('\n') for l in f]
    except OSError:
        return []


def cmd_table(out):
    rows = results(out)
    done = [r for r in rows if r.get('status') == 'compared']
    skipped = [r for r in rows if r.get('status') == 'skipped']
    failed = [r for r in rows if r.get('status') == 'strata-failed']
    nodraw = [r for r in rows if r.get('status') == 'exact-failed']
    print('| file | OpenSCAD s | strata s | covered | differing non-edge (coverage / depth / normal) | edge differing | lone | notes |')
    print('| --- | ---: | ---: | ---: | --- | ---: | ---: | --- |')
    tot = dict(nonedge=0, coverage=0, depth=0, normal=0, edge_diff=0, lone=0, covered_exact=0, edge_pixels=0)
    for r in sorted(done, key=lambda r: r['file']):
        for k in tot:
            tot[k] += int(r[k])
        ne = int(r['nonedge'])
        cell = '**%d** (%s / %s / %s)' % (ne, r['coverage'], r['depth'], r['normal']) if ne else '0'
        print('| %s | %s | %s | %s | %s | %s | %s | %s |' % (r['file'], r['openscad_s'], r['strata_s'], r['covered_exact'],
                                                        cell, r['edge_diff'], r['lone'], notes(out, r)))
    differing = sum(1 for r in done if int(r['nonedge']))
    print()
    print('%d files compared, %d with differing non-edge pixels; totals: %d covered pixels (exact), '
          '%d differing non-edge (%d coverage, %d depth, %d normal), %d of %d edge pixels differing, %d lone.'
          % (len(done), differing, tot['covered_exact'], tot['nonedge'], tot['coverage'], tot['depth'],
             tot['normal'], tot['edge_diff'], tot['edge_pixels'], tot['lone']))
    for title, group in (('strata-render refused the .csg', failed),
                         ("strata-render cannot draw OpenSCAD's exact STL", nodraw),
                         ('skipped', skipped)):
        if not group:
            continue
        print()
        print('### %s (%d)' % (title, len(group)))
        print()
        print('| file | why |')
        print('| --- | --- |')
        for r in sorted(group, key=lambda r: r['file']):
            print('| %s | %s |' % (r['file'], r.get('reason', '').replace('|', '\\|')))


def cmd_side(out, n):
    done = [r for r in results(out) if r.get('status') == 'compared' and int(r['nonedge'])]
    # Known causes last: a node strata leaves out, a part OpenSCAD's CGAL dropped.
    known = lambda r: 'not supported' in notes(out, r) or 'OpenSCAD: ERROR' in notes(out, r)
    done.sort(key=lambda r: (known(r), -int(r['nonedge'])))
    for r in done[:int(n)]:
        print(r['dir'])


def cmd_recompare(out, size):
    """compare again every compared model of OUT (after a change of the rules)."""
    import contextlib
    import io
    for r in results(out):
        if r.get('status') != 'compared':
            continue
        d = os.path.join(out, r['dir'])
        buf = io.StringIO()
        with contextlib.redirect_stdout(buf):
            cmd_compare(d, size, r['camera'], r['diag'])
        keep = [l for l in open(os.path.join(d, 'result')) if l.split('=', 1)[0] in
                ('file', 'openscad_s', 'camera', 'diag', 'strata_s', 'status')]
        with open(os.path.join(d, 'result.part'), 'w') as f:
            f.writelines(keep)
            f.write(buf.getvalue().strip().replace(' ', '\n') + '\n')
        os.replace(os.path.join(d, 'result.part'), os.path.join(d, 'result'))


def main(argv):
    cmds = {'camera': (cmd_camera, 1), 'compare': (cmd_compare, 4), 'table': (cmd_table, 1), 'side': (cmd_side, 2),
            'recompare': (cmd_recompare, 2)}
    if len(argv) < 2 or argv[1] not in cmds or len(argv) - 2 != cmds[argv[1]][1]:
        sys.exit(__doc__)
    cmds[argv[1]][0](*argv[2:])


if __name__ == '__main__':
    main(sys.argv)
