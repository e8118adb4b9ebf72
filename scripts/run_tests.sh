#!/usr/bin/env bash
# Every test: build (with test targets), run all gtest and rostest targets, print the verdict.
set -euo pipefail
source "$(dirname "${BASH_SOURCE[0]}")/env.sh"
"$REPO_ROOT/scripts/build.sh" tests
cd "$WS"
rm -rf "$WS/build/test_results/lane_keeping"
set +e
catkin_make -DCMAKE_BUILD_TYPE=Release -DPYTHON_EXECUTABLE=/usr/bin/python3 -j1 run_tests >"$BUILD_ROOT/run_tests.log" 2>&1
set -e
grep -E "^\[( +OK|  FAILED|  PASSED|==========)|FAILURE|ERROR|rostest" "$BUILD_ROOT/run_tests.log" | grep -v "^\[       OK" | tail -n 80 || true
catkin_test_results --verbose "$WS/build/test_results" | tail -n 40
