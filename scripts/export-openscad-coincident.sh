#!/bin/sh
# Regenerates the OpenSCAD references under tests/data/coincident/: models in
# which faces of different solids coincide. For each NAME.scad there:
#   NAME.csg  OpenSCAD's CSG export (what strata reads);
#   NAME.off  OpenSCAD's exact (CGAL) result, `openscad -o NAME.off`; where the
#             result is empty OpenSCAD refuses to export it, and NAME.empty
#             (one line saying so) is written instead;
#   NAME.png  OpenSCAD's preview (OpenCSG, 256x256) for a human to compare; it
#             shows the z-fighting OpenSCAD's own preview suffers from.
# Then it prints, for each .off, its vertices, faces, volume (divergence
# theorem) and whether it is closed (every edge used by exactly two faces, in
# opposite directions): the figures in tests/data/coincident/README.md.
#
#   scripts/export-openscad-coincident.sh
#
# Needs openscad 2021.01 (Debian 12's `openscad`), xvfb-run (Debian's `xvfb`)
# for the previews, and python3.
set -eu
here=$(cd "$(dirname "$0")/.." && pwd)
dir=$here/tests/data/coincident
command -v openscad >/dev/null 2>&1 || { echo "export-openscad-coincident: openscad is not installed (apt-get install openscad)" >&2; exit 1; }
command -v xvfb-run >/dev/null 2>&1 || { echo "export-openscad-coincident: xvfb-run is not installed (apt-get install xvfb)" >&2; exit 1; }

for scad in "$dir"/*.scad; do
    name=${scad%.scad}
    openscad -o "$name.csg" "$scad" 2>/dev/null
    rm -f "$name.off" "$name.empty"
    if openscad -o "$name.off" "$scad" 2>"$name.log"; then
        echo "wrote $name.csg $name.off"
    elif grep -q "Current top level object is empty" "$name.log"; then
        rm -f "$name.off"
        echo "OpenSCAD 2021.01's exact result is empty (\"Current top level object is empty.\"), so it writes no .off." >"$name.empty"
        echo "wrote $name.csg $name.empty"
    else
        cat "$name.log" >&2
        rm -f "$name.log"
        echo "export-openscad-coincident: openscad failed on $scad" >&2
        exit 1
    fi
    rm -f "$name.log"
    xvfb-run -a -s "-screen 0 1280x1024x24" openscad --preview -o "$name.png" --imgsize=256,256 --viewall --autocenter "$scad" >/dev/null 2>&1 \
        || { echo "export-openscad-coincident: openscad --preview failed on $scad" >&2; exit 1; }
    echo "wrote $name.png"
done

python3 - "$dir" <<'PY'
import collections, glob, os, sys

def read_off(path):
    tokens = []
    for line in open(path):
        line = line.split('#', 1)[0].split()
        tokens.extend(line)
    assert tokens[0] == 'OFF', path
    nv, nf = int(tokens[1]), int(tokens[2])
    pos = 4
    verts = []
    for _ in range(nv):
        verts.append(tuple(float(t) for t in tokens[pos:pos + 3]))
        pos += 3
    faces = []
    for _ in range(nf):
        n = int(tokens[pos])
        faces.append([int(t) for t in tokens[pos + 1:pos + 1 + n]])
        pos += 1 + n
    return verts, faces

def volume(verts, faces):
    total = 0.0
    for f in faces:
        a = verts[f[0]]
        for i in range(1, len(f) - 1):
            b, c = verts[f[i]], verts[f[i + 1]]
            total += (a[0] * (b[1] * c[2] - b[2] * c[1])
                      - a[1] * (b[0] * c[2] - b[2] * c[0])
                      + a[2] * (b[0] * c[1] - b[1] * c[0]))
    return total / 6.0

def closed(faces):
    directed = collections.Counter()
    for f in faces:
        for i in range(len(f)):
            directed[(f[i], f[(i + 1) % len(f)])] += 1
    return all(n == 1 and directed.get((b, a), 0) == 1 for (a, b), n in directed.items())

print("%-28s %6s %6s %16s %s" % ("name", "verts", "faces", "volume", "closed"))
for scad in sorted(glob.glob(os.path.join(sys.argv[1], "*.scad"))):
    name = scad[:-5]
    base = os.path.basename(name)
    if os.path.exists(name + ".empty"):
        print("%-28s %6s %6s %16s %s" % (base, "-", "-", "empty", "-"))
        continue
    verts, faces = read_off(name + ".off")
    print("%-28s %6d %6d %16.6g %s" % (base, len(verts), len(faces), volume(verts, faces), "yes" if closed(faces) else "NO"))
PY
