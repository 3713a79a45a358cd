#!/bin/bash
# embed.sh BUILD SRC [CFLAGS]: install the build tree into a temporary prefix and compile
# examples/c/torus_quarter.c with the line its header documents (pkg-config --static rg2), then
# run it: the program checks its torus against the implicit equation and writes STEP. The compiler
# is $CC (the one that built the library: ctest sets it), else cc.
set -u
build=${1:?build dir} src=${2:?source dir} extra=${3:-}
tmp=$(mktemp -d) || exit 1
trap 'rm -rf "$tmp"' EXIT
cmake --install "$build" --prefix "$tmp/prefix" >"$tmp/install.log" 2>&1 || { cat "$tmp/install.log"; echo "FAIL: cmake --install"; exit 1; }
export PKG_CONFIG_PATH=$tmp/prefix/lib/pkgconfig
flags=$(pkg-config --cflags --libs --static rg2) || { echo "FAIL: pkg-config rg2"; exit 1; }
# shellcheck disable=SC2086
"${CC:-cc}" $extra "$src/examples/c/torus_quarter.c" $flags -o "$tmp/torus_quarter" || { echo "FAIL: ${CC:-cc} ... \$(pkg-config --cflags --libs --static rg2)"; exit 1; }
out=$("$tmp/torus_quarter" "$tmp/q.step") || { echo "FAIL: torus_quarter: $out"; exit 1; }
head -c 13 "$tmp/q.step" | grep -q "ISO-10303-21" || { echo "FAIL: no STEP file written"; exit 1; }
echo "$out"
echo "embed: installed, compiled with pkg-config --static rg2, ran: ok"
