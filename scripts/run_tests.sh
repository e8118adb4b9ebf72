#!/usr/bin/env bash
# Every test: build (with test targets), run all gtest and rostest targets, print the verdict; then the
# fuzz targets over their corpora and regressions (fuzz/run.sh); then the core and stability gtests under
# the sanitizers (scripts/run_sanitized_tests.sh).
set -euo pipefail
source "$(dirname "${BASH_SOURCE[0]}")/env.sh"
"$REPO_ROOT/scripts/build.sh" tests
cd "$WS"
rm -rf "$WS/build/test_results/lane_keeping"
set +e
catkin_make -DCMAKE_BUILD_TYPE=Release -DPYTHON_EXECUTABLE=/usr/bin/python3 -j1 run_tests >"$BUILD_ROOT/run_tests.log" 2>&1
set -e
grep -E "^\[( +OK|  FAILED|  PASSED|==========)|FAILURE|ERROR|rostest" "$BUILD_ROOT/run_tests.log" | grep -v "^\[       OK" | tail -n 80 || true
set +e
catkin_test_results --verbose "$WS/build/test_results" | tail -n 40
tests_status=${PIPESTATUS[0]}
# The libFuzzer targets (fuzz/, docs/fuzzing.md): built with clang in build-fuzz/, each run over its seed
# corpus and its regression inputs, then fuzzed for 20,000 inputs or 30 s; any finding fails the tests.
echo "== fuzz targets: corpus + regressions + 20000 inputs or 30 s each"
LK_FUZZ_MAX_TIME="${LK_FUZZ_MAX_TIME:-30}" bash "$REPO_ROOT/fuzz/run.sh" 20000
fuzz_status=$?
# The core and stability gtests under AddressSanitizer + UndefinedBehaviorSanitizer (build-sanitize/). The
# gap suite runs clean too but takes 23 min more under the sanitizers: run it with
# `bash scripts/run_sanitized_tests.sh gap` (docs/reliability.md).
echo "== gtests under AddressSanitizer + UndefinedBehaviorSanitizer: core, stability"
bash "$REPO_ROOT/scripts/run_sanitized_tests.sh" core stability
sanitize_status=$?
[ "$tests_status" -eq 0 ] && [ "$fuzz_status" -eq 0 ] && [ "$sanitize_status" -eq 0 ]
