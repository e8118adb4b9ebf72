#!/usr/bin/env bash
# The gtest suites under AddressSanitizer + UndefinedBehaviorSanitizer (issue 16): builds the test
# binaries in the sanitizer workspace (scripts/build.sh --sanitize TARGETS: clang-16, build-sanitize/) and runs
# each there. Any sanitizer report aborts its binary (halt_on_error, -fno-sanitize-recover) and fails the run;
# a failure names the test (a failed assertion's Suite.Test, or the test a sanitizer report aborted).
# Usage: scripts/run_sanitized_tests.sh [core|stability|gap ...]   (default: all three; the gap suite takes
# about 23 min under the sanitizers: bench/sanitized_gap_tests.sh)
# Environment: LK_SANITIZE_NO_BUILD=1 (built already), LK_SANITIZE_RESULTS=DIR (a JUnit file per suite there,
# sanitized-<suite>.xml, for scripts/test_summary.py).
set -euo pipefail
export LK_BUILD_ROOT="${LK_BUILD_ROOT:-$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)/build-sanitize}"
source "$(dirname "${BASH_SOURCE[0]}")/env.sh"
suites=("$@")
[ ${#suites[@]} -gt 0 ] || suites=(core stability gap)
targets=(lk_simulate lk_stability)  # the configuration and stability tool tests run these binaries
for suite in "${suites[@]}"; do targets+=("lane_keeping_${suite}_tests"); done
[ "${LK_SANITIZE_NO_BUILD:-0}" = 1 ] || "$REPO_ROOT/scripts/build.sh" --sanitize "${targets[@]}"
export ASAN_OPTIONS="halt_on_error=1:detect_leaks=1:strict_string_checks=1:detect_stack_use_after_return=1"
export ASAN_SYMBOLIZER_PATH="${ASAN_SYMBOLIZER_PATH:-$(command -v llvm-symbolizer-16 || command -v llvm-symbolizer || true)}"
export UBSAN_OPTIONS="halt_on_error=1:print_stacktrace=1"
RESULTS="${LK_SANITIZE_RESULTS:-}"
[ -z "$RESULTS" ] || mkdir -p "$RESULTS"
status=0
for suite in "${suites[@]}"; do
  bin="$WS/devel/lib/lane_keeping/lane_keeping_${suite}_tests"
  log="$BUILD_ROOT/sanitized_${suite}.log"
  tmp="$BUILD_ROOT/test_tmp/${suite}"  # the gtests' TempDir(): not /tmp, shared with a Release run
  mkdir -p "$tmp"
  xml=()
  [ -z "$RESULTS" ] || { rm -f "$RESULTS/sanitized-${suite}.xml"; xml=(--gtest_output="xml:$RESULTS/sanitized-${suite}.xml"); }
  start=$(date +%s)
  if (cd "$REPO_ROOT" && TEST_TMPDIR="$tmp" "$bin" "${xml[@]}" >"$log" 2>&1); then
    echo "[sanitize] $suite: $(grep -E '^\[  PASSED' "$log") in $(( $(date +%s) - start )) s, no sanitizer report"
  else
    status=1
    echo "[sanitize] $suite: FAILED (log: $log)"
    grep -E "^\[  FAILED  \]|ERROR: AddressSanitizer|ERROR: LeakSanitizer|runtime error|SUMMARY" "$log" | head -20
    # A sanitizer report aborts the binary before gtest writes its XML: name the test that was running.
    running=$(grep -E '^\[ RUN      \]' "$log" | tail -1 | sed 's/^\[ RUN      \] //')
    if [ -n "$running" ] && ! grep -qE "^\[       OK \] $running |^\[  FAILED  \] $running " "$log"; then
      echo "[sanitize] $suite: aborted in $running"
      if [ -n "$RESULTS" ]; then
        what=$(grep -m1 -E "ERROR: AddressSanitizer|ERROR: LeakSanitizer|runtime error" "$log" | sed -e 's/&/\&amp;/g' -e 's/"/\&quot;/g' -e 's/</\&lt;/g')
        printf '<?xml version="1.0" encoding="UTF-8"?>\n<testsuites><testsuite name="%s" tests="1" failures="1">\n  <testcase classname="%s" name="%s"><failure message="aborted: %s (log: %s)"/></testcase>\n</testsuite></testsuites>\n' \
          "${running%%.*}" "${running%%.*}" "${running#*.}" "${what:-no report in the log}" "$log" >"$RESULTS/sanitized-${suite}.xml"
      fi
    fi
  fi
done
exit $status
