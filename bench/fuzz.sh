#!/usr/bin/env bash
# The fuzzing campaign (issue 16 item 1; docs/fuzzing.md): every libFuzzer target for EXECUTIONS inputs
# (default 1,000,000) on a copy of its seed corpus; prints executions, exec/s, crashes, timeouts,
# sanitizer reports and corpus size per target. Usage: bench/fuzz.sh [EXECUTIONS] [TARGET...]
exec bash "$(dirname "${BASH_SOURCE[0]}")/../fuzz/run.sh" "${1:-1000000}" "${@:2}"
