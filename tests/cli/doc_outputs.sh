#!/usr/bin/env bash
# Output the docs quote: in README.md and docs/*.md, a code block line '$ rg2 ...' followed by
# lines of output, a fenced block after '<!-- output of: COMMAND -->', and the lines of a block
# after '<!-- each line: COMMAND -->' (COMMAND with {file} for the line's text up to its first
# ':', one run per line) must be what the command prints now (stdout and stderr; run in the
# source directory, exit code not checked). Quoted lines match program lines in order; lines
# with no '...' line between them match consecutive program lines; a quoted line may be part of
# a program line, and '...' in it stands for any text. Numbers compare as written, except
# rounding-level ones (|x| < 1e-9 in e-notation: residuals, gaps, coordinates that should be 0),
# which are bounds: the program's magnitude at most 4 times the quoted one (0 stays 0), and
# numbers of 8 or more significant digits, which agree to 1e-8 relative. A block after
# '<!-- numbers vary by build -->' (counts that follow the tessellation's diagonals, which the
# AVX-512 kernels may pick otherwise) compares its words only, any number for each number.
# Usage: bash doc_outputs.sh <path-to-rg2> <source-dir>
set -u
. "$(dirname "$0")/lib.sh"
command -v python3 >/dev/null || { echo "doc_outputs: no python3, skipped"; exit 0; }
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
mkdir "$tmp/bin"
printf '#!/bin/sh\nexec "%s" "$@"\n' "$(cd "$(dirname "$RG2")" && pwd)/$(basename "$RG2")" >"$tmp/bin/rg2"
chmod +x "$tmp/bin/rg2"
out=$(cd "$SRC" && PATH="$tmp/bin:$PATH" python3 - README.md docs/*.md <<'EOF'
import re, subprocess, sys

NUM = r'-?\d+(?:\.\d+)?(?:e[-+]?\d+)?'
TOKEN = re.compile(r'(\.\.\.)|(?<![\w.])(' + NUM + r')(?![\w]|\.\d)')

def pattern(line):
    """A regex for a quoted line: literal text, a capture per number, '...' as any text."""
    parts, nums, pos = [], [], 0
    for m in TOKEN.finditer(line):
        parts.append(re.escape(line[pos:m.start()]))
        if m.group(1):
            parts.append('.*?')
        else:
            parts.append('(' + NUM + ')')
            nums.append(m.group(2))
        pos = m.end()
    parts.append(re.escape(line[pos:]))
    return re.compile(''.join(parts)), nums

def sig_digits(s):
    return len(re.sub(r'^[-0.]*', '', s.split('e')[0]).replace('.', ''))

def same_number(doc, got):
    d, g = float(doc), float(got)
    if 'e' in doc and abs(d) < 1e-9:
        return g == 0 if d == 0 else abs(g) <= 4 * abs(d)
    if sig_digits(doc) >= 8:
        return abs(g - d) <= 1e-8 * abs(d)
    return doc == got

def line_matches(quoted, actual, loose):
    rx, nums = pattern(quoted)
    m = rx.search(actual)
    return bool(m) and (loose or all(same_number(d, g) for d, g in zip(nums, m.groups())))

def compare(where, cmd, quoted, loose=False):
    """quoted: list of (line number, text); '...' lines allow a gap. Returns an error or None."""
    r = subprocess.run(['bash', '-c', cmd], stdout=subprocess.PIPE, stderr=subprocess.STDOUT)
    lines = r.stdout.decode('utf-8', 'replace').split('\n')
    groups, cur = [], []
    for ln, q in quoted:
        if q.strip() == '...':
            if cur:
                groups.append(cur)
            cur = []
        else:
            cur.append((ln, q))
    if cur:
        groups.append(cur)
    start = 0
    for g in groups:
        found = None
        for s in range(start, len(lines) - len(g) + 1):
            if all(line_matches(q, lines[s + k], loose) for k, (_, q) in enumerate(g)):
                found = s
                break
        if found is None:
            for ln, q in g:   # name the first quoted line that the program does not print
                if not any(line_matches(q, a, loose) for a in lines[start:]):
                    return '%s:%d: `%s` does not print: %s' % (where, ln, cmd, q.strip())
            return '%s:%d: `%s` prints these lines, but not together in this order' % (where, g[0][0], cmd)
        start = found + len(g)
    return None

errors, checked = [], 0
for path in sys.argv[1:]:
    text = open(path, encoding='utf-8').read().split('\n')
    i, marker, loose = 0, None, False
    while i < len(text):
        line = text[i]
        if re.match(r'\s*<!-- numbers vary by build -->\s*$', line):
            loose = True
            i += 1
            continue
        m = re.match(r'\s*<!-- (output of|each line): (.*) -->\s*$', line)
        if m:
            marker = (m.group(1), m.group(2))
            i += 1
            continue
        fenced = line.startswith('```')
        if fenced or (line.startswith('    ') and (i == 0 or not text[i - 1].strip())):
            block = []
            if fenced:
                i += 1
                while i < len(text) and not text[i].startswith('```'):
                    block.append((i + 1, text[i]))
                    i += 1
                i += 1
            else:
                while i < len(text) and (text[i].startswith('    ') or not text[i].strip()):
                    block.append((i + 1, text[i][4:]))
                    i += 1
            block = [(ln, t) for ln, t in block if t.strip()]
            if marker and marker[0] == 'output of':
                checked += 1
                e = compare(path, marker[1], block, loose)
                e and errors.append(e)
            elif marker:
                for ln, t in block:
                    checked += 1
                    e = compare(path, marker[1].replace('{file}', t.split(':')[0]), [(ln, t)], loose)
                    e and errors.append(e)
            else:
                cmd, quoted = None, []
                for ln, t in block + [(0, '$ ')]:
                    if t.lstrip().startswith('$ '):
                        if cmd and quoted:
                            checked += 1
                            e = compare(path, cmd[1], quoted, loose)
                            e and errors.append(e)
                        cmd, quoted = ((ln, t.lstrip()[2:].split('  #')[0].strip()) if t.lstrip()[2:].startswith('rg2 ') else None), []
                    elif cmd:
                        quoted.append((ln, t))
            marker, loose = None, False
            continue
        if line.strip():
            marker, loose = None, False
        i += 1
for e in errors:
    print(e)
print('count', checked)
EOF
)
doc_report doc_outputs "quoted outputs" 5 "$out"
finish
