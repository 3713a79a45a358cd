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
finish() { echo "$(basename "$0" .sh): $pass passed, $fail failed"; [ "$fail" = 0 ]; }
