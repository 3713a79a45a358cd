#!/usr/bin/env python3
"""Instructions per point of every method of rg2_bench, counted by valgrind's callgrind.

    python3 bench/instructions.py [torus|merged|freeform ...]     (default: torus)

Runs build-bench/bench/rg2_bench --quick --only CASE under `valgrind --tool=callgrind` and divides
each method's inclusive instruction count (the method's function and everything it calls) by the
points it evaluated. Unlike the timings, these counts do not depend on the host's clock or on
what the machine's other guests do: the same binary and input give the same counts. They count
work, not time: a vector or a scalar instruction counts one, and memory stalls do not count.
valgrind emulates no AVX-512, so rg2 runs its AVX2 kernels (x86-64-v3 clones) here; the
hand-written AVX-512 kernels that a native run takes on an AVX-512 CPU are not counted.

The torus takes about 2.5 minutes, the merged design about 6, the free-form mesh about 30.
"""
import json
import os
import re
import shutil
import subprocess
import sys
import tempfile

BENCH = 'build-bench/bench/rg2_bench'
# rg2_bench's method functions, in its table's order: (symbol, label, level)
METHODS = [
    ('m_grid0', 'rg2 grid (rg2_surface_grid)', 0),
    ('m_grid1', 'rg2 grid (rg2_surface_grid)', 1),
    ('m_grid2', 'rg2 grid (rg2_surface_grid)', 2),
    ('m_point0', 'rg2 per point (rg2_patch_point)', 0),
    ('m_point1', 'rg2 per point (rg2_patch_point_normal)', 1),
    ('m_point2', 'rg2 per point (rg2_patch_eval order 2)', 2),
    ('m_s1421_0', 'SISL s1421 per point', 0),
    ('m_s1421_1', 'SISL s1421 per point', 1),
    ('m_s1506_0', 'SISL s1506 grid, whole surface', 0),
    ('m_s1506_1', 'SISL s1506 grid, whole surface', 1),
    ('m_bs_d0', 'OCCT Geom_BSplineSurface D0/D1', 0),
    ('m_bs_d1', 'OCCT Geom_BSplineSurface D0/D1', 1),
    ('m_ad_d0', 'OCCT GeomAdaptor_Surface D0/D1', 0),
    ('m_ad_d1', 'OCCT GeomAdaptor_Surface D0/D1', 1),
    ('m_slprops', 'OCCT GeomLProp_SLProps', 2),
]
LEVEL = ['position', 'position + unit normal', '+ K and H']
GRID_CALLS = 4  # run_grid: 3 untimed calls, then the timed one
# the ratios of issue 8's targets: (grid level, peer symbol)
PAIRS = [(0, 'm_s1506_0'), (0, 'm_ad_d0'), (1, 'm_s1506_1'), (1, 'm_ad_d1'), (2, 'm_slprops')]


def fail(msg):
    sys.exit(f'instructions.py: {msg}')


def count(case, tmp):
    out, js = os.path.join(tmp, f'cg.{case}'), os.path.join(tmp, f'{case}.json')
    r = subprocess.run(['valgrind', '--tool=callgrind', f'--callgrind-out-file={out}', BENCH, js, '--quick',
                        '--only', case], stdout=subprocess.DEVNULL, stderr=subprocess.PIPE, text=True)
    if r.returncode:
        fail(f'rg2_bench under callgrind failed ({r.returncode}):\n{r.stderr[-2000:]}')
    return parse(out, json.load(open(js))['cases'][0])


def parse(out, c):
    ann = subprocess.run(['callgrind_annotate', '--tree=caller', '--inclusive=yes', '--threshold=100', out],
                         capture_output=True, text=True, check=True).stdout
    ir, calls, callers = {}, {}, 0
    for line in ann.splitlines():
        m = re.match(r'\s*[\d,]+ \([^)]*\)\s+<\s+\S*:\S+ \((\d+)x\)', line)
        if m:  # a caller line of the next function's block: its calls
            callers += int(m.group(1))
            continue
        m = re.match(r'\s*([\d,]+) \([^)]*\)\s+\*\s+\S*:(\w+)(?:\.\w+)? \[', line)
        if m:  # the function's own line: its inclusive count
            ir[m.group(2)], calls[m.group(2)] = int(m.group(1).replace(',', '')), callers
        if not line.strip() or m:
            callers = 0
    reps, pts = c['repetitions'], c['points']
    if calls.get('rg2_surface_grid') != 3 * reps * GRID_CALLS:
        fail(f"{calls.get('rg2_surface_grid')} calls of rg2_surface_grid, expected {3 * reps * GRID_CALLS}: "
             'rg2_bench changed, update GRID_CALLS')
    per = {}
    for sym, _, _ in METHODS:
        if not calls.get(sym):
            fail(f'{sym} not in the callgrind profile: rg2_bench changed, update METHODS')
        per[sym] = ir[sym] / (calls[sym] * (GRID_CALLS if sym.startswith('m_grid') else 1) * pts)
    return c, per


def main(cases):
    with tempfile.TemporaryDirectory() as tmp:
        for case in cases:
            c, per = count(case, tmp)
            print(f"#### {case}: {c['surface']}\n")
            print(f"{c['points']} points, {c['repetitions']} repetitions; instructions per point, inclusive "
                  '(valgrind callgrind; rg2 on its AVX2 kernels)\n')
            print('| method | output | instructions per point |')
            print('|---|---|---:|')
            for sym, label, level in METHODS:
                print(f'| {label} | {LEVEL[level]} | {per[sym]:.1f} |')
            print('\n| peer / rg2 grid | instructions |')
            print('|---|---:|')
            for level, peer in PAIRS:
                name = next(lbl for s, lbl, _ in METHODS if s == peer)
                print(f'| {name}, {LEVEL[level]} | {per[peer] / per["m_grid%d" % level]:.1f}x |')
            print()


if __name__ == '__main__':
    if not os.path.exists(BENCH):
        fail(f'{BENCH} not found: run make bench first')
    for tool in ('valgrind', 'callgrind_annotate'):
        if not shutil.which(tool):
            fail(f'{tool} not found: apt-get install valgrind')
    cases = sys.argv[1:] or ['torus']
    for case in cases:
        if case not in ('torus', 'merged', 'freeform'):
            fail(f'unknown case {case!r}: torus, merged or freeform')
    main(cases)
