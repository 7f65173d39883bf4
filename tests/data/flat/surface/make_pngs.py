#!/usr/bin/env python3
"""Writes the small PNG images of this folder (no imaging library needed)."""
import struct, zlib

def chunk(kind, data):
    return struct.pack('>I', len(data)) + kind + data + struct.pack('>I', zlib.crc32(kind + data) & 0xffffffff)

def pack_row(samples, depth):
    if depth == 8:
        return bytes(samples)
    if depth == 16:
        return b''.join(struct.pack('>H', s) for s in samples)
    out, acc, bits = bytearray(), 0, 0
    for s in samples:
        acc = (acc << depth) | s
        bits += depth
        if bits == 8:
            out.append(acc); acc, bits = 0, 0
    if bits:
        out.append(acc << (8 - bits))
    return bytes(out)

def png(path, width, height, color_type, depth, pixel, palette=None, interlace=False, extra=()):
    """pixel(x, y) -> tuple of samples for one pixel; extra: (kind, data) chunks after PLTE."""
    def raw(xs, ys):
        data = b''
        for y in ys:
            samples = []
            for x in xs:
                samples.extend(pixel(x, y))
            data += b'\0' + pack_row(samples, depth)
        return data
    if interlace:
        passes = [(0, 0, 8, 8), (4, 0, 8, 8), (0, 4, 4, 8), (2, 0, 4, 4), (0, 2, 2, 4), (1, 0, 2, 2), (0, 1, 1, 2)]
        data = b''
        for x0, y0, dx, dy in passes:
            xs, ys = list(range(x0, width, dx)), list(range(y0, height, dy))
            if xs and ys:
                data += raw(xs, ys)
    else:
        data = raw(range(width), range(height))
    out = b'\x89PNG\r\n\x1a\n'
    out += chunk(b'IHDR', struct.pack('>IIBBBBB', width, height, depth, color_type, 0, 0, 1 if interlace else 0))
    if palette:
        out += chunk(b'PLTE', b''.join(bytes(c) for c in palette))
    for kind, body in extra:
        out += chunk(kind, body)
    out += chunk(b'IDAT', zlib.compress(data, 9))
    out += chunk(b'IEND', b'')
    open(path, 'wb').write(out)

# 8-bit RGB, 5 x 4, colours that weigh the channels differently.
rgb = [[(255, 0, 0), (0, 255, 0), (0, 0, 255), (255, 255, 255), (0, 0, 0)],
       [(12, 200, 7), (100, 100, 100), (250, 128, 3), (1, 2, 3), (77, 0, 255)],
       [(30, 60, 90), (255, 255, 0), (0, 255, 255), (200, 10, 150), (9, 99, 199)],
       [(128, 128, 128), (64, 32, 16), (3, 250, 60), (180, 180, 20), (40, 200, 120)]]
png('rgb.png', 5, 4, 2, 8, lambda x, y: rgb[y][x])
# 16-bit grey, 3 x 3: the low byte must not count.
g16 = [[0x0000, 0x80ff, 0xffff], [0x1234, 0x00ff, 0xfe01], [0x7f80, 0x4000, 0xc0de]]
png('grey16.png', 3, 3, 0, 16, lambda x, y: (g16[y][x],))
# 2-bit palette, 4 x 3.
pal = [(10, 20, 30), (200, 100, 50), (0, 255, 128), (255, 255, 255)]
idx = [[0, 1, 2, 3], [3, 2, 1, 0], [1, 1, 3, 0]]
png('palette.png', 4, 3, 3, 2, lambda x, y: (idx[y][x],), palette=pal)
# 4-bit grey, interlaced (Adam7), with a grey+alpha twin: 6 x 5.
png('grey4_interlaced.png', 6, 5, 0, 4, lambda x, y: ((x * 3 + y * 5) % 16,), interlace=True)
png('grey_alpha.png', 6, 5, 4, 8, lambda x, y: ((x * 40 + y * 17) % 256, (x * 91) % 256))
# 8-bit palette, 5 x 3, and its twin with a transparency (tRNS) and
# ancillary chunks a heightmap does not use (gamma, text, a time): the twin
# must give the same heights (OpenSCAD 2021.01 gives both the same mesh).
pal8 = [(10, 20, 30), (200, 100, 50), (0, 255, 128), (255, 255, 255), (90, 0, 180)]
idx8 = [[0, 1, 2, 3, 4], [4, 3, 2, 1, 0], [2, 2, 4, 0, 1]]
png('palette8.png', 5, 3, 3, 8, lambda x, y: (idx8[y][x],), palette=pal8)
png('palette8_chunks.png', 5, 3, 3, 8, lambda x, y: (idx8[y][x],), palette=pal8,
    extra=[(b'tRNS', bytes([0, 128, 255, 40])), (b'gAMA', struct.pack('>I', 45455)),
           (b'tEXt', b'Comment\0a heightmap'), (b'tIME', struct.pack('>HBBBBB', 2026, 11, 29, 12, 0, 0))])
