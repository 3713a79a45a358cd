#!/usr/bin/env bash
# make check-tsan (make test runs it): data races between threads, with two detectors.
#   tsan      clang -fsanitize=thread, -DRG2_NO_CLONES (the resolver of the AVX-512 clones runs
#             before TSan's runtime is set up, rg2.h), OpenMP through LLVM's libomp with its
#             Archer tool (OMP_TOOL_LIBRARIES: it tells TSan about OpenMP's barriers and locks;
#             libomp itself is not instrumented, hence ignore_noninstrumented_modules=1). Runs the
#             tests that use threads: test_threads (concurrent callers of every call, the check
#             and the locales among them), test_pool, and tests of calls with OpenMP regions.
#             test_grid (40 s under TSan), test_check (20 s) and test_locale (5 s) are left out:
#             test_threads runs the grid, the check and both locales on threads.
#   helgrind  valgrind's helgrind on test_threads' parsing stage, built with GCC without OpenMP.
#             The JSON parser is Debian's libcjson, which nothing here instruments for TSan, and
#             its parse writes process-wide state (src/json.c): only valgrind sees those writes.
# Both trees are kept between runs (incremental builds). Usage: scripts/check_tsan.sh <source-dir> <build-root>
set -eu
src=$(cd "$1" && pwd) root=$2
mkdir -p "$root" && root=$(cd "$root" && pwd)
jobs=$(nproc 2>/dev/null || echo 2)
for tool in clang valgrind; do
  command -v $tool >/dev/null || { echo "check-tsan: $tool is not installed (scripts/deps.sh test)" >&2; exit 1; }
done
archer=$(dirname "$(readlink -f "$(command -v clang)")")/../lib/libarcher.so
[ -f "$archer" ] || { echo "check-tsan: no $archer (libomp-dev: scripts/deps.sh test)" >&2; exit 1; }
tests="test_threads test_pool test_tess test_surface test_cap test_render test_export"
t0=$(date +%s)

build() { # name, build type, then cmake options; builds the targets in $targets
  local dir=$root/$1 type=$2; shift 2
  cmake -S "$src" -B "$dir" -DCMAKE_BUILD_TYPE="$type" -DRG2_BUILD_TESTS=ON -DRG2_OCCT_TESTS=OFF "$@" \
    >"$dir.cmake.log" 2>&1 || { cat "$dir.cmake.log"; echo "check-tsan: cmake failed ($dir)" >&2; exit 1; }
  # shellcheck disable=SC2086
  cmake --build "$dir" -j"$jobs" --target $targets >"$dir.build.log" 2>&1 ||
    { grep -E "error|warning" "$dir.build.log" | head -40; echo "check-tsan: build failed ($dir.build.log)" >&2; exit 1; }
}

echo "check-tsan: ThreadSanitizer build (clang, libomp + Archer)"
targets=$tests
build tsan RelWithDebInfo -DCMAKE_C_COMPILER=clang -DCMAKE_C_FLAGS="-fsanitize=thread -DRG2_NO_CLONES -Werror" \
  -DCMAKE_EXE_LINKER_FLAGS=-fsanitize=thread -DCMAKE_SHARED_LINKER_FLAGS=-fsanitize=thread
# die_after_fork=0: test_pool calls the pool in a forked child (TSan refuses threads after a fork)
(cd "$root/tsan" && OMP_TOOL_LIBRARIES=$archer \
  TSAN_OPTIONS="ignore_noninstrumented_modules=1 die_after_fork=0 history_size=4" \
  ctest -j"$jobs" --output-on-failure -R "^(${tests// /|})\$" >"$root/tsan.ctest.log" 2>&1) ||
  { grep -E -A30 "WARNING: ThreadSanitizer|FAIL|Failed" "$root/tsan.ctest.log" | head -80
    echo "check-tsan: tsan: failed ($root/tsan.ctest.log)" >&2; exit 1; }
echo "check-tsan: tsan: $(grep -E "tests passed" "$root/tsan.ctest.log")"

echo "check-tsan: helgrind build (GCC, no OpenMP, unoptimised: it builds in half the time)"
targets=test_threads
build helgrind Debug -DCMAKE_C_COMPILER=gcc -DCMAKE_C_FLAGS=-Werror -DRG2_OPENMP=OFF
(cd "$src" && valgrind --tool=helgrind --error-exitcode=1 "$root/helgrind/tests/test_threads" parse \
  >"$root/helgrind.log" 2>&1) ||
  { grep -E -A20 "Possible data race|FAIL" "$root/helgrind.log" | head -60
    echo "check-tsan: helgrind: races or failures ($root/helgrind.log)" >&2; exit 1; }
echo "check-tsan: helgrind: $(grep -E "ERROR SUMMARY" "$root/helgrind.log" | sed 's/^==[0-9]*== //') ($(tail -n 20 "$root/helgrind.log" | grep -E "passed"))"
echo "check-tsan: $(($(date +%s) - t0)) s"
