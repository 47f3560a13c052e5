# Two commands do everything on a fresh Debian 12 machine:
#   make demo   install dependencies, build the tools the demo runs, run the sample case
#   make test   install dependencies, build everything (tools, tests, bench cases), run the test suite (what CI runs)
BUILD     ?= build
JOBS      ?= $(shell nproc)
CTEST_ARGS ?= -LE bench-long
PREFIX    ?= /usr/local

.PHONY: all deps configure build demo-tools test test-asan fuzz demo bench install clean

all: build

deps:
	./scripts/install-deps

# A new build tree gets Ninja (scripts/install-deps installs it; it schedules the compile units of all
# targets together); an existing tree keeps the generator it was made with.
GENERATOR = $(if $(wildcard $(BUILD)/CMakeCache.txt),,-G Ninja)

# ccache (scripts/install-deps installs it) keeps compiled units between build trees and clones:
# CCACHE_BASEDIR makes the cached compile commands independent of where the clone lives, so a second
# clone or a rebuild compiles only what changed. Without ccache the build is the same, only slower.
CCACHE   := $(shell command -v ccache 2>/dev/null)
LAUNCHER  = $(if $(CCACHE),-DCMAKE_CXX_COMPILER_LAUNCHER=$(CCACHE) -DCMAKE_C_COMPILER_LAUNCHER=$(CCACHE))
export CCACHE_BASEDIR ?= $(CURDIR)
export CCACHE_SLOPPINESS ?= time_macros,include_file_mtime,include_file_ctime

configure: deps
	cmake -S . -B $(BUILD) $(GENERATOR) -DCMAKE_BUILD_TYPE=Release $(LAUNCHER)

build: configure
	cmake --build $(BUILD) -j $(JOBS)

# Only the executables the demo runs (tools/CMakeLists.txt, target ugs-demo-tools): a first
# `make demo` compiles no test (the suite is most of the compile units).
demo-tools: configure
	cmake --build $(BUILD) -j $(JOBS) --target ugs-demo-tools

test: build
	cd $(BUILD) && ctest --output-on-failure -j $(JOBS) $(CTEST_ARGS)

# The suite under AddressSanitizer and UndefinedBehaviorSanitizer, in its own build tree.
test-asan: deps
	cmake -S . -B build-asan -DCMAKE_BUILD_TYPE=Debug -DUGS_SANITIZE=ON
	cmake --build build-asan -j $(JOBS)
	cd build-asan && ASAN_OPTIONS=detect_leaks=1:abort_on_error=1 UBSAN_OPTIONS=print_stacktrace=1 \
	  ctest --output-on-failure -j $(JOBS) -LE "bench-long|no-asan"

# The libFuzzer targets, FUZZ_SECONDS each, in their own clang tree (docs/fuzzing.md: the release run).
FUZZ_SECONDS ?= 600
fuzz: deps
	/usr/bin/python3 tests/fuzz/run_fuzz.py --source $(CURDIR) --build $(CURDIR)/build-fuzz --seconds $(FUZZ_SECONDS) --fuzz-seed 0 --jobs $(JOBS)

# The faulted run goes alongside the continuous one and the calibration (make -j).
demo: demo-tools
	$(MAKE) -C data-samples/po-plain -j $(JOBS) demo UGS_BIN=$(abspath $(BUILD))/tools

bench: build
	./bench/run-all $(BUILD)

install: build
	cmake --install $(BUILD) --prefix $(PREFIX)

clean:
	rm -rf $(BUILD) build-asan

# The suites labelled numerics (tests/*/CMakeLists.txt) under three OpenBLAS kernels: a tolerance that
# holds on one CPU's floating-point path only fails here rather than on a user's machine (issue 39;
# docs/cli.md, Determinism). Debian's OpenBLAS is built with DYNAMIC_ARCH, so OPENBLAS_CORETYPE picks
# the kernel; "native" unsets it (a caller's environment may force one). About 12 min on a loaded
# 2-core machine (735 s at load 13-15, the Sobol' e2e run ~4 min of each pass): not part of `make test`.
# NUMERICS_CTEST_ARGS narrows it (.ci/run: "-E EnsembleSobolSolve", the quick passes in CI).
NUMERICS_CTEST_ARGS ?=
.PHONY: test-numerics-portability
test-numerics-portability: build
	for core in Prescott Haswell native; do \
	  echo "== OpenBLAS kernel: $$core"; \
	  if [ $$core = native ]; then run="env -u OPENBLAS_CORETYPE"; else run="env OPENBLAS_CORETYPE=$$core"; fi; \
	  (cd $(BUILD) && $$run ctest --output-on-failure -j $(JOBS) -L numerics $(NUMERICS_CTEST_ARGS)) || exit 1; \
	done
