#!/usr/bin/env bash
# make check-memory: the rg2 command under valgrind memcheck on every example design and on
# every row of the bad-input table (tests/bad/table.tsv). Any memory error or leak (of any
# kind) fails the run. Needs a non-sanitized build (valgrind and ASan do not mix).
# Usage: scripts/check_memory.sh <path-to-rg2> <source-dir>
set -u
rg2=$1 src=$2
command -v valgrind >/dev/null || { echo "check-memory: valgrind is not installed (scripts/deps.sh test)" >&2; exit 1; }
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
vg="valgrind -q --leak-check=full --show-leak-kinds=all --errors-for-leak-kinds=all --error-exitcode=99
    --suppressions=$src/tests/valgrind/rg2.supp --log-file=$tmp/vg.%p.log"
runs=0 fails=0
# run EXPECTED-EXIT command...: valgrind must report nothing, the command must exit as expected
run() {
  local want=$1; shift
  rm -f "$tmp"/vg.*.log
  OMP_NUM_THREADS=2 $vg "$@" >"$tmp/out" 2>&1
  local rc=$?
  runs=$((runs + 1))
  if [ "$rc" = 99 ] || [ -s "$(ls "$tmp"/vg.*.log 2>/dev/null | head -1)" ]; then
    fails=$((fails + 1)); echo "MEMCHECK FAIL: $*" >&2; cat "$tmp"/vg.*.log >&2
  elif [ "$rc" != "$want" ]; then
    fails=$((fails + 1)); echo "EXIT $rc (expected $want): $*" >&2; head -5 "$tmp/out" >&2
  fi
}
has() { "$rg2" --help | grep -q "^  $1 "; }
# every example through build (all writers), check and render; info, mesh, the face-per-mesh
# layout and the IGES B-rep form once (each valgrind start costs about a second)
for f in "$src"/examples/*.json; do
  b=$(basename "$f" .json)
  run 0 "$rg2" build -q "$f" -o "$tmp/$b.step" -o "$tmp/$b.igs" -o "$tmp/$b.bv" -o "$tmp/$b.stl" \
    -o "$tmp/$b.glb" -o "$tmp/$b.json" --density 3
  if has check; then run 0 "$rg2" check "$f" --samples 4; fi
  if has render; then run 0 "$rg2" render "$f" -o "$tmp/$b.png" --size 64x48 --mode mean --boundaries; fi
  rm -f "$tmp/$b".*
done
ex="$src/examples/torus_sphere.json"
run 0 "$rg2" info --map "$ex"
run 0 "$rg2" mesh "$ex" -o "$tmp/mesh.json"
run 0 "$rg2" build -q "$ex" --face-per-mesh --ap242 -o "$tmp/m.step" -o "$tmp/m.igs" -o "$tmp/m.obj" -o "$tmp/m.ply" -o "$tmp/m.bez"
run 0 "$rg2" build -q "$src/examples/fig9_polar_sphere.json" --iges-brep -o "$tmp/b.igs"
if has render; then run 0 "$rg2" render "$src/examples/fig1_torus.json" -o "$tmp/apart.png" --size 64x48 --apart --mesh; fi
run 0 "$rg2" build -q "$src/examples/fig9_polar_sphere.json" --iges-brep --face-per-mesh -o "$tmp/bm.igs"
run 0 "$rg2" demo
run 0 "$rg2" shapes
# the error paths: every row of the bad-input table (tests/bad/table.tsv, see its header), its
# inputs read from a scratch copy (as tests/cli/bad_table.sh), never from the source tree
mkdir -p "$tmp/in/tests/bad" && cp -R "$src/tests/bad/." "$tmp/in/tests/bad/"
while IFS=$'\t' read -r file code msg args; do
  case "$file" in ''|'#'*) continue ;; esac
  in="$tmp/in/tests/bad/$file"
  mkdir -p "$tmp/bad"
  words=()
  for w in $args; do
    w=${w//\{in\}/$in}
    words+=("${w//\{tmp\}/$tmp/bad}")
  done
  run "$code" "$rg2" "${words[@]}"
  rm -rf "$tmp/bad"
done <"$src/tests/bad/table.tsv"
echo "valgrind memcheck: $runs runs of rg2"
echo "check-memory: $((runs - fails)) passed, $fails failed"
[ "$fails" = 0 ]
