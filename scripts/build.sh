#!/usr/bin/env bash
# Configures and builds one flavour of strata.
#   scripts/build.sh release   -> build/       (Release)
#   scripts/build.sh asan      -> build-asan/  (Debug: AddressSanitizer + UBSan, synchronous KHR_debug checks)
# Incremental: a second run with nothing changed takes seconds.
set -euo pipefail
cd "$(dirname "$0")/.."

flavour=${1:-release}
jobs=${STRATA_JOBS:-$(nproc)}
case "$flavour" in
  release) dir=build;      args=(-DCMAKE_BUILD_TYPE=Release) ;;
  asan)    dir=build-asan; args=(-DCMAKE_BUILD_TYPE=Debug -DSTRATA_SANITIZE=ON) ;;
  *) echo "usage: scripts/build.sh release|asan" >&2; exit 2 ;;
esac

if [[ ! -f $dir/build.ninja ]]; then
  cmake -S . -B "$dir" -G Ninja "${args[@]}" >/dev/null
fi
cmake --build "$dir" -j "$jobs"
