#!/usr/bin/env bash
# Every test (docs/tests.md), on the machine's cores (2 here):
#   1. the Release workspace with the test binaries (scripts/build.sh tests);
#   2. every catkin test (the gtest binaries, the rostests, the pytest files) with ctest, two at a time, while the
#      sanitizer workspace builds beside them at the lowest priority (scripts/build.sh --sanitize: clang-16 with
#      AddressSanitizer + UndefinedBehaviorSanitizer and libFuzzer's coverage, so one build serves both of 3.);
#   3. in that workspace, two at a time: the core and stability gtests (scripts/run_sanitized_tests.sh), and the
#      fuzz targets, each over its regression inputs and seed corpus, then fuzzed 20,000 inputs or 30 s (fuzz/run.sh);
#   4. the rostests that run in realtime or load every core (label `serial`, CMakeLists.txt), one at a time with
#      nothing else running;
#   5. the verdict (scripts/test_summary.py): every result file, the slowest tests, and each failure by name:
#      gtest binary and Suite.Test, rostest and test case, pytest node id, sanitized suite and test, fuzz target.
# Logs in build/test_logs/ (ctest.log: every catkin test's output); the gap suite under the sanitizers and the
# million-input fuzzing campaign are their own commands (bench/sanitized_gap_tests.sh, bench/fuzz.sh).
# Environment: LK_TEST_JOBS (tests at a time, default: the number of cores).
set -euo pipefail
source "$(dirname "${BASH_SOURCE[0]}")/env.sh"
JOBS="${LK_TEST_JOBS:-$(nproc)}"
LOGS="$BUILD_ROOT/test_logs"
SANITIZE_ROOT="$REPO_ROOT/build-sanitize"
CATKIN_RESULTS="$WS/build/test_results/lane_keeping"
OTHER_RESULTS="$LOGS/results"  # the sanitized gtests' and the fuzz targets' JUnit files
rm -rf "$LOGS"
mkdir -p "$LOGS" "$OTHER_RESULTS"
t0=$(date +%s)
phase() { echo "== $(( $(date +%s) - t0 )) s: $*"; }

phase "build: Release workspace with the test binaries"
"$REPO_ROOT/scripts/build.sh" tests
rm -rf "$CATKIN_RESULTS"
mkdir -p "$CATKIN_RESULTS"

# 2. The sanitizer workspace's build in the background, at the lowest priority: it takes the cycles the tests
# leave (rostests wait on messages and timers), and the tests keep theirs.
SANITIZE_TARGETS=(lk_simulate lk_stability lane_keeping_core_tests lane_keeping_stability_tests lane_keeping_fuzz_targets)
phase "tests: ctest -j$JOBS (all but the serial rostests); beside them: the sanitizer workspace's build (nice 19)"
nice -n 19 "$REPO_ROOT/scripts/build.sh" --sanitize "${SANITIZE_TARGETS[@]}" >"$LOGS/sanitize_build.log" 2>&1 &
sanitize_build=$!
set +e
(cd "$WS/build" && ctest -j"$JOBS" -LE serial --output-log "$LOGS/ctest.log" --timeout 900) >"$LOGS/ctest_parallel.txt" 2>&1
ctest_status=$?
grep -E "Test +#|tests passed|tests failed" "$LOGS/ctest_parallel.txt" | sed 's/_ctest_lane_keeping_//'
phase "waiting for the sanitizer workspace's build"
# Nothing of ours runs beside it now: back to the normal priority where allowed (root, as in CI's container; an
# unprivileged user cannot lower a nice value and keeps 19). At 19 on a machine others keep busy, the build got
# almost no CPU (measured: 30 % of it built in the 17 min the tests took beside three other builds).
renice -n 0 -g "$(ps -o pgid= -p "$sanitize_build" | tr -d ' ')" >/dev/null 2>&1 || true
wait "$sanitize_build"
sanitize_build_status=$?
set -e
tail -n 1 "$LOGS/sanitize_build.log"

# 3. Sanitized gtests and fuzz targets, one core each.
sanitized_status=1
fuzz_status=1
if [ "$sanitize_build_status" -eq 0 ]; then
  phase "sanitized core and stability gtests | fuzz targets: regressions, corpus, 20000 inputs or 30 s each"
  set +e
  LK_SANITIZE_NO_BUILD=1 LK_SANITIZE_RESULTS="$OTHER_RESULTS" bash "$REPO_ROOT/scripts/run_sanitized_tests.sh" core stability \
    >"$LOGS/sanitized.txt" 2>&1 &
  sanitized=$!
  LK_FUZZ_NO_BUILD=1 LK_FUZZ_JOBS=$((JOBS > 1 ? JOBS - 1 : 1)) LK_FUZZ_MAX_TIME="${LK_FUZZ_MAX_TIME:-30}" \
    LK_FUZZ_RESULTS="$OTHER_RESULTS" bash "$REPO_ROOT/fuzz/run.sh" 20000 >"$LOGS/fuzz.txt" 2>&1
  fuzz_status=$?
  wait "$sanitized"
  sanitized_status=$?
  set -e
  cat "$LOGS/sanitized.txt" "$LOGS/fuzz.txt"
else
  echo "[sanitize] the sanitizer workspace's build failed (log: $LOGS/sanitize_build.log, $SANITIZE_ROOT/catkin_make.log)"
  tail -n 30 "$LOGS/sanitize_build.log"
fi

# 4. The rostests that must run alone.
phase "tests: the serial rostests (realtime, or a busy process on every core), one at a time"
set +e
(cd "$WS/build" && ctest -L serial --output-log "$LOGS/ctest_serial.log" --timeout 900) >"$LOGS/ctest_serial.txt" 2>&1
serial_status=$?
set -e
grep -E "Test +#|tests passed|tests failed" "$LOGS/ctest_serial.txt" | sed 's/_ctest_lane_keeping_//'
cat "$LOGS/ctest_serial.log" >>"$LOGS/ctest.log"

# 5. The verdict.
phase "summary"
set +e
/usr/bin/python3 "$REPO_ROOT/scripts/test_summary.py" --expect sanitized-core --expect sanitized-stability \
  $(for f in "$REPO_ROOT"/fuzz/*_fuzz.cpp; do f=$(basename "$f"); echo "--expect fuzz-${f%_fuzz.cpp}"; done) \
  "$CATKIN_RESULTS" "$OTHER_RESULTS"
summary_status=$?
set -e
for part in ctest:$ctest_status serial:$serial_status sanitize_build:$sanitize_build_status sanitized:$sanitized_status fuzz:$fuzz_status; do
  [ "${part#*:}" -eq 0 ] || echo "FAILED  ${part%%:*} (exit ${part#*:}; logs: $LOGS)"
done
phase "done"
[ "$ctest_status" -eq 0 ] && [ "$serial_status" -eq 0 ] && [ "$sanitize_build_status" -eq 0 ] && \
  [ "$sanitized_status" -eq 0 ] && [ "$fuzz_status" -eq 0 ] && [ "$summary_status" -eq 0 ]
