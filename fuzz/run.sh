#!/usr/bin/env bash
# Runs the libFuzzer targets (fuzz/*_fuzz.cpp): builds them if needed (fuzz/build.sh: the sanitizer
# workspace build-sanitize/), replays each target's regression inputs (fuzz/regressions/<target>/), then
# fuzzes it for EXECUTIONS inputs on a copy of its seed corpus (fuzz/corpus/<target>/ plus the regressions, in
# build-fuzz/work/<target>/: the checked-in corpus never grows), with its dictionary, a time limit per input and
# an RSS limit. LK_FUZZ_JOBS targets at a time (default 1; scripts/run_tests.sh runs two beside the sanitized
# gtests). Prints per target: executions, exec/s, crashes, timeouts, out-of-memory, sanitizer reports, corpus size.
# Exit status 1 on any finding; the inputs are in build-fuzz/findings/<target>/, the logs beside them.
# Usage: fuzz/run.sh EXECUTIONS [TARGET...]   targets (default: every fuzz/<target>_fuzz.cpp): sim_config csv_log
# bag_log path gap_report log_mapping options
# Environment: LK_FUZZ_SEED (libFuzzer -seed, default 1: a run is reproducible), LK_FUZZ_TIMEOUT (s per
# input, default 10), LK_FUZZ_RSS_MB (default 2048), LK_FUZZ_MAX_TIME (s of fuzzing per target: stop at
# EXECUTIONS or then, whichever comes first; default none), LK_FUZZ_NO_BUILD=1 (the targets are built already).
set -uo pipefail
source "$(dirname "${BASH_SOURCE[0]}")/../scripts/env.sh"
EXECUTIONS="${1:-1000000}"
shift || true
targets=("$@")
if [ ${#targets[@]} -eq 0 ]; then  # every fuzz/<target>_fuzz.cpp
  for harness in "$REPO_ROOT"/fuzz/*_fuzz.cpp; do harness=$(basename "$harness"); targets+=("${harness%_fuzz.cpp}"); done
fi
OUT="${LK_FUZZ_BUILD:-$REPO_ROOT/build-fuzz}"
BIN="${LK_SANITIZE_ROOT:-$REPO_ROOT/build-sanitize}/ws/devel/lib/lane_keeping"
JOBS="${LK_FUZZ_JOBS:-1}"
RESULTS="${LK_FUZZ_RESULTS:-}"  # a folder for one JUnit file per target (scripts/test_summary.py reads them)
[ "${LK_FUZZ_NO_BUILD:-0}" = 1 ] || bash "$REPO_ROOT/fuzz/build.sh" || exit 1
export ASAN_OPTIONS="halt_on_error=1:detect_leaks=1:allocator_may_return_null=0"
export ASAN_SYMBOLIZER_PATH="${ASAN_SYMBOLIZER_PATH:-$(command -v llvm-symbolizer-16 || command -v llvm-symbolizer || true)}"
export UBSAN_OPTIONS="halt_on_error=1:print_stacktrace=1"
FLAGS=(-timeout="${LK_FUZZ_TIMEOUT:-10}" -rss_limit_mb="${LK_FUZZ_RSS_MB:-2048}" -seed="${LK_FUZZ_SEED:-1}"
       -print_final_stats=1)
[ -n "${LK_FUZZ_MAX_TIME:-}" ] && FLAGS+=(-max_total_time="$LK_FUZZ_MAX_TIME")
mkdir -p "$OUT/findings"
[ -z "$RESULTS" ] || mkdir -p "$RESULTS"

# One target: regressions, then fuzzing; writes its table row to $OUT/findings/<target>.row, what it found
# to <target>.found (empty: nothing), and, with LK_FUZZ_RESULTS, a JUnit file fuzz-<target>.xml.
run_target() {
  local target=$1
  local bin="$BIN/${target}_fuzz"
  local work="$OUT/work/$target" findings="$OUT/findings/$target" log="$OUT/findings/$target.log"
  local row="$OUT/findings/$target.row" found="$OUT/findings/$target.found"
  rm -rf "$work" "$findings"
  mkdir -p "$work" "$findings"
  : >"$log"
  : >"$found"
  local start seconds=0 runs="" rate="" crashes=0 timeouts=0 ooms=0 reports=0 corpus=""
  start=$(date +%s)
  if [ ! -x "$bin" ]; then
    echo "no target $target ($bin)" >"$found"
  else
    cp "$REPO_ROOT/fuzz/corpus/$target/"* "$work/"
    local regressions=("$REPO_ROOT/fuzz/regressions/$target/"*)
    local dict=()
    [ -f "$REPO_ROOT/fuzz/$target.dict" ] && dict=(-dict="$REPO_ROOT/fuzz/$target.dict")
    # 1. Every regression input once (each once crashed, hung or broke the contract).
    if [ -e "${regressions[0]}" ]; then
      cp "${regressions[@]}" "$work/"
      "$bin" "${FLAGS[@]}" -artifact_prefix="$findings/" "${regressions[@]}" >>"$log" 2>&1 || true
    fi
    # 2. Fuzzing from the corpus copy.
    "$bin" "${FLAGS[@]}" "${dict[@]}" -runs="$EXECUTIONS" -artifact_prefix="$findings/" "$work" >>"$log" 2>&1 || true
    runs=$(grep -Eo 'stat::number_of_executed_units: *[0-9]+' "$log" | tail -1 | grep -Eo '[0-9]+$')
    rate=$(grep -Eo 'stat::average_exec_per_sec: *[0-9]+' "$log" | tail -1 | grep -Eo '[0-9]+$')
    crashes=$(find "$findings" -name 'crash-*' | wc -l)
    timeouts=$(find "$findings" -name 'timeout-*' | wc -l)
    ooms=$(find "$findings" -name 'oom-*' | wc -l)
    crashes=$((crashes + $(find "$findings" -name 'leak-*' | wc -l)))
    # Sanitizer reports: ASan's memory errors (lower-case kinds; SEGV and the ABRT of a broken contract are
    # crashes), leaks, UBSan's runtime errors; plus the harness's own contract findings.
    reports=$(grep -cE 'ERROR: AddressSanitizer: [a-z]|ERROR: LeakSanitizer|runtime error:|lane_keeping fuzz finding' "$log")
    corpus="$(find "$work" -type f | wc -l) files, $(du -sk "$work" | cut -f1) kB"
    if [ -z "$runs" ] || [ $((crashes + timeouts + ooms + reports)) -gt 0 ]; then
      { echo "FINDING: $crashes crashes, $timeouts timeouts, $ooms out-of-memory, $reports sanitizer reports (inputs: $findings, log: $log)"
        grep -E 'ERROR: |runtime error:|lane_keeping fuzz finding|Test unit written|SUMMARY' "$log" | head -8; } >"$found"
    fi
  fi
  seconds=$(( $(date +%s) - start ))
  printf '%-11s %10s %8s %7s %8s %4s %9s %s (%s s)\n' "$target" "${runs:-?}" "${rate:-?}" "$crashes" "$timeouts" "$ooms" \
    "$reports" "${corpus:-none}" "$seconds" >"$row"
  if [ -n "$RESULTS" ]; then
    local failure=""
    if [ -s "$found" ]; then
      failure="<failure message=\"$(head -1 "$found" | sed -e 's/&/\&amp;/g' -e 's/"/\&quot;/g' -e 's/</\&lt;/g')\"/>"
    fi
    printf '<?xml version="1.0" encoding="UTF-8"?>\n<testsuite name="fuzz-%s" tests="1" failures="%d" time="%d">\n  <testcase classname="fuzz" name="%s_fuzz: regressions, corpus, %s inputs" time="%d">%s</testcase>\n</testsuite>\n' \
      "$target" "$([ -s "$found" ] && echo 1 || echo 0)" "$seconds" "$target" "${runs:-?}" "$seconds" "$failure" \
      >"$RESULTS/fuzz-$target.xml"
  fi
}

pids=()
for target in "${targets[@]}"; do
  while [ "$(jobs -rp | wc -l)" -ge "$JOBS" ]; do wait -n || true; done
  run_target "$target" &
  pids+=($!)
done
wait "${pids[@]}" 2>/dev/null || true
status=0
printf '%-11s %10s %8s %7s %8s %4s %9s %s\n' target executions exec/s crashes timeouts oom sanitizer corpus
for target in "${targets[@]}"; do
  cat "$OUT/findings/$target.row"
  if [ -s "$OUT/findings/$target.found" ]; then
    status=1
    echo "  [fuzz] $target: $(head -1 "$OUT/findings/$target.found")"
    tail -n +2 "$OUT/findings/$target.found" | sed 's/^/    /'
  fi
done
exit $status
