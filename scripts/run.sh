#!/usr/bin/env bash
# make run: the main job on the bundled example design.
set -eu
rg2=$1 design=$2 out=$3
# Pictures (per-pixel exact: shaded with patch boundaries, mean curvature, zebra) and the check table.
if [ -f "$design" ] && "$rg2" --help | grep -q '^  render'; then
  name=$(basename "${design%.json}")
  "$rg2" render "$design" -o "$out/$name-shaded.png" --mode shaded --boundaries
  "$rg2" render "$design" -o "$out/$name-mean.png" --mode mean
  "$rg2" render "$design" -o "$out/$name-zebra.png" --mode zebra
  echo "pictures: $out/$name-shaded.png $out/$name-mean.png $out/$name-zebra.png"
  "$rg2" check "$design"
fi
if [ -f "$design" ] && "$rg2" --help | grep -q '^  build'; then
  "$rg2" info "$design"
  exec "$rg2" build "$design" -o "$out/$(basename "${design%.json}").step"
fi
"$rg2" demo
