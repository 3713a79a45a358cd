# Shared helpers for the CLI tests (sourced): expect exit codes, message substrings, no files.
RG2=${1:?path to rg2}
SRC=${2:?source dir}
pass=0 fail=0
ok() { pass=$((pass + 1)); }
bad() { fail=$((fail + 1)); echo "FAIL: $*" >&2; }
# expect CODE SUBSTRING -- command...   (checks exit code and that stdout+stderr contain SUBSTRING)
expect() {
  local code=$1 sub=$2; shift 3
  local out rc
  out=$("$@" 2>&1); rc=$?
  if [ "$rc" != "$code" ]; then bad "$* -> exit $rc, expected $code: $out"; return; fi
  case "$out" in *"$sub"*) ok ;; *) bad "$* -> output lacks '$sub': $out" ;; esac
}
# png_is FILE W H: the PNG signature and IHDR: width, height, bit depth 8, colour type 2 (RGB)
png_is() {
  local f=$1 w=$2 h=$3
  [ -f "$f" ] || { bad "$f missing"; return; }
  local hdr
  hdr=$(od -An -tx1 -N26 "$f" | tr -d ' \n')
  local want
  want=$(printf '89504e470d0a1a0a0000000d49484452%08x%08x0802' "$w" "$h")
  [ "$hdr" = "$want" ] && ok || bad "$f header $hdr, expected $want"
}

# doc_report NAME WHAT MIN OUT: the docs checks' python prints a failure per line and last
# 'count N', the number of WHAT it compared; fewer than MIN means it found too little to check.
doc_report() {
  local name=$1 what=$2 min=$3 out=$4 n e
  n=$(sed -n 's/^count //p' <<<"$out")
  while IFS= read -r e; do [ -n "$e" ] && bad "$e"; done < <(grep -v '^count ' <<<"$out")
  echo "$name: ${n:-0} $what compared"
  [ "${n:-0}" -ge "$min" ] && ok || bad "only '${n:-0}' $what found"
}

finish() { echo "$(basename "$0" .sh): $pass passed, $fail failed"; [ "$fail" = 0 ]; }
