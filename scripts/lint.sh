#!/usr/bin/env bash
# The checks CI runs beside the tests: every C++ source formatted as .clang-format says, and clang-tidy
# (.clang-tidy: naming, bug-prone and performance checks, warnings as errors) clean on the library and the
# command line. Needs a configured build/ (compile_commands.json): run scripts/test.sh or scripts/build.sh
# first. Usage: scripts/lint.sh [--format-only]
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
cd "$root"
mapfile -t sources < <(git ls-files '*.cpp' '*.hpp')
echo "pdeface: clang-format on ${#sources[@]} files" >&2
clang-format --dry-run --Werror "${sources[@]}"
[[ "${1:-}" == "--format-only" ]] && exit 0
[[ -f build/compile_commands.json ]] || { echo "pdeface: no build/compile_commands.json; build first" >&2; exit 2; }
echo "pdeface: clang-tidy on modules/, formats/, pipeline/, apps/" >&2
run-clang-tidy -p build -j "$(nproc)" -quiet "$root/(modules|formats|pipeline|apps)/.*\\.cpp\$" >build/clang-tidy.log 2>&1 ||
  { grep -E "(warning|error):" build/clang-tidy.log | sort -u >&2; echo "pdeface: clang-tidy failed (build/clang-tidy.log)" >&2; exit 1; }
