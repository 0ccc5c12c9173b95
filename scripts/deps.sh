#!/usr/bin/env bash
# Installs the Debian packages pdeface builds with, and only those missing. Safe to run again.
set -euo pipefail

packages=(
  build-essential cmake pkg-config
  libeigen3-dev libopenmesh-dev libtinygltf-dev libdraco-dev draco
  libfast-float-dev libstb-dev nlohmann-json3-dev libnanoflann-dev
  libmeshoptimizer-dev zlib1g-dev libzstd-dev libutfcpp-dev libturbojpeg0-dev
  libcli11-dev libfmt-dev libgtest-dev libgmock-dev libbenchmark-dev
  # The Python module (python/): pybind11, numpy; its tests and Dask batch: pytest, Dask distributed.
  python3-dev pybind11-dev python3-numpy python3-pytest python3-dask python3-distributed
)
# The tests also run the Khronos glTF validator on node (from Debian unless node is already there).
if [[ "${1:-}" == "--test" ]] && ! { command -v node && command -v npm; } >/dev/null; then
  packages+=(nodejs npm)
fi
# ... and show GLBs in three.js in headless Chromium (tools/gltf_viewer: a face shows its photo).
if [[ "${1:-}" == "--test" ]]; then
  packages+=(chromium)
fi

# scripts/fuzz.sh: clang and its runtime libraries (libFuzzer, sanitizers).
if [[ "${1:-}" == "--fuzz" ]]; then
  packages+=(clang libclang-rt-14-dev)
fi

missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if ((${#missing[@]})); then
  echo "pdeface: installing ${missing[*]}" >&2
  sudo=""; [[ $(id -u) -eq 0 ]] || sudo="sudo"
  $sudo apt-get update -qq
  DEBIAN_FRONTEND=noninteractive $sudo apt-get install -y -qq "${missing[@]}" >/dev/null
fi
