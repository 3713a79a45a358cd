#!/usr/bin/env python3
"""Mutation testing for rg2: does the test suite notice a wrong line of the library?

usage: scripts/mutate.py CLONE BUILD SRCFILE [--n N] [--seed S] [--tests REGEX] [--lines A-B]
                         [--out TSV] [--list]

CLONE: a git clone of rg2 whose working tree is mutated in place, one mutant at a time, and
restored after each (run it in a clone, never in the tree you edit); BUILD: a configured build
directory of CLONE, e.g.
  cmake -S CLONE -B BUILD -DCMAKE_BUILD_TYPE=Release -DRG2_BUILD_TESTS=ON -DRG2_OCCT_TESTS=OFF
SRCFILE: e.g. src/surface.c.  A mutant changes one operator (+ - * / < <= > >= == != && ||) or
one constant (a float times 1.01, an integer plus 1) on one code line, outside comments, string
literals, messages, allocations and loop bounds (a loop bound read past an array is a
sanitizer's finding, not the test's); N mutants are drawn with the seed. Each is rebuilt and
the tests run (ctest -R REGEX, stopping at the first failure): "killed" if a test fails,
"SURVIVED" if none does. Survivors are printed and written to the TSV for triage: equivalent
(no observable change), seen only by a sanitizer or a test outside REGEX, or a test gap.
docs/robustness.md ("Mutation testing") gives the figures of the last pass.
"""
import argparse, os, random, re, subprocess, sys, time

OPS = [  # (pattern, replacement, kind)
    (r'(?<= )\+(?= )', '-', 'plus->minus'),
    (r'(?<= )-(?= )', '+', 'minus->plus'),
    (r'(?<= )\*(?= )', '/', 'mul->div'),
    (r'(?<= )/(?= )', '*', 'div->mul'),
    (r'(?<=[ ])<(?=[ ])', '<=', 'lt->le'),
    (r'(?<=[ ])<=(?=[ ])', '<', 'le->lt'),
    (r'(?<=[ ])>(?=[ ])', '>=', 'gt->ge'),
    (r'(?<=[ ])>=(?=[ ])', '>', 'ge->gt'),
    (r'(?<=[ ])==(?=[ ])', '!=', 'eq->ne'),
    (r'(?<=[ ])!=(?=[ ])', '==', 'ne->eq'),
    (r'(?<=[ ])&&(?=[ ])', '||', 'and->or'),
    (r'(?<=[ ])\|\|(?=[ ])', '&&', 'or->and'),
    (r'(?<![\w.])(\d+\.\d*(?:e-?\d+)?)(?![\w.])', None, 'float-const'),
    (r'(?<![\w.\[])([1-9]\d?)(?![\w.\]x])', None, 'int-const'),
]


def code_part(line):
    """The line without // comments and string literals' contents (masked with spaces)."""
    out, i, n, in_str = [], 0, len(line), False
    while i < n:
        c = line[i]
        if in_str:
            if c == '\\':
                out.append('  '); i += 2; continue
            if c == '"':
                in_str = False; out.append(c)
            else:
                out.append(' ')
        else:
            if c == '"':
                in_str = True; out.append(c)
            elif c == "'":
                j = line.find("'", i + 2 if i + 1 < n and line[i + 1] == '\\' else i + 1)
                j = n - 1 if j < 0 else j
                out.append(' ' * (j - i + 1)); i = j + 1; continue
            elif line.startswith('//', i):
                out.append(' ' * (n - i)); break
            elif line.startswith('/*', i):
                j = line.find('*/', i + 2)
                j = n if j < 0 else j + 2
                out.append(' ' * (j - i)); i = j; continue
            else:
                out.append(c)
        i += 1
    return ''.join(out)[:n]


def sites(lines, lo, hi):
    res, in_block = [], False
    for k, line in enumerate(lines):
        ln = k + 1
        s = line
        if in_block:
            if '*/' in s:
                in_block = False
            continue
        st = s.strip()
        if st.startswith('/*') and '*/' not in st:
            in_block = True; continue
        if st.startswith('#') or st.startswith('*') or st.startswith('/*') or not st:
            continue
        if ln < lo or ln > hi:
            continue
        code = code_part(line)
        if any(w in code for w in ('snprintf', 'rg2__fail', 'rg2__num', 'set_err', 'sizeof', 'alloc(', 'memcpy', 'memset')):
            continue
        for pat, rep, kind in OPS:
            if st.startswith('for (') and kind[:2] in ('lt', 'le', 'gt', 'ge', 'eq', 'ne'):
                continue  # loop bounds: out-of-range reads that only a sanitizer build reports
            for m in re.finditer(pat, code):
                a, b = m.span(1) if m.groups() else m.span()
                tok = line[a:b]
                if kind == 'float-const':
                    v = float(tok)
                    new = repr(v * 1.01 + (0.01 if v == 0 else 0))
                elif kind == 'int-const':
                    new = str(int(tok) + 1)
                else:
                    new = rep
                res.append((ln, a, b, tok, new, kind))
    return res


def run(cmd, cwd, timeout):
    try:
        p = subprocess.run(cmd, cwd=cwd, stdout=subprocess.PIPE, stderr=subprocess.STDOUT,
                           timeout=timeout, text=True)
        return p.returncode, p.stdout
    except subprocess.TimeoutExpired:
        return 124, 'timeout'


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument('clone'); ap.add_argument('build'); ap.add_argument('src')
    ap.add_argument('--n', type=int, default=60)
    ap.add_argument('--seed', type=int, default=1)
    ap.add_argument('--tests', default='^test_')
    ap.add_argument('--lines', default='1-999999')
    ap.add_argument('--out', default=None, help='survivor table (default /tmp/mut_FILE.tsv)')
    ap.add_argument('--list', action='store_true', help='only list the mutation sites')
    a = ap.parse_args()
    path = os.path.join(a.clone, a.src)
    if not a.list and subprocess.run(['git', '-C', a.clone, 'diff', '--quiet', '--', a.src]).returncode != 0:
        sys.exit('%s has uncommitted changes in %s: run in a clean clone' % (a.src, a.clone))
    orig = open(path).read()
    lines = orig.split('\n')
    lo, hi = map(int, a.lines.split('-'))
    all_sites = sites(lines, lo, hi)
    random.Random(a.seed).shuffle(all_sites)
    chosen = all_sites[:a.n]
    if a.list:
        for s in sorted(chosen):
            print('%d: %s -> %s (%s): %s' % (s[0], s[3], s[4], s[5], lines[s[0] - 1].strip()))
        return
    rc, out = run(['cmake', '--build', a.build, '-j2'], a.clone, 900)
    if rc != 0:
        sys.exit('the unmutated build fails:\n' + out[-3000:])
    rc, out = run(['ctest', '--test-dir', a.build, '-R', a.tests, '-j2', '--timeout', '300'], a.clone, 3600)
    if rc != 0:
        sys.exit('the unmutated tests fail:\n' + out[-3000:])
    outf = open(a.out or ('/tmp/mut_' + os.path.basename(a.src) + '.tsv'), 'w')
    killed = survived = nobuild = 0
    t0 = time.time()
    try:
        for i, (ln, s0, s1, tok, new, kind) in enumerate(chosen):
            ml = list(lines)
            ml[ln - 1] = lines[ln - 1][:s0] + new + lines[ln - 1][s1:]
            open(path, 'w').write('\n'.join(ml))
            rc, out = run(['cmake', '--build', a.build, '-j2'], a.clone, 900)
            if rc != 0:
                nobuild += 1; verdict = 'nobuild'
            else:
                rc, out = run(['ctest', '--test-dir', a.build, '-R', a.tests, '-j2', '--timeout', '120',
                               '--stop-on-failure'], a.clone, 1800)
                if rc != 0:
                    killed += 1; verdict = 'killed'
                    m = re.search(r'\d+ - (\S+) \(', out)
                    verdict += ' by ' + (m.group(1) if m else '?')
                else:
                    survived += 1; verdict = 'SURVIVED'
            rec = '%s:%d %s: %s -> %s | %s' % (a.src, ln, kind, tok, new, lines[ln - 1].strip())
            print('[%d/%d %.0fs] %s  %s' % (i + 1, len(chosen), time.time() - t0, verdict, rec), flush=True)
            outf.write('%s\t%d\t%s\t%s\t%s\t%s\n' % (verdict, ln, kind, tok, new, lines[ln - 1].strip()))
            outf.flush()
    finally:
        open(path, 'w').write(orig)
        run(['cmake', '--build', a.build, '-j2'], a.clone, 900)
    print('%s: %d mutants: %d killed, %d survived, %d did not build (of %d sites)'
          % (a.src, len(chosen), killed, survived, nobuild, len(all_sites)))


if __name__ == '__main__':
    main()
