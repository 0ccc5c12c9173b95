#!/usr/bin/env bash
# Builds the .pdef decoder's libFuzzer target with clang (in build-fuzz/, instrumented with the address and
# undefined-behaviour sanitizers) and runs it for SECONDS (default 25) on the golden files as seeds. Crashes
# are written to build-fuzz/findings/; the exit status is libFuzzer's (non-zero on a finding).
#   scripts/fuzz.sh [SECONDS]
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
seconds=${1:-25}
"$root/scripts/deps.sh" --fuzz
launcher=()
if command -v ccache >/dev/null; then
  export CCACHE_BASEDIR="${CCACHE_BASEDIR:-$(dirname "$root")}"
  launcher=(-DCMAKE_CXX_COMPILER_LAUNCHER=ccache -DCMAKE_C_COMPILER_LAUNCHER=ccache)
fi
build="$root/build-fuzz"
CC=clang CXX=clang++ cmake -S "$root" -B "$build" -DCMAKE_BUILD_TYPE=RelWithDebInfo -DPDEFACE_BUILD_FUZZERS=ON \
  -DPDEFACE_BUILD_TESTS=OFF -DPDEFACE_BUILD_BENCHMARKS=OFF "${launcher[@]}" >/dev/null
cmake --build "$build" --target pdef_fuzz --parallel "$(nproc)"
corpus="$build/corpus"
mkdir -p "$corpus" "$build/findings"
cp "$root"/tests/data/pdef/*.pdef "$corpus/"
"$build/fuzz/pdef_fuzz" "$corpus" -max_total_time="$seconds" -max_len=65536 -timeout=10 -rss_limit_mb=2048 \
  -artifact_prefix="$build/findings/" -print_final_stats=1
