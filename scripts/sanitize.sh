#!/usr/bin/env bash
# Builds the test suite and the command with the address and undefined-behaviour sanitizers (clang, in
# build-san/, shared with scripts/fuzz.sh) and runs every test: a memory error, a leak or undefined
# behaviour anywhere fails the test that met it. Extra arguments go to ctest (e.g. -R formats).
#   scripts/sanitize.sh [CTEST ARGS...]
set -euo pipefail
source "$(dirname "$0")/lib/build-san.sh"
# The Khronos glTF validator for the GLB tests (they skip without it), as scripts/test.sh installs it.
if command -v npm >/dev/null && [[ ! -d "$build/tools/node_modules/gltf-validator" ]]; then
  npm install --silent --no-audit --no-fund --prefix "$build/tools" gltf-validator >/dev/null 2>&1 ||
    echo "pdeface: could not install gltf-validator; the validator tests will be skipped" >&2
fi
cmake --build "$build" --parallel "$(nproc)"
# The real scans: under the sanitizers every test that aligns one takes about a minute, and 24 scans in
# several suites would take over an hour on 2 cores. So the suite runs on 4 of them — Draco, PLY (the
# point cloud), VRML (in metres, cut) and GLB (ICT, holes) — so that CI stays well under an hour; the OBJ
# reader is under the sanitizers through its fixtures and fuzz target. The tests of the other 20 are
# skipped, saying so. PDEFACE_SANITIZE_FACES=all runs them all.
faces="${PDEFACE_DATA:-$root/../shared/faces}"
if [[ -d "$faces" && "${PDEFACE_SANITIZE_FACES:-}" != all ]]; then
  subset="$build/faces"
  rm -rf "$subset"
  mkdir -p "$subset"
  for scan in facefuns_f56_points.ply facefuns_m46.drc fran_cut.wrl ict_02.glb MANIFEST.md; do
    [[ -e "$faces/$scan" ]] && ln -s "$(cd "$faces" && pwd)/$scan" "$subset/$scan"
  done
  export PDEFACE_DATA="$subset"
fi
cd "$build"
# Four tests run whole jobs through the command (the main compare job on the sample face, a compare batch,
# two tables: 5-15 minutes each under the sanitizers); the library code they drive runs under the
# sanitizers in compare_test and table_test, and the jobs themselves in scripts/test.sh.
whole_jobs="Cli\.(CompareWithNoInputIsTheMainJob|CompareBatchReportsABadScanAndCompletesTheOthers|Table.*)$"
ctest --output-on-failure --parallel "$(nproc)" --timeout 900 -E "$whole_jobs" "$@"
