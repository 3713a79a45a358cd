#!/bin/bash
# subdirectory.sh SRC: a host project that embeds rg2 with add_subdirectory (the usual way to
# vendor a CMake library, or FetchContent) must configure, and its program must compile rg2's
# sources and see rg2.h: the top-level CMakeLists.txt once took every path from
# CMAKE_SOURCE_DIR / CMAKE_BINARY_DIR, the host's directories there ("cmake/rg2.pc.in does not
# exist", no sources); its tests are off by default there. Configured and built dry (make -n): the sources are compiled for real by
# every other test.
set -u
src=${1:?source dir}
tmp=$(mktemp -d) || exit 1
trap 'rm -rf "$tmp"' EXIT
mkdir -p "$tmp/host"
cp "$src/examples/c/torus_quarter.c" "$tmp/host/app.c"
cat >"$tmp/host/CMakeLists.txt" <<EOT
cmake_minimum_required(VERSION 3.16)
project(host C)
add_subdirectory("$src" rg2)
add_executable(app app.c)
target_link_libraries(app PRIVATE rg2::rg2) # (the alias of the installed package's name)
EOT
cmake -S "$tmp/host" -B "$tmp/build" -G "Unix Makefiles" >"$tmp/cfg.log" 2>&1 || { cat "$tmp/cfg.log"; echo "FAIL: a host project with add_subdirectory(rg2) does not configure"; exit 1; }
[ -f "$tmp/build/rg2/rg2.pc" ] || { echo "FAIL: rg2.pc not generated in rg2's build directory"; exit 1; }
[ ! -d "$tmp/build/rg2/tests" ] || { echo "FAIL: a subproject rg2 configured its tests (RG2_BUILD_TESTS defaults to ON only at the top level)"; exit 1; }
# (make -n stops at the not yet built librg2.a the program links: the commands before it are the test)
dry=$(cmake --build "$tmp/build" --target app -- -n 2>&1)
echo "$dry" | grep -q "src/pool.c" || { echo "FAIL: the host build does not compile rg2's src/pool.c"; exit 1; }
echo "$dry" | grep "app.c" | grep -q -- "-I$src/include" || { echo "FAIL: the host program does not get rg2's include directory"; exit 1; }
echo "subdirectory: a host project with add_subdirectory(rg2) configures and builds rg2 and its program: ok"
