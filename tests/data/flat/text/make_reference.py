#!/usr/bin/env python3
"""Regenerates the text() reference outlines with OpenSCAD 2021.01.

For each case, text(...) is scaled by 65536 (one unit of OpenSCAD's Clipper
grid becomes 1) and moved by a whole shift so that every coordinate is an
integer below 10^6 in magnitude: DXF export writes six significant digits,
which then hold every grid point exactly. Run from this folder:
    python3 make_reference.py
It writes <case>.scad and <case>.dxf (and <case>.csg, the node as OpenSCAD
exports it). The shift of each case is in cases.txt.
"""
import os
import subprocess
import sys

CASES = [
    ("o", 'text("o");'),
    ("hg_center", 'text("Hg", size=7, spacing=1.3, halign="center", valign="center");'),
    ("serif_bold", 'text("Rag", font="Liberation Serif:style=Bold");'),
    ("ttb", 'text("ABC", size=5, direction="ttb");'),
    ("btt_center", 'text("Hi", size=6, direction="btt", halign="center", valign="center");'),
    ("kerning", 'text("AVAT", size=8);'),
    ("fn40", 'text("S", size=4, $fn=40);'),
    ("fa_fs", 'text("e", size=20, $fa=5, $fs=0.5);'),
    ("accents", 'text("\u00c5\u00c7\u00f8\u00e9", size=6);'),
    ("mono_right_bottom", 'text("Mono#1", size=4, font="Liberation Mono", halign="right", valign="bottom");'),
    ("space", 'text("a b");'),
    ("hebrew_rtl", 'text("\u05e9\u05dc\u05d5\u05dd", size=6, direction="rtl", language="he", script="Hebr");'),
    ("fallback", 'text("Fb", font="NoSuchFont Foo");'),
    ("bold_italic_top", 'text("fig", size=9, font="Liberation Sans:style=Bold Italic", valign="top", halign="right");'),
    ("overlap", 'text("OOO", size=6, spacing=0.5);'),
    # fonts/StrataCubicTest.otf (CFF: cubic Beziers), found through OPENSCAD_FONT_PATH.
    ("cubic", 'text("ODS", size=6, font="Strata Cubic Test");'),
    ("cubic_fn48", 'text("SO", size=5, font="Strata Cubic Test", $fn=48);'),
    ("cubic_fn20", 'text("DO", size=5, font="Strata Cubic Test", $fn=20, halign="center");'),
]

ENV = dict(os.environ, OPENSCAD_FONT_PATH=os.path.abspath("fonts"))

LIMIT = 999999


def openscad(src, out):
    with open("_tmp.scad", "w", encoding="utf-8") as f:
        f.write(src + "\n")
    subprocess.run(["openscad", "-o", out, "_tmp.scad"], check=True, capture_output=True, env=ENV)


def dxf_points(path):
    lines = open(path).read().split("\n")
    pts = []
    for i in range(len(lines) - 1):
        if lines[i].strip() in ("10", "20", "11", "21"):
            pts.append(float(lines[i + 1]))
    return pts[0::4], pts[1::4]


def main():
    table = []
    for name, call in CASES:
        openscad(call, "_tmp.dxf")
        xs, ys = dxf_points("_tmp.dxf")
        tx = -round((min(xs) + max(xs)) / 2 * 65536)
        ty = -round((min(ys) + max(ys)) / 2 * 65536)
        for lo, hi, t in ((min(xs), max(xs), tx), (min(ys), max(ys), ty)):
            if max(abs(lo * 65536 + t), abs(hi * 65536 + t)) > LIMIT - 100:
                sys.exit(f"{name}: too large for exact DXF coordinates")
        scad = (f"// {call}\n// scaled by 2^16 and shifted by [{tx}, {ty}]: see README.md\n"
                f"multmatrix([[65536, 0, 0, {tx}], [0, 65536, 0, {ty}], [0, 0, 1, 0], [0, 0, 0, 1]])\n"
                f"    {call}\n")
        with open(f"{name}.scad", "w", encoding="utf-8") as f:
            f.write(scad)
        subprocess.run(["openscad", "-o", f"{name}.dxf", f"{name}.scad"], check=True, capture_output=True, env=ENV)
        subprocess.run(["openscad", "-o", f"{name}.csg", f"{name}.scad"], check=True, capture_output=True, env=ENV)
        xs, ys = dxf_points(f"{name}.dxf")
        for v in xs + ys:
            if v != int(v) or abs(v) > LIMIT:
                sys.exit(f"{name}: coordinate {v} is not exact")
        table.append(f"{name} {tx} {ty} {len(xs)}")
        print(table[-1])
    with open("cases.txt", "w") as f:
        f.write("# case shift_x shift_y vertices (shift in grid units of 1/65536)\n")
        f.write("\n".join(table) + "\n")
    for tmp in ("_tmp.scad", "_tmp.dxf"):
        if os.path.exists(tmp):
            os.remove(tmp)


if __name__ == "__main__":
    main()
