#!/bin/sh
# Fuzzes the .csg parser with libFuzzer under AddressSanitizer, LeakSanitizer and
# UndefinedBehaviorSanitizer for a bounded time, and fails on any finding.
#
#   scripts/fuzz.sh [SECONDS]        (default 60; or set STRATA_FUZZ_SECONDS)
#
# Builds tests/fuzz (target strata_fuzz_csg) in build-fuzz/ with clang, every
# library instrumented (see tests/fuzz/CMakeLists.txt), then runs it on the seeds
# in tests/fuzz/corpus/ plus what earlier runs found (build-fuzz/corpus/).
# A crash, leak, timeout, out-of-memory or sanitizer report stops the run with a
# non-zero status and leaves the input that caused it in build-fuzz/findings/;
# replay it with:  build-fuzz/tests/fuzz/strata_fuzz_csg build-fuzz/findings/<file>
# Needs Debian's clang and libclang-rt-14-dev (installed here when run as root).
set -eu

seconds=${1:-${STRATA_FUZZ_SECONDS:-60}}
root=$(cd "$(dirname "$0")/.." && pwd)
build=$root/build-fuzz
jobs=${STRATA_JOBS:-2}

# Debian's libFuzzer runtime (libclang-rt-14-dev) lives beside clang's other runtimes.
fuzzer_runtime_present() {
    ls /usr/lib/llvm-*/lib/clang/*/lib/linux/libclang_rt.fuzzer-x86_64.a >/dev/null 2>&1
}

if ! command -v clang++ >/dev/null 2>&1 || ! fuzzer_runtime_present; then
    if [ "$(id -u)" = 0 ] && command -v apt-get >/dev/null 2>&1; then
        echo "fuzz.sh: installing clang and libclang-rt-14-dev" >&2
        apt-get install -y --no-install-recommends clang libclang-rt-14-dev >/dev/null ||
            { apt-get update >/dev/null && apt-get install -y --no-install-recommends clang libclang-rt-14-dev >/dev/null; }
    else
        echo "fuzz.sh: needs clang and libFuzzer: apt-get install clang libclang-rt-14-dev" >&2
        exit 2
    fi
fi

flags="-fsanitize=fuzzer-no-link,address,undefined -fno-sanitize-recover=undefined -fno-omit-frame-pointer"
# Configure every time (a few seconds): picks up new sources and keeps the flags.
mkdir -p "$build"
CC=clang CXX=clang++ cmake -S "$root" -B "$build" -G Ninja -DCMAKE_BUILD_TYPE=RelWithDebInfo \
    -DSTRATA_BUILD_FUZZERS=ON -DSTRATA_BUILD_TESTS=ON -DSTRATA_SANITIZE=OFF \
    -DCMAKE_C_FLAGS="$flags" -DCMAKE_CXX_FLAGS="$flags" >"$build/configure.log" 2>&1 ||
    { cat "$build/configure.log" >&2; echo "fuzz.sh: configuring $build failed" >&2; exit 2; }
cmake --build "$build" --target strata_fuzz_csg -j "$jobs"

mkdir -p "$build/corpus" "$build/findings"
echo "fuzz.sh: fuzzing the .csg parser for $seconds s" >&2
# -timeout: one input taking longer than 10 s is a hang; -rss_limit_mb: memory
# must follow the tree, not run away; ASan's leak check runs at every input's end.
set +e
ASAN_OPTIONS=${ASAN_OPTIONS:-detect_leaks=1:allocator_may_return_null=0} \
UBSAN_OPTIONS=${UBSAN_OPTIONS:-print_stacktrace=1:halt_on_error=1} \
"$build/tests/fuzz/strata_fuzz_csg" \
    -max_total_time="$seconds" -timeout=10 -rss_limit_mb=2048 -max_len=65536 \
    -dict="$root/tests/fuzz/csg.dict" -artifact_prefix="$build/findings/" \
    -print_final_stats=1 "$build/corpus" "$root/tests/fuzz/corpus" 2>"$build/fuzz.log"
status=$?
set -e
if [ "$status" -ne 0 ]; then
    tail -n 60 "$build/fuzz.log" >&2
    echo "fuzz.sh: FAILED (status $status); full log: $build/fuzz.log; reproducers:" >&2
    ls -1 "$build/findings" >&2
    exit 1
fi
grep -E '^(Done|stat::)' "$build/fuzz.log" >&2 || true
echo "fuzz.sh: no findings in $seconds s (log: $build/fuzz.log)" >&2
