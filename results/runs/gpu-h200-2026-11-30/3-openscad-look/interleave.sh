#!/usr/bin/env bash
# strata-bench of three commits, interleaved, on one GPU: old (aae7a4f), mid
# (b9be1e7: one projection per leaf, no waits between passes, no coverage
# tiles on a GPU), new (mid + auto peeling's passes of the frame before)
set -u
out=$1; look=$2; mkdir -p "$out/cmp"
export LD_LIBRARY_PATH=$PWD/.gpu/lib
[ -e /usr/local/nvidia/lib64/libEGL_nvidia.so.0 ] && export LD_LIBRARY_PATH=$LD_LIBRARY_PATH:/usr/local/nvidia/lib64
export FONTCONFIG_FILE=$PWD/.gpu/fonts/fonts.conf OPENSCAD_FONT_PATH=$PWD/.gpu/fonts
m=.gpu/models
files=examples/gear.csg,examples/openscad_menger_sponge.csg,examples/stacked_holes.csg,examples/imported_mesh.csg,examples/lettering.csg,examples/vase.csg,$m/Basics_CSG-modules.csg,$m/Parametric_candleStand.csg,$m/Old_example006.csg,$m/Old_example016.csg,$m/Functions_recursion.csg,$m/Parametric_sign.csg,$m/Basics_CSG.csg,$m/Advanced_children.csg,$m/Basics_text_on_cube.csg,$m/Old_example010.csg
la=(); [ "$look" = openscad ] && la=(--light openscad --no-outline)
for round in 1 2; do
  for b in old mid new; do
    bin=.gpu/bin/strata-bench; [ $b != new ] && bin=.gpu/$b/strata-bench
    timeout 100 $bin --no-opencsg "${la[@]}" --scenes cheese --k 64,256 --size 1024x768 --frames 20 --warmup 5 --json "$out/cmp/$b-cheese-$round.json" 2>&1 | grep '^cheese' | sed "s/^/$b /"
    timeout 100 $bin --no-opencsg "${la[@]}" --files $files --size 1024x768 --frames 20 --warmup 5 --json "$out/cmp/$b-files-$round.json" 2>&1 | grep -v '^ \|^#\|^scene' | sed "s/^/$b /"
  done
done
tar -C "$out" -cf "$out/cmp.tar" cmp && rm -rf "$out/cmp"
