# `make demo` and `make test` do the whole set-up on a fresh Debian 12 machine. `make demo` builds
# only the `aperture` executable and the libraries it links (the first result comes fast);
# `make test` builds the rest (test suites) and runs ctest.
BUILD_DIR ?= build
JOBS ?= $(shell nproc)
# Unity build (CMake option APERTURE_UNITY_BUILD): a cold build compiles about a third less
# (docs/results/eco.md), so the fresh-clone path has it on. With a warm compiler cache an edit
# recompiles its whole batch of files: for incremental development use `make UNITY=OFF ...`
# (a separate BUILD_DIR keeps both trees: `make UNITY=OFF BUILD_DIR=build-dev test`).
UNITY ?= ON
DEMO_OUT ?= out/demo
APERTURE := $(BUILD_DIR)/apps/aperture

.PHONY: all deps configure build test test-asan test-tsan test-slurm fuzz fuzz-smoke demo python bench clean

all: build

deps:
	@scripts/install-deps.sh

configure: deps
	@cmake -S . -B $(BUILD_DIR) -G Ninja -DCMAKE_BUILD_TYPE=Release -DAPERTURE_UNITY_BUILD=$(UNITY) >/dev/null

build: configure
	@cmake --build $(BUILD_DIR) -j $(JOBS)

test: build
	@cd $(BUILD_DIR) && ctest --output-on-failure -j $(JOBS)

# Sanitizers (issue 18, scripts/test-sanitized.sh): the suites listed are built at -O1 in their
# own folder and run binary by binary; any finding fails. `make test-asan`: AddressSanitizer +
# UndefinedBehaviorSanitizer (leaks too). `make test-tsan`: ThreadSanitizer over the concurrent
# parts (SUITE:FILTER keeps a suite to its threaded tests); third-party suppressions with their
# reasons in scripts/tsan-suppressions.txt.
ASAN_SUITES ?= config output control
TSAN_SUITES ?= output 'perception:FrameGraph*:ParallelExecutor*:TimingStats*:DurationRecord*'
test-asan: deps
	@scripts/test-sanitized.sh $(BUILD_DIR)-asan address,undefined $(JOBS) $(ASAN_SUITES)
test-tsan: deps
	@scripts/test-sanitized.sh $(BUILD_DIR)-tsan thread $(JOBS) $(TSAN_SUITES)

# libFuzzer targets of fuzz/ (issue 18, scripts/fuzz.sh): clang build in $(BUILD_DIR)-fuzz holding
# only the fuzzers and the parser sources they call; each target runs FUZZ_S seconds in turn and
# any crash, leak, timeout or out-of-memory fails. `fuzz-smoke` is the short CI form.
FUZZ_S ?= 60
fuzz:
	@scripts/install-deps.sh fuzz
	@scripts/fuzz.sh $(BUILD_DIR)-fuzz $(FUZZ_S) $(JOBS)

fuzz-smoke:
	@scripts/install-deps.sh fuzz
	@scripts/fuzz-smoke.sh $(BUILD_DIR)-fuzz-smoke $(JOBS)

# scripts/slurm/bench.sbatch for real: a 4-shard bench plus the merge on a one-node Slurm that the
# test starts on localhost and stops, compared with the unsharded run. The daemons need root:
# through sudo when not root (as scripts/install-deps.sh).
test-slurm: configure
	@cmake --build $(BUILD_DIR) -j $(JOBS) --target aperture
	@if [ "$$(id -u)" -ne 0 ] && command -v sudo >/dev/null; then \
	  sudo scripts/slurm/test-single-node.sh $(APERTURE); \
	else \
	  scripts/slurm/test-single-node.sh $(APERTURE); \
	fi

demo: configure
	@cmake --build $(BUILD_DIR) -j $(JOBS) --target aperture
	@scripts/demo.sh $(APERTURE) $(DEMO_OUT)

# The `aperture` Python module in $(BUILD_DIR)/python/ (python/CMakeLists.txt).
python: configure
	@cmake --build $(BUILD_DIR) -j $(JOBS) --target aperture_python
	@echo "python: PYTHONPATH=$(BUILD_DIR)/python python3 -c 'import aperture; print(aperture.__version__)'"

bench: configure
	@cmake --build $(BUILD_DIR) -j $(JOBS) --target bench
	@for b in $(BUILD_DIR)/tests/*_bench; do echo "== $$b"; $$b --benchmark_min_time=0.2 || exit 1; done

clean:
	rm -rf $(BUILD_DIR)
