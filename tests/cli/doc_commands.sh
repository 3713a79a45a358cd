#!/usr/bin/env bash
# Commands in the docs that a reader may copy: every rg2 command on an example file, quoted in
# README.md or docs/*.md (an inline `rg2 ...` span, which may wrap a line, or a line of a code
# block), must run as written in a shell and exit 0 (a missing -o or a 'K|L' placeholder fails).
# Usage: bash doc_commands.sh <path-to-rg2> <source-dir>
set -u
. "$(dirname "$0")/lib.sh"
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
ln -s "$(cd "$SRC" && pwd)/examples" "$tmp/examples"
mkdir "$tmp/out" "$tmp/bin"
printf '#!/bin/sh\nexec "%s" "$@"\n' "$(cd "$(dirname "$RG2")" && pwd)/$(basename "$RG2")" >"$tmp/bin/rg2"
chmod +x "$tmp/bin/rg2"
n=0
while IFS= read -r line; do
  [ -n "$line" ] || continue
  n=$((n + 1))
  out=$(cd "$tmp" && PATH="$tmp/bin:$PATH" bash -c "$line" 2>&1 >/dev/null)
  rc=$?
  [ "$rc" = 0 ] && ok || bad "docs command '$line' exits $rc: ${out%%$'\n'*}"
done < <(perl -0777 -ne '
  while (/`(rg2 [^`]*examples\/[^`]*)`/g) { my $c = $1; $c =~ s/\s*\n\s*/ /g; print "$c\n" }
  while (/^[ \t]*(?:\$ )?(rg2 \w+ [^\n#]*examples\/[^\n#]*)/mg) { print "$1\n" }
' "$SRC"/README.md "$SRC"/docs/*.md | sort -u)
[ "$n" -ge 10 ] && ok || bad "only $n docs commands found"
finish
