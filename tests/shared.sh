#!/bin/bash
# shared.sh SRC: rg2 built as a shared library (-DBUILD_SHARED_LIBS=ON), as a distribution would
# package it. Checked: the SONAME carries the header's version (librg2.so.MAJOR.MINOR before 1.0,
# when a minor version may change the ABI; it was a bare librg2.so, so every version claimed the
# same ABI); the library exports only rg2_ names, each an identifier (GCC's target_clones
# resolvers, rg2_f.resolver, were exported too); rg2.pc and `rg2 --version` say the header's
# version; an installed copy links through plain pkg-config (with rg2.pc alone on the path:
# cJSON's and libpng's .pc files are not needed) and the example program runs on it.
# The compiler is $CC (ctest sets the one that built the tests), else cc.
set -u
src=${1:?source dir}
tmp=$(mktemp -d) || exit 1
trap 'rm -rf "$tmp"' EXIT
for tool in readelf nm pkg-config; do
    command -v "$tool" >/dev/null 2>&1 || { echo "FAIL: $tool is needed (binutils, pkg-config)"; exit 1; }
done
ver() { sed -n "s/^#define RG2_VERSION_$1 \([0-9][0-9]*\)$/\1/p" "$src/include/rg2.h"; }
major=$(ver MAJOR) minor=$(ver MINOR) patch=$(ver PATCH)
[ -n "$major" ] && [ -n "$minor" ] && [ -n "$patch" ] || { echo "FAIL: no RG2_VERSION_MAJOR/MINOR/PATCH in rg2.h"; exit 1; }
if [ "$major" = 0 ]; then soname=librg2.so.0.$minor; else soname=librg2.so.$major; fi
# the caller's sanitizer flags are not wanted here (ctest runs this from the ASan build)
env -u CFLAGS -u LDFLAGS cmake -S "$src" -B "$tmp/build" -DCMAKE_BUILD_TYPE=Release -DBUILD_SHARED_LIBS=ON \
    -DRG2_BUILD_TESTS=OFF ${CC:+-DCMAKE_C_COMPILER="$CC"} >"$tmp/log" 2>&1 &&
    cmake --build "$tmp/build" -j2 >>"$tmp/log" 2>&1 || { tail -30 "$tmp/log"; echo "FAIL: the shared build"; exit 1; }
lib=$(readlink -f "$tmp/build/librg2.so")
got=$(readelf -d "$lib" | sed -n 's/.*Library soname: \[\(.*\)\]/\1/p')
[ "$got" = "$soname" ] || { echo "FAIL: SONAME '$got', expected '$soname' (rg2.h says $major.$minor.$patch)"; exit 1; }
[ "$(basename "$lib")" = "librg2.so.$major.$minor.$patch" ] || { echo "FAIL: the library file is $(basename "$lib")"; exit 1; }
other=$(nm -D --defined-only "$lib" | awk '$3 !~ /^rg2_[A-Za-z0-9_]+$/ {print $3}')
[ -z "$other" ] || { echo "FAIL: librg2.so exports names other than rg2_ and an identifier (a target_clones resolver such as rg2_f.resolver goes into cmake/rg2.map's local list):"; echo "$other" | head; exit 1; }
n=$(nm -D --defined-only "$lib" | grep -c ' rg2_')
out=$("$tmp/build/rg2" --version) || { echo "FAIL: rg2 --version on the shared library"; exit 1; }
[ "$out" = "rg2 $major.$minor.$patch" ] || { echo "FAIL: rg2 --version says '$out'"; exit 1; }
cmake --install "$tmp/build" --prefix "$tmp/prefix" >>"$tmp/log" 2>&1 || { tail "$tmp/log"; echo "FAIL: cmake --install"; exit 1; }
[ -L "$tmp/prefix/lib/$soname" ] && [ -L "$tmp/prefix/lib/librg2.so" ] || { ls -l "$tmp/prefix/lib"; echo "FAIL: the installed $soname / librg2.so links"; exit 1; }
out=$(env -u LD_LIBRARY_PATH "$tmp/prefix/bin/rg2" --version 2>&1) && [ "$out" = "rg2 $major.$minor.$patch" ] ||
    { echo "FAIL: the installed rg2 does not run on the installed library: $out"; exit 1; }
# rg2.h uses neither cJSON nor libpng, and librg2.so links them itself: plain pkg-config works
# with no .pc file but rg2's (rg2.pc had Requires.private: libcjson libpng, which pkg-config
# reads even without --static: "Package libcjson was not found"), and --static still names them
only=(env PKG_CONFIG_LIBDIR="$tmp/prefix/lib/pkgconfig" PKG_CONFIG_PATH=)
out=$("${only[@]}" pkg-config --cflags --libs rg2 2>&1) ||
    { echo "FAIL: pkg-config --cflags --libs rg2 with only rg2.pc on the path: $out"; exit 1; }
out=$("${only[@]}" pkg-config --libs --static rg2 2>&1) && echo " $out " | grep -q -- " -lcjson " &&
    echo " $out " | grep -q -- " -lpng[0-9]* " ||
    { echo "FAIL: pkg-config --libs --static rg2 does not name cJSON and libpng: $out"; exit 1; }
export PKG_CONFIG_PATH=$tmp/prefix/lib/pkgconfig
[ "$(pkg-config --modversion rg2)" = "$major.$minor.$patch" ] || { echo "FAIL: rg2.pc says $(pkg-config --modversion rg2)"; exit 1; }
# shellcheck disable=SC2046
"${CC:-cc}" "$src/examples/c/torus_quarter.c" $(pkg-config --cflags --libs rg2) -o "$tmp/app" || { echo "FAIL: cc app.c \$(pkg-config --cflags --libs rg2)"; exit 1; }
readelf -d "$tmp/app" | grep -q "NEEDED.*\[$soname\]" || { echo "FAIL: the program does not record $soname"; exit 1; }
out=$(LD_LIBRARY_PATH=$tmp/prefix/lib "$tmp/app" "$tmp/q.step") || { echo "FAIL: the program on the installed shared library: $out"; exit 1; }
head -c 13 "$tmp/q.step" | grep -q "ISO-10303-21" || { echo "FAIL: no STEP file written"; exit 1; }
echo "shared: $soname ($n rg2_ names exported, nothing else), installed, linked with pkg-config, ran: ok"
