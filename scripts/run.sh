#!/usr/bin/env bash
# make run: the main job on the bundled example design.
set -eu
rg2=$1 design=$2 out=$3
if [ -f "$design" ] && "$rg2" --help | grep -q '^  build'; then
  "$rg2" info "$design"
  exec "$rg2" build "$design" -o "$out/$(basename "${design%.json}").step"
fi
"$rg2" demo
