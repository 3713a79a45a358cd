# rg2 top-level Makefile: thin wrapper over CMake.
#   make run    build and run the main job on the bundled example design (outputs in out/)
#   make test   install what is missing, build under ASan+UBSan, run every test
#   make bench  build optimised and run the benchmark against SISL and OpenCASCADE
#   make check-memory  the rg2 command under valgrind on every example and bad input (make test runs it)
#   make check-portable  build with clang, and with GCC without OpenMP or AVX-512; run the tests (make test runs it)
#   make check-tsan  the threaded tests under ThreadSanitizer, the parser under helgrind (make test runs it)
#   make fuzz   build the libFuzzer harnesses (clang) into build-fuzz/ and run each FUZZ_SECONDS
#   make gallery  render every example design into docs/pictures/gallery/ and write docs/gallery.md
#   make check-freecad  FreeCAD opens our STEP / IGES (installs freecad-python3, ~930 MB; not in make test)
#   make check-cross ARCH=aarch64|s390x|i686  cross build, every test under qemu-user (slow: 30-60 min
#               or more an architecture; installs a cross GCC and qemu-user; not in make test)
JOBS ?= $(shell nproc 2>/dev/null || echo 2)
MAKEFLAGS += --no-print-directory
DESIGN ?= examples/torus_sphere.json
FUZZ_SECONDS ?= 60

ARCH ?= aarch64

.PHONY: all build run test bench clean check-memory check-portable check-tsan check-freecad check-cross fuzz gallery

all: build

build:
	@scripts/deps.sh base
	@cmake -S . -B build -DCMAKE_BUILD_TYPE=Release -DRG2_BUILD_TESTS=OFF >/dev/null
	@cmake --build build -j$(JOBS) | grep -E "warning|error|Linking" || true

run: build
	@mkdir -p out
	@scripts/run.sh build/rg2 $(DESIGN) out

test:
	@scripts/deps.sh test
	@cmake -S . -B build-test -DCMAKE_BUILD_TYPE=RelWithDebInfo -DRG2_SANITIZE=ON -DRG2_BUILD_TESTS=ON >/dev/null
	@cmake --build build-test -j$(JOBS)
	@cd build-test && ASAN_OPTIONS=detect_leaks=1 LSAN_OPTIONS=suppressions=$(CURDIR)/tests/lsan.supp ctest --output-on-failure -j$(JOBS)
	@$(MAKE) --no-print-directory check-memory
	@$(MAKE) --no-print-directory check-portable
	@$(MAKE) --no-print-directory check-tsan

# valgrind needs a build without sanitizers: build/ (Release, with debug info for the reports)
check-memory:
	@scripts/deps.sh test
	@cmake -S . -B build -DCMAKE_BUILD_TYPE=Release -DCMAKE_C_FLAGS=-g -DRG2_BUILD_TESTS=OFF >/dev/null
	@cmake --build build -j$(JOBS)
	@scripts/check_memory.sh build/rg2 .

# the library, the command and the tests with clang, and with GCC on the portable paths
check-portable:
	@scripts/deps.sh test
	@scripts/check_portable.sh . build-portable

# races: ThreadSanitizer (clang, libomp + Archer) and helgrind, in build-tsan/ (kept: incremental)
check-tsan:
	@scripts/deps.sh test
	@scripts/check_tsan.sh . build-tsan

gallery: build
	@scripts/gallery.py build/rg2 docs

check-freecad: build
	@scripts/deps.sh freecad
	@scripts/freecad_check.sh build/rg2 .

check-cross:
	@scripts/check_cross.sh . build-cross-$(ARCH) $(ARCH)

fuzz:
	@scripts/deps.sh fuzz
	@scripts/fuzz.sh $(FUZZ_SECONDS)

bench:
	@scripts/deps.sh bench
	@cmake -S . -B build-bench -DCMAKE_BUILD_TYPE=Release -DRG2_BUILD_TESTS=OFF -DRG2_BUILD_BENCH=ON >/dev/null
	@cmake --build build-bench -j$(JOBS)
	@mkdir -p out
	@build-bench/bench/rg2_bench out/bench.json

clean:
	rm -rf build build-test build-bench build-fuzz build-portable build-tsan out
