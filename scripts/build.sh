#!/usr/bin/env bash
# Builds lane_keeping in a catkin workspace outside the source tree:
#   build/ws/src/lane_keeping -> the repository (the repo root is the package).
# Usage: scripts/build.sh [extra catkin_make arguments, e.g. tests]
set -euo pipefail
source "$(dirname "${BASH_SOURCE[0]}")/env.sh"
"$REPO_ROOT/scripts/install_deps.sh"
mkdir -p "$WS/src"
if [ ! -e "$WS/src/lane_keeping" ]; then
  ln -s "$REPO_ROOT" "$WS/src/lane_keeping"
fi
cd "$WS"
JOBS="${LK_JOBS:-$(nproc)}"
# Always build every target first (tools must not go stale against a rebuilt library), then any
# extra targets asked for (e.g. tests).
{ catkin_make -DCMAKE_BUILD_TYPE=Release -DPYTHON_EXECUTABLE=/usr/bin/python3 -j"$JOBS" &&
  { [ $# -eq 0 ] || catkin_make -DCMAKE_BUILD_TYPE=Release -DPYTHON_EXECUTABLE=/usr/bin/python3 -j"$JOBS" "$@"; }
} >"$BUILD_ROOT/catkin_make.log" 2>&1 || {
  tail -n 60 "$BUILD_ROOT/catkin_make.log"
  echo "[build] catkin_make failed; full log: $BUILD_ROOT/catkin_make.log" >&2
  exit 1
}
echo "[build] ok ($WS)"
