#!/usr/bin/env bash
# Builds the libFuzzer targets (fuzz/CMakeLists.txt) in the sanitizer workspace (scripts/build.sh --sanitize:
# clang-16, AddressSanitizer + UndefinedBehaviorSanitizer, libFuzzer's coverage), where the sanitized gtests are
# built too; cheap when up to date. The targets land in build-sanitize/ws/devel/lib/lane_keeping/<target>_fuzz.
set -euo pipefail
exec bash "$(dirname "${BASH_SOURCE[0]}")/../scripts/build.sh" --sanitize lane_keeping_fuzz_targets
