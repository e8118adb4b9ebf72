#!/usr/bin/env bash
# The gtest suites under AddressSanitizer + UndefinedBehaviorSanitizer (issue 16): builds the test
# binaries in the sanitizer workspace (scripts/build.sh --sanitize TARGETS) and runs each in it.
# Any sanitizer report aborts its binary (halt_on_error, -fno-sanitize-recover) and fails the run.
# Usage: scripts/run_sanitized_tests.sh [core|stability|gap ...]   (default: all three)
set -euo pipefail
export LK_BUILD_ROOT="${LK_BUILD_ROOT:-$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)/build-sanitize}"
source "$(dirname "${BASH_SOURCE[0]}")/env.sh"
suites=("$@")
[ ${#suites[@]} -gt 0 ] || suites=(core stability gap)
targets=(lk_simulate)  # the configuration tests run the binary
for suite in "${suites[@]}"; do targets+=("lane_keeping_${suite}_tests"); done
"$REPO_ROOT/scripts/build.sh" --sanitize "${targets[@]}"
export ASAN_OPTIONS="halt_on_error=1:detect_leaks=1:strict_string_checks=1:detect_stack_use_after_return=1"
export UBSAN_OPTIONS="halt_on_error=1:print_stacktrace=1"
status=0
for suite in "${suites[@]}"; do
  bin="$WS/devel/lib/lane_keeping/lane_keeping_${suite}_tests"
  start=$(date +%s)
  if (cd "$REPO_ROOT" && "$bin" --gtest_brief=1 >"$BUILD_ROOT/sanitized_${suite}.log" 2>&1); then
    echo "[sanitize] $suite: $(grep -E '^\[  PASSED' "$BUILD_ROOT/sanitized_${suite}.log") in $(( $(date +%s) - start )) s, no sanitizer report"
  else
    status=1
    echo "[sanitize] $suite: FAILED (log: $BUILD_ROOT/sanitized_${suite}.log)"
    grep -E "ERROR: AddressSanitizer|runtime error|FAILED|SUMMARY" "$BUILD_ROOT/sanitized_${suite}.log" | head -20
  fi
done
exit $status
