#!/usr/bin/env bash
# The main job on the built-in sample face: pdeface compare (PDE against Draco, decimation + Draco and raw
# meshes, in size and fidelity) and the top of its report; then the steps one by one: describe the face,
# convert it between formats, align it, slice it into profile curves and rebuild it as a PDE surface.
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
"$root/scripts/deps.sh"
"$root/scripts/build.sh" --target pdeface
pdeface="$root/build/apps/pdeface/pdeface"
out="$root/build/demo"
mkdir -p "$out"

(cd "$out" && "$pdeface" compare --quiet)
# The top of the report: its first lines and the summary table.
sed -n '1,3p;/^## Summary across scans/,/^$/p;/^| variant | scans/,/^$/p' "$out/pdeface-report/report.md" | uniq
echo "the whole report: $out/pdeface-report/report.html"

"$pdeface" sample "$out/sample.ply"
"$pdeface" info "$out/sample.ply"
for ext in wrl obj glb drc; do
  "$pdeface" convert "$out/sample.ply" "$out/sample.$ext"
done
"$pdeface" info "$out/sample.drc"
"$pdeface" align "$out/sample.glb" -o "$out/aligned.ply" --crop --preview "$out/aligned.svg" \
  --landmarks-out "$out/landmarks.json"
"$pdeface" profiles "$out/sample.glb" -o "$out/profiles.json" --svg "$out/profiles.svg"
"$pdeface" reconstruct "$out/sample.glb" -o "$out/sample_pde.glb" --profiles "$out/curves.json"
"$pdeface" table "$out/sample.ply" --ratios 0.05,0.1,0.2,0.3 -o "$out/table.md" --csv "$out/table.csv"
sed -n '/## Profile error (mm)/,/## Profile error on/p' "$out/table.md" | head -n -1
echo "demo outputs in $out"
