#!/usr/bin/env python3
"""Markdown tables from rg2_bench's JSON (out/bench.json), as in docs/performance.md.
Usage: python3 bench/bench_table.py [out/bench.json]"""
import json
import sys


def main(path):
    d = json.load(open(path))
    print(f"Machine: {d['cpu']}, {d['threads_available']} hardware threads; rg2 {d['rg2_version']}.")
    for c in d.get('cases', []):
        print(f"\n#### {c['name']}: {c['surface']}\n")
        print(f"{int(c['patches'])} patches x {int(c['points_per_patch'])} points = {int(c['points'])} points, "
              f"{c['repetitions']} interleaved repetitions; every output checked against the {c['checked_against']}.")
        if 'host_steal_percent' in c:
            print(f"Host: {c['host_steal_percent']:.1f} % of the machine's CPU time went to other guests (steal) during this case.")
        if 'positions_fit' in c:
            print(f"Output {c['points'] * 24e-6:.1f} MB of positions (fits {c['positions_fit']}), "
                  f"{c['points'] * 48e-6:.1f} MB with normals (fits {c['normals_fit']}).")
        print()
        print("| method | output | median ms | M points/s | max position error | max normal error | max K, H error | check |")
        print("|---|---|---:|---:|---:|---:|---:|---|")
        for m in c['methods']:
            mem = m['peer'] == 'memory'
            ok = '-' if mem else ('ok' if m['output_correct'] else 'WRONG')
            e = (lambda x: '-') if mem else (lambda x: f"{x:.1e}")
            print(f"| {m['method']} | {m['output']} | {m['median_s'] * 1e3:.3f} | {m['mpoints_per_s']:.1f} | "
                  f"{e(m['max_pos_err_rel'])} | {e(m['max_normal_err'])} | "
                  f"{e(max(m['max_K_err_rel'], m['max_H_err_rel']))} | {ok} |")
        print("\n| ratio (same run, medians, 1 thread) | value | target | | write ceiling allows | with patch reads |")
        print("|---|---:|---:|---|---:|---:|")
        for r in c['ratios']:
            t = f">= {r['target']:g}x" if 'target' in r else ''
            met = ('met' if r['met'] else 'missed' if r.get('reachable', True) else 'out of reach') if 'target' in r else ''
            b = f"{r['write_ceiling_bound']:.1f}x" if 'write_ceiling_bound' in r else ''
            tb = f"{r['traffic_bound']:.1f}x" if 'traffic_bound' in r else ''
            print(f"| {r['pair']} | {r['ratio']:.2f}x | {t} | {met} | {b} | {tb} |")
    if 'grid_scaling' in d:
        paired = any('speedup_2_threads_paired' in r for r in d['grid_scaling']['threads'])
        host = any('host_parallelism_2_threads' in r for r in d['grid_scaling']['threads'])
        rounds = any('speedup_2_threads_paired_rounds' in r for r in d['grid_scaling']['threads'])
        alone = [r['mpoints_per_s_1_thread_pinned'] for r in d['grid_scaling']['threads']
                 if 'mpoints_per_s_1_thread_pinned' in r]
        cpus = [int(c['cpu']) for c in alone[0]] if alone else []
        if rounds:
            print(f"\nEach figure the median of {int(d['grid_scaling']['threads'][0]['rounds'])} rounds of the whole "
                  "table; the paired ratio of each round in brackets.")
        print("\n| points per patch | output | 1 thread M pts/s | 2 threads M pts/s | 2t / 1t (medians) | "
              + ("2t / 1t (paired calls) | " if paired else "")
              + ("rounds | " if rounds else "")
              + "2t / 1t (fastest calls) | 2t / 1t, second core busy | write ceiling M pts/s | 1 thread / ceiling | "
              "output MB, fits |" + (" steal % | host 2t / 1t (probe) |" if host else "")
              + "".join(f" 1 thread on CPU {c} M pts/s |" for c in cpus)
              + (" 2 threads / (CPUs alone added up) |" if cpus else ""))
        print("|---|---|---:|---:|---:|" + ("---:|" if paired else "") + ("---|" if rounds else "")
              + "---:|---:|---:|---:|---|"
              + ("---:|---:|" if host else "") + "---:|" * len(cpus) + ("---:|" if cpus else ""))
        for r in d['grid_scaling']['threads']:
            c = f"{r['ceiling_mpoints_per_s']:.1f}" if 'ceiling_mpoints_per_s' in r else '-'
            f = f"{r['fraction_of_ceiling_1_thread']:.2f}" if 'fraction_of_ceiling_1_thread' in r else '-'
            print(f"| {r['points_per_patch_side']}^2 | {r['output']} | {r['mpoints_per_s_1_thread']:.1f} | "
                  f"{r['mpoints_per_s_2_threads']:.1f} | {r['speedup_2_threads']:.2f}x | "
                  + (f"{r['speedup_2_threads_paired']:.2f}x | " if paired else "")
                  + ("(" + " ".join(f"{x:.2f}" for x in r.get('speedup_2_threads_paired_rounds', [])) + ") | "
                     if rounds else "")
                  + f"{r['speedup_2_threads_fastest_calls']:.2f}x | "
                  f"{r['speedup_2_threads_second_core_busy']:.2f}x | {c} | {f} | "
                  f"{r['output_bytes'] * 1e-6:.1f}, {r.get('output_fits', '')} |"
                  + (f" {r.get('host_steal_percent', float('nan')):.1f} | {r.get('host_parallelism_2_threads', float('nan')):.2f}x |"
                     if host else "")
                  + "".join(f" {c['mpoints_per_s']:.1f} |" for c in r.get('mpoints_per_s_1_thread_pinned', []))
                  + (f" {r['efficiency_2_threads_of_both_cpus_alone']:.2f} |"
                     if 'efficiency_2_threads_of_both_cpus_alone' in r else ""))
    if 'construction' in d:
        cs = d['construction']
        rb = 'rebuild_per_control_point_spread_100_to_1000' in cs
        print("\n| control points | patches | build 1 thread ms | ns per control point | build 2 threads ms |"
              + (" rebuild 1 thread ms | ns per control point | rebuild 2 threads ms |" if rb else ""))
        print("|---|---:|---:|---:|---:|" + ("---:|---:|---:|" if rb else ""))
        for r in cs['sizes']:
            n = int(round(r['control_points'] ** 0.5))
            row = (f"| {n} x {n} | {int(r['patches'])} | {r['median_s_1_thread'] * 1e3:.3f} | "
                   f"{r['ns_per_control_point_1_thread']:.0f} | {r['median_s_2_threads'] * 1e3:.3f} |")
            if rb:
                row += (f" {r['rebuild_median_s_1_thread'] * 1e3:.3f} | {r['rebuild_ns_per_control_point_1_thread']:.0f} | "
                        f"{r['rebuild_median_s_2_threads'] * 1e3:.3f} |")
            print(row)
        print(f"\nFrom 100^2 to 1000^2 control points the time per control point stays within a factor "
              f"{cs['per_control_point_spread_100_to_1000']:.2f} for rg2_surface_build"
              + (f", {cs['rebuild_per_control_point_spread_100_to_1000']:.2f} for rg2_surface_rebuild." if rb else "."))
    if 'tessellation' in d:
        again = 'again_median_s_1_thread' in d['tessellation'][0]
        print("\n| density | vertices | triangles | tessellation 1 thread ms | 2 threads ms "
              + ("| again into the same mesh, 1 thread ms | 2 threads ms " if again else "")
              + "| grid of the same points ms | tessellation / grid |" + (" again / grid |" if again else ""))
        print("|---:|---:|---:|---:|---:|---:|---:|" + ("---:|---:|---:|" if again else ""))
        for r in d['tessellation']:
            g = r['grid_median_s_1_thread']
            a = (f"{r['again_median_s_1_thread'] * 1e3:.3f} | {r['again_median_s_2_threads'] * 1e3:.3f} | "
                 if again else "")
            print(f"| {int(r['density'])} | {int(r['vertices'])} | {int(r['triangles'])} | "
                  f"{r['median_s_1_thread'] * 1e3:.3f} | {r['median_s_2_threads'] * 1e3:.3f} | {a}"
                  f"{g * 1e3:.3f} | {r['median_s_1_thread'] / g:.2f} |"
                  + (f" {r['again_median_s_1_thread'] / g:.2f} |" if again else ""))
    if 'files' in d:
        fs = d['files']
        print(f"\n| writing the {fs['surface']} ({int(fs['patches'])} patches) | seconds | MB |")
        print("|---|---:|---:|")
        for r in fs['methods']:
            print(f"| {r['method']} | {r['median_s']:.3f} | {r['bytes'] * 1e-6:.1f} |")
        print(f"\nOpenCASCADE's writers against rg2's for the same surface as one face: STEP "
              f"{fs['ratio_occt_step_to_rg2']:.1f}x, IGES {fs['ratio_occt_iges_to_rg2']:.1f}x the time; OpenCASCADE "
              f"read rg2's files back as written: {'yes' if fs['read_back_ok'] else 'NO'}.")
    if 'picking' in d:
        pk = d['picking']
        print(f"\nPicking on the {pk['surface']}: {int(pk['closest_queries'])} closest-point queries, "
              f"{int(pk['rays'])} rays ({int(pk['rays_hitting'])} hit), {int(pk['repetitions'])} interleaved "
              f"repetitions, medians, thread CPU time; rg2_locator_build {pk['locator_build_median_us']:.1f} us"
              + "".join(f"; {r['method']} Init and a first query {r['setup_median_us']:.0f} us" for r in pk['closest']
                        if 'setup_median_us' in r and r['peer'] != 'rg2') + ".\n")
        print("| closest point | queries | us per query | worst distance error | worst point error | failed |")
        print("|---|---:|---:|---:|---:|---:|")
        for r in pk['closest']:
            print(f"| {r['method']} | {int(r['queries'])} | {r['median_us_per_query']:.2f} | "
                  f"{r['max_distance_err']:.1e} | {r['max_point_err']:.1e} | {int(r['failures'])} |")
        if 'closest_by_distance' in pk:
            bands = pk['closest_by_distance']
            names = list(bands[0]['median_us_per_query'].keys())
            lab = [f"[{b['distance_from']:g}, {b['distance_below']:g})" if 'distance_below' in b
                   else f">= {b['distance_from']:g}" for b in bands]
            print("\n| us per query, by distance from the surface | " + " | ".join(lab) + " |")
            print("|---|" + "---:|" * len(bands))
            print("| queries | " + " | ".join(str(int(b['queries'])) for b in bands) + " |")
            for n in names:
                print(f"| {n} | " + " | ".join(f"{b['median_us_per_query'][n]:.2f}" for b in bands) + " |")
        print("\n| first ray hit | rays | us per ray | worst t error x \\|d\\| | worst point error | failed (hit/miss) |")
        print("|---|---:|---:|---:|---:|---:|")
        for r in pk['ray']:
            print(f"| {r['method']} | {int(r['queries'])} | {r['median_us_per_query']:.2f} | "
                  f"{r['max_t_err_length']:.1e} | {r['max_point_err']:.1e} | {int(r['failures'])} "
                  f"({int(r['hit_miss_disagreements'])}) |")
        if 'rg2_closest_max_dist_minus_bound' in pk:
            print(f"\nrg2's proven bound (rg2_hit.bound): closest, distance - bound at most "
                  f"{pk['rg2_closest_max_dist_minus_bound']:.1e} (above the exact distance: "
                  f"{int(pk['rg2_closest_bound_above_exact'])}); ray, (t - bound) x |d| at most "
                  f"{pk['rg2_ray_max_t_minus_bound_length']:.1e} (above the exact t: {int(pk['rg2_ray_bound_above_exact'])}).")
        print("\n| ratio (same run, medians, 1 thread) | peer time / rg2 time |")
        print("|---|---:|")
        for r in pk['ratios']:
            print(f"| {r['rg2']} against {r['peer']} | {r['peer_over_rg2']:.2f}x |")
    print(f"\nPeak memory (getrusage ru_maxrss): {d['peak_rss_kb'] / 1024:.0f} MB.")
    if 'ceiling_fastest_way_counts' in d:
        w = ', '.join(f"{k} {v}" for k, v in d['ceiling_fastest_way_counts'].items())
        print(f"\nWrite ceiling: the fastest way of writing, counted over all ceiling measurements: {w}.")
    if 'traffic_fastest_way_counts' in d:
        w = ', '.join(f"{k} {v}" for k, v in d['traffic_fastest_way_counts'].items())
        print(f"Patch reads + writes: the fastest way, counted likewise: {w}.")


if __name__ == '__main__':
    main(sys.argv[1] if len(sys.argv) > 1 else 'out/bench.json')
