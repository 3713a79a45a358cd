#!/usr/bin/env bash
# Options in the docs and in --help agree: every option an 'rg2 CMD --help' lists is named in
# README.md or a reference page of docs/, and every option of an rg2 command written in them (an
# inline `rg2 CMD ...` span or a code block line) is one that 'rg2 CMD --help' lists ('rg2 shape':
# --u-.../--v-... as its --D-... options, and the parameters 'rg2 shapes --json' gives).
# Usage: bash doc_options.sh <path-to-rg2> <source-dir>
set -u
. "$(dirname "$0")/lib.sh"
command -v python3 >/dev/null || { echo "doc_options: no python3, skipped"; exit 0; }
out=$(cd "$SRC" && python3 - "$RG2" README.md docs/{design-format,shapes,curves,poles,export,render,gallery,MATH}.md <<'EOF'
import json, re, subprocess, sys
rg2, docs = sys.argv[1], sys.argv[2:]
OPT = re.compile(r'(?<![\w-])--[A-Za-z][\w-]*')
cmds = ['build', 'check', 'render', 'info', 'mesh', 'shapes', 'shape', 'curve', 'demo']
helps = {c: subprocess.run([rg2, c, '--help'], stdout=subprocess.PIPE, stderr=subprocess.STDOUT).stdout.decode()
         for c in cmds}
known = {c: set(OPT.findall(h)) | {'--help'} for c, h in helps.items()}
params = {p for s in json.loads(subprocess.run([rg2, 'shapes', '--json'], stdout=subprocess.PIPE).stdout)['shapes']
          for p in s['params']}
known['shape'] |= {'--' + p for p in params}
text = {p: open(p, encoding='utf-8').read() for p in docs}
alltext = '\n'.join(text.values())
n = 0
for c in cmds:
    for o in sorted(known[c]):
        if o in ('--PARAM', '--help') or ('--' + o[2:]) in ('--' + p for p in params):
            continue
        n += 1
        if not re.search(r'(?<![\w-])' + re.escape(o) + r'(?![\w-])', alltext):
            print('rg2 %s --help lists %s, which no doc names' % (c, o))
for path, t in text.items():
    spans = [m.group(1) for m in re.finditer(r'`(rg2 [^`]*)`', t)]
    spans += re.findall(r'^[ \t]*(?:\$ )?(rg2 \w+[^\n#]*)', t, flags=re.M)
    for s in spans:
        words = s.split()
        c = words[1] if len(words) > 1 else ''
        if c not in known:
            continue
        for o in OPT.findall(s):
            n += 1
            d = re.sub(r'^--[uv]-', '--D-', o) if c == 'shape' else o
            if o not in known[c] and d not in known[c]:
                print('%s: `%s`: rg2 %s --help has no %s' % (path, ' '.join(s.split()), c, o))
print('count', n)
EOF
)
doc_report doc_options options 50 "$out"
finish
