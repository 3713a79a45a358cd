#!/usr/bin/env bash
# CLI tests of rg2 build / info / mesh: good designs write their outputs; bad designs exit 1
# with a message naming the problem and write nothing; usage errors exit 2.
# Usage: bash design.sh <path-to-rg2> <source-dir>
set -u
rg2=$1 src=$2
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
fails=0 passes=0
ok() { passes=$((passes + 1)); }
bad() { echo "FAIL: $*" >&2; fails=$((fails + 1)); }

# expect CODE SUBSTRING -- command...: exit code and a stderr substring
expect() {
  local code=$1 sub=$2; shift 2
  "$@" >"$tmp/out" 2>"$tmp/err"
  local rc=$?
  if [ "$rc" != "$code" ]; then bad "$* -> exit $rc, expected $code ($(head -c 300 "$tmp/err"))"; return; fi
  if [ -n "$sub" ] && ! grep -qF -- "$sub" "$tmp/err"; then bad "$* -> message '$(cat "$tmp/err")' lacks '$sub'"; return; fi
  ok
}

for cmd in build info mesh; do
  "$rg2" $cmd --help >"$tmp/out" 2>&1 && grep -q "usage: rg2 $cmd" "$tmp/out" && ok || bad "$cmd --help"
  expect 2 "" "$rg2" $cmd
  expect 2 "unknown option" "$rg2" $cmd --frobnicate "$src/examples/torus_sphere.json"
done
"$rg2" --help | grep -q '^  build' && ok || bad "build missing from rg2 --help"

# good design: several outputs
expect 0 "" "$rg2" build -q "$src/examples/torus_sphere.json" -o "$tmp/ts.step" -o "$tmp/ts.json"
[ -s "$tmp/ts.step" ] && head -1 "$tmp/ts.step" | grep -q "ISO-10303-21" && ok || bad "ts.step not written"
[ -s "$tmp/ts.json" ] && ok || bad "ts.json not written"
# export.md shows the .json dump's keys in the order the file has them
file_keys=$(grep -oE '"[a-z_]+":' "$tmp/ts.json" | tr -d '":' | awk '!seen[$0]++' | tr '\n' ' ')
doc_keys=$(grep '^| `.json`' "$src/docs/export.md" | grep -oE '(^|[^:])"[a-z_]+"' | grep -oE '[a-z_]+' | tr '\n' ' ')
[ "$file_keys" = "$doc_keys" ] && ok || bad "export.md .json keys '$doc_keys', the file has '$file_keys'"
# IGES as B-rep shells: one 514 per output surface (torus_sphere: 1), faces 510 per patch (120)
expect 0 "" "$rg2" build -q "$src/examples/torus_sphere.json" -o "$tmp/ts.igs" --iges-brep
n514=$(awk 'substr($0,73,1)=="D" && substr($0,74)%2==1 && $1==514' "$tmp/ts.igs" | wc -l)
n510=$(awk 'substr($0,73,1)=="D" && substr($0,74)%2==1 && $1==510' "$tmp/ts.igs" | wc -l)
[ "$n514" -eq 1 ] && [ "$n510" -eq 120 ] && ok || bad "ts.igs B-rep: $n514 shells, $n510 faces"
# a failed set of outputs leaves files that were there as they were (none is overwritten before
# every output is written), whichever output fails
cp "$tmp/ts.step" "$tmp/prev.step"
expect 1 "/nonexistent-rg2-dir/b.igs: cannot write" "$rg2" build -q "$src/examples/fig1_torus.json" -o "$tmp/ts.step" -o /nonexistent-rg2-dir/b.igs
cmp -s "$tmp/ts.step" "$tmp/prev.step" && ok || bad "a failed build changed the ts.step that was there"
expect 1 "/nonexistent-rg2-dir/b.igs: cannot write" "$rg2" build -q "$src/examples/fig1_torus.json" -o /nonexistent-rg2-dir/b.igs -o "$tmp/ts.step"
cmp -s "$tmp/ts.step" "$tmp/prev.step" && ok || bad "a failed build changed the ts.step that was there (failing output first)"
ls "$tmp" | grep -q '\.tmp$' && bad "temporary file left behind" || ok
# an output that is a directory is refused before any file is written (its rename failed only
# after ts.step had been replaced), by every writer
mkdir "$tmp/adir.igs" "$tmp/adir.json" "$tmp/adir.png"
expect 1 "$tmp/adir.igs: cannot write: it is a directory" "$rg2" build -q "$src/examples/fig1_torus.json" -o "$tmp/ts.step" -o "$tmp/adir.igs"
cmp -s "$tmp/ts.step" "$tmp/prev.step" && ok || bad "a build with a directory as output changed the ts.step that was there"
expect 1 "$tmp/adir.json: cannot write: it is a directory" "$rg2" mesh "$src/examples/fig1_torus.json" -o "$tmp/adir.json"
expect 1 "$tmp/adir.png: cannot write: it is a directory" "$rg2" render "$src/examples/fig1_torus.json" -o "$tmp/adir.png" --size 16x16
[ -z "$(find "$tmp"/adir.* -mindepth 1)" ] && ! ls "$tmp" | grep -q '\.tmp$' && ok || bad "files left by the directory outputs"
rmdir "$tmp/adir.igs" "$tmp/adir.json" "$tmp/adir.png"
# a symbolic link to a directory is replaced by the rename, as a link to a file is: not refused
mkdir "$tmp/ldir" && ln -s ldir "$tmp/link.step"
expect 0 "" "$rg2" build -q "$src/examples/fig1_torus.json" -o "$tmp/link.step"
[ -f "$tmp/link.step" ] && [ ! -L "$tmp/link.step" ] && [ -d "$tmp/ldir" ] && ok || bad "link.step was not replaced by the STEP file"
rm -rf "$tmp/ldir" "$tmp/link.step"
# an empty design file name is named as such (it read ": cannot open: No such file or directory")
expect 1 "rg2 build: input/output error: '': cannot open: the file name is empty" "$rg2" build -q "" -o "$tmp/e.step"
expect 1 "rg2 info: input/output error: '': cannot open: the file name is empty" "$rg2" info ""
[ ! -e "$tmp/e.step" ] && ok || bad "a build of an empty file name wrote e.step"
# a link to a file and a named pipe as outputs: each name becomes the file, the target unchanged
echo target > "$tmp/target.step" && ln -s target.step "$tmp/flink.step" && mkfifo "$tmp/pipe.igs"
expect 0 "" "$rg2" build -q "$src/examples/fig1_torus.json" -o "$tmp/flink.step" -o "$tmp/pipe.igs"
[ -f "$tmp/flink.step" ] && [ ! -L "$tmp/flink.step" ] && [ -f "$tmp/pipe.igs" ] && [ ! -p "$tmp/pipe.igs" ] &&
  [ "$(cat "$tmp/target.step")" = target ] && grep -q ISO-10303-21 "$tmp/flink.step" && ok ||
  bad "the link or pipe output was not replaced by a file, or the link's target changed"
rm -f "$tmp/target.step" "$tmp/flink.step" "$tmp/pipe.igs"
# a hidden file with a name is no name that is only the extension ('.step' is refused, in
# bad/table.tsv): '.ts.step' (named '.ts') and '..step' (named '.') are written
expect 0 "" "$rg2" build -q "$src/examples/fig1_torus.json" -o "$tmp/.ts.step" -o "$tmp/..step"
grep -q ISO-10303-21 "$tmp/.ts.step" && grep -q ISO-10303-21 "$tmp/..step" && ok ||
  bad "the hidden outputs .ts.step and ..step were not written"
rm -f "$tmp/.ts.step" "$tmp/..step"
# a file written over keeps its permission bits, as with sed -i (0600 and 0444 became 0644); a
# new file has 0666 & ~umask; build, mesh and render write through the same helper
for m in 600 444 640; do
  echo x > "$tmp/p$m.step" && chmod "$m" "$tmp/p$m.step" && echo x > "$tmp/p$m.json" && chmod "$m" "$tmp/p$m.json"
  expect 0 "" "$rg2" build -q "$src/examples/fig1_torus.json" -o "$tmp/p$m.step"
  expect 0 "" "$rg2" mesh "$src/examples/fig1_torus.json" -o "$tmp/p$m.json"
  [ "$(stat -c %a "$tmp/p$m.step")" = "$m" ] && [ "$(stat -c %a "$tmp/p$m.json")" = "$m" ] &&
    grep -q ISO-10303-21 "$tmp/p$m.step" && ok ||
    bad "a $m file written over: modes $(stat -c %a "$tmp/p$m.step") (build), $(stat -c %a "$tmp/p$m.json") (mesh)"
  rm -f "$tmp/p$m.step" "$tmp/p$m.json"
done
for u in 022 077; do
  expect 0 "" bash -c "umask $u && exec '$rg2' build -q '$src/examples/fig1_torus.json' -o '$tmp/new$u.step'"
done
[ "$(stat -c %a "$tmp/new022.step")" = 644 ] && [ "$(stat -c %a "$tmp/new077.step")" = 600 ] && ok ||
  bad "new files under umask 022 and 077: $(stat -c %a "$tmp/new022.step") and $(stat -c %a "$tmp/new077.step")"
rm -f "$tmp/new022.step" "$tmp/new077.step"
expect 0 "" "$rg2" info --map "$src/examples/torus_sphere.json"
grep -q "exact on ring *48 patches" "$tmp/out" && grep -q "exact on ball *24 patches" "$tmp/out" &&
  grep -q "transition *48 patches" "$tmp/out" && ok || bad "info counts: $(cat "$tmp/out")"
# the map: a line per u index (15), a letter per v index (8), as many A, B and '.' as the design's
# "expect" gives patches on the ring, on the ball and in transitions (48, 24, 48)
awk '/^    u +[0-9]+  /{ n++; m = $3; w += length(m) != 8; a += gsub(/A/, "", m); b += gsub(/B/, "", m); t += gsub(/[.]/, "", m) }
  END { exit !(n == 15 && !w && a == 48 && b == 24 && t == 48) }' "$tmp/out" && ok || bad "info --map: $(cat "$tmp/out")"
# the ends of a tube: fig. 10's capsule capped at both; a south cap only on a mesh polar at both
# ends leaves a hole at the north pole, which info names
expect 0 "" "$rg2" info "$src/examples/fig10_sphere_cylinder.json"
grep -q "ends: south (v start) capped; north (v end) capped" "$tmp/out" && ok || bad "info ends: $(cat "$tmp/out")"
sed 's/"sphere": {"cap": "beside"}/"sphere": {"cap": "beside", "ends": "south"}/' "$src/examples/fig9_polar_sphere.json" >"$tmp/north_hole.json"
expect 0 "" "$rg2" info "$tmp/north_hole.json"
grep -q "ends: south (v start) capped; north (v end) a polar point, not capped: a hole around the pole" "$tmp/out" &&
  ok || bad "info north hole: $(cat "$tmp/out")"
rm -f "$tmp/north_hole.json"
# what a placement does to the listed kind: a sphere transformed by a non-uniform scale (an
# ellipsoid), by a uniform scale of 2 with a turn and a shift, and by a reflection (none)
for tr in '"scale": [2, 1, 1]|, stretched or sheared by its placement (not these proportions)' \
          '"scale": 2, "rotate": {"axis": [1, 2, 3], "degrees": 33}, "translate": [1, 2, 3]|, scaled by 2 by its placement' \
          '"scale": [1, 1, -1]|'; do
  printf '{"shapes": {"b": {"kind": "sphere"}}, "meshes": {"s": {"shape": "b"}, "t": {"transform": "s", %s}}}' \
    "${tr%%|*}" >"$tmp/placed.json"
  expect 0 "" "$rg2" info "$tmp/placed.json"
  want="b@meshes.t *sphere radius=1${tr#*|}\$"
  grep -q "^  B $want" "$tmp/out" && grep -q "^  A b *sphere radius=1\$" "$tmp/out" && ok ||
    bad "info of a placed sphere (${tr%%|*}): $(cat "$tmp/out")"
done
rm -f "$tmp/placed.json"
expect 0 "" "$rg2" mesh "$src/examples/fig1_torus.json" -o "$tmp/mesh.json"
grep -q '"rg2 control mesh 1"' "$tmp/mesh.json" && grep -q '"patch_shape"' "$tmp/mesh.json" && ok || bad "mesh.json content"

# a design file name that is not UTF-8 (Latin-1 'é'): the mesh file stays UTF-8 JSON, the byte a '?'
cp "$src/examples/fig1_torus.json" "$tmp/lat"$'\xe9'".json"
expect 0 "" "$rg2" mesh "$tmp/lat"$'\xe9'".json" -o "$tmp/lat.json"
grep -qF "\"$tmp/lat?.json\"" "$tmp/lat.json" && ! LC_ALL=C grep -q $'\xe9' "$tmp/lat.json" && ok ||
  bad "mesh of a Latin-1 file name: $(grep -a '"design"' "$tmp/lat.json")"
rm -f "$tmp/lat"$'\xe9'".json" "$tmp/lat.json"

# a bad extension among several outputs: a usage error before the build, nothing written
expect 2 "unknown export format '.xyz'" "$rg2" build -q "$src/examples/fig5_workflow.json" -o "$tmp/w.step" -o "$tmp/w.xyz"
[ -e "$tmp/w.step" ] && bad "w.step written despite a bad -o" || ok
expect 2 "has no extension" "$rg2" build -q "$src/examples/fig5_workflow.json" -o "$tmp/noext"
expect 2 "listed twice" "$rg2" build -q "$src/examples/fig5_workflow.json" -o "$tmp/w.step" -o "$tmp/w.step"
# the same output named two ways is refused whether or not the file exists yet
mkdir "$tmp/dup"
abs_rg2=$(cd "$(dirname "$rg2")" && pwd)/$(basename "$rg2") abs_src=$(cd "$src" && pwd)
expect 2 "output './a.step' is listed twice (as 'a.step')" bash -c "cd '$tmp/dup' && '$abs_rg2' build -q '$abs_src/examples/fig5_workflow.json' -o a.step -o ./a.step"
expect 2 "is listed twice" "$rg2" build -q "$src/examples/fig5_workflow.json" -o "$tmp/dup/b.step" -o "$tmp/dup//b.step"
# in a directory that does not exist the names are compared lexically ("." and empty components dropped)
expect 2 "output '$tmp/none/c.step' is listed twice (as '$tmp/none/./c.step')" "$rg2" build -q "$src/examples/fig5_workflow.json" -o "$tmp/none/./c.step" -o "$tmp/none/c.step"
[ -z "$(ls -A "$tmp/dup")" ] && ok || bad "a refused duplicate output wrote $(ls -A "$tmp/dup")"
# files at the temporary file's names are never written through: a design file named like one
# builds and keeps its bytes, and symbolic links planted at the old name (<output>.tmp) and at
# the name the run will use (exec keeps the shell's pid, which names the temporary file) leave
# their target alone
cp "$src/examples/fig1_torus.json" "$tmp/dup/o.json.tmp"
expect 0 "" "$rg2" build -q "$tmp/dup/o.json.tmp" -o "$tmp/dup/o.json"
echo victim >"$tmp/dup/victim"
expect 0 "" bash -c "ln -s '$tmp/dup/victim' '$tmp/dup/p.step.tmp' && ln -s '$tmp/dup/victim' '$tmp/dup/p.step.'\$\$'.tmp' && exec '$rg2' build -q '$src/examples/fig1_torus.json' -o '$tmp/dup/p.step'"
cmp -s "$src/examples/fig1_torus.json" "$tmp/dup/o.json.tmp" && [ "$(cat "$tmp/dup/victim")" = victim ] &&
  [ -f "$tmp/dup/o.json" ] && [ ! -L "$tmp/dup/p.step" ] && grep -q "ISO-10303-21" "$tmp/dup/p.step" &&
  [ "$(ls "$tmp/dup" | grep -c '\.tmp$')" = 3 ] && ok ||
  bad "a file at a temporary name was written through, or outputs missing: $(ls -l "$tmp/dup")"
# a later output that cannot be written: the outputs already written are removed again
expect 1 "$tmp/no/such/dir/w.igs" "$rg2" build -q "$src/examples/fig5_workflow.json" -o "$tmp/w.step" -o "$tmp/no/such/dir/w.igs"
[ -e "$tmp/w.step" ] && bad "w.step left behind after a failed build" || ok

# an unwritable output: exit 1 naming the path
expect 1 "$tmp/no/such/dir/x.step" "$rg2" build -q "$src/examples/fig5_workflow.json" -o "$tmp/no/such/dir/x.step"
expect 1 "$tmp/no/such/dir/m.json" "$rg2" mesh "$src/examples/fig5_workflow.json" -o "$tmp/no/such/dir/m.json"

# bad designs: exit 1, the message, no output file
check_bad() {
  local file=$1 sub=$2
  for cmd in build mesh; do
    rm -f "$tmp/o.step" "$tmp/o.json"
    if [ $cmd = build ]; then
      expect 1 "$sub" "$rg2" build -q "$src/tests/data/$file" -o "$tmp/o.step"
    else
      expect 1 "$sub" "$rg2" mesh "$src/tests/data/$file" -o "$tmp/o.json"
    fi
    [ -e "$tmp/o.step" ] || [ -e "$tmp/o.json" ] || compgen -G "$tmp/o.*tmp" >/dev/null && bad "$cmd $file wrote output" || ok
  done
  expect 1 "$sub" "$rg2" info "$src/tests/data/$file"
}
check_bad bad_syntax.json "bad_syntax.json:3:3: malformed JSON"
check_bad bad_key.json "meshes.M: unknown key 'closd' (did you mean 'closed'?)"
check_bad bad_shape.json "unknown shape kind 'sphre' (did you mean 'sphere'?)"
check_bad bad_merge.json "meshes 'tube' and 'band' do not agree in v (the direction that must match when merging along u): 6 vs 8 control points (make both with the same partition there: the same arcs or knots)"
check_bad bad_index.json "meshes.E.points[0].at: control point [3, 6] is outside the 8 x 6 points of mesh 'T' (indices count from 0: [0..7, 0..5])"
check_bad bad_overflow.json "shapes.t.R: number is not finite"
check_bad bad_weight.json "meshes.E.points[0].W: weight W = -0.5, must be > 0"
check_bad bad_type.json "shapes.t.R: expected a number, found a string"
check_bad bad_missing.json "meshes.M: missing key 'along'"
check_bad bad_scalar.json "junction 2 has K"
check_bad no_such_design.json "cannot open"

# a twisted merge (the upper cylinder's circle starts 45 degrees on) builds, with a note from info
# (stdout) and build (stderr; none with -q)
cat >"$tmp/twist.json" <<'EOF'
{"shapes": {"c": {"kind": "cylinder"}}, "meshes": {
  "A": {"shape": "c", "u": {"arcs": 8}, "v": {"segments": 3, "from": 0, "to": 1}},
  "B": {"shape": "c", "u": {"arcs": 8, "from": 45}, "v": {"segments": 3, "from": 1.5, "to": 2.5}},
  "M": {"merge": ["A", "B"], "along": "v"}}}
EOF
note="twist.json: meshes.M.merge[1]: the closed u rows of 'A' and 'B' meet turned by 45 degrees"
"$rg2" info "$tmp/twist.json" | grep -qF "note: $tmp/$note" && ok || bad "info twist.json: no note"
expect 0 "rg2 build: note: $tmp/$note" "$rg2" build "$tmp/twist.json" -o "$tmp/twist.obj"
expect 0 "" "$rg2" build -q "$tmp/twist.json" -o "$tmp/twist.obj"
[ -s "$tmp/err" ] && bad "build -q twist.json printed: $(cat "$tmp/err")" || ok
# a closed surface: info says which way its normal points (a capped cylinder reversed along u
# points in, which FreeCAD turns round without a word)
cat >"$tmp/inward.json" <<'EOF'
{"shapes": {"c": {"kind": "cylinder"}}, "meshes": {
  "A": {"shape": "c", "u": {"arcs": 8}, "v": {"segments": 3, "from": -1, "to": 1}},
  "out": {"cap": "A"}, "R": {"reverse": "A", "dir": "u"}, "in": {"cap": "R"}},
 "output": ["out", "in"]}
EOF
"$rg2" info "$tmp/inward.json" >"$tmp/out" 2>&1
[ "$(grep -c '  closed: the normal points out (enclosed volume about' "$tmp/out")" = 1 ] && ok || bad "info inward.json: $(cat "$tmp/out")"
grep -q '  closed: the normal points IN (enclosed volume about -.*reverse the mesh along u or v' "$tmp/out" && ok ||
  bad "info inward.json: no inward normal: $(cat "$tmp/out")"
# info --near: the nearest control point, found again here from rg2 mesh's d and W, and printed
# with the mesh's d and W; the edit it prints, applied (a move), changes exactly the patches it
# names (the build dumps compared patch by patch): an uncapped torus + sphere, and the capped elbow
# near its south and north ends (the cap refits) and in its middle; a polar point is named as the
# pole to edit
near_case() { # design X,Y,Z
  local design=$1 at=$2
  "$rg2" mesh "$design" -o "$tmp/near_mesh.json" >/dev/null 2>&1 &&
    "$rg2" info --near "$at" "$design" >"$tmp/near_info" 2>&1 &&
    "$rg2" build -q "$design" -o "$tmp/near_a.json" >/dev/null 2>&1 || { bad "info --near $at $design: $(cat "$tmp/near_info")"; return; }
  python3 - "$design" "$at" "$tmp" "$rg2" <<'PY' && ok || bad "info --near $at $design: $(cat "$tmp/near_info")"
import json, math, re, subprocess, sys
design, at, tmp, rg2 = sys.argv[1:5]
x = [float(t) for t in at.split(',')]
mesh = json.load(open(tmp + '/near_mesh.json'))
best = None
for o, m in enumerate(mesh['meshes']):
    for i in range(m['nu']):
        for j in range(m['nv']):
            d, w = m['d'][i][j], m['W'][i][j]
            e = sum((d[k] - x[k]) ** 2 for k in range(3))
            if w > 0 and (best is None or e < best[0]):
                best = (e, o, m['name'], i, j)
info = open(tmp + '/near_info').read()
g = re.search(r"nearest control point to \(.*\): surface (\d+), mesh '([^']*)' \[(\d+), (\d+)\], d = \(([^)]*)\), W = ([0-9.e+-]+), ([0-9.e+-]+) away", info)
assert g, info
o, name, i, j, dist = int(g[1]), g[2], int(g[3]), int(g[4]), float(g[7])
assert (o, name, i, j) == best[1:], (o, name, i, j, best)
# its d and W as rg2 mesh gives them (printed to 10 digits)
d, w = mesh['meshes'][o]['d'][i][j], mesh['meshes'][o]['W'][i][j]
pd = [float(t) for t in g[5].split(',')]
assert all(abs(pd[k] - d[k]) <= 1e-9 * max(1.0, abs(d[k])) for k in range(3)) and abs(float(g[6]) - w) <= 1e-9 * abs(w), (pd, g[6], d, w)
assert abs(dist - math.sqrt(best[0])) <= 1e-3 * max(dist, 1e-300), (dist, best)
pole = re.search(r'it is the (south|north) polar point', info)
if pole:
    assert j in (0, mesh['meshes'][o]['nv'] - 1)
    sys.exit(0)
ch = re.search(r'changes (\d+) patches: \(i, j\) with i in (\d+\.\.\d+|[0-9, ]+), j in (\d+\.\.\d+|[0-9, ]+)(.*)', info)
assert ch, info
def ids(t):
    t = t.strip()
    if '..' in t:
        a, b = t.split('..')
        return set(range(int(a), int(b) + 1))
    return {int(v) for v in t.split(',')}
want = {(a, b) for a in ids(ch[2]) for b in ids(ch[3])}

src = json.load(open(design))
src['meshes']['near_e'] = {'edit': name, 'points': [{'at': [i, j], 'move': [0.05, 0.02, -0.03]}]}
ends = re.search(r'"ends": "(\w+)"', info)
if ends:
    src['meshes']['near_c'] = {'cap': 'near_e', 'ends': ends[1]}
src['output'] = 'near_c' if ends else 'near_e'
json.dump(src, open(tmp + '/near_ed.json', 'w'))
subprocess.run([rg2, 'build', '-q', tmp + '/near_ed.json', '-o', tmp + '/near_b.json'], check=True)
A = json.load(open(tmp + '/near_a.json'))['surfaces'][o]
B = json.load(open(tmp + '/near_b.json'))['surfaces'][0]
assert (A['nu'], A['nv']) == (B['nu'], B['nv'])
got = {(k // A['nv'], k % A['nv']) for k in range(A['nu'] * A['nv']) if A['patches'][k] != B['patches'][k]}
for c in re.finditer(r"the (south|north) cap's \(j in (\d+)\.\.(\d+), every i\)", ch[4]):
    want |= {(a, b) for a in range(A['nu']) for b in range(int(c[2]), int(c[3]) + 1)}
assert len(want) == int(ch[1]), (ch[1], len(want))
assert got == want, (sorted(got - want), sorted(want - got))
PY
}
near_case "$src/examples/torus_sphere.json" 0.2,-2.2,0
near_case "$src/examples/pipe_elbow.json" 0.5,0,-3
near_case "$src/examples/pipe_elbow.json" 3.5,-2.6,0
grep -qF "that edit changes 32 patches: (i, j) with i in 5, 6, 7, 0, j in 3..4, and the south cap's (j in 0..2, every i)" "$tmp/near_info" && ok || bad "info --near by the south cap: $(tail -1 "$tmp/near_info")"
near_case "$src/examples/pipe_elbow.json" 3.3,-0.4,-0.2
# by the north cap: the cap's rows after the body's (j from 3 + 29 - 3, the south cap's 3 first)
near_case "$src/examples/pipe_elbow.json" -2.5,3.5,0
near_case "$src/examples/pipe_elbow.json" 3,3,0
near_case "$src/examples/fig9_polar_sphere.json" 0,0,5
grep -q "it is the north polar point (the whole collapsed row v 7)" "$tmp/near_info" && ok || bad "info --near at a pole: $(cat "$tmp/near_info")"
# and the surface point nearest to it: 0.1 outside the ring of torus_sphere (R 3, r 0.6 about z)
# at 75 degrees round, 100 round the tube, the nearest point is the torus's own there, 0.1 away
at=$(python3 -c 'import math; a, t = math.radians(75), math.radians(100); q = 3 + 0.7 * math.cos(t)
print("%.17g,%.17g,%.17g" % (q * math.cos(a), q * math.sin(a), 0.7 * math.sin(t)))')
"$rg2" info --near "$at" "$src/examples/torus_sphere.json" >"$tmp/near_info" 2>&1
python3 - "$at" "$tmp/near_info" <<'PY' && ok || bad "info --near $at: nearest surface point: $(tail -1 "$tmp/near_info")"
import math, re, sys
x = [float(t) for t in sys.argv[1].split(',')]
g = re.search(r"nearest surface point: surface 0 patch \((\d+),(\d+)\) .*point \(([^)]*)\), ([0-9.e+-]+) away, normal \([^)]*\), exact on 'ring'", open(sys.argv[2]).read())
p = [float(t) for t in g[3].split(',')]
on = abs(math.hypot(math.hypot(p[0], p[1]) - 3, p[2]) - 0.6)
assert on <= 1e-9 and abs(math.dist(p, x) - 0.1) <= 1e-9 and abs(float(g[4]) - 0.1) <= 1e-9, (on, math.dist(p, x), g[4])
PY
# info --ray: from 1 outside that torus point along its inward normal, the first hit is the
# point itself at t = 1 (0.5 along a direction of length 2), on a patch exact on the ring
ray=$(python3 -c 'import math; a, t = math.radians(75), math.radians(100); n = (math.cos(t) * math.cos(a), math.cos(t) * math.sin(a), math.sin(t))
q = 3 + 0.6 * math.cos(t); p = (q * math.cos(a), q * math.sin(a), 0.6 * math.sin(t))
print(",".join("%.17g" % v for v in [p[k] + n[k] for k in range(3)] + [-2 * n[k] for k in range(3)]))')
"$rg2" info --ray "$ray" "$src/examples/torus_sphere.json" >"$tmp/ray_info" 2>&1
python3 - "$ray" "$tmp/ray_info" <<'PY' && ok || bad "info --ray $ray: $(tail -2 "$tmp/ray_info")"
import math, re, sys
r = [float(t) for t in sys.argv[1].split(',')]
g = re.search(r"first hit: surface 0 patch \((\d+),(\d+)\) .*point \(([^)]*)\), t = ([0-9.e+-]+) \(([0-9.e+-]+) along the ray\), normal \(([^)]*)\), exact on 'ring'", open(sys.argv[2]).read())
p = [float(t) for t in g[3].split(',')]
n = [float(t) for t in g[6].split(',')]
on = abs(math.hypot(math.hypot(p[0], p[1]) - 3, p[2]) - 0.6)
want = [r[k] + 0.5 * r[3 + k] for k in range(3)]
assert on <= 1e-9 and math.dist(p, want) <= 1e-9 and abs(float(g[4]) - 0.5) <= 1e-9 and abs(float(g[5]) - 1) <= 1e-9, (on, p, want, g[4], g[5])
assert abs(abs(sum(n[k] * r[3 + k] for k in range(3))) / 2 - 1) <= 1e-5, n  # the normal along the ray there
PY
# both in one call (the surfaces' locators built once, kept for the second query): the same lines
"$rg2" info --near "$at" --ray "$ray" "$src/examples/torus_sphere.json" >"$tmp/both_info" 2>&1
{ grep "nearest surface point:" "$tmp/near_info"; grep -A1 "^ray from" "$tmp/ray_info"; } >"$tmp/both_want"
{ grep "nearest surface point:" "$tmp/both_info"; grep -A1 "^ray from" "$tmp/both_info"; } >"$tmp/both_got"
[ -s "$tmp/both_want" ] && cmp -s "$tmp/both_want" "$tmp/both_got" && ok ||
    bad "info --near --ray in one call: $(diff "$tmp/both_want" "$tmp/both_got" | head -4)"
"$rg2" info --ray 0,0,10,0,0,1 "$src/examples/torus_sphere.json" >"$tmp/ray_info" 2>&1
grep -q "^  meets no surface$" "$tmp/ray_info" && ok || bad "info --ray away from the design: $(tail -2 "$tmp/ray_info")"
expect 2 "rg2 info: --ray needs six numbers X,Y,Z,DX,DY,DZ" "$rg2" info "$src/examples/torus_sphere.json" --ray
expect 2 "six numbers X,Y,Z,DX,DY,DZ" "$rg2" info --ray 1,2,3,4,5 "$src/examples/torus_sphere.json"
expect 2 "rg2 info: --ray: the direction (DX, DY, DZ) is zero" "$rg2" info --ray 1,2,3,0,0,0 "$src/examples/torus_sphere.json"
expect 2 "--ray" "$rg2" info --ray 1,2,3,0,inf,0 "$src/examples/torus_sphere.json"
expect 2 "rg2 info: --near needs three numbers X,Y,Z" "$rg2" info --near 1,2 "$src/examples/torus_sphere.json"
expect 2 "rg2 info: --near needs three numbers X,Y,Z" "$rg2" info "$src/examples/torus_sphere.json" --near
expect 2 "--near" "$rg2" info --near 1,nan,2 "$src/examples/torus_sphere.json"
# closed along v only (the cylinder transposed: u open) is not a closed surface: no normal line
cat >"$tmp/transposed.json" <<'EOF'
{"shapes": {"c": {"kind": "cylinder"}}, "meshes": {
  "A": {"shape": "c", "u": {"arcs": 8}, "v": {"segments": 3, "from": -1, "to": 1}}, "T": {"transpose": "A"}},
 "output": ["T"]}
EOF
"$rg2" info "$tmp/transposed.json" >"$tmp/out" 2>&1
grep -q "(u open, v closed)" "$tmp/out" && ! grep -q "closed: the normal" "$tmp/out" && ok ||
  bad "info transposed.json (u open): $(cat "$tmp/out")"
# and the volume: the torus R = 0.03, r = 0.01 of 8 x 6 arcs is tessellated at density 4 with
# vertices on it, 32 steps around and 24 round the tube (the arcs' parametrisation is near
# uniform in angle): the polyhedron of equal steps encloses 2 pi^2 R r^2 sinc(2 pi / 32) sinc(2 pi
# / 24) = 5.8168e-05 (each step's quads are planar; Pappus over the polygon)
cat >"$tmp/small_torus.json" <<'EOF'
{"shapes": {"t": {"kind": "torus", "R": 0.03, "r": 0.01}},
 "meshes": {"a": {"shape": "t", "u": {"arcs": 8}, "v": {"arcs": 6}}}, "output": ["a"]}
EOF
vol=$("$rg2" info "$tmp/small_torus.json" | sed -n 's/^  closed: the normal points out (enclosed volume about \([-0-9.e+]*\))$/\1/p')
awk -v v="$vol" 'BEGIN { pi = 3.141592653589793; s = sin(2 * pi / 32) / (2 * pi / 32) * sin(2 * pi / 24) / (2 * pi / 24)
  e = 2 * pi * pi * 0.03 * 0.01 * 0.01 * s; exit !(v != "" && (v - e) / e < 1e-3 && (e - v) / e < 1e-3) }' && ok ||
  bad "info small_torus.json: enclosed volume '$vol', the polyhedron of equal steps 5.8168e-05"
# the progress line is for a terminal (a pty from script(1)): it names the design and the first
# output, "and the other outputs" when there are more; -q keeps the terminal silent
if command -v script >/dev/null; then
  ts=$src/examples/torus_sphere.json
  pty() { script -qec "$(printf '%q ' "$@")" /dev/null </dev/null | tr -d '\r'; }
  out=$(pty "$rg2" build "$ts" -o "$tmp/p1.obj")
  [[ "$out" == *"rg2 build: reading and building $ts"*"rg2 build: writing $tmp/p1.obj"* ]] &&
    [[ "$out" != *"other outputs"* ]] && ok || bad "build on a terminal, one output: $out"
  out=$(pty "$rg2" build "$ts" -o "$tmp/p2.obj" -o "$tmp/p2.stl")
  [[ "$out" == *"rg2 build: writing $tmp/p2.obj and the other outputs"* ]] && ok || bad "build on a terminal, two outputs: $out"
  out=$(pty "$rg2" build -q "$ts" -o "$tmp/p3.obj")
  [ -z "$out" ] && [ -s "$tmp/p3.obj" ] && ok || bad "build -q on a terminal printed: $out"
fi
# a write error is the file's, not a surface's: no "(surface k is mesh ...)" is appended (that
# suffix is for a message naming a surface; /proc takes no new files, even for root)
if [ -d /proc/self ]; then
  expect 1 "/proc/x.step: cannot write" "$rg2" build -q "$src/examples/torus_sphere.json" -o /proc/x.step
  grep -q "is mesh" "$tmp/err" && bad "a write error names a mesh: $(cat "$tmp/err")" || ok
fi
# --surface K: output K alone, its patches those of the whole build's surface K (the .json
# export, compared as data); out of range, a usage error before anything is written
f1=$src/examples/fig1_torus.json
expect 0 "" "$rg2" build -q "$f1" -o "$tmp/f1all.json"
for k in 0 2 3; do
  expect 0 "" "$rg2" build -q "$f1" --surface $k -o "$tmp/f1s$k.json" -o "$tmp/f1s$k.step"
  python3 - "$tmp/f1all.json" "$tmp/f1s$k.json" "$tmp/f1s$k.step" $k <<'PY' && ok || bad "build --surface $k: not the whole build's surface $k"
import json, sys
whole, one = (json.load(open(p))["surfaces"] for p in sys.argv[1:3])
k = int(sys.argv[4])
assert len(whole) == 4 and len(one) == 1 and one[0] == whole[k]
assert whole[0] != whole[2] and whole[0] != whole[3] and whole[2] != whole[3]  # (so K is told apart)
step = open(sys.argv[3]).read()
assert step.count("B_SPLINE_SURFACE_WITH_KNOTS") == one[0]["nu"] * one[0]["nv"], step.count("B_SPLINE_SURFACE_WITH_KNOTS")
PY
done
expect 2 "rg2 build: --surface 4: the design has 4 surfaces (0..3)" "$rg2" build -q "$f1" --surface 4 -o "$tmp/f1s4.step"
expect 2 "rg2 build: --surface needs a surface index (an integer >= 0), not 'x'" "$rg2" build -q "$f1" --surface x -o "$tmp/f1sx.step"
[ ! -e "$tmp/f1s4.step" ] && [ ! -e "$tmp/f1sx.step" ] && ok || bad "build --surface out of range wrote a file"
"$rg2" build --help | grep -q -- "--surface K" && ok || bad "build --help lacks --surface"
echo "cli design: $passes passed, $fails failed"
[ "$fails" = 0 ]
