#!/usr/bin/env bash
# Run under xvfb-run: start rviz with a config, wait, take a screenshot of the root window, stop rviz.
# usage: rviz_screenshot.sh CONFIG.rviz OUT.png WAIT_SECONDS
set -u
rviz -d "$1" __name:=rviz_screenshot &
pid=$!
sleep "$3"
import -window root "$2"
status=$?
kill "$pid" 2>/dev/null
wait "$pid" 2>/dev/null
exit $status
