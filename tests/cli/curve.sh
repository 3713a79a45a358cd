# CLI: rg2 --version/--help and rg2 curve, including bad input.
. "$(dirname "$0")/lib.sh"
expect 0 "rg2 0." -- "$RG2" --version
expect 0 "commands:" -- "$RG2" --help
expect 2 "unknown command" -- "$RG2" frobnicate
expect 2 "unknown command 'bild' (did you mean 'build'?)" -- "$RG2" bild
expect 2 "unknown command 'chek' (did you mean 'check'?)" -- "$RG2" chek
expect 0 "usage: rg2 curve" -- "$RG2" curve --help
expect 0 "4 rational cubic Bezier segments" -- "$RG2" curve --arcs 4
expect 0 '"segments"' -- "$RG2" curve --arcs 5 --radius 2 --json
expect 0 "3 rational cubic Bezier segments" -- "$RG2" curve --angles 100,120,140
expect 1 "arc 1 has opening angle" -- "$RG2" curve --angles 100,180,80
expect 1 "sum to 2 pi" -- "$RG2" curve --angles 100,100,100
expect 2 "not a finite number" -- "$RG2" curve --angles 100,abc,80
expect 0 "2 rational cubic Bezier segments" -- "$RG2" curve --points "0,0;1,0;2,1;3,0;4,2"
expect 1 "w[1] = -1" -- "$RG2" curve --points "0,0;1,0;2,1;3,0;4,2" --w 1,1,-1,1,1,1
expect 1 "junction 2 has K" -- "$RG2" curve --points "0,0;1,0;2,1;3,0;4,2" --g 0,0,-9,0,0
expect 2 "need 6 weights" -- "$RG2" curve --points "0,0;1,0;2,1;3,0;4,2" --w 1,1
expect 2 "unknown option" -- "$RG2" curve --bogus
# the numbers of a design file's range, as rg2 shape checks them (--radius 0 printed all-zero
# segments, -1 and 1e-300 were taken, 1e308 read "control point 0 coordinate 0 is not finite")
expect 2 "rg2 curve: --radius 0: the radius must be > 0" -- "$RG2" curve --arcs 3 --radius 0
expect 2 "rg2 curve: --radius -1: the radius must be > 0" -- "$RG2" curve --radius -1
expect 2 "--radius: number 1e-300 is outside the supported range (0 or a magnitude from 1e-100 to 1e+100)" -- "$RG2" curve --radius 1e-300
expect 2 "--radius: number 1e+308 is outside the supported range" -- "$RG2" curve --arcs 3 --radius 1e308
expect 0 "3 rational cubic Bezier segments" -- "$RG2" curve --arcs 3 --radius 1e100
expect 2 "--start: number 1e+200 is outside the supported range" -- "$RG2" curve --start 1e200
expect 2 "--angles item 2: number 1e-200 is outside the supported range" -- "$RG2" curve --angles 100,120,1e-200
expect 2 "--points item 7: number 1e-200 is outside the supported range" -- "$RG2" curve --points "0,0;1,0;2,1;3,1e-200;4,2"
expect 2 "--w item 2: number 1e+300 is outside the supported range" -- "$RG2" curve --points "0,0;1,0;2,1;3,0;4,2" --w 1,1,1e300,1,1,1
expect 2 "--b item 0: number 1e-101 is outside" -- "$RG2" curve --points "0,0;1,0;1,1;0,1" --closed --b 1e-101,1,1,1
expect 2 "--g item 3: number -1e+150 is outside" -- "$RG2" curve --points "0,0;1,0;1,1;0,1" --closed --g 0,0,0,-1e150
# the JSON output is exact: the 90-degree circle's middle weight (1 + 2 cos 45)/3
"$RG2" curve --arcs 4 --json | grep -q '0.80473785412436' && ok || bad "exact circle weight"
expect 2 "usage: rg2" -- "$RG2"
expect 0 "usage: rg2 demo" -- "$RG2" demo --help
# the help and the output name the same sample count
expect 0 "over 33 x 33 samples per patch" -- "$RG2" demo --help
expect 0 "over 33 x 33 samples per patch" -- "$RG2" demo
# up to 100000 arcs, the design file's limit
expect 0 "5000 rational cubic Bezier segments" -- "$RG2" curve --arcs 5000
expect 2 "need 3..100000 arcs" -- "$RG2" curve --arcs 100001
[ "$("$RG2" curve --arcs 100000 | head -1)" = "100000 rational cubic Bezier segments (dim 2, closed)" ] && ok ||
  bad "curve --arcs 100000 (the limit itself) refused"
# an empty --points is a list of 0 points: refused with a message, as an empty --w is
expect 1 "rg2 curve: invalid argument: scalars: 0 control points, an open direction needs at least 4" -- "$RG2" curve --points ''
# too few arcs: the message counts arcs, not the library's control points
expect 1 "rg2 curve: 2 arcs given; a closed circle (the default without --open) needs at least 3 arcs" -- "$RG2" curve --angles 100,120
expect 1 "rg2 curve: --open: 4 arcs given; an open curve needs at least 5 arcs" -- "$RG2" curve --arcs 4 --open
expect 0 "1 rational cubic Bezier segments" -- "$RG2" curve --arcs 5 --open
# no partition given: the unit circle in 4 arcs of 90 degrees
[ "$("$RG2" curve --json)" = "$("$RG2" curve --arcs 4 --json)" ] && [ -n "$("$RG2" curve --json)" ] && ok ||
  bad "rg2 curve without arcs is not the circle in 4 arcs"
# nums JSON FIRST COUNT: COUNT numbers of the JSON text from the FIRST (1-based), in order
nums() { echo "$1" | grep -o -- '-\?[0-9][0-9.eE+-]*' | sed -n "$2,$(($2 + $3 - 1))p" | tr '\n' ' '; }
# close "GOT" "WANT": as many numbers, each within 1e-14 relative (and absolute below 1)
close() {
  awk -v g="$1" -v w="$2" 'BEGIN { n = split(g, a, " "); m = split(w, b, " "); if (n != m) exit 1
    for (k = 1; k <= n; k++) { d = a[k] - b[k]; if (d < 0) d = -d; s = b[k] < 0 ? -b[k] : b[k]
      if (d > 1e-14 * (s > 1 ? s : 1)) exit 1 } }'
}
# --open: 5 arcs of 30 degrees for 4 points, one produced arc, [30, 60] degrees, of radius 2:
# end points 2 (cos 30, sin 30) and 2 (cos 60, sin 60), middle weight (1 + 2 cos 15)/3
j=$("$RG2" curve --angles 30,30,30,30,30 --open --radius 2 --json)
[ "$(echo "$j" | grep -c '"w"')" = 1 ] && echo "$j" | grep -q '"closed": false' && ok || bad "--open: one open segment: $j"
close "$(nums "$j" 2 4)" "1 0.97728388419271217 0.97728388419271217 1" && ok || bad "--open: 30-degree weights: $j"
close "$(nums "$j" 6 2)" "1.7320508075688772 1" && ok || bad "--open: the arc starts at 30 degrees: $j"
close "$(nums "$j" 12 2)" "1 1.7320508075688772" && ok || bad "--open: the arc ends at 60 degrees: $j"
# --start 45 --radius 3: junction 0 at 45 degrees on the circle of radius 3, junction 1 at 135
j=$("$RG2" curve --arcs 4 --start 45 --radius 3 --json)
close "$(nums "$j" 6 2) $(nums "$j" 12 2)" "2.1213203435596424 2.1213203435596424 -2.1213203435596424 2.1213203435596424" &&
  ok || bad "--start 45: first arc: $j"
# --dim 1: the uniform cubic B-spline of 0, 1, 3, 4, 7: segment 1 is (P0 + 4 P1 + P2) / 6 .. with
# Bezier points (2 P1 + P2) / 3, (P1 + 2 P2) / 3
j=$("$RG2" curve --points "0;1;3;4;7" --dim 1 --json)
echo "$j" | tr -d ' \n' | grep -q '"points":\[\[1.1666666666666667\],\[1.6666666666666667\],\[2.3333333333333335\],\[2.83333333333333[0-9]*\]\]' &&
  [ "$(echo "$j" | grep -c '"w"')" = 2 ] && ok || bad "--dim 1 B-spline: $j"
# --closed: 4 points, 4 segments; --b changes the curve (b = 1 everywhere is the uniform B-spline)
j=$("$RG2" curve --points "0,0;1,0;1,1;0,1" --closed --json)
[ "$(echo "$j" | grep -c '"w"')" = 4 ] && echo "$j" | grep -q '"closed": true' &&
  echo "$j" | tr -d ' \n' | grep -q '"points":\[\[0.16666666666666666,0.16666666666666666\],\[0.33333333333333331,0\]' &&
  ok || bad "--closed uniform B-spline: $j"
jb=$("$RG2" curve --points "0,0;1,0;1,1;0,1" --closed --b 1,2,1,1 --json)
[ "$j" != "$jb" ] && ok || bad "--b 1,2,1,1 changes nothing"
jg=$("$RG2" curve --points "0,0;1,0;1,1;0,1" --closed --b 1,1,1,1 --g 0,0,0,0 --w 1,1,1,1 --json)
[ "$j" = "$jg" ] && ok || bad "the default scalars given explicitly give another curve"
# --dim is an integer 1..4: 0, 5 and a trailing letter are refused (not read as 2 or clamped)
for d in 0 5 2x; do expect 2 "rg2 curve: --dim $d: need an integer 1..4" -- "$RG2" curve --dim "$d" --points 0,0; done
# an empty --w is a count of 0 weights, not "the defaults": 4 open points need 5
expect 2 "4 open points need 5 weights (--w)" -- "$RG2" curve --points "0,0;1,0;2,1;3,0" --w ''
# any radius > 0 in range is taken, small ones too: junction 0 of the default circle at (R, 0)
for r in 0.001 1e-99; do
  close "$(nums "$("$RG2" curve --arcs 3 --radius "$r" --json)" 6 1)" "$r" && ok || bad "--radius $r: b0 is not at x = $r"
done
# circle_segments ANGLES START R TOL: the segments on stdin (rg2 curve --json, or rg2 demo's
# text) are the circle's, from cos and sin computed here: b0 and b3 on the circle of radius R at
# the arc's ends, b1 and b2 on the tangents there (to TOL and 10 TOL), the middle weights
# (1 + 2 cos(a / 2)) / 3 (to 1e-15); with demo's control points p_k, b1 and b2 of segment k on
# the leg (p_k, p_k+1) (docs/MATH.md section 1)
circle_segments() {
  python3 -c 'import json, math, re, sys
a = [float(x) for x in sys.argv[1].split(",")]; t, R, tol = map(float, sys.argv[2:5])
text = sys.stdin.read(); num = r"(-?[0-9.e+-]+)"
if text.startswith("{"):
    segs, p = json.loads(text)["segments"], None
else:
    segs = [{"w": [1, float(g[1]), float(g[2]), 1], "points": [[float(v) for v in q] for q in re.findall(r"\(%s, %s\)" % (num, num), g[3])]}
            for g in re.finditer(r"segment \d+ \(weights 1, %s, %s, 1\):(.*)" % (num, num), text)]
    p = [[float(g[1]), float(g[2])] for g in re.finditer(r"p\d+ = \(%s, %s\)" % (num, num), text)]
    assert len(p) == len(a), p
assert len(segs) == len(a), segs
for k, s in enumerate(segs):
    q = s["points"]; e = [math.radians(t), math.radians(t + a[k])]; t += a[k]
    assert len(q) == 4, (k, q)
    for b, u in ((q[0], e[0]), (q[3], e[1])):
        assert math.hypot(b[0] - R * math.cos(u), b[1] - R * math.sin(u)) < tol, (k, b)
    for b, r in ((q[1], q[0]), (q[2], q[3])):
        assert abs((b[0] - r[0]) * r[0] + (b[1] - r[1]) * r[1]) < 10 * tol and math.hypot(b[0] - r[0], b[1] - r[1]) > 0.1, (k, b)
    c = math.cos(math.radians(a[k]) / 2)
    assert abs(s["w"][1] - (1 + 2 * c) / 3) < 1e-15 and s["w"][1] == s["w"][2], (k, s["w"])
    if p:
        l0, l1 = p[k], p[(k + 1) % len(p)]; leg = [l1[0] - l0[0], l1[1] - l0[1]]
        for b in q[1:3]:
            assert abs(leg[0] * (b[1] - l0[1]) - leg[1] * (b[0] - l0[0])) < 10 * tol * math.hypot(*leg), (k, b, l0, l1)' "$@"
}
if command -v python3 >/dev/null; then
  # the text form prints the segments --json prints: the same weights and points (both %.17g)
  for args in "--arcs 5 --radius 2 --start 10" "--points 0,0,0;1,0,1;2,1,0;3,0,2;4,2,1;5,1,1 --dim 3" "--points 0;1;3;4;7 --dim 1"; do
    # shellcheck disable=SC2086
    t=$("$RG2" curve $args) && j=$("$RG2" curve $args --json) &&
      python3 -c 'import json, re, sys
t, j = sys.argv[1] + "\n", json.loads(sys.argv[2])
segs = re.findall(r"segment (\d+)  weights 1 (\S+) (\S+) 1\n((?:  b\d.*\n){4})", t)
assert len(segs) == len(j["segments"]) > 0 and t.startswith("%d rational" % len(segs)), t
for (k, w1, w2, pts), s in zip(segs, j["segments"]):
    assert [1, float(w1), float(w2), 1] == s["w"], (k, w1, w2, s["w"])
    rows = [[float(x) for x in line.split()[1:]] for line in pts.strip("\n").split("\n")]
    assert rows == s["points"], (k, rows, s["points"])' "$t" "$j" &&
      ok || bad "curve $args: the text form differs from --json"
  done
  "$RG2" curve --angles 50,70,100,140 --start 10 --radius 2 --json | circle_segments 50,70,100,140 10 2 1e-14 &&
    ok || bad "curve --json: control points off the circle and its tangents"
  # demo: the unit circle in 4 arcs of 90 degrees (points printed to 6 decimals), then the torus
  # of R 3, r 1 as 8 x 6 patches within 1e-12 of it
  d=$("$RG2" demo) && circle_segments 90,90,90,90 0 1 1e-6 <<<"$d" && grep -q '^  8 x 6 rational bi-cubic patches' <<<"$d" &&
    awk '/largest distance from the torus/ { n++; far += !($NF < 1e-12) } END { exit n != 1 || far }' <<<"$d" &&
    ok || bad "demo: $d"
fi
# --name=value is split for every command; a flag given a value is refused wherever it stands in
# the command's list of flags (first, middle, last), and a valued option keeps its value
for f in --json --open --help; do expect 2 "rg2 curve: $f takes no value ('$f=1')" -- "$RG2" curve "$f=1"; done
[ "$("$RG2" curve --arcs=5 --radius=2)" = "$("$RG2" curve --arcs 5 --radius 2)" ] && ok || bad "curve --arcs=5 --radius=2 differs from the spaced form"
finish
