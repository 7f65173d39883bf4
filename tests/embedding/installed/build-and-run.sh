#!/usr/bin/env bash
# The test EmbeddingExample.Installed: a host outside strata's tree builds
# against an installed strata. Installs the build into an empty prefix, then
# builds docs/embedding.md's example against that prefix twice, through
# find_package(strata) (this folder's CMakeLists.txt) and through
# `pkg-config --static strata`, and runs both (each checks strata's images
# against closed forms and exits non-zero when one is wrong).
#   build-and-run.sh BUILD_DIR SCRATCH_DIR
# Environment, from tests/embedding/CMakeLists.txt: CMAKE (the cmake that
# configured BUILD_DIR), GENERATOR, CXX, LIBDIR (the prefix's library folder),
# FLAGS (compile and link flags the host needs as well: the sanitizers of an
# ASan build).
set -euo pipefail
build=$1 work=$2
here=$(cd "$(dirname "$0")" && pwd)
: "${CMAKE:?}" "${GENERATOR:?}" "${CXX:?}" "${LIBDIR:?}" "${FLAGS=}"

rm -rf "$work"
mkdir -p "$work/src"
prefix=$work/prefix
start=$SECONDS
step() { echo "[$((SECONDS - start)) s] $*"; }

step "installing $build into $prefix"
"$CMAKE" --install "$build" --prefix "$prefix" >"$work/install.log"
cp "$here/CMakeLists.txt" "$here/../EmbeddingExample.cpp" "$work/src/"

# The two builds run side by side; each writes a log that a failure shows.
step "building the example with find_package(strata) and with pkg-config"
(
  "$CMAKE" -S "$work/src" -B "$work/cmake" -G "$GENERATOR" -DCMAKE_PREFIX_PATH="$prefix" \
    -DCMAKE_CXX_COMPILER="$CXX" -DCMAKE_CXX_FLAGS="$FLAGS" -DCMAKE_EXE_LINKER_FLAGS="$FLAGS"
  "$CMAKE" --build "$work/cmake"
) >"$work/cmake.log" 2>&1 &
cmake_build=$!
(
  export PKG_CONFIG_PATH=$prefix/$LIBDIR/pkgconfig
  set -x
  # shellcheck disable=SC2046,SC2086  # word splitting of the flags is meant
  "$CXX" -std=c++20 $FLAGS "$work/src/EmbeddingExample.cpp" -o "$work/pkg-config-example" \
    $(pkg-config --cflags --libs --static strata)
) >"$work/pkg-config.log" 2>&1 &
pkg_config_build=$!

failed=0
wait $cmake_build || { failed=1; echo "find_package build failed:"; cat "$work/cmake.log"; }
wait $pkg_config_build || { failed=1; echo "pkg-config build failed:"; cat "$work/pkg-config.log"; }
((failed == 0)) || exit 1

# Run from the scratch folder, away from the source and build trees.
cd "$work"
step "running the find_package build"
"$work/cmake/strata-embedding-example"
step "running the pkg-config build"
"$work/pkg-config-example"
step "both builds of the example passed"
# An ASan build's install and the two programs take about 1.5 GB; a failed
# run keeps them for a look.
rm -rf "$prefix" "$work/cmake" "$work/pkg-config-example"
