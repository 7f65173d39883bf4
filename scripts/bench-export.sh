#!/usr/bin/env bash
# Exact export as a user meets it: whole processes, `strata-render FILE
# --export x.stl` against OpenSCAD's own CGAL export (`openscad -o x.stl
# FILE`), interleaved, RUNS times each; prints a Markdown table of the
# medians (wall seconds, peak resident memory), their ratio, the two
# results' volumes (from the binary and ASCII STL files), and each file's
# triangles and audit (strata_mesh_audit: "clean", or the degenerate
# triangles, open or non-manifold edges after welding, and crossing pairs).
#
#   scripts/bench-export.sh [--runs N] FILE.csg...
#
# Needs a Release build (build/, with tests/bench/strata_mesh_audit),
# openscad 2021.01, python3 and GNU time.
set -euo pipefail
cd "$(dirname "$0")/.."

runs=3
files=()
while (($#)); do
  case $1 in
    --runs) runs=$2; shift 2 ;;
    *) files+=("$1"); shift ;;
  esac
done
((${#files[@]})) || { echo "usage: scripts/bench-export.sh [--runs N] FILE.csg..." >&2; exit 2; }
for tool in openscad python3 /usr/bin/time; do
  command -v "$tool" >/dev/null || { echo "bench-export: $tool is not installed" >&2; exit 1; }
done
render=build/apps/strata-render/strata-render
audit=build/tests/bench/strata_mesh_audit
for exe in "$render" "$audit"; do
  [[ -x $exe ]] || { echo "bench-export: build $exe first (scripts/build.sh release)" >&2; exit 1; }
done

work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT

measure() {
  /usr/bin/time -f "%e %M" -o "$work/t" "$@" >/dev/null 2>&1 || { echo "fail fail"; return; }
  cat "$work/t"
}
median() { sort -g | awk '{v[NR] = $1} END {print (NR % 2) ? v[(NR + 1) / 2] : (v[NR / 2] + v[NR / 2 + 1]) / 2}'; }
# The volume enclosed by an STL file, binary or ASCII, by the divergence theorem.
volume() {
  python3 - "$1" <<'PY'
import re, struct, sys
data = open(sys.argv[1], 'rb').read()
tris = []
if data[:5] == b'solid' and b'facet' in data[:1000]:
    pts = [tuple(map(float, m)) for m in re.findall(rb'vertex\s+(\S+)\s+(\S+)\s+(\S+)', data)]
    tris = [pts[i:i + 3] for i in range(0, len(pts), 3)]
else:
    n = struct.unpack('<I', data[80:84])[0]
    for i in range(n):
        f = struct.unpack('<12f', data[84 + 50 * i:84 + 50 * i + 48])
        tris.append((f[3:6], f[6:9], f[9:12]))
v = sum(a[0] * (b[1] * c[2] - b[2] * c[1]) - a[1] * (b[0] * c[2] - b[2] * c[0]) + a[2] * (b[0] * c[1] - b[1] * c[0])
        for a, b, c in tris) / 6
print('%.6g' % v)
PY
}

# The audit of one STL: "triangles | clean" or "triangles | what is wrong".
audited() {
  [[ -f $1 ]] || { echo "- | -"; return; }
  { "$audit" "$1" || true; } | python3 -c '
import json, sys
a = json.loads(sys.stdin.read())
faults = [(a["degenerate"], "degenerate"), (a["boundary_edges"], "open edges"),
          (a["nonmanifold_edges"], "non-manifold edges"), (a["misoriented_edges"], "misoriented edges"),
          (a["self_intersections"], "crossing pairs")]
said = ", ".join("%d %s" % (n, what) for n, what in faults if n)
print("%d | %s" % (a["triangles"], said or "clean"))'
}

echo "| model | strata s | OpenSCAD s | strata / OpenSCAD | strata MiB | OpenSCAD MiB | strata volume | OpenSCAD volume | strata triangles | strata audit | OpenSCAD triangles | OpenSCAD audit |"
echo "| --- | ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: | --- | ---: | --- |"
for f in "${files[@]}"; do
  : >"$work/s"
  : >"$work/o"
  for ((i = 0; i < runs; i++)); do
    measure "$render" "$f" --export "$work/s.stl" >>"$work/s"
    measure openscad -o "$work/o.stl" "$f" >>"$work/o"
  done
  st=$(cut -d' ' -f1 "$work/s" | median)
  ot=$(cut -d' ' -f1 "$work/o" | median)
  sm=$(cut -d' ' -f2 "$work/s" | median)
  om=$(cut -d' ' -f2 "$work/o" | median)
  sv=$( [[ -f $work/s.stl ]] && volume "$work/s.stl" || echo "-")
  ov=$( [[ -f $work/o.stl ]] && volume "$work/o.stl" || echo "-")
  sa=$(audited "$work/s.stl")
  oa=$(audited "$work/o.stl")
  awk -v n="$(basename "$f")" -v st="$st" -v ot="$ot" -v sm="$sm" -v om="$om" -v sv="$sv" -v ov="$ov" -v sa="$sa" -v oa="$oa" \
    'BEGIN {printf "| `%s` | %.2f | %.2f | %.2f | %.0f | %.0f | %s | %s | %s | %s |\n", n, st, ot, (ot > 0 ? st / ot : 0), sm / 1024, om / 1024, sv, ov, sa, oa}'
  rm -f "$work/s.stl" "$work/o.stl"
done
