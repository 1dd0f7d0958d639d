#!/usr/bin/env bash
# The short fuzzing run for CI (issue 18, `make fuzz-smoke`): builds the libFuzzer targets
# (scripts/fuzz.sh) and runs each for SECONDS (default 15) from its seeds alone, so every seed input
# runs and a few seconds of mutations follow; any finding fails. A fresh corpus each time: CI
# checks the seeds and the code as they are, not a corpus grown by earlier runs.
#   scripts/fuzz-smoke.sh BUILD_DIR JOBS [SECONDS]
set -euo pipefail
cd "$(dirname "$0")/.."
build_dir=$1 jobs=$2 seconds=${3:-15}
rm -rf "$build_dir/fuzz-corpus" "$build_dir/fuzz-findings"
exec scripts/fuzz.sh "$build_dir" "$seconds" "$jobs"
