#!/usr/bin/env bash
# The main job on the built-in sample face: describe it, and convert it between formats.
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
"$root/scripts/deps.sh"
"$root/scripts/build.sh" --target pdeface
pdeface="$root/build/apps/pdeface/pdeface"
out="$root/build/demo"
mkdir -p "$out"

"$pdeface" sample "$out/sample.ply"
"$pdeface" info "$out/sample.ply"
for ext in wrl obj glb drc; do
  "$pdeface" convert "$out/sample.ply" "$out/sample.$ext"
done
"$pdeface" info "$out/sample.drc"
"$pdeface" align "$out/sample.glb" -o "$out/aligned.ply" --crop --preview "$out/aligned.svg" \
  --landmarks-out "$out/landmarks.json"
echo "demo outputs in $out"
