#!/usr/bin/env bash
# Builds the libFuzzer targets (fuzz/: one per reader, the .pdef decoder, and the whole path) with clang in
# build-san/ (address and undefined-behaviour sanitizers; shared with scripts/sanitize.sh) and runs each for
# SECONDS (default 25), seeded with tests/data/ and with those fixtures converted to every format. A target's
# corpus grows in build-san/corpus/<target>/ across runs; crashes, leaks, timeouts (> 10 s for one input; 30
# for Draco, glTF and .pdef, 60 for the whole path) and inputs that need more than 2 GB are written to
# build-san/findings/. The exit status is non-zero if any target found something. TARGETS (default: all)
# limits the run, e.g.
#   scripts/fuzz.sh 600 obj_fuzz ply_fuzz
set -euo pipefail
seconds=${1:-25}
shift || true
source "$(dirname "$0")/lib/build-san.sh"
all=(vrml_fuzz obj_fuzz ply_fuzz off_fuzz stl_fuzz gltf_fuzz draco_fuzz pdef_fuzz path_fuzz)
targets=("${@:-${all[@]}}")
cmake --build "$build" --target fuzzers pdeface --parallel "$(nproc)"
data="$root/tests/data"
seeds="$build/seeds"
if [[ ! -d "$seeds" ]]; then # the fixtures as they are, and each mesh fixture in every writable format
  mkdir -p "$seeds"/{vrml,obj,ply,off,stl,gltf,draco,pdef}
  cp "$data"/vrml/*.wrl "$seeds/vrml/"; cp "$data"/obj/*.obj "$seeds/obj/"; cp "$data"/ply/*.ply "$seeds/ply/"
  cp "$data"/off/*.off "$seeds/off/"; cp "$data"/stl/*.stl "$seeds/stl/"; cp "$data"/gltf/*.gl* "$seeds/gltf/"
  cp "$data"/draco/*.drc "$seeds/draco/"; cp "$data"/pdef/*.pdef "$seeds/pdef/"
  for f in "$data"/vrml/v2_attributes.wrl "$data"/obj/*.obj "$data"/ply/attributes_ascii.ply; do
    name=$(basename "${f%.*}")
    for out in vrml/$name.wrl obj/$name.obj ply/$name.ply ply/${name}_ascii.ply:--ascii off/$name.off \
      stl/$name.stl stl/${name}_ascii.stl:--ascii gltf/$name.glb gltf/$name.gltf gltf/${name}_draco.glb:--draco \
      draco/$name.drc draco/${name}_0.drc:--draco-level=0; do
      option=(); [[ $out == *:* ]] && option=("${out#*:}")
      "$build/apps/pdeface/pdeface" convert "$f" "$seeds/${out%%:*}" "${option[@]}" >/dev/null 2>&1 || true
    done
  done
fi
declare -A corpus_of=([vrml_fuzz]=vrml [obj_fuzz]=obj [ply_fuzz]=ply [off_fuzz]=off [stl_fuzz]=stl
  [gltf_fuzz]=gltf [draco_fuzz]=draco [pdef_fuzz]=pdef [path_fuzz]="vrml obj ply off stl gltf draco pdef")
mkdir -p "$build/findings"
failed=()
for target in "${targets[@]}"; do
  corpus="$build/corpus/$target"
  mkdir -p "$corpus"
  dirs=()
  for d in ${corpus_of[$target]}; do dirs+=("$seeds/$d"); done
  # Seconds one input may take: the whole path runs landmark detection; libdraco (Draco files, and Draco
  # data in glTF) has known slow paths, bounded but not fail-fast; a .pdef input is decoded and encoded up
  # to three times, each encoding's surface checks bounded (about 3 s under the sanitizers at most on a
  # face of 4096 samples; docs/robustness.md).
  timeout=10; [[ $target == path_fuzz ]] && timeout=60; [[ $target == draco_fuzz || $target == gltf_fuzz || $target == pdef_fuzz ]] && timeout=30
  dict=(); [[ -f "$root/fuzz/${target%_fuzz}.dict" ]] && dict=(-dict="$root/fuzz/${target%_fuzz}.dict")
  echo "pdeface: fuzzing $target for $seconds s" >&2
  if ! "$build/fuzz/$target" "$corpus" "${dirs[@]}" "${dict[@]}" -max_total_time="$seconds" -max_len=65536 \
      -timeout="$timeout" -rss_limit_mb=2048 -artifact_prefix="$build/findings/$target-" -print_final_stats=1 \
      >"$build/findings/$target.log" 2>&1; then
    failed+=("$target")
    tail -n 60 "$build/findings/$target.log" >&2
  fi
  grep -E "^(stat::number_of_executed_units|stat::peak_rss_mb)|cov: .* ft: " "$build/findings/$target.log" |
    tail -n 3 >&2 || true
done
if ((${#failed[@]})); then
  echo "pdeface: fuzzing found something in: ${failed[*]} (build-san/findings/)" >&2
  exit 1
fi
echo "pdeface: ${#targets[@]} fuzz targets ran ${seconds} s each, nothing found" >&2
