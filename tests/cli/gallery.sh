#!/usr/bin/env bash
# The gallery (docs/gallery.md, made by scripts/gallery.py): the script renders every example
# design into valid PNGs of the gallery's size and writes one section per design; the committed
# page has a section for every design in examples/ and every picture it shows is committed.
# Usage: bash gallery.sh <path-to-rg2> <source-dir>
set -u
. "$(dirname "$0")/lib.sh"
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
cd "$SRC" || exit 1

if ! python3 scripts/gallery.py "$RG2" "$tmp" >"$tmp/log" 2>&1; then
  bad "gallery.py failed: $(cat "$tmp/log")"
fi
designs=$(ls examples/*.json | sed 's,examples/,,; s,\.json$,,' | sort)
sections() { grep '^## ' "$1" | sed 's/^## //' | sort; }
pictures() { grep -o '(pictures/gallery/[^)]*\.png)' "$1" | tr -d '()' | sort; }
for page in "$tmp/gallery.md" docs/gallery.md; do
  [ -f "$page" ] || { bad "$page missing"; continue; }
  [ "$(sections "$page")" = "$designs" ] && ok || bad "$page sections differ from examples/: $(diff <(sections "$page") <(echo "$designs") | tr '\n' ' ')"
done
[ "$(pictures "$tmp/gallery.md")" = "$(pictures docs/gallery.md)" ] && ok || bad "docs/gallery.md shows other pictures than scripts/gallery.py makes: run make gallery"
n=0
for pic in $(pictures "$tmp/gallery.md"); do
  n=$((n + 1))
  [ -f "docs/$pic" ] || bad "docs/$pic (shown in docs/gallery.md) is not committed"
  png_is "$tmp/$pic" 400 300
done
[ "$n" -ge "$(echo "$designs" | wc -l)" ] && ok || bad "only $n pictures"
finish
