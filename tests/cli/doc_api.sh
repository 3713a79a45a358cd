#!/usr/bin/env bash
# C names in the docs: every rg2_ name (not the internal rg2__ ones) that README.md or the reference
# pages of docs/ (not the performance and robustness records, which name benchmark programs)
# mention exists in include/rg2.h, and every call written out with its arguments,
# `rg2_name(a, b, ...)`, has as many as the prototype (a call that elides some with '...' is
# skipped).
# Usage: bash doc_api.sh <path-to-rg2> <source-dir>   (the rg2 path is unused)
set -u
. "$(dirname "$0")/lib.sh"
command -v python3 >/dev/null || { echo "doc_api: no python3, skipped"; exit 0; }
out=$(cd "$SRC" && python3 - include/rg2.h README.md docs/{design-format,shapes,curves,poles,export,render,gallery,MATH}.md <<'EOF'
import re, sys
header = re.sub(r'/\*.*?\*/|//[^\n]*', '', open(sys.argv[1]).read(), flags=re.S)
words = set(re.findall(r'\brg2_\w+', header))
arity = {}
for m in re.finditer(r'\b(rg2_\w+)\s*\(([^;{}]*?)\)\s*;', header, flags=re.S):
    a = m.group(2).strip()
    arity[m.group(1)] = 0 if a in ('', 'void') else a.count(',') + 1
calls = 0
for path in sys.argv[2:]:
    for ln, line in enumerate(open(path, encoding='utf-8'), 1):
        for name in re.findall(r'\brg2_(?!_)\w+', line):
            if name not in words:
                print('%s:%d: %s is not in include/rg2.h' % (path, ln, name))
        for m in re.finditer(r'\b(rg2_(?!_)\w+)\(([^()`]*)\)', line):
            name, a = m.group(1), m.group(2).strip()
            if name not in arity or '...' in a or '…' in a:
                continue
            calls += 1
            n = 0 if a == '' else a.count(',') + 1
            if n != arity[name]:
                print('%s:%d: %s(%s) has %d arguments, include/rg2.h %d' % (path, ln, name, a, n, arity[name]))
print('count', calls)
EOF
)
doc_report doc_api "calls with arguments" 20 "$out"
finish
