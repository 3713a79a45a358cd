#!/usr/bin/env bash
# CLI on a design whose output holds patches of higher degree (Fig. 15: the general-quadratic
# saddle cap, degree (5,3) cap patches): rg2 info counts them per degree on the surface line
# (and says nothing on all-bi-3 surfaces); rg2 render pictures them, the same bytes for 1 and 2
# threads; rg2 check holds G2 and exactness on them.
# Usage: bash xdegree.sh <path-to-rg2> <source-dir>
set -u
. "$(dirname "$0")/lib.sh"
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
ex=$SRC/examples/fig15_saddle_caps.json

out=$("$RG2" info "$ex" 2>&1)
line1=$(printf '%s\n' "$out" | grep '^surface 1:')
line0=$(printf '%s\n' "$out" | grep '^surface 0:')
# the cap rows are degree (5,3); the body may be stored at the caps' degree too
case "$line1" in *"= 96 patches ("[0-9]*" of degree (5,3))") ok ;; *) bad "info surface 1: '$line1'" ;; esac
n5=$(printf '%s\n' "$line1" | sed -n 's/.*(\([0-9]*\) of degree (5,3))$/\1/p')
[ -n "$n5" ] && [ "$n5" -ge 24 ] && ok || bad "info surface 1: $n5 patches of degree (5,3), at least the 24 cap patches"
case "$line0" in *"= 96 patches") ok ;; *) bad "info surface 0 (all bi-3): '$line0'" ;; esac
expect 0 "" -- "$RG2" info --help
"$RG2" info --help | grep -q "of degree" && ok || bad "info --help does not mention higher degrees"

for mode in shaded mean; do
  "$RG2" render "$ex" --surface 1 -o "$tmp/$mode.1.png" --mode "$mode" --size 120x90 --threads 1 &&
    "$RG2" render "$ex" --surface 1 -o "$tmp/$mode.2.png" --mode "$mode" --size 120x90 --threads 2 &&
    [ -s "$tmp/$mode.1.png" ] && cmp -s "$tmp/$mode.1.png" "$tmp/$mode.2.png" && ok ||
    bad "render $mode of the degree-(5,3) caps failed or depends on the thread count"
done
expect 0 "" -- "$RG2" check "$ex" --require g2,exact,weights
finish
