#!/usr/bin/env bash
# The main job: build, then run the paper's Fig 6 case headless and print the summary.
# Extra arguments go to lk_simulate (e.g. --set tracker.k_y=0.15).
set -euo pipefail
source "$(dirname "${BASH_SOURCE[0]}")/env.sh"
"$REPO_ROOT/scripts/build.sh" >/dev/null
mkdir -p "$BUILD_ROOT/runs"
"$WS/devel/lib/lane_keeping/lk_simulate" --config "$REPO_ROOT/config/scenarios/fig6.yaml" \
  --out "$BUILD_ROOT/runs/fig6.csv" "$@"
