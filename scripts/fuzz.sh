#!/usr/bin/env bash
# `make fuzz` (issue 18): builds the libFuzzer targets of fuzz/ in their own build folder (clang,
# -DAPERTURE_FUZZ=ON: only the fuzzers and the parser sources they call) and runs each target for
# SECONDS, one after the other, on its corpus (kept in BUILD_DIR/fuzz-corpus/TARGET between runs)
# and its seeds. Prints each target's executions/s and final coverage (libFuzzer's cov = covered
# edges, ft = features); any crash, leak, timeout or out-of-memory fails the run and leaves the
# input in BUILD_DIR/fuzz-findings/.
#   scripts/fuzz.sh BUILD_DIR SECONDS JOBS [TARGET ...]     (TARGET e.g. times_txt; default: all)
set -euo pipefail
cd "$(dirname "$0")/.."
build_dir=$1 seconds=$2 jobs=$3
shift 3

cmake -S . -B "$build_dir" -G Ninja -DCMAKE_BUILD_TYPE=Release -DCMAKE_CXX_COMPILER=clang++ \
  -DAPERTURE_FUZZ=ON >/dev/null
cmake --build "$build_dir" -j "$jobs"

targets=("$@")
if ((${#targets[@]} == 0)); then
  for source in fuzz/*_fuzzer.cc; do
    name=${source#fuzz/}
    targets+=("${name%_fuzzer.cc}")
  done
fi

# Seeds: fuzz/seeds/TARGET (small inputs written for the fuzzers) plus the repository's own
# files of each format; the `--set` items of the documentation, each on every built-in scenario.
seeds_dir=$build_dir/fuzz-seeds
rm -rf "$seeds_dir"
mkdir -p "$seeds_dir/set_override"
i=0
while IFS= read -r item; do
  for scenario in gap gapflyt led tags forest; do
    printf '%s\n%s\n' "$scenario" "$item" >"$seeds_dir/set_override/${scenario}_$i"
  done
  i=$((i + 1))
done < <(grep -rhoE -- "--set '?[a-z_]+(\.[a-z_]+)*=[^ '\`\"]+" README.md docs |
  sed -E "s/^--set '?//" | sort -u)
seed_dirs() {
  [[ -d fuzz/seeds/$1 ]] && echo "fuzz/seeds/$1"
  case $1 in
    calibration_file) echo tests/data/calibration ;;
    set_override) echo "$seeds_dir/set_override" ;;
  esac
}
dictionary() {
  case $1 in
    calibration_file | scenario_yaml | set_override | led_configuration) echo -dict=fuzz/yaml.dict ;;
  esac
}

findings_dir=$build_dir/fuzz-findings
mkdir -p "$findings_dir"
failed=()
for target in "${targets[@]}"; do
  binary=$build_dir/fuzz/${target}_fuzzer
  [[ -x "$binary" ]] || { echo "fuzz: no target '$target' (fuzz/${target}_fuzzer.cc)" >&2; exit 2; }
  corpus=$build_dir/fuzz-corpus/$target
  mkdir -p "$corpus"
  log=$build_dir/fuzz-$target.log
  start=$(date +%s)
  # -timeout: seconds for one input; -rss_limit_mb also caps a single allocation (malloc_limit).
  # shellcheck disable=SC2046  # folder names and the dictionary option: no spaces
  if "$binary" "$corpus" $(seed_dirs "$target") $(dictionary "$target") \
    -max_total_time="$seconds" -rss_limit_mb=2048 -timeout=10 -print_final_stats=1 \
    -artifact_prefix="$findings_dir/$target-" >"$log" 2>&1; then
    status=clean
  else
    status="FINDING (see $log and $findings_dir/)"
    failed+=("$target")
  fi
  executions=$(sed -nE 's/^stat::number_of_executed_units: *//p' "$log")
  per_second=$(sed -nE 's/^stat::average_exec_per_sec: *//p' "$log")
  coverage=$(grep -oE 'cov: [0-9]+ ft: [0-9]+' "$log" | tail -n 1 || true)
  echo "fuzz $target: $(($(date +%s) - start)) s, ${executions:-?} executions," \
    "${per_second:-?} exec/s, ${coverage:-no coverage line}, corpus $(find "$corpus" -type f | wc -l)" \
    "files: $status"
done
if ((${#failed[@]})); then
  echo "fuzz: findings in ${failed[*]}" >&2
  exit 1
fi
echo "fuzz: all targets clean"
