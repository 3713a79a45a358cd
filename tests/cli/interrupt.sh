#!/usr/bin/env bash
# An interrupted rg2 leaves nothing half-written: outputs go to "<path>.<pid>.tmp" and are renamed
# when complete; SIGTERM / SIGHUP while a large STEP file is being written must remove that file.
# (SIGINT is handled the same way, but a background job of a script ignores it, and rg2 keeps an
# ignored signal ignored, as nohup expects.)
# Usage: bash interrupt.sh <path-to-rg2> <source-dir>
set -u
rg2=$1
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
fails=0 passes=0
echo '{"shapes": {"t": {"kind": "torus"}}, "meshes": {"m": {"shape": "t", "u": {"arcs": 600}, "v": {"arcs": 400}}}}' >"$tmp/big.json"
# appears FILE PID: 0 once FILE exists, 1 if process PID ends first (or after a minute)
appears() {
  for _ in $(seq 600); do
    [ -e "$1" ] && return 0
    kill -0 "$2" 2>/dev/null || return 1
    sleep 0.1
  done
  return 1
}
for sig in TERM HUP; do
  out=$tmp/big_$sig.step
  "$rg2" build "$tmp/big.json" -o "$out" >/dev/null 2>&1 &
  pid=$!
  if appears "$out.$pid.tmp" "$pid"; then
    kill -"$sig" "$pid"
    wait "$pid"
    rc=$?
    if compgen -G "$out*" >/dev/null; then
      echo "FAIL: SIG$sig during the write left $(ls "$tmp" | tr '\n' ' ')" >&2; fails=$((fails + 1))
    elif [ "$rc" -lt 128 ]; then
      echo "FAIL: SIG$sig: exit $rc, expected death by the signal" >&2; fails=$((fails + 1))
    else
      passes=$((passes + 1))
    fi
  else
    wait "$pid"
    echo "FAIL: SIG$sig: the 240,000-patch STEP write never showed its .tmp file (finished too fast?)" >&2
    fails=$((fails + 1))
  fi
done
# a file already at the first temporary name (left by a killed run of the same pid, as in
# containers that reuse pids): the run writes "<path>.<pid>.1.tmp", and its cleanup removes that
# one, not the file it did not make (exec keeps the shell's pid)
out=$tmp/stale.step
bash -c 'echo stale >"$1.$$.tmp"; exec "$2" build "$3" -o "$1"' _ "$out" "$rg2" "$tmp/big.json" >/dev/null 2>&1 &
pid=$!
if appears "$out.$pid.1.tmp" "$pid"; then
  kill -TERM "$pid"
  wait "$pid"
  if [ "$(cat "$out.$pid.tmp" 2>/dev/null)" != stale ] || [ -e "$out.$pid.1.tmp" ] || [ -e "$out" ]; then
    echo "FAIL: SIGTERM with a stale temporary file: left $(ls "$tmp" | tr '\n' ' ')" >&2; fails=$((fails + 1))
  else
    passes=$((passes + 1))
  fi
else
  wait "$pid"
  echo "FAIL: the write with a stale temporary file never showed $out.$pid.1.tmp" >&2; fails=$((fails + 1))
fi
echo "interrupt: $passes passed, $fails failed"
[ "$fails" = 0 ]
