#!/usr/bin/env bash
# Every test (docs/tests.md), on the machine's cores (2 here), in the order that leaves no core idle:
#   1. the Release workspace with the test binaries (scripts/build.sh tests), then the sanitizer workspace
#      (scripts/build.sh --sanitize: clang-16 with AddressSanitizer + UndefinedBehaviorSanitizer, one build for the
#      sanitized gtests and the fuzz targets), each on every core: from ccache in a clone, both take a minute or two;
#   2. every catkin test but the serial rostests (the gtest binaries, the rostests, the pytest files) with ctest, two
#      at a time; beside them, at the lowest priority (nice 19), the core and stability gtests in the sanitizer
#      workspace (scripts/run_sanitized_tests.sh, each suite in four gtest shards, two at a time): they take the
#      cycles the tests leave;
#   3. the rostests that run in realtime, on a bag's clock, or load every core (label `serial`, CMakeLists.txt), one
#      at a time; beside them, where they leave the cores idle, the fuzz targets (nice 10: each over its regression
#      inputs and seed corpus, then fuzzed 20,000 inputs or 30 s, fuzz/run.sh) and the sanitized gtests still
#      running (nice 19);
#   4. what of 3. is still running, back at the normal priority (where allowed: root, as in CI's container);
#   5. the verdict (scripts/test_summary.py): every result file, the slowest tests, the count of test cases by kind,
#      and each failure by name: gtest binary and Suite.Test, rostest and test case, pytest node id, sanitized suite
#      and test, fuzz target.
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
# A process and its descendants (to give a background run its priority back).
tree_pids() { local pid; for pid in "$@"; do echo "$pid"; tree_pids $(pgrep -P "$pid" || true); done; }

# 1. Both workspaces, one after the other, each on every core.
phase "build: Release workspace with the test binaries"
"$REPO_ROOT/scripts/build.sh" tests
rm -rf "$CATKIN_RESULTS"
mkdir -p "$CATKIN_RESULTS"
SANITIZE_TARGETS=(lk_simulate lk_stability lane_keeping_core_tests lane_keeping_stability_tests lane_keeping_fuzz_targets)
phase "build: the sanitizer workspace"
set +e
"$REPO_ROOT/scripts/build.sh" --sanitize "${SANITIZE_TARGETS[@]}" >"$LOGS/sanitize_build.log" 2>&1
sanitize_build_status=$?
set -e
tail -n 1 "$LOGS/sanitize_build.log"
if [ "$sanitize_build_status" -ne 0 ]; then
  echo "[sanitize] the sanitizer workspace's build failed (log: $LOGS/sanitize_build.log, $SANITIZE_ROOT/catkin_make.log)"
  tail -n 30 "$LOGS/sanitize_build.log"
fi

# 2. The parallel catkin tests; the sanitized gtests beside them at the lowest priority.
sanitized_status=1
fuzz_status=1
background=()
if [ "$sanitize_build_status" -eq 0 ]; then
  LK_SANITIZE_NO_BUILD=1 LK_SANITIZE_RESULTS="$OTHER_RESULTS" LK_SANITIZE_SHARDS=4 LK_SANITIZE_JOBS="$JOBS" \
    nice -n 19 bash "$REPO_ROOT/scripts/run_sanitized_tests.sh" stability core >"$LOGS/sanitized.txt" 2>&1 &
  sanitized=$!
  background+=("$sanitized")
fi
phase "tests: ctest -j$JOBS (all but the serial rostests); beside them: the sanitized gtests (nice 19)"
set +e
(cd "$WS/build" && ctest -j"$JOBS" -LE serial --output-log "$LOGS/ctest.log" --timeout 900) >"$LOGS/ctest_parallel.txt" 2>&1
ctest_status=$?
set -e
grep -E "Test +#|tests passed|tests failed" "$LOGS/ctest_parallel.txt" | sed 's/_ctest_lane_keeping_//'

# 3. The rostests that must have the cores to themselves, one at a time; the fuzz targets beside them at nice 10 (a
# waking rostest node preempts them at once; the fuzzing's 30 s are wall-clock time, so it must not wait behind the
# sanitized gtests at nice 19).
if [ "$sanitize_build_status" -eq 0 ]; then
  LK_FUZZ_NO_BUILD=1 LK_FUZZ_JOBS=1 LK_FUZZ_MAX_TIME="${LK_FUZZ_MAX_TIME:-30}" LK_FUZZ_RESULTS="$OTHER_RESULTS" \
    nice -n 10 bash "$REPO_ROOT/fuzz/run.sh" 20000 >"$LOGS/fuzz.txt" 2>&1 &
  fuzz=$!
  background+=("$fuzz")
fi
phase "tests: the serial rostests (realtime, a bag's clock, or a busy process on every core), one at a time; beside them: the fuzz targets (nice 10)"
set +e
(cd "$WS/build" && ctest -L serial --output-log "$LOGS/ctest_serial.log" --timeout 900) >"$LOGS/ctest_serial.txt" 2>&1
serial_status=$?
set -e
grep -E "Test +#|tests passed|tests failed" "$LOGS/ctest_serial.txt" | sed 's/_ctest_lane_keeping_//'
cat "$LOGS/ctest_serial.log" >>"$LOGS/ctest.log"

# 4. Nothing of ours runs beside them now: back to the normal priority where allowed (an unprivileged user cannot
# lower a nice value and keeps 19; on a machine others keep busy, 19 gets almost no CPU).
if [ ${#background[@]} -gt 0 ]; then
  phase "waiting for the sanitized gtests and the fuzz targets"
  renice -n 0 -p $(tree_pids "${background[@]}") >/dev/null 2>&1 || true
  set +e
  wait "$sanitized"
  sanitized_status=$?
  wait "$fuzz"
  fuzz_status=$?
  set -e
  cat "$LOGS/sanitized.txt" "$LOGS/fuzz.txt"
fi

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
