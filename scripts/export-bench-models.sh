#!/bin/sh
# Regenerates tests/bench/models/, the real-model set of the benchmarks, from
# OpenSCAD's shipped examples (CC0-1.0): every example that draws something
# is exported with `openscad -o NAME.csg`, named after its folder and file
# (Old/example006.scad -> Old_example006.csg), and the files the exports
# import (STL, DXF, PNG, DAT) are copied beside them, as the .csg expects.
#
#   scripts/export-bench-models.sh [EXAMPLES_DIR]     (default /usr/share/openscad/examples)
#
# Needs openscad 2021.01 (Debian 12's `openscad`). Left out: Functions/echo
# (it only prints) and Old/example023 (its shapes read dimensions from a DXF
# file it never imports: OpenSCAD draws nothing either). The import() lines
# carry the imported file's mtime as `timestamp`; nothing reads it.
set -eu

src=${1:-/usr/share/openscad/examples}
here=$(cd "$(dirname "$0")/.." && pwd)
dst=$here/tests/bench/models

command -v openscad >/dev/null 2>&1 || { echo "export-bench-models: openscad is not installed (apt-get install openscad)" >&2; exit 1; }
[ -d "$src" ] || { echo "export-bench-models: $src: no such folder" >&2; exit 1; }

mkdir -p "$dst"
for scad in "$src"/*/*.scad; do
    folder=$(basename "$(dirname "$scad")")
    name=$(basename "$scad" .scad)
    case "$folder/$name" in
        Functions/echo|Old/example023) continue ;;
    esac
    out=$dst/${folder}_$name.csg
    # openscad writes its ECHO and WARNING lines on stderr; keep them out of the way.
    if ! (cd "$(dirname "$scad")" && openscad -o "$out" "$scad" 2>"$out.log"); then
        cat "$out.log" >&2
        rm -f "$out.log"
        echo "export-bench-models: openscad failed on $scad" >&2
        exit 1
    fi
    rm -f "$out.log"
    # The files it imports, relative to the .scad's folder, beside the .csg.
    grep -o 'file = "[^"]*"' "$out" | sed 's/^file = "//; s/"$//' | sort -u | while read -r imported; do
        cp "$(dirname "$scad")/$imported" "$dst/$imported"
    done
    echo "wrote $out"
done
