#!/usr/bin/env bash
# The target_clones copies of the library's functions (RG2_HOT, src/grid.c: AVX-512, AVX2 and
# baseline) must hold no multiply-add: the library is built with -ffp-contract=off so that every
# clone rounds as the baseline does (the grid's promise of the same bits whatever outputs are
# asked rests on it on CPUs that take the clones), but GCC's vectoriser has formed a
# vfmaddsub in a clone despite it (rg2_patch_eval's curvatures, twenty-fourth stop). The
# hand-written AVX-512 kernels use multiply-adds on purpose; they are not clones.
# usage: clones.sh LIBRARY EXPECT (EXPECT 1: a GCC x86-64 build with clones, tests/CMakeLists.txt)
lib=$1 expect=${2:-0}
command -v objdump >/dev/null || { echo "objdump not found (binutils)"; exit 1; }
# per function of the disassembly: "name count", count = its multiply-add instructions
counts=$(objdump -d --no-show-raw-insn "$lib" | awk '
  /^[0-9a-f]+ <.*>:$/ { if (f != "") print f, k; f = ""; k = 0
                        if ($2 ~ /\.(arch_x86_64_v[34]|default)>:$/) { f = substr($2, 2, length($2) - 3) } next }
  f != "" && /vf(n)?m(add|sub)/ { k++ }
  END { if (f != "") print f, k }') || exit 1
clones=$(printf '%s\n' "$counts" | awk 'NF == 2 {print $1}' | sort -u)
if [ -z "$clones" ]; then
  if [ "$expect" = 1 ]; then
    echo "FAIL: a GCC x86-64 build without target_clones copies in $lib"; exit 1
  fi
  echo "no target_clones copies in this build (clang, RG2_NO_CLONES, RG2_NATIVE or not x86-64): nothing to check"
  exit 0
fi
bad=0
n=$(printf '%s\n' "$clones" | wc -l)
while read -r f k; do
  [ -n "$f" ] && [ "$k" -ne 0 ] && { echo "FAIL: $f holds $k multiply-add instructions"; bad=1; }
done <<<"$counts"
[ "$expect" = 1 ] || { echo "FAIL: target_clones copies where none were expected"; exit 1; }
for want in rg2_patch_point rg2_patch_point_normal grid_patch; do
  printf '%s\n' "$clones" | grep -qx "$want.arch_x86_64_v4" || { echo "FAIL: no AVX-512 clone of $want"; bad=1; }
done
[ $bad = 0 ] && echo "ok: $n clone copies, none with a multiply-add"
exit $bad
