#!/usr/bin/env bash
# CLI tests of rg2 render / rg2 check: pictures of every mode are valid PNGs of the asked size;
# every example design checks G2 and exact; strict limits and bad designs fail with the right
# exit code and a message; usage errors exit 2.
# Usage: bash render_check.sh <path-to-rg2> <source-dir>
set -u
. "$(dirname "$0")/lib.sh"
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
ex=$SRC/examples/torus_sphere.json

for cmd in render check; do
  "$RG2" $cmd --help 2>&1 | grep -q "usage: rg2 $cmd" && ok || bad "$cmd --help"
  expect 2 "usage" -- "$RG2" $cmd
  expect 2 "unknown option" -- "$RG2" $cmd --frobnicate "$ex"
done
expect 2 "--mode" -- "$RG2" render "$ex" -o "$tmp/x.png" --mode fancy
expect 2 "--size" -- "$RG2" render "$ex" -o "$tmp/x.png" --size 10x10
expect 2 "--range" -- "$RG2" render "$ex" -o "$tmp/x.png" --range 1
expect 2 "--range 2,1: needs lo < hi" -- "$RG2" render "$ex" -o "$tmp/x.png" --mode mean --range 2,1
expect 2 "rg2 render: --stripes 2.5: needs a whole number of stripe pairs, 1..1000" -- "$RG2" render "$ex" -o "$tmp/x.png" --mode zebra --stripes 2.5
# the ranges' edges (docs/render.md: elevation in [-90, 90], fov in (1, 170)): a value just past a
# closed edge, or on an open one, is a usage error, not the renderer's refusal (exit 1)
for v in "--elevation 90.5" "--elevation -90.5"; do
  expect 2 "rg2 render: $v: the elevation must lie in [-90, 90] degrees" -- "$RG2" render "$ex" -o "$tmp/x.png" $v
done
for v in "--fov 170" "--fov 1"; do
  expect 2 "rg2 render: $v: the field of view must lie in (1, 170) degrees" -- "$RG2" render "$ex" -o "$tmp/x.png" $v
done
! compgen -G "$tmp/x.png*" >/dev/null && ok || bad "a failed render left a file"
expect 1 "cannot write" -- "$RG2" render "$ex" -o "$tmp/no/such/dir/x.png"
expect 2 "give it a .png name" -- "$RG2" render "$ex" -o "$tmp/x.jpg"
[ -e "$tmp/x.jpg" ] && bad "x.jpg written" || ok
expect 2 "give it a .png name" -- "$RG2" render "$ex" -o "$tmp/png"
expect 2 "--surface 7: the design has 1 surface" -- "$RG2" render "$ex" -o "$tmp/s.png" --surface 7
[ -e "$tmp/s.png" ] && bad "s.png written" || ok

i=0
for mode in shaded mean gauss zebra; do
  i=$((i + 1))
  expect 0 "" -- "$RG2" render "$ex" -o "$tmp/$mode.png" --mode $mode --size $((120 + i))x96 --boundaries --mesh
  png_is "$tmp/$mode.png" $((120 + i)) 96
done
# options, each against a picture it must equal or differ from (232 x 120: room for the colour bar)
pic() { local out=$1; shift; "$RG2" render "$ex" -o "$tmp/$out.png" --size 232x120 "$@" || bad "render $*"; }
same() { cmp -s "$tmp/$1.png" "$tmp/$2.png" && ok || bad "$1.png and $2.png differ: $3"; }
differ() { cmp -s "$tmp/$1.png" "$tmp/$2.png" && bad "$1.png and $2.png are the same: $3" || ok; }
pic sh; pic sh_view --azimuth 35 --elevation 25; pic sh_az --azimuth 40; pic sh_notint --no-tint
pic sh_nobar --no-colorbar; pic sh_s0 --surface 0
same sh sh_view "--azimuth 35 --elevation 25 are the defaults"
differ sh sh_az "--azimuth 40 turns the view"
differ sh sh_notint "--no-tint: exact pieces are tinted by default"
same sh sh_nobar "--no-colorbar: shaded pictures have no colour bar"
same sh sh_s0 "--surface 0 of a one-surface design is the design"
pic me --mode mean; pic me_notint --mode mean --no-tint; pic me_nobar --mode mean --no-colorbar
# an option the mode (or the outputs) does not use: a note naming it, exit 0, nothing else changes
expect 0 "note: --no-tint has no effect (only the shaded mode tints)" -- "$RG2" render "$ex" -o "$tmp/n1.png" --size 64x48 --mode mean --no-tint
expect 0 "note: --stripes has no effect" -- "$RG2" render "$ex" -o "$tmp/n2.png" --size 64x48 --stripes 4
expect 0 "note: --range has no effect" -- "$RG2" render "$ex" -o "$tmp/n3.png" --size 64x48 --mode zebra --range 0,1
expect 0 "note: --no-colorbar has no effect" -- "$RG2" render "$ex" -o "$tmp/n4.png" --size 64x48 --no-colorbar
out=$("$RG2" render "$ex" -o "$tmp/n5.png" --size 64x48 --mode zebra --stripes 4 --no-colorbar --range 0,1 2>&1)
case "$out" in *"--stripes has no effect"*) bad "zebra uses --stripes: $out" ;; *) ok ;; esac
# a picture in which no pixel shows the surface (far away): a note, exit 0; none when it shows
expect 0 "note: no pixel shows the surface" -- "$RG2" render "$ex" -o "$tmp/far.png" --size 64x48 --distance 1e6
png_is "$tmp/far.png" 64 48
out=$("$RG2" render "$ex" -o "$tmp/near.png" --size 64x48 --distance 100 2>&1) && [ -z "$out" ] && ok || bad "--distance 100: $out"
# a curvature picture too small for the colour bar: a note, and none where the bar fits
expect 0 "note: no colour bar at 400x100 (it needs at least 221x120 pixels)" -- "$RG2" render "$ex" -o "$tmp/b1.png" --size 400x100 --mode mean
out=$("$RG2" render "$ex" -o "$tmp/b2.png" --size 221x120 --mode gauss 2>&1) && [ -z "$out" ] && ok || bad "221x120 gauss: $out"
expect 0 "note: --iges-brep has no effect (no IGES output)" -- "$RG2" build "$ex" -o "$tmp/n.obj" --iges-brep
expect 0 "note: --ap242 has no effect (no STEP output)" -- "$RG2" build "$ex" -o "$tmp/n.igs" --ap242
expect 0 "note: --density has no effect" -- "$RG2" build "$ex" -o "$tmp/n.step" --density 4
# a design below CAD kernels' resolution: a note for STEP and IGES, none for meshes, none with -q,
# none just above 1e-3 mm. The torus R = 3e-8, r = 1e-8 spans sqrt(2 (2 (R + r))^2 + (2 r)^2)
# = 1.149e-7 (its control points lie within R + r of the axis, the circles' ends on the box);
# R = 3e-4, r = 1e-4 spans 1.149e-3
tiny() { printf '{"shapes": {"t": {"kind": "torus", "R": %s, "r": %s}}, "meshes": {"T": {"shape": "t"}}}' "$1" "$2" > "$tmp/$3.json"; }
tiny 3e-8 1e-8 tiny
tiny 3e-4 1e-4 small
expect 0 "note: the surfaces span 1.15e-07 mm (bounding-box diagonal)" -- "$RG2" build "$tmp/tiny.json" -o "$tmp/tiny.step"
expect 0 "below 0.001 mm they may read the file as invalid" -- "$RG2" build "$tmp/tiny.json" -o "$tmp/tiny.igs" -o "$tmp/tiny.obj"
for args in "$tmp/tiny.json -o $tmp/tiny.obj" "-q $tmp/tiny.json -o $tmp/tiny.step" "$tmp/small.json -o $tmp/small.step"; do
  out=$("$RG2" build $args 2>&1)
  [ -z "$out" ] && ok || bad "rg2 build $args: $out"
done
out=$("$RG2" build "$ex" -o "$tmp/n.step" -o "$tmp/n.igs" -o "$tmp/n.stl" --ap242 --iges-brep --density 4 --face-per-mesh 2>&1)
[ -z "$out" ] && ok || bad "options every output uses gave: $out"
out=$("$RG2" build -q "$ex" -o "$tmp/n.obj" --iges-brep 2>&1)
[ -z "$out" ] && ok || bad "-q keeps notes quiet: $out"
same me me_notint "--no-tint: curvature pictures are not tinted"
differ me me_nobar "--no-colorbar: the mean-curvature bar is drawn by default"
# every H of the design lies below 100 (rg2 check: H in [-1.0081, 1.25022]): any range above
# clamps every pixel to the lowest colour, the same picture without the bar's labels
pic r1 --mode mean --no-colorbar --range 100,200; pic r2 --mode mean --no-colorbar --range 300,4000
pic r3 --mode mean --no-colorbar --range -0.5,0.5
same r1 r2 "ranges above every H clamp alike"
differ r1 r3 "a range inside the curvatures colours the surface"
differ r3 me_nobar "--range -0.5,0.5 is not the robust range"
# a two-surface design: each surface alone differs from both together and from the other
f9=$SRC/examples/fig9_polar_sphere.json
"$RG2" render "$f9" -o "$tmp/f9.png" --size 96x64 && "$RG2" render "$f9" -o "$tmp/f9_0.png" --size 96x64 --surface 0 &&
  "$RG2" render "$f9" -o "$tmp/f9_1.png" --size 96x64 --surface 1 || bad "render fig9 --surface"
differ f9 f9_0 "--surface 0 of two"; differ f9 f9_1 "--surface 1 of two"; differ f9_0 f9_1 "--surface 0 and 1"
expect 2 "--surface 2: the design has 2 surfaces" -- "$RG2" render "$f9" -o "$tmp/f9_2.png" --surface 2
# --apart: Fig. 1's four overlapping tori laid out apart differ from them on top of each other;
# one surface apart is the surface as placed (test_render measures the layout itself)
# (drawn as placed, overlapping outputs get a note on stderr pointing to --apart; fig9's two
# spheres side by side do not)
f1=$SRC/examples/fig1_torus.json
"$RG2" render "$f1" -o "$tmp/f1.png" --size 96x64 2>"$tmp/f1.err" &&
  "$RG2" render "$f1" -o "$tmp/f1_apart.png" --size 96x64 --apart 2>"$tmp/f1_apart.err" &&
  "$RG2" render "$f1" -o "$tmp/f1_s2.png" --size 96x64 --surface 2 2>"$tmp/f1_s2.err" &&
  "$RG2" render "$f1" -o "$tmp/f1_s0.png" --size 96x64 --surface 0 2>"$tmp/f1_s0.err" &&
  "$RG2" render "$f1" -o "$tmp/f1_s2_apart.png" --size 96x64 --surface 2 --apart 2>"$tmp/f1_s2_apart.err" ||
  bad "render fig1 --apart"
grep -q "note: output surfaces 0 and 1 overlap.*--apart" "$tmp/f1.err" && ok || bad "fig1 as placed: no overlap note"
[ ! -s "$tmp/f1_apart.err" ] && [ ! -s "$tmp/f1_s2.err" ] && [ ! -s "$tmp/f1_s0.err" ] && ok ||
  bad "overlap note with --apart or --surface (2 or 0)"
"$RG2" render "$f9" -o "$tmp/f9n.png" --size 96x64 2>"$tmp/f9.err" && [ ! -s "$tmp/f9.err" ] && ok ||
  bad "fig9 (surfaces side by side): $(cat "$tmp/f9.err")"
differ f1 f1_apart "--apart lays the four tori out"
same f1_s2 f1_s2_apart "--apart with one surface"
# ... so it gets a note, as other options the run does not use
grep -q "note: --apart has no effect (one surface to draw)" "$tmp/f1_s2_apart.err" && ok ||
  bad "--apart with one surface: no note: $(cat "$tmp/f1_s2_apart.err")"
expect 0 "note: --apart has no effect (one surface to draw)" -- "$RG2" render "$ex" -o "$tmp/n6.png" --size 64x48 --apart
png_is "$tmp/f1_apart.png" 96 64
# a small torus inside a big one (same centre, off the origin): the small box lies within the big
# one on every axis, so they overlap by all of the smaller extent, in either output order
for order in '"S", "B"' '"B", "S"'; do
  printf '{"shapes": {"s": {"kind": "torus", "R": 0.3, "r": 0.1, "translate": [5, 5, 0]}, "b": {"kind": "torus", "R": 3, "r": 1, "translate": [5, 5, 0]}}, "meshes": {"S": {"shape": "s"}, "B": {"shape": "b"}}, "output": [%s]}' "$order" >"$tmp/nest.json"
  expect 0 "note: output surfaces 0 and 1 overlap" -- "$RG2" render "$tmp/nest.json" -o "$tmp/nest.png" --size 16x16
done
# --size: the smallest picture, 16x16, is drawn; a height needs its digits right after the x
# (strtol took '+50' and ' 50'); a --size without a value is a usage error, not a crash
png_is "$tmp/nest.png" 16 16
for sz in 100x+50 "100x 50" 15x16 16x15; do
  expect 2 "rg2 render: --size needs WxH, each 16..8192 (e.g. 800x600), not '$sz'" -- "$RG2" render "$ex" -o "$tmp/x.png" --size "$sz"
done
out=$("$RG2" render "$ex" -o "$tmp/x.png" --size 2>&1); rc=$?
[ "$rc" = 2 ] && [ "$out" = "rg2 render: --size needs WxH, each 16..8192 (e.g. 800x600)" ] && ok || bad "--size without a value: exit $rc: $out"
expect 2 "rg2 render: --range needs lo,hi" -- "$RG2" render "$ex" -o "$tmp/x.png" --mode mean --range
expect 2 "--range 1,1: needs lo < hi" -- "$RG2" render "$ex" -o "$tmp/x.png" --mode mean --range 1,1
[ ! -e "$tmp/x.png" ] && ok || bad "a refused render wrote x.png"
# the curvature modes use --range and --no-colorbar, and no mode but shaded is told about --no-tint
# it was not given: no note
for m in mean gauss; do
  out=$("$RG2" render "$ex" -o "$tmp/m.png" --size 16x16 --mode $m --range -1,1 --no-colorbar 2>&1) && [ -z "$out" ] && ok ||
    bad "render --mode $m --range --no-colorbar: $out"
done
# same bytes for 1 and 2 threads
"$RG2" render "$ex" -o "$tmp/t1.png" --mode zebra --size 160x120 --threads 1 &&
  "$RG2" render "$ex" -o "$tmp/t2.png" --mode zebra --size 160x120 --threads 2 &&
  cmp -s "$tmp/t1.png" "$tmp/t2.png" && ok || bad "render depends on the thread count"

# every example: G2 and exact, at every sample count (next to a pole rounding grows like
# 1/v^2 with the distance v to it: the verdict must not depend on --samples)
for f in "$SRC"/examples/*.json; do
  req=g2,exact,weights
  case "$f" in *fig11_cube_tube.json) req=g2,weights ;; esac # no patch of it stays exact
  for n in 16 64 256 1000; do
    expect 0 "" -- "$RG2" check "$f" --require $req --samples $n
  done
done
# nothing exact to measure does not keep the exact promise
expect 3 "failed: exact" -- "$RG2" check "$SRC/examples/fig11_cube_tube.json" --require exact
expect 3 "NO EXACT PATCH" -- "$RG2" check "$SRC/examples/fig11_cube_tube.json" --require g2,exact
# a pole design says what it did next to its poles
expect 0 "next to a pole" -- "$RG2" check "$SRC/examples/fig9_polar_sphere.json" --samples 256
expect 0 "16 at a pole" -- "$RG2" check "$SRC/examples/fig9_polar_sphere.json"
# normals undefined away from a pole (a cylinder band of height 1e-95): G1 and G2 fail and the
# table says how many samples could not be measured
thin=$SRC/tests/data/thin_band.json
expect 3 "failed: g1" -- "$RG2" check "$thin" --require g1
expect 3 "failed: g2" -- "$RG2" check "$thin" --require g2
expect 3 "5304 not measured" -- "$RG2" check "$thin" --require g2
expect 3 "NOT MEASURED" -- "$RG2" check "$thin" --require g2
# ... and where the first of them is, and why
expect 3 "the first at surface 0 u seam (7,0)|(0,0) t=0, point (1, " -- "$RG2" check "$thin" --require g2
expect 3 "0): an undefined normal or metric" -- "$RG2" check "$thin" --require g2
expect 0 "" -- "$RG2" check "$thin" --require g0
# a mesh merged with itself folds back inside its transitions: the seams are G2, the surface is
# not regular, and the table says where
fold=$SRC/tests/data/folded_merge.json
expect 3 "NOT REGULAR" -- "$RG2" check "$fold" --require g2
expect 3 "failed: g1" -- "$RG2" check "$fold" --require g1
expect 0 "" -- "$RG2" check "$fold" --require g0
expect 0 "(17 per seam)" -- "$RG2" check "$ex"
"$RG2" check --help | grep -q "17 samples" && ok || bad "check --help: samples per seam"
out=$("$RG2" check "$ex" --json 2>&1)
case "$out" in *'"g2":	true'*'"exact":	true'*) ok ;; *) bad "check --json: $out" ;; esac
case "$("$RG2" check "$ex")" in *"ring"*"ball"*"G2 curvature jump"*) ok ;; *) bad "check table lacks shapes or G2 line" ;; esac
# an impossible limit is a failed promise: exit 3 naming it
expect 3 "failed: g2" -- "$RG2" check "$ex" --require g2 --tol g2=0
expect 3 "exact" -- "$RG2" check "$ex" --require exact --tol exact=0
expect 2 "--require" -- "$RG2" check "$ex" --require g3
# a looser limit measures the same samples and passes (limits above 1e-4 rad / 1e-2 once left
# every sample unmeasured)
expect 0 "0 not measured" -- "$RG2" check "$ex" --require g2 --tol g1=1e-3 --tol g2=0.5
expect 0 "16 at a pole (no normal there), 0 not measured" -- \
  "$RG2" check "$SRC/examples/fig9_polar_sphere.json" --require g2 --tol g1=1 --tol g2=1
expect 2 "--require '': needs a comma-separated list" -- "$RG2" check "$ex" --require ""
expect 2 "--require 'g2,,exact': needs a comma-separated list" -- "$RG2" check "$ex" --require g2,,exact
expect 2 "--tol" -- "$RG2" check "$ex" --tol g2
# every --tol kind sets its own limit: the table's row (or the JSON's exact_limit) shows it
for k in g0:"G0 position gap" g1:"G1 normal angle" g2:"G2 curvature jump"; do
  "$RG2" check "$ex" --tol "${k%%:*}=3e-3" | grep "${k#*:}" | grep -q "(limit 3e-03" && ok || bad "--tol ${k%%:*}=3e-3 not in its row"
done
"$RG2" check "$ex" --tol exact=3e-3 --json | grep -q '"exact_limit":[[:space:]]*0.003,' && ok || bad "--tol exact=3e-3 not the exact_limit"
expect 2 "--require '  ': needs a comma-separated list" -- "$RG2" check "$ex" --require "  "
# the report does not depend on the thread count (text and JSON, a pole design, a fold)
"$RG2" check --help | grep -q -- "--threads N" && ok || bad "check --help: --threads"
for f in "$ex" "$SRC/examples/fig9_polar_sphere.json" "$SRC/examples/fig14_mobius.json" "$fold"; do
  for fmt in "" --json; do
    "$RG2" check "$f" $fmt --threads 1 >"$tmp/c1.txt" 2>&1
    "$RG2" check "$f" $fmt --threads 2 >"$tmp/c2.txt" 2>&1
    [ -s "$tmp/c1.txt" ] && cmp -s "$tmp/c1.txt" "$tmp/c2.txt" && ok ||
      bad "check $f $fmt: --threads 2 differs from --threads 1"
  done
done
for n in 0 -1 x 1.5 2000; do
  expect 2 "--threads needs an integer 1..1024" -- "$RG2" check "$ex" --threads $n
done
expect 2 "--threads needs an integer 1..1024" -- "$RG2" check "$ex" --threads
# a bad single number: one line naming the value (it printed an item message and then a second line)
for args in "render $ex -o $tmp/one.png --azimuth abc" "build -q $ex -o $tmp/one.obj --density 4x" "check $ex --tol g1=x"; do
  out=$("$RG2" $args 2>&1); rc=$?
  [ "$rc" = 2 ] && [ "$(printf '%s\n' "$out" | wc -l)" = 1 ] && ok || bad "rg2 $args: exit $rc, not one line: $out"
done
# a subnormal tolerance is a finite number >= 0 (it was called 'not a finite number')
expect 0 "" -- "$RG2" check "$ex" --tol g1=1e-310
# render.md gives one memory figure per pixel (it gave 125 and 140 bytes)
# (per pixel: the crossing search's memory per triangle is another figure)
per_pixel=$(tr '\n' ' ' <"$SRC/docs/render.md" | grep -o 'about [0-9]* bytes per  *pixel' |
    grep -o 'about [0-9]* bytes' | sort -u | tr '\n' ' ')
[ "$per_pixel" = "about 131 bytes " ] && ok || bad "docs/render.md: bytes per pixel: $per_pixel"
# --name=value is --name value, in every subcommand; a flag given a value is a usage error
expect 0 "" -- "$RG2" render "$ex" -o "$tmp/eq.png" --size=64x48 --azimuth=10 --mode=gauss
png_is "$tmp/eq.png" 64 48
expect 0 "" -- "$RG2" check "$ex" --tol=g1=1e-3 --samples=4 --threads=1
expect 0 "" -- "$RG2" build -q "$ex" -o "$tmp/eq.obj" --density=2
expect 0 "torus R = 3, r = 2" -- "$RG2" shape torus --r=2 --u-arcs=5
expect 0 "3 rational cubic Bezier segments" -- "$RG2" curve --angles=120,120,120
expect 2 "rg2 render: --apart takes no value ('--apart=1')" -- "$RG2" render "$ex" -o "$tmp/eq2.png" --apart=1
expect 2 "rg2 render: unknown option '--frob'" -- "$RG2" render "$ex" -o "$tmp/eq2.png" --frob=1
# options a designer guesses get the option that does it, not a look-alike ('--view' was '--size')
expect 2 "unknown option '--view' (did you mean '--azimuth A --elevation E'?)" -- "$RG2" render "$ex" -o "$tmp/v.png" --view top
expect 2 "unknown option '--zebra' (did you mean '--mode zebra'?)" -- "$RG2" render "$ex" -o "$tmp/v.png" --zebra
expect 2 "unknown option '--gaussian' (did you mean '--mode gauss'?)" -- "$RG2" render "$ex" -o "$tmp/v.png" --gaussian
expect 2 "unknown option '--curvature' (did you mean '--mode mean or --mode gauss'?)" -- "$RG2" render "$ex" -o "$tmp/v.png" --curvature
[ ! -e "$tmp/eq2.png" ] && ok || bad "a refused --name=value wrote a picture"
# --on: every patch against a named shape. The patches tagged with it lie on it (the residual
# relative to the surface's size, at least the shape's); in torus_sphere exactly those do.
for f in "$SRC"/examples/*.json; do
  for name in $(python3 -c 'import json, sys; print(" ".join(json.load(open(sys.argv[1])).get("shapes", {})))' "$f"); do
    "$RG2" check "$f" --json --on "$name" > "$tmp/on.json" 2>&1 &&
      python3 - "$tmp/on.json" "$name" <<'PY' && ok || bad "check --on $name: $f: tagged patches off their shape"
import json, sys
r = json.load(open(sys.argv[1]))
tagged = sum(s["patches"] for s in r["shapes"] if s["label"] == sys.argv[2])
on = sum(e["on"] for e in r["on"])
sys.exit(0 if r["on"] and on >= tagged and all(e["shape"] == sys.argv[2] for e in r["on"]) else 1)
PY
  done
done
expect 0 "on shape ball       surface 0: 24 of 120 patches within 1e-11 of its size" -- "$RG2" check "$ex" --on ball --on ring
expect 0 "on shape ring       surface 0: 48 of 120 patches within 1e-11 of its size" -- "$RG2" check "$ex" --on ball --on ring
# --on's worst patch on the shape and nearest off it: raising --tol exact to the nearest residual
# off the shape takes that patch in (residuals <= the tolerance count) as the new worst, and
# the text report says what the JSON one does (JSON numbers round-trip)
"$RG2" check "$ex" --json --on ball > "$tmp/on1.json" 2>&1 || bad "check --json --on ball"
near=$(python3 -c 'import json, sys; print(repr(json.load(open(sys.argv[1]))["on"][0]["nearest_off"]))' "$tmp/on1.json")
"$RG2" check "$ex" --json --on ball --tol exact="$near" > "$tmp/on2.json" 2>&1 || bad "check --on ball --tol exact=$near"
"$RG2" check "$ex" --on ball --tol exact="$near" > "$tmp/on2.txt" 2>&1 || bad "check --on ball --tol exact=$near (text)"
# (the nearest residual is printed exactly: one ulp below it the patch is off again)
below=$(python3 -c 'import math, sys; print(repr(math.nextafter(float(sys.argv[1]), 0)))' "$near")
"$RG2" check "$ex" --json --on ball --tol exact="$below" > "$tmp/on3.json" 2>&1 || bad "check --on ball --tol exact=$below"
# (and tolerances of 1, the surface's size: every patch on it, none off; and 1e-300: none on)
for x in 1 1e-300; do
  "$RG2" check "$ex" --json --on ball --tol exact=$x > "$tmp/tol$x.json" 2>&1 || bad "check --json --on ball --tol exact=$x"
  "$RG2" check "$ex" --on ball --tol exact=$x > "$tmp/tol$x.txt" 2>&1 || bad "check --on ball --tol exact=$x"
done
"$RG2" check "$ex" --json > "$tmp/plain.json" 2>&1 || bad "check --json"
python3 - "$tmp"/on{1,2}.json "$tmp/on2.txt" "$tmp"/tol1.{json,txt} "$tmp"/tol1e-300.{json,txt} "$tmp"/{on3,plain}.json <<'PY' && ok || bad "check --on ball: worst and nearest"
import json, re, sys
a, b, c, d, e = (json.load(open(sys.argv[k]))["on"][0] for k in (1, 2, 4, 6, 8))
# the report around the "on" array is the plain one, every number bit for bit, and as text
full, plain = json.load(open(sys.argv[1])), json.load(open(sys.argv[9]))
ok = full.pop("on") is not None and full == plain
text = open(sys.argv[1]).read()
ok = ok and text[:text.find(',\n\t"on":')] + "\n}\n" == open(sys.argv[9]).read()
ok = ok and e["on"] == a["on"] and e["nearest_off"] == a["nearest_off"]
t, t3, t0 = (open(sys.argv[k]).read() for k in (3, 5, 7))
ok = ok and all(open(sys.argv[k]).read().endswith("}\n") for k in (1, 2, 4, 6))  # (a line ends the JSON report)
def where(s):
    i, j = map(int, re.fullmatch(r"patch \((\d+),(\d+)\)", s).groups())
    return i, j
ok = ok and a["patches"] == b["patches"] == 120 and 0 < a["on"] < b["on"] < 120
ok = ok and a["worst_on"] <= 1e-11 < a["nearest_off"] and b["worst_on"] == a["nearest_off"] < b["nearest_off"]
ok = ok and b["worst_on_where"] == a["nearest_off_where"] != a["worst_on_where"] != b["nearest_off_where"]
ok = ok and all(0 <= k < 120 for w in (a["worst_on_where"], a["nearest_off_where"], b["nearest_off_where"]) for k in where(w))
line = "on shape ball       surface 0: %d of 120 patches within %s of its size, worst %.2e at %s; nearest off it %.2e at %s\n" % (
    b["on"], "%g" % b["worst_on"], b["worst_on"], b["worst_on_where"], b["nearest_off"], b["nearest_off_where"])
ok = ok and line in t
ok = ok and c["on"] == 120 and "nearest_off" not in c and "nearest_off_where" not in c and c["worst_on"] < 1
ok = ok and "on shape ball       surface 0: 120 of 120 patches within 1 of its size, worst %.2e at %s\n" % (c["worst_on"], c["worst_on_where"]) in t3
ok = ok and d["on"] == 0 and "worst_on" not in d and "worst_on_where" not in d and d["nearest_off"] <= a["worst_on"]
ok = ok and "on shape ball       surface 0: 0 of 120 patches within 1e-300 of its size; nearest off it %.2e at %s\n" % (
    d["nearest_off"], d["nearest_off_where"]) in t0
if not ok:
    print(a, b, c, d, repr(line), t, t3, t0, sep="\n", file=sys.stderr)
sys.exit(0 if ok else 1)
PY
expect 2 "--on 'rin': $ex: the design has no shape of that name (its shapes: ring, ball)" -- "$RG2" check "$ex" --on rin
expect 2 "--on needs the name" -- "$RG2" check "$ex" --on
[ "$("$RG2" check "$ex" --on ball --on ball | grep -c '^on shape')" = 1 ] && ok || bad "check --on ball --on ball: measured twice"
# bad designs: exit 1 with the loader's message
expect 1 "K = " -- "$RG2" check "$SRC/tests/data/bad_scalar.json"
expect 1 "" -- "$RG2" render "$SRC/tests/data/bad_weight.json" -o "$tmp/bad.png"
[ ! -e "$tmp/bad.png" ] && ok || bad "render of a bad design wrote a file"
finish
