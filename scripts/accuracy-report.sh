#!/usr/bin/env bash
# Regenerates docs/accuracy.md and docs/images/accuracy/*.png: every shot of
# the accuracy corpus (tests/accuracy/scenes.txt) rendered by the GPU path and
# by the CPU reference, compared per pixel, with auto layers and with one layer
# per operand.
#
#   scripts/accuracy-report.sh          # the CI sizes (96x96 and 128x128)
#   scripts/accuracy-report.sh --full   # the larger sweep (every image 3x larger);
#                                       # writes docs/accuracy-full.md, no pictures
#
# It builds build/ (Release; STRATA_BUILD_DIR picks another) as far as the GL
# test binary, runs it with
# STRATA_ACCURACY_REPORT set (AccuracyTest.cpp then writes a row per shot to
# results.tsv and a strata | reference | diff strip per shot), and turns the
# rows into the Markdown tables. Needs only bash and awk beyond the build.
set -euo pipefail
cd "$(dirname "$0")/.."

full=0
[[ ${1:-} == --full ]] && full=1

build=${STRATA_BUILD_DIR:-build}
if [[ ! -f $build/build.ninja ]]; then
  cmake -S . -B "$build" -G Ninja -DCMAKE_BUILD_TYPE=Release >/dev/null
fi
cmake --build "$build" -j "${STRATA_JOBS:-$(nproc)}" --target strata_gl_tests

out=$build/accuracy-report
rm -rf "$out"
mkdir -p "$out"
status=0
if [[ $full == 1 ]]; then
  export STRATA_ACCURACY_FULL=1
  doc=docs/accuracy-full.md
else
  doc=docs/accuracy.md
fi
STRATA_ACCURACY_REPORT=$(pwd)/$out "$build/tests/strata_gl_tests" \
  --gtest_filter='Corpus/AccuracyGLTest.*' >"$out/gtest.log" 2>&1 || status=$?
[[ -s $out/results.tsv ]] || { echo "accuracy-report: no results (see $out/gtest.log)" >&2; exit 1; }

# One picture per family: the shot that shows the family best.
declare -A picture=(
  [stack]=stack_shells_8_p0 [deep]=deep_tree_13_p0 [nary]=nary_cheese_64_p0 [nonconvex]=coil_cut_p0
  [through]=through_front_back_p0 [thin]=thin_box_p0 [near]=near_difference_p0 [inside]=eye_in_subtrahend_p0
  [transform]=mirrored_p0 [coincident]=coincident_side_pockets_p0
)
families=(stack deep nary nonconvex through thin near inside transform coincident)
if [[ $full == 0 ]]; then
  rm -rf docs/images/accuracy
  mkdir -p docs/images/accuracy
  for f in "${families[@]}"; do
    cp "$out/${picture[$f]}.png" "docs/images/accuracy/$f.png"
  done
  cp "$out/${picture[stack]}-layers1.png" docs/images/accuracy/stack-one-layer.png
fi

renderer=$(head -n1 "$out/renderer.txt" 2>/dev/null || true)
# What the page says by hand of real models (from "### Lone pixels on real
# models" to the scenes' table) is not measured here: it is kept as it is.
kept=$out/kept.md
if [[ -f $doc ]]; then
  awk '/^### Lone pixels on real models/ {on = 1} /^## The scenes/ {on = 0} on' "$doc" | sed -e :a -e '/^\n*$/{$d;N;ba' -e '}' >"$kept"
else
  : >"$kept"
fi
{
  if [[ $full == 1 ]]; then
    echo "# Accuracy, the larger sweep (every image 3x larger): strata against the CPU reference"
    echo
    echo "<!-- Written by scripts/accuracy-report.sh --full; edit the script, not this file. -->"
    echo
    echo "The same corpus and bounds as [accuracy.md](accuracy.md), at three times the image sizes."
  else
    echo "# Accuracy: strata against the CPU reference, pixel by pixel"
    echo
    echo "<!-- Written by scripts/accuracy-report.sh; edit the script, not this file. -->"
  fi
  cat <<'EOF'

Every shot of the accuracy corpus is rendered twice, by the GPU path
(`render::Renderer`: depth peeling and the per-pixel CSG evaluator) and by the
CPU reference (`reference::ReferenceScene`: Embree finds every crossing of each
ray with each leaf, the tree is evaluated on interval lists), with the same
camera, and the two images are compared per pixel (`tests/accuracy/Compare.h`).

## How to run it

| what | command |
| --- | --- |
| the suite, as CI runs it | `ctest --test-dir build -R Accuracy`: the GPU comparisons (label `gpu`; about a minute on 2 cores) and the CPU tests of the comparison and the corpus |
| one shot | `build/tests/strata_gl_tests --gtest_filter='*MatchesTheReference/stack_shells_8_p0'` |
| the larger sweep (3x the image sizes) | `STRATA_ACCURACY_FULL=1 build/tests/strata_gl_tests --gtest_filter='Corpus/Accuracy*'` |
| this page | `scripts/accuracy-report.sh` (`--full` writes `docs/accuracy-full.md` for the sweep) |
| the corpus | `python3 tests/accuracy/generate.py` rewrites `tests/accuracy/scenes/`, `meshes/` and `scenes.txt` |

A failing comparison names its scene and manifest line and writes
`build/accuracy-failures/<shot>-{strata,reference,diff,strip,shaded}.png`.

## What is compared

For each pixel, in this order (the first that fails is the pixel's verdict):

- **coverage**: both paths see a surface, or both see none (a miss must have depth +inf);
- **depth**: the view depth `dot(P - eye, f)` agrees within 1e-4 of the scene's
  bounding-box diagonal;
- **normal**: the result's outward normal agrees within 1 degree;
- **leaf**: the same leaf's surface;
- **cut**: the same cut bit, i.e. the leaf's face is shown as its own face or
  as a cut face (the colour scheme's cut-face colour, where the leaf has no
  `color()`). The shaded colour is a function of the normal, the leaf and this
  bit, so a non-edge pixel shaded in another colour fails here. A GPU frame
  carries no such bit: it is read back from strata's shaded image, by shading
  the frame's own surfaces once as uncut and once as cut with the same pass
  (`Renderer::shade`) and taking the one that is the pixel's colour. Where
  both give the same colour (the leaf has a `color()`) the bit does not show
  and is not compared.

**Edge pixels** are counted apart, and the **reference image alone** defines
them (the CPU reference is the oracle: strata's image must not excuse its own
errors by making edges of them). In the reference image, two of a pixel's 8
neighbours are separated by

- an **edge**: a silhouette (coverage differs), a leaf boundary (leaf id
  differs), a crease (the normals differ by more than 30 degrees) or a depth
  step (one surface point lies off the other's tangent plane by more than half
  a pixel footprint plus the depth tolerance);
- else a **facet boundary**: the normals differ by more than 1 degree (the
  normal tolerance), so every boundary between two facets of a tessellated
  sphere, cylinder or torus is one.

A pixel beside an edge is an edge pixel, whatever its verdict: a silhouette
one pixel off (strata covers a pixel beside the reference's outline that the
reference does not, or the other way round) is at a reference edge. A pixel
beside a facet boundary is an edge pixel when it differs **only in its
normal**, by at most 30 degrees, on the right leaf: a pixel centre on the
boundary (or on a sliver facet, or at a vertex where several facets meet) may
go to one facet in the rasterizer and to another in the reference's exact ray
test. Any other disagreement there (coverage, depth, leaf, cut, a normal
turned further) counts as a non-edge one, since coverage, depth and leaf are
continuous across a facet boundary; so a one-layer render's wrong depths on a
curved surface are not excused by its facets. The GPU image's own
silhouettes, creases and steps make no edges: a speckled or pinholed surface,
a patch of the wrong leaf or the wrong depth fails by every pixel of it that
is not beside an edge of the reference, its own outline included.

The bounds, both required:

- at least **99.99%** of the non-edge pixels agree in all five: one pixel in
  ten thousand, so at 96x96 not one non-edge pixel may disagree, at 128x128
  at most one, and in the larger sweep (3x: 288x288 to 600x450) at most eight
  to twenty-seven, fewer where many pixels are edges;
- the edge pixels that disagree are at most **1%** of the image.

The one-layer run (`settings.layers = 1`, one dual-peel pass per operand) must
**fail** both bounds on every shot flagged `nonconvex-stack`: a non-convex
operand (crossed four or more times by some ray of the shot) needs more than
one layer, and the suite must see it.

The **coincident** family breaks the corpus's rule that no two operands have
faces in one plane, on purpose: the models of `tests/data/coincident` (flush
pockets, through holes and a slot flush with two faces or a side, pockets
touching, unions of shared faces, gear teeth on a ring, an intersection
keeping a shared face, A | A, A & A and A - A, a cube's face through a
sphere's equator), each as written, turned by odd angles, and turned and
scaled by 1e-3 and by 1e3. Both paths take surfaces within the coincidence
tolerance along a ray as one place (`render::coincidenceTolerance`: 2^-20 of
the largest magnitude the view's float depths carry). That the reference is
right on them, not only equal to strata, is `CoincidentExactTest`
(strata_tests): the reference's image of each model of `tests/data/coincident`
against its image of OpenSCAD's exact (CGAL) result of that model, `NAME.off`,
from four views at 160x120, must agree on coverage, depth and normal in 99.99%
of the pixels off the exact image's edges (leaf ids left out: the exact mesh
is one leaf), and `identical_difference` must render nothing.

EOF
  echo "## Pictures, one per family"
  echo
  echo "Each strip is strata | reference | diff. Both images use the same false"
  echo "colour (a hue per leaf, brightness from the normal against the view ray);"
  echo "in the diff, agreeing pixels are the reference dimmed (edge pixels tinted"
  echo "blue), and disagreements are red (coverage), orange to yellow (depth, at 1x"
  echo "to 1000x the tolerance), cyan (normal), green (leaf) and magenta (cut), at"
  echo "half strength on edge pixels."
  echo
  if [[ $full == 0 ]]; then
    for f in "${families[@]}"; do
      echo "**$f** (\`${picture[$f]}\`)"
      echo
      echo "![$f](images/accuracy/$f.png)"
      echo
    done
    echo "**stack, one layer per operand** (\`${picture[stack]}\`): strata peels only the"
    echo "nearest and farthest surface of the leaf of eight shells, so the plates between"
    echo "them are cut away; the comparison fails, as it must."
    echo
    echo "![stack, one layer](images/accuracy/stack-one-layer.png)"
    echo
  else
    echo "(The sweep writes no pictures; \`scripts/accuracy-report.sh\` does.)"
    echo
  fi
  awk -F'\t' -v notes=tests/accuracy/notes.txt -v renderer="$renderer" -v kept="$kept" '
    BEGIN {
      while ((getline line < notes) > 0) {
        if (line ~ /^#/) continue
        split(line, parts, "\t"); note[parts[1] ".csg"] = parts[2]
      }
    }
    NR == 1 { for (i = 1; i <= NF; i++) col[$i] = i; next }
    {
      shot = $col["shot"]
      if ($col["layers"] == "auto") {
        order[++n] = shot; row[shot] = $0
      } else {
        one[shot] = $0
      }
    }
    function pct(x) { return sprintf("%.4f%%", 100 * x) }
    END {
      passed = 0; flagged = 0; flaggedFailed = 0; scenes = 0
      for (k = 1; k <= n; k++) {
        split(row[order[k]], a, "\t")
        if (a[col["passed"]] == "yes") passed++
        if (!(a[col["scene"]] in seen)) { seen[a[col["scene"]]] = 1; scenes++ }
        if (a[col["flags"]] ~ /nonconvex-stack/) {
          flagged++
          split(one[order[k]], b, "\t")
          if (b[col["passed"]] == "no" && b[col["agreement"]] < 0.9999) flaggedFailed++
        }
      }
      printf "## Results\n\n"
      printf "%d scenes, %d shots: **%d of %d pass** with auto layers. With one layer per operand, " \
             "**%d of %d** shots flagged `nonconvex-stack` fail both bounds, as they must.\n\n",
             scenes, n, passed, n, flaggedFailed, flagged
      if (renderer != "") printf "Renderer: %s.\n\n", renderer
      printf "Columns: covered = pixels the reference sees a surface on; edge = edge pixels (beside an edge of the reference image, or a facet swap beside a facet boundary); " \
             "non-edge dis. = non-edge disagreements as coverage/depth/normal/leaf/cut, with the normal ones that are a neighbouring facet'"'"'s normal in brackets; agreement = agreeing non-edge pixels; " \
             "edge dis. = disagreeing edge pixels, as a share of the image, and of them the normals, with those that are a neighbouring facet'"'"'s normal in brackets; dz/tol = the largest non-edge " \
             "depth error over the tolerance; normal = the largest non-edge normal error in degrees; " \
             "layers = the most peel passes any operand took; one layer = agreement and verdict with " \
             "`layers = 1` (flagged shots in bold).\n\n"
      printf "| shot | proj | size | layers | covered | edge | non-edge dis. (c/d/n/l/cut) | agreement | edge dis. | dz/tol | normal | pass | one layer |\n"
      printf "| --- | --- | --- | ---: | ---: | ---: | --- | ---: | ---: | ---: | ---: | --- | --- |\n"
      family = ""
      for (k = 1; k <= n; k++) {
        split(row[order[k]], a, "\t")
        if (a[col["family"]] != family) {
          family = a[col["family"]]
          printf "| **%s** | | | | | | | | | | | | |\n", family
        }
        oneText = "-"
        if (order[k] in one) {
          split(one[order[k]], b, "\t")
          oneText = pct(b[col["agreement"]]) " " (b[col["passed"]] == "yes" ? "pass" : "FAIL")
          if (a[col["flags"]] ~ /nonconvex-stack/) oneText = "**" oneText "**"
        }
        printf "| `%s` | %s | %s | %s | %s | %s | %s/%s/%s (%s)/%s/%s | %s | %s (%s), n %s (%s) | %.3f | %.3g | %s | %s |\n",
          order[k], a[col["projection"]], a[col["size"]], a[col["max_layers"]], a[col["covered"]],
          a[col["edge_pixels"]], a[col["nonedge_coverage"]], a[col["nonedge_depth"]], a[col["nonedge_normal"]],
          a[col["nonedge_normal_neighbour"]], a[col["nonedge_leaf"]], a[col["nonedge_cut"]], pct(a[col["agreement"]]), a[col["edge_disagree"]],
          pct(a[col["edge_disagree_fraction"]]), a[col["edge_normal"]], a[col["edge_normal_neighbour"]], a[col["max_dz_over_tol"]], a[col["max_normal_deg"]],
          (a[col["passed"]] == "yes" ? "yes" : "**NO**"), oneText
      }
      total = 0; neighbour = 0; normals = 0; leaves = 0; cuts = 0; coverage = 0; depth = 0
      edges = 0; edgeNormals = 0; edgeNeighbour = 0; failing = ""
      for (k = 1; k <= n; k++) {
        split(row[order[k]], a, "\t")
        total += a[col["nonedge_coverage"]] + a[col["nonedge_depth"]] + a[col["nonedge_normal"]] + a[col["nonedge_leaf"]] + a[col["nonedge_cut"]]
        coverage += a[col["nonedge_coverage"]]
        depth += a[col["nonedge_depth"]]
        normals += a[col["nonedge_normal"]]
        neighbour += a[col["nonedge_normal_neighbour"]]
        leaves += a[col["nonedge_leaf"]]
        cuts += a[col["nonedge_cut"]]
        edges += a[col["edge_disagree"]]
        edgeNormals += a[col["edge_normal"]]
        edgeNeighbour += a[col["edge_normal_neighbour"]]
        if (a[col["passed"]] != "yes") {
          failing = failing sprintf("- `%s`: %s of the non-edge pixels agree (coverage/depth/normal/leaf/cut " \
                                    "%s/%s/%s/%s/%s); edge disagreements %s of the image\n",
                                    order[k], pct(a[col["agreement"]]), a[col["nonedge_coverage"]], a[col["nonedge_depth"]],
                                    a[col["nonedge_normal"]], a[col["nonedge_leaf"]], a[col["nonedge_cut"]],
                                    pct(a[col["edge_disagree_fraction"]]))
        }
      }
      printf "\n### What the remaining disagreements are\n\n"
      printf "Over all %d shots with auto layers there are %d non-edge disagreements: %d coverage, %d depth, " \
             "%d normal (%d of them a neighbouring facet'"'"'s normal), %d leaf and %d cut. ", \
             n, total, coverage, depth, normals, neighbour, leaves, cuts
      printf "There are %d disagreeing edge pixels, %d of them normals; %d of those are the normal of a " \
             "neighbouring pixel'"'"'s facet in the reference. Such a pixel'"'"'s ray passes within rounding " \
             "of the boundary between two facets (a sphere'"'"'s, cylinder'"'"'s or torus'"'"'s tessellation), and " \
             "the rasterizer and the reference'"'"'s exact test pick different sides: the depth agrees, the " \
             "normal is the other facet'"'"'s. A facet boundary is an edge of the reference image, so they count " \
             "against the 1%% edge bound.\n", edges, edgeNormals, edgeNeighbour
      if (failing != "") printf "\nThe shots that fail:\n\n%s", failing
      # The sections written by hand (real models), kept from the page as it was.
      first = 1
      while ((getline line < kept) > 0) {
        if (first) printf "\n"
        first = 0
        print line
      }
      printf "\n## The scenes\n\n| scene | what it is for |\n| --- | --- |\n"
      for (k = 1; k <= n; k++) {
        split(row[order[k]], a, "\t")
        s = a[col["scene"]]
        if (s in listed) continue
        listed[s] = 1
        printf "| `%s` | %s |\n", s, note[s]
      }
    }' "$out/results.tsv"
} >"$doc"

echo "accuracy-report: wrote $doc$([[ $full == 0 ]] && echo " and docs/images/accuracy/")"
if [[ $status != 0 ]]; then
  echo "accuracy-report: some comparisons FAILED (see $out/gtest.log and build/accuracy-failures/)" >&2
fi
exit $status
