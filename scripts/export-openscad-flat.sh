#!/bin/sh
# Regenerates the OpenSCAD references under tests/data/flat/: for each NAME.scad
# in the folders below, OpenSCAD's CSG export (NAME.csg, what strata reads) and
# its mesh of the same model (NAME.off: `openscad -o NAME.off`, 3D results;
# NAME.stl in polyhedron/, since OpenSCAD's OFF keeps a polyhedron's faces as
# they were given and only its STL shows how it splits them) or outline
# (NAME.svg, 2D results). tests/model/FlatExportsTest.cpp compares
# strata's meshes with them.
#
#   scripts/export-openscad-flat.sh
#
# Needs openscad 2021.01 (Debian 12's `openscad`).
set -eu
here=$(cd "$(dirname "$0")/.." && pwd)
command -v openscad >/dev/null 2>&1 || { echo "export-openscad-flat: openscad is not installed (apt-get install openscad)" >&2; exit 1; }

for dir in "$here"/tests/data/flat/extrude "$here"/tests/data/flat/hull "$here"/tests/data/flat/resize "$here"/tests/data/flat/projection "$here"/tests/data/flat/polyhedron; do
    for scad in "$dir"/*.scad; do
        name=${scad%.scad}
        openscad -o "$name.csg" "$scad" 2>/dev/null
        mesh=$name.off
        case $dir in */polyhedron) mesh=$name.stl ;; esac
        if ! openscad -o "$mesh" "$scad" 2>"$name.log"; then
            cat "$name.log" >&2
            rm -f "$name.log"
            echo "export-openscad-flat: openscad failed on $scad" >&2
            exit 1
        fi
        rm -f "$name.log"
        echo "wrote $name.csg $mesh"
    done
done
