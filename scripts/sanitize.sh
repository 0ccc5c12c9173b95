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
cd "$build"
ctest --output-on-failure --parallel "$(nproc)" --timeout 900 "$@"
