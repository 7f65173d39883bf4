#!/usr/bin/env bash
# Export as a user meets it, three ways, whole processes, interleaved, RUNS
# times each: strata's image-space export (`strata-render FILE --export
# x.off --export-sampled`, the GPU's result peel and the contouring, at --export-resolution R),
# strata's exact export (`--export-exact`, CGAL) and OpenSCAD's own CGAL
# export (`openscad -o x.off FILE`). Prints a Markdown table of the medians
# (wall seconds, peak resident memory) and, for the image-space result
# against the exact one, the volume difference and the Hausdorff distance
# (CGAL's, by build/tests/bench/strata_mesh_compare) in cells and in parts of
# the box's diagonal (against OpenSCAD's result, marked *, where strata's
# exact export did not finish). A cell is the exact result's longest side / R. An export that fails or runs past TIMEOUT seconds
# shows "-". The triangles of both strata meshes, their ratio, and the
# image-space mesh's audit (build/tests/bench/strata_mesh_audit: "clean", or
# its degenerate triangles, open or non-manifold edges and crossing pairs).
#
#   scripts/bench-image-export.sh [--runs N] [--resolution R] [--timeout S] [--no-openscad] FILE.csg...
#
# Needs a Release build (build/), python3 and GNU time; openscad 2021.01
# unless --no-openscad.
set -euo pipefail
cd "$(dirname "$0")/.."

runs=3
resolution=512
timeout_s=1200
openscad=1
files=()
while (($#)); do
  case $1 in
    --runs) runs=$2; shift 2 ;;
    --resolution) resolution=$2; shift 2 ;;
    --timeout) timeout_s=$2; shift 2 ;;
    --no-openscad) openscad=0; shift ;;
    *) files+=("$1"); shift ;;
  esac
done
((${#files[@]})) || { echo "usage: scripts/bench-image-export.sh [--runs N] [--resolution R] [--timeout S] [--no-openscad] FILE.csg..." >&2; exit 2; }
tools=(python3 /usr/bin/time)
((openscad)) && tools+=(openscad)
for tool in "${tools[@]}"; do
  command -v "$tool" >/dev/null || { echo "bench-image-export: $tool is not installed" >&2; exit 1; }
done
render=build/apps/strata-render/strata-render
compare=build/tests/bench/strata_mesh_compare
audit=build/tests/bench/strata_mesh_audit
for exe in "$render" "$compare" "$audit"; do
  [[ -x $exe ]] || { echo "bench-image-export: build $exe first (scripts/build.sh release)" >&2; exit 1; }
done

work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT

# "seconds kilobytes" of one run, or "fail fail".
measure() {
  /usr/bin/time -f "%e %M" -o "$work/t" timeout "$timeout_s" "$@" >/dev/null 2>&1 || { echo "fail fail"; return; }
  cat "$work/t"
}
median() {
  { grep -v fail || true; } | sort -g | awk '{v[NR] = $1} END {if (NR == 0) print "-"; else print (NR % 2) ? v[(NR + 1) / 2] : (v[NR / 2] + v[NR / 2 + 1]) / 2}'
}
fmt_s() { [[ $1 == - ]] && echo - || awk -v v="$1" 'BEGIN {printf "%.2f", v}'; }
fmt_m() { [[ $1 == - ]] && echo - || awk -v v="$1" 'BEGIN {printf "%.0f", v / 1024}'; }
# "triangles verdict" of a mesh file, or "- -".
audited() {
  [[ -f $1 ]] || { echo "- -"; return; }
  "$audit" "$1" 2>/dev/null | python3 -c '
import json, sys
a = json.load(sys.stdin)
bad = [f"{a[k]} {name}" for k, name in (("degenerate", "degenerate"), ("boundary_edges", "open"),
       ("nonmanifold_edges", "non-manifold"), ("misoriented_edges", "misoriented"),
       ("self_intersections", "crossing")) if a[k]]
print(a["triangles"], ", ".join(bad) if bad else "clean")' || echo "- -"
}

echo "| model | image s | image MiB | exact s | exact MiB | OpenSCAD s | OpenSCAD MiB | image / OpenSCAD s | volume off | Hausdorff (cells) | Hausdorff / diagonal | image triangles | exact triangles | image / exact triangles | image audit |"
echo "| --- | ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: | --- |"
for f in "${files[@]}"; do
  : >"$work/i"; : >"$work/e"; : >"$work/o"
  for ((r = 0; r < runs; r++)); do
    measure "$render" "$f" --export "$work/i.off" --export-sampled --export-resolution "$resolution" >>"$work/i"
    measure "$render" "$f" --export "$work/e.off" --export-exact >>"$work/e"
    if ((openscad)); then measure openscad -o "$work/o.off" "$f" >>"$work/o"; else echo "fail fail" >>"$work/o"; fi
  done
  it=$(cut -d' ' -f1 "$work/i" | median); im=$(cut -d' ' -f2 "$work/i" | median)
  et=$(cut -d' ' -f1 "$work/e" | median); em=$(cut -d' ' -f2 "$work/e" | median)
  ot=$(cut -d' ' -f1 "$work/o" | median); om=$(cut -d' ' -f2 "$work/o" | median)
  ratio=-
  [[ $it != - && $ot != - ]] && ratio=$(awk -v a="$it" -v b="$ot" 'BEGIN {printf "%.2f", a / b}')
  # Against strata's exact result, or OpenSCAD's where that one did not
  # finish (marked *).
  voff=- hcells=- hdiag=- ref=$work/e.off mark=""
  [[ -f $ref ]] || { ref=$work/o.off; mark="*"; }
  if [[ -f $work/i.off && -f $ref ]] && read -r vi ve h side diag < <("$compare" "$work/i.off" "$ref"); then
    # A cell: the exact result's longest side / R (the grid's box is the
    # leaves' that the result lies in, about that side).
    read -r voff hcells hdiag < <(awk -v vi="$vi" -v ve="$ve" -v h="$h" -v s="$side" -v d="$diag" -v n="$resolution" \
      'BEGIN {printf "%.2e %.2f %.1e\n", (vi - ve) / ve, h / (s / n), h / d}')
  fi
  [[ $voff != - ]] && voff+=$mark
  read -r itri iaudit < <(audited "$work/i.off")
  read -r etri _ < <(audited "$work/e.off")
  tratio=-
  [[ $itri != - && $etri != - ]] && tratio=$(awk -v a="$itri" -v b="$etri" 'BEGIN {printf "%.2f", a / b}')
  echo "| \`$(basename "$f")\` | $(fmt_s "$it") | $(fmt_m "$im") | $(fmt_s "$et") | $(fmt_m "$em") | $(fmt_s "$ot") | $(fmt_m "$om") | $ratio | $voff | $hcells | $hdiag | $itri | $etri | $tratio | $iaudit |"
  rm -f "$work/i.off" "$work/e.off" "$work/o.off"
done
