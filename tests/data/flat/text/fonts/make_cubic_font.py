#!/usr/bin/python3
"""Writes StrataCubicTest.otf: a tiny CFF (PostScript-outline) font whose
curves are cubic Beziers, for text()'s cubic path. Needs fontTools
(Debian: python3-fonttools). Glyphs: 'O' (an ellipse with a counter),
'D' (lines and cubics), 'S' (an open S-curve stroke), space. Family
"Strata Cubic Test", style Regular. Drawn here; no outline comes from another font.
"""
from fontTools.fontBuilder import FontBuilder
from fontTools.pens.t2CharStringPen import T2CharStringPen

UPEM = 1000
K = 0.5523  # cubic approximation of a quarter circle


def ellipse(pen, cx, cy, rx, ry, clockwise):
    kx, ky = rx * K, ry * K
    pts = [(cx + rx, cy), (cx, cy + ry), (cx - rx, cy), (cx, cy - ry)]
    ctrl = [((cx + rx, cy + ky), (cx + kx, cy + ry)),
            ((cx - kx, cy + ry), (cx - rx, cy + ky)),
            ((cx - rx, cy - ky), (cx - kx, cy - ry)),
            ((cx + kx, cy - ry), (cx + rx, cy - ky))]
    if not clockwise:
        pen.moveTo(pts[0])
        for i in range(4):
            pen.curveTo(ctrl[i][0], ctrl[i][1], pts[(i + 1) % 4])
    else:
        pen.moveTo(pts[0])
        for i in reversed(range(4)):
            pen.curveTo(ctrl[i][1], ctrl[i][0], pts[i])
    pen.closePath()


def draw_O(pen):
    ellipse(pen, 330, 350, 290, 360, clockwise=False)
    ellipse(pen, 330, 350, 180, 260, clockwise=True)


def draw_D(pen):
    pen.moveTo((80, 0))
    pen.lineTo((300, 0))
    pen.curveTo((520, 0), (640, 150), (640, 350))
    pen.curveTo((640, 560), (520, 700), (300, 700))
    pen.lineTo((80, 700))
    pen.closePath()
    pen.moveTo((190, 100))
    pen.lineTo((190, 600))
    pen.lineTo((290, 600))
    pen.curveTo((450, 600), (525, 500), (525, 350))
    pen.curveTo((525, 200), (450, 100), (290, 100))
    pen.closePath()


def draw_S(pen):
    pen.moveTo((60, 120))
    pen.curveTo((120, 0), (420, -40), (520, 120))
    pen.curveTo((600, 260), (420, 330), (300, 370))
    pen.curveTo((180, 410), (90, 470), (170, 590))
    pen.curveTo((250, 700), (450, 680), (520, 600))
    pen.lineTo((440, 540))
    pen.curveTo((390, 600), (290, 610), (250, 550))
    pen.curveTo((200, 480), (300, 440), (390, 410))
    pen.curveTo((560, 350), (700, 250), (610, 90))
    pen.curveTo((500, -110), (100, -60), (-20, 80))
    pen.closePath()


def main():
    order = [".notdef", "space", "O", "D", "S"]
    fb = FontBuilder(UPEM, isTTF=False)
    fb.setupGlyphOrder(order)
    fb.setupCharacterMap({0x20: "space", ord("O"): "O", ord("D"): "D", ord("S"): "S"})
    charstrings = {}
    widths = {".notdef": 500, "space": 300, "O": 660, "D": 700, "S": 640}
    drawers = {"O": draw_O, "D": draw_D, "S": draw_S}
    for name in order:
        pen = T2CharStringPen(widths[name], None)
        if name in drawers:
            drawers[name](pen)
        charstrings[name] = pen.getCharString()
    fb.setupCFF("StrataCubicTest-Regular", {"FullName": "Strata Cubic Test Regular"}, charstrings, {})
    fb.setupHorizontalMetrics({n: (widths[n], 0) for n in order})
    fb.setupHorizontalHeader(ascent=800, descent=-200)
    fb.setupNameTable({"familyName": "Strata Cubic Test", "styleName": "Regular"})
    fb.setupOS2(sTypoAscender=800, sTypoDescender=-200, usWinAscent=800, usWinDescent=200)
    fb.setupPost()
    fb.save("StrataCubicTest.otf")


if __name__ == "__main__":
    main()
