#!/usr/bin/env bash
# `make test-asan` and `make test-tsan` (issue 18): builds test suites with a sanitizer in their own
# build folder and runs each suite's binary (GoogleTest), optionally with a filter that leaves out
# closed-loop flights; any sanitizer finding aborts that binary and fails the run.
#   scripts/test-sanitized.sh BUILD_DIR SANITIZERS JOBS SUITE[:GTEST_FILTER] ...
# e.g. scripts/test-sanitized.sh build-asan address,undefined 2 config output 'sim:-*Sitl*'
set -euo pipefail
cd "$(dirname "$0")/.."
build_dir=$1 sanitizers=$2 jobs=$3
shift 3
((${#@})) || { echo "test-sanitized: name at least one test suite" >&2; exit 2; }

# -O1: instrumented code compiles several times faster than at the Release -O3 and still runs the
# numerically heavy tests at a usable speed.
cmake -S . -B "$build_dir" -G Ninja -DCMAKE_BUILD_TYPE=Release -DCMAKE_CXX_FLAGS_RELEASE="-O1 -DNDEBUG" \
  -DAPERTURE_UNITY_BUILD=ON -DAPERTURE_SANITIZE="$sanitizers" >/dev/null
targets=()
for spec in "$@"; do targets+=("aperture_${spec%%:*}_tests"); done
cmake --build "$build_dir" -j "$jobs" --target "${targets[@]}"

# Findings stop the process (-fno-sanitize-recover at compile time, halt_on_error here) with a
# stack trace; leaks are findings too.
export ASAN_OPTIONS=detect_leaks=1:halt_on_error=1:detect_stack_use_after_return=1
export UBSAN_OPTIONS=print_stacktrace=1:halt_on_error=1
export TSAN_OPTIONS=halt_on_error=1:second_deadlock_stack=1:suppressions=$PWD/scripts/tsan-suppressions.txt
failed=()
for spec in "$@"; do
  suite=${spec%%:*}
  filter='*'
  [[ "$spec" == *:* ]] && filter=${spec#*:}
  echo "== $sanitizers: aperture_${suite}_tests --gtest_filter=$filter"
  start=$(date +%s)
  if ! "$build_dir/tests/aperture_${suite}_tests" --gtest_filter="$filter" --gtest_brief=1; then
    failed+=("$suite")
  fi
  echo "== $suite: $(($(date +%s) - start)) s"
done
if ((${#failed[@]})); then
  echo "test-sanitized ($sanitizers): failed suites: ${failed[*]}" >&2
  exit 1
fi
echo "test-sanitized ($sanitizers): all suites clean"
