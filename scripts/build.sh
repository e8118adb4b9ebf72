#!/usr/bin/env bash
# Builds lane_keeping in a catkin workspace outside the source tree:
#   build/ws/src/lane_keeping -> the repository (the repo root is the package).
# Usage: scripts/build.sh [--sanitize] [extra catkin_make arguments, e.g. tests]
#   --sanitize: clang-16 with AddressSanitizer + UndefinedBehaviorSanitizer (any report aborts) and libFuzzer's
#   coverage, with debug info, in its own workspace build-sanitize/ws: the sanitized gtests
#   (scripts/run_sanitized_tests.sh) and the fuzz targets (fuzz/run.sh) are built there.
set -euo pipefail
SANITIZE=0
if [ "${1:-}" = "--sanitize" ]; then
  SANITIZE=1
  shift
  export LK_BUILD_ROOT="${LK_BUILD_ROOT:-$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)/build-sanitize}"
fi
source "$(dirname "${BASH_SOURCE[0]}")/env.sh"
"$REPO_ROOT/scripts/install_deps.sh"
# The package folder holds a symlink to each top-level entry of the repository except build
# directories and .git: a symlink to the whole repository would let ROS's package crawler (roslaunch,
# rostest, <node pkg=...>) walk build/ws/src/lane_keeping/build/ws/... without end.
PKG="$WS/src/lane_keeping"
if [ -L "$PKG" ]; then rm "$PKG"; fi
mkdir -p "$PKG"
for entry in "$REPO_ROOT"/* "$REPO_ROOT"/.[!.]*; do
  name="$(basename "$entry")"
  case "$name" in build|build-*|.git|.ci) continue ;; esac
  [ -e "$PKG/$name" ] || ln -s "$entry" "$PKG/$name"
done
for link in "$PKG"/*; do  # drop links to entries that no longer exist
  [ -L "$link" ] && [ ! -e "$link" ] && rm "$link"
done
cd "$WS"
# catkin writes the environment of its test targets (build/catkin_generated/setup_cached.sh) at
# configure time and lists only the devel folders that exist then: on a fresh workspace the
# generated Python messages would be missing from the rostests' PYTHONPATH. Create them first.
mkdir -p "$WS/devel/lib/python3/dist-packages" "$WS/devel/lib/pkgconfig"
JOBS="${LK_JOBS:-$(nproc)}"
CMAKE_ARGS=(-DCMAKE_BUILD_TYPE=Release -DPYTHON_EXECUTABLE=/usr/bin/python3)
# ccache (Debian's package, installed by install_deps.sh): a rebuild after a branch switch, a fresh clone or a
# `git worktree` compiles only what changed. base_dir makes the cache's keys relative to the checkout.
LAUNCHER=()
if command -v ccache >/dev/null 2>&1; then
  export CCACHE_BASEDIR="${CCACHE_BASEDIR:-$(dirname "$REPO_ROOT")}"
  LAUNCHER=(-DCMAKE_CXX_COMPILER_LAUNCHER=ccache -DCMAKE_C_COMPILER_LAUNCHER=ccache)
fi
CMAKE_ARGS+=("${LAUNCHER[@]}")
if [ "$SANITIZE" = 1 ]; then
  # clang-16, so that one build serves the sanitized gtests and the libFuzzer targets (fuzz/CMakeLists.txt):
  # every object has the sanitizers; what the harnesses link (lane_keeping_core, the gap readers, the bag reader)
  # also has libFuzzer's coverage instrumentation (-fsanitize=fuzzer-no-link, fuzz/CMakeLists.txt; in a binary
  # without libFuzzer, as the gtests, its hooks are the sanitizer runtime's no-ops), only the harnesses link
  # libFuzzer.
  SAN="-fsanitize=address,undefined -fno-sanitize-recover=undefined -fno-omit-frame-pointer"
  # The build has debug info (-g, for the sanitizers' stack traces), which holds the compiler's working directory:
  # ccache then keys every object on that directory, so no two clones shared one (issue 45: a fresh clone missed
  # the cache for every sanitized object). Mapped to the repository's root as `.`, the directory
  # (./build-sanitize/ws/build/lane_keeping) is the same in every clone, ccache leaves it out of the key, and a
  # report's paths read from the repository's root.
  DEBUG_MAP="-fdebug-prefix-map=$REPO_ROOT=."
  CMAKE_ARGS=(-DCMAKE_BUILD_TYPE=RelWithDebInfo -DPYTHON_EXECUTABLE=/usr/bin/python3 -DCMAKE_CXX_COMPILER=clang++-16
              "-DCMAKE_CXX_FLAGS=$SAN $DEBUG_MAP" "-DCMAKE_EXE_LINKER_FLAGS=$SAN"
              "-DCMAKE_SHARED_LINKER_FLAGS=$SAN" -DLANE_KEEPING_FUZZ_TARGETS=ON "${LAUNCHER[@]}")
  # A workspace configured for another compiler (gcc, before issue 45) starts afresh: CMake cannot switch.
  if [ -f "$WS/build/CMakeCache.txt" ] && ! grep -q '^CMAKE_CXX_COMPILER:.*clang++-16$' "$WS/build/CMakeCache.txt"; then
    rm -rf "$WS/build" "$WS/devel"
    mkdir -p "$WS/devel/lib/python3/dist-packages" "$WS/devel/lib/pkgconfig"
  fi
fi
# Always build every target first (tools must not go stale against a rebuilt library), then any
# extra targets asked for (e.g. tests).
# (The sanitizer variant builds only the targets asked for, when any are: it is slow, and only tests run in it.)
if [ "$SANITIZE" = 1 ] && [ $# -gt 0 ]; then FIRST=("$@"); else FIRST=(); fi
{ catkin_make "${CMAKE_ARGS[@]}" -j"$JOBS" "${FIRST[@]}" &&
  { [ $# -eq 0 ] || [ ${#FIRST[@]} -gt 0 ] || catkin_make "${CMAKE_ARGS[@]}" -j"$JOBS" "$@"; }
} >"$BUILD_ROOT/catkin_make.log" 2>&1 || {
  tail -n 60 "$BUILD_ROOT/catkin_make.log"
  echo "[build] catkin_make failed; full log: $BUILD_ROOT/catkin_make.log" >&2
  exit 1
}
# A workspace configured before that fix still has the empty PYTHONPATH: reconfigure it once.
if ! grep -q "^export PYTHONPATH='.*dist-packages" "$WS/build/catkin_generated/setup_cached.sh"; then
  (cd "$WS/build" && cmake . >>"$BUILD_ROOT/catkin_make.log" 2>&1)
fi
echo "[build] ok ($WS)"
