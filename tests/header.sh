#!/bin/bash
# header.sh SRC: include/rg2.h compiles without a warning in a host's strictest settings: C11 and
# C17 with gcc and clang, C++98, C++11 and C++20 with g++ and clang++, all under -Werror with
# -Wold-style-cast, -Wzero-as-null-pointer-constant, -Wconversion, -Wsign-conversion, -Wcast-qual
# and -Wshadow. The inline helpers are called, so their bodies are checked in use. (C++ hosts with
# -Wold-style-cast -Werror could not include the header: its helpers cast with (size_t) and
# returned 0 for a null pointer.) A compiler that is not installed is skipped; gcc and g++ must be.
set -u
src=${1:?source dir}
tmp=$(mktemp -d) || exit 1
trap 'rm -rf "$tmp"' EXIT
cat >"$tmp/host.c" <<'EOT'
#include "rg2.h"
int host_use(const rg2_mesh *m, const rg2_surface *s);
int host_use(const rg2_mesh *m, const rg2_surface *s)
{
    double *p = rg2_mesh_at(m, 1, 2);
    rg2_patch *a = rg2_surface_patch(s, 0, 1);
    const rg2_xpatch *x = rg2_surface_xpatch(s, 1, 0);
    return !p + !a + !x + !rg2_version() + (rg2_version_number() != RG2_VERSION_NUMBER);
}
EOT
cp "$tmp/host.c" "$tmp/host.cpp"
strict="-Wall -Wextra -Wpedantic -Wconversion -Wsign-conversion -Wcast-qual -Wshadow -Werror"
fails=0 runs=0
one() { # compiler, language standard, file, extra flags
    command -v "$1" >/dev/null 2>&1 || { echo "skip: $1 not installed"; return; }
    runs=$((runs + 1))
    # shellcheck disable=SC2086
    if ! out=$("$1" -std="$2" $strict $4 -I"$src/include" -c "$3" -o "$tmp/host.o" 2>&1); then
        echo "FAIL: $1 -std=$2: rg2.h does not compile cleanly"; echo "$out" | head -20; fails=$((fails + 1))
    fi
}
command -v gcc >/dev/null && command -v g++ >/dev/null || { echo "FAIL: gcc and g++ are needed"; exit 1; }
for cc in gcc clang; do
    for std in c11 c17; do one $cc $std "$tmp/host.c" "-Wstrict-prototypes -Wmissing-prototypes"; done
done
for cxx in g++ clang++; do
    for std in c++98 c++11 c++20; do one $cxx $std "$tmp/host.cpp" "-Wold-style-cast -Wzero-as-null-pointer-constant"; done
done
[ "$fails" = 0 ] || exit 1
echo "header: rg2.h clean under strict warnings in $runs compiler/standard pairs: ok"
