#!/usr/bin/env bash
# ROS benchmarks of the lane_keeping loop (print figures, assert nothing):
#  1. lockstep real-time factor (simulated s per wall s) of the paper's Fig 6 case (brush tires, plant
#     step 0.1 ms), three processes vs nodelets in one manager (shared thread, and the manager's own
#     worker threads), actuator at 10 kHz (linear hold, the paper's tau2 = 0.1 ms) and at 1 kHz
#     (zero-order hold: a digital actuator);
#  2. realtime mode: how far the plant lags behind the wall clock, and how old each loop sample is
#     when it reaches a subscriber in another process (lk_latency_probe).
# Usage: bench/ros_bench.sh [repeats (default 3)]   (build first: scripts/build.sh)
# Uses its own roscore on port ${LK_BENCH_PORT:-11417}.
set -euo pipefail
source "$(dirname "${BASH_SOURCE[0]}")/../scripts/env.sh"
REPEATS="${1:-3}"
set +u; source "$WS/devel/setup.bash"; set -u
export ROS_MASTER_URI="http://localhost:${LK_BENCH_PORT:-11417}"
LAUNCH="$REPO_ROOT/launch/closed_loop.launch"
SCENARIO="$REPO_ROOT/config/scenarios/fig6.yaml"
TMP="$(mktemp -d)"
cat >"$TMP/zoh_1khz.yaml" <<'YAML'
actuator: {rate: 1000.0}
delays: {hold: zoh}
YAML

roscore -p "${LK_BENCH_PORT:-11417}" >"$TMP/roscore.log" 2>&1 &
ROSCORE_PID=$!
cleanup() { kill "$ROSCORE_PID" 2>/dev/null || true; wait "$ROSCORE_PID" 2>/dev/null || true; rm -rf "$TMP"; }
trap cleanup EXIT
for _ in $(seq 50); do rostopic list >/dev/null 2>&1 && break; sleep 0.2; done

# rtf DURATION ARGS... -> prints the real-time factor of one lockstep run
rtf() {
  local duration="$1"; shift
  roslaunch "$LAUNCH" scenario:="$SCENARIO" duration:="$duration" "$@" >"$TMP/run.log" 2>&1 || true
  sed -n 's/^wall time: .*(\([0-9.e+]*\)x real time.*/\1/p' "$TMP/run.log" | head -n 1
}

median() { sort -g | awk '{v[NR]=$1} END {if (NR == 0) {print "n/a"} else {print v[int((NR + 1) / 2)]}}'; }
best() { sort -g | tail -n 1; }

echo "== lockstep real-time factor, Fig 6 case (brush), plant step 0.1 ms, median and best of $REPEATS =="
echo "$(uptime)"
printf "%-44s %-26s %10s %10s %10s\n" "set-up" "actuator" "sim [s]" "median" "best"
for setup in processes nodelets_shared nodelets_workers; do
  case $setup in
    processes) sargs=(nodelets:=false); label="three processes";;
    nodelets_shared) sargs=(nodelets:=true shared_thread:=true); label="nodelets, one shared thread (default)";;
    nodelets_workers) sargs=(nodelets:=true shared_thread:=false); label="nodelets, manager worker threads";;
  esac
  for rate in 10k 1k; do
    if [ $rate = 10k ]; then rargs=(); rlabel="10 kHz, linear hold"; else rargs=(overrides:="$TMP/zoh_1khz.yaml"); rlabel="1 kHz, zero-order hold"; fi
    duration=20
    [ $setup = processes ] && duration=4
    [ $setup = processes ] && [ $rate = 1k ] && duration=10
    [ $setup = nodelets_workers ] && [ $rate = 10k ] && duration=4
    values=()
    for _ in $(seq "$REPEATS"); do values+=("$(rtf "$duration" "${sargs[@]}" "${rargs[@]}")"); done
    printf "%-44s %-26s %10s %9sx %9sx\n" "$label" "$rlabel" "$duration" \
      "$(printf '%s\n' "${values[@]}" | median)" "$(printf '%s\n' "${values[@]}" | best)"
  done
done

echo
echo "== realtime mode: 10 s of the Fig 6 case paced by the wall clock =="
for setup in nodelets processes; do
  if [ $setup = nodelets ]; then args=(nodelets:=true); label="nodelets, 10 kHz linear (tau2 = 0.1 ms)";
  else args=(nodelets:=false overrides:="$TMP/zoh_1khz.yaml"); label="three processes, 1 kHz zoh"; fi
  "$WS/devel/lib/lane_keeping/lk_latency_probe" __ns:=lane_keeping >"$TMP/probe.log" 2>&1 &
  probe=$!
  sleep 1
  roslaunch "$LAUNCH" scenario:="$SCENARIO" duration:=10 time_mode:=realtime "${args[@]}" >"$TMP/run.log" 2>&1 || true
  for _ in $(seq 50); do kill -0 "$probe" 2>/dev/null || break; sleep 0.1; done
  kill "$probe" 2>/dev/null || true
  wait "$probe" 2>/dev/null || true
  echo "-- $label"
  grep -E "^(wall time|realtime lag):" "$TMP/run.log" || tail -n 20 "$TMP/run.log"
  echo "sample age at a subscriber in another process (arrival wall time - (wall time of t = 0 + stamp)):"
  cat "$TMP/probe.log"
done
