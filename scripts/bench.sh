#!/usr/bin/env bash
# Builds Release and prints one table: every stage of issue 21 (encode, decode to PLY from 21k to 1M
# vertices, landmark detection, compare per scan, peak memory, .pdef -> mesh in process, the readers),
# pdeface against draco_encoder / draco_decoder / libdraco in the same run, as ratios (docs/performance.md
# explains every row). Needs the real scans ($PDEFACE_DATA, default ../shared/faces). Takes ~8 minutes
# on 2 cores (--quick: ~1). --smoke (CI): every benchmark program once for a few iterations, no table,
# no judgement of time (~30 s: compare_bench runs one comparison).
# Usage: scripts/bench.sh [--quick] [--runs N] [--json FILE] [--smoke]
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
"$root/scripts/deps.sh"
if [[ " $* " == *" --smoke "* ]]; then
  "$root/scripts/build.sh" >/dev/null # every benchmark program
else
  "$root/scripts/build.sh" --target pdeface pdef_bench align_bench readers_bench >/dev/null
fi
exec python3 "$root/scripts/bench.py" "$@"
