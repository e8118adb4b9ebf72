#!/usr/bin/env bash
# The gap gtests under AddressSanitizer + UndefinedBehaviorSanitizer: the long campaign the test command leaves out
# (about 23 min on this 2-core VM; the replays and fits run 5-10x slower under ASan). Run it when src/core/gap or
# test/core/gap changes; its last figures are in docs/reliability.md (Sanitizers).
# Usage: bench/sanitized_gap_tests.sh   (builds in build-sanitize/, logs in build-sanitize/sanitized_gap.log)
exec bash "$(dirname "${BASH_SOURCE[0]}")/../scripts/run_sanitized_tests.sh" gap
