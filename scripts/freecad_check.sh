#!/usr/bin/env bash
# FreeCAD 0.20 (Debian freecad-python3, through OpenCASCADE 7.6) opens rg2's STEP and IGES files:
# a torus (R = 3, r = 1) as STEP, as IGES B-rep and as plain IGES, the bundled design as STEP
# and IGES B-rep, and the capped pipe elbow as STEP (its free edges are the poles' degenerate ones). Checked: STEP and IGES B-rep arrive as one shell with every edge shared by two
# faces, valid; plain IGES as loose faces (FreeCAD does not sew); the torus's surface points lie
# on the exact torus and its area is 4 pi^2 R r. Not part of `make test` (FreeCAD is ~930 MB);
# run it with `make check-freecad`, which installs freecad-python3 if missing.
# Usage: scripts/freecad_check.sh <path-to-rg2> <source-dir>
set -u
. "$(dirname "$0")/../tests/cli/lib.sh" "$@"
rg2=$RG2 src=$SRC
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
command -v freecadcmd >/dev/null || { echo "FAIL: freecadcmd not found (apt-get install freecad-python3)" >&2; exit 1; }

"$rg2" build -q "$src/tests/data/torus_8x6.json" -o "$tmp/torus.step" -o "$tmp/torus.igs" || bad "rg2 build torus"
"$rg2" build -q "$src/tests/data/torus_8x6.json" -o "$tmp/torus_brep.igs" --iges-brep || bad "rg2 build torus --iges-brep"
"$rg2" build -q "$src/examples/torus_sphere.json" -o "$tmp/design.step" || bad "rg2 build design"
"$rg2" build -q "$src/examples/torus_sphere.json" -o "$tmp/design_brep.igs" --iges-brep || bad "rg2 build design --iges-brep"
"$rg2" build -q "$src/examples/pipe_elbow.json" -o "$tmp/elbow.step" || bad "rg2 build pipe_elbow"

# check FILE FACES SHELLS FREE TORUS
check() {
  local f=$1 faces=$2 shells=$3 free=$4 torus=$5 line
  line=$(FC_FILE="$tmp/$f" FC_TORUS="$torus" timeout 300 freecadcmd "$src/tests/freecad/fc_check.py" 2>&1 | grep '^FC ')
  echo "  $line"
  [ -n "$line" ] || { bad "$f: FreeCAD printed no result"; return; }
  local got_faces got_shells got_free valid area dev
  got_faces=$(sed -n 's/.* faces=\([0-9]*\).*/\1/p' <<<"$line")
  got_shells=$(sed -n 's/.* shells=\([0-9]*\).*/\1/p' <<<"$line")
  got_free=$(sed -n 's/.* free=\([0-9]*\).*/\1/p' <<<"$line")
  valid=$(sed -n 's/.* valid=\([0-9]*\).*/\1/p' <<<"$line")
  area=$(sed -n 's/.* area=\([^ ]*\).*/\1/p' <<<"$line")
  dev=$(sed -n 's/.* torus_dev=\([^ ]*\).*/\1/p' <<<"$line")
  [ "$got_faces" = "$faces" ] && [ "$got_shells" = "$shells" ] && [ "$got_free" = "$free" ] && [ "$valid" = 1 ] &&
    ok || bad "$f: faces $got_faces (want $faces), shells $got_shells (want $shells), free edges $got_free (want $free), valid $valid"
  if [ -n "$torus" ]; then
    awk -v a="$area" -v d="$dev" 'BEGIN { pi = atan2(0, -1); e = a - 4 * pi * pi * 3; if (e < 0) e = -e;
      exit !(e <= 1e-9 * a && d <= 1e-12) }' && ok || bad "$f: area $area (4 pi^2 R r = 118.4352528...), torus deviation $dev"
  fi
}
check torus.step 48 1 0 1
check torus_brep.igs 48 1 0 1
check torus.igs 48 0 192 1
check design.step 120 1 0 ""
check design_brep.igs 120 1 0 ""
# a capped surface: one closed shell whose only free edges are the fan faces' zero-length edges
# at the poles (8 per pole on the elbow), as docs/export.md says
line=$(FC_FILE="$tmp/elbow.step" timeout 300 freecadcmd "$src/tests/freecad/fc_check.py" 2>&1 | grep '^FC ')
echo "  $line"
[[ "$line" == *" faces=256 "*" shells=1 "*"free=16 "*"valid=1 "*" degenerate=16 closed=1"* ]] && ok ||
  bad "elbow.step: want 256 faces, 1 shell, 16 free edges all degenerate, closed: $line"
finish
