#!/usr/bin/env bash
# The gtest suites under AddressSanitizer + UndefinedBehaviorSanitizer (issue 16): builds the test
# binaries in the sanitizer workspace (scripts/build.sh --sanitize TARGETS: clang-16, build-sanitize/) and runs
# each there. Any sanitizer report aborts its binary (halt_on_error, -fno-sanitize-recover) and fails the run;
# a failure names the test (a failed assertion's Suite.Test, or the test a sanitizer report aborted).
# Usage: scripts/run_sanitized_tests.sh [core|stability|gap ...]   (default: all three; the gap suite takes
# about 23 min under the sanitizers: bench/sanitized_gap_tests.sh)
# Environment: LK_SANITIZE_NO_BUILD=1 (built already), LK_SANITIZE_RESULTS=DIR (a JUnit file per suite there,
# sanitized-<suite>.xml, for scripts/test_summary.py), LK_SANITIZE_SHARDS=N (each suite in N processes, gtest's
# own sharding: every test runs in exactly one; default 1), LK_SANITIZE_JOBS=N (processes at a time, default 1).
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
SHARDS="${LK_SANITIZE_SHARDS:-1}"
JOBS="${LK_SANITIZE_JOBS:-1}"

# One shard of one suite: its log sanitized_<suite>[.<shard>].log, its JUnit file in $BUILD_ROOT/sanitized_xml/, and a
# one-line verdict in <log>.verdict (the test a sanitizer report aborted, when one did).
run_shard() {
  local suite=$1 shard=$2
  local name="$suite"
  [ "$SHARDS" -eq 1 ] || name="$suite.$shard"
  local bin="$WS/devel/lib/lane_keeping/lane_keeping_${suite}_tests"
  local log="$BUILD_ROOT/sanitized_${name}.log" xml="$BUILD_ROOT/sanitized_xml/${name}.xml"
  local tmp="$BUILD_ROOT/test_tmp/${name}"  # the gtests' TempDir(): not /tmp, shared with a Release run or a shard
  mkdir -p "$tmp"
  rm -f "$xml" "$log.verdict"
  local start
  start=$(date +%s)
  if (cd "$REPO_ROOT" && TEST_TMPDIR="$tmp" GTEST_TOTAL_SHARDS="$SHARDS" GTEST_SHARD_INDEX="$shard" \
        "$bin" --gtest_output="xml:$xml" >"$log" 2>&1); then
    echo "[sanitize] $name: $(grep -E '^\[  PASSED' "$log") in $(( $(date +%s) - start )) s, no sanitizer report" >"$log.verdict"
    return 0
  fi
  {
    echo "[sanitize] $name: FAILED in $(( $(date +%s) - start )) s (log: $log)"
    grep -E "^\[  FAILED  \]|ERROR: AddressSanitizer|ERROR: LeakSanitizer|runtime error|SUMMARY" "$log" | head -20 || true
  } >"$log.verdict"
  # A sanitizer report aborts the binary before gtest writes its XML: name the test that was running.
  local running what
  running=$(grep -E '^\[ RUN      \]' "$log" | tail -1 | sed 's/^\[ RUN      \] //' || true)
  if [ -n "$running" ] && ! grep -qE "^\[       OK \] $running |^\[  FAILED  \] $running " "$log"; then
    echo "[sanitize] $name: aborted in $running" >>"$log.verdict"
    what=$(grep -m1 -E "ERROR: AddressSanitizer|ERROR: LeakSanitizer|runtime error" "$log" | sed -e 's/&/\&amp;/g' -e 's/"/\&quot;/g' -e 's/</\&lt;/g' || true)
    printf '<?xml version="1.0" encoding="UTF-8"?>\n<testsuites><testsuite name="%s" tests="1" failures="1">\n  <testcase classname="%s" name="%s"><failure message="aborted: %s (log: %s)"/></testcase>\n</testsuite></testsuites>\n' \
      "${running%%.*}" "${running%%.*}" "${running#*.}" "${what:-no report in the log}" "$log" >"$xml"
  fi
  return 1
}

mkdir -p "$BUILD_ROOT/sanitized_xml"
pids=()
for suite in "${suites[@]}"; do
  for ((shard = 0; shard < SHARDS; shard++)); do
    while [ "$(jobs -rp | wc -l)" -ge "$JOBS" ]; do wait -n || true; done
    run_shard "$suite" "$shard" &
    pids+=($!)
  done
done
status=0
for pid in "${pids[@]}"; do wait "$pid" || status=1; done
for suite in "${suites[@]}"; do
  names=("$suite")
  [ "$SHARDS" -eq 1 ] || names=($(for ((shard = 0; shard < SHARDS; shard++)); do echo "$suite.$shard"; done))
  for name in "${names[@]}"; do cat "$BUILD_ROOT/sanitized_${name}.log.verdict" 2>/dev/null || echo "[sanitize] $name: no verdict"; done
  # One JUnit file per suite, whatever the shards: the testsuites of every shard's file under one root.
  if [ -n "$RESULTS" ]; then
    /usr/bin/python3 - "$RESULTS/sanitized-${suite}.xml" "${names[@]/#/$BUILD_ROOT/sanitized_xml/}" <<'EOF'
import os, sys
import xml.etree.ElementTree as ET
out, shards = sys.argv[1], [path + '.xml' for path in sys.argv[2:]]
merged = ET.Element('testsuites')
tests = failures = 0
for path in shards:
    if not os.path.exists(path):
        continue  # a shard that died without a file: its verdict says so, and the run fails
    root = ET.parse(path).getroot()
    for suite in ([root] if root.tag == 'testsuite' else root.findall('testsuite')):
        merged.append(suite)
        tests += len(suite.findall('testcase'))
        failures += sum(1 for case in suite.findall('testcase') if case.find('failure') is not None)
merged.set('tests', str(tests))
merged.set('failures', str(failures))
if any(os.path.exists(path) for path in shards):
    ET.ElementTree(merged).write(out, encoding='UTF-8', xml_declaration=True)
EOF
  fi
done
exit $status
