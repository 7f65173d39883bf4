#!/usr/bin/env bash
# Writes the export pictures of docs/export.md and the README from a
# Release build: OpenSCAD's CSG example rendered as a scene, its image-space
# export at 64 cells rendered as a plain mesh, and the export at 128 cells
# with its triangle edges (strata-view's edge overlay), close up; and the
# gear's exact and sampled (512 cells) exports with their edges, side by side.
#
#   scripts/export-figures.sh      (from the repository root)
set -euo pipefail
render=build/apps/strata-render/strata-render
view=build/apps/strata-view/strata-view
out=docs/images/export
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
scene=examples/openscad_CSG.csg
"$render" "$scene" -o "$out/scene.png" --imgsize 480,360
"$render" "$scene" --export "$work/64.off" --export-sampled --export-resolution 64
"$render" "$work/64.off" -o "$out/mesh-64.png" --imgsize 480,360
"$render" "$scene" --export "$work/128.off" --export-sampled --export-resolution 128
printf 'size 480 400\ncamera 14,-20,18,0,0,0\nshow edges on\nscreenshot %s\nquit\n' "$PWD/$out/edges-128.png" >"$work/edges.script"
xvfb-run -a -s "-screen 0 1280x1024x24" "$view" "$work/128.off" --script "$work/edges.script"
"$render" examples/gear.csg --export "$work/gear-exact.off"
"$render" examples/gear.csg --export "$work/gear-sampled.off" --export-sampled
for kind in exact sampled; do
  printf 'size 480 360\ncamera 40,-22,30,18,-6,4\nshow edges on\nscreenshot %s\nquit\n' "$PWD/$out/gear-$kind-edges.png" >"$work/gear.script"
  xvfb-run -a -s "-screen 0 1280x1024x24" "$view" "$work/gear-$kind.off" --script "$work/gear.script"
done
