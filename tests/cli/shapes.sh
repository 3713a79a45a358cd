# CLI: rg2 shapes (listing) and rg2 shape (building named shapes and NURBS), with bad input.
. "$(dirname "$0")/lib.sh"
expect 0 "usage: rg2 shapes" -- "$RG2" shapes --help
expect 0 "usage: rg2 shape NAME" -- "$RG2" shape --help
# a bare 'rg2 shape' is a usage error: the usage goes to stderr, as for the other commands
out=$("$RG2" shape 2>/dev/null); rc=$?
err=$("$RG2" shape 2>&1 >/dev/null)
if [ "$rc" = 2 ] && [ -z "$out" ]; then ok; else bad "rg2 shape -> exit $rc, stdout '$out' (expected 2 and nothing)"; fi
case "$err" in *"usage: rg2 shape NAME"*) ok ;; *) bad "rg2 shape: stderr lacks the usage: $err" ;; esac
# every shape is listed with its parameters and builds with its defaults
for s in torus cyclide sphere cylinder cone hyperboloid1_ruled hyperboloid1 hyperboloid2 paraboloid hypar ellipsoid; do
  expect 0 "$s" -- "$RG2" shapes
  expect 0 "rational bi-cubic patches" -- "$RG2" shape "$s"
done
expect 0 "R=3 r=1" -- "$RG2" shapes
# the default partitions of docs/shapes.md ("Default partitions": "N arcs, full circle" or "N knot
# intervals of [A, B]") are what 'rg2 shape NAME', 'rg2 shapes' and a design mesh without u / v use
dtmp=$(mktemp -d)
cells() { # NAME -> "NU NV V_KNOTS_OR_-": the table row's counts, and the v knots it implies
  awk -v s="$1" -F' [|] ' '/^\*\*Default partitions\*\*/ { on = 1 }
    on && index($0, "| `" s "` |") == 1 { split($2, a, " "); split($3, b, " ");
      k = "-"; if ($3 ~ /knot intervals of/) { lo = $3; sub(/.*\[/, "", lo); hi = lo; sub(/,.*/, "", lo);
        sub(/.*, /, "", hi); sub(/\].*/, "", hi); k = "";
        for (i = 0; i <= b[1]; i++) k = k (i ? " " : "") sprintf("%.6g", lo + (hi - lo) * i / b[1]) }
      print a[1], b[1], k; exit }' "$SRC/docs/shapes.md"
}
for s in torus cyclide sphere cylinder cone hyperboloid1_ruled hyperboloid1 hyperboloid2 paraboloid hypar ellipsoid; do
  read -r nu nv knots <<< "$(cells "$s")"
  if [ -z "$nu" ] || [ -z "$nv" ]; then bad "docs/shapes.md: no default partition row for $s"; continue; fi
  expect 0 "$nu x $nv rational bi-cubic patches" -- "$RG2" shape "$s"
  [ "$knots" != "-" ] && expect 0 "v: polynomial, $nv segments, knots: $knots" -- "$RG2" shape "$s"
  row=$(awk -v s="$s" -F' [|] ' 'index($0, "| `" s "` |") == 1 && /arcs|knot intervals/ { print $2 "; v: " $3 }' "$SRC/docs/shapes.md")
  row=${row% |}
  expect 0 "default u: $row" -- "$RG2" shapes
  # the shape's own lines of the listing: a direction of arcs is a circle, one of knot intervals a polynomial
  kind() { case "$1" in *arcs*) echo "circle (angles)" ;; *) echo "polynomial (knots)" ;; esac; }
  blk=$("$RG2" shapes | awk -v s="$s" '$1 == s { on = 1; next } on && /^[^ ]/ { exit } on')
  [[ "$blk" == *"u: $(kind "${row%%; v: *}"), v: $(kind "${row#*; v: }")"*"default u: $row"* ]] && ok ||
    bad "rg2 shapes: $s's lines do not name its directions' kinds and defaults ($row): $blk"
  printf '{"format": "rg2 design 1", "shapes": {"S": {"kind": "%s"}}, "meshes": {"M": {"shape": "S"}}}' "$s" > "$dtmp/d.json"
  expect 0 "-> $nu x $nv = $((nu * nv)) patches" -- "$RG2" info "$dtmp/d.json"
done
# a partly given direction: an open circle range without a count takes arcs about as fine as the
# default full circle's (the torus's 8: ceil(sweep / 45) arcs), in a design as from rg2 shape; a
# polynomial direction takes the missing count or range from the defaults (cylinder: 3 of [0, 1])
for sw in 7 45 90 300 359; do
  n=$(( (sw + 44) / 45 ))
  expect 0 "$n x 6 rational bi-cubic patches" -- "$RG2" shape torus --u-sweep "$sw"
  printf '{"shapes": {"S": {"kind": "torus"}}, "meshes": {"M": {"shape": "S", "u": {"to": %s}}}}' "$sw" > "$dtmp/d.json"
  expect 0 "-> $n x 6 = $((n * 6)) patches" -- "$RG2" info "$dtmp/d.json"
  printf '{"shapes": {"S": {"kind": "torus"}}, "meshes": {"M": {"shape": "S", "u": {"from": 10, "to": %s}}}}' "$((sw + 10))" > "$dtmp/d.json"
  expect 0 "-> $n x 6 = $((n * 6)) patches" -- "$RG2" info "$dtmp/d.json"
done
expect 0 "v: polynomial, 5 segments, knots: 0 0.2 0.4 0.6 0.8 1" -- "$RG2" shape cylinder --v-segments 5
expect 0 "v: polynomial, 3 segments, knots: 0.5 1 1.5 2" -- "$RG2" shape cylinder --v-range 0.5,2
printf '{"shapes": {"S": {"kind": "cylinder"}}, "meshes": {"M": {"shape": "S", "v": {"segments": 5}}}}' > "$dtmp/d.json"
expect 0 "-> 6 x 5 = 30 patches" -- "$RG2" info "$dtmp/d.json"
printf '{"shapes": {"S": {"kind": "cylinder"}}, "meshes": {"M": {"shape": "S", "v": {"from": 0.5, "to": 2}}}}' > "$dtmp/d.json"
expect 0 "-> 6 x 3 = 18 patches" -- "$RG2" info "$dtmp/d.json"
rm -rf "$dtmp"
expect 0 '"default_segments": [6, 4], "default_closed": [true, false]' -- "$RG2" shapes --json
expect 0 '"name": "cyclide", "params": {"a": 2' -- "$RG2" shapes --json
expect 0 "8 x 6 rational bi-cubic patches" -- "$RG2" shape torus --R 3 --r 1 --u-arcs 8 --v-arcs 6
expect 0 "3 x 4 rational bi-cubic patches" -- "$RG2" shape torus --u-arcs 3 --u-sweep 90 --v-angles 60,120,90,90
expect 0 "open circle, 3 arcs from 45 deg, total 90 deg" -- "$RG2" shape torus --u-arcs 3 --u-sweep 90 --u-start 45
expect 0 "open circle, 1 arc from 0 deg, total 40 deg: 40" -- "$RG2" shape torus --u-sweep 40
expect 0 "6 x 3 rational bi-cubic patches" -- "$RG2" shape sphere --radius 2 --v-knots 0.25,0.4,0.6,0.75
expect 0 "knots: 0.5 0.875 1.25 1.625 2" -- "$RG2" shape cone --k 2 --v-range 0.5,2 --v-segments 4 --center 1,0,0 --axis 1,0,0
expect 0 "all positive" -- "$RG2" shape ellipsoid --a 3 --b 2 --c 1 --scale 10 --center 1000,0,0
# the summary names the placement given, in the order it applies, after the partitions (it showed
# none, so a designer could not see that --center or --axis took effect); no line without one
expect 0 "placement: axis (1, 0, 0), centre (1, 0, 0)" -- "$RG2" shape cone --k 2 --v-range 0.5,2 --v-segments 4 --center 1,0,0 --axis 1,0,0
expect 0 "placement: scale 10, centre (1000, 0, 0)" -- "$RG2" shape ellipsoid --a 3 --b 2 --c 1 --scale 10 --center 1000,0,0
expect 0 $'60 60 60 60 60 60\n  placement: centre (0, 0, -2.5)\n  control mesh 8 x 6' -- "$RG2" shape torus --u-arcs 8 --v-arcs 6 --centre 0,0,-2.5
expect 0 "placement: scale (1, 1, -1), axis (0, 1, 1), then the --xform matrix" -- "$RG2" shape paraboloid --scale 1,1,-1 --axis 0,1,1 --xform 1,0,0,0,0,1,0,0,0,0,1,0,0,0,0,1
expect 0 "placement: the --xform matrix" -- "$RG2" shape sphere --xform 2,0,0,0,0,2,0,0,0,0,2,0,0,0,0,1
# the parameters and placement given are echoed so that they read back as typed (6 digits showed
# --center 1000.0001 as 1000 and --R 3.0000001 as 3)
expect 0 $'torus R = 3.0000001, r = 0.1\n' -- "$RG2" shape torus --R 3.0000001 --r 0.1
expect 0 "placement: scale 1234567.25, axis (0.1, 0.2, 0.3), centre (1000.0001, -2.5e-07, 0)" -- "$RG2" shape sphere --scale 1234567.25 --axis 0.1,0.2,0.3 --center 1000.0001,-2.5e-7,0
out=$("$RG2" shape torus --R 3 --r 1 --u-arcs 8 --v-arcs 6 2>&1)
case "$out" in *placement*) bad "a placement line without placement options: $out" ;; *) ok ;; esac
# the residual reported is tiny (exact shape)
out=$("$RG2" shape cyclide --a 2 --c 1 --mu 0.5 --u-arcs 7 --v-arcs 5 --scale 100 --center 1e3,-2e3,5e2)
case "$out" in *"max |f|/|grad f| = "*) r=$(printf '%s\n' "$out" | sed -n 's/.*(\([0-9.e+-]*\) of the size.*/\1/p')
  awk -v r="$r" 'BEGIN { exit !(r + 0 <= 1e-13) }' && ok || bad "cyclide residual $r" ;;
  *) bad "cyclide summary: $out" ;; esac
# weights: warning on stderr, exit 0
expect 0 "warning: 1 patch has homogeneous weights <= 0" -- "$RG2" shape cyclide --a 1 --c 0.8 --mu 0.97 --u-arcs 3 --v-arcs 3
# JSON dump: patches with 4x4 homogeneous points, exact torus weight (1 + 2 cos 30)/3 in the mesh scalars
expect 0 '"patches": [' -- "$RG2" shape torus --u-arcs 3 --v-arcs 3 --json
"$RG2" shape torus --u-arcs 4 --v-arcs 4 --json | grep -q '0.80473785412436' && ok || bad "exact circle weight in JSON"
if command -v python3 >/dev/null; then
  "$RG2" shape hypar --u-knots -1,0,1 --v-knots -1,-0.5,0.5,1 --json |
    python3 -c 'import json,sys; d=json.load(sys.stdin); s=d["surface"]; assert s["nu"]==2 and s["nv"]==3 and len(s["patches"])==6 and len(s["patches"][0]["h"][3][3])==4' && ok || bad "hypar JSON"
fi
# NURBS from a JSON spec and file
N='{"nu":4,"nv":5,"points":[[0,0,0],[0,1,0],[0,2,0],[0,3,0],[0,4,0],[1,0,0],[1,1,1],[1,2,1],[1,3,1],[1,4,0],[2,0,0],[2,1,1],[2,2,2],[2,3,1],[2,4,0],[3,0,0],[3,1,0],[3,2,0],[3,3,0],[3,4,0]],"knots_u":[0,0,0,0,1,1,1,1],"knots_v":[0,0,0,0,0.4,1,1,1,1]}'
expect 0 "1 x 2 rational bi-cubic patches" -- "$RG2" shape nurbs --spec "$N"
tmp=$(mktemp -d); trap 'rm -rf "$tmp"' EXIT
printf '%s' "$N" > "$tmp/n.json"
expect 0 '"shape": "nurbs"' -- "$RG2" shape nurbs --file "$tmp/n.json" --json
expect 1 "cannot read" -- "$RG2" shape nurbs --file "$tmp/missing.json"
expect 1 "malformed JSON" -- "$RG2" shape nurbs --spec '{"nu": 4,'
expect 1 "the first or last span of the domain" -- "$RG2" shape nurbs --spec "$(printf '%s' "$N" | sed 's/0.4,1,1,1,1/0.4,0.4,1,1,1/')"
expect 1 "nurbs.knots_u: expected nu + 4 = 8 knots, found 7" -- "$RG2" shape nurbs --spec "$(printf '%s' "$N" | sed 's/"knots_u":\[0,/"knots_u":[/')"
expect 1 "nurbs: weight [0][1] = -1 must be finite and > 0" -- "$RG2" shape nurbs --spec "$(printf '%s' "$N" | sed 's/"knots_u"/"weights":[1,-1,1,1,1,1,1,1,1,1,1,1,1,1,1,1,1,1,1,1],"knots_u"/')"
expect 2 "exactly one of --file" -- "$RG2" shape nurbs
# bad input: each with its message
expect 2 "unknown shape 'donut'" -- "$RG2" shape donut
# a misspelt shape names the closest; 'rg2 shapes NAME' points to 'rg2 shape NAME'
expect 2 "unknown shape 'tours'" -- "$RG2" shape tours
expect 2 "did you mean 'torus'?" -- "$RG2" shape tours
# a size along the axis is the v knots, not an option: said so ('--height' got the parameter list alone)
expect 2 "cylinder takes --radius: its extent is not a parameter but its v knots, which place the rings (--v-range A,B" -- "$RG2" shape cylinder --height 3
expect 2 "cone takes --k: its extent is not a parameter but its v knots" -- "$RG2" shape cone --radius 2
expect 2 "unknown option '--length'; cylinder takes --radius: its extent is not a parameter but its v knots" -- "$RG2" shape cylinder --length 3
expect 2 "unknown option '--h'; cylinder takes --radius: its extent is not a parameter but its v knots" -- "$RG2" shape cylinder --h 3
# another shape's parameter is no extent: the parameter list alone
expect 2 "unknown option '--R'; cylinder takes --radius (see rg2 shape --help)" -- "$RG2" shape cylinder --R 2
expect 2 "unknown option '--radius'; torus takes --R --r (see rg2 shape --help)" -- "$RG2" shape torus --radius 2
expect 2 "rg2 shapes: unexpected argument 'torus' (rg2 shapes lists every shape; to build one: rg2 shape torus)" -- "$RG2" shapes torus
expect 1 "r = 2 must be < R = 1" -- "$RG2" shape torus --R 1 --r 2
expect 1 "b^2 = a^2 - c^2" -- "$RG2" shape cyclide --a 1 --c 2
expect 1 "parameter radius = -1 must be > 0" -- "$RG2" shape sphere --radius -1
expect 1 "must sum to 2 pi" -- "$RG2" shape torus --u-angles 100,100,100 --u-closed
expect 1 "arc 1 has opening angle" -- "$RG2" shape cylinder --u-angles 90,180,90
expect 1 "past 2 pi" -- "$RG2" shape cylinder --u-arcs 5 --u-sweep 400
expect 1 "knot 2 (= 0.5) is not greater than knot 1" -- "$RG2" shape sphere --v-knots 0.2,0.5,0.5
expect 1 "v knot 0 = -1 must be > 0" -- "$RG2" shape hyperboloid1 --v-knots -1,1
expect 1 "|v| < 1" -- "$RG2" shape hyperboloid2 --v-range 0,1.5
# an empty or reversed range names the option and its values (it read "equal partition: knot 1
# (= 4) is not greater than knot 0 (= 5)", exit 1; a negative sweep "arc 0 has opening angle")
expect 2 "rg2 shape: --v-range 5,2: the range is empty (5 >= 2)" -- "$RG2" shape cylinder --v-range 5,2 --v-segments 3
expect 2 "rg2 shape: --v-range 0.5,0.5: the range is empty (0.5 >= 0.5)" -- "$RG2" shape cone --v-range 0.5,0.5
expect 2 "rg2 shape: --u-range 1,-0.1: the range is empty (1 >= -0.1)" -- "$RG2" shape hypar --u-range 1,-0.1
expect 2 "rg2 shape: --u-sweep -90: the range is empty (a sweep of -90 <= 0 degrees)" -- "$RG2" shape torus --u-sweep -90
expect 2 "rg2 shape: --v-sweep 0: the range is empty (a sweep of 0 <= 0 degrees)" -- "$RG2" shape torus --v-arcs 3 --v-sweep 0
expect 0 "knots: -2 -1 0" -- "$RG2" shape cylinder --v-range -2,0 --v-segments 2
# v knots 1, 2, 3: the mirrored data knot lies at v = 0, a control point of weight 0 (at infinity,
# no coordinates) that the range check once divided by ("coordinates up to inf")
expect 0 "all positive" -- "$RG2" shape hyperboloid1 --v-knots 1,2,3
expect 0 "all positive" -- "$RG2" shape hyperboloid1 --v-knots 0.5,1
expect 1 "k = 0 gives a plane" -- "$RG2" shape cone --k 0
expect 1 "--scale 0: scale factors must be non-zero" -- "$RG2" shape torus --scale 0
expect 2 "v is a circle direction" -- "$RG2" shape torus --v-knots 1,2
expect 2 "u is a polynomial direction" -- "$RG2" shape hypar --u-arcs 4
expect 2 "needs --u-sweep" -- "$RG2" shape torus --u-open
# angles typed in radians, as a design file refuses them: a total of 2 pi, pi or pi / 2 degrees
# (to 1e-3) unless openness is stated (--u-angles 1.5708 x 4 built an open 6.28-degree sliver)
expect 1 "rg2 shape: torus: the --u-angles sum to 6.2832 degrees, which is 2 pi (a full circle in radians); angles are in degrees (a full circle is 360): convert them (times 180 / pi), or add --u-open if an open ring of 6.2832 degrees is meant" -- "$RG2" shape torus --u-angles 1.5708,1.5708,1.5708,1.5708
expect 1 "the --v-angles sum to 3.1416 degrees, which is pi (a half circle" -- "$RG2" shape torus --v-angles 1.0472,1.0472,1.0472
expect 1 "--u-sweep 1.5708 degrees, which is pi / 2 (a quarter circle" -- "$RG2" shape cylinder --u-sweep 1.5708
expect 1 "--u-sweep 6.2819 degrees, which is 2 pi" -- "$RG2" shape cylinder --u-arcs 1 --u-sweep 6.2819
expect 0 "u: open circle, 4 arcs from 0 deg, total 6.2832 deg" -- "$RG2" shape torus --u-angles 1.5708,1.5708,1.5708,1.5708 --u-open
expect 0 "u: open circle, 1 arc from 0 deg, total 1.5708 deg" -- "$RG2" shape cylinder --u-sweep 1.5708 --u-open
expect 0 "u: open circle, 1 arc from 0 deg, total 6.2769 deg" -- "$RG2" shape cylinder --u-arcs 1 --u-sweep 6.2769
expect 2 "torus takes --R --r" -- "$RG2" shape torus --radius 2
# the design file's limits: 100000 arcs or intervals per direction, 1000000 patches
expect 0 "v: polynomial, 4200 segments" -- "$RG2" shape cylinder --u-arcs 3 --v-segments 4200 --samples 1
expect 2 "--v-segments 100001: need an integer 1..100000" -- "$RG2" shape cylinder --v-segments 100001
expect 1 "size limit exceeded: cylinder: 2000000 patches, more than the limit of 1000000" -- "$RG2" shape cylinder --u-arcs 100 --v-segments 20000
# the smallest arc, 0.005 rad (0.286479 deg), is in the help: 1256 arcs make a circle, 1257 do not
expect 0 "[0.286479, 180) (0.005 rad up to pi, excluded), so a full circle has 3 to 1256 arcs" -- "$RG2" shape --help
expect 0 "1256 arcs" -- "$RG2" shape torus --u-arcs 1256 --v-arcs 3 --samples 1
expect 1 "below the smallest supported arc of 0.005 rad (0.286479 deg)" -- "$RG2" shape torus --u-arcs 1257 --v-arcs 3
grep -q "lies in \[0.286479, 180) degrees" "$SRC/docs/design-format.md" && ok || bad "design-format.md lacks the smallest arc"
expect 2 "--R needs a number, not 'abc'" -- "$RG2" shape torus --R abc
expect 2 "--xform needs 16 numbers" -- "$RG2" shape torus --xform 1,2,3
# the numeric range and placement checks of design files (rg2_number_check, rg2_mesh_check_range,
# rg2_shape_mesh's weights): never a nan summary or a bare nan in --json
expect 2 "--R: number 1e+200 is outside the supported range" -- "$RG2" shape torus --R 1e200
expect 2 "--r: number 1e+299 is outside the supported range" -- "$RG2" shape torus --r 1e299 --R 1e99 --json
expect 2 "--center item 0: number 1e+101 is outside" -- "$RG2" shape sphere --center 1e101,0,0
# a list of two names its item too
expect 2 "--v-range item 1: number 1e+101 is outside" -- "$RG2" shape cone --v-range 0.5,1e101
expect 1 "sphere: coordinates up to" -- "$RG2" shape sphere --radius 1e60 --scale 1e60
expect 1 "torus: coordinates up to 4.68015e-200, size 1.34027e-199: outside the supported range" -- "$RG2" shape torus --R 3e-100 --r 1e-100 --scale 1e-100
expect 1 "--axis 0,0,0: the axis is the zero vector" -- "$RG2" shape cone --axis 0,0,0
expect 1 "the placement gives control point" -- "$RG2" shape torus --xform 1,0,0,0,0,1,0,0,0,0,1,0,0,0,0,-1
expect 1 "ellipsoid: v knot 1 = 1 must lie in (0, 1)" -- "$RG2" shape ellipsoid --v-knots 0.5,1,1.5
expect 1 "torus: coordinates up to" -- "$RG2" shape torus --R 1e90 --r 1e89
expect 0 "usage: rg2 shape NAME" -- "$RG2" shape torus --R 2 --help
# --samples N: the residual over (N + 1) x (N + 1) samples per patch (default 8)
expect 0 "over 4 x 4 samples per patch" -- "$RG2" shape torus --samples 3
expect 0 "over 9 x 9 samples per patch" -- "$RG2" shape torus
for args in "torus" "cone --v-range 0,1 --v-segments 2" "sphere --v-knots 0.01,0.5,0.99" "torus --scale 1e-50" \
            "torus --R 1e50 --r 1e49"; do
  if "$RG2" shape $args --json | python3 -c 'import json, math, sys
d = json.load(sys.stdin, parse_constant=lambda c: sys.exit("bare " + c))
r = d["max_residual"]
sys.exit(0 if r is not None and math.isfinite(r) else "residual %r" % r)'; then ok
  else bad "rg2 shape $args --json: not valid JSON with a finite max_residual"; fi
done
# a circle direction refuses each polynomial option; zero scale factors in any axis; a misspelt
# nurbs is suggested as the exact shapes are
for o in "--u-range 0,1" "--u-segments 3" "--u-knots 0,1"; do
  expect 2 "rg2 shape: torus: u is a circle direction" -- "$RG2" shape torus $o
done
for sc in 0,1,1 1,0,1 1,1,0; do expect 1 "--scale $sc: scale factors must be non-zero" -- "$RG2" shape torus --scale $sc; done
expect 2 "did you mean 'nurbs'?" -- "$RG2" shape nurb
# the arcs a sweep needs past the limit: the message names the limit that --u-arcs states
lim=$("$RG2" shape torus --u-arcs 0 2>&1 | sed -n 's/.*need an integer 1\.\.\([0-9]*\).*/\1/p')
expect 2 "--u-arcs $(( (10000000 + 44) / 45 )): at most $lim" -- "$RG2" shape torus --u-sweep 1e7
# the size printed is the bounding-box diagonal of the torus: x, y in [-(R + r), R + r], z in [-r, r];
# the residual of the exact shape is rounding, at any scale
for p in "3 1 1" "5 2 1" "3 1 1000" "3 1 0.001"; do
  read -r R r k <<< "$p"
  out=$("$RG2" shape torus --R "$R" --r "$r" --scale "$k")
  got=$(printf '%s\n' "$out" | sed -n 's/.*(\([0-9.e+-]*\) of the size \([0-9.e+-]*\)).*/\1 \2/p')
  awk -v g="$got" -v R="$R" -v r="$r" -v k="$k" 'BEGIN { split(g, a, " "); d = k * sqrt(8 * (R + r)^2 + 4 * r^2)
    exit !(a[1] != "" && a[1] + 0 <= 1e-13 && a[2] > d * (1 - 1e-5) && a[2] < d * (1 + 1e-5)) }' && ok ||
    bad "torus R=$R r=$r scale $k: residual and size '$got', size expected $(awk -v R="$R" -v r="$r" -v k="$k" 'BEGIN { print k * sqrt(8 * (R + r)^2 + 4 * r^2) }')"
done
# the listed arcs or knots: all of them, or the first 12 arcs (knots of 12 segments) and " ..."
for n in 6 12 13 14; do
  for c in "u torus --u-arcs $n" "v cylinder --v-segments $n"; do
    set -- $c; want=$((n > 12 ? 12 : n)); [ "$2" = cylinder ] && want=$((want + 1))
    line=$("$RG2" shape "${@:2}" | grep "^  $1: "); line=${line#*deg:}; line=${line#*knots:}
    vals=$(printf '%s' "${line% ...}" | wc -w); more=no; [[ "$line" == *" ..." ]] && more=yes
    [ "$vals" = "$want" ] && [ "$more" = "$([ "$n" -gt 12 ] && echo yes || echo no)" ] && ok ||
      bad "rg2 shape ${*:2}: $vals values listed, ' ...': $more (want $want, ' ...' iff more than 12): $line"
  done
done
finish
