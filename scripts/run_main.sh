#!/usr/bin/env bash
# The main job: build (installing Debian packages if needed), then run the paper's Fig 6 case as the
# three ROS nodes (nodelets, lockstep), headless, and print the run summary. Extra arguments go to
# roslaunch (e.g. tau2:=1.9019505e-3, nodelets:=false for three processes). roslaunch's own output is
# kept in build/runs/main_roslaunch.log. The same run in-process: lk_simulate (see README).
set -euo pipefail
source "$(dirname "${BASH_SOURCE[0]}")/env.sh"
"$REPO_ROOT/scripts/build.sh" >/dev/null
set +u  # the ROS setup scripts read unset variables
source "$WS/devel/setup.bash"
set -u
mkdir -p "$BUILD_ROOT/runs"
# A private ROS master port, so that the job never joins someone else's roscore.
PORT=$((11400 + RANDOM % 500))
export ROS_MASTER_URI="http://localhost:$PORT"
OUT="$BUILD_ROOT/runs/main_roslaunch.log"
status=0
roslaunch -p "$PORT" lane_keeping closed_loop.launch nodelets:=true \
  scenario:="$REPO_ROOT/config/scenarios/fig6.yaml" log_file:="$BUILD_ROOT/runs/fig6.csv" "$@" >"$OUT" 2>&1 || status=$?
# The plant prints the summary block; show it (without colour codes) and any error.
sed -e 's/\x1b\[[0-9;]*m//g' "$OUT" | awk '/== lane_keeping run summary/{show=1} show && /^(loop messages|log):/{print; if ($1=="log:") show=0; next} show{print}'
if grep -q -E "FATAL|invalid configuration|run stopped|ERROR" "$OUT"; then
  sed -e 's/\x1b\[[0-9;]*m//g' "$OUT" | grep -E "FATAL|invalid configuration|run stopped|ERROR" | head -5
  echo "(full output: $OUT)"
  exit 1
fi
exit $status
