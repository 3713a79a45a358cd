#!/usr/bin/env bash
# The bad-input table (tests/bad/table.tsv): every row is one user mistake. Each must give the
# expected non-zero exit code, a message containing the expected text, no output file (the
# temporary directory stays empty, no .tmp is left), and an unchanged input file. The inputs are
# read from a scratch copy of tests/bad (at .../tests/bad, as some messages name it), so an rg2
# that writes over its input (a mutant once did) cannot change the source tree for later runs.
# Usage: bash bad_table.sh <path-to-rg2> <source-dir>
set -u
. "$(dirname "$0")/lib.sh"
table="$SRC/tests/bad/table.tsv"
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
mkdir -p "$work/tests/bad" && cp -R "$SRC/tests/bad/." "$work/tests/bad/" || { bad "cannot copy $SRC/tests/bad"; finish; exit 1; }
rows=0
while IFS=$'\t' read -r file code msg args; do
  case "$file" in ''|'#'*) continue ;; esac
  rows=$((rows + 1))
  in="$work/tests/bad/$file"
  tmp=$(mktemp -d)
  sum_before=$( [ -f "$in" ] && md5sum <"$in" )
  words=()
  for w in $args; do
    w=${w//\{in\}/$in}
    words+=("${w//\{tmp\}/$tmp}")
  done
  out=$("$RG2" "${words[@]}" 2>&1 </dev/null)
  rc=$?
  want=${msg//\{in\}/$in}
  what="row $rows ($file: rg2 $args)"
  if [ "$rc" != "$code" ]; then
    bad "$what: exit $rc, expected $code: $out"
  elif [[ "$out" != *"$want"* ]]; then
    bad "$what: message lacks '$want': $out"
  elif [[ "$out" != "rg2 "* ]]; then
    bad "$what: message does not start with the command name: $out"
  elif [ -n "$(ls -A "$tmp")" ]; then
    bad "$what: left files behind: $(ls -A "$tmp")"
  elif [ -f "$in" ] && { [ "$(md5sum <"$in")" != "$sum_before" ] || ! cmp -s "$in" "$SRC/tests/bad/$file"; }; then
    bad "$what: changed the input file"
    cp "$SRC/tests/bad/$file" "$in"
  elif compgen -G "$in.*tmp" >/dev/null || [ -e /nonexistent-rg2-dir ]; then
    bad "$what: left a temporary file"
  else
    ok
  fi
  rm -rf "$tmp"
done <"$table"
[ "$rows" -ge 30 ] && ok || bad "only $rows rows in $table (need at least 30)"
# README's "How this is checked" counts the rows
grep -q "($rows user mistakes:" "$SRC/README.md" && ok || bad "README.md does not say '($rows user mistakes:' (the rows of $table)"
finish
