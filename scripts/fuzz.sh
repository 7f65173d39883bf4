#!/bin/sh
# Fuzzes strata's input parsers with libFuzzer under AddressSanitizer,
# LeakSanitizer and UndefinedBehaviorSanitizer for a bounded time each, and
# fails on any finding: the .csg parser, then the file readers behind
# import() and surface(), one target per format (STL, OBJ, OFF, PLY, DXF,
# SVG, surface .dat and PNG), text()'s glyphs, and strata-view's script
# language.
#
#   scripts/fuzz.sh [SECONDS [READER_SECONDS]]
#   scripts/fuzz.sh --geometry SECONDS
#
# SECONDS for the .csg parser (default 60, or STRATA_FUZZ_SECONDS),
# READER_SECONDS for each of the others (default 10, or
# STRATA_FUZZ_READER_SECONDS; 0 leaves them out). Builds tests/fuzz (targets strata_fuzz_csg and
# strata_fuzz_<format>) in build-fuzz/ with clang, every library instrumented
# (see tests/fuzz/CMakeLists.txt), then runs each on its seeds
# (tests/fuzz/corpus/ for the parser, tests/fuzz/seeds/<format>/ for the
# readers) plus what earlier runs found (build-fuzz/corpus-<target>/).
# A crash, leak, timeout, out-of-memory or sanitizer report stops the run with
# a non-zero status and leaves the input that caused it in
# build-fuzz/findings/<target>-*; replay it with
#   build-fuzz/tests/fuzz/strata_fuzz_<target> build-fuzz/findings/<file>
# --geometry builds and runs only strata_fuzz_geometry (small random trees
# built into meshes: 2D, extrusions, hulls, Minkowski sums, projections),
# for SECONDS. It instruments strata_model and the exact room's CGAL, many
# minutes of building, so CI does not run it; it is for long runs by hand.
# Needs Debian's clang and libclang-rt-14-dev (installed here when run as root).
set -eu

geometry=
if [ "${1:-}" = --geometry ]; then
    geometry=1
    shift
fi

seconds=${1:-${STRATA_FUZZ_SECONDS:-60}}
reader_seconds=${2:-${STRATA_FUZZ_READER_SECONDS:-10}}
readers="stl obj off ply dxf svg dat png text script"
[ "$reader_seconds" = 0 ] && readers=""
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
    -DSTRATA_BUILD_FUZZERS=ON -DSTRATA_BUILD_TESTS=ON -DSTRATA_SANITIZE=OFF -DSTRATA_FUZZ_GEOMETRY="${geometry:-OFF}" \
    -DCMAKE_C_FLAGS="$flags" -DCMAKE_CXX_FLAGS="$flags" >"$build/configure.log" 2>&1 ||
    { cat "$build/configure.log" >&2; echo "fuzz.sh: configuring $build failed" >&2; exit 2; }
targets=strata_fuzz_csg
for r in $readers; do targets="$targets strata_fuzz_$r"; done
[ -n "$geometry" ] && targets=strata_fuzz_geometry
# shellcheck disable=SC2086 # one word per target
cmake --build "$build" --target $targets -j "$jobs"

mkdir -p "$build/findings"
# One target for a bounded time: fuzz NAME SECONDS SEEDS [libFuzzer options].
# -timeout: one input taking longer than 10 s is a hang; -rss_limit_mb: memory
# must follow the input, not run away; ASan's leak check runs at every input's end.
fuzz() {
    name=$1 secs=$2 seeds=$3
    shift 3
    mkdir -p "$build/corpus-$name"
    echo "fuzz.sh: fuzzing $name for $secs s" >&2
    set +e
    ASAN_OPTIONS=${ASAN_OPTIONS:-detect_leaks=1:allocator_may_return_null=0} \
    UBSAN_OPTIONS=${UBSAN_OPTIONS:-print_stacktrace=1:halt_on_error=1} \
    "$build/tests/fuzz/strata_fuzz_$name" \
        -max_total_time="$secs" -timeout=10 -rss_limit_mb=2048 -max_len=65536 \
        -artifact_prefix="$build/findings/$name-" -print_final_stats=1 "$@" \
        "$build/corpus-$name" "$seeds" 2>"$build/fuzz-$name.log"
    status=$?
    set -e
    if [ "$status" -ne 0 ]; then
        tail -n 60 "$build/fuzz-$name.log" >&2
        echo "fuzz.sh: $name FAILED (status $status); full log: $build/fuzz-$name.log; reproducers:" >&2
        ls -1 "$build/findings" >&2
        exit 1
    fi
    grep -E '^(Done|stat::number_of_executed_units|stat::peak_rss_mb)' "$build/fuzz-$name.log" >&2 || true
}

if [ -n "$geometry" ]; then
    # An exact evaluation under the sanitizers takes up to minutes; more
    # memory than a parser.
    fuzz geometry "$seconds" "$root/tests/fuzz/seeds/geometry" -timeout=300 -rss_limit_mb=4096 -max_len=256
    echo "fuzz.sh: no findings (geometry $seconds s)" >&2
    exit 0
fi
fuzz csg "$seconds" "$root/tests/fuzz/corpus" -dict="$root/tests/fuzz/csg.dict"
for r in $readers; do
    fuzz "$r" "$reader_seconds" "$root/tests/fuzz/seeds/$r"
done
echo "fuzz.sh: no findings (the parser $seconds s, each reader ${reader_seconds} s)" >&2
