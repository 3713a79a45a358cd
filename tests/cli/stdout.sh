#!/usr/bin/env bash
# A report that cannot be written is a failure: every command that prints to stdout exits 1
# with a message when stdout is full (/dev/full), never 0 with the report lost.
# Usage: bash stdout.sh <path-to-rg2> <source-dir>
set -u
. "$(dirname "$0")/lib.sh"
[ -w /dev/full ] || { echo "stdout: no /dev/full, skipped"; exit 0; }
ex=$SRC/examples/fig1_torus.json
for args in "info $ex" "info --map $ex" "check $ex" "check --json $ex" "shapes" "shapes --json" "shape torus" \
            "shape torus --json" "curve --arcs 4" "demo" "--help" "--version" "build --help"; do
  out=$("$RG2" $args 2>&1 >/dev/full); rc=$?
  [ "$rc" = 1 ] && [[ "$out" == *"cannot write the standard output: No space left on device"* ]] && ok ||
    bad "rg2 $args >/dev/full: exit $rc: $out"
done
# a failed promise keeps its exit code (3) and still reports the lost output
out=$("$RG2" check "$ex" --tol g2=0 --require g2 2>&1 >/dev/full); rc=$?
[ "$rc" = 3 ] && [[ "$out" == *"cannot write the standard output"* ]] && ok || bad "check --require >/dev/full: exit $rc: $out"
# and the same commands to a working stdout exit 0
"$RG2" info "$ex" >/dev/null && "$RG2" --version >/dev/null && ok || bad "info / --version to /dev/null failed"
finish
