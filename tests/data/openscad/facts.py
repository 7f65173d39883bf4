#!/usr/bin/env python3
"""Works out, independently of strata, what tests/scene/ExamplesTest.cpp expects
of each checked-in OpenSCAD export, and prints it as C++ initialisers to paste.

For each NAME.csg here:
  leaves       primitive lines (cube, sphere, cylinder, polyhedron, import,
               surface, and each extrusion or hull with the subtree it holds) that
               are not inside a node strata leaves out; `background` counts those
               under a '%' modifier.
  unsupported  the outermost nodes strata leaves out, by name: how many, and the
               line of the first one (nodes nested inside them are not counted).
  leafBounds   bounds of the union of all kept leaves, as OpenSCAD itself computes
               them: the file with unsupported subtrees cut out and every
               difference/intersection turned into union, exported with
               `openscad -o x.stl` (exact CGAL evaluation), bbox of the STL's vertices.
               This is what geometry::Model::bounds must be, when strata's
               tessellation matches OpenSCAD's.
  resultBounds bbox of OpenSCAD's exact result of the file with unsupported
               subtrees cut out (otherwise unchanged): the model's bounds must
               contain it. For a plain union it equals leafBounds.

Run from anywhere: python3 tests/data/openscad/facts.py [NAME.csg ...]  (needs
openscad 2021.01; all exports here when no name is given; about 3 minutes).
It reads only the .csg text and OpenSCAD's output; it calls no strata code.
"""
import os
import re
import shutil
import struct
import subprocess
import sys
import tempfile

HERE = os.path.dirname(os.path.abspath(__file__))
SUPPORTED_OPS = {"group", "union", "difference", "intersection", "multmatrix", "color", "render"}
PRIMITIVES = {"cube", "sphere", "cylinder", "polyhedron", "import", "linear_extrude", "rotate_extrude", "surface",
              "hull", "minkowski"}
# Nodes whose whole subtree makes one leaf: the extrusions, and hull (and a
# minkowski of convex solids, one leaf per choice of parts; none of the
# examples here has one).
EXTRUSIONS = {"linear_extrude", "rotate_extrude", "hull", "minkowski"}
# Inside them: the 2D nodes that make a shape, and solids for a hull.
FLAT_NODES = SUPPORTED_OPS | PRIMITIVES | {"square", "circle", "polygon", "text", "offset", "import"}
MESH_EXTENSIONS = (".stl", ".off", ".obj", ".ply")
LINE = re.compile(r"^([%#!*]?)(\t*)([a-z_][a-z_0-9]*)\((.*)\)\s*([{;])\s*$")


def analyse(path):
    """One pass over the export's lines (OpenSCAD writes one node per line)."""
    lines = open(path).read().split("\n")
    stack = []  # per open '{': (name, cut, background, inside an extrusion)
    leaves = background = 0
    unsupported = {}  # name -> [count, first line]
    kept, leaves_only = [], []
    for number, text in enumerate(lines, start=1):
        stripped = text.strip()
        cut = any(s[1] for s in stack)
        in_background = any(s[2] for s in stack)
        in_extrusion = any(s[3] for s in stack)
        if stripped == "}":
            name, was_cut, _, _ = stack.pop()
            if not cut:  # the closing brace of a kept node (a cut node's own brace has was_cut)
                kept.append(text)
                leaves_only.append(text)
            continue
        if stripped == "":
            kept.append(text)
            leaves_only.append(text)
            continue
        m = LINE.match(text)
        if not m:
            sys.exit(f"{path}:{number}: cannot read line: {text!r}")
        modifier, _, name, args, opener = m.groups()
        is_mesh_import = name == "import" and re.search(r'file = "[^"]*(' + "|".join(
            re.escape(e) for e in MESH_EXTENSIONS) + r')"', args, re.I)
        if in_extrusion:
            supported = name in FLAT_NODES
        else:
            supported = name in SUPPORTED_OPS or (name in PRIMITIVES and (name != "import" or is_mesh_import))
        this_cut = cut or not supported
        if not cut and not supported:
            entry = unsupported.setdefault(name, [0, number])
            entry[0] += 1
        if not this_cut:
            if name in PRIMITIVES and not in_extrusion:
                leaves += 1
                if in_background or modifier == "%":
                    background += 1
            kept.append(text)
            if name in ("difference", "intersection") and not in_extrusion:
                text = text.replace(name + "(", "union(", 1)
            leaves_only.append(text)
        if opener == "{":
            stack.append((name, this_cut, in_background or modifier == "%", in_extrusion or name in EXTRUSIONS))
    if stack:
        sys.exit(f"{path}: unbalanced braces")
    return leaves, background, unsupported, "\n".join(kept), "\n".join(leaves_only)


def stl_bounds(path):
    data = open(path, "rb").read()
    points = []
    if data[:5] == b"solid" and b"facet" in data[:300]:
        for m in re.finditer(rb"vertex\s+(\S+)\s+(\S+)\s+(\S+)", data):
            points.append(tuple(float(v) for v in m.groups()))
    else:
        count = struct.unpack("<I", data[80:84])[0]
        for i in range(count):
            f = struct.unpack("<12f", data[84 + 50 * i: 84 + 50 * i + 48])
            points += [f[3:6], f[6:9], f[9:12]]
    if not points:
        return None
    return [min(p[k] for p in points) for k in range(3)], [max(p[k] for p in points) for k in range(3)]


def openscad_bounds(text, workdir, stem):
    scad = os.path.join(workdir, stem + ".csg")
    stl = os.path.join(workdir, stem + ".stl")
    with open(scad, "w") as f:
        f.write(text)
    run = subprocess.run(["openscad", "-o", stl, scad], capture_output=True, text=True)
    if run.returncode != 0 or not os.path.exists(stl):
        if "empty" in run.stderr.lower():
            return None
        sys.exit(f"openscad failed on {stem}:\n{run.stderr}")
    return stl_bounds(stl)


def cpp_bounds(b):
    if b is None:
        return "std::nullopt"
    lo, hi = b
    return "Box{{%s}, {%s}}" % (", ".join("%.9g" % v for v in lo), ", ".join("%.9g" % v for v in hi))


def main():
    names = sys.argv[1:] or sorted(f for f in os.listdir(HERE) if f.endswith(".csg"))
    work = tempfile.mkdtemp(prefix="strata-facts-")
    try:
        for f in os.listdir(HERE):
            if f.lower().endswith(MESH_EXTENSIONS):
                shutil.copy(os.path.join(HERE, f), work)
        for name in names:
            leaves, background, unsupported, kept, leaves_only = analyse(os.path.join(HERE, name))
            stem = name[:-4]
            leaf_box = openscad_bounds(leaves_only, work, stem + ".leaves")
            result_box = openscad_bounds(kept, work, stem + ".result")
            uns = ", ".join('{"%s", %d, %d}' % (n, c, l) for n, (c, l) in sorted(unsupported.items()))
            print('    {"%s", %d, %d, {%s},\n     %s,\n     %s},' % (
                name, leaves, background, uns, cpp_bounds(leaf_box), cpp_bounds(result_box)))
    finally:
        shutil.rmtree(work)


if __name__ == "__main__":
    main()
