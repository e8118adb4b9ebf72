#!/usr/bin/env bash
# Runs the libFuzzer targets (fuzz/*_fuzz.cpp): builds them if needed (fuzz/build.sh), replays each
# target's regression inputs (fuzz/regressions/<target>/), then fuzzes it for EXECUTIONS inputs on a copy
# of its seed corpus (fuzz/corpus/<target>/ plus the regressions, in build-fuzz/work/<target>/: the
# checked-in corpus never grows), with its dictionary, a time limit per input and an RSS limit.
# Prints per target: executions, exec/s, crashes, timeouts, out-of-memory, sanitizer reports, corpus size.
# Exit status 1 on any finding; the inputs are in build-fuzz/findings/<target>/, the logs beside them.
# Usage: fuzz/run.sh EXECUTIONS [TARGET...]   targets: sim_config csv_log bag_log path gap_report log_mapping options
# Environment: LK_FUZZ_SEED (libFuzzer -seed, default 1: a run is reproducible), LK_FUZZ_TIMEOUT (s per
# input, default 10), LK_FUZZ_RSS_MB (default 2048), LK_FUZZ_MAX_TIME (s of fuzzing per target: stop at
# EXECUTIONS or then, whichever comes first; default none).
set -uo pipefail
source "$(dirname "${BASH_SOURCE[0]}")/../scripts/env.sh"
EXECUTIONS="${1:-1000000}"
shift || true
targets=("$@")
[ ${#targets[@]} -gt 0 ] || targets=(sim_config csv_log bag_log path gap_report log_mapping options)
OUT="${LK_FUZZ_BUILD:-$REPO_ROOT/build-fuzz}"
bash "$REPO_ROOT/fuzz/build.sh" || exit 1
export ASAN_OPTIONS="halt_on_error=1:detect_leaks=1:allocator_may_return_null=0"
export ASAN_SYMBOLIZER_PATH="${ASAN_SYMBOLIZER_PATH:-$(command -v llvm-symbolizer-16 || command -v llvm-symbolizer || true)}"
export UBSAN_OPTIONS="halt_on_error=1:print_stacktrace=1"
FLAGS=(-timeout="${LK_FUZZ_TIMEOUT:-10}" -rss_limit_mb="${LK_FUZZ_RSS_MB:-2048}" -seed="${LK_FUZZ_SEED:-1}"
       -print_final_stats=1)
[ -n "${LK_FUZZ_MAX_TIME:-}" ] && FLAGS+=(-max_total_time="$LK_FUZZ_MAX_TIME")
status=0
printf '%-11s %10s %8s %7s %8s %4s %9s %s\n' target executions exec/s crashes timeouts oom sanitizer corpus
for target in "${targets[@]}"; do
  bin="$OUT/${target}_fuzz"
  [ -x "$bin" ] || { echo "[fuzz] no target $target ($bin)"; status=1; continue; }
  work="$OUT/work/$target" findings="$OUT/findings/$target" log="$OUT/findings/$target.log"
  rm -rf "$work" "$findings"
  mkdir -p "$work" "$findings"
  cp "$REPO_ROOT/fuzz/corpus/$target/"* "$work/"
  regressions=("$REPO_ROOT/fuzz/regressions/$target/"*)
  dict=()
  [ -f "$REPO_ROOT/fuzz/$target.dict" ] && dict=(-dict="$REPO_ROOT/fuzz/$target.dict")
  : >"$log"
  start=$(date +%s)
  # 1. Every regression input once (each once crashed, hung or broke the contract).
  if [ -e "${regressions[0]}" ]; then
    cp "${regressions[@]}" "$work/"
    "$bin" "${FLAGS[@]}" -artifact_prefix="$findings/" "${regressions[@]}" >>"$log" 2>&1 || true
  fi
  # 2. Fuzzing from the corpus copy.
  "$bin" "${FLAGS[@]}" "${dict[@]}" -runs="$EXECUTIONS" -artifact_prefix="$findings/" "$work" >>"$log" 2>&1 || true
  seconds=$(( $(date +%s) - start ))
  runs=$(grep -Eo 'stat::number_of_executed_units: *[0-9]+' "$log" | tail -1 | grep -Eo '[0-9]+$')
  rate=$(grep -Eo 'stat::average_exec_per_sec: *[0-9]+' "$log" | tail -1 | grep -Eo '[0-9]+$')
  crashes=$(find "$findings" -name 'crash-*' | wc -l)
  timeouts=$(find "$findings" -name 'timeout-*' | wc -l)
  ooms=$(find "$findings" -name 'oom-*' | wc -l)
  leaks=$(find "$findings" -name 'leak-*' | wc -l)
  crashes=$((crashes + leaks))
  # Sanitizer reports: ASan's memory errors (lower-case kinds; SEGV and the ABRT of a broken contract are
  # crashes), leaks, UBSan's runtime errors; plus the harness's own contract findings.
  reports=$(grep -cE 'ERROR: AddressSanitizer: [a-z]|ERROR: LeakSanitizer|runtime error:|lane_keeping fuzz finding' "$log")
  corpus="$(find "$work" -type f | wc -l) files, $(du -sk "$work" | cut -f1) kB"
  printf '%-11s %10s %8s %7s %8s %4s %9s %s (%s s)\n' "$target" "${runs:-?}" "${rate:-?}" "$crashes" "$timeouts" "$ooms" \
    "$reports" "$corpus" "$seconds"
  if [ -z "$runs" ] || [ $((crashes + timeouts + ooms + reports)) -gt 0 ]; then
    status=1
    echo "  [fuzz] $target: FINDING (inputs: $findings, log: $log)"
    grep -E 'ERROR: |runtime error:|lane_keeping fuzz finding|Test unit written|SUMMARY' "$log" | head -8 | sed 's/^/    /'
  fi
done
exit $status
