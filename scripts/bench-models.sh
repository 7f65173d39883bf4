#!/usr/bin/env bash
# The real-model benchmark: every model of tests/bench/models (OpenSCAD's
# examples) and examples/, timed against OpenSCAD's preview on this machine:
#
#   - first image, as whole processes: strata-render against
#     `openscad --preview` of the same .csg (scripts/bench-first-image.sh);
#   - steady frames: strata-bench --files, strata against OpenCSG rendering
#     the tree as OpenSCAD's preview does (its products, its convexity);
#
# and joined into one Markdown table (scripts/models-table.py).
#
#   scripts/bench-models.sh [--runs N] [--frames N] [--size W,H] [--out DIR] [FILE.csg...]
#
# Defaults: 3 runs, 5 frames after 1 warm-up, 1024,768, DIR bench-models-out,
# the whole set. DIR receives first-image.md, frames.json and models.md.
# Needs a Release build (build/), openscad 2021.01, Xvfb and GNU time.
set -euo pipefail
cd "$(dirname "$0")/.."

runs=3 frames=5 size=1024,768 out=bench-models-out
files=()
while (($#)); do
  case $1 in
    --runs) runs=$2; shift 2 ;;
    --frames) frames=$2; shift 2 ;;
    --size) size=$2; shift 2 ;;
    --out) out=$2; shift 2 ;;
    -h|--help) sed -n '2,17p' "$0" | sed 's/^# \{0,1\}//'; exit 0 ;;
    *) files+=("$1"); shift ;;
  esac
done
((${#files[@]})) || files=(tests/bench/models/*.csg examples/*.csg)
bench=build/apps/strata-bench/strata-bench
[[ -x $bench ]] || { echo "bench-models: build $bench first (scripts/build.sh release)" >&2; exit 1; }
mkdir -p "$out"

echo "bench-models: first images of ${#files[@]} models, $runs runs each" >&2
scripts/bench-first-image.sh --runs "$runs" --size "$size" "${files[@]}" >"$out/first-image.md"

echo "bench-models: steady frames" >&2
list=$(IFS=,; echo "${files[*]}")
xvfb-run -a -s "-screen 0 1280x1024x24" "$bench" --files "$list" --size "${size/,/x}" \
  --frames "$frames" --warmup 1 --json "$out/frames.json" >"$out/frames.txt"

python3 scripts/models-table.py "$out/first-image.md" "$out/frames.json" >"$out/models.md"
cat "$out/models.md"
