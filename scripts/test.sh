#!/usr/bin/env bash
# Builds everything and runs the whole test suite. Real scans come from $PDEFACE_DATA (default
# ../shared/faces); the tests that need them are skipped, saying so, when they are absent.
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
"$root/scripts/deps.sh" --test
# The Khronos glTF validator (npm package gltf-validator) for the GLB tests; they skip without it.
if command -v npm >/dev/null && [[ ! -d "$root/build/tools/node_modules/gltf-validator" ]]; then
  npm install --silent --no-audit --no-fund --prefix "$root/build/tools" gltf-validator >/dev/null 2>&1 ||
    echo "pdeface: could not install gltf-validator; the validator tests will be skipped" >&2
fi
# three.js and playwright-core for the viewer tests (tools/gltf_viewer; Debian's chromium, no download).
if command -v npm >/dev/null && [[ ! -d "$root/tools/gltf_viewer/node_modules/three" ]]; then
  npm install --silent --no-audit --no-fund --prefix "$root/tools/gltf_viewer" >/dev/null 2>&1 ||
    echo "pdeface: could not install the glTF viewer's packages; the viewer tests will be skipped" >&2
fi
"$root/scripts/build.sh"
cd "$root/build"
ctest --output-on-failure --parallel "$(nproc)" --timeout 300
