#!/usr/bin/env bash
# gmsh (a second CAD client, reading through OpenCASCADE) meshes rg2's STEP and IGES files:
# a torus (R = 3, r = 1, closed both ways) written as STEP and IGES B-rep (face per patch and
# face per mesh) and as plain IGES is meshed by `gmsh -2`; every mesh node must lie on the exact
# torus, and the mesh must be conforming (no triangle edge used only once: gmsh saw every seam as
# one shared curve) for STEP and IGES B-rep. Plain IGES has no shared edges, so there the mesh is open along every seam until
# gmsh sews the faces (Geometry.OCCSewFaces): the check can fail, and does where it should.
# Usage: bash gmsh.sh <path-to-rg2> <source-dir>
set -u
. "$(dirname "$0")/lib.sh" "$@"
rg2=$RG2
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT

if ! command -v gmsh >/dev/null; then
  echo "FAIL: gmsh is not installed (make test installs it: scripts/deps.sh test)" >&2
  exit 1
fi

"$rg2" build -q "$SRC/tests/data/torus_8x6.json" -o "$tmp/t.step" -o "$tmp/t.igs" && ok || bad "rg2 build (STEP, IGES)"
"$rg2" build -q "$SRC/tests/data/torus_8x6.json" -o "$tmp/tb.igs" --iges-brep && ok || bad "rg2 build --iges-brep"
"$rg2" build -q "$SRC/tests/data/torus_8x6.json" -o "$tmp/tm.step" -o "$tmp/tbm.igs" --iges-brep --face-per-mesh && ok ||
  bad "rg2 build --iges-brep --face-per-mesh"

# nodes, triangles, triangle edges used once, and the largest distance of a node from the torus
# (relative to R + r) of a gmsh .msh (format 2)
msh_stats() {
  awk '
    /^\$Nodes/ { sec = "n"; getline; next }
    /^\$EndNodes/ { sec = ""; next }
    /^\$Elements/ { sec = "e"; getline; next }
    /^\$EndElements/ { sec = ""; next }
    sec == "n" {
      nodes++
      rho = sqrt($2 * $2 + $3 * $3); d = sqrt((rho - 3) ^ 2 + $4 ^ 2) - 1
      if (d < 0) d = -d
      if (d > worst) worst = d
    }
    sec == "e" && $2 == 2 {
      tris++
      n = NF; a = $(n - 2); b = $(n - 1); c = $n
      e[a < b ? a " " b : b " " a]++; e[b < c ? b " " c : c " " b]++; e[a < c ? a " " c : c " " a]++
    }
    END {
      for (k in e) if (e[k] == 1) free++
      printf "%d %d %d %.3g\n", nodes, tris, free + 0, worst / 4
    }' "$1"
}

# mesh FILE WHAT EXPECT_CONFORMING [gmsh options]: mesh a file and check it
mesh() {
  local f=$1 what=$2 conforming=$3; shift 3
  if ! timeout 300 gmsh "$f" -2 -clmax 0.3 -format msh2 "$@" -o "$tmp/out.msh" >"$tmp/gmsh.log" 2>&1; then
    bad "$what: gmsh failed: $(tail -3 "$tmp/gmsh.log")"
    return
  fi
  read -r nodes tris free worst < <(msh_stats "$tmp/out.msh")
  echo "  gmsh $what: $nodes nodes, $tris triangles, $free triangle edges used once, nodes off the torus by $worst (relative)"
  [ "$tris" -gt 1000 ] && ok || bad "$what: only $tris triangles"
  awk -v w="$worst" 'BEGIN { exit !(w <= 1e-12) }' && ok || bad "$what: nodes $worst off the torus"
  if [ "$conforming" = 1 ]; then
    [ "$free" -eq 0 ] && ok || bad "$what: $free triangle edges used once (the seams are not shared)"
  else
    [ "$free" -gt 0 ] && ok || bad "$what: no open seam although the faces share no edges"
  fi
}

mesh "$tmp/t.step" "STEP" 1
mesh "$tmp/tb.igs" "IGES B-rep" 1
mesh "$tmp/tm.step" "STEP, face per mesh" 1
mesh "$tmp/tbm.igs" "IGES B-rep, face per mesh" 1
mesh "$tmp/t.igs" "IGES, untrimmed surfaces" 0
mesh "$tmp/t.igs" "IGES, untrimmed surfaces, sewn by gmsh" 1 -setnumber Geometry.OCCSewFaces 1

finish
