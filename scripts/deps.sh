#!/usr/bin/env bash
# Installs strata's Debian 12 packages if any is missing. Idempotent: when all
# are present it runs no apt-get at all. Needs root (or sudo) only to install.
set -euo pipefail

packages=(
  build-essential cmake ninja-build pkg-config git
  clang libclang-rt-14-dev               # libFuzzer target (tests/fuzz)
  libglm-dev libopenmesh-dev
  libpng-dev libopenexr-dev              # PNG and EXR output
  libopenimageio-dev openimageio-tools   # the tests read images back through OpenImageIO, apart from the writers
  libegl-dev libegl-mesa0 libglx-mesa0 libgl1-mesa-dri libepoxy-dev libglfw3-dev
  libembree-dev libcli11-dev
  libpolyclipping-dev libglu1-mesa-dev   # 2D booleans and offsets (Clipper 6, as OpenSCAD); extrusion caps (GLU's tessellator)
  libfreetype-dev libharfbuzz-dev libfontconfig-dev fonts-liberation2   # text(), OpenSCAD's default font
  libxml2-dev                            # import() of SVG files
  libqhull-dev                           # hull() and minkowski(): convex hulls
  libcgal-dev                            # exact results of differences and intersections inside hull/resize/projection/minkowski, and --export-exact
  lib3mf-dev                             # --export to 3MF
  libmimalloc-dev                        # the exact results' numbers (GMP's allocations on mimalloc)
  libgtest-dev libgmock-dev
  libimgui-dev                           # strata-view's panel (Dear ImGui, GLFW + OpenGL 3 backends)
  libopencsg-dev libglew-dev             # strata-bench's OpenCSG comparator (built only where found)
  xvfb xauth x11-utils                   # a display for the window tests; xwininfo sees their windows
  openscad                               # .scad scenes: strata runs openscad to export their CSG (optional at run time; the tests compare the two routes)
)

missing=()
for p in "${packages[@]}"; do
  if ! dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed"; then
    missing+=("$p")
  fi
done

if ((${#missing[@]})); then
  echo "strata: installing ${#missing[@]} missing packages: ${missing[*]}"
  SUDO=""
  if [[ $(id -u) -ne 0 ]]; then SUDO="sudo"; fi
  $SUDO apt-get update -qq
  DEBIAN_FRONTEND=noninteractive $SUDO apt-get install -y -qq --no-install-recommends "${missing[@]}" >/dev/null
fi
