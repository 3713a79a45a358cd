/* bench.c -- rg2_bench: rg2 grid and per-point evaluation against SISL (s1421, s1506) and
 * OpenCASCADE (Geom_BSplineSurface, GeomAdaptor_Surface, GeomLProp_SLProps) on the same
 * surfaces in the same run, with interleaved repetitions and medians; the memory write ceiling;
 * 1 vs 2 threads; construction time; peak memory; files; picking (rg2_locator's closest point and
 * first ray hit against GeomAPI_ProjectPointOnSurf, GeomAPI_IntCS, IntCurveSurface_HInter, SISL
 * s1954 and s1856). Every method's output is checked (the exact torus, or the independent
 * evaluator rg2_patch_eval) so that a wrong fast path cannot win.
 * Usage: rg2_bench [out.json] [--quick] [--only torus|merged|tessellation|freeform|scaling|
 *                  construction|files|picking]
 */
#define _POSIX_C_SOURCE 200809L
#define _DEFAULT_SOURCE /* madvise */
#include "bench.h"
#include "timing.h"
#include "harness.h"
#include "rg2.h"

#include <cjson/cJSON.h>
#include <math.h>
#include <sisl.h>
#include <stddef.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <pthread.h>
#include <stdatomic.h>
#include <sys/mman.h>
#include <sys/resource.h>
#include <time.h>
#include <unistd.h>
#ifdef _OPENMP
#include <omp.h>
#endif
#if defined(__SSE2__)
#include <emmintrin.h>
#endif

static int quick = 0;            /* --quick: fewer repetitions (smoke test) */
static const char *only = NULL;  /* --only PART: one of torus, merged, tessellation, freeform, scaling,
                                    construction, files, picking */

static int want(const char *part) { return !only || !strcmp(only, part); }

/* The clock of the timings: wall time, except in the single-thread comparisons of run_case,
 * which use the CPU time of the calling thread. On this shared machine a long peer call loses
 * time slices to other processes (a 1 s call at load 3 on 2 cores runs ~70 % of its wall time)
 * while a 0.3 ms grid call mostly does not, which would inflate the ratios; thread CPU time
 * counts only the time the method ran (stalls on memory included). On an idle machine both agree. */
static clockid_t bench_clock = CLOCK_MONOTONIC;

static double now(void) { return bench_seconds(bench_clock); }

static void *xmalloc(size_t bytes)
{
    void *p = malloc(bytes ? bytes : 1);
    if (!p) {
        fprintf(stderr, "rg2_bench: out of memory (%zu bytes)\n", bytes);
        exit(1);
    }
    return p;
}

static long peak_rss_kb(void)
{
    struct rusage ru;
    getrusage(RUSAGE_SELF, &ru);
    return ru.ru_maxrss;
}

/* CPU time the hypervisor gave to other guests while this machine's CPUs wanted to run ("steal",
 * /proc/stat) and all CPU time, in clock ticks, summed over the CPUs; 0, 0 where unknown. On a
 * shared host the peers and rg2 lose different shares of their speed to it, so the report gives
 * it for each part of the run. */
static void host_ticks(double *steal, double *total)
{
    *steal = *total = 0;
    FILE *f = fopen("/proc/stat", "r");
    if (!f)
        return;
    double v[8] = {0};
    if (fscanf(f, "cpu %lf %lf %lf %lf %lf %lf %lf %lf", &v[0], &v[1], &v[2], &v[3], &v[4], &v[5], &v[6], &v[7]) == 8) {
        *steal = v[7];
        for (int k = 0; k < 8; k++)
            *total += v[k];
    }
    fclose(f);
}

/* The share of CPU time stolen since host_ticks gave s0, t0, in percent (-1: unknown). */
static double steal_percent(double s0, double t0)
{
    double s1, t1;
    host_ticks(&s1, &t1);
    return t1 > t0 ? 100.0 * (s1 - s0) / (t1 - t0) : -1.0;
}

static void die_rg2(const char *what, const rg2_error *err)
{
    fprintf(stderr, "rg2_bench: %s: %s\n", what, err->msg);
    exit(1);
}

/* ---- the memory write ceiling --------------------------------------------------------- */

/* 64-byte aligned buffers (outputs and ceiling): the ceiling's vector stores need it, and the
 * grid writes whole cache lines into them too. */
static void *xalloc64(size_t bytes)
{
    void *p = aligned_alloc(64, (bytes + 63) / 64 * 64 + 64);
    if (!p) {
        fprintf(stderr, "rg2_bench: out of memory (%zu bytes)\n", bytes);
        exit(1);
    }
    return p;
}

static volatile double sink;

/* The ways of writing n doubles that the ceiling tries (buf 64-byte aligned, n a multiple of 8). */
static void w_memset(double *buf, size_t n) { memset(buf, 0x5a, n * sizeof(double)); }

static void w_plain(double *buf, size_t n)
{
    for (size_t i = 0; i < n; i++)
        buf[i] = 1.25;
}

#if defined(__GNUC__) && defined(__x86_64__)
#include <immintrin.h>
#define BENCH_X86 1
__attribute__((target("avx2"))) static void w_avx2(double *buf, size_t n)
{
    __m256d v = _mm256_set1_pd(1.5);
    for (size_t i = 0; i + 4 <= n; i += 4)
        _mm256_store_pd(buf + i, v);
}
__attribute__((target("avx512f"))) static void w_avx512(double *buf, size_t n)
{
    __m512d v = _mm512_set1_pd(1.75);
    for (size_t i = 0; i + 8 <= n; i += 8)
        _mm512_store_pd(buf + i, v);
}
/* AVX-512 stores with prefetchw 3 KB ahead (the reads for ownership start early; the grid's
 * plain-store path does the same) */
__attribute__((target("avx512f,prfchw"))) static void w_avx512_pfw(double *buf, size_t n)
{
    __m512d v = _mm512_set1_pd(1.25);
    for (size_t i = 0; i + 8 <= n; i += 8) {
        __builtin_prefetch(buf + i + 384, 1, 3);
        _mm512_store_pd(buf + i, v);
    }
}
__attribute__((target("avx512f"))) static void w_stream512(double *buf, size_t n)
{
    __m512d v = _mm512_set1_pd(2.5);
    for (size_t i = 0; i + 8 <= n; i += 8)
        _mm512_stream_pd(buf + i, v);
    _mm_sfence();
}
#else
#define BENCH_X86 0
#endif

static void w_stream(double *buf, size_t n)
{
#if defined(__SSE2__)
    __m128d v = _mm_set1_pd(1.5);
    for (size_t i = 0; i + 2 <= n; i += 2)
        _mm_stream_pd(buf + i, v);
    _mm_sfence();
#else
    w_plain(buf, n);
#endif
}

/* The grid's memory traffic without its arithmetic: per patch, its 512 bytes read (summed into a
 * stored value, so the loads cannot be dropped) and `per` doubles written to each of the nb
 * outputs (at out[b] + k per) in one of the write ceiling's ways: memset, AVX-512 stores, the
 * same with prefetchw 3 KB ahead, AVX-512 streaming stores (per a multiple of 8, 64-byte aligned
 * outputs), or plain C (any per). */
enum { TW_PLAIN, TW_MEMSET, TW_AVX512, TW_AVX512_PFW, TW_STREAM512, N_TW };
static const char *const tw_name[N_TW] = {"plain stores", "memset", "AVX-512 aligned 64-byte", "AVX-512 + prefetchw",
                                          "AVX-512 streaming"};
#if BENCH_X86
__attribute__((target("avx512f,prfchw"))) static void t_avx512(const rg2_patch *P, size_t np, double *const *out,
                                                               int nb, size_t per, int way)
{
    for (size_t k = 0; k < np; k++) {
        const double *h = &P[k].h[0][0][0];
        __m512d v = _mm512_loadu_pd(h);
        for (int q = 1; q < 8; q++)
            v = _mm512_add_pd(v, _mm512_loadu_pd(h + 8 * q));
        for (int b = 0; b < nb; b++) {
            double *d = out[b] + k * per;
            if (way == TW_MEMSET) {
                memset(d, 0x5a, per * sizeof(double));
                d[0] = _mm512_reduce_add_pd(v);
            } else if (way == TW_STREAM512) {
                for (size_t i = 0; i < per; i += 8)
                    _mm512_stream_pd(d + i, v);
            } else if (way == TW_AVX512_PFW) {
                for (size_t i = 0; i < per; i += 8) {
                    __builtin_prefetch(d + i + 384, 1, 3);
                    _mm512_store_pd(d + i, v);
                }
            } else {
                for (size_t i = 0; i < per; i += 8)
                    _mm512_store_pd(d + i, v);
            }
        }
    }
    _mm_sfence();
}
#endif
static void t_plain(const rg2_patch *P, size_t np, double *const *out, int nb, size_t per)
{
    for (size_t k = 0; k < np; k++) {
        const double *h = &P[k].h[0][0][0];
        double acc[8] = {0};
        for (int q = 0; q < 64; q++) /* 8 independent sums */
            acc[q & 7] += h[q];
        double v = ((acc[0] + acc[1]) + (acc[2] + acc[3])) + ((acc[4] + acc[5]) + (acc[6] + acc[7]));
        for (int b = 0; b < nb; b++)
            for (size_t i = 0; i < per; i++)
                out[b][k * per + i] = v;
    }
}

static int traffic_winner[N_TW]; /* how often each way was the fastest */

/* The fastest of these ways, each once untimed, then timed: how fast any grid evaluator that
 * reads its patches from this surface's array could at best be. */
static double traffic_time(const rg2_patch *P, size_t np, double *const *out, int nb, size_t per)
{
    double best = INFINITY;
    int win = 0;
#if BENCH_X86
    int vec = !(per & 7) && __builtin_cpu_supports("avx512f");
#else
    int vec = 0;
#endif
    for (int way = 0; way < N_TW; way++) {
        if (way != TW_PLAIN && !vec)
            continue;
        double t = 0;
        for (int pass = 0; pass < 2; pass++) {
            t = now();
#if BENCH_X86
            if (way != TW_PLAIN)
                t_avx512(P, np, out, nb, per, way);
            else
#endif
                t_plain(P, np, out, nb, per);
            t = now() - t;
        }
        sink = out[0][per / 2];
        if (t < best)
            best = t, win = way;
    }
    traffic_winner[win]++;
    return best;
}

typedef struct {
    const char *name;
    void (*fn)(double *, size_t);
    const char *cpu; /* required CPU feature, or NULL */
} writer;
static const writer writers[] = {
    {"memset", w_memset, NULL},
    {"plain stores", w_plain, NULL},
    {"SSE2 streaming", w_stream, NULL},
#if BENCH_X86
    {"AVX2 aligned 32-byte", w_avx2, "avx2"},
    {"AVX-512 aligned 64-byte", w_avx512, "avx512f"},
    {"AVX-512 + prefetchw", w_avx512_pfw, "avx512f"},
    {"AVX-512 streaming", w_stream512, "avx512f"},
#endif
};
enum { N_WRITERS = sizeof writers / sizeof writers[0] };
static int ceil_winner[N_WRITERS]; /* how often each way was the fastest */

static int writer_ok(const writer *w)
{
#if BENCH_X86
    if (w->cpu && !strcmp(w->cpu, "avx2"))
        return __builtin_cpu_supports("avx2");
    if (w->cpu && !strcmp(w->cpu, "avx512f"))
        return __builtin_cpu_supports("avx512f");
#endif
    return !w->cpu;
}

/* The write ceiling for nb buffers of bytes[k] each (the very arrays the grid writes): every
 * way of writing, each once untimed (warm: pages touched, lines cached as far as they fit) and
 * then timed; the fastest time. */
static double ceiling_time(double *const *buf, const size_t *bytes, int nb)
{
    double best = INFINITY;
    int win = 0;
    for (int w = 0; w < N_WRITERS; w++) {
        if (!writer_ok(&writers[w]))
            continue;
        for (int k = 0; k < nb; k++)
            writers[w].fn(buf[k], bytes[k] / sizeof(double));
        double t = now();
        for (int k = 0; k < nb; k++)
            writers[w].fn(buf[k], bytes[k] / sizeof(double));
        t = now() - t;
        sink = buf[0][bytes[0] / 16];
        if (t < best)
            best = t, win = w;
    }
    ceil_winner[win]++;
    return best;
}

/* Size in bytes of cpu0's cache of this level (data or unified) from sysfs, as lscpu reads it;
 * glibc's sysconf can report the host's total L3 in a virtual machine (384 MB for a 32 MB one). */
static long sysfs_cache_size(int level)
{
    for (int i = 0; i < 8; i++) {
        char path[96], type[32] = "";
        int lv = 0;
        long kb = 0;
        snprintf(path, sizeof path, "/sys/devices/system/cpu/cpu0/cache/index%d/level", i);
        FILE *f = fopen(path, "r");
        if (!f)
            break;
        int ok = fscanf(f, "%d", &lv) == 1;
        fclose(f);
        snprintf(path, sizeof path, "/sys/devices/system/cpu/cpu0/cache/index%d/type", i);
        if (!ok || lv != level || !(f = fopen(path, "r")))
            continue;
        ok = fscanf(f, "%31s", type) == 1;
        fclose(f);
        snprintf(path, sizeof path, "/sys/devices/system/cpu/cpu0/cache/index%d/size", i);
        if (!ok || !strcmp(type, "Instruction") || !(f = fopen(path, "r")))
            continue;
        ok = fscanf(f, "%ldK", &kb) == 1;
        fclose(f);
        if (ok && kb > 0)
            return kb * 1024;
    }
    return 0;
}

/* Where an output of this many bytes lives: "L2", "L3" or "memory" (sizes from sysfs, else
 * sysconf). */
static const char *cache_level(double bytes)
{
    long l2 = sysfs_cache_size(2), l3 = sysfs_cache_size(3);
    if (l2 <= 0)
        l2 = sysconf(_SC_LEVEL2_CACHE_SIZE);
    if (l3 <= 0)
        l3 = sysconf(_SC_LEVEL3_CACHE_SIZE);
    if (l2 <= 0)
        l2 = 2L << 20;
    /* an L3 reported past 64 MB is a socket's (an AMD EPYC Zen 5 guest reported 508 MB): a core
     * complex shares 32 MB */
    if (l3 <= 0 || l3 > 64L << 20)
        l3 = 32L << 20;
    return bytes <= (double)l2 ? "L2" : bytes <= 0.5 * (double)l3 ? "L3" : "memory";
}

/* ---- surfaces ---------------------------------------------------------------------------- */

/* The B-spline (degree 3, triple interior knots) holding a patchwork exactly. */
static void bspline_from(const rg2_surface *s, bspline *b)
{
    b->spans1 = s->nu;
    b->spans2 = s->nv;
    b->in1 = 3 * s->nu + 1;
    b->in2 = 3 * s->nv + 1;
    b->knots1 = xmalloc(sizeof(double) * (size_t)(b->in1 + 4));
    b->knots2 = xmalloc(sizeof(double) * (size_t)(b->in2 + 4));
    for (int k = 0; k < b->in1 + 4; k++)
        b->knots1[k] = k < 4 ? 0.0 : k >= b->in1 ? s->nu : (double)((k - 1) / 3);
    for (int k = 0; k < b->in2 + 4; k++)
        b->knots2[k] = k < 4 ? 0.0 : k >= b->in2 ? s->nv : (double)((k - 1) / 3);
    b->hcoef = xmalloc(sizeof(double) * 4 * (size_t)b->in1 * (size_t)b->in2);
    for (int J = 0; J < b->in2; J++)
        for (int I = 0; I < b->in1; I++) {
            int i = I / 3 < s->nu ? I / 3 : s->nu - 1, j = J / 3 < s->nv ? J / 3 : s->nv - 1;
            const rg2_patch *P = rg2_surface_patch(s, i, j);
            memcpy(b->hcoef + ((size_t)J * b->in1 + I) * 4, P->h[I - 3 * i][J - 3 * j], sizeof(double) * 4);
        }
}

static void bspline_free(bspline *b)
{
    free(b->knots1);
    free(b->knots2);
    free(b->hcoef);
}

/* A free-form open mesh of nu x nv control points: a smooth height field with random
 * rational weights and random G2 scalars (fixed seed). */
static void freeform_mesh(int nu, int nv, uint64_t seed, rg2_mesh *m)
{
    rg2_error err;
    if (rg2_mesh_init(m, nu, nv, 0, 0, &err))
        die_rg2("free-form mesh", &err);
    rg2t_rng r;
    rg2t_seed(&r, seed);
    rg2_scalars *sc[2] = {&m->su, &m->sv};
    for (int d = 0; d < 2; d++) {
        for (int k = 0; k < rg2_scalars_num_w(sc[d]); k++)
            sc[d]->w[k] = rg2t_uniform(&r, 0.8, 1.25);
        for (int k = 0; k < sc[d]->n; k++) {
            sc[d]->b[k] = rg2t_uniform(&r, 0.8, 1.25);
            sc[d]->g[k] = rg2t_uniform(&r, -0.3, 0.3);
        }
    }
    for (int i = 0; i < nu; i++)
        for (int j = 0; j < nv; j++) {
            double *p = rg2_mesh_at(m, i, j), W = rg2t_uniform(&r, 0.7, 1.4);
            double x = i, y = j, z = 3.0 * sin(0.11 * i) * cos(0.07 * j) + rg2t_uniform(&r, -0.2, 0.2);
            p[0] = W * x, p[1] = W * y, p[2] = W * z, p[3] = W;
        }
}

/* A merged mesh built in code (no design example in main yet): u closed around the axis
 * (8 arcs); v open: 6 rows of the outer half of a torus (R = 3, r = 1) followed by 6 rows of a
 * cylinder of radius 3 rising from the torus top, the torus scalars continued by the uniform
 * B-spline scalars (w = 1, b = 1, g = 0) of the cylinder rows. */
#ifndef RG2_BENCH_DESIGN
static void merged_surface(rg2_surface *out)
{
    const double R = 3.0, r = 1.0;
    rg2_error err;
    int nu = 8, nt = 6, nc = 6, nv = nt + nc;
    double au[8], csu[16], at[7], cst[12];
    for (int i = 0; i < nu; i++)
        au[i] = 2 * M_PI / nu;
    for (int k = 0; k < nt + 1; k++)
        at[k] = M_PI / 6; /* 30 degree arcs starting at -90 degrees */
    rg2_mesh m;
    rg2_scalars st;
    if (rg2_mesh_init(&m, nu, nv, 1, 0, &err) || rg2_circle_coeffs(au, nu, 1, 0.0, csu, &err) ||
        rg2_circle_coeffs(at, nt + 1, 0, -M_PI / 2 - M_PI / 6, cst, &err) ||
        rg2_scalars_from_angles(&st, at, nt + 1, 0, &err))
        die_rg2("merged mesh", &err);
    rg2_scalars_free(&m.su);
    if (rg2_scalars_from_angles(&m.su, au, nu, 1, &err))
        die_rg2("merged mesh", &err);
    for (int k = 0; k < nt + 1; k++)
        m.sv.w[k] = st.w[k];
    for (int k = 0; k < nt; k++) {
        m.sv.b[k] = st.b[k];
        m.sv.g[k] = st.g[k];
    }
    for (int i = 0; i < nu; i++)
        for (int j = 0; j < nv; j++) {
            double *p = rg2_mesh_at(&m, i, j);
            double rad = j < nt ? R + r * cst[2 * j] : R;
            p[0] = rad * csu[2 * i];
            p[1] = rad * csu[2 * i + 1];
            p[2] = j < nt ? r * cst[2 * j + 1] : r + 0.6 * (j - nt + 1);
            p[3] = 1.0;
        }
    if (rg2_surface_build(&m, out, &err))
        die_rg2("merged surface", &err);
    rg2_scalars_free(&st);
    rg2_mesh_free(&m);
}
#endif

/* ---- one benchmark case -------------------------------------------------------------- */

typedef struct {
    const char *name, *what;
    rg2_surface s;
    int torus; /* 1: check against the exact torus (R, r) */
    double R, r, scale;
    int n, reps;
    size_t pts;
    bspline b;
    grid_params g;
    SISLSurf *sisl;
    occt_surf *occt;
    int m1, m2;
    double *x, *y;                           /* SISL grid parameters */
    double *ref_pos, *ref_nrm, *ref_K, *ref_H; /* rg2_patch_eval, patch layout */
    /* output buffers */
    double *pos, *nrm, *K, *H, *eder, *snorm;
} bcase;

enum { LAYOUT_PATCH = 0, LAYOUT_SISL = 1, LAYOUT_NONE = 2 };

typedef struct {
    const double *pos, *nrm, *K, *H;
    int pstride, layout;
} result;

typedef struct {
    const char *name, *peer;
    int level; /* 0 positions, 1 + unit normals, 2 + K and H */
    double (*run)(bcase *c, result *res);
} method;

static double run_grid(bcase *c, int level, result *res)
{
    rg2_grid_out o = {.pos = c->pos};
    if (level >= 1)
        o.normal = c->nrm;
    if (level >= 2)
        o.K = c->K, o.H = c->H;
    rg2_error err;
    /* three untimed calls first: the output in the caches' steady state, as in a viewer that
     * re-tessellates into its buffers, and as the ceiling's buffer after its passes (measured:
     * after a single warm-up call the caches of this machine still give 15-25 % less) */
    for (int w = 0; w < 3; w++)
        if (rg2_surface_grid(&c->s, c->n, c->n, 1, &o, &err))
            die_rg2("rg2_surface_grid", &err);
    double t = now();
    if (rg2_surface_grid(&c->s, c->n, c->n, 1, &o, &err))
        die_rg2("rg2_surface_grid", &err);
    t = now() - t;
    *res = (result){c->pos, c->nrm, c->K, c->H, 3, LAYOUT_PATCH};
    return t;
}
static double m_grid0(bcase *c, result *r) { return run_grid(c, 0, r); }
static double m_grid1(bcase *c, result *r) { return run_grid(c, 1, r); }
static double m_grid2(bcase *c, result *r) { return run_grid(c, 2, r); }

/* Per-point loops over the patch layout. */
#define FOR_POINTS(c)                                                                              \
    for (int pi = 0, idx = 0; pi < (c)->s.nu; pi++)                                              \
        for (int pj = 0; pj < (c)->s.nv; pj++)                                                   \
            for (int a = 0; a < (c)->n; a++)                                                     \
                for (int b = 0; b < (c)->n; b++, idx++)

static double m_point0(bcase *c, result *res)
{
    double t = now();
    FOR_POINTS(c)
    rg2_patch_point(rg2_surface_patch(&c->s, pi, pj), c->g.t[a], c->g.t[b], c->pos + 3 * idx);
    t = now() - t;
    *res = (result){c->pos, NULL, NULL, NULL, 3, LAYOUT_PATCH};
    return t;
}

static double m_point1(bcase *c, result *res)
{
    double t = now();
    FOR_POINTS(c)
    rg2_patch_point_normal(rg2_surface_patch(&c->s, pi, pj), c->g.t[a], c->g.t[b], c->pos + 3 * idx,
                           c->nrm + 3 * idx);
    t = now() - t;
    *res = (result){c->pos, c->nrm, NULL, NULL, 3, LAYOUT_PATCH};
    return t;
}

/* rg2_patch_eval order 2 at every point (the per-point method and the reference). */
static void eval_all(const bcase *c, double *pos, double *nrm, double *K, double *H)
{
    FOR_POINTS(c)
    {
        rg2_eval e;
        rg2_patch_eval(rg2_surface_patch(&c->s, pi, pj), c->g.t[a], c->g.t[b], 2, &e);
        memcpy(pos + 3 * idx, e.p, sizeof e.p);
        memcpy(nrm + 3 * idx, e.n, sizeof e.n);
        K[idx] = e.K;
        H[idx] = e.H;
    }
}

static double m_point2(bcase *c, result *res)
{
    double t = now();
    eval_all(c, c->pos, c->nrm, c->K, c->H);
    t = now() - t;
    *res = (result){c->pos, c->nrm, c->K, c->H, 3, LAYOUT_PATCH};
    return t;
}

static void normalize3(const double *in, double *out)
{
    double l = sqrt(in[0] * in[0] + in[1] * in[1] + in[2] * in[2]);
    double il = l > 0 ? 1.0 / l : 0.0;
    out[0] = in[0] * il, out[1] = in[1] * il, out[2] = in[2] * il;
}

/* Seconds since t0; a SISL error status is reported (and the check will fail). */
static double sisl_elapsed(const char *fn, int stat, double t0)
{
    double t = now() - t0;
    if (stat < 0)
        fprintf(stderr, "rg2_bench: %s status %d\n", fn, stat);
    return t;
}

static double run_s1421(bcase *c, int ider, result *res)
{
    int lk1 = 0, lk2 = 0, stat = 0;
    double der[9], nn[3];
    double t = now();
    FOR_POINTS(c)
    {
        double par[2] = {pi + c->g.t[a], pj + c->g.t[b]};
        s1421(c->sisl, ider, par, &lk1, &lk2, der, nn, &stat);
        memcpy(c->pos + 3 * idx, der, sizeof(double) * 3);
        if (ider)
            normalize3(nn, c->nrm + 3 * idx);
    }
    t = sisl_elapsed("s1421", stat, t);
    *res = (result){c->pos, ider ? c->nrm : NULL, NULL, NULL, 3, LAYOUT_PATCH};
    return t;
}
static double m_s1421_0(bcase *c, result *r) { return run_s1421(c, 0, r); }
static double m_s1421_1(bcase *c, result *r) { return run_s1421(c, 1, r); }

static double run_s1506(bcase *c, int ider, result *res)
{
    int stat = 0;
    double t = now();
    s1506(c->sisl, ider, c->m1, c->x, c->m2, c->y, c->eder, c->snorm, &stat);
    if (ider) /* unit normals, as every other method delivers */
        for (size_t i = 0; i < c->pts; i++)
            normalize3(c->snorm + 3 * i, c->nrm + 3 * i);
    t = sisl_elapsed("s1506", stat, t);
    *res = (result){c->eder, ider ? c->nrm : NULL, NULL, NULL, ider ? 9 : 3, LAYOUT_SISL};
    return t;
}
static double m_s1506_0(bcase *c, result *r) { return run_s1506(c, 0, r); }
static double m_s1506_1(bcase *c, result *r) { return run_s1506(c, 1, r); }

static double run_occt(bcase *c, occt_method meth, result *res)
{
    double t = now();
    occt_eval(c->occt, meth, &c->g, c->pos, c->nrm, c->K, c->H);
    t = now() - t;
    int n1 = meth == OCCT_BSPLINE_D1 || meth == OCCT_ADAPTOR_D1 || meth == OCCT_SLPROPS;
    int kh = meth == OCCT_SLPROPS;
    *res = (result){c->pos, n1 ? c->nrm : NULL, kh ? c->K : NULL, kh ? c->H : NULL, 3, LAYOUT_PATCH};
    return t;
}
static double m_bs_d0(bcase *c, result *r) { return run_occt(c, OCCT_BSPLINE_D0, r); }
static double m_bs_d1(bcase *c, result *r) { return run_occt(c, OCCT_BSPLINE_D1, r); }
static double m_ad_d0(bcase *c, result *r) { return run_occt(c, OCCT_ADAPTOR_D0, r); }
static double m_ad_d1(bcase *c, result *r) { return run_occt(c, OCCT_ADAPTOR_D1, r); }
static double m_slprops(bcase *c, result *r) { return run_occt(c, OCCT_SLPROPS, r); }

static double run_ceiling(bcase *c, int level, result *res)
{
    *res = (result){NULL, NULL, NULL, NULL, 0, LAYOUT_NONE};
    double *bufs[2] = {c->pos, c->nrm};
    size_t bytes[2] = {c->pts * 24, c->pts * 24};
    return ceiling_time(bufs, bytes, level ? 2 : 1);
}
static double m_ceil0(bcase *c, result *r) { return run_ceiling(c, 0, r); }
static double m_ceil1(bcase *c, result *r) { return run_ceiling(c, 1, r); }

static double run_traffic(bcase *c, int level, result *res)
{
    *res = (result){NULL, NULL, NULL, NULL, 0, LAYOUT_NONE};
    double *bufs[2] = {c->pos, c->nrm};
    return traffic_time(c->s.patch, (size_t)c->s.nu * (size_t)c->s.nv, bufs, level ? 2 : 1, 3 * (size_t)c->n * (size_t)c->n);
}
static double m_traffic0(bcase *c, result *r) { return run_traffic(c, 0, r); }
static double m_traffic1(bcase *c, result *r) { return run_traffic(c, 1, r); }

static const method methods[] = {
    {"rg2 grid (rg2_surface_grid)", "rg2", 0, m_grid0},
    {"rg2 grid (rg2_surface_grid)", "rg2", 1, m_grid1},
    {"rg2 grid (rg2_surface_grid)", "rg2", 2, m_grid2},
    {"rg2 per point (rg2_patch_point)", "rg2", 0, m_point0},
    {"rg2 per point (rg2_patch_point_normal)", "rg2", 1, m_point1},
    {"rg2 per point (rg2_patch_eval order 2)", "rg2", 2, m_point2},
    {"SISL s1421 per point", "SISL", 0, m_s1421_0},
    {"SISL s1421 per point", "SISL", 1, m_s1421_1},
    {"SISL s1506 grid, whole surface", "SISL", 0, m_s1506_0},
    {"SISL s1506 grid, whole surface", "SISL", 1, m_s1506_1},
    {"OCCT Geom_BSplineSurface D0/D1", "OpenCASCADE", 0, m_bs_d0},
    {"OCCT Geom_BSplineSurface D0/D1", "OpenCASCADE", 1, m_bs_d1},
    {"OCCT GeomAdaptor_Surface D0/D1", "OpenCASCADE", 0, m_ad_d0},
    {"OCCT GeomAdaptor_Surface D0/D1", "OpenCASCADE", 1, m_ad_d1},
    {"OCCT GeomLProp_SLProps", "OpenCASCADE", 2, m_slprops},
    {"write ceiling (fastest of 7 ways, warm)", "memory", 0, m_ceil0},
    {"write ceiling (fastest of 7 ways, warm)", "memory", 1, m_ceil1},
    {"patch reads + writes, no arithmetic", "memory", 0, m_traffic0},
    {"patch reads + writes, no arithmetic", "memory", 1, m_traffic1},
};
enum {
    M_GRID0, M_GRID1, M_GRID2, M_PT0, M_PT1, M_PT2, M_S1421_0, M_S1421_1, M_S1506_0, M_S1506_1,
    M_BS0, M_BS1, M_AD0, M_AD1, M_SLP, M_CEIL0, M_CEIL1, M_TRAF0, M_TRAF1, N_METHODS
};
static const char *level_name[] = {"position", "position + unit normal", "+ K and H"};

/* Map an output index of a layout to its patch-layout index. */
static size_t to_patch_index(const bcase *c, int layout, size_t i)
{
    if (layout != LAYOUT_SISL)
        return i;
    size_t gi = i % (size_t)c->m1, gj = i / (size_t)c->m1;
    size_t pi = gi / (size_t)c->n, a = gi % (size_t)c->n, pj = gj / (size_t)c->n, b = gj % (size_t)c->n;
    return (((pi * (size_t)c->s.nv + pj) * (size_t)c->n + a) * (size_t)c->n) + b;
}

typedef struct {
    double pos, nrm, K, H;
    int ok;
} check;

/* Worst errors of a result: against the exact torus (implicit equation, exact normal and
 * curvatures at the computed point), or against rg2_patch_eval. Normals compare with sign;
 * H compares in absolute value (orientation conventions differ between libraries). */
static check check_result(const bcase *c, int level, const result *r)
{
    check k = {0, 0, 0, 0, 1};
    if (r->layout == LAYOUT_NONE)
        return k;
    for (size_t i = 0; i < c->pts; i++) {
        const double *p = r->pos + (size_t)r->pstride * i;
        const double *n = r->nrm ? r->nrm + 3 * i : NULL;
        double ep[3], en[3], eK, eH;
        if (c->torus) {
            double rho = hypot(p[0], p[1]), q = rho - c->R;
            double d = fabs(hypot(q, p[2]) - c->r);
            k.pos = fmax(k.pos, d / c->scale);
            double g[3] = {p[0] / rho * q, p[1] / rho * q, p[2]};
            normalize3(g, en);
            double cv = q / c->r;
            eK = cv / (c->r * (c->R + c->r * cv));
            eH = (c->R + 2 * c->r * cv) / (2 * c->r * (c->R + c->r * cv));
            if (n && en[0] * n[0] + en[1] * n[1] + en[2] * n[2] < 0) /* torus normal orientation */
                en[0] = -en[0], en[1] = -en[1], en[2] = -en[2];
            (void)ep;
        } else {
            size_t j = to_patch_index(c, r->layout, i);
            memcpy(ep, c->ref_pos + 3 * j, sizeof ep);
            memcpy(en, c->ref_nrm + 3 * j, sizeof en);
            eK = c->ref_K[j];
            eH = c->ref_H[j];
            double d[3] = {p[0] - ep[0], p[1] - ep[1], p[2] - ep[2]};
            k.pos = fmax(k.pos, sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]) / c->scale);
        }
        if (n && level >= 1) {
            double d[3] = {n[0] - en[0], n[1] - en[1], n[2] - en[2]};
            k.nrm = fmax(k.nrm, sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]));
        }
        if (r->K && level >= 2) {
            double ks = fmax(fabs(eH) + sqrt(fabs(eH * eH - eK)), 1.0 / c->scale);
            k.K = fmax(k.K, fabs(r->K[i] - eK) / (ks * ks));
            k.H = fmax(k.H, fabs(fabs(r->H[i]) - fabs(eH)) / ks);
        }
    }
    k.ok = k.pos <= 1e-11 && k.nrm <= 1e-8 && k.K <= 1e-7 && k.H <= 1e-7;
    return k;
}

static void case_setup(bcase *c, int n, int reps)
{
    c->n = n;
    c->reps = quick ? 3 : reps;
    size_t np = (size_t)c->s.nu * (size_t)c->s.nv;
    c->pts = np * (size_t)n * (size_t)n;
    c->g = (grid_params){c->s.nu, c->s.nv, n, xmalloc(sizeof(double) * (size_t)n)};
    for (int a = 0; a < n; a++)
        c->g.t[a] = a == n - 1 ? 1.0 : (double)a / (n - 1);
    bspline_from(&c->s, &c->b);
    c->sisl = newSurf(c->b.in1, c->b.in2, 4, 4, c->b.knots1, c->b.knots2, c->b.hcoef, 2, 3, 1);
    c->occt = occt_make(&c->b);
    c->m1 = c->s.nu * n;
    c->m2 = c->s.nv * n;
    c->x = xmalloc(sizeof(double) * (size_t)c->m1);
    c->y = xmalloc(sizeof(double) * (size_t)c->m2);
    for (int i = 0; i < c->m1; i++)
        c->x[i] = i / n + c->g.t[i % n];
    for (int j = 0; j < c->m2; j++)
        c->y[j] = j / n + c->g.t[j % n];
    c->pos = xalloc64(c->pts * 3 * sizeof(double));
    c->nrm = xalloc64(c->pts * 3 * sizeof(double));
    c->K = xalloc64(c->pts * sizeof(double));
    c->H = xalloc64(c->pts * sizeof(double));
    c->eder = xalloc64(c->pts * 9 * sizeof(double));
    c->snorm = xalloc64(c->pts * 3 * sizeof(double));
    memset(c->pos, 0, c->pts * 3 * sizeof(double)); /* touch every page before timing */
    memset(c->nrm, 0, c->pts * 3 * sizeof(double));
    memset(c->eder, 0, c->pts * 9 * sizeof(double));
    memset(c->snorm, 0, c->pts * 3 * sizeof(double));
    if (!c->torus) { /* the independent evaluator as the reference */
        c->ref_pos = xmalloc(c->pts * 3 * sizeof(double));
        c->ref_nrm = xmalloc(c->pts * 3 * sizeof(double));
        c->ref_K = xmalloc(c->pts * sizeof(double));
        c->ref_H = xmalloc(c->pts * sizeof(double));
        eval_all(c, c->ref_pos, c->ref_nrm, c->ref_K, c->ref_H);
    }
    if (c->scale == 0)
        c->scale = rg2t_surface_scale(&c->s);
}

static void case_free(bcase *c)
{
    freeSurf(c->sisl);
    occt_free(c->occt);
    bspline_free(&c->b);
    free(c->g.t);
    free(c->x);
    free(c->y);
    free(c->pos), free(c->nrm), free(c->K), free(c->H), free(c->eder), free(c->snorm);
    free(c->ref_pos), free(c->ref_nrm), free(c->ref_K), free(c->ref_H);
    rg2_surface_free(&c->s);
}

/* Ratio pairs (a over b) with the issue's targets (0: informative). */
typedef struct {
    int a, b;
    double target;
    const char *label;
} pair;
static const pair pairs[] = {
    {M_GRID0, M_S1506_0, 25, "grid positions / SISL s1506"},
    {M_GRID0, M_AD0, 60, "grid positions / GeomAdaptor D0"},
    {M_GRID1, M_S1506_1, 30, "grid pos+normals / SISL s1506"},
    {M_GRID1, M_AD1, 50, "grid pos+normals / GeomAdaptor D1"},
    {M_GRID2, M_SLP, 50, "grid with K, H / GeomLProp_SLProps"},
    {M_GRID0, M_S1421_0, 0, "grid positions / SISL s1421"},
    {M_GRID0, M_BS0, 0, "grid positions / Geom_BSplineSurface D0"},
    {M_GRID1, M_S1421_1, 0, "grid pos+normals / SISL s1421"},
    {M_GRID1, M_BS1, 0, "grid pos+normals / Geom_BSplineSurface D1"},
    {M_PT0, M_S1421_0, 0, "per point positions / SISL s1421"},
    {M_PT0, M_AD0, 0, "per point positions / GeomAdaptor D0"},
    {M_PT1, M_S1421_1, 0, "per point pos+normals / SISL s1421"},
    {M_PT1, M_AD1, 0, "per point pos+normals / GeomAdaptor D1"},
    {M_PT2, M_SLP, 0, "per point with K, H / GeomLProp_SLProps"},
    {M_GRID0, M_CEIL0, 0, "grid positions / write ceiling"},
    {M_GRID1, M_CEIL1, 0, "grid pos+normals / write ceiling"},
    {M_GRID0, M_TRAF0, 0, "grid positions / patch reads + writes"},
    {M_GRID1, M_TRAF1, 0, "grid pos+normals / patch reads + writes"},
};

static cJSON *run_case(bcase *c)
{
    int nm = N_METHODS, reps = c->reps;
    double *times = xmalloc(sizeof(double) * (size_t)(nm * reps));
    check chk[N_METHODS];
    printf("\n== %s: %s\n   %d x %d patches, %d x %d points per patch = %zu points, %d interleaved repetitions\n"
           "   output %.1f MB positions (fits %s), %.1f MB with normals (fits %s); rg2 grid timed after 3 untimed "
           "calls, the ceiling after a warm pass per way\n",
           c->name, c->what, c->s.nu, c->s.nv, c->n, c->n, c->pts, reps, c->pts * 24e-6, cache_level(c->pts * 24.0),
           c->pts * 48e-6, cache_level(c->pts * 48.0));
    fflush(stdout);
    bench_clock = CLOCK_THREAD_CPUTIME_ID; /* every method here runs on this one thread */
    double steal0, total0;
    host_ticks(&steal0, &total0);
    for (int rep = 0; rep < reps; rep++)
        for (int k = 0; k < nm; k++) {
            result r;
            times[k * reps + rep] = methods[k].run(c, &r);
            if (rep == 0)
                chk[k] = check_result(c, methods[k].level, &r);
        }
    bench_clock = CLOCK_MONOTONIC;
    double steal = steal_percent(steal0, total0);
    cJSON *jc = cJSON_CreateObject();
    cJSON_AddStringToObject(jc, "name", c->name);
    cJSON_AddStringToObject(jc, "surface", c->what);
    cJSON_AddNumberToObject(jc, "patches", (double)c->s.nu * c->s.nv);
    cJSON_AddNumberToObject(jc, "points_per_patch", (double)c->n * c->n);
    cJSON_AddNumberToObject(jc, "points", (double)c->pts);
    cJSON_AddNumberToObject(jc, "repetitions", reps);
    cJSON_AddStringToObject(jc, "checked_against", c->torus ? "exact torus" : "rg2_patch_eval");
    cJSON_AddStringToObject(jc, "positions_fit", cache_level(c->pts * 24.0));
    cJSON_AddStringToObject(jc, "normals_fit", cache_level(c->pts * 48.0));
    cJSON *jm = cJSON_AddArrayToObject(jc, "methods");
    double mpts[N_METHODS];
    cJSON_AddStringToObject(jc, "clock", "CPU time of the calling thread (CLOCK_THREAD_CPUTIME_ID)");
    printf("   times: CPU time of the calling thread (time slices lost to other processes do not count)\n");
    if (steal >= 0) {
        printf("   host: %.1f %% of this machine's CPU time went to other guests during this case (steal)\n", steal);
        cJSON_AddNumberToObject(jc, "host_steal_percent", steal);
    }
    printf("   %-42s %-24s %10s %10s  %-9s %-9s %-9s %s\n", "method", "output", "median ms", "M pts/s",
           "pos err", "nrm err", "K,H err", "check");
    for (int k = 0; k < nm; k++) {
        double med = bench_median(times + k * reps, reps);
        mpts[k] = (double)c->pts / med / 1e6;
        const check *q = &chk[k];
        printf("   %-42s %-24s %10.3f %10.1f  %-9.1e %-9.1e %-9.1e %s\n", methods[k].name,
               level_name[methods[k].level], med * 1e3, mpts[k], q->pos, q->nrm, fmax(q->K, q->H),
               methods[k].peer[0] == 'm' ? "-" : q->ok ? "ok" : "WRONG");
        cJSON *o = cJSON_CreateObject();
        cJSON_AddStringToObject(o, "method", methods[k].name);
        cJSON_AddStringToObject(o, "peer", methods[k].peer);
        cJSON_AddStringToObject(o, "output", level_name[methods[k].level]);
        cJSON_AddNumberToObject(o, "median_s", med);
        cJSON_AddNumberToObject(o, "mpoints_per_s", mpts[k]);
        cJSON_AddNumberToObject(o, "max_pos_err_rel", q->pos);
        cJSON_AddNumberToObject(o, "max_normal_err", q->nrm);
        cJSON_AddNumberToObject(o, "max_K_err_rel", q->K);
        cJSON_AddNumberToObject(o, "max_H_err_rel", q->H);
        cJSON_AddBoolToObject(o, "output_correct", q->ok);
        cJSON_AddItemToArray(jm, o);
    }
    printf("   ratios (same run, medians, single thread):\n");
    cJSON *jr = cJSON_AddArrayToObject(jc, "ratios");
    for (size_t p = 0; p < sizeof pairs / sizeof pairs[0]; p++) {
        double ratio = mpts[pairs[p].a] / mpts[pairs[p].b];
        int valid = chk[pairs[p].a].ok && chk[pairs[p].b].ok;
        printf("     %-44s %8.2fx", pairs[p].label, ratio);
        /* the most any method writing the same bytes could reach (write ceiling / peer), and any
         * that also reads this surface's patches (patch reads + writes / peer, at most the former) */
        int grid = pairs[p].a == M_GRID0 ? 0 : pairs[p].a == M_GRID1 ? 1 : -1;
        int peer = grid >= 0 && pairs[p].b != M_CEIL0 + grid && pairs[p].b != M_TRAF0 + grid;
        double bound = peer ? mpts[M_CEIL0 + grid] / mpts[pairs[p].b] : 0;
        double tbound = peer ? fmin(mpts[M_CEIL0 + grid], mpts[M_TRAF0 + grid]) / mpts[pairs[p].b] : 0;
        /* a target above the bound with patch reads is out of reach for any method in this run */
        int reachable = bound <= 0 || tbound >= pairs[p].target;
        if (pairs[p].target > 0)
            printf("   target >= %gx: %-12s", pairs[p].target,
                   !valid                      ? "INVALID"
                   : ratio >= pairs[p].target ? "met"
                   : reachable                ? "missed"
                                              : "out of reach");
        if (bound > 0)
            printf("   (write ceiling allows %.1fx, with patch reads %.1fx)", bound, tbound);
        printf("\n");
        cJSON *o = cJSON_CreateObject();
        cJSON_AddStringToObject(o, "pair", pairs[p].label);
        cJSON_AddNumberToObject(o, "ratio", ratio);
        if (bound > 0) {
            cJSON_AddNumberToObject(o, "write_ceiling_bound", bound);
            cJSON_AddNumberToObject(o, "traffic_bound", tbound);
        }
        if (pairs[p].target > 0) {
            cJSON_AddNumberToObject(o, "target", pairs[p].target);
            cJSON_AddBoolToObject(o, "met", valid && ratio >= pairs[p].target);
            cJSON_AddBoolToObject(o, "reachable", reachable);
        }
        cJSON_AddItemToArray(jr, o);
    }
    free(times);
    return jc;
}

/* ---- 1 vs 2 threads; main-memory sizes ---------------------------------------------------- */

/* A thread that keeps one core busy (as another process would) while `spin` is set. */
static atomic_int spin;
static void *spinner(void *unused)
{
    (void)unused;
    volatile unsigned long x = 0;
    while (atomic_load_explicit(&spin, memory_order_relaxed))
        x++;
    return NULL;
}

/* The host's parallelism at this moment: a fixed loop of vector multiply-adds (12 independent
 * chains, no memory: the grid kernels' kind of work) on one thread, then on two threads at once;
 * returns 2 t1 / t2, about 2 when the machine's two vCPUs run on two cores, about 1 when the
 * host has put them on the two hardware threads of one core (they then share its multiply-add
 * pipes: seen here for minutes at a time, 2 x 3.2 ms alone against 6.0 ms together) or lets one
 * wait: then no code gets 2 threads' worth of arithmetic. Neither the host's steal time nor a
 * scalar loop shows the shared core; this does. Median of 5 (each thread times its own loop,
 * both starting together, so the second vCPU's wake-up does not count). */
#if defined(__GNUC__) && defined(__x86_64__)
__attribute__((noinline, target("avx512f"))) static double fma_chains_avx512(void)
{
    __m512d a[12], m = _mm512_set1_pd(0.999999), c = _mm512_set1_pd(1e-9);
    for (int k = 0; k < 12; k++)
        a[k] = _mm512_set1_pd(k);
    for (long i = 0; i < 100000; i++) {
        for (int k = 0; k < 12; k++)
            a[k] = _mm512_fmadd_pd(a[k], m, c);
        __asm__("" : "+v"(a[0]), "+v"(a[1]), "+v"(a[2]), "+v"(a[3]), "+v"(a[4]), "+v"(a[5]));
        __asm__("" : "+v"(a[6]), "+v"(a[7]), "+v"(a[8]), "+v"(a[9]), "+v"(a[10]), "+v"(a[11]));
    }
    double s = 0;
    for (int k = 0; k < 12; k++)
        s += _mm512_reduce_add_pd(a[k]);
    return s;
}
#define HAVE_FMA_CHAINS_AVX512 1
#endif

/* One run of the multiply-add loop; with a start line (both threads at once), its own time. */
typedef struct {
    atomic_int *start; /* NULL: alone */
    double t, sum;
} fma_run;

__attribute__((noinline)) static void *fma_loop(void *arg)
{
    fma_run *r = arg;
    if (r->start) { /* both threads begin together, whenever the second vCPU is woken */
        atomic_fetch_add(r->start, 1);
        while (atomic_load(r->start) < 2)
            ;
    }
    double t0 = bench_seconds(CLOCK_MONOTONIC);
#ifdef HAVE_FMA_CHAINS_AVX512
    if (__builtin_cpu_supports("avx512f")) {
        r->sum = fma_chains_avx512();
        r->t = bench_seconds(CLOCK_MONOTONIC) - t0;
        return NULL;
    }
#endif
    double a[8] = {1, 2, 3, 4, 5, 6, 7, 8}, m = 0.999999, c = 1e-9;
    for (long i = 0; i < 1000000; i++)
        for (int k = 0; k < 8; k++)
            a[k] = fma(a[k], m, c);
    r->sum = 0;
    for (int k = 0; k < 8; k++)
        r->sum += a[k];
    r->t = bench_seconds(CLOCK_MONOTONIC) - t0;
    return NULL;
}

/* t1 / t_a + t1 / t_b: the two threads' speeds together, each over its speed alone. */
static double host_parallelism(void)
{
    double r[5];
    for (int k = 0; k < 5; k++) {
        fma_run alone = {NULL, 0, 0};
        fma_loop(&alone);
        atomic_int start = 0;
        fma_run a = {&start, 0, 0}, b = {&start, 0, 0};
        pthread_t th;
        if (pthread_create(&th, NULL, fma_loop, &b)) {
            r[k] = 1.0;
            continue;
        }
        fma_loop(&a);
        pthread_join(th, NULL);
        sink += alone.sum + a.sum + b.sum;
        r[k] = alone.t / a.t + alone.t / b.t;
    }
    return bench_median(r, 5);
}

#define WARM_CALLS 4 /* untimed calls before each timed one of the threads table, in-cache sizes */

/* Median time of 1- and 2-thread calls (alternating pairs) while another thread spins. */
static void busy_core_times(const rg2_surface *torus, int n, const rg2_grid_out *o, int reps, int warm, double *m1,
                            double *m2)
{
    double *t = xmalloc(sizeof(double) * 2 * (size_t)reps);
    pthread_t tid;
    atomic_store(&spin, 1);
    if (pthread_create(&tid, NULL, spinner, NULL)) {
        fprintf(stderr, "rg2_bench: cannot start a thread\n");
        exit(1);
    }
    rg2_error err;
    for (int rep = 0; rep < reps; rep++)
        for (int th = 1; th <= 2; th++) { /* as in threads_row: untimed calls, timed call */
            for (int w = 0; w < warm; w++)
                if (rg2_surface_grid(torus, n, n, th, o, &err))
                    die_rg2("rg2_surface_grid", &err);
            double t0 = now();
            if (rg2_surface_grid(torus, n, n, th, o, &err))
                die_rg2("rg2_surface_grid", &err);
            t[(th - 1) * reps + rep] = now() - t0;
        }
    atomic_store(&spin, 0);
    pthread_join(tid, NULL);
    *m1 = bench_median(t, reps);
    *m2 = bench_median(t + reps, reps);
    free(t);
}

/* One row of the 1 vs 2 threads table, measured once (one round). */
typedef struct {
    double m1, m2;       /* M points/s, medians of the 1- and 2-thread calls */
    double paired;       /* median of the ratios of paired calls */
    double fastest;      /* ratio of the fastest calls */
    double busy;         /* 2t / 1t with the second core busy */
    double mc, frac;     /* the write ceiling (M points/s) and 1 thread's fraction of it; NaN for K, H */
    double steal, par;   /* host steal % during the calls; the host probe (lower of before and after) */
    double alone0, alone1; /* M points/s of 1-thread calls pinned to the first and second CPU */
    double eff;          /* 2 threads over the two CPUs' speeds alone added up */
} thread_row;

static int cpus[2], ncpus; /* the first two CPUs the bench may run on */

/* M points/s of 1-thread calls with the caller pinned to CPU cpu (NaN if it cannot be pinned).
 * Pinned only around these calls: the pool's worker, created earlier, keeps its own affinity. */
static double alone_on(int cpu, const rg2_surface *torus, int n, const rg2_grid_out *o, int reps, double *t)
{
    size_t pts = (size_t)torus->nu * torus->nv * n * n;
    rg2_error err;
    if (bench_pin(cpu))
        return NAN;
    for (int w = 0; w < 3; w++) /* its lines into this core's cache, as in run_grid */
        if (rg2_surface_grid(torus, n, n, 1, o, &err))
            die_rg2("rg2_surface_grid", &err);
    for (int rep = 0; rep < reps; rep++) {
        double t0 = now();
        if (rg2_surface_grid(torus, n, n, 1, o, &err))
            die_rg2("rg2_surface_grid", &err);
        t[rep] = now() - t0;
    }
    bench_unpin();
    return pts / bench_median(t, reps) / 1e6;
}

static void threads_row(const rg2_surface *torus, int n, int level, double *pos, double *nrm, double *K, double *H,
                        thread_row *row)
{
    size_t pts = (size_t)torus->nu * torus->nv * n * n;
    /* calls of 0.02-1 ms below 256^2: enough of them to span about 0.1 s */
    int reps = quick ? 5 : n >= 256 ? 9 : n >= 64 ? 101 : 301, warm = n >= 256 ? 1 : WARM_CALLS;
    rg2_grid_out o = {.pos = pos, .normal = level ? nrm : NULL, .K = level > 1 ? K : NULL, .H = level > 1 ? H : NULL};
    double *t1 = xmalloc(sizeof(double) * (size_t)reps * 6), *t2 = t1 + reps, *tc = t2 + reps, *t3 = tc + reps;
    double *pr = t3 + reps, *ta = pr + reps;
    double best[2] = {0, 0};
    rg2_error err;
    /* untimed calls first, as in run_grid: the output in the caches' steady state and the
     * pool's worker created before the first timed 2-thread call; for 20 ms at least,
     * so that the worker's vCPU is running (the first configuration of a run measured
     * 1.79x after 3 warm-up calls, 1.91x when run again right after) */
    double w0 = now();
    for (int w = 0; w < 3 || now() - w0 < 0.02; w++)
        for (int th = 1; th <= 2; th++)
            if (rg2_surface_grid(torus, n, n, th, &o, &err))
                die_rg2("rg2_surface_grid", &err);
    double steal0, total0, par0 = host_parallelism();
    host_ticks(&steal0, &total0);
    for (int rep = 0; rep < reps; rep++) { /* interleaved */
        /* 1 and 2 threads alternating, each timed call right after untimed ones with the
         * same thread count: an application evaluates into the same arrays with the same
         * threads call after call, each thread then finding its part of them in its own
         * core's cache, while a call right after one with the other thread count first
         * fetches half of its lines from the other core (32^2 positions, 1 thread: 37
         * instead of 29 us when the two alternated call by call). Outputs that stay in the
         * caches take WARM_CALLS calls to come back to that state: on the AMD Zen 5 machine
         * 2 threads made 1.28x one at 32^2 positions after 1 untimed call, 1.53x after 2,
         * 1.65x after 4, 1.62x after 8 (64^2: 1.48x, 1.57x, 1.76x, 1.78x) */
        for (int th = 1; th <= 2; th++) {
            for (int w = 0; w < warm; w++)
                if (rg2_surface_grid(torus, n, n, th, &o, &err))
                    die_rg2("rg2_surface_grid", &err);
            double t0 = now();
            if (rg2_surface_grid(torus, n, n, th, &o, &err))
                die_rg2("rg2_surface_grid", &err);
            double t = now() - t0;
            (th == 1 ? t1 : t2)[rep] = t;
            best[th - 1] = rep == 0 ? t : fmin(best[th - 1], t);
        }
    }
    row->steal = steal_percent(steal0, total0);
    row->par = fmin(par0, host_parallelism());
    /* the ceiling in its own loop: between the grid calls it would let the pool's worker
     * fall asleep, and every 2-thread call would then pay a wake-up (milliseconds when
     * the machine is loaded); alternated with 1-thread grid calls for the same load */
    for (int rep = 0; rep < reps; rep++) {
        double *bufs[2] = {pos, nrm};
        size_t bytes[2] = {pts * 24, pts * 24};
        tc[rep] = ceiling_time(bufs, bytes, level ? 2 : 1);
        for (int w = 0; w < 3; w++) /* steady state, as in run_grid */
            if (rg2_surface_grid(torus, n, n, 1, &o, &err))
                die_rg2("rg2_surface_grid", &err);
        double t0 = now();
        if (rg2_surface_grid(torus, n, n, 1, &o, &err))
            die_rg2("rg2_surface_grid", &err);
        t3[rep] = now() - t0;
    }
    /* the same with the second core busy: the pool's caller never waits for a worker that
     * has no core, so 2 threads should cost no more than 1 */
    double bt1, bt2;
    busy_core_times(torus, n, &o, reps, warm, &bt1, &bt2);
    /* each CPU alone: a host may give the two vCPUs unequal shares of their cores (on the AMD
     * Zen 5 machine the second ran these kernels 18-35 % slower at times); 2 threads then make
     * at most the two speeds added up, and the pool's efficiency is how much of that sum they
     * got */
    row->alone0 = ncpus == 2 ? alone_on(cpus[0], torus, n, &o, reps, ta) : NAN;
    row->alone1 = ncpus == 2 ? alone_on(cpus[1], torus, n, &o, reps, ta) : NAN;
    row->m1 = pts / bench_median(t1, reps) / 1e6;
    row->m2 = pts / bench_median(t2, reps) / 1e6;
    double mc = pts / bench_median(tc, reps) / 1e6, m3 = pts / bench_median(t3, reps) / 1e6;
    row->mc = level < 2 ? mc : NAN;
    row->frac = level < 2 ? m3 / mc : NAN;
    row->fastest = best[0] / best[1]; /* fastest single calls */
    row->busy = bt1 / bt2;
    /* the ratio of each 1-thread call to the 2-thread call right after it (tens of
     * microseconds apart), then the median: the speedup at one moment, which the ratio
     * of the two medians is not when the host's load drifts during the loop */
    for (int rep = 0; rep < reps; rep++)
        pr[rep] = t1[rep] / t2[rep];
    row->paired = bench_median(pr, reps);
    row->eff = row->m2 / (row->alone0 + row->alone1);
    free(t1);
}

#define THREAD_ROUNDS 3

/* The median over `rounds` rounds of the double at offset `field` of thread_row. */
static double round_median(const thread_row *r, int rounds, size_t field)
{
    double v[THREAD_ROUNDS];
    for (int k = 0; k < rounds; k++)
        v[k] = *(const double *)((const char *)&r[k] + field);
    return bench_median(v, rounds);
}

static cJSON *threads_and_sizes(const rg2_surface *torus)
{
    cJSON *j = cJSON_CreateObject();
    cJSON *jt = cJSON_AddArrayToObject(j, "threads");
    int sizes[] = {32, 64, 256}, rounds = quick ? 1 : THREAD_ROUNDS;
    ncpus = bench_cpus(cpus, 2);
    thread_row rows[3][3][THREAD_ROUNDS];
    /* the whole table `rounds` times over, and each figure the median of its rounds: a row
     * measured in one stretch of 0.1-1 s took the host's state of that stretch (on the AMD Zen 4
     * machine the same row, 64^2 with normals, gave 1.57x in one run and 1.83x and 1.85x in the
     * runs right before and after it, the host probe at 1.97-2.00 in all three) */
    for (int round = 0; round < rounds; round++)
        for (int si = 0; si < 3; si++) {
            int n = sizes[si];
            size_t pts = (size_t)torus->nu * torus->nv * n * n;
            double *pos = xalloc64(pts * 24), *nrm = xalloc64(pts * 24), *K = xalloc64(pts * 8), *H = xalloc64(pts * 8);
            memset(pos, 0, pts * 24), memset(nrm, 0, pts * 24), memset(K, 0, pts * 8), memset(H, 0, pts * 8);
            for (int level = 0; level < 3; level++)
                threads_row(torus, n, level, pos, nrm, K, H, &rows[si][level][round]);
            free(pos), free(nrm), free(K), free(H);
        }
    printf("\n== rg2 grid on the torus: 1 vs 2 threads (single calls alternating), and the write ceiling at "
           "each output size\n");
    printf("   (each figure the median of %d rounds of the whole table, spread over the run; paired: the median "
           "ratio of\n    a 1-thread call to the 2-thread call right after it, and in brackets that of each round;\n",
           rounds);
    printf("    steal %%: CPU time of this machine's 2 vCPUs that went to other guests while the 1- and 2-thread "
           "calls ran,\n    the most of the rounds; host 2t: what 2 threads of pure vector multiply-adds got over 1, "
           "the lowest\n    of before and after those calls in all rounds: about 1 when the host runs both vCPUs on one "
           "core, about 2 on two;\n    cpu N alone: M points/s of 1-thread calls pinned to that CPU; 2t/sum: 2 threads over those "
           "two speeds added up,\n    what 2 threads can make at most when the host gives the two vCPUs unequal "
           "shares of their cores)\n");
    char a0[16] = "cpu ? alone", a1[16] = "cpu ? alone";
    if (ncpus == 2) {
        snprintf(a0, sizeof a0, "cpu %d alone", cpus[0]);
        snprintf(a1, sizeof a1, "cpu %d alone", cpus[1]);
    }
    printf("   %-9s %-24s %12s %12s %8s %8s %-16s %10s %14s %10s  %-17s %s %s %12s %12s %7s\n", "per patch", "output",
           "1 thr Mpt/s", "2 thr Mpt/s", "2t/1t", "(paired)", "(rounds)", "(2nd busy)", "ceiling Mpt/s", "1t/ceil",
           "output fits", "steal %", "host 2t", a0, a1, "2t/sum");
    for (int si = 0; si < 3; si++)
        for (int level = 0; level < 3; level++) {
            const thread_row *r = rows[si][level];
            int n = sizes[si];
            size_t pts = (size_t)torus->nu * torus->nv * n * n;
#define MED(f) round_median(r, rounds, offsetof(thread_row, f))
            thread_row md = {MED(m1),     MED(m2),     MED(paired), MED(fastest), MED(busy),
                             MED(mc),     MED(frac),   r[0].steal,  r[0].par,     MED(alone0),
                             MED(alone1), MED(eff)};
#undef MED
            for (int k = 1; k < rounds; k++) {
                md.steal = fmax(md.steal, r[k].steal);
                md.par = fmin(md.par, r[k].par);
            }
            char each[64] = "", *e = each;
            for (int k = 0; k < rounds; k++)
                e += snprintf(e, sizeof each - (size_t)(e - each), "%s%.2f", k ? " " : "(", r[k].paired);
            snprintf(e, sizeof each - (size_t)(e - each), ")");
            char steal[16] = "-"; /* (unknown: no /proc/stat, or no tick during a short --quick row) */
            if (md.steal >= 0)
                snprintf(steal, sizeof steal, "%.1f", md.steal);
            double obytes = (double)pts * (level == 0 ? 24 : level == 1 ? 48 : 64);
            printf("   %4d^2    %-24s %12.1f %12.1f %7.2fx %7.2fx %-16s %9.2fx %14.1f %10.2f   %.1f MB, %-6s "
                   "%5s %7.2fx %12.1f %12.1f %7.2f\n",
                   n, level_name[level], md.m1, md.m2, md.m2 / md.m1, md.paired, each, md.busy, md.mc, md.frac,
                   obytes * 1e-6, cache_level(obytes), steal, md.par, md.alone0, md.alone1, md.eff);
            cJSON *o2 = cJSON_CreateObject();
            cJSON_AddNumberToObject(o2, "points_per_patch_side", n);
            cJSON_AddStringToObject(o2, "output", level_name[level]);
            cJSON_AddNumberToObject(o2, "output_bytes", obytes);
            cJSON_AddStringToObject(o2, "output_fits", cache_level(obytes));
            cJSON_AddNumberToObject(o2, "rounds", rounds);
            cJSON_AddNumberToObject(o2, "mpoints_per_s_1_thread", md.m1);
            cJSON_AddNumberToObject(o2, "mpoints_per_s_2_threads", md.m2);
            cJSON_AddNumberToObject(o2, "speedup_2_threads", md.m2 / md.m1);
            cJSON_AddNumberToObject(o2, "speedup_2_threads_paired", md.paired);
            cJSON *jr = cJSON_AddArrayToObject(o2, "speedup_2_threads_paired_rounds");
            for (int k = 0; k < rounds; k++)
                cJSON_AddItemToArray(jr, cJSON_CreateNumber(r[k].paired));
            cJSON_AddNumberToObject(o2, "speedup_2_threads_fastest_calls", md.fastest);
            cJSON_AddNumberToObject(o2, "speedup_2_threads_second_core_busy", md.busy);
            if (md.steal >= 0)
                cJSON_AddNumberToObject(o2, "host_steal_percent", md.steal);
            cJSON_AddNumberToObject(o2, "host_parallelism_2_threads", md.par);
            if (ncpus == 2) {
                cJSON *ja = cJSON_AddArrayToObject(o2, "mpoints_per_s_1_thread_pinned");
                double al[2] = {md.alone0, md.alone1};
                for (int c = 0; c < 2; c++) {
                    cJSON *jc = cJSON_CreateObject();
                    cJSON_AddNumberToObject(jc, "cpu", cpus[c]);
                    cJSON_AddNumberToObject(jc, "mpoints_per_s", al[c]);
                    cJSON_AddItemToArray(ja, jc);
                }
                cJSON_AddNumberToObject(o2, "efficiency_2_threads_of_both_cpus_alone", md.eff);
            }
            if (level < 2) {
                cJSON_AddNumberToObject(o2, "ceiling_mpoints_per_s", md.mc);
                cJSON_AddNumberToObject(o2, "fraction_of_ceiling_1_thread", md.frac);
            }
            cJSON_AddItemToArray(jt, o2);
        }
    return j;
}

/* ---- construction time ------------------------------------------------------------------ */

/* Seconds to write `bytes` of fresh memory once, allocated as rg2's big arrays are (2 MiB aligned,
 * advised as huge pages, populated, then written): what any program pays for memory that is new
 * to it, whatever it computes. */
static double first_touch(size_t bytes)
{
    size_t whole = (bytes + ((size_t)2 << 20) - 1) & ~(((size_t)2 << 20) - 1);
    void *p = NULL;
    if (posix_memalign(&p, (size_t)2 << 20, whole) != 0) {
        fprintf(stderr, "rg2_bench: out of memory (%zu bytes)\n", whole);
        exit(1);
    }
    double t0 = bench_seconds(CLOCK_MONOTONIC);
#if defined(__linux__) && defined(MADV_HUGEPAGE)
    (void)madvise(p, whole, MADV_HUGEPAGE);
#ifdef MADV_POPULATE_WRITE
    (void)madvise(p, whole, MADV_POPULATE_WRITE);
#endif
#endif
    memset(p, 1, bytes);
    double t = bench_seconds(CLOCK_MONOTONIC) - t0;
    free(p);
    return t;
}

/* The build of the largest mesh once "cold", after 3 s with nothing allocated: memory as a new
 * process gets it. A virtual machine whose kernel hands memory freed for about 2 s back to its
 * host (free page reporting) pays the host's first touch of every page again; the interleaved
 * batches above reuse memory freed a moment before and do not. Alternated twice with a first
 * touch of the same bytes after the same pause (first_touch): the part of the cold build that is
 * the memory's, not rg2's. */
static cJSON *construction_cold(int size)
{
    rg2_mesh m;
    rg2_error err;
    freeform_mesh(size, size, 1000 + 4, &m);
    size_t bytes = (size_t)(size - 3) * (size_t)(size - 3) * 16 * 4 * sizeof(double); /* the patches */
#ifdef _OPENMP
    omp_set_num_threads(1);
#endif
    double build[2], touch[2];
    for (int k = 0; k < 2; k++) {
        rg2_surface surf;
        sleep(3);
        double t0 = bench_seconds(CLOCK_MONOTONIC);
        if (rg2_surface_build(&m, &surf, &err))
            die_rg2("rg2_surface_build", &err);
        build[k] = bench_seconds(CLOCK_MONOTONIC) - t0;
        rg2_surface_free(&surf);
        sleep(3);
        touch[k] = first_touch(bytes);
    }
#ifdef _OPENMP
    omp_set_num_threads(2);
#endif
    rg2_mesh_free(&m);
    printf("   cold, after 3 s with nothing allocated (memory as a new process gets it), 1 thread, twice:\n"
           "   build %d x %d %.3f s and %.3f s; writing its %.0f MB of patches once, fresh, after the same\n"
           "   pause: %.3f s and %.3f s (the memory's part, whatever the program computes)\n",
           size, size, build[0], build[1], bytes / 1e6, touch[0], touch[1]);
    cJSON *o = cJSON_CreateObject();
    cJSON_AddNumberToObject(o, "control_points", (double)size * size);
    cJSON_AddItemToObject(o, "build_s", cJSON_CreateDoubleArray(build, 2));
    cJSON_AddItemToObject(o, "first_touch_s", cJSON_CreateDoubleArray(touch, 2));
    cJSON_AddNumberToObject(o, "bytes", (double)bytes);
    return o;
}

static cJSON *construction(void)
{
    int sizes[] = {10, 32, 100, 316, 1000};
    int ns = 5, reps = quick ? 3 : 7;
    rg2_mesh meshes[5];
    for (int s = 0; s < ns; s++)
        freeform_mesh(sizes[s], sizes[s], 1000 + s, &meshes[s]);
    /* t[((s * 2 + th) * 2 + kind) * reps + rep]: kind 0 rg2_surface_build (fresh memory each time),
     * kind 1 rg2_surface_rebuild into the surface of the previous call (an editing loop) */
    double *t = xmalloc(sizeof(double) * (size_t)(ns * reps * 4));
    printf("\n== construction (mesh -> patches), free-form open meshes, %d interleaved repetitions of batches:\n"
           "   rg2_surface_build (fresh memory: its page faults included) and rg2_surface_rebuild (into the\n"
           "   previous surface's memory, as in an editing loop)\n", reps);
    printf("   %-12s %10s %13s %13s %13s %13s %13s\n", "control pts", "patches", "build 1t ms", "ns / ctrl pt",
           "build 2t ms", "rebuild 1t ms", "ns / ctrl pt");
    for (int rep = 0; rep < reps; rep++)
        for (int s = 0; s < ns; s++)
            for (int th = 0; th < 2; th++) {
#ifdef _OPENMP
                omp_set_num_threads(th + 1);
#endif
                rg2_surface surf;
                rg2_error err;
                double t0 = now(), tb, tfree = 0;
                int calls = 0;
                do { /* a batch (>= 20 ms) of builds; freeing is not timed */
                    if (rg2_surface_build(&meshes[s], &surf, &err))
                        die_rg2("rg2_surface_build", &err);
                    double tf = now();
                    rg2_surface_free(&surf);
                    tfree += now() - tf;
                    calls++;
                } while ((tb = now() - t0) < 0.02);
                t[((s * 2 + th) * 2) * reps + rep] = (tb - tfree) / calls;
                if (rg2_surface_build(&meshes[s], &surf, &err)) /* untimed: the memory to reuse */
                    die_rg2("rg2_surface_build", &err);
                t0 = now(), calls = 0;
                do {
                    if (rg2_surface_rebuild(&meshes[s], &surf, &err))
                        die_rg2("rg2_surface_rebuild", &err);
                    calls++;
                } while ((tb = now() - t0) < 0.02);
                t[((s * 2 + th) * 2 + 1) * reps + rep] = tb / calls;
                rg2_surface_free(&surf);
            }
#ifdef _OPENMP
    omp_set_num_threads(2);
#endif
    cJSON *arr = cJSON_CreateArray();
    double per_cp[2][5];
    for (int s = 0; s < ns; s++) {
        double cp = (double)sizes[s] * sizes[s];
        double m1 = bench_median(t + ((s * 2) * 2) * reps, reps), m2 = bench_median(t + ((s * 2 + 1) * 2) * reps, reps);
        double r1 = bench_median(t + ((s * 2) * 2 + 1) * reps, reps), r2 = bench_median(t + ((s * 2 + 1) * 2 + 1) * reps, reps);
        int np = (sizes[s] - 3) * (sizes[s] - 3);
        printf("   %4d x %-5d %10d %13.3f %13.1f %13.3f %13.3f %13.1f\n", sizes[s], sizes[s], np, m1 * 1e3,
               m1 / cp * 1e9, m2 * 1e3, r1 * 1e3, r1 / cp * 1e9);
        cJSON *o = cJSON_CreateObject();
        cJSON_AddNumberToObject(o, "control_points", cp);
        cJSON_AddNumberToObject(o, "patches", np);
        cJSON_AddNumberToObject(o, "median_s_1_thread", m1);
        cJSON_AddNumberToObject(o, "median_s_2_threads", m2);
        cJSON_AddNumberToObject(o, "ns_per_control_point_1_thread", m1 / cp * 1e9);
        cJSON_AddNumberToObject(o, "rebuild_median_s_1_thread", r1);
        cJSON_AddNumberToObject(o, "rebuild_median_s_2_threads", r2);
        cJSON_AddNumberToObject(o, "rebuild_ns_per_control_point_1_thread", r1 / cp * 1e9);
        per_cp[0][s] = m1 / cp;
        per_cp[1][s] = r1 / cp;
        cJSON_AddItemToArray(arr, o);
        rg2_mesh_free(&meshes[s]);
    }
    /* linear in the number of control points: the time per control point stays flat */
    double spread[2];
    for (int k = 0; k < 2; k++) {
        double lo = per_cp[k][2], hi = per_cp[k][2];
        for (int s = 2; s < ns; s++)
            lo = fmin(lo, per_cp[k][s]), hi = fmax(hi, per_cp[k][s]);
        spread[k] = hi / lo;
    }
    printf("   linearity: from 100^2 to 1000^2 control points (100x more) the time per control point stays within\n"
           "   a factor %.2f for rg2_surface_rebuild, %.2f for rg2_surface_build (1 thread; the build's extra is\n"
           "   the page faults and zeroing of fresh memory, on 2 MiB pages from 2 MiB of patches up)\n",
           spread[1], spread[0]);
    cJSON *root = cJSON_CreateObject();
    if (!quick)
        cJSON_AddItemToObject(root, "cold", construction_cold(sizes[ns - 1]));
    cJSON_AddItemToObject(root, "sizes", arr);
    cJSON_AddNumberToObject(root, "per_control_point_spread_100_to_1000", spread[0]);
    cJSON_AddNumberToObject(root, "rebuild_per_control_point_spread_100_to_1000", spread[1]);
    free(t);
    return root;
}

/* ---- tessellation ------------------------------------------------------------------------- */

/* One timed batch (>= 20 ms of calls, wall time) of rg2_tessellate at density d on th threads,
 * or with again != 0 of rg2_retessellate into one mesh (an editing loop); seconds per call. */
static double tess_batch(const rg2_surface *s, int d, int th, int again)
{
#ifdef _OPENMP
    omp_set_num_threads(th);
#else
    (void)th;
#endif
    rg2_error err;
    rg2_tess R = {0};
    if (again && rg2_retessellate(s, d, 0, &R, &err)) /* the mesh an editing loop already has */
        die_rg2("rg2_retessellate", &err);
    double t0 = bench_seconds(CLOCK_MONOTONIC), tb, tfree = 0;
    int calls = 0;
    do {
        if (again) {
            if (rg2_retessellate(s, d, 0, &R, &err))
                die_rg2("rg2_retessellate", &err);
        } else {
            rg2_tess T;
            if (rg2_tessellate(s, d, 0, &T, &err))
                die_rg2("rg2_tessellate", &err);
            double tf = bench_seconds(CLOCK_MONOTONIC);
            rg2_tess_free(&T);
            tfree += bench_seconds(CLOCK_MONOTONIC) - tf;
        }
        calls++;
    } while ((tb = bench_seconds(CLOCK_MONOTONIC) - t0) < 0.02);
    rg2_tess_free(&R);
    return (tb - tfree) / calls;
}

/* The tessellation of surface s (rg2_tessellate: the meshes of the OBJ/STL/PLY/glTF exporters;
 * rg2_retessellate: again into the same mesh) at densities 8 ... 64, 1 and 2 threads, against
 * the grid evaluation of the same points (rg2_surface_grid, positions and unit normals,
 * 1 thread): what the mesh's vertex numbering, copies, triangles and fresh memory cost on top of
 * the evaluation. Checked: every vertex bitwise equal to the grid's point of its patch and
 * (u, v), and rg2_retessellate's mesh bitwise rg2_tessellate's. */
static cJSON *tessellation(const rg2_surface *s)
{
    enum { TESS1, TESS2, AGAIN1, AGAIN2, GRID1, NT };
    int dens[] = {8, 16, 32, 64}, nd = 4, reps = quick ? 3 : 7, nvert[4], ntri[4];
    size_t np = (size_t)s->nu * (size_t)s->nv;
    double *t = xmalloc(sizeof(double) * (size_t)(nd * NT * reps));
    printf("\n== tessellation (rg2_tessellate, positions + unit normals + triangles, seams shared) of the merged\n"
           "   surface, %zu patches, and again into the same mesh (rg2_retessellate, as an editing loop does),\n"
           "   against rg2_surface_grid of the same points (1 thread); wall time, medians of %d interleaved\n"
           "   batches of >= 20 ms\n", np, reps);
    rg2_tess R = {0};
    for (int q = 0; q < nd; q++) { /* check */
        int n = dens[q] + 1;
        size_t pts = np * (size_t)n * (size_t)n;
        double *pos = xmalloc(sizeof(double) * 3 * pts), *nrm = xmalloc(sizeof(double) * 3 * pts);
        rg2_grid_out go = {.pos = pos, .normal = nrm};
        rg2_error err;
        rg2_tess T;
        if (rg2_surface_grid(s, n, n, 1, &go, &err) || rg2_tessellate(s, dens[q], 0, &T, &err) ||
            rg2_retessellate(s, dens[nd - 1 - q], 0, &R, &err) || rg2_retessellate(s, dens[q], 0, &R, &err))
            die_rg2("tessellation check", &err);
        size_t bad = 0, nv = (size_t)T.n_vertices;
        for (size_t v = 0; v < nv; v++) {
            int a = (int)lround(T.uv[2 * v] * dens[q]), b = (int)lround(T.uv[2 * v + 1] * dens[q]);
            size_t k = ((size_t)T.patch[v] * (size_t)n + (size_t)a) * (size_t)n + (size_t)b;
            bad += memcmp(T.pos + 3 * v, pos + 3 * k, 3 * sizeof(double)) != 0 ||
                   memcmp(T.normal + 3 * v, nrm + 3 * k, 3 * sizeof(double)) != 0;
        }
        if (bad || T.n_triangles <= 0) {
            fprintf(stderr, "rg2_bench: tessellation at density %d: %zu vertices differ from the grid\n", dens[q], bad);
            exit(1);
        }
        if (R.n_vertices != T.n_vertices || R.n_triangles != T.n_triangles ||
            memcmp(R.pos, T.pos, 3 * nv * sizeof(double)) || memcmp(R.normal, T.normal, 3 * nv * sizeof(double)) ||
            memcmp(R.uv, T.uv, 2 * nv * sizeof(double)) || memcmp(R.patch, T.patch, nv * sizeof(int)) ||
            memcmp(R.tri, T.tri, 3 * (size_t)T.n_triangles * sizeof(int))) {
            fprintf(stderr, "rg2_bench: rg2_retessellate at density %d differs from rg2_tessellate\n", dens[q]);
            exit(1);
        }
        nvert[q] = T.n_vertices;
        ntri[q] = T.n_triangles;
        rg2_tess_free(&T);
        free(pos);
        free(nrm);
    }
    rg2_tess_free(&R);
    for (int rep = 0; rep < reps; rep++)
        for (int q = 0; q < nd; q++) {
            double *tq = t + (size_t)(q * NT) * (size_t)reps + (size_t)rep;
            tq[TESS1 * reps] = tess_batch(s, dens[q], 1, 0);
            tq[TESS2 * reps] = tess_batch(s, dens[q], 2, 0);
            tq[AGAIN1 * reps] = tess_batch(s, dens[q], 1, 1);
            tq[AGAIN2 * reps] = tess_batch(s, dens[q], 2, 1);
            int n = dens[q] + 1;
            size_t pts = np * (size_t)n * (size_t)n;
            double *pos = xmalloc(sizeof(double) * 3 * pts), *nrm = xmalloc(sizeof(double) * 3 * pts);
            rg2_grid_out go = {.pos = pos, .normal = nrm};
            rg2_error err;
            memset(pos, 1, sizeof(double) * 3 * pts);
            memset(nrm, 1, sizeof(double) * 3 * pts);
            double t0 = bench_seconds(CLOCK_MONOTONIC), tb;
            int calls = 0;
            do {
                if (rg2_surface_grid(s, n, n, 1, &go, &err))
                    die_rg2("rg2_surface_grid", &err);
                calls++;
            } while ((tb = bench_seconds(CLOCK_MONOTONIC) - t0) < 0.02);
            tq[GRID1 * reps] = tb / calls;
            free(pos);
            free(nrm);
        }
#ifdef _OPENMP
    omp_set_num_threads(2);
#endif
    printf("   %-8s %10s %11s %11s %11s %12s %12s %11s %11s %12s\n", "density", "vertices", "triangles", "tess 1t ms",
           "tess 2t ms", "again 1t ms", "again 2t ms", "grid 1t ms", "tess / grid", "again / grid");
    cJSON *arr = cJSON_CreateArray();
    for (int q = 0; q < nd; q++) {
        double m[NT];
        for (int k = 0; k < NT; k++)
            m[k] = bench_median(t + (size_t)(q * NT + k) * (size_t)reps, reps);
        printf("   %-8d %10d %11d %11.3f %11.3f %12.3f %12.3f %11.3f %11.2f %12.2f\n", dens[q], nvert[q], ntri[q],
               m[TESS1] * 1e3, m[TESS2] * 1e3, m[AGAIN1] * 1e3, m[AGAIN2] * 1e3, m[GRID1] * 1e3, m[TESS1] / m[GRID1],
               m[AGAIN1] / m[GRID1]);
        cJSON *o = cJSON_CreateObject();
        cJSON_AddNumberToObject(o, "density", dens[q]);
        cJSON_AddNumberToObject(o, "vertices", nvert[q]);
        cJSON_AddNumberToObject(o, "triangles", ntri[q]);
        cJSON_AddNumberToObject(o, "median_s_1_thread", m[TESS1]);
        cJSON_AddNumberToObject(o, "median_s_2_threads", m[TESS2]);
        cJSON_AddNumberToObject(o, "again_median_s_1_thread", m[AGAIN1]);
        cJSON_AddNumberToObject(o, "again_median_s_2_threads", m[AGAIN2]);
        cJSON_AddNumberToObject(o, "grid_median_s_1_thread", m[GRID1]);
        cJSON_AddNumberToObject(o, "mvertices_per_s_1_thread", nvert[q] / m[TESS1] / 1e6);
        cJSON_AddNumberToObject(o, "again_mvertices_per_s_1_thread", nvert[q] / m[AGAIN1] / 1e6);
        cJSON_AddItemToArray(arr, o);
    }
    free(t);
    return arr;
}

/* ---- main ------------------------------------------------------------------------------- */

static void cpu_model(char *buf, size_t len)
{
    snprintf(buf, len, "unknown");
    FILE *f = fopen("/proc/cpuinfo", "r");
    if (!f)
        return;
    char line[512];
    while (fgets(line, sizeof line, f))
        if (!strncmp(line, "model name", 10)) {
            char *p = strchr(line, ':');
            if (p) {
                snprintf(buf, len, "%s", p + 2);
                buf[strcspn(buf, "\n")] = 0;
            }
            break;
        }
    fclose(f);
}

/* ---- files -------------------------------------------------------------------------------- */

/* Writing the free-form surface (200 x 200 control points, 197 x 197 patches) to files: rg2's
 * STEP and IGES of it as one B-spline surface (the face-per-mesh layout, the net of 592 x 592
 * poles) against OpenCASCADE's STEPControl_Writer and IGESControl_Writer of the same surface as
 * one face, and rg2's face-per-patch files (38 809 faces sharing their edges; no peer writes
 * those from a surface). Wall time of the whole call, file written and closed, medians of
 * interleaved repetitions, into a directory in memory (/dev/shm) where there is one, so that the
 * disk's write-back does not time the writers. Checked: OpenCASCADE reads rg2's one-surface
 * files back as one face of 592 x 592 poles. */
enum { F_RG2_STEP, F_OCCT_STEP, F_RG2_IGES, F_OCCT_IGES, F_RG2_STEP_P, F_RG2_IGES_P, F_RG2_IGES_B, NF };
static const char *const f_name[NF] = {"rg2 STEP, one surface (face per mesh)", "OCCT STEPControl_Writer, one face",
                                       "rg2 IGES, one surface (entity 128)", "OCCT IGESControl_Writer, one face",
                                       "rg2 STEP, face per patch (shared edges)", "rg2 IGES, entity 128 per patch",
                                       "rg2 IGES, B-rep shell, face per patch"};
static const char *const f_file[NF] = {"rm.step", "om.step", "rm.igs", "om.igs", "rp.step", "rp.igs", "rb.igs"};

static double file_write(const rg2_surface *s, occt_surf *o, int m, const char *path, long *bytes)
{
    double t0 = bench_seconds(CLOCK_MONOTONIC);
    int bad;
    if (m == F_OCCT_STEP || m == F_OCCT_IGES) {
        bad = occt_write(o, path, m == F_OCCT_IGES);
    } else {
        rg2_export_opts eo;
        rg2_export_opts_default(&eo);
        eo.layout = (m == F_RG2_STEP || m == F_RG2_IGES) ? RG2_STEP_FACE_PER_MESH : RG2_STEP_FACE_PER_PATCH;
        eo.iges_brep = m == F_RG2_IGES_B;
        rg2_error err;
        bad = rg2_export_file(s, 1, path, &eo, &err) != RG2_OK;
        if (bad)
            fprintf(stderr, "rg2_bench: %s: %s\n", path, err.msg);
    }
    double t = bench_seconds(CLOCK_MONOTONIC) - t0;
    FILE *f = bad ? NULL : fopen(path, "rb");
    if (!f || fseek(f, 0, SEEK_END) || (*bytes = ftell(f)) <= 0) {
        fprintf(stderr, "rg2_bench: %s: %s was not written\n", f_name[m], path);
        exit(1);
    }
    fclose(f);
    return t;
}

static cJSON *files(void)
{
    int reps = quick ? 1 : 3;
    rg2_mesh m;
    rg2_surface s;
    rg2_error err;
    freeform_mesh(200, 200, 42, &m);
    if (rg2_surface_build(&m, &s, &err))
        die_rg2("free-form surface", &err);
    rg2_mesh_free(&m);
    bspline b;
    bspline_from(&s, &b);
    occt_surf *o = occt_make(&b);
    char dir[64];
    snprintf(dir, sizeof dir, "%s/rg2_bench_XXXXXX", access("/dev/shm", W_OK) == 0 ? "/dev/shm" : "/tmp");
    if (!mkdtemp(dir)) {
        perror("rg2_bench: mkdtemp");
        exit(1);
    }
    printf("\n== files: the free-form surface (%d x %d patches) written to STEP and IGES, into %s; wall\n"
           "   time of the whole call, medians of %d interleaved repetitions\n",
           s.nu, s.nv, dir, reps);
    double *t = xmalloc(sizeof(double) * NF * (size_t)reps);
    long bytes[NF] = {0};
    int faces[2] = {0}, nu[2] = {0}, nv[2] = {0};
    for (int r = 0; r < reps; r++)
        for (int k = 0; k < NF; k++) {
            char path[128];
            snprintf(path, sizeof path, "%s/%s", dir, f_file[k]);
            t[k * reps + r] = file_write(&s, o, k, path, &bytes[k]);
            if (r == 0 && (k == F_RG2_STEP || k == F_RG2_IGES)) /* read back by OpenCASCADE */
                faces[k == F_RG2_IGES] = occt_read_poles(path, k == F_RG2_IGES, &nu[k == F_RG2_IGES], &nv[k == F_RG2_IGES]);
            remove(path);
        }
    rmdir(dir);
    int ok = 1;
    for (int q = 0; q < 2; q++)
        ok &= faces[q] == 1 && nu[q] == b.in1 && nv[q] == b.in2;
    printf("   OpenCASCADE reads rg2's one-surface files back: STEP %d face(s) of %d x %d poles, IGES %d of %d x %d "
           "(%d x %d written): %s\n",
           faces[0], nu[0], nv[0], faces[1], nu[1], nv[1], b.in1, b.in2, ok ? "ok" : "WRONG");
    cJSON *j = cJSON_CreateObject(), *jm = cJSON_AddArrayToObject(j, "methods");
    cJSON_AddStringToObject(j, "surface", "free-form open mesh 200 x 200 control points");
    cJSON_AddNumberToObject(j, "patches", (double)s.nu * s.nv);
    cJSON_AddStringToObject(j, "directory", dir);
    cJSON_AddBoolToObject(j, "read_back_ok", ok);
    double med[NF];
    for (int k = 0; k < NF; k++) {
        med[k] = bench_median(t + k * reps, reps);
        printf("   %-44s %8.3f s  %7.1f MB\n", f_name[k], med[k], bytes[k] / 1e6);
        cJSON *x = cJSON_CreateObject();
        cJSON_AddStringToObject(x, "method", f_name[k]);
        cJSON_AddNumberToObject(x, "median_s", med[k]);
        cJSON_AddNumberToObject(x, "bytes", (double)bytes[k]);
        cJSON_AddItemToArray(jm, x);
    }
    printf("   OCCT STEP / rg2 STEP (one surface): %.1fx; OCCT IGES / rg2 IGES: %.1fx\n",
           med[F_OCCT_STEP] / med[F_RG2_STEP], med[F_OCCT_IGES] / med[F_RG2_IGES]);
    cJSON_AddNumberToObject(j, "ratio_occt_step_to_rg2", med[F_OCCT_STEP] / med[F_RG2_STEP]);
    cJSON_AddNumberToObject(j, "ratio_occt_iges_to_rg2", med[F_OCCT_IGES] / med[F_RG2_IGES]);
    if (!ok) {
        fprintf(stderr, "rg2_bench: OpenCASCADE did not read rg2's files back as written\n");
        exit(1);
    }
    free(t);
    occt_free(o);
    bspline_free(&b);
    rg2_surface_free(&s);
    return j;
}

/* ---- picking ------------------------------------------------------------------------------- */

/* The closest surface point and the first hit of a ray on the torus (R = 3, r = 1, 48 patches),
 * rg2_locator against OpenCASCADE (GeomAPI_ProjectPointOnSurf; GeomAPI_IntCS and
 * IntCurveSurface_HInter) and SISL (s1954; s1856) on the one B-spline surface holding the
 * patches, every method answering the same queries (fixed seed), checked against the torus's
 * closed form (closest) and the first root of its implicit equation along the ray. Thread CPU
 * time, medians of interleaved repetitions; GeomAPI_IntCS, the slowest, answers the first 200 rays
 * only. */
#define PK_R 3.0
#define PK_r 1.0
enum { PC_RG2, PC_OCCT_GRAD, PC_OCCT_TREE, PC_SISL, NPC };
/* the closest-point queries' bands of distance from the surface */
enum { PK_NB = 5 };
static const double pk_band[PK_NB + 1] = {0, 0.1, 0.5, 1, 2, INFINITY};
enum { PR_RG2, PR_OCCT_INTCS, PR_OCCT_HINTER, PR_SISL, NPR };
static const char *const pc_name[NPC] = {"rg2_locator_closest", "OCCT GeomAPI_ProjectPointOnSurf (Grad)",
                                         "OCCT GeomAPI_ProjectPointOnSurf (Tree)", "SISL s1954"};
static const char *const pr_name[NPR] = {"rg2_locator_ray", "OCCT GeomAPI_IntCS", "OCCT IntCurveSurface_HInter",
                                         "SISL s1856"};
static const char *const pc_peer[NPC] = {"rg2", "OpenCASCADE", "OpenCASCADE", "SISL"};
static const char *const pr_peer[NPR] = {"rg2", "OpenCASCADE", "OpenCASCADE", "SISL"};

typedef struct {
    rg2_locator *L;
    occt_proj *proj[2];
    occt_rayer *rayer;
    occt_surf *occt;
    SISLSurf *sisl;
} pick_ctx;

static double dist3(const double *a, const double *b)
{
    return sqrt((a[0] - b[0]) * (a[0] - b[0]) + (a[1] - b[1]) * (a[1] - b[1]) + (a[2] - b[2]) * (a[2] - b[2]));
}

/* One closest-point query by method m: 1 and the point and distance, or 0 (none found). */
static int pick_closest(const pick_ctx *P, int m, const double *x, double *p, double *dist)
{
    rg2_error err;
    switch (m) {
    case PC_RG2: {
        rg2_hit h;
        if (rg2_locator_closest(P->L, x, &h, &err))
            die_rg2("rg2_locator_closest", &err);
        memcpy(p, h.p, sizeof h.p);
        *dist = h.dist;
        return h.i >= 0;
    }
    case PC_OCCT_GRAD:
    case PC_OCCT_TREE:
        return occt_closest(P->proj[m == PC_OCCT_TREE], x, p, dist);
    default: {
        int jpt = 0, jcrv = 0, stat = 0, lk1 = 0, lk2 = 0;
        double *gpar = NULL, der[3], nn[3], best = INFINITY;
        SISLIntcurve **wcurve = NULL;
        s1954(P->sisl, (double *)x, 3, 1e-15, 1e-10, &jpt, &gpar, &jcrv, &wcurve, &stat);
        for (int k = 0; stat >= 0 && k < jpt; k++) {
            s1421(P->sisl, 0, gpar + 2 * k, &lk1, &lk2, der, nn, &stat);
            double d = dist3(der, x);
            if (stat >= 0 && d < best)
                best = d, memcpy(p, der, sizeof der);
        }
        free(gpar);
        if (wcurve)
            freeIntcrvlist(wcurve, jcrv);
        *dist = best;
        return best < INFINITY;
    }
    }
}

/* One ray by method m: 1 and the point and t (in units of d), or 0 (a miss). */
static int pick_ray(const pick_ctx *P, int m, const double *o, const double *d, double *p, double *t)
{
    rg2_error err;
    switch (m) {
    case PR_RG2: {
        rg2_hit h;
        if (rg2_locator_ray(P->L, o, d, INFINITY, &h, &err))
            die_rg2("rg2_locator_ray", &err);
        memcpy(p, h.p, sizeof h.p);
        *t = h.dist;
        return h.i >= 0;
    }
    case PR_OCCT_INTCS:
        return occt_ray_intcs(P->occt, o, d, p, t);
    case PR_OCCT_HINTER:
        return occt_ray_hinter(P->rayer, o, d, p, t);
    default: {
        int npt = 0, ncrv = 0, stat = 0, lk1 = 0, lk2 = 0;
        double *par = NULL, der[3], nn[3], best = INFINITY, dd = d[0] * d[0] + d[1] * d[1] + d[2] * d[2];
        SISLIntcurve **curves = NULL;
        s1856(P->sisl, (double *)o, (double *)d, 3, 1e-15, 1e-10, &npt, &par, &ncrv, &curves, &stat);
        for (int k = 0; stat >= 0 && k < npt; k++) {
            s1421(P->sisl, 0, par + 2 * k, &lk1, &lk2, der, nn, &stat);
            double tk = ((der[0] - o[0]) * d[0] + (der[1] - o[1]) * d[1] + (der[2] - o[2]) * d[2]) / dd;
            if (stat >= 0 && tk >= 0 && tk < best)
                best = tk, memcpy(p, der, sizeof der);
        }
        free(par);
        if (curves)
            freeIntcrvlist(curves, ncrv);
        *t = best;
        return best < INFINITY;
    }
    }
}

/* The torus's implicit function at q: > 0 outside, < 0 inside. */
static double torus_f(const double *q)
{
    double s = q[0] * q[0] + q[1] * q[1] + q[2] * q[2] + PK_R * PK_R - PK_r * PK_r;
    return s * s - 4 * PK_R * PK_R * (q[0] * q[0] + q[1] * q[1]);
}

/* The first t >= 0 where o + t d enters the torus (INFINITY: it misses): 20000 samples over the
 * part of the ray inside the ball of radius R + r for the first sign change, then bisection to
 * the last bit. */
static double ray_exact(const double *o, const double *d)
{
    double a = d[0] * d[0] + d[1] * d[1] + d[2] * d[2], b = o[0] * d[0] + o[1] * d[1] + o[2] * d[2];
    double c = o[0] * o[0] + o[1] * o[1] + o[2] * o[2] - (PK_R + PK_r) * (PK_R + PK_r);
    double disc = b * b - a * c;
    if (disc <= 0)
        return INFINITY;
    double t0 = fmax(0.0, (-b - sqrt(disc)) / a), t1 = (-b + sqrt(disc)) / a;
    if (t1 <= t0)
        return INFINITY;
    int steps = 20000;
    double prev = t0;
    for (int k = 1; k <= steps; k++) {
        double t = t0 + (t1 - t0) * k / steps, q[3] = {o[0] + t * d[0], o[1] + t * d[1], o[2] + t * d[2]};
        if (torus_f(q) <= 0) {
            double lo = prev, hi = t; /* f(lo) > 0 >= f(hi) */
            for (;;) {
                double mid = 0.5 * (lo + hi);
                if (!(mid > lo && mid < hi))
                    break;
                double qm[3] = {o[0] + mid * d[0], o[1] + mid * d[1], o[2] + mid * d[2]};
                if (torus_f(qm) <= 0)
                    hi = mid;
                else
                    lo = mid;
            }
            return hi;
        }
        prev = t;
    }
    return INFINITY;
}

/* Errors of one method's answers (first n queries) against the exact ones. */
typedef struct {
    double dist, point; /* worst |distance - exact| (ray: |t - t_exact| |d|), worst |p - exact point| */
    int failed, mismatch, answered;
} pick_err;

static cJSON *pick_json(const char *name, const char *peer, int n, double med, double setup, const pick_err *e,
                        int ray)
{
    cJSON *o = cJSON_CreateObject();
    cJSON_AddStringToObject(o, "method", name);
    cJSON_AddStringToObject(o, "peer", peer);
    cJSON_AddNumberToObject(o, "queries", n);
    cJSON_AddNumberToObject(o, "median_us_per_query", med * 1e6);
    if (setup >= 0)
        cJSON_AddNumberToObject(o, "setup_median_us", setup * 1e6);
    cJSON_AddNumberToObject(o, ray ? "max_t_err_length" : "max_distance_err", e->dist);
    cJSON_AddNumberToObject(o, "max_point_err", e->point);
    cJSON_AddNumberToObject(o, "failures", e->failed);
    if (ray)
        cJSON_AddNumberToObject(o, "hit_miss_disagreements", e->mismatch);
    return o;
}

static cJSON *picking(void)
{
    const int nq = 1000, reps = quick ? 3 : 7;
    /* rays per method: GeomAPI_IntCS (about 6.5 ms a ray on this torus, its polyhedron made for
     * every ray) answers the first 200 only, keeping the section near 30 s; every closest-point
     * method answers all the queries */
    const int nrq[NPR] = {nq, 200, nq, nq};
    rg2_surface s;
    rg2_error err;
    if (rg2t_torus(PK_R, PK_r, 8, 6, NULL, &s, &err))
        die_rg2("torus", &err);
    bspline b;
    bspline_from(&s, &b);
    pick_ctx P = {0};
    P.sisl = newSurf(b.in1, b.in2, 4, 4, b.knots1, b.knots2, b.hcoef, 2, 3, 1);
    P.occt = occt_make(&b);
    if (rg2_locator_build(&s, &P.L, &err))
        die_rg2("rg2_locator_build", &err);

    /* the queries (fixed seed) and their exact answers */
    rg2t_rng rng;
    rg2t_seed(&rng, 20261206);
    double *x = xmalloc(sizeof(double) * 3 * nq), *xe = xmalloc(sizeof(double) * 3 * nq), *de = xmalloc(sizeof(double) * nq);
    /* ordered by their distance band (bands timed apart as well as together) */
    int bstart[PK_NB + 1] = {0};
    for (int bd = 0, q = 0; bd < PK_NB; bd++) {
        rg2t_seed(&rng, 20261206);
        bstart[bd] = q;
        for (int g = 0; g < nq;) {
            double v[3] = {rg2t_uniform(&rng, -5, 5), rg2t_uniform(&rng, -5, 5), rg2t_uniform(&rng, -2.5, 2.5)};
            double rho = hypot(v[0], v[1]), tube = hypot(rho - PK_R, v[2]);
            if (rho < 0.05 || tube < 0.05) /* equidistant from whole circles there */
                continue;
            g++;
            double dist = fabs(tube - PK_r);
            if (!(dist >= pk_band[bd] && dist < pk_band[bd + 1]))
                continue;
            memcpy(x + 3 * q, v, sizeof v);
            de[q] = dist;
            double c[3] = {PK_R * v[0] / rho, PK_R * v[1] / rho, 0};
            for (int k = 0; k < 3; k++)
                xe[3 * q + k] = c[k] + PK_r * (v[k] - c[k]) / tube;
            q++;
        }
    }
    bstart[PK_NB] = nq;
    double *o = xmalloc(sizeof(double) * 3 * nq), *d = xmalloc(sizeof(double) * 3 * nq), *te = xmalloc(sizeof(double) * nq);
    int hits = 0;
    for (int q = 0; q < nq; q++) {
        double az = rg2t_uniform(&rng, 0, 2 * M_PI), el = rg2t_uniform(&rng, -1.2, 1.2);
        double *oq = o + 3 * q, *dq = d + 3 * q;
        oq[0] = 10 * cos(el) * cos(az), oq[1] = 10 * cos(el) * sin(az), oq[2] = 10 * sin(el);
        double target[3] = {rg2t_uniform(&rng, -4.3, 4.3), rg2t_uniform(&rng, -4.3, 4.3), rg2t_uniform(&rng, -1.2, 1.2)};
        for (int k = 0; k < 3; k++)
            dq[k] = target[k] - oq[k];
        te[q] = ray_exact(oq, dq);
        hits += te[q] < INFINITY;
    }

    printf("\n== picking: torus R = 3, r = 1, 48 patches; %d closest-point queries in [-5, 5]^2 x [-2.5, 2.5]\n"
           "   (none within 0.05 of the axis or the core circle), %d rays from the sphere of radius 10 toward\n"
           "   [-4.3, 4.3]^2 x [-1.2, 1.2] (%d hit the torus); %d interleaved repetitions, medians, CPU time of the\n"
           "   calling thread\n",
           nq, nq, hits, reps);
    fflush(stdout);
    bench_clock = CLOCK_THREAD_CPUTIME_ID;
    double steal0, total0;
    host_ticks(&steal0, &total0);
    double *tc = xmalloc(sizeof(double) * NPC * reps), *tr = xmalloc(sizeof(double) * NPR * reps);
    double *tcb = xmalloc(sizeof(double) * NPC * PK_NB * reps); /* per band, per query */
    double *tb = xmalloc(sizeof(double) * 3 * reps); /* setup: locator build, projectors Grad / Tree */
    double *pc = xmalloc(sizeof(double) * 3 * nq * NPC), *dc = xmalloc(sizeof(double) * nq * NPC);
    double *pr = xmalloc(sizeof(double) * 3 * nq * NPR), *trr = xmalloc(sizeof(double) * nq * NPR);
    int *fc = xmalloc(sizeof(int) * nq * NPC), *fr = xmalloc(sizeof(int) * nq * NPR);
    for (int rep = 0; rep < reps; rep++) {
        /* setup of the searches: made anew each repetition (the queries use them) */
        rg2_locator_free(P.L);
        double t0 = now();
        if (rg2_locator_build(&s, &P.L, &err))
            die_rg2("rg2_locator_build", &err);
        tb[rep] = now() - t0;
        for (int k = 0; k < 2; k++) {
            occt_proj_free(P.proj[k]);
            t0 = now();
            P.proj[k] = occt_proj_make(P.occt, k);
            double wp[3], wd, warm[3] = {5, 5, 2.5}; /* one query: the Tree's samples are made in the first */
            occt_closest(P.proj[k], warm, wp, &wd);
            tb[(1 + k) * reps + rep] = now() - t0;
        }
        occt_rayer_free(P.rayer);
        P.rayer = occt_rayer_make(P.occt);
        for (int m = 0; m < NPC; m++) {
            double all = 0;
            for (int bd = 0; bd < PK_NB; bd++) {
                t0 = now();
                for (int q = bstart[bd]; q < bstart[bd + 1]; q++) {
                    size_t i = (size_t)m * nq + q;
                    fc[i] = pick_closest(&P, m, x + 3 * q, pc + 3 * i, dc + i);
                }
                double t = now() - t0;
                all += t;
                tcb[(m * PK_NB + bd) * reps + rep] = t / (bstart[bd + 1] > bstart[bd] ? bstart[bd + 1] - bstart[bd] : 1);
            }
            tc[m * reps + rep] = all / nq;
        }
        for (int m = 0; m < NPR; m++) {
            t0 = now();
            for (int q = 0; q < nrq[m]; q++) {
                size_t i = (size_t)m * nq + q;
                fr[i] = pick_ray(&P, m, o + 3 * q, d + 3 * q, pr + 3 * i, trr + i);
            }
            tr[m * reps + rep] = (now() - t0) / nrq[m];
        }
    }
    bench_clock = CLOCK_MONOTONIC;
    double steal = steal_percent(steal0, total0);

    /* errors of the last repetition's answers (the same in every repetition) */
    pick_err ec[NPC], er[NPR];
    for (int m = 0; m < NPC; m++) {
        pick_err *e = &ec[m];
        *e = (pick_err){0, 0, 0, 0, 0};
        for (int q = 0; q < nq; q++) {
            size_t i = (size_t)m * nq + q;
            if (!fc[i]) {
                e->failed++;
                continue;
            }
            e->answered++;
            double ed = fabs(dc[i] - de[q]), ep = dist3(pc + 3 * i, xe + 3 * q);
            e->dist = fmax(e->dist, ed), e->point = fmax(e->point, ep);
            if (!(ed <= 1e-6 && ep <= 1e-6)) {
                e->failed++;
                if (getenv("RG2_BENCH_PICK_VERBOSE"))
                    fprintf(stderr, "closest %s q %d x (%.17g, %.17g, %.17g): dist %.17g exact %.17g, point off %.3g\n",
                            pc_name[m], q, x[3 * q], x[3 * q + 1], x[3 * q + 2], dc[i], de[q], ep);
            }
        }
    }
    for (int m = 0; m < NPR; m++) {
        pick_err *e = &er[m];
        *e = (pick_err){0, 0, 0, 0, 0};
        for (int q = 0; q < nrq[m]; q++) {
            size_t i = (size_t)m * nq + q;
            const double *dq = d + 3 * q, *oq = o + 3 * q;
            double len = sqrt(dq[0] * dq[0] + dq[1] * dq[1] + dq[2] * dq[2]);
            int exact_hit = te[q] < INFINITY;
            if (fr[i] != exact_hit) {
                e->mismatch++, e->failed++;
                if (getenv("RG2_BENCH_PICK_VERBOSE"))
                    fprintf(stderr, "ray %s q %d o (%.17g, %.17g, %.17g) d (%.17g, %.17g, %.17g): %s, exact t %.17g\n",
                            pr_name[m], q, oq[0], oq[1], oq[2], dq[0], dq[1], dq[2], fr[i] ? "hit" : "miss", te[q]);
                continue;
            }
            if (!exact_hit)
                continue;
            e->answered++;
            double et = fabs(trr[i] - te[q]) * len, xq[3];
            for (int k = 0; k < 3; k++)
                xq[k] = oq[k] + te[q] * dq[k];
            double ep = dist3(pr + 3 * i, xq);
            e->dist = fmax(e->dist, et), e->point = fmax(e->point, ep);
            if (!(et <= 1e-6 && ep <= 1e-6)) {
                e->failed++;
                if (getenv("RG2_BENCH_PICK_VERBOSE"))
                    fprintf(stderr, "ray %s q %d: t %.17g exact %.17g (length error %.3g), point off %.3g\n", pr_name[m],
                            q, trr[i], te[q], et, ep);
            }
        }
    }

    /* rg2's proven bound (rg2_hit.bound), untimed: how far below the answer it stays, and whether
     * it ever exceeds the exact answer (it must not, beyond rounding) */
    double gap_c = 0, gap_r = 0;
    int over_c = 0, over_r = 0;
    for (int q = 0; q < nq; q++) {
        rg2_hit h;
        if (rg2_locator_closest(P.L, x + 3 * q, &h, &err))
            die_rg2("rg2_locator_closest", &err);
        gap_c = fmax(gap_c, h.dist - h.bound);
        over_c += h.bound > de[q] + 1e-12;
        const double *dq = d + 3 * q;
        double len = sqrt(dq[0] * dq[0] + dq[1] * dq[1] + dq[2] * dq[2]);
        if (rg2_locator_ray(P.L, o + 3 * q, dq, INFINITY, &h, &err))
            die_rg2("rg2_locator_ray", &err);
        if (h.i >= 0)
            gap_r = fmax(gap_r, (h.dist - h.bound) * len);
        over_r += te[q] < INFINITY && h.bound * len > te[q] * len + 1e-12;
    }

    cJSON *j = cJSON_CreateObject();
    cJSON_AddStringToObject(j, "surface", "torus R = 3, r = 1, 8 x 6 arcs, 48 rational bi-cubic patches");
    cJSON_AddNumberToObject(j, "repetitions", reps);
    cJSON_AddStringToObject(j, "clock", "CPU time of the calling thread (CLOCK_THREAD_CPUTIME_ID)");
    if (steal >= 0) {
        printf("   host: %.1f %% of this machine's CPU time went to other guests during this section (steal)\n", steal);
        cJSON_AddNumberToObject(j, "host_steal_percent", steal);
    }
    double mb[3];
    for (int k = 0; k < 3; k++)
        mb[k] = bench_median(tb + k * reps, reps);
    printf("   setup: rg2_locator_build %.1f us; GeomAPI_ProjectPointOnSurf Init on the surface and a first query: Grad "
           "%.1f us, Tree %.1f us\n",
           mb[0] * 1e6, mb[1] * 1e6, mb[2] * 1e6);
    cJSON_AddNumberToObject(j, "locator_build_median_us", mb[0] * 1e6);
    double mc[NPC], mr[NPR];
    printf("   %-42s %7s %11s  %-13s %-13s %s\n", "closest point", "queries", "us / query", "distance err",
           "point err", "failed (none, or off > 1e-6)");
    cJSON *jc = cJSON_AddArrayToObject(j, "closest");
    cJSON_AddNumberToObject(j, "closest_queries", nq);
    for (int m = 0; m < NPC; m++) {
        mc[m] = bench_median(tc + m * reps, reps);
        printf("   %-42s %7d %11.2f  %-13.2e %-13.2e %d\n", pc_name[m], nq, mc[m] * 1e6, ec[m].dist, ec[m].point,
               ec[m].failed);
        cJSON_AddItemToArray(jc, pick_json(pc_name[m], pc_peer[m], nq, mc[m],
                                           m == PC_RG2 ? mb[0] : m == PC_SISL ? -1 : mb[m], &ec[m], 0));
    }
    printf("   closest point, us per query by distance from the surface:\n     %-40s", "distance");
    for (int bd = 0; bd < PK_NB; bd++) {
        char band[32];
        snprintf(band, sizeof band, bd + 1 < PK_NB ? "[%g, %g)" : ">= %g", pk_band[bd], pk_band[bd + 1]);
        printf(" %10s", band);
    }
    printf("\n     %-40s", "queries");
    for (int bd = 0; bd < PK_NB; bd++)
        printf(" %10d", bstart[bd + 1] - bstart[bd]);
    printf("\n");
    cJSON *jb = cJSON_AddArrayToObject(j, "closest_by_distance");
    for (int bd = 0; bd < PK_NB; bd++) {
        cJSON *o1 = cJSON_CreateObject();
        cJSON_AddNumberToObject(o1, "distance_from", pk_band[bd]);
        if (bd + 1 < PK_NB)
            cJSON_AddNumberToObject(o1, "distance_below", pk_band[bd + 1]);
        cJSON_AddNumberToObject(o1, "queries", bstart[bd + 1] - bstart[bd]);
        cJSON *ju = cJSON_AddObjectToObject(o1, "median_us_per_query");
        for (int m = 0; m < NPC; m++)
            cJSON_AddNumberToObject(ju, pc_name[m], bench_median(tcb + (m * PK_NB + bd) * reps, reps) * 1e6);
        cJSON_AddItemToArray(jb, o1);
    }
    for (int m = 0; m < NPC; m++) {
        printf("     %-40s", pc_name[m]);
        for (int bd = 0; bd < PK_NB; bd++)
            printf(" %10.2f", bench_median(tcb + (m * PK_NB + bd) * reps, reps) * 1e6);
        printf("\n");
    }
    printf("   %-42s %7s %11s  %-13s %-13s %s\n", "first ray hit", "rays", "us / ray", "t err x |d|", "point err",
           "failed (hit/miss wrong, or off > 1e-6)");
    cJSON *jr = cJSON_AddArrayToObject(j, "ray");
    cJSON_AddNumberToObject(j, "rays", nq);
    cJSON_AddNumberToObject(j, "rays_hitting", hits);
    for (int m = 0; m < NPR; m++) {
        mr[m] = bench_median(tr + m * reps, reps);
        printf("   %-42s %7d %11.2f  %-13.2e %-13.2e %d (%d hit/miss)\n", pr_name[m], nrq[m], mr[m] * 1e6, er[m].dist,
               er[m].point, er[m].failed, er[m].mismatch);
        cJSON_AddItemToArray(jr, pick_json(pr_name[m], pr_peer[m], nrq[m], mr[m], -1, &er[m], 1));
    }
    printf("   rg2's proven bound (rg2_hit.bound): closest, dist - bound <= %.2e (above the exact distance: %d);\n"
           "   ray, (t - bound) |d| <= %.2e (above the exact t: %d)\n",
           gap_c, over_c, gap_r, over_r);
    cJSON_AddNumberToObject(j, "rg2_closest_max_dist_minus_bound", gap_c);
    cJSON_AddNumberToObject(j, "rg2_closest_bound_above_exact", over_c);
    cJSON_AddNumberToObject(j, "rg2_ray_max_t_minus_bound_length", gap_r);
    cJSON_AddNumberToObject(j, "rg2_ray_bound_above_exact", over_r);
    printf("   ratios (same run, medians, single thread; peer time / rg2 time):\n");
    cJSON *jq = cJSON_AddArrayToObject(j, "ratios");
    for (int m = 1; m < NPC + NPR - 1; m++) {
        int ray = m >= NPC;
        int k = ray ? m - NPC + 1 : m;
        double ratio = ray ? mr[k] / mr[PR_RG2] : mc[k] / mc[PC_RG2];
        char label[128];
        snprintf(label, sizeof label, "%s is %.1fx as fast as %s", ray ? "rg2 ray" : "rg2 closest", ratio,
                 ray ? pr_name[k] : pc_name[k]);
        printf("     %s\n", label);
        cJSON *r = cJSON_CreateObject();
        cJSON_AddStringToObject(r, "pair", label);
        cJSON_AddStringToObject(r, "rg2", ray ? pr_name[0] : pc_name[0]);
        cJSON_AddStringToObject(r, "peer", ray ? pr_name[k] : pc_name[k]);
        cJSON_AddNumberToObject(r, "peer_over_rg2", ratio);
        cJSON_AddItemToArray(jq, r);
    }
    free(tc), free(tr), free(tcb), free(tb), free(pc), free(dc), free(pr), free(trr), free(fc), free(fr);
    free(x), free(xe), free(de), free(o), free(d), free(te);
    for (int k = 0; k < 2; k++)
        occt_proj_free(P.proj[k]);
    occt_rayer_free(P.rayer);
    rg2_locator_free(P.L);
    occt_free(P.occt);
    freeSurf(P.sisl);
    bspline_free(&b);
    rg2_surface_free(&s);
    return j;
}

static int write_json(cJSON *root, const char *path)
{
    char *txt = cJSON_Print(root);
    char tmp[4096];
    snprintf(tmp, sizeof tmp, "%s.tmp", path);
    FILE *f = fopen(tmp, "w");
    if (!f || !txt || fputs(txt, f) < 0 || fclose(f) != 0 || rename(tmp, path) != 0) {
        fprintf(stderr, "rg2_bench: cannot write %s\n", path);
        free(txt);
        remove(tmp);
        return 1;
    }
    free(txt);
    return 0;
}

int main(int argc, char **argv)
{
    const char *out = "out/bench.json";
    for (int i = 1; i < argc; i++) {
        if (!strcmp(argv[i], "--quick"))
            quick = 1;
        else if (!strcmp(argv[i], "--only") && i + 1 < argc)
            only = argv[++i];
        else if (!strcmp(argv[i], "--help") || !strcmp(argv[i], "-h")) {
            printf("usage: rg2_bench [out.json] [--quick] [--only torus|merged|tessellation|freeform|scaling|construction|files|picking]\n");
            return 0;
        } else
            out = argv[i];
    }
    char cpu[256];
    cpu_model(cpu, sizeof cpu);
    int nthreads = 1;
#ifdef _OPENMP
    nthreads = omp_get_max_threads();
#endif
    printf("rg2_bench %s on %s, %d hardware threads available\n", rg2_version(), cpu, nthreads);
    cJSON *root = cJSON_CreateObject();
    cJSON_AddStringToObject(root, "rg2_version", rg2_version());
    cJSON_AddStringToObject(root, "cpu", cpu);
    cJSON_AddNumberToObject(root, "threads_available", nthreads);
    cJSON *jcases = cJSON_AddArrayToObject(root, "cases");
    rg2_error err;

    bcase torus = {.name = "torus", .what = "torus R = 3, r = 1, 8 x 6 arcs, 48 rational bi-cubic patches",
                   .torus = 1, .R = 3.0, .r = 1.0, .scale = 4.0};
    if (want("torus")) {
        if (rg2t_torus(3.0, 1.0, 8, 6, NULL, &torus.s, &err))
            die_rg2("torus", &err);
        case_setup(&torus, 64, 9);
        cJSON_AddItemToArray(jcases, run_case(&torus));
        case_free(&torus);
    }

    if (want("merged") || want("tessellation")) {
#ifdef RG2_BENCH_DESIGN
    bcase merged = {.name = "merged", .what = "merged design " RG2_BENCH_DESIGN " (surface 0)"};
    {
        rg2_design *d = NULL;
        if (rg2_design_load(RG2_BENCH_DESIGN, &d, &err) || rg2_surface_copy(rg2_design_surface(d, 0), &merged.s, &err))
            die_rg2(RG2_BENCH_DESIGN, &err);
        rg2_design_free(d);
    }
#else
    bcase merged = {.name = "merged", .what = "merged mesh built in code (no design module in this tree): outer "
                                              "half torus rows + cylinder rows (8 x 12 control points)"};
    merged_surface(&merged.s);
#endif
    if (want("merged")) {
        case_setup(&merged, 64, 9);
        cJSON_AddItemToArray(jcases, run_case(&merged));
    }
    cJSON_AddItemToObject(root, "tessellation", tessellation(&merged.s));
    if (want("merged"))
        case_free(&merged);
    else
        rg2_surface_free(&merged.s);
    }

    if (want("freeform")) {
    bcase ff = {.name = "freeform", .what = "free-form open mesh 200 x 200 control points, random weights and "
                                            "G2 scalars"};
    {
        rg2_mesh m;
        freeform_mesh(200, 200, 42, &m);
        if (rg2_surface_build(&m, &ff.s, &err))
            die_rg2("free-form surface", &err);
        rg2_mesh_free(&m);
    }
    case_setup(&ff, 8, 9);
    cJSON_AddItemToArray(jcases, run_case(&ff));
    case_free(&ff);
    }
    cJSON_AddNumberToObject(root, "peak_rss_kb_after_cases", (double)peak_rss_kb());

    if (want("scaling")) {
        rg2_surface ts;
        if (rg2t_torus(3.0, 1.0, 8, 6, NULL, &ts, &err))
            die_rg2("torus", &err);
        cJSON_AddItemToObject(root, "grid_scaling", threads_and_sizes(&ts));
        rg2_surface_free(&ts);
        cJSON_AddNumberToObject(root, "peak_rss_kb_after_scaling", (double)peak_rss_kb());
    }
    if (want("construction"))
        cJSON_AddItemToObject(root, "construction", construction());
    if (want("files"))
        cJSON_AddItemToObject(root, "files", files());
    if (want("picking"))
        cJSON_AddItemToObject(root, "picking", picking());
    long rss = peak_rss_kb();
    cJSON_AddNumberToObject(root, "peak_rss_kb", (double)rss);
    printf("\npeak memory (getrusage ru_maxrss): %.1f MB\n", rss / 1024.0);
    printf("write ceiling: the fastest way, counted over all ceiling measurements:");
    cJSON *jw = cJSON_AddObjectToObject(root, "ceiling_fastest_way_counts");
    for (int w = 0; w < N_WRITERS; w++)
        if (writer_ok(&writers[w])) {
            printf(" %s %d%s", writers[w].name, ceil_winner[w], w + 1 < N_WRITERS ? "," : "\n");
            cJSON_AddNumberToObject(jw, writers[w].name, ceil_winner[w]);
        }
    printf("patch reads + writes: the fastest way, counted likewise:");
    cJSON *jt = cJSON_AddObjectToObject(root, "traffic_fastest_way_counts");
    for (int w = 0; w < N_TW; w++) {
        printf(" %s %d%s", tw_name[w], traffic_winner[w], w + 1 < N_TW ? "," : "\n");
        cJSON_AddNumberToObject(jt, tw_name[w], traffic_winner[w]);
    }
    int rc = write_json(root, out);
    if (!rc)
        printf("wrote %s\n", out);
    cJSON_Delete(root);
    return rc;
}
