#!/usr/bin/env bash
# Install the Debian packages a make target needs, only those missing (idempotent).
# Usage: scripts/deps.sh base|test|bench|fuzz|freecad
set -eu
base="cmake make gcc g++ pkg-config libcjson-dev libpng-dev"
test="$base clang libomp-dev libclang-rt-14-dev valgrind gmsh locales libocct-data-exchange-dev libocct-modeling-algorithms-dev libocct-modeling-data-dev libocct-foundation-dev libtbb-dev"
bench="$test libsisl-dev"
fuzz="$base clang libclang-rt-14-dev"
freecad="$base freecad-python3"
case "${1:-base}" in
  base) want=$base ;;
  test) want=$test ;;
  bench) want=$bench ;;
  fuzz) want=$fuzz ;;
  freecad) want=$freecad ;;
  *) echo "deps.sh: unknown set '$1'" >&2; exit 2 ;;
esac
missing=""
for p in $want; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing="$missing $p"
done
[ -z "$missing" ] && exit 0
echo "installing Debian packages:$missing"
SUDO=""
if [ "$(id -u)" != 0 ]; then
  if command -v sudo >/dev/null; then SUDO=sudo; else echo "need root to install:$missing" >&2; exit 1; fi
fi
export DEBIAN_FRONTEND=noninteractive
$SUDO apt-get update -qq || true
$SUDO apt-get install -y -qq --no-install-recommends $missing >/dev/null
