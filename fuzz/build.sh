#!/usr/bin/env bash
# Builds the libFuzzer targets (fuzz/CMakeLists.txt) with clang++-16 into build-fuzz/ (LK_FUZZ_BUILD to
# move it); cheap when up to date. LK_JOBS parallel jobs (default 2: the machine has 2 cores).
set -euo pipefail
source "$(dirname "${BASH_SOURCE[0]}")/../scripts/env.sh"
"$REPO_ROOT/scripts/install_deps.sh"
OUT="${LK_FUZZ_BUILD:-$REPO_ROOT/build-fuzz}"
mkdir -p "$OUT"
if [ ! -f "$OUT/CMakeCache.txt" ]; then
  CXX=clang++-16 cmake -S "$REPO_ROOT/fuzz" -B "$OUT" -DCMAKE_BUILD_TYPE=RelWithDebInfo >"$OUT/build.log" 2>&1 || {
    tail -n 30 "$OUT/build.log"; echo "[fuzz build] cmake failed; log: $OUT/build.log" >&2; exit 1; }
fi
cmake --build "$OUT" -j"${LK_JOBS:-2}" >>"$OUT/build.log" 2>&1 || {
  grep -E "error|Error" "$OUT/build.log" | tail -n 30
  echo "[fuzz build] failed; log: $OUT/build.log" >&2
  exit 1
}
echo "[fuzz build] ok ($OUT)"
