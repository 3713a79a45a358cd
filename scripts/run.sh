#!/usr/bin/env bash
# make run: the main job on the bundled example design (default: the paper's Fig. 8, a torus
# joined with a sphere). Builds it into CAD and mesh files, renders three pictures from the
# exact surface, and prints the design summary and the exactness/continuity check.
set -eu
rg2=$1 design=$2 out=$3
name=$(basename "${design%.json}")
"$rg2" info "$design"
echo
"$rg2" build -q "$design" -o "$out/$name.step" -o "$out/$name.igs" -o "$out/$name.glb"
echo "wrote $out/$name.step $out/$name.igs $out/$name.glb"
for mode in shaded mean zebra; do
  opts=""
  [ "$mode" = shaded ] && opts="--boundaries"
  "$rg2" render "$design" -o "$out/$name-$mode.png" --mode "$mode" $opts
done
echo "wrote $out/$name-shaded.png $out/$name-mean.png $out/$name-zebra.png"
echo
"$rg2" check "$design" --require g2,exact,weights
