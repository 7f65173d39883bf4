#!/usr/bin/env bash
# Time to first image, as a user meets it: whole processes, strata-render
# against OpenSCAD's preview of the same .csg, at the same size, interleaved,
# RUNS times each; prints a Markdown table of the medians (wall seconds and
# peak resident memory) and their ratio.
#
#   scripts/bench-first-image.sh [--runs N] [--size W,H] FILE.csg...
#
# Needs a Release build (build/), openscad 2021.01, xvfb-run and GNU time
# (/usr/bin/time). OpenSCAD renders into a running Xvfb, as strata-bench's
# OpenCSG comparator does, so neither side pays for starting a display.
set -euo pipefail
cd "$(dirname "$0")/.."

runs=3
size=1024,768
files=()
while (($#)); do
  case $1 in
    --runs) runs=$2; shift 2 ;;
    --size) size=$2; shift 2 ;;
    *) files+=("$1"); shift ;;
  esac
done
((${#files[@]})) || { echo "usage: scripts/bench-first-image.sh [--runs N] [--size W,H] FILE.csg..." >&2; exit 2; }
for tool in openscad Xvfb /usr/bin/time; do
  command -v "$tool" >/dev/null || { echo "bench-first-image: $tool is not installed" >&2; exit 1; }
done
render=build/apps/strata-render/strata-render
[[ -x $render ]] || { echo "bench-first-image: build $render first (scripts/build.sh release)" >&2; exit 1; }

work=$(mktemp -d)
display=:$((90 + RANDOM % 100))
Xvfb "$display" -screen 0 1280x1024x24 >/dev/null 2>&1 &
xvfb=$!
trap 'kill $xvfb 2>/dev/null; rm -rf "$work"' EXIT
sleep 1

# One measurement: "seconds kilobytes" of the command.
measure() {
  /usr/bin/time -f "%e %M" -o "$work/t" "$@" >/dev/null 2>&1 || { echo "fail fail"; return; }
  cat "$work/t"
}
median() { sort -g | awk '{v[NR] = $1} END {print (NR % 2) ? v[(NR + 1) / 2] : (v[NR / 2] + v[NR / 2 + 1]) / 2}'; }

echo "| model | strata s | OpenSCAD s | strata / OpenSCAD | strata MiB | OpenSCAD MiB |"
echo "| --- | ---: | ---: | ---: | ---: | ---: |"
for f in "${files[@]}"; do
  : >"$work/s"
  : >"$work/o"
  for ((i = 0; i < runs; i++)); do
    measure "$render" "$f" -o "$work/s.png" --imgsize "$size" >>"$work/s"
    DISPLAY=$display measure openscad --preview -o "$work/o.png" --imgsize="$size" "$f" >>"$work/o"
  done
  st=$(cut -d' ' -f1 "$work/s" | median)
  ot=$(cut -d' ' -f1 "$work/o" | median)
  sm=$(cut -d' ' -f2 "$work/s" | median)
  om=$(cut -d' ' -f2 "$work/o" | median)
  awk -v n="$(basename "$f")" -v st="$st" -v ot="$ot" -v sm="$sm" -v om="$om" \
    'BEGIN {printf "| `%s` | %.2f | %.2f | %.2f | %.0f | %.0f |\n", n, st, ot, (ot > 0 ? st / ot : 0), sm / 1024, om / 1024}'
done
