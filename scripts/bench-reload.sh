#!/usr/bin/env bash
# Reload after an edit, as strata-view's user meets it: the model is opened
# from a copy, then the copy is replaced RUNS times the way an editor saves
# (a temporary renamed over it), alternating between the model and the model
# with a comment line added, so each save is a real change. After each
# reload the script asks `print load`; the table gives the medians of its
# figures (docs/viewer.md, "Live reload"):
#   load_ms         parse and mesh, on the worker thread
#   handover_ms     from the worker's end to the upload's start: the window's
#                   thread finishing the frame it is on, waking, taking the model
#   upload_ms       Renderer::setScene on the window's thread
#   first_frame_ms  from the upload to the first frame drawn and swapped (glFinish)
#   total_ms        from the file watch noticing the save to that frame
# A save waits up to one poll of the file (200 ms) before it is noticed;
# total_ms starts when it is.
#
#   scripts/bench-reload.sh [--runs N] [--size W,H] FILE.csg...
#
# Needs a Release build of strata-view (build/) and Xvfb. The copies live in
# a temporary folder: a model that import()s files by a relative path would
# not find them there. "leaves" are the frame's operands (print stats).
set -euo pipefail
here=$PWD
cd "$(dirname "$0")/.."

runs=5
size=1024,768
files=()
while (($#)); do
  case $1 in
    --runs) runs=$2; shift 2 ;;
    --size) size=$2; shift 2 ;;
    /*) files+=("$1"); shift ;;
    *) files+=("$here/$1"); shift ;;
  esac
done
((${#files[@]})) || { echo "usage: scripts/bench-reload.sh [--runs N] [--size W,H] FILE.csg..." >&2; exit 2; }
[[ $runs =~ ^[1-9][0-9]*$ ]] || { echo "bench-reload: --runs wants a whole number >= 1, not '$runs'" >&2; exit 2; }
[[ $size =~ ^[1-9][0-9]*,[1-9][0-9]*$ ]] || { echo "bench-reload: --size wants W,H, not '$size'" >&2; exit 2; }
command -v Xvfb >/dev/null || { echo "bench-reload: Xvfb is not installed" >&2; exit 1; }
view=build/apps/strata-view/strata-view
[[ -x $view ]] || { echo "bench-reload: build $view first (scripts/build.sh release)" >&2; exit 1; }

for f in "${files[@]}"; do
  [[ -r $f ]] || { echo "bench-reload: cannot read $f" >&2; exit 1; }
done

work=$(mktemp -d)
display=:$((90 + RANDOM % 100))
Xvfb "$display" -screen 0 1920x1200x24 >/dev/null 2>&1 &
xvfb=$!
trap 'kill $xvfb 2>/dev/null; rm -rf "$work"' EXIT
sleep 1

median() { sort -g | awk '{v[NR] = $1} END {print (NR % 2) ? v[(NR + 1) / 2] : (v[NR / 2] + v[NR / 2 + 1]) / 2}'; }
# The value after NAME on each "load_ms ..." line of the output.
figure() { awk -v name="$1" '$1 == "load_ms" {for (i = 1; i < NF; i++) if ($i == name) print $(i + 1)}' "$work/out"; }

echo "| model | leaves | load ms | handover ms | upload ms | first frame ms | total ms |"
echo "| --- | ---: | ---: | ---: | ---: | ---: | ---: |"
for f in "${files[@]}"; do
  cp "$f" "$work/model.csg"
  { cat "$f"; printf '\n// edited\n'; } >"$work/edited.csg"
  cp "$f" "$work/watched.csg"
  {
    echo "size ${size/,/ }"
    echo "open watched.csg"
    echo "print stats"
    for ((i = 0; i < runs; i++)); do
      if ((i % 2 == 0)); then echo "copy edited.csg watched.csg"; else echo "copy model.csg watched.csg"; fi
      echo "wait-reload"
      echo "print load"
    done
    echo "quit"
  } >"$work/script.txt"
  # The model on the command line: the window opens at its default camera.
  if ! DISPLAY=$display "$view" "$f" --script "$work/script.txt" >"$work/out" 2>"$work/err"; then
    echo "bench-reload: strata-view failed on $f: $(head -1 "$work/err")" >&2
    echo "| \`$(basename "$f")\` | fail | | | | | |"
    continue
  fi
  leaves=$(awk '$1 == "total_ms" {for (i = 1; i < NF; i++) if ($i == "operands") print $(i + 1)}' "$work/out" | head -1)
  n=$(grep -c '^load_ms ' "$work/out" || true)
  ((n == runs)) || { echo "bench-reload: $f: $n of $runs reloads reported" >&2; }
  awk -v m="$(basename "$f")" -v leaves="$leaves" -v l="$(figure load_ms | median)" -v h="$(figure handover_ms | median)" \
    -v u="$(figure upload_ms | median)" -v fr="$(figure first_frame_ms | median)" -v t="$(figure total_ms | median)" \
    'BEGIN {printf "| `%s` | %s | %.1f | %.1f | %.1f | %.1f | %.1f |\n", m, leaves, l, h, u, fr, t}'
done
