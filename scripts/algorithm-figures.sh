#!/usr/bin/env bash
# Regenerates the pictures of docs/algorithm.md (docs/images/algorithm/*.png)
# and of docs/embedding.md (docs/images/embedding/embedding.png), rendered by
# strata itself through its public API:
#
#   scripts/algorithm-figures.sh
#
# It builds build/ (Release; STRATA_BUILD_DIR picks another) as far as the two
# programs in tests/embedding/, runs strata-algorithm-figures (which prints the
# figures the document quotes, and fails if a picture would contradict the
# document) and the embedding example (which checks its own results).
# Headless: EGL on Mesa llvmpipe suffices.
set -euo pipefail
cd "$(dirname "$0")/.."

build=${STRATA_BUILD_DIR:-build}
if [[ ! -f $build/build.ninja ]]; then
  cmake -S . -B "$build" -G Ninja -DCMAKE_BUILD_TYPE=Release >/dev/null
fi
cmake --build "$build" -j "${STRATA_JOBS:-$(nproc)}" --target strata-algorithm-figures strata-embedding-example

rm -f docs/images/algorithm/*.png docs/images/embedding/*.png
"$build/tests/embedding/strata-algorithm-figures" docs/images/algorithm
"$build/tests/embedding/strata-embedding-example" docs/images/embedding
echo "algorithm-figures: wrote docs/images/algorithm/ and docs/images/embedding/"
