#!/bin/bash
# embed.sh BUILD SRC [CFLAGS [pkgconfig|cmake]]: install the build tree into a temporary prefix and
# build examples/c/torus_quarter.c against it the documented way, then run it: the program
# checks its torus against the implicit equation and writes STEP. The compiler is $CC (the one
# that built the library: ctest sets it), else cc.
#   pkgconfig (the default): with the line its header documents (pkg-config --static rg2).
#   cmake: a tiny consumer project, find_package(rg2 REQUIRED) + target_link_libraries(app
#          rg2::rg2), configured with CMAKE_PREFIX_PATH at the prefix (no CMake package was
#          installed: find_package(rg2) failed).
set -u
build=${1:?build dir} src=${2:?source dir} extra=${3:-} mode=${4:-pkgconfig}
tmp=$(mktemp -d) || exit 1
trap 'rm -rf "$tmp"' EXIT
cmake --install "$build" --prefix "$tmp/prefix" >"$tmp/install.log" 2>&1 || { cat "$tmp/install.log"; echo "FAIL: cmake --install"; exit 1; }
case $mode in
pkgconfig)
    export PKG_CONFIG_PATH=$tmp/prefix/lib/pkgconfig
    flags=$(pkg-config --cflags --libs --static rg2) || { echo "FAIL: pkg-config rg2"; exit 1; }
    # shellcheck disable=SC2086
    "${CC:-cc}" $extra "$src/examples/c/torus_quarter.c" $flags -o "$tmp/torus_quarter" || { echo "FAIL: ${CC:-cc} ... \$(pkg-config --cflags --libs --static rg2)"; exit 1; }
    how="compiled with pkg-config --static rg2" ;;
cmake)
    for f in rg2Config.cmake rg2ConfigVersion.cmake rg2Targets.cmake; do
        [ -f "$tmp/prefix/lib/cmake/rg2/$f" ] || { ls -R "$tmp/prefix/lib"; echo "FAIL: no lib/cmake/rg2/$f installed"; exit 1; }
    done
    mkdir -p "$tmp/app"
    cp "$src/examples/c/torus_quarter.c" "$tmp/app/torus_quarter.c"
    cat >"$tmp/app/CMakeLists.txt" <<'EOT'
cmake_minimum_required(VERSION 3.16)
project(app C)
find_package(rg2 REQUIRED)
add_executable(torus_quarter torus_quarter.c)
target_link_libraries(torus_quarter PRIVATE rg2::rg2)
EOT
    ver() { sed -n "s/^#define RG2_VERSION_$1 \([0-9][0-9]*\)$/\1/p" "$src/include/rg2.h"; }
    major=$(ver MAJOR) minor=$(ver MINOR) patch=$(ver PATCH)
    if [ "$major" = 0 ]; then other=0.$((minor + 1)); else other=$((major + 1)).0; fi
    # the package's version file: rg2's own version is found, the next ABI's is not (before 1.0
    # a minor version may change the ABI, as the SONAME says)
    cat >>"$tmp/app/CMakeLists.txt" <<EOT
find_package(rg2 $major.$minor.$patch EXACT REQUIRED)
find_package(rg2 $other QUIET)
if(rg2_FOUND)
  message(FATAL_ERROR "find_package(rg2 $other) accepted rg2 $major.$minor.$patch")
endif()
EOT
    env -u CFLAGS -u LDFLAGS cmake -S "$tmp/app" -B "$tmp/app/build" -DCMAKE_PREFIX_PATH="$tmp/prefix" \
        ${CC:+-DCMAKE_C_COMPILER="$CC"} -DCMAKE_C_FLAGS="$extra" -DCMAKE_EXE_LINKER_FLAGS="$extra" \
        >"$tmp/cfg.log" 2>&1 || { cat "$tmp/cfg.log"; echo "FAIL: find_package(rg2 REQUIRED) in a consumer project"; exit 1; }
    cmake --build "$tmp/app/build" >"$tmp/build.log" 2>&1 || { cat "$tmp/build.log"; echo "FAIL: building the consumer linked to rg2::rg2"; exit 1; }
    cp "$tmp/app/build/torus_quarter" "$tmp/torus_quarter"
    # a C++ project (rg2.h's extern "C"): the package enables C for OpenMP's C component itself
    mkdir -p "$tmp/appxx"
    # (the linked library's version number against the header's: the same install)
    printf '#include <rg2.h>\n#include <cstdio>\nint main() { std::printf("%%s %%d\\n", rg2_version(), rg2_version_number()); return rg2_version_number() != RG2_VERSION_NUMBER; }\n' \
        >"$tmp/appxx/v.cpp"
    cat >"$tmp/appxx/CMakeLists.txt" <<'EOT'
cmake_minimum_required(VERSION 3.16)
project(appxx CXX)
find_package(rg2 REQUIRED)
add_executable(v v.cpp)
target_link_libraries(v PRIVATE rg2::rg2)
EOT
    # the C++ compiler of the C compiler's family (the sanitizer runtimes of GCC and clang differ)
    case "${CC:-}" in *clang*) cxx=${CC%clang*}clang++${CC##*clang} ;; *gcc*) cxx=${CC%gcc*}g++${CC##*gcc} ;; *) cxx= ;; esac
    command -v "$cxx" >/dev/null 2>&1 || cxx=
    env -u CFLAGS -u CXXFLAGS -u LDFLAGS cmake -S "$tmp/appxx" -B "$tmp/appxx/build" -DCMAKE_PREFIX_PATH="$tmp/prefix" \
        ${CC:+-DCMAKE_C_COMPILER="$CC"} ${cxx:+-DCMAKE_CXX_COMPILER="$cxx"} \
        -DCMAKE_CXX_FLAGS="$extra" -DCMAKE_EXE_LINKER_FLAGS="$extra" \
        >"$tmp/cfgxx.log" 2>&1 || { cat "$tmp/cfgxx.log"; echo "FAIL: find_package(rg2 REQUIRED) in a C++ project"; exit 1; }
    cmake --build "$tmp/appxx/build" >"$tmp/buildxx.log" 2>&1 || { cat "$tmp/buildxx.log"; echo "FAIL: building the C++ consumer"; exit 1; }
    v=$("$tmp/appxx/build/v") && [ "$v" = "$major.$minor.$patch $((major * 10000 + minor * 100 + patch))" ] ||
        { echo "FAIL: the C++ consumer did not run, or its library's version is not the header's: '$v'"; exit 1; }
    how="built with find_package(rg2) and rg2::rg2, in C and in C++ (rg2 $v)" ;;
*) echo "FAIL: unknown mode '$mode'"; exit 1 ;;
esac
out=$("$tmp/torus_quarter" "$tmp/q.step") || { echo "FAIL: torus_quarter: $out"; exit 1; }
head -c 13 "$tmp/q.step" | grep -q "ISO-10303-21" || { echo "FAIL: no STEP file written"; exit 1; }
echo "$out"
echo "embed: installed, $how, ran: ok"
