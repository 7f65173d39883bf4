#!/usr/bin/env bash
# Sets up, builds both flavours (Release, and ASan+UBSan) and runs the whole
# test suite in each, then the parsers' fuzzers for a bounded time each.
#   STRATA_FUZZ_SECONDS=0 scripts/test.sh   skips the fuzzers
set -euo pipefail
cd "$(dirname "$0")/.."

scripts/deps.sh

export LSAN_OPTIONS="suppressions=$(pwd)/tests/lsan.supp:print_suppressions=0"
# intercept_tls_get_addr=0: LeakSanitizer's record of the dynamic TLS of
# dlopen'ed libraries (Mesa's driver) can hold a garbage range ("DTLS 41 at
# 0x30f4-0x18000041f6" with LSAN_OPTIONS=verbosity=1), and its exit-time check
# then dies on it ("Tracer caught signal 11") after the test has passed. Not
# tracking it only leaves those blocks out of the roots of the leak search:
# it can add leak reports, never hide one.
export ASAN_OPTIONS="detect_leaks=1:abort_on_error=1:intercept_tls_get_addr=0"
export UBSAN_OPTIONS="print_stacktrace=1:halt_on_error=1"

# The window tests need an X display: give them a virtual one when there is none.
# -noreset: by default Xvfb resets itself whenever its last client leaves, and
# a client that connects during that reset is dropped before its setup is
# answered ("Failed to open display"). Parallel tests open and close the
# display all the time, so without it a window test fails now and then.
run_ctest=(ctest)
if [[ -z ${DISPLAY:-} ]] && command -v xvfb-run >/dev/null; then
  run_ctest=(xvfb-run -a -s "-screen 0 1280x1024x24 -noreset" ctest)
fi

# In each tree only the whole runs (ctest label `whole`, see
# tests/CMakeLists.txt): each test binary in one to four processes, and the
# embedding example. The same tests as a plain ctest, which gives every test
# a process of its own and pays a process's start over a thousand times.
phase() { echo "== strata: $1 (at ${SECONDS} s)"; }
for flavour in release asan; do
  phase "$flavour build"
  scripts/build.sh "$flavour"
  dir=build; [[ $flavour == asan ]] && dir=build-asan
  phase "$flavour tests"
  "${run_ctest[@]}" --test-dir "$dir" --output-on-failure -j "$(nproc)" --timeout 900 -L whole
done

fuzz_seconds=${STRATA_FUZZ_SECONDS:-30}
reader_seconds=${STRATA_FUZZ_READER_SECONDS:-5}
if [[ $fuzz_seconds != 0 && -x scripts/fuzz.sh ]]; then
  phase "fuzzing the .csg parser for ${fuzz_seconds}s and each file reader for ${reader_seconds}s"
  scripts/fuzz.sh "$fuzz_seconds" "$reader_seconds"
fi
phase "all tests passed"
