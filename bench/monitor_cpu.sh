#!/usr/bin/env bash
# CPU of the live gap monitor beside a realtime closed loop (issue 17 item 4; prints figures, asserts
# nothing). The loop runs as nodelets in realtime on the sinusoidal lane; the monitor replays at
# 500 Hz and reads vehicle_state, steering_torque and desired_steering
#   * at 1 kHz each: a car whose plant steps, actuator and tracker all run at 1 kHz (digital
#     actuator with zero-order hold, tau2 = 1 ms) — the input rate the issue names;
#   * at 10, 10 and 1 kHz: the default loop (plant step and actuator at 10 kHz).
# Two set-ups: the monitor in its own process (its CPU from /proc), and as a nodelet in the loop's
# manager (intra-process, no serialisation): its cost is the manager's CPU with the monitor minus
# without it, side by side. Shares are of one core over the run's wall time.
# Usage: bench/monitor_cpu.sh [duration s (default 30)] [repeats (default 2)]
set -euo pipefail
source "$(dirname "${BASH_SOURCE[0]}")/../scripts/env.sh"
DURATION="${1:-30}"
REPEATS="${2:-2}"
set +u; source "$WS/devel/setup.bash"; set -u
export ROS_MASTER_URI="http://localhost:${LK_BENCH_PORT:-11418}"
TMP="$(mktemp -d)"
roscore -p "${LK_BENCH_PORT:-11418}" >"$TMP/roscore.log" 2>&1 &
ROSCORE_PID=$!
cleanup() { kill "$ROSCORE_PID" 2>/dev/null || true; wait "$ROSCORE_PID" 2>/dev/null || true; rm -rf "$TMP"; }
trap cleanup EXIT
for _ in $(seq 50); do rostopic list >/dev/null 2>&1 && break; sleep 0.2; done
TICKS=$(getconf CLK_TCK)
cat >"$TMP/loop_1khz.yaml" <<'YAML'
simulation: {step: 0.001}
actuator: {rate: 1000.0}
delays: {hold: zoh, desired_steering_to_actuator: 0.001, steering_angle_to_actuator: 0.001}
YAML
cpu_of() { awk '{print $14 + $15}' "/proc/$1/stat"; }

# run OVERRIDES PATTERN ARGS... -> "cpu_seconds wall_seconds statuses" of the process matching PATTERN
run() {
  local overrides="$1" pattern="$2"; shift 2
  roslaunch "$REPO_ROOT/launch/closed_loop.launch" scenario:="$REPO_ROOT/config/scenarios/sinusoid.yaml" \
    overrides:="$overrides" duration:="$DURATION" time_mode:=realtime nodelets:=true "$@" >"$TMP/run.log" 2>&1 &
  local launch_pid=$! pid="" cpu0 cpu1
  for _ in $(seq 200); do pid=$(pgrep -f "$pattern" | head -n 1 || true); [ -n "$pid" ] && break; sleep 0.1; done
  timeout $((DURATION + 30)) rostopic echo -p /lane_keeping/gap_status/level >"$TMP/statuses.txt" 2>/dev/null &
  local echo_pid=$!
  cpu0=$(cpu_of "$pid"); cpu1="$cpu0"
  while kill -0 "$launch_pid" 2>/dev/null; do cpu1=$(cpu_of "$pid" 2>/dev/null || echo "$cpu1"); sleep 0.2; done
  kill "$echo_pid" 2>/dev/null || true
  local wall; wall=$(sed -n 's/^wall time: *\([0-9.e+]*\) s.*/\1/p' "$TMP/run.log" | head -n 1)
  echo "$(awk -v a="$cpu0" -v b="$cpu1" -v hz="$TICKS" 'BEGIN {print (b - a) / hz}') ${wall:-nan} $(($(wc -l <"$TMP/statuses.txt") - 1))"
}

for LOOP in 1khz 10khz; do
  OVERRIDES=""; [ "$LOOP" = 1khz ] && OVERRIDES="$TMP/loop_1khz.yaml"
  echo "== loop at $LOOP, sinusoid lane, ${DURATION} s realtime, $REPEATS runs each =="
  for r in $(seq "$REPEATS"); do
    read -r cpu wall n < <(run "$OVERRIDES" "lib/lane_keeping/gap_monitor " monitor:=true monitor_nodelet:=false)
    awk -v c="$cpu" -v w="$wall" -v n="$n" 'BEGIN {printf "  monitor process:  %5.1f %% of one core (%.2f s CPU / %.1f s), %d statuses\n", 100 * c / w, c, w, n}'
    read -r base wall0 _ < <(run "$OVERRIDES" "nodelet manager __name:=manager" monitor:=false)
    read -r with wall1 n < <(run "$OVERRIDES" "nodelet manager __name:=manager" monitor:=true)
    awk -v a="$base" -v b="$with" -v w0="$wall0" -v w1="$wall1" -v n="$n" \
      'BEGIN {printf "  monitor nodelet:  %5.1f %% of one core (manager %.1f %% with it, %.1f %% without), %d statuses\n", 100 * (b / w1 - a / w0), 100 * b / w1, 100 * a / w0, n}'
  done
done
