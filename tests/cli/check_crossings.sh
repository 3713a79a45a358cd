#!/usr/bin/env bash
# CLI tests of rg2 check --intersections and --require no-crossings: every example surface
# keeps the promise alone (the examples' output lists, except Fig. 1's overlaid torus variants,
# keep it together); two crossing cylinders break it (exit 3, the row, the JSON object whose
# point lies on both cylinders); without the option the report has no crossings row; bad
# densities are usage errors.
# Usage: bash check_crossings.sh <path-to-rg2> <source-dir>
set -u
. "$(dirname "$0")/lib.sh"
cyl=$SRC/tests/data/crossing_cylinders.json

"$RG2" check --help | grep -q -- "--intersections" && ok || bad "--help lacks --intersections"
"$RG2" check --help | grep -q -- "no-crossings" && ok || bad "--help lacks no-crossings"
for f in "$SRC"/examples/*.json; do
  case $f in
    */fig1_torus.json) expect 3 "failed: no-crossings" -- "$RG2" check "$f" --require no-crossings ;;
    *) expect 0 "crossings            0 of" -- "$RG2" check "$f" --require no-crossings ;;
  esac
done
# the torus pushed through its tube: G2, regular and on its torus where unmoved, but it crosses itself
expect 3 "failed: no-crossings" -- "$RG2" check "$SRC/tests/data/torus_pushed_through.json" --require g2,exact,weights,no-crossings
# the crossing cylinders: the promise fails, the row names both surfaces
expect 3 "failed: no-crossings" -- "$RG2" check "$cyl" --require no-crossings
expect 0 "x surface 1 patch" -- "$RG2" check "$cyl" --intersections 2
expect 3 "FAIL" -- "$RG2" check "$cyl" --intersections --require no-crossings,g2,exact
# each alone is clean: g2 and exact hold while no-crossings fails (only no-crossings named)
out=$("$RG2" check "$cyl" --require g2,exact,no-crossings 2>&1 >/dev/null)
[ "$out" = "rg2 check: $cyl: required promise failed: no-crossings" ] && ok || bad "stderr: $out"
# JSON: the crossings object, its point on x^2 + y^2 = 1 and y^2 + z^2 = 1 (independently)
"$RG2" check "$cyl" --json --intersections 3 | python3 -c '
import json, sys
c = json.load(sys.stdin)["crossings"]
x, y, z = c["point"]
assert c["density"] == 3 and c["crossings"] > 0 and not c["ok"], c
assert abs(x*x + y*y - 1) < 1e-12 and abs(y*y + z*z - 1) < 1e-12, (x, y, z)
assert {c["a"]["surface"], c["b"]["surface"]} == {0, 1}, c
' && ok || bad "the JSON crossings object"
# without the option: no row, no object (the old report)
"$RG2" check "$cyl" | grep -q crossings && bad "a crossings row without --intersections" || ok
"$RG2" check "$cyl" --json | grep -q crossings && bad "a crossings object without --intersections" || ok
# the density is optional: a following design name is not taken for it
expect 0 "density 4)" -- "$RG2" check --intersections "$cyl"
# nor a design whose name begins with a digit (it was taken for the density: a usage error)
tmp=$(mktemp -d)
cp "$cyl" "$tmp/2cyl.json"
rg2abs=$(cd "$(dirname "$RG2")" && pwd)/$(basename "$RG2")
expect 0 "density 4)" -- sh -c 'cd "$1" && "$2" check --intersections 2cyl.json' sh "$tmp" "$rg2abs"
expect 2 "--intersections needs an integer 1..1000, not '2.5'" -- "$RG2" check "$cyl" --intersections 2.5
rm -rf "$tmp"
expect 2 "--intersections needs an integer 1..1000, not '0'" -- "$RG2" check "$cyl" --intersections 0
expect 2 "--intersections needs an integer 1..1000, not '-2'" -- "$RG2" check "$cyl" --intersections -2
expect 2 "--intersections needs an integer 1..1000, not '1001'" -- "$RG2" check "$cyl" --intersections 1001
expect 2 "unknown promise 'no-crossing'" -- "$RG2" check "$cyl" --require no-crossing
# spaces around the items of a quoted list ("g2, exact") are not part of the names
expect 3 "required promise failed: no-crossings" -- "$RG2" check "$cyl" --require "g2, exact ,	no-crossings"
expect 0 "G2 curvature jump" -- "$RG2" check "$SRC/examples/torus_sphere.json" --require " g2 , exact"
expect 2 "(an empty item)" -- "$RG2" check "$cyl" --require "g2, ,exact"
expect 1 "exceed the limit of 4000000: a lower density" -- "$RG2" check "$cyl" --intersections 300

# --surface K: output K alone, named K. Fig. 1's overlaid variants cross each other, but each
# alone keeps the promise; so does each crossing cylinder.
"$RG2" check --help | grep -q -- "--surface K" && ok || bad "--help lacks --surface"
for k in 0 1 2 3; do
  expect 0 "crossings            0 of" -- "$RG2" check "$SRC/examples/fig1_torus.json" --surface $k --require no-crossings
done
expect 0 "crossings            0 of" -- "$RG2" check "$cyl" --surface 1 --intersections --require g2,exact,no-crossings
# every design with several outputs: the whole report's worst gaps and largest |k| are the worst
# over the outputs checked alone (the first output on a tie), at the same place, and each alone
# names only its own number
python3 - "$RG2" "$SRC" "$cyl" <<'PY' && ok || bad "--surface reports against the whole design's"
import glob, json, subprocess, sys
rg2, src, cyl = sys.argv[1], sys.argv[2], sys.argv[3]
def check(path, *extra):
    r = subprocess.run([rg2, "check", path, "--json", *extra], capture_output=True, text=True)
    assert r.returncode == 0, (path, extra, r.stderr)
    return json.loads(r.stdout)
designs = 0
for path in sorted(glob.glob(src + "/examples/*.json")) + [cyl]:
    whole = check(path)
    n = whole["surfaces"]
    if n < 2:
        continue
    designs += 1
    parts = [check(path, "--surface", str(k)) for k in range(n)]
    for k, p in enumerate(parts):
        assert p["surfaces"] == 1, (path, k)
        for g in ("g0_position", "g1_normal_angle", "g2_curvature_jump"):
            assert p[g]["surface"] == k, (path, k, g, p[g])
        if "largest_curvature" in p:
            assert p["largest_curvature"]["surface"] == k, (path, k)
        for s in p["shapes"]:
            assert s["patches"] == 0 or s["where"].startswith("surface %d " % k), (path, k, s)
    assert whole["patches"] == sum(p["patches"] for p in parts), path
    assert whole["seams"] == sum(p["seams"] for p in parts), path
    for g in ("g0_position", "g1_normal_angle", "g2_curvature_jump"):
        worst = max(p[g]["value"] for p in parts)
        first = next(p for p in parts if p[g]["value"] == worst)
        assert whole[g] == first[g], (path, g, whole[g], first[g])
    ks = [p["largest_curvature"] for p in parts if "largest_curvature" in p]
    big = max(abs(x["k"]) for x in ks)
    assert whole["largest_curvature"] == next(x for x in ks if abs(x["k"]) == big), path
assert designs >= 5, designs
PY
expect 2 "rg2 check: --surface 4: the design has 4 surfaces (0..3)" -- "$RG2" check "$SRC/examples/fig1_torus.json" --surface 4
expect 2 "rg2 check: --surface 2: the design has 2 surfaces (0..1)" -- "$RG2" check "$SRC/examples/fig9_polar_sphere.json" --surface 2
expect 2 "rg2 check: --surface 1: the design has 1 surface (0..0)" -- "$RG2" check "$SRC/examples/torus_sphere.json" --surface 1
# --on names each surface by its number in the design: Fig. 9's two outputs 0 and 1, in that
# order, and output 1 alone as 1
on_surfaces() {
  "$RG2" check "$SRC/examples/fig9_polar_sphere.json" --on ball "$@" | sed -n 's/^on shape ball *surface \([-0-9]*\):.*/\1/p' | tr '\n' ' '
}
[ "$(on_surfaces)" = "0 1 " ] && ok || bad "fig9 --on ball names surfaces '$(on_surfaces)', not '0 1 '"
[ "$(on_surfaces --surface 1)" = "1 " ] && ok || bad "fig9 --on ball --surface 1 names surfaces '$(on_surfaces --surface 1)', not '1 '"
expect 2 "--surface needs a surface index (an integer >= 0), not '-1'" -- "$RG2" check "$cyl" --surface -1
expect 2 "--surface needs a surface index (an integer >= 0), not '1.5'" -- "$RG2" check "$cyl" --surface 1.5
expect 2 "--surface needs a surface index (an integer >= 0), not 'b'" -- "$RG2" check "$cyl" --surface b
# a second --surface would silently replace the first: refused in every command that takes it
expect 2 "rg2 check: --surface given twice ('0', then '1'); it takes one surface (without it: all)" -- "$RG2" check "$cyl" --surface 0 --surface 1
expect 2 "rg2 render: --surface given twice ('1', then '1')" -- "$RG2" render "$cyl" --surface 1 --surface 1 -o "$tmp/twice.png"
expect 2 "rg2 build: --surface given twice ('0', then '2')" -- "$RG2" build "$cyl" --surface 0 --surface 2 -o "$tmp/twice.step"
[ ! -e "$tmp/twice.png" ] && [ ! -e "$tmp/twice.step" ] && ok || bad "a refused --surface left a file"
finish
