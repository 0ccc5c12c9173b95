# Sourced by scripts/sanitize.sh and scripts/fuzz.sh: configures build-san/, the one build both use, with
# clang, every target instrumented with the address and undefined-behaviour sanitizers (any finding fatal)
# and libFuzzer's coverage, at -O1 with assertions on. Defines $root and $build.
root=$(cd "$(dirname "${BASH_SOURCE[0]}")/../.." && pwd)
build="$root/build-san"
"$root/scripts/deps.sh" --fuzz
launcher=()
if command -v ccache >/dev/null; then
  export CCACHE_BASEDIR="${CCACHE_BASEDIR:-$(dirname "$root")}"
  launcher=(-DCMAKE_CXX_COMPILER_LAUNCHER=ccache -DCMAKE_C_COMPILER_LAUNCHER=ccache)
fi
CC=clang CXX=clang++ cmake -S "$root" -B "$build" -DCMAKE_BUILD_TYPE=Sanitize -DCMAKE_CXX_FLAGS_SANITIZE="-O1 -gline-tables-only" \
  -DPDEFACE_SANITIZE=ON -DPDEFACE_BUILD_FUZZERS=ON -DPDEFACE_BUILD_TESTS=ON -DPDEFACE_BUILD_BENCHMARKS=OFF \
  "${launcher[@]}" >/dev/null
# Any finding ends the program with a report (UBSan included: -fno-sanitize-recover); leaks are findings.
export ASAN_OPTIONS="${ASAN_OPTIONS:-detect_leaks=1:abort_on_error=0:allocator_may_return_null=0}"
export UBSAN_OPTIONS="${UBSAN_OPTIONS:-print_stacktrace=1:halt_on_error=1}"
# OpenMesh 9 leaks 48 bytes once per process (tests/formats/ply/openmesh_lsan.supp says why).
export LSAN_OPTIONS="${LSAN_OPTIONS:-suppressions=$root/tests/formats/ply/openmesh_lsan.supp:print_suppressions=0}"
