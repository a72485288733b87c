# simtree's front door. `make demo` and `make test` each install what they need (Debian 12),
# build, then run. Everything else is a step of those two.

BUILD      ?= build
ASAN_BUILD ?= build-asan
BENCH_BUILD ?= build-bench
ODR_BUILD  ?= build-odr
FUZZ_BUILD ?= build-fuzz
JOBS       ?= $(shell nproc)
SHARED     ?= $(abspath ../shared)
SIMTREE    := $(BUILD)/bin/simtree
# Warnings are errors in CI (CI=true), warnings elsewhere.
WERROR     := $(if $(filter true,$(CI)),ON,OFF)
# Unity builds: CMake compiles a target's sources eight to a file, so Eigen, Open3D and the
# standard headers are parsed and their templates instantiated once per eight sources instead of
# once per source. File-local names must differ across a target's sources (UNITY=OFF builds each
# source alone, as the odr-check does).
UNITY      ?= ON
CMAKE_ARGS := -DSIMTREE_SHARED_DIR=$(SHARED) -DSIMTREE_WERROR=$(WERROR) -DCMAKE_UNITY_BUILD=$(UNITY)

.PHONY: all deps configure build cli demo test test-fast asan odr-check fuzz bench format clean

all: build

deps:
	@scripts/install-deps.sh

configure: deps
	cmake -S . -B $(BUILD) -DCMAKE_BUILD_TYPE=Release $(CMAKE_ARGS)

# Everything: libraries, the CLI, tests.
build: configure
	cmake --build $(BUILD) -j $(JOBS)

# Only the CLI (what the demo needs).
cli: configure
	cmake --build $(BUILD) -j $(JOBS) --target simtree

# The main job end to end: synth of the default species into out/demo/capture, `simtree run` into
# out/demo/result, `simtree eval` against the truth; prints the path of report.html.
demo: cli
	@scripts/demo.sh $(SIMTREE) out/demo

# Every test (fast and end-to-end) in the Release build.
test: build
	ctest --test-dir $(BUILD) --output-on-failure -j $(JOBS)

test-fast: build
	ctest --test-dir $(BUILD) --output-on-failure -j $(JOBS) -L fast

# The fast suite under AddressSanitizer + UndefinedBehaviorSanitizer; the slow suites are not built.
# -O1 -g1: sanitizer reports keep function names and lines, and the heavy template files build in
# well under half the time of -O2 -g (core/tree_json.cc: 47 s -> 18 s); CI builds the project
# three times (Release, sanitizers, fuzzers).
asan: deps
	cmake -S . -B $(ASAN_BUILD) -DCMAKE_BUILD_TYPE=RelWithDebInfo \
	  -DCMAKE_CXX_FLAGS_RELWITHDEBINFO="-O1 -g1 -DNDEBUG" -DSIMTREE_SANITIZE=ON \
	  -DSIMTREE_SLOW_TESTS=OFF $(CMAKE_ARGS)
	cmake --build $(ASAN_BUILD) -j $(JOBS)
	ASAN_OPTIONS=detect_leaks=1:detect_container_overflow=0:abort_on_error=1 \
	UBSAN_OPTIONS=print_stacktrace=1:halt_on_error=1 \
	  ctest --test-dir $(ASAN_BUILD) --output-on-failure -j $(JOBS) -L fast

# The compiler's one-definition-rule check: every library linked into one LTO program with -Wodr
# (simtree_odr_check). Every build's TypeNames tests make the same check from the sources in a
# second; this one also sees what the sources cannot show (macros, generated code). Not in CI: the
# fat LTO objects double the build.
odr-check: deps
	cmake -S . -B $(ODR_BUILD) -DCMAKE_BUILD_TYPE=Debug -DCMAKE_CXX_FLAGS_DEBUG=-O0 \
	  -DSIMTREE_ODR_CHECK=ON -DSIMTREE_BUILD_TESTS=OFF -DSIMTREE_BUILD_APPS=OFF $(CMAKE_ARGS) \
	  -DCMAKE_UNITY_BUILD=OFF
	cmake --build $(ODR_BUILD) -j $(JOBS) --target simtree_odr_check

# Every reader under libFuzzer with ASan + UBSan (docs/fuzzing.md): a clang build of the readers'
# libraries only, seeds written by simtree's writers, then each target for FUZZ_SECONDS (FUZZ_JOBS
# at once; FUZZ_TARGETS to pick some). Fails on any crash, hang, memory blowup or sanitizer report.
# -O1 -g1 and assertions on: reports keep their lines, and a failed assert is a finding too.
FUZZ_SECONDS ?= 60
FUZZ_JOBS    ?= 1
FUZZ_TARGETS ?=
fuzz: deps
	cmake -S . -B $(FUZZ_BUILD) -DCMAKE_BUILD_TYPE=RelWithDebInfo -DCMAKE_CXX_FLAGS_RELWITHDEBINFO="-O1 -g1" \
	  -DCMAKE_C_COMPILER=clang-14 -DCMAKE_CXX_COMPILER=clang++-14 -DSIMTREE_FUZZ=ON $(CMAKE_ARGS)
	cmake --build $(FUZZ_BUILD) -j $(JOBS) --target fuzzers
	FUZZ_SECONDS=$(FUZZ_SECONDS) FUZZ_JOBS=$(FUZZ_JOBS) SHARED=$(SHARED) \
	  fuzz/run.sh $(FUZZ_BUILD) $(FUZZ_TARGETS)

# Benchmarks (Google Benchmark and side-by-side peers); see docs/benchmarks.md.
bench: deps
	cmake -S . -B $(BENCH_BUILD) -DCMAKE_BUILD_TYPE=Release -DSIMTREE_BUILD_BENCH=ON $(CMAKE_ARGS)
	cmake --build $(BENCH_BUILD) -j $(JOBS)
	bench/run.sh $(BENCH_BUILD)

format:
	git ls-files '*.cc' '*.h' | xargs clang-format -i

clean:
	rm -rf $(BUILD) $(ASAN_BUILD) $(BENCH_BUILD) $(ODR_BUILD) $(FUZZ_BUILD) out
