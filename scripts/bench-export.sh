#!/usr/bin/env bash
# Exact export as a user meets it: whole processes, `strata-render FILE
# --export x.stl` against OpenSCAD's own CGAL export (`openscad -o x.stl
# FILE`), interleaved, RUNS times each; prints a Markdown table of the
# medians (wall seconds, peak resident memory), their ratio, the two
# results' volumes (from the binary and ASCII STL files), and each file's
# triangles and audit (strata_mesh_audit: "clean", or the degenerate
# triangles, open or non-manifold edges after welding, and crossing pairs).
#
#   scripts/bench-export.sh [--runs N] [--manifold] FILE.csg...
#
# --manifold adds a third program, as a comparator only: Manifold (the
# manifold-3d WebAssembly package, MANIFOLD_VERSION below, run by node),
# which reads the same .csg through scripts/manifold/csg2manifold.mjs (a
# translator that cuts spheres, cylinders, circles and extrusions as
# OpenSCAD 2021.01 does, so that the three evaluate the same polyhedra) and
# writes a binary STL. Its columns, after the others: the whole process
# (node start, loading the WebAssembly, parsing, building, evaluating,
# writing) in wall seconds and peak MiB, Manifold's own evaluation
# (building the Manifold tree and its booleans, timed inside the process,
# forced by getMesh: no start, load, parse or write), the volume, triangles
# and audit of its STL. A model it cannot read (text(), say) shows "-",
# and the reason goes to stderr. manifold-3d is installed on first use
# with npm into ${XDG_CACHE_HOME:-~/.cache}/strata-bench/manifold, outside
# the repository; nothing in the build or the tests needs it.
#
# Needs a Release build (build/, with tests/bench/strata_mesh_audit; or
# STRATA_RENDER and STRATA_AUDIT naming the two programs), openscad 2021.01,
# python3 and GNU time; node and npm for --manifold.
set -euo pipefail
cd "$(dirname "$0")/.."

MANIFOLD_VERSION=3.5.4

runs=3
manifold=0
files=()
while (($#)); do
  case $1 in
    --runs) runs=$2; shift 2 ;;
    --manifold) manifold=1; shift ;;
    *) files+=("$1"); shift ;;
  esac
done
((${#files[@]})) || { echo "usage: scripts/bench-export.sh [--runs N] [--manifold] FILE.csg..." >&2; exit 2; }
tools=(openscad python3 /usr/bin/time)
if ((manifold)); then tools+=(node npm); fi
for tool in "${tools[@]}"; do
  command -v "$tool" >/dev/null || { echo "bench-export: $tool is not installed" >&2; exit 1; }
done
render=${STRATA_RENDER:-build/apps/strata-render/strata-render}
audit=${STRATA_AUDIT:-build/tests/bench/strata_mesh_audit}
for exe in "$render" "$audit"; do
  [[ -x $exe ]] || { echo "bench-export: build $exe first (scripts/build.sh release)" >&2; exit 1; }
done

# manifold-3d in a cache outside the repository, at the pinned version; npm
# writes no package.json or lock there (--no-save), and runs no install
# scripts: only the WebAssembly module is used.
if ((manifold)); then
  manifold_dir=${XDG_CACHE_HOME:-$HOME/.cache}/strata-bench/manifold
  manifold_js=$manifold_dir/node_modules/manifold-3d/manifold.js
  if [[ $(node -p "require('$manifold_dir/node_modules/manifold-3d/package.json').version" 2>/dev/null) != "$MANIFOLD_VERSION" ]]; then
    echo "bench-export: installing manifold-3d@$MANIFOLD_VERSION into $manifold_dir" >&2
    mkdir -p "$manifold_dir"
    npm install --no-save --no-audit --no-fund --ignore-scripts --omit=optional --omit=peer \
      --prefix "$manifold_dir" "manifold-3d@$MANIFOLD_VERSION" >&2
  fi
  [[ -f $manifold_js ]] || { echo "bench-export: no $manifold_js after npm install" >&2; exit 1; }
fi

work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT

measure() {
  /usr/bin/time -f "%e %M" -o "$work/t" "$@" >/dev/null 2>&1 || { echo "fail fail"; return; }
  cat "$work/t"
}
# One Manifold run: "wall KiB evaluation", the last from the translator's
# timing line (building and evaluating); its refusal or error, if any, is
# kept in $work/m.why.
measure_manifold() {
  if /usr/bin/time -f "%e %M" -o "$work/t" node scripts/manifold/csg2manifold.mjs --module "$manifold_js" "$1" "$2" \
      >/dev/null 2>"$work/m.err"; then
    echo "$(cat "$work/t") $(python3 -c 'import json, sys; t = json.loads(open(sys.argv[1]).read().splitlines()[-1]); print(t["build_s"] + t["evaluate_s"])' "$work/m.err")"
  else
    tail -n 1 "$work/m.err" >"$work/m.why"
    echo "fail fail fail"
  fi
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

head="| model | strata s | OpenSCAD s | strata / OpenSCAD | strata MiB | OpenSCAD MiB | strata volume | OpenSCAD volume | strata triangles | strata audit | OpenSCAD triangles | OpenSCAD audit |"
rule="| --- | ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: | --- | ---: | --- |"
if ((manifold)); then
  head+=" Manifold s | Manifold eval s | Manifold MiB | Manifold volume | Manifold triangles | Manifold audit |"
  rule+=" ---: | ---: | ---: | ---: | ---: | --- |"
fi
echo "$head"
echo "$rule"
for f in "${files[@]}"; do
  : >"$work/s"
  : >"$work/o"
  : >"$work/m"
  rm -f "$work/m.why"
  for ((i = 0; i < runs; i++)); do
    measure "$render" "$f" --export "$work/s.stl" >>"$work/s"
    measure openscad -o "$work/o.stl" "$f" >>"$work/o"
    if ((manifold)); then measure_manifold "$f" "$work/m.stl" >>"$work/m"; fi
  done
  st=$(cut -d' ' -f1 "$work/s" | median)
  ot=$(cut -d' ' -f1 "$work/o" | median)
  sm=$(cut -d' ' -f2 "$work/s" | median)
  om=$(cut -d' ' -f2 "$work/o" | median)
  sv=$( [[ -f $work/s.stl ]] && volume "$work/s.stl" || echo "-")
  ov=$( [[ -f $work/o.stl ]] && volume "$work/o.stl" || echo "-")
  sa=$(audited "$work/s.stl")
  oa=$(audited "$work/o.stl")
  row=$(awk -v n="$(basename "$f")" -v st="$st" -v ot="$ot" -v sm="$sm" -v om="$om" -v sv="$sv" -v ov="$ov" -v sa="$sa" -v oa="$oa" \
    'BEGIN {printf "| `%s` | %.2f | %.2f | %.2f | %.0f | %.0f | %s | %s | %s | %s |", n, st, ot, (ot > 0 ? st / ot : 0), sm / 1024, om / 1024, sv, ov, sa, oa}')
  if ((manifold)); then
    if [[ -f $work/m.why ]]; then
      echo "bench-export: Manifold on $f: $(cat "$work/m.why")" >&2
      row+=" - | - | - | - | - | - |"
    else
      mt=$(cut -d' ' -f1 "$work/m" | median)
      mm=$(cut -d' ' -f2 "$work/m" | median)
      me=$(cut -d' ' -f3 "$work/m" | median)
      mv=$(volume "$work/m.stl")
      ma=$(audited "$work/m.stl")
      row+=$(awk -v mt="$mt" -v me="$me" -v mm="$mm" -v mv="$mv" -v ma="$ma" \
        'BEGIN {printf " %.2f | %.3f | %.0f | %s | %s |", mt, me, mm / 1024, mv, ma}')
    fi
  fi
  echo "$row"
  rm -f "$work/s.stl" "$work/o.stl" "$work/m.stl"
done
