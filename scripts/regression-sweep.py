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
  regression-sweep.py side OUT N IMAGES
      the N files with the most differing non-edge pixels, listed for the
      shell to put their strata | exact | diff strips in IMAGES.

A pixel's verdict, first that fails: coverage (hit in one image only), depth
(view depth apart by more than 1e-4 of the exact box's diagonal), normal
(more than 1 degree apart). The exact image alone says which pixels are edge
pixels: one whose 8 neighbours are not all on its face (a neighbour missed
where it hits or the other way round, a normal more than 1 degree off, or a
point off its tangent plane by more than the depth tolerance); the image's
border counts as a miss. A lone pixel: covered, its 8 neighbours covered, and
its normal more than 1 degree from each of theirs, in strata's image but not
in the exact one.

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
    if data[:5] == b'solid' and b'facet' in data[:2000]:
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

    # Edge pixels of the exact image: not all 8 neighbours on the pixel's face.
    edge = np.zeros((h, w), bool)
    for (dy, dx, hq), (_, _, nq), (_, _, pq) in zip(neighbours(he, False), neighbours(ne, 0.0), neighbours(pe, 0.0)):
        off = np.abs(np.einsum('ijk,ijk->ij', pq - pe, ne))
        same = (hq == he) & (~he | ((np.einsum('ijk,ijk->ij', nq, ne) >= cos_tol) & (off <= tol)))
        edge |= ~same

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

    ne_ = ~edge
    fig = dict(covered_exact=int(he.sum()), covered_strata=int(hs.sum()),
               edge_pixels=int((edge & (hs | he)).sum()),
               coverage=int((cov & ne_).sum()), depth=int((dep & ne_).sum()), normal=int((nor & ne_).sum()),
               edge_diff=int((bad & edge).sum()), lone=int(lone_px.sum()))
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
    img[bad & edge] = (230, 200, 0, 255)
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


def cmd_table(out):
    rows = results(out)
    done = [r for r in rows if r.get('status') == 'compared']
    skipped = [r for r in rows if r.get('status') == 'skipped']
    failed = [r for r in rows if r.get('status') not in ('compared', 'skipped')]
    print('| file | OpenSCAD s | strata s | covered | differing non-edge (coverage / depth / normal) | edge differing | lone |')
    print('| --- | ---: | ---: | ---: | --- | ---: | ---: |')
    tot = dict(nonedge=0, coverage=0, depth=0, normal=0, edge_diff=0, lone=0, covered_exact=0, edge_pixels=0)
    for r in sorted(done, key=lambda r: r['file']):
        for k in tot:
            tot[k] += int(r[k])
        ne = int(r['nonedge'])
        cell = '**%d** (%s / %s / %s)' % (ne, r['coverage'], r['depth'], r['normal']) if ne else '0'
        print('| %s | %s | %s | %s | %s | %s | %s |' % (r['file'], r['openscad_s'], r['strata_s'], r['covered_exact'],
                                                   cell, r['edge_diff'], r['lone']))
    differing = sum(1 for r in done if int(r['nonedge']))
    print()
    print('%d files compared, %d with differing non-edge pixels; totals: %d covered pixels (exact), '
          '%d differing non-edge (%d coverage, %d depth, %d normal), %d of %d edge pixels differing, %d lone.'
          % (len(done), differing, tot['covered_exact'], tot['nonedge'], tot['coverage'], tot['depth'],
             tot['normal'], tot['edge_diff'], tot['edge_pixels'], tot['lone']))
    if failed:
        print()
        print('### strata failed (%d)' % len(failed))
        print()
        print('| file | what |')
        print('| --- | --- |')
        for r in sorted(failed, key=lambda r: r['file']):
            print('| %s | %s: %s |' % (r['file'], r.get('status'), r.get('reason', '').replace('|', '\\|')))
    if skipped:
        print()
        print('### skipped (%d)' % len(skipped))
        print()
        print('| file | why |')
        print('| --- | --- |')
        for r in sorted(skipped, key=lambda r: r['file']):
            print('| %s | %s |' % (r['file'], r.get('reason', '').replace('|', '\\|')))


def cmd_side(out, n):
    done = [r for r in results(out) if r.get('status') == 'compared' and int(r['nonedge'])]
    done.sort(key=lambda r: -int(r['nonedge']))
    for r in done[:int(n)]:
        print(r['dir'])


def main(argv):
    cmds = {'camera': (cmd_camera, 1), 'compare': (cmd_compare, 4), 'table': (cmd_table, 1), 'side': (cmd_side, 2)}
    if len(argv) < 2 or argv[1] not in cmds or len(argv) - 2 != cmds[argv[1]][1]:
        sys.exit(__doc__)
    cmds[argv[1]][0](*argv[2:])


if __name__ == '__main__':
    main(sys.argv)
