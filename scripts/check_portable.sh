#!/usr/bin/env bash
# make check-portable (make test runs it): the library, the rg2 command and the tests built two
# more ways, warnings as errors, and every test run on each:
#   clang   the compiler many embedders use (its OpenMP through libomp, which deps.sh installs)
#   plain   GCC without OpenMP and without the AVX-512 kernels and clones (RG2_OPENMP=OFF,
#           -DRG2_NO_CLONES): the portable paths, one thread
# Usage: scripts/check_portable.sh <source-dir> <build-root>
set -eu
src=$(cd "$1" && pwd) root=$2
mkdir -p "$root" && root=$(cd "$root" && pwd)
command -v clang >/dev/null || { echo "check-portable: clang is not installed (scripts/deps.sh test)" >&2; exit 1; }
jobs=$(nproc 2>/dev/null || echo 2)
one() { # name, C compiler, C++ compiler, C flags, then cmake options
  local name=$1 cc=$2 cxx=$3 cflags=$4; shift 4
  local dir=$root/$name
  echo "check-portable: $name build"
  CC=$cc CXX=$cxx CFLAGS=$cflags cmake -S "$src" -B "$dir" -DCMAKE_BUILD_TYPE=RelWithDebInfo -DRG2_BUILD_TESTS=ON "$@" \
    >"$dir.cmake.log" 2>&1 ||
    { cat "$dir.cmake.log"; echo "check-portable: $name: cmake failed" >&2; exit 1; }
  cmake --build "$dir" -j"$jobs" >"$dir.build.log" 2>&1 ||
    { grep -E "error|warning" "$dir.build.log" | head -40; echo "check-portable: $name: build failed (warnings are errors)" >&2; exit 1; }
  (cd "$dir" && ctest -j"$jobs" --output-on-failure >"$dir.ctest.log" 2>&1) ||
    { grep -E "FAIL|Failed|\*\*\*" "$dir.ctest.log" | head -40; echo "check-portable: $name: tests failed ($dir.ctest.log)" >&2; exit 1; }
  echo "check-portable: $name: $(grep -E "tests passed" "$dir.ctest.log")"
}
# (CFLAGS reaches only a fresh cache, hence the fresh build trees: -Werror for our sources and tests)
rm -rf "$root/clang" "$root/plain"
one clang clang clang++ -Werror
one plain gcc g++ "-Werror -DRG2_NO_CLONES" -DRG2_OPENMP=OFF
