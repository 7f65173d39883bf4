#!/usr/bin/env bash
# The main job: set up, build, and render every bundled example scene headless
# (EGL, no display needed) to PNG files in out/examples/.
set -euo pipefail
cd "$(dirname "$0")/.."

scripts/deps.sh
scripts/build.sh release

mkdir -p out/examples
status=0
shopt -s nullglob
for scene in examples/*.csg examples/*.stl examples/*.off examples/*.obj examples/*.ply; do
  name=$(basename "${scene%.*}")
  if build/apps/strata-render/strata-render "$scene" -o "out/examples/$name.png" --imgsize 800,600; then
    echo "rendered $scene -> out/examples/$name.png"
  else
    echo "FAILED: $scene" >&2
    status=1
  fi
done
echo "strata: the images are in $(pwd)/out/examples/"
exit $status
