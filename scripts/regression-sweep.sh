#!/usr/bin/env bash
# strata against OpenSCAD's exact result on a folder of .scad models (made for
# OpenSCAD 2021.01's regression suite, testdata/scad): for each model,
# `openscad -o exact.stl` (CGAL's exact result, as F6 gives it) and
# `openscad -o m.csg` (what strata reads); strata-render draws both, the .csg
# through its image-space CSG and the exact mesh as one plain closed mesh, from
# one camera (OpenSCAD's default view fitted to the exact result's box) at one
# size, and scripts/regression-sweep.py compares the depth and normal AOVs
# pixel by pixel: coverage, depth (1e-4 of the box's diagonal), normal (1
# degree). Pixels at an edge of the exact image (a neighbour off the pixel's
# face) are counted apart, and so are lone pixels (a normal apart from all 8
# neighbours in strata's image only). Prints a Markdown table (file, OpenSCAD
# and strata seconds, covered pixels, differing non-edge pixels by kind,
# differing edge pixels, lone pixels), the files strata failed on and the
# files skipped with the reason: a 2D or empty result, an OpenSCAD error, a
# missing font or import, a timeout.
#
#   scripts/regression-sweep.sh [--size W,H] [--jobs N] [--timeout S] [--out DIR]
#                               [--images DIR] [--redo] FOLDER|FILE.scad...
#
# --size: the images (320,240); --jobs: models at a time (1); --timeout: the
# limit on each openscad and strata-render run, seconds (120); --out: the
# work folder (build/regression-sweep), one folder per model with both
# images, the AOVs, diff.png (the exact image in grey, differing non-edge
# pixels red for coverage, blue for depth, green for normal, differing edge
# pixels yellow, lone pixels magenta), the logs and the figures; a model
# whose figures are there is not run again unless --redo is given, so an
# interrupted sweep goes on where it stopped. --images: where the strata |
# exact | diff strips of the 5 files with the most differing non-edge pixels
# go ($out/images), a difference with a known cause (a node strata leaves
# out, a part OpenSCAD's CGAL dropped with an ERROR) ranked after the others.
# The table is also written to $out/sweep.md.
#
# A model's .csg is written beside its .scad for the render (as a hidden
# .regression-sweep-*.csg, removed afterwards) so that relative import()s
# and surface()s resolve as they do from the .scad.
#
# Needs a Release build (build/apps/strata-render/strata-render, or
# STRATA_RENDER naming it), openscad 2021.01, python3 with numpy (Debian's
# python3-numpy; /usr/bin/python3 is tried when the python3 on PATH has
# none), GNU timeout, and oiiotool (Debian's openimageio-tools) for the strips.
set -euo pipefail
here=$(cd "$(dirname "$0")/.." && pwd)

size=320,240
jobs=1
limit=120
out=$here/build/regression-sweep
images=
redo=0
one=
paths=()
while (($#)); do
  case $1 in
    --size) size=$2; shift 2 ;;
    --jobs) jobs=$2; shift 2 ;;
    --timeout) limit=$2; shift 2 ;;
    --out) out=$2; shift 2 ;;
    --images) images=$2; shift 2 ;;
    --redo) redo=1; shift ;;
    --one) one=$2; shift 2 ;;  # internal: one model, run by the sweep's xargs
    -h|--help) sed -n '2,/^set -euo/p' "$0" | sed '$d; s/^# \{0,1\}//'; exit 0 ;;
    *) paths+=("$1"); shift ;;
  esac
done
[[ $size =~ ^[0-9]+,[0-9]+$ ]] || { echo "regression-sweep: --size wants W,H, got $size" >&2; exit 2; }
render=${STRATA_RENDER:-$here/build/apps/strata-render/strata-render}
[[ -x $render ]] || { echo "regression-sweep: build $render first (scripts/build.sh release), or name it in STRATA_RENDER" >&2; exit 1; }
render=$(cd "$(dirname "$render")" && pwd)/$(basename "$render")
for tool in openscad timeout oiiotool; do
  command -v "$tool" >/dev/null || { echo "regression-sweep: $tool is not installed" >&2; exit 1; }
done
py=
for p in python3 /usr/bin/python3; do
  if "$p" -c 'import numpy' 2>/dev/null; then py=$p; break; fi
done
[[ -n $py ]] || { echo "regression-sweep: python3 with numpy is needed (apt-get install python3-numpy)" >&2; exit 1; }
tool=$here/scripts/regression-sweep.py
mkdir -p "$out"
out=$(cd "$out" && pwd)
images=${images:-$out/images}

# One model: "root<TAB>file" in $one. Writes $out/KEY/result, lines of
# key=value: file, status (compared, skipped, strata-failed, exact-failed),
# reason, and the figures.
sweep_one() {
  local root=${one%%$'\t'*} scad=${one#*$'\t'}
  local rel=${scad#"$root"/}
  local key=${rel//\//__}
  key=${key%.scad}
  key=${key// /_}
  local d=$out/$key
  [[ $redo == 0 && -f $d/result ]] && return 0
  rm -rf "$d"
  mkdir -p "$d"
  local res=$d/result.part
  echo "file=$rel" >"$res"
  skip() { echo "status=skipped" >>"$res"; echo "reason=$1" >>"$res"; mv "$res" "$d/result"; }
  # The first line of a log that says what went wrong.
  first() { grep -m1 -E "$2" "$1" | tr -d '\r' | cut -c1-160 || true; }

  local t0 t1 rc=0
  t0=$EPOCHREALTIME
  timeout "$limit" openscad -o "$d/exact.stl" "$scad" >"$d/openscad.log" 2>&1 || rc=$?
  t1=$EPOCHREALTIME
  local log=$d/openscad.log
  if ((rc == 124)); then skip "OpenSCAD's exact export timed out (${limit} s)"; return 0; fi
  if grep -q "Current top level object is not a 3D object" "$log"; then skip "2D result"; return 0; fi
  local font
  font=$(first "$log" "Can't get font|Can't read font|[Ff]ont .*not found|No font")
  if [[ -n $font ]]; then skip "font missing: $font"; return 0; fi
  if grep -q "Current top level object is empty" "$log"; then
    local why
    why=$(first "$log" "Can't open|Could not open|couldn't be opened")
    [[ -n $why ]] || why=$(first "$log" "ERROR|WARNING")
    if grep -qE "Can't open (import )?file|Can't open include|Could not open|Can't open input file|couldn't be opened" "$log"; then
      skip "import or include missing: $why"
    elif grep -qE "experimental" "$log"; then
      skip "empty result, needs an experimental feature: $why"
    else
      skip "empty result${why:+ ($why)}"
    fi
    return 0
  fi
  if ((rc > 128)); then skip "OpenSCAD crashed (signal $((rc - 128)))"; return 0; fi
  if ((rc != 0)) || [[ ! -s $d/exact.stl ]]; then
    skip "OpenSCAD failed (status $rc): $(first "$log" "ERROR|error|Error|WARNING")"
    return 0
  fi
  echo "openscad_s=$(awk "BEGIN {printf \"%.2f\", $t1 - $t0}")" >>"$res"

  local csg
  csg=$(dirname "$scad")/.regression-sweep-$$-$(basename "${scad%.scad}").csg
  rc=0
  timeout "$limit" openscad -o "$csg" "$scad" >"$d/csg.log" 2>&1 || rc=$?
  if ((rc != 0)) || [[ ! -s $csg ]]; then
    rm -f "$csg"
    skip "OpenSCAD's CSG export failed (status $rc): $(first "$d/csg.log" "ERROR|error|WARNING")"
    return 0
  fi

  local cam diag
  if ! read -r cam diag < <("$py" "$tool" camera "$d/exact.stl" 2>"$d/camera.log"); then
    rm -f "$csg"
    skip "OpenSCAD's STL: $(tail -n1 "$d/camera.log")"
    return 0
  fi
  echo "camera=$cam" >>"$res"
  echo "diag=$diag" >>"$res"
  rc=0
  t0=$EPOCHREALTIME
  timeout "$limit" "$render" "$csg" -o "$d/strata.png" --depth "$d/strata-depth.exr" --normal "$d/strata-normal.exr" \
    --imgsize "$size" --camera "$cam" >"$d/strata.log" 2>&1 || rc=$?
  t1=$EPOCHREALTIME
  mv "$csg" "$d/m.csg"
  if ((rc != 0)); then
    { echo "status=strata-failed"; echo "reason=$( ((rc == 124)) && echo "timed out (${limit} s)" || tail -n1 "$d/strata.log" | cut -c1-200)"; } >>"$res"
    mv "$res" "$d/result"
    return 0
  fi
  echo "strata_s=$(awk "BEGIN {printf \"%.2f\", $t1 - $t0}")" >>"$res"
  rc=0
  timeout "$limit" "$render" "$d/exact.stl" -o "$d/exact.png" --depth "$d/exact-depth.exr" --normal "$d/exact-normal.exr" \
    --imgsize "$size" --camera "$cam" >"$d/exact-render.log" 2>&1 || rc=$?
  if ((rc != 0)); then
    { echo "status=exact-failed"; echo "reason=strata-render cannot draw OpenSCAD's STL: $(tail -n1 "$d/exact-render.log" | cut -c1-200)"; } >>"$res"
    mv "$res" "$d/result"
    return 0
  fi
  local fig
  fig=$("$py" "$tool" compare "$d" "$size" "$cam" "$diag")
  echo "status=compared" >>"$res"
  tr ' ' '\n' <<<"$fig" >>"$res"
  mv "$res" "$d/result"
}

if [[ -n $one ]]; then
  sweep_one
  exit 0
fi

((${#paths[@]})) || { echo "usage: scripts/regression-sweep.sh [--size W,H] [--jobs N] [--timeout S] [--out DIR] [--images DIR] [--redo] FOLDER|FILE.scad..." >&2; exit 2; }
list=$out/files.txt
: >"$list"
for p in "${paths[@]}"; do
  if [[ -d $p ]]; then
    root=$(cd "$p" && pwd)
    find "$root" -name '*.scad' ! -name '.regression-sweep-*' | LC_ALL=C sort | sed "s|^|$root\t|" >>"$list"
  elif [[ -f $p ]]; then
    root=$(cd "$(dirname "$p")" && pwd)
    printf '%s\t%s/%s\n' "$root" "$root" "$(basename "$p")" >>"$list"
  else
    echo "regression-sweep: no such file or folder: $p" >&2; exit 1
  fi
done
n=$(wc -l <"$list")
echo "regression-sweep: $n models, $jobs at a time, into $out" >&2
args=(--size "$size" --timeout "$limit" --out "$out")
((redo)) && args+=(--redo)
export STRATA_RENDER=$render
tr '\n' '\0' <"$list" | xargs -0 -P "$jobs" -I{} bash "$0" "${args[@]}" --one {}

"$py" "$tool" table "$out" | tee "$out/sweep.md"
mkdir -p "$images"
"$py" "$tool" side "$out" 5 | while IFS= read -r key; do
  oiiotool "$out/$key/strata.png" "$out/$key/exact.png" "$out/$key/diff.png" --mosaic 3x1 -o "$images/$key.png" ||
    echo "regression-sweep: no strip for $key" >&2
done
