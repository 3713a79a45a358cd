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
for sig in TERM HUP; do
  out=$tmp/big_$sig.step
  "$rg2" build "$tmp/big.json" -o "$out" >/dev/null 2>&1 &
  pid=$!
  seen=0
  for _ in $(seq 600); do
    if [ -e "$out.$pid.tmp" ]; then seen=1; break; fi
    kill -0 "$pid" 2>/dev/null || break
    sleep 0.1
  done
  if [ "$seen" = 1 ]; then
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
echo "interrupt: $passes passed, $fails failed"
[ "$fails" = 0 ]
