#!/bin/sh
# Regenerates tests/data/openscad/ from OpenSCAD's shipped examples (CC0-1.0):
# each chosen example is exported with `openscad -o NAME.csg`, named after its
# folder and file (Basics/CSG.scad -> Basics_CSG.csg), and the STL files that the
# exports import are copied beside them (import() paths are relative to the .csg).
#
#   scripts/export-openscad-examples.sh [EXAMPLES_DIR]     (default /usr/share/openscad/examples)
#
# Needs openscad 2021.01 (Debian 12's `openscad`). After regenerating, run
# tests/data/openscad/facts.py and check that the numbers pasted into
# tests/scene/ExamplesTest.cpp still hold. The import() lines carry the STL's
# mtime as `timestamp`, so they change from machine to machine; nothing reads it.
set -eu

src=${1:-/usr/share/openscad/examples}
here=$(cd "$(dirname "$0")/.." && pwd)
dst=$here/tests/data/openscad

command -v openscad >/dev/null 2>&1 || { echo "export-openscad-examples: openscad is not installed (apt-get install openscad)" >&2; exit 1; }
[ -d "$src" ] || { echo "export-openscad-examples: $src: no such folder" >&2; exit 1; }

# Only 3D CSG (cube, sphere, cylinder, polyhedron, import, transforms, colours, render):
supported="Basics/CSG Basics/CSG-modules Basics/logo Old/example002 Old/example011 Old/example012
           Old/example014 Old/example016 Old/example024"
# With nodes strata leaves out (linear_extrude, text, rotate_extrude, hull, 2D shapes):
unsupported="Basics/LetterBlock Basics/rotate_extrude Old/example006 Parametric/candleStand"

mkdir -p "$dst"
for example in $supported $unsupported; do
    out=$dst/$(echo "$example" | tr / _).csg
    # openscad writes its ECHO and WARNING lines on stderr; keep them out of the way.
    if ! openscad -o "$out" "$src/$example.scad" 2>"$out.log"; then
        cat "$out.log" >&2
        rm -f "$out.log"
        echo "export-openscad-examples: openscad failed on $example.scad" >&2
        exit 1
    fi
    rm -f "$out.log"
    echo "wrote $out"
done
cp "$src/Old/example012.stl" "$src/Old/example016.stl" "$dst/"
echo "copied example012.stl example016.stl"
