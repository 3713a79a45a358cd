/* grid.c -- fast evaluation of rational bi-3 patches on regular parameter grids (positions,
 * unit normals, derivatives, curvatures) and a fast per-point evaluator.
 *
 * METHOD: separable evaluation. The Bernstein values (and derivatives) at the grid
 * parameters are tabulated once per grid size (a cache keeps the tables of the first 8 sizes a
 * process asks for; other sizes tabulate per call): per v index as four structure-of-arrays columns, per
 * u index as the constants of Horner forms (row_consts). Per block of up to BLK columns of a
 * patch, the column sums c_r(v_b) = sum_s h_rs B_s(v_b) (16 numbers per column; with B' and B''
 * when derivatives are wanted) are formed once, in the order of rg2_patch_eval; every point of
 * every row is then sum_r B_r(u_a) c_r(v_b) over a row constant, as ((c3 t/3 + c2) t + c1) 3t + c0
 * in t = u / (1 - u) (reversed past u = 1/2): 3 multiply-adds per homogeneous value instead of 4
 * (first derivatives by the hodograph: 2 instead of 3 on differences of the column sums in u, 3
 * terms on differences of the control points in v; second derivatives by B''), in a
 * branch-free loop over the columns that the compiler vectorises (x86-64 with GCC: AVX-512 /
 * AVX2 / baseline clones chosen at load time). On AVX-512 CPUs hand-written kernels take whole
 * patches (grid_patch_avx512): rcp14 / rsqrt14 and two Newton steps instead of divisions and
 * square roots (but divisions on AMD CPUs, whose divider runs beside the multiply-adds: grid_hwdiv),
 * normals in two phases (cross products, then square roots: cross8r), for rows wider than 8
 * points each 8 normals right after the next 8 positions (seg_cross_unit_avx512; see
 * docs/performance.md), and rows wider than 8 points skip the undefined-normal test where a
 * bound of the patch settles it (cross_threshold),
 * permutes for the x, y, z interleave, plain stores with prefetchw for outputs in
 * the caches and streaming stores past RG2_STREAM_BYTES (rows that do not start on a cache line
 * shifted to the lines as they are stored: shifter); the kernels take AMD's form or Intel's by
 * the CPU (amd_or: divisions, interleave, pages touched ahead of the streaming stores, each
 * chosen as measured on both; the same bits either way). The quotient rule and the
 * curvature formulas are those of rg2_patch_eval (eval.c), which stays the independent
 * reference; tests/test_grid.c holds the two to 1e-14. Patches of higher degree (s->xp) take
 * the separable scalar grid of xpatch.c. Threads: the pool of pool.c (runs of patches claimed
 * by the caller and the workers; the caller never waits for a worker that has not started).
 */
#include "export_internal.h"
#include "internal.h"

#include <stdatomic.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#ifdef RG2_HAVE_OPENMP
#include <omp.h>
#endif

/* RG2_HOT (src/internal.h): the hot kernels and the per-point evaluators are multi-versioned. */

/* Hand-written AVX-512 kernels for positions, normals and the second-order quantities
 * (reciprocals by rcp14/rsqrt14 and two Newton steps instead of divisions, interleaving
 * permutes, masked tails, optional streaming stores), chosen at run time when the CPU has
 * AVX-512F/DQ. */
#if defined(__GNUC__) && defined(__x86_64__) && !defined(RG2_NO_CLONES)
#define RG2_AVX512 1
#include <immintrin.h>
#else
#define RG2_AVX512 0
#endif

/* Outputs larger than this (bytes) per thread of the call are written with streaming stores on
 * the AVX-512 path; smaller ones with plain stores and prefetchw ahead of them
 * (RG2_PREFETCHW_AHEAD), and they stay in the caches for the consumer. Measured on the Intel
 * machine (2 MiB L2 per core, large shared L3), each in the caches' steady state: positions alone,
 * plain + prefetchw faster than streaming by 1.25x at 4.7 MB and 1.1x at 11.8 and 15.7 MB,
 * streaming faster by 1.45x at 23.6 MB and 2x at 75 MB; positions + normals (two arrays),
 * streaming 1.3x faster at 9.4 MB, equal at 23.6 MB. Positions alone streamed past twice this
 * until the AMD Zen 4 machine, whose 32 MB L3 the host shares with other guests: 11.8 MB of
 * positions (the merged design) ran at 416-762 M points/s with plain stores (medians of 31
 * alternating calls; the fastest 790-1190) and 1007-1077 streamed (fastest 1040-1175). */
#ifndef RG2_STREAM_BYTES
#define RG2_STREAM_BYTES ((size_t)8 << 20)
#endif

#define BSTEP 64       /* columns per block (column sums, structure-of-arrays temporaries) */
#define BLK (BSTEP + 8) /* the most: the last block also takes up to 8 columns left over */

/* The columns of the block starting at column b0 of m: BSTEP, the last block what is left, and up
 * to 8 columns left over after a full block join it (a block of 1 column after 64, as for
 * 65 or 129 points a row, cost every row a call of its own and two more partial cache lines). */
static inline int block_cols(int m, int b0)
{
    return m - b0 <= BLK ? m - b0 : BSTEP;
}

/* Test hooks (tests/test_grid.c): the portable kernels on any CPU; the division mode (-1: as
 * grid_hwdiv decides); the spread normals of wide rows (tables.spread; 0: never, two phases);
 * the output size per thread past which stores stream (SIZE_MAX: never); whether streamed
 * outputs touch their pages ahead (-1: as grid_pages decides). */
int rg2__grid_portable = 0;
int rg2__grid_hwdiv = -1;
int rg2__grid_spread = 1;
size_t rg2__grid_stream_bytes = RG2_STREAM_BYTES;
int rg2__grid_pages = -1;

/* hook if it is 0 or 1 (a test forcing a choice), else whether the CPU is AMD's: the kernels'
 * choices below were measured to differ between AMD's cores and Intel's. */
static int amd_or(int hook)
{
    if (hook >= 0)
        return hook;
#if RG2_AVX512
    return __builtin_cpu_is("amd");
#else
    return 0;
#endif
}

/* Whether the AVX-512 kernels divide by the hardware (1 / w, 1 / (EG - F^2)) instead of rcp14 and
 * Newton steps: on AMD CPUs, whose divider runs beside the multiply-add pipes the kernels keep
 * busy (Zen 5, measured: positions 0.99-1.08x in L3 and 1.07x for 8 x 8 patches in main memory;
 * the results correctly rounded where the Newton steps leave about 1 ulp); not on Intel's
 * (Sapphire Rapids: slower in earlier stops; 0.99-1.05x in the fourteenth, docs/performance.md).
 * The normalisation's 1 / sqrt takes Newton steps on every CPU (rsqrt8).
 * rg2__grid_hwdiv (a test hook) forces 0 or 1. */
#if RG2_AVX512
static int grid_hwdiv(void)
{
    return amd_or(rg2__grid_hwdiv);
}
#endif

/* Whether streamed outputs touch their pages ahead of the streaming stores (prefetch_pages): on
 * AMD CPUs, where it was measured to pay (Zen 5 guest: 1.05-1.63x, see prefetch_pages); not on
 * Intel's, where the prefetches themselves wait for the page walks (Sapphire Rapids class KVM
 * guest, fourteenth stop, medians of 21-41 alternating calls: without them the merged design's
 * positions 1.16-1.19x, with normals 1.10x; the torus with normals 1.10x at 64 x 64 per patch,
 * positions 1.23x and normals 1.13x at 256 x 256; the free-form mesh's 8 x 8 patches positions
 * 1.20x, normals 1.08x). Rows of positions streamed four at a time go with it (rows_avx512).
 * rg2__grid_pages (a test hook) forces 0 or 1. */
static int grid_pages(void)
{
    return amd_or(rg2__grid_pages);
}

typedef struct {
    int n, m, order;
    int avx512; /* use the AVX-512 kernels (this CPU has them) */
    int hwdiv;  /* ... with divisions by the hardware (grid_hwdiv) */
    int stream; /* large output: non-temporal stores (bypass the caches) */
    int pages;  /* ... touching the pages ahead of them (prefetch_pages) */
    int spread; /* with normals: each 8 normals of a wide row after the next 8 positions */
    double *ddu;                       /* n * 4: B_r''(u) of each row */
    double *ht;                        /* n * 8: the rows' Horner constants (row_consts) */
    int arev;                          /* rows a >= arev (u > 1/2) take the reversed Horner form */
    double *bv[4], *hv[4], *ddv[4];    /* m each; hv: 3 B^2_q(v), q < 3 (see vsumh; hv[3] unused) */
    double *mem;
    int cached; /* mem belongs to the tables cache (tables_get), not to this call */
} tables;

/* The Horner constants of a row at u. Along u, sum_r B_r(u) c_r = lambda (c0 + 3 c1 t + 3 c2 t^2 +
 * c3 t^3) with t = u / (1 - u) and lambda = (1 - u)^3, evaluated as ((c3 t/3 + c2) t + c1) 3t + c0
 * (3 multiply-adds instead of 4; the binomials ride on t/3 and 3t); the hodograph
 * sum_q 3 B^2_q(u) d_q = mu (d0 + 2 d1 t + d2 t^2), mu = 3 (1 - u)^2, as (d2 t/2 + d1) 2t + d0 (2
 * instead of 3). Past u = 1/2 the same forms run in s = (1 - u) / u on the reversed coefficients,
 * with lambda = u^3 and mu = 3 u^2, so that t, s <= 1: the rounding error stays that of the
 * Bernstein sums (Horner's bound is sum |a_i| t^i, here the Bernstein bound over lambda). The
 * kernels drop lambda and mu: positions are h / w of the same scaled sums, and the normal is the
 * direction of (mu a) x (lambda b), a and b the tangents; the second order scales back with
 * mu / lambda, 1 / lambda and 2 mu. ht: t/3, t, 3t, t/2, 2t, mu / lambda, 1 / lambda, 2 mu. */
static void row_consts(double u, double ht[8])
{
    double s = 1.0 - u, t = u <= 0.5 ? u / s : s / u, l = u <= 0.5 ? s : u; /* l: 1 - u, or u */
    double lambda = l * l * l, mu = 3.0 * l * l;
    ht[0] = t / 3.0, ht[1] = t, ht[2] = 3.0 * t, ht[3] = 0.5 * t, ht[4] = 2.0 * t;
    ht[5] = 3.0 / l, ht[6] = 1.0 / lambda, ht[7] = 2.0 * mu;
}

static void tables_free(tables *t)
{
    free(t->mem);
    memset(t, 0, sizeof *t);
}

/* The call's choices, which the tables cache does not keep: the outputs' order and the kernels. */
static void tables_mode(tables *t, int order)
{
    t->order = order;
#if RG2_AVX512
    t->avx512 = !rg2__grid_portable && __builtin_cpu_supports("avx512f") && __builtin_cpu_supports("avx512dq");
    t->hwdiv = t->avx512 && grid_hwdiv();
#endif
}

static rg2_status tables_make(tables *t, int n, int m, int order, rg2_error *err)
{
    memset(t, 0, sizeof *t);
    size_t m8 = ((size_t)m + 7) & ~(size_t)7; /* v columns padded to whole 8-lane vectors */
    size_t per = (size_t)n * 4 + (size_t)n * 8 + m8 * 12;
    t->mem = rg2__calloc(per, sizeof(double));
    if (!t->mem)
        return rg2__fail(err, RG2_ENOMEM, "grid: out of memory for %d x %d tables", n, m);
    t->n = n;
    t->m = m;
    tables_mode(t, order);
    double *q = t->mem;
    t->ddu = q, q += (size_t)n * 4;
    t->ht = q, q += (size_t)n * 8;
    t->arev = n;
    for (int s = 0; s < 4; s++) {
        t->bv[s] = q, q += m8;
        t->hv[s] = q, q += m8;
        t->ddv[s] = q, q += m8;
    }
    for (int a = 0; a < n; a++) {
        double u = a == n - 1 ? 1.0 : (double)a / (double)(n - 1);
        double B[4];
        rg2__bern3(u, B, NULL, t->ddu + 4 * a);
        if (u > 0.5 && t->arev == n)
            t->arev = a;
        row_consts(u, t->ht + 8 * a);
    }
    for (int b = 0; b < m; b++) {
        double v = b == m - 1 ? 1.0 : (double)b / (double)(m - 1);
        double B[4], DD[4], s1 = 1.0 - v;
        rg2__bern3(v, B, NULL, DD);
        for (int s = 0; s < 4; s++) {
            t->bv[s][b] = B[s];
            t->ddv[s][b] = DD[s];
        }
        t->hv[0][b] = 3.0 * s1 * s1;
        t->hv[1][b] = 6.0 * v * s1;
        t->hv[2][b] = 3.0 * v * v;
    }
    /* The padding columns (the AVX-512 kernels' lanes past the last point, computed but never
     * stored) repeat the last column, v = 1: with zeros there the lanes' weight was 0 and 1 / w
     * raised FE_DIVBYZERO, then FE_INVALID (0 * inf), which a host with floating-point traps
     * enabled took as SIGFPE. Now they compute a point of the patch that the grid computes
     * anyway, so they raise only what that point raises; the stored lanes are unchanged. */
    for (size_t b = (size_t)m; b < m8; b++)
        for (int s = 0; s < 4; s++) {
            t->bv[s][b] = t->bv[s][m - 1];
            t->hv[s][b] = t->hv[s][m - 1];
            t->ddv[s][b] = t->ddv[s][m - 1];
        }
    return RG2_OK;
}

/* The tables of the first TABLE_SLOTS grid sizes asked for, kept for the life of the process.
 * Making them costs a call about 0.45 us, and with 2 threads more: the worker has read the
 * previous call's tables, so rewriting them made the caller wait for every line to come back
 * from the other core (the AMD Zen 5 machine: the 2-thread call's first patch 1.0 us later than
 * the 1-thread call's, a whole 2-thread call of 49 K points 16-18 us). An entry is written once,
 * published by a compare-and-swap into a free slot and never changed; when every slot holds
 * another size, a call makes its own tables. */
#define TABLE_SLOTS 8
#define TABLE_MAX_DOUBLES 32768 /* larger tables (past about 1300 x 1300 points) are not kept */
static _Atomic(tables *) table_slot[TABLE_SLOTS];

static rg2_status tables_get(tables *t, int n, int m, int order, rg2_error *err)
{
    for (int k = 0; k < TABLE_SLOTS; k++) {
        const tables *c = atomic_load_explicit(&table_slot[k], memory_order_acquire);
        if (c && c->n == n && c->m == m) {
            *t = *c;
            tables_mode(t, order);
            return RG2_OK;
        }
    }
    rg2_status st = tables_make(t, n, m, order, err);
    size_t m8 = ((size_t)m + 7) & ~(size_t)7;
    if (st || (size_t)n * 12 + m8 * 12 > TABLE_MAX_DOUBLES)
        return st;
    tables *c = malloc(sizeof *c);
    if (!c)
        return RG2_OK; /* this call's own tables */
    *c = *t;
    c->cached = 1;
    for (int k = 0; k < TABLE_SLOTS; k++) {
        tables *none = NULL;
        if (atomic_compare_exchange_strong_explicit(&table_slot[k], &none, c, memory_order_acq_rel,
                                                    memory_order_relaxed)) {
            t->cached = 1;
            return RG2_OK;
        }
    }
    free(c); /* every slot taken */
    return RG2_OK;
}

int rg2__grid_tables_cached(int n, int m)
{
    for (int k = 0; k < TABLE_SLOTS; k++) {
        const tables *c = atomic_load_explicit(&table_slot[k], memory_order_acquire);
        if (c && c->n == n && c->m == m)
            return 1;
    }
    return 0;
}

/* Release a call's tables (tables_get): its own are freed, the cache's stay. */
static void tables_put(tables *t)
{
    if (!t->cached)
        tables_free(t);
}

#if defined(__GNUC__)
/* Free the cache at exit (memory checkers see no blocks left). */
__attribute__((destructor)) static void tables_cache_free(void)
{
    for (int k = 0; k < TABLE_SLOTS; k++) {
        tables *c = atomic_exchange(&table_slot[k], NULL);
        if (c) {
            free(c->mem);
            free(c);
        }
    }
}
#endif

/* Column sums of one block of columns, in the order of rg2_patch_eval (v first):
 * c[r][k][i] = sum_s h[r][s][k] bv[s][b0 + i]. */
static inline void vsum(const rg2_patch *P, double *const bv[4], int b0, int cnt, double c[4][4][BLK])
{
    const double *restrict v0 = bv[0] + b0, *restrict v1 = bv[1] + b0, *restrict v2 = bv[2] + b0,
                           *restrict v3 = bv[3] + b0;
    for (int r = 0; r < 4; r++)
        for (int k = 0; k < 4; k++) {
            double h0 = P->h[r][0][k], h1 = P->h[r][1][k], h2 = P->h[r][2][k], h3 = P->h[r][3][k];
            double *restrict dst = c[r][k];
            for (int i = 0; i < cnt; i++)
                dst[i] = h0 * v0[i] + h1 * v1[i] + h2 * v2[i] + h3 * v3[i];
            for (int i = cnt; i < BLK && (i & 7); i++) /* whole 8-lane vectors stay defined */
                dst[i] = 0.0;
        }
}

/* The v-derivative column sums by the hodograph, as in u (RSUMH): sum_s h_rs B_s'(v) =
 * sum_q 3 B^2_q(v) (h_r,q+1 - h_rs), from the control point differences of a patch. */
static inline void hdiff(const rg2_patch *P, double dh[4][3][4])
{
    for (int r = 0; r < 4; r++)
        for (int q = 0; q < 3; q++)
            for (int k = 0; k < 4; k++)
                dh[r][q][k] = P->h[r][q + 1][k] - P->h[r][q][k];
}

/* c[r][k][i] = sum_q dh[r][q][k] hv[q][b0 + i]: the v-derivative column sums of one block. */
static inline void vsumh(double dh[4][3][4], double *const hv[4], int b0, int cnt, double c[4][4][BLK])
{
    const double *restrict v0 = hv[0] + b0, *restrict v1 = hv[1] + b0, *restrict v2 = hv[2] + b0;
    for (int r = 0; r < 4; r++)
        for (int k = 0; k < 4; k++) {
            double d0 = dh[r][0][k], d1 = dh[r][1][k], d2 = dh[r][2][k];
            double *restrict dst = c[r][k];
            for (int i = 0; i < cnt; i++)
                dst[i] = d0 * v0[i] + d1 * v1[i] + d2 * v2[i];
            for (int i = cnt; i < BLK && (i & 7); i++)
                dst[i] = 0.0;
        }
}

/* The u-sums of a point as the Horner forms of row_consts (T: the row's constants; rev: the
 * reversed form past u = 1/2), over lambda; the hodograph's over mu, on the differences
 * c_q+1 - c_q, formed the same way in every kernel so that the bits agree. */
#define HOR3(a0, a1, a2, a3) ((((a3)*T[0] + (a2)) * T[1] + (a1)) * T[2] + (a0))
#define HOR2(d0, d1, d2) (((d2)*T[3] + (d1)) * T[4] + (d0))
#define RSUMP(c, k)                                                                                    \
    (rev ? HOR3(c[3][k][i], c[2][k][i], c[1][k][i], c[0][k][i]) : HOR3(c[0][k][i], c[1][k][i], c[2][k][i], c[3][k][i]))
#define DIF(c, k, q) (c[(q) + 1][k][i] - c[q][k][i])
#define RSUMHP(c, k) (rev ? HOR2(DIF(c, k, 2), DIF(c, k, 1), DIF(c, k, 0)) : HOR2(DIF(c, k, 0), DIF(c, k, 1), DIF(c, k, 2)))
/* sum_r U[r] c[r][k][i] (U: the row's B'' values) */
#define USUM(U, c, k) (U[0] * c[0][k][i] + U[1] * c[1][k][i] + U[2] * c[2][k][i] + U[3] * c[3][k][i])

/* Positions of one row segment of cnt points. */
static inline void seg_pos(const double *restrict T, double c[4][4][BLK], int cnt, double *restrict pos,
                           const int rev)
{
    for (int i = 0; i < cnt; i++) {
        double X = RSUMP(c, 0), Y = RSUMP(c, 1), Z = RSUMP(c, 2), W = RSUMP(c, 3);
        double iw = 1.0 / W;
        pos[3 * i] = X * iw;
        pos[3 * i + 1] = Y * iw;
        pos[3 * i + 2] = Z * iw;
    }
}

/* Unit normal n of a x b, 0 where |a x b|^2 <= 1e-30 |a|^2 |b|^2 (branch-free; invariant under
 * positive scalings of a and b); returns 1 where defined, else 0. Shared by both portable kernels,
 * so positions and normals do not depend on which outputs were requested (bitwise). */
static inline double normal1(const double a[3], const double b[3], double n[3])
{
    double cx = a[1] * b[2] - a[2] * b[1];
    double cy = a[2] * b[0] - a[0] * b[2];
    double cz = a[0] * b[1] - a[1] * b[0];
    double l2 = cx * cx + cy * cy + cz * cz;
    double E = a[0] * a[0] + a[1] * a[1] + a[2] * a[2], G = b[0] * b[0] + b[1] * b[1] + b[2] * b[2];
    double ok = (double)(l2 > 1e-30 * (E * G));
    double il = ok / sqrt(l2 + (1.0 - ok));
    n[0] = cx * il;
    n[1] = cy * il;
    n[2] = cz * il;
    return ok;
}

/* Positions and unit normals of one row segment: the normal of the tangents over their scales
 * (a = hu' - hu'_w p, b = hv' - hv'_w p, see row_consts). */
static inline void seg_pos_normal(const double *restrict T, double c0[4][4][BLK], double c1[4][4][BLK], int cnt,
                                  double *restrict pos, double *restrict nrm, const int rev)
{
    for (int i = 0; i < cnt; i++) {
        double h[4], hu[4], hv[4];
#pragma GCC unroll 4
        for (int k = 0; k < 4; k++) {
            h[k] = RSUMP(c0, k);
            hu[k] = RSUMHP(c0, k);
            hv[k] = RSUMP(c1, k);
        }
        double iw = 1.0 / h[3];
        double p[3], a[3], b[3];
#pragma GCC unroll 3
        for (int k = 0; k < 3; k++) {
            p[k] = h[k] * iw;
            a[k] = hu[k] - hu[3] * p[k];
            b[k] = hv[k] - hv[3] * p[k];
        }
        double n[3];
        normal1(a, b, n);
        pos[3 * i] = p[0];
        pos[3 * i + 1] = p[1];
        pos[3 * i + 2] = p[2];
        nrm[3 * i] = n[0];
        nrm[3 * i + 1] = n[1];
        nrm[3 * i + 2] = n[2];
    }
}

static inline void put3(double *restrict dst, const double *restrict x, const double *restrict y,
                        const double *restrict z, int cnt)
{
    for (int i = 0; i < cnt; i++) {
        dst[3 * i] = x[i];
        dst[3 * i + 1] = y[i];
        dst[3 * i + 2] = z[i];
    }
}

/* Everything (second order) of one row segment in structure-of-arrays form. */
typedef struct {
    _Alignas(64) double p[3][BLK];
    _Alignas(64) double su[3][BLK];
    _Alignas(64) double sv[3][BLK];
    _Alignas(64) double suu[3][BLK];
    _Alignas(64) double suv[3][BLK];
    _Alignas(64) double svv[3][BLK];
    _Alignas(64) double nn[3][BLK];
    _Alignas(64) double K[BLK];
    _Alignas(64) double H[BLK];
} soa_full;

/* The formulas of rg2_patch_eval for the points 0 <= i < cnt of a row segment, from the scaled
 * u-sums of row_consts as full_avx512 (which gives the formulas); huu is the Bernstein sum (DDU). */
static inline __attribute__((always_inline)) void
full_soa_rev(const double *restrict T, const double *restrict DDU, double c0[4][4][BLK], double c1[4][4][BLK],
             double c2[4][4][BLK], int cnt, soa_full *restrict S, const int rev)
{
    double(*p)[BLK] = S->p, (*su)[BLK] = S->su, (*sv)[BLK] = S->sv, (*suu)[BLK] = S->suu;
    double(*suv)[BLK] = S->suv, (*svv)[BLK] = S->svv, (*nn)[BLK] = S->nn, *KK = S->K, *HH = S->H;
    const double fu = T[5], rl = T[6], m2 = T[7];
    for (int i = 0; i < cnt; i++) {
        double h[4], hu[4], hv[4], huu[4], huv[4], hvv[4];
#pragma GCC unroll 4
        for (int k = 0; k < 4; k++) {
            h[k] = RSUMP(c0, k);
            hu[k] = RSUMHP(c0, k);
            hv[k] = RSUMP(c1, k);
            huu[k] = USUM(DDU, c0, k);
            huv[k] = RSUMHP(c1, k);
            hvv[k] = RSUMP(c2, k);
        }
        double iw = 1.0 / h[3], iwu = iw * fu, iwl = iw * rl;
        double P[3], A[3], B[3], Su[3], Sv[3], Suu[3], Suv[3], Svv[3];
#pragma GCC unroll 3
        for (int k = 0; k < 3; k++) {
            P[k] = h[k] * iw;
            A[k] = hu[k] - hu[3] * P[k];
            B[k] = hv[k] - hv[3] * P[k];
            Su[k] = A[k] * iwu;
            Sv[k] = B[k] * iw;
            Suu[k] = (huu[k] - m2 * hu[3] * Su[k] - huu[3] * P[k]) * iwl;
            Suv[k] = (fu * (huv[k] - hu[3] * Sv[k] - huv[3] * P[k]) - hv[3] * Su[k]) * iw;
            Svv[k] = (hvv[k] - 2.0 * hv[3] * Sv[k] - hvv[3] * P[k]) * iw;
        }
        /* where the normal is undefined (ok = 0): n = 0, L = M = N = 0 and K = H = 0 over a
         * denominator >= 1 */
        double nv[3];
        double ok = normal1(A, B, nv);
        double E = Su[0] * Su[0] + Su[1] * Su[1] + Su[2] * Su[2];
        double F = Su[0] * Sv[0] + Su[1] * Sv[1] + Su[2] * Sv[2];
        double G = Sv[0] * Sv[0] + Sv[1] * Sv[1] + Sv[2] * Sv[2];
        double n0 = nv[0], n1 = nv[1], n2 = nv[2];
        double L = Suu[0] * n0 + Suu[1] * n1 + Suu[2] * n2;
        double M = Suv[0] * n0 + Suv[1] * n1 + Suv[2] * n2;
        double N = Svv[0] * n0 + Svv[1] * n1 + Svv[2] * n2;
        /* (EG - F^2 cancels: at a collapsed side's noise tangents it can come out 0 or below
         * where ok = 1, a division by zero a trapping host sees; such points count as undefined
         * here, and fix_collapsed gives them rg2_patch_eval's values) */
        double det = E * G - F * F;
        ok *= (double)(det > 1e-30 * (E * G));
        det = det * ok + (1.0 - ok);
#pragma GCC unroll 3
        for (int k = 0; k < 3; k++) {
            p[k][i] = P[k];
            su[k][i] = Su[k];
            sv[k][i] = Sv[k];
            suu[k][i] = Suu[k];
            suv[k][i] = Suv[k];
            svv[k][i] = Svv[k];
        }
        nn[0][i] = n0;
        nn[1][i] = n1;
        nn[2][i] = n2;
        double idet = 1.0 / det;
        KK[i] = (L * N - M * M) * idet;
        HH[i] = (E * N - 2.0 * F * M + G * L) * (0.5 * idet);
    }
}

RG2_HOT static void full_soa(const double *restrict T, const double *restrict DDU, double c0[4][4][BLK],
                             double c1[4][4][BLK], double c2[4][4][BLK], int cnt, soa_full *restrict S, int rev)
{
    if (rev)
        full_soa_rev(T, DDU, c0, c1, c2, cnt, S, 1);
    else
        full_soa_rev(T, DDU, c0, c1, c2, cnt, S, 0);
}

/* Copy a computed row segment to the requested outputs at point index `at`. */
static void full_out(const soa_full *S, int cnt, const rg2_grid_out *o, size_t at)
{
    size_t o3 = 3 * at;
    put3(o->pos + o3, S->p[0], S->p[1], S->p[2], cnt);
    struct {
        double *dst;
        const double(*src)[BLK];
    } vec[] = {{o->normal, S->nn}, {o->du, S->su}, {o->dv, S->sv}, {o->duu, S->suu}, {o->duv, S->suv},
               {o->dvv, S->svv}};
    for (int q = 0; q < 6; q++)
        if (vec[q].dst)
            put3(vec[q].dst + o3, vec[q].src[0], vec[q].src[1], vec[q].src[2], cnt);
    if (o->K)
        memcpy(o->K + at, S->K, sizeof(double) * (size_t)cnt);
    if (o->H)
        memcpy(o->H + at, S->H, sizeof(double) * (size_t)cnt);
}
#undef HOR3
#undef HOR2
#undef RSUMP
#undef DIF
#undef RSUMHP
#undef USUM

#if RG2_AVX512
#define RG2_AVX512_FN __attribute__((target("avx512f,avx512dq,fma,prfchw")))

/* 1 / x: with hw, the division (correctly rounded; on CPUs whose divider is fast, it runs
 * beside the multiply-add pipes, see grid_hwdiv); else rcp14 then two Newton steps (relative
 * error 2^-14 -> 2^-28 -> 2^-56, ~1 ulp: 5 multiply-adds). */
RG2_AVX512_FN static inline __m512d recip8(__m512d x, int hw)
{
    const __m512d one = _mm512_set1_pd(1.0);
    if (hw)
        return _mm512_div_pd(one, x);
    __m512d y = _mm512_rcp14_pd(x);
    y = _mm512_fmadd_pd(y, _mm512_fnmadd_pd(x, y, one), y);
    return _mm512_fmadd_pd(y, _mm512_fnmadd_pd(x, y, one), y);
}

/* 1 / sqrt(x) to ~1 ulp: rsqrt14 then two Newton steps y (3/2 - (x/2) y^2), 3 operations each, on
 * every CPU: on AMD Zen 4 the square root and division took 24 cycles of the divider per 8 points
 * (15 and 9) beside the 1 / w of the positions, and the Newton steps made the normals 1.04-1.07x
 * faster (medians of 25 alternating calls, torus, merged-size and free-form grids). */
RG2_AVX512_FN static inline __m512d rsqrt8(__m512d x)
{
    const __m512d c15 = _mm512_set1_pd(1.5);
    __m512d hx = _mm512_mul_pd(_mm512_set1_pd(0.5), x), y = _mm512_rsqrt14_pd(x);
    for (int it = 0; it < 2; it++)
        y = _mm512_mul_pd(y, _mm512_fnmadd_pd(_mm512_mul_pd(hx, y), y, c15));
    return y;
}

/* The row's Horner forms (row_consts): T holds t/3, t, 3t, t/2, 2t broadcast. */
RG2_AVX512_FN static inline __m512d hor3(__m512d c0, __m512d c1, __m512d c2, __m512d c3, const __m512d T[5])
{
    return _mm512_fmadd_pd(_mm512_fmadd_pd(_mm512_fmadd_pd(c3, T[0], c2), T[1], c1), T[2], c0);
}

RG2_AVX512_FN static inline __m512d hor2(__m512d d0, __m512d d1, __m512d d2, const __m512d T[5])
{
    return _mm512_fmadd_pd(_mm512_fmadd_pd(d2, T[3], d1), T[4], d0);
}

/* The u-sums of a row (sum_r B_r(u) c[r][k], over lambda) and of its hodograph (over mu) from column
 * sums in registers; rev: the reversed form past u = 1/2 (a constant in every caller). */
#define RSUM(rev, c, k, T) ((rev) ? hor3(c[3][k], c[2][k], c[1][k], c[0][k], T) : hor3(c[0][k], c[1][k], c[2][k], c[3][k], T))
#define RSUMH(rev, d, k, T) ((rev) ? hor2(d[2][k], d[1][k], d[0][k], T) : hor2(d[0][k], d[1][k], d[2][k], T))

/* a . b for 8 points */
RG2_AVX512_FN static inline __m512d dot8(const __m512d a[3], const __m512d b[3])
{
    return _mm512_fmadd_pd(a[2], b[2], _mm512_fmadd_pd(a[1], b[1], _mm512_mul_pd(a[0], b[0])));
}

/* Unit normal n = a x b / |a x b|, 0 where |a x b|^2 <= 1e-30 (a.a) (b.b), in two phases: cross8r
 * gives c = a x b (3 vectors) and returns |c|^2 (NaN where the normal is undefined), which the
 * two-phase kernels store at nb (32 doubles, pos_cross8); unit8r (unit8 from nb) turns them into
 * unit normals and returns the mask of points where they are defined. The
 * row kernels form all the cross products of a row (or of a few short rows) before the first
 * square root, so that the long latency of the square root and division no longer holds up the
 * next points' sums, and the normals of a row are stored together (streaming stores: 1.15x for
 * 8 x 8 patches in main memory, AMD Zen 4; rows wider than 8 points now interleave the two
 * phases 8 points apart, seg_cross_unit_avx512). a, b are the tangents over a positive scale
 * (hu - hu_w p, hv - hv_w p with p = h / w and the scaled sums of row_consts, one multiply-add
 * per component), which the normalisation cancels and the test is invariant under.
 * The test is taken as |a x b|^2 > 1e-30 (a.b)^2: by Lagrange's identity (a.a)(b.b) =
 * |a x b|^2 + (a.b)^2 the two differ by the factor 1 - 1e-30 (and rounding), and one dot product
 * takes the place of two. Shared by all AVX-512 kernels (same bits).
 * bounded (the row kernels of wide patches): thr is cross_threshold's bound on 1e-30 (a.b)^2 over
 * the patch, and when every lane not in pad (lanes past the row's end) has |a x b|^2 > thr, all
 * pass the test without it (a.b and the products: 5 multiply-adds per 8 points, normals 1.02-1.11x
 * on 16- to 256-point rows, AMD Zen 4); the lanes are decided as by the test, so the same bits.
 * 8 x 8 patches test every point: there the bound cost as much as it saved. */
RG2_AVX512_FN static inline __m512d cross8r(const __m512d a[3], const __m512d b[3], __m512d c[3], __m512d thr,
                                            __mmask8 pad, const int bounded)
{
    c[0] = _mm512_fmsub_pd(a[1], b[2], _mm512_mul_pd(a[2], b[1]));
    c[1] = _mm512_fmsub_pd(a[2], b[0], _mm512_mul_pd(a[0], b[2]));
    c[2] = _mm512_fmsub_pd(a[0], b[1], _mm512_mul_pd(a[1], b[0]));
    __m512d l2 = dot8(c, c);
    if (bounded && __builtin_expect((__mmask8)(_mm512_cmp_pd_mask(l2, thr, _CMP_GT_OQ) | pad) == 0xff, 1))
        return l2;
    __m512d F = dot8(a, b);
    __mmask8 ok = _mm512_cmp_pd_mask(l2, _mm512_mul_pd(_mm512_mul_pd(_mm512_set1_pd(1e-30), F), F), _CMP_GT_OQ);
    return _mm512_mask_mov_pd(_mm512_set1_pd(__builtin_nan("")), ok, l2);
}

/* A bound thr >= 1e-30 (a.b)^2 over all points of patch P, for the tangents a, b of pos_cross8
 * (the scaled sums of row_consts): points with |a x b|^2 > thr pass cross8r's test whatever a.b is.
 * M = max |h[r][s][k]| (all four components), w_min = min h[r][s][3]. The column sums are
 * Bernstein sums, at most M; their differences 2 M; the v-derivative ones (weights 3 B^2_q(v),
 * summing to 3, on differences) 6 M. Along u the scaled sums c0 + 3 c1 t + 3 c2 t^2 + c3 t^3 and
 * d0 + 2 d1 t + d2 t^2 (t <= 1) are at most 8 and 4 times their largest coefficient: |h| <= 8 M,
 * |hu| <= 8 M, |hv| <= 48 M. With every weight positive the point p = h / w is a convex
 * combination of the control points h / w, so |p_k| <= M / w_min, and with S = M (1 + M / w_min)
 * |a_k| = |hu_k - hu_w p_k| <= 8 S, |b_k| <= 48 S, (a.b)^2 <= |a|^2 |b|^2 <= 1327104 S^4.
 * thr = 1e-30 * 2e6 S^4 (a margin of 1.5 for rounding). +inf (every point tested) when a weight
 * is not positive, or the numbers are out of range: thr below 1e-280 (the test's products would
 * be subnormal) or 2e6 S^4 above 1e300 (|a x b|^2 could overflow to inf, which the test rejects). */
RG2_AVX512_FN static inline __m512d cross_threshold(const rg2_patch *P)
{
    const double *h = &P->h[0][0][0];
    __m512d mx = _mm512_setzero_pd(), wmin = _mm512_set1_pd(__builtin_inf());
    for (int q = 0; q < 8; q++) {
        __m512d x = _mm512_loadu_pd(h + 8 * q);
        mx = _mm512_max_pd(mx, _mm512_abs_pd(x));
        wmin = _mm512_mask_min_pd(wmin, 0x88, wmin, x);
    }
    double M = _mm512_reduce_max_pd(mx), wm = _mm512_reduce_min_pd(wmin), thr = __builtin_inf();
    if (wm > 0) { /* (S below 1e75 first: 2e6 S^4 is then below 1e307 and raises no FE_OVERFLOW; above,
                   * bound > 1e300 and thr stays +inf) */
        double S = M * (1.0 + M / wm);
        if (S < 1e75) {
            double bound = 2e6 * (S * S) * (S * S);
            thr = 1e-30 * bound;
            if (!(thr >= 1e-280) || !(bound <= 1e300))
                thr = __builtin_inf();
        }
    }
    return _mm512_set1_pd(thr);
}

RG2_AVX512_FN static inline __mmask8 unit8r(const __m512d c[3], __m512d l2, __m512d n[3])
{
    __mmask8 ok = _mm512_cmp_pd_mask(l2, l2, _CMP_ORD_Q);
    __m512d il = _mm512_maskz_mov_pd(ok, rsqrt8(l2)); /* (lanes not ok: whatever rsqrt8 gave, zeroed) */
    for (int k = 0; k < 3; k++)
        n[k] = _mm512_mul_pd(c[k], il);
    return ok;
}

/* Both phases at once, in registers (the second-order kernel): every point tested, so the same
 * bits. */
RG2_AVX512_FN static inline __mmask8 normal8(const __m512d a[3], const __m512d b[3], __m512d n[3])
{
    __m512d c[3], l2 = cross8r(a, b, c, _mm512_setzero_pd(), 0, 0);
    return unit8r(c, l2, n);
}

/* Points x, y, z of 8 lanes interleaved as 24 doubles in o[0..2], in the kernels' form for AMD's
 * cores or Intel's (amd: the hw of grid_hwdiv, a constant in every kernel). On AMD one
 * single-source permute per input puts each value in the lane it takes in its output vector
 * (px = x0 x3 x6 x1 x4 x7 x2 x5, py = y5 y0 y3 y6 y1 y4 y7 y2, pz = z2 z5 z0 z3 z6 z1 z4 z7), and
 * each output is two blends of them: 3 permutes and 6 blends instead of 6 two-source permutes
 * (the shuffle pipes were a limit of the 8 x 8 normal kernel: +3-6 % there, +3-5 % for 64-point
 * rows with normals, AMD Zen 5). On Intel, where blends and multiply-adds share the two 512-bit
 * ports, the 6 two-source permutes (3 instructions fewer) are faster: normals 0.98-1.10x, 1.02x in
 * the middle of 18 pairs (torus, merged design, free-form mesh; medians of 31-61 alternating
 * calls, Sapphire Rapids class, fourteenth stop). The same bits either way. */
RG2_AVX512_FN static inline __attribute__((always_inline)) void xyz8(__m512d x, __m512d y, __m512d z, __m512d o[3],
                                                                     const int amd)
{
    if (!amd) { /* o[j] from x and y, then z: lanes 0-7 of the first source, 8-15 of the second */
        const __m512i a0 = _mm512_set_epi64(10, 2, 0, 9, 1, 0, 8, 0), b0 = _mm512_set_epi64(7, 6, 9, 4, 3, 8, 1, 0);
        const __m512i a1 = _mm512_set_epi64(5, 0, 12, 4, 0, 11, 3, 0), b1 = _mm512_set_epi64(7, 12, 5, 4, 11, 2, 1, 10);
        const __m512i a2 = _mm512_set_epi64(0, 15, 7, 0, 14, 6, 0, 13), b2 = _mm512_set_epi64(15, 6, 5, 14, 3, 2, 13, 0);
        o[0] = _mm512_permutex2var_pd(_mm512_permutex2var_pd(x, a0, y), b0, z);
        o[1] = _mm512_permutex2var_pd(_mm512_permutex2var_pd(x, a1, y), b1, z);
        o[2] = _mm512_permutex2var_pd(_mm512_permutex2var_pd(x, a2, y), b2, z);
        return;
    }
    const __m512i ix = _mm512_set_epi64(5, 2, 7, 4, 1, 6, 3, 0), iy = _mm512_set_epi64(2, 7, 4, 1, 6, 3, 0, 5);
    const __m512i iz = _mm512_set_epi64(7, 4, 1, 6, 3, 0, 5, 2);
    __m512d px = _mm512_permutexvar_pd(ix, x), py = _mm512_permutexvar_pd(iy, y), pz = _mm512_permutexvar_pd(iz, z);
    /* o0: x at lanes 0 3 6, y at 1 4 7, z at 2 5; o1: x 1 4 7, y 2 5, z 0 3 6; o2: x 2 5, y 0 3 6, z 1 4 7 */
    o[0] = _mm512_mask_blend_pd(0x24, _mm512_mask_blend_pd(0x92, px, py), pz);
    o[1] = _mm512_mask_blend_pd(0x49, _mm512_mask_blend_pd(0x24, px, py), pz);
    o[2] = _mm512_mask_blend_pd(0x92, _mm512_mask_blend_pd(0x49, px, py), pz);
}

/* How a row segment reaches memory: plain stores, streaming stores straight into a 64-byte
 * aligned destination of whole vectors (ST_STREAM_PF: the same, but the first line of each page,
 * which the caller asked for ahead with prefetch_pages, as a plain store: stream_line), or
 * streaming stores of the vectors shifted to the cache lines of any other destination (shifter;
 * the kernels that do not shift, the two-phase normals, store such rows to an L1 buffer and
 * stream it out). */
enum { ST_PLAIN, ST_STREAM, ST_SHIFT, ST_STREAM_PF };

/* Plain stores ask for the lines this far ahead (doubles) with prefetchw, so that the reads for
 * ownership are under way before the stores reach them (+25 % for 4.7 MB of positions in L3). */
#ifndef RG2_PREFETCHW_AHEAD
#define RG2_PREFETCHW_AHEAD 384
#endif

#ifndef RG2_POS_ROWS
#define RG2_POS_ROWS 4 /* rows per pass of seg_pos_cxr_avx512 (1 row: 0.85-0.88x in L2 and L3, AMD Zen 5) */
#endif
_Static_assert(RG2_POS_ROWS >= 1 && RG2_POS_ROWS <= 4, "seg_pos_cxr_avx512 holds at most 4 rows");

#ifndef RG2_PATCH_AHEAD
#define RG2_PATCH_AHEAD 1
#endif

/* One whole cache line of output at dst (64-byte aligned) for ST_STREAM_PF: streamed, except the
 * first line of a page, which goes out as a plain store. The caller asked for that line ahead of
 * time (prefetch_pages) for the page's address translation, so the caches hold it, and a
 * streaming store to a line the caches hold has to evict it first (see prefetch_pages). */
RG2_AVX512_FN static inline __attribute__((always_inline)) void stream_line(double *dst, __m512d v)
{
    if (__builtin_expect(((uintptr_t)dst & 4095) < 64, 0))
        _mm512_store_pd(dst, v);
    else
        _mm512_stream_pd(dst, v);
}

/* 8 interleaved points (24 doubles) at dst: q < 8 stores only 3 q doubles (masked); plain
 * stores first ask for the lines `ahead` doubles further on. */
RG2_AVX512_FN static inline __attribute__((always_inline)) void put8a(double *dst, const __m512d o[3], int q, int st,
                                                                      size_t ahead)
{
    if (st == ST_PLAIN) /* (prefetches never fault, past the array's end included) */
        for (int k = 0; k < 3; k++)
            __builtin_prefetch(dst + ahead + 8 * k, 1, 3);
    if (st == ST_STREAM) {
        _mm512_stream_pd(dst, o[0]);
        _mm512_stream_pd(dst + 8, o[1]);
        _mm512_stream_pd(dst + 16, o[2]);
    } else if (st == ST_STREAM_PF) {
        stream_line(dst, o[0]);
        stream_line(dst + 8, o[1]);
        stream_line(dst + 16, o[2]);
    } else if (q == 8) {
        _mm512_storeu_pd(dst, o[0]);
        _mm512_storeu_pd(dst + 8, o[1]);
        _mm512_storeu_pd(dst + 16, o[2]);
    } else {
        for (int k = 0, left = 3 * q; k < 3 && left > 0; k++, left -= 8)
            _mm512_mask_storeu_pd(dst + 8 * k, (__mmask8)(left >= 8 ? 0xff : (1u << left) - 1u), o[k]);
    }
}

RG2_AVX512_FN static inline __attribute__((always_inline)) void put8(double *dst, const __m512d o[3], int q, int st)
{
    put8a(dst, o, q, st, RG2_PREFETCHW_AHEAD);
}

/* Copy n doubles with streaming stores on the 64-byte aligned part of dst (whole cache lines
 * bypass the caches; the partial lines at both ends are stored normally). */
RG2_AVX512_FN static void stream_copy(double *dst, const double *src, int n)
{
    int h = 0;
    for (; h < n && ((uintptr_t)(dst + h) & 63); h++)
        dst[h] = src[h];
    for (; h + 8 <= n; h += 8)
        _mm512_stream_pd(dst + h, _mm512_loadu_pd(src + h));
    for (; h < n; h++)
        dst[h] = src[h];
}

/* A row segment streamed to a destination that does not start on a cache line, or does not end
 * on one (ST_SHIFT): the interleaved output vectors are shifted by the destination's
 * misalignment s (doubles) as they come, each by one two-source permute with the previous one, so
 * that the whole lines go out as streaming stores at the pace they are computed and the partial
 * lines at both ends (shared with the neighbouring segments) as masked plain stores; a segment
 * that the next one continues (keep) hands it its last, partial line instead. */
typedef struct {
    double *a;        /* the 64-byte aligned address at or before the segment's start */
    __m512i idx;      /* lanes 8 - s .. 15 - s of (previous, current) */
    __m512d prev;     /* the vector pushed last */
    __m512d tail;     /* has_tail: the segment's last, partial vector, for the next segment */
    long s, len, j;   /* misalignment (doubles), doubles to store, aligned vectors stored so far */
    long lo_min;      /* the first valid lane's index: 0, or -s with the previous segment's tail */
    int keep, has_tail; /* keep: the next segment continues at the end of this one */
} shifter;

/* Start a segment of len doubles at dst. When the previous segment of w was kept (w->has_tail:
 * it ended at dst), its last s lanes lead this segment's first vector, so that the line they
 * share goes out whole; keep: this segment's last partial vector waits for the next one. */
RG2_AVX512_FN static inline void shift_init(shifter *w, double *dst, int len, int keep)
{
    const __m512i iota = _mm512_set_epi64(7, 6, 5, 4, 3, 2, 1, 0);
    long s = (long)(((uintptr_t)dst >> 3) & 7);
    if (w->has_tail) { /* prev[8 - s + l] = tail[l], l < s */
        __m512i rot = _mm512_and_si512(_mm512_add_epi64(iota, _mm512_set1_epi64(s)), _mm512_set1_epi64(7));
        w->prev = _mm512_permutexvar_pd(rot, w->tail);
        w->lo_min = -s;
    } else {
        w->prev = _mm512_setzero_pd();
        w->lo_min = 0;
    }
    w->s = s;
    w->a = dst - s;
    w->len = len;
    w->j = 0;
    w->keep = keep;
    w->has_tail = 0;
    w->idx = _mm512_add_epi64(_mm512_set1_epi64(8 - s), iota);
}

/* The next aligned vector of the destination: lane l holds dst[8 j + l - s]. */
RG2_AVX512_FN static inline __attribute__((always_inline)) void shift_store(shifter *w, __m512d v)
{
    long lo = 8 * w->j - w->s; /* the destination index of lane 0 */
    if (lo >= w->lo_min && lo + 8 <= w->len) {
        _mm512_stream_pd(w->a + 8 * w->j, v);
    } else if (w->keep && lo < w->len && lo + 8 > w->len) {
        w->tail = v;
        w->has_tail = 1;
    } else {
        unsigned m = 0xff;
        if (lo < w->lo_min)
            m &= 0xffu << (w->lo_min - lo);
        if (lo + 8 > w->len)
            m &= lo < w->len ? (1u << (w->len - lo)) - 1u : 0u;
        if (m)
            _mm512_mask_store_pd(w->a + 8 * w->j, (__mmask8)m, v);
    }
    w->j++;
}

/* 8 interleaved points (24 doubles) into the shifted stream. */
RG2_AVX512_FN static inline __attribute__((always_inline)) void shift_put8(shifter *w, const __m512d o[3])
{
    for (int k = 0; k < 3; k++) {
        shift_store(w, _mm512_permutex2var_pd(w->prev, w->idx, o[k]));
        w->prev = o[k];
    }
}

/* shift_put8 for the positions kernels: when the three vectors are whole lines inside the
 * segment, one test instead of three. Rows from 16 bytes past a line, free-form mesh at about
 * 150 MB: 33 points a row 1.20-1.26x, 65 points 1.38x, 129 points 1.14-1.18x, 257 points
 * 1.03-1.09x, 24, 40 and 64 points even, 28 points 0.96x (AMD Zen 5, old and new builds
 * alternating, medians of 7 calls, three to five rounds; not measured on Intel). The spread
 * normals take it for their positions (64 points a row from 16 bytes past a line 1.04-1.09x, 65
 * points from an aligned start 1.05-1.07x, medians of 7 calls, four rounds), not for the normals
 * themselves: with it there too they went 0.80-0.88x (and 0.90-0.96x with it in every shifted
 * store). */
RG2_AVX512_FN static inline __attribute__((always_inline)) void shift_put8_pos(shifter *w, const __m512d o[3])
{
    long lo = 8 * w->j - w->s;
    if (lo >= w->lo_min && lo + 24 <= w->len) {
        double *d = w->a + 8 * w->j;
        _mm512_stream_pd(d, _mm512_permutex2var_pd(w->prev, w->idx, o[0]));
        _mm512_stream_pd(d + 8, _mm512_permutex2var_pd(o[0], w->idx, o[1]));
        _mm512_stream_pd(d + 16, _mm512_permutex2var_pd(o[1], w->idx, o[2]));
        w->prev = o[2];
        w->j += 3;
    } else {
        shift_put8(w, o);
    }
}

/* The lanes of the last vector pushed that fall into the next aligned vector. */
RG2_AVX512_FN static inline void shift_end(shifter *w)
{
    shift_store(w, _mm512_permutex2var_pd(w->prev, w->idx, w->prev));
}

/* sum_s h[r][s][k] V[s] for 8 columns: the products rounded before the sums (no FMA), as
 * rg2_patch_eval rounds them. */
RG2_AVX512_FN static inline __m512d colsum8(const rg2_patch *P, const __m512d V[4], int r, int k)
{
    __m512d acc = _mm512_mul_pd(_mm512_set1_pd(P->h[r][0][k]), V[0]);
    acc = _mm512_add_pd(acc, _mm512_mul_pd(_mm512_set1_pd(P->h[r][1][k]), V[1]));
    acc = _mm512_add_pd(acc, _mm512_mul_pd(_mm512_set1_pd(P->h[r][2][k]), V[2]));
    return _mm512_add_pd(acc, _mm512_mul_pd(_mm512_set1_pd(P->h[r][3][k]), V[3]));
}

/* Column sums of one block, as vsum (past cnt, the padded tables' repeat of the last column). */
RG2_AVX512_FN static void vsum_avx512(const rg2_patch *P, double *const bv[4], int b0, int cnt,
                                      double c[4][4][BLK])
{
    for (int i = 0; i < cnt; i += 8) {
        __m512d V[4];
        for (int s = 0; s < 4; s++)
            V[s] = _mm512_loadu_pd(bv[s] + b0 + i);
        for (int r = 0; r < 4; r++)
            for (int k = 0; k < 4; k++)
                _mm512_store_pd(&c[r][k][i], colsum8(P, V, r, k));
    }
}

/* hdiff with 4-lane vectors (the same differences). */
RG2_AVX512_FN static inline void hdiff_avx(const rg2_patch *P, double dh[4][3][4])
{
    for (int r = 0; r < 4; r++)
        for (int q = 0; q < 3; q++)
            _mm256_storeu_pd(dh[r][q], _mm256_sub_pd(_mm256_loadu_pd(P->h[r][q + 1]), _mm256_loadu_pd(P->h[r][q])));
}

/* sum_q dh[r][q][k] V[q] for 8 columns (vsumh), products rounded before the sums. */
RG2_AVX512_FN static inline __m512d colsum8h(double dh[4][3][4], const __m512d V[3], int r, int k)
{
    __m512d acc = _mm512_mul_pd(_mm512_set1_pd(dh[r][0][k]), V[0]);
    acc = _mm512_add_pd(acc, _mm512_mul_pd(_mm512_set1_pd(dh[r][1][k]), V[1]));
    return _mm512_add_pd(acc, _mm512_mul_pd(_mm512_set1_pd(dh[r][2][k]), V[2]));
}

/* vsumh with vectors. */
RG2_AVX512_FN static void vsumh_avx512(double dh[4][3][4], double *const hv[4], int b0, int cnt,
                                       double c[4][4][BLK])
{
    for (int i = 0; i < cnt; i += 8) {
        __m512d V[3];
        for (int q = 0; q < 3; q++)
            V[q] = _mm512_loadu_pd(hv[q] + b0 + i);
        for (int r = 0; r < 4; r++)
            for (int k = 0; k < 4; k++)
                _mm512_store_pd(&c[r][k][i], colsum8h(dh, V, r, k));
    }
}

/* The 16 v-derivative column sums of a patch at most 8 points wide (vsumh), in registers. */
RG2_AVX512_FN static inline void vsumh_narrow(const rg2_patch *P, double *const hv[4], __m512d c[4][4])
{
    double dh[4][3][4];
    hdiff_avx(P, dh);
    __m512d V[3];
    for (int q = 0; q < 3; q++)
        V[q] = _mm512_loadu_pd(hv[q]); /* padded to 8 (tables_make) */
    for (int r = 0; r < 4; r++)
        for (int k = 0; k < 4; k++)
            c[r][k] = colsum8h(dh, V, r, k);
}

/* The 16 column sums of a patch at most 8 points wide, kept in registers. */
RG2_AVX512_FN static inline void vsum_narrow(const rg2_patch *P, double *const bv[4], __m512d c[4][4])
{
    __m512d V[4];
    for (int s = 0; s < 4; s++)
        V[s] = _mm512_loadu_pd(bv[s]); /* padded to 8 (tables_make) */
    for (int r = 0; r < 4; r++)
        for (int k = 0; k < 4; k++)
            c[r][k] = colsum8(P, V, r, k);
}

/* The 4 Bernstein values of a row broadcast to vectors. */
RG2_AVX512_FN static inline void bcast4(const double *U, __m512d u[4])
{
    for (int r = 0; r < 4; r++)
        u[r] = _mm512_set1_pd(U[r]);
}

/* A row's Horner constants t/3, t, 3t, t/2, 2t broadcast to vectors. */
RG2_AVX512_FN static inline void bcastT(const double *HT, __m512d T[5])
{
    for (int q = 0; q < 5; q++)
        T[q] = _mm512_set1_pd(HT[q]);
}

/* Columns i..i+7 of a block's column sums as vectors. */
RG2_AVX512_FN static inline void csum_at(double c[4][4][BLK], int i, __m512d v[4][4])
{
    for (int r = 0; r < 4; r++)
        for (int k = 0; k < 4; k++)
            v[r][k] = _mm512_load_pd(&c[r][k][i]);
}

/* Columns i..i+7 of a block's column sum differences (cdiff_block) as vectors. */
RG2_AVX512_FN static inline void cdiff_at(double d[3][4][BLK], int i, __m512d v[3][4])
{
    for (int q = 0; q < 3; q++)
        for (int k = 0; k < 4; k++)
            v[q][k] = _mm512_load_pd(&d[q][k][i]);
}

/* The differences of consecutive column sums of a block, d[q][k] = c[q + 1][k] - c[q][k] (the
 * hodograph's, RSUMH), once per block for the normal rows instead of once per row: 12
 * subtractions fewer per 8 points, normals 1.03-1.09x on 16- to 256-point rows (AMD Zen 4,
 * medians of 31-61 alternating calls; the same bits). */
RG2_AVX512_FN static void cdiff_block(double c[4][4][BLK], int cnt, double d[3][4][BLK])
{
    for (int i = 0; i < cnt; i += 8)
        for (int q = 0; q < 3; q++)
            for (int k = 0; k < 4; k++)
                _mm512_store_pd(&d[q][k][i], _mm512_sub_pd(_mm512_load_pd(&c[q + 1][k][i]), _mm512_load_pd(&c[q][k][i])));
}

/* The differences of consecutive column sums as vectors (the hodograph's, RSUMH). */
RG2_AVX512_FN static inline void cdiff_v(__m512d c[4][4], __m512d d[3][4])
{
    for (int q = 0; q < 3; q++)
        for (int k = 0; k < 4; k++)
            d[q][k] = _mm512_sub_pd(c[q + 1][k], c[q][k]);
}

/* Positions of 8 points of a row (T: its Horner constants) from their column sums c, interleaved
 * x, y, z in o[0..2]. */
RG2_AVX512_FN static inline __attribute__((always_inline)) void pos8(const __m512d T[5], __m512d c[4][4],
                                                                     __m512d o[3], int hw, const int rev)
{
    __m512d iw = recip8(RSUM(rev, c, 3, T), hw);
    xyz8(_mm512_mul_pd(RSUM(rev, c, 0, T), iw), _mm512_mul_pd(RSUM(rev, c, 1, T), iw),
         _mm512_mul_pd(RSUM(rev, c, 2, T), iw), o, hw);
}

/* Positions and unit normals of 8 points of a row (T: its Horner constants) from their column sums
 * c0, their differences dc and the v-derivative column sums c1: positions interleaved in po, the
 * cross product of the tangents (over their common scale) to cr, |cr|^2 returned (cross8r). The
 * expressions of full_avx512 (bitwise the same positions and normals). */
RG2_AVX512_FN static inline __attribute__((always_inline)) __m512d
pos_cross8r(const __m512d T[5], __m512d c0[4][4], __m512d dc[3][4], __m512d c1[4][4], __m512d po[3], __m512d cr[3],
            __m512d thr, __mmask8 pad, const int bounded, int hw, const int rev)
{
    __m512d iw = recip8(RSUM(rev, c0, 3, T), hw);
    __m512d hu3 = RSUMH(rev, dc, 3, T), hv3 = RSUM(rev, c1, 3, T);
    __m512d p[3], a[3], b[3];
    for (int k = 0; k < 3; k++) {
        p[k] = _mm512_mul_pd(RSUM(rev, c0, k, T), iw);
        a[k] = _mm512_fnmadd_pd(hu3, p[k], RSUMH(rev, dc, k, T));
        b[k] = _mm512_fnmadd_pd(hv3, p[k], RSUM(rev, c1, k, T));
    }
    __m512d l2 = cross8r(a, b, cr, thr, pad, bounded);
    xyz8(p[0], p[1], p[2], po, hw);
    return l2;
}

/* pos_cross8r with the cross product and its squared length stored at nb (seg_unit_avx512 reads them). */
RG2_AVX512_FN static inline __attribute__((always_inline)) void
pos_cross8(const __m512d T[5], __m512d c0[4][4], __m512d dc[3][4], __m512d c1[4][4], __m512d po[3], double *nb,
           __m512d thr, __mmask8 pad, const int bounded, int hw, const int rev)
{
    __m512d c[3], l2 = pos_cross8r(T, c0, dc, c1, po, c, thr, pad, bounded, hw, rev);
    for (int k = 0; k < 3; k++)
        _mm512_store_pd(nb + 8 * k, c[k]);
    _mm512_store_pd(nb + 24, l2);
}

/* Positions of one row segment of cnt points at dst, stored as st (short rows: see
 * seg_pos_cxr_avx512). */
RG2_AVX512_FN static inline __attribute__((always_inline)) void
seg_pos_avx512(const double *HT, double c[4][4][BLK], int cnt, double *dst, int st, shifter *w, int hw,
               const int rev)
{
    __m512d T[5];
    bcastT(HT, T);
    for (int i = 0; i < cnt; i += 8) { /* the last vector may be partial: padded, masked store */
        __m512d cv[4][4], o[3];
        csum_at(c, i, cv);
        pos8(T, cv, o, hw, rev);
        if (st == ST_SHIFT)
            shift_put8_pos(w, o);
        else
            put8(dst + 3 * i, o, cnt - i < 8 ? cnt - i : 8, st);
    }
    if (st == ST_SHIFT)
        shift_end(w);
}

/* The x, y, z column sums of a block interleaved like the output: cx[r][3 b + k] = c[r][k][b]. */
RG2_AVX512_FN static void interleave_csum(double c[4][4][BLK], int cnt, double cx[4][3 * BLK], int hw)
{
    for (int r = 0; r < 4; r++)
        for (int i = 0; i < cnt; i += 8) {
            __m512d o[3];
            xyz8(_mm512_load_pd(&c[r][0][i]), _mm512_load_pd(&c[r][1][i]), _mm512_load_pd(&c[r][2][i]), o, hw);
            for (int j = 0; j < 3; j++)
                _mm512_store_pd(&cx[r][3 * i + 8 * j], o[j]);
        }
}

/* Positions of R rows of cnt points (row k: Horner constants HT + 8 k, output at dst + k stride,
 * all in the form rev), from the interleaved column sums cx (x, y, z) and c (for w): the sums and
 * products of seg_pos_avx512 lane by lane (the same bits), with 1 / w spread to the x, y, z lanes
 * by 3 permutes instead of interleaving the results by 6 (pays off from about 16 rows per block:
 * interleave_csum costs 24 permutes per 8 columns). With R > 1 each column sum is loaded once for
 * all R rows and their reciprocal chains overlap; plain stores ask for the lines `ahead` doubles
 * on (with R rows per pass: R rows on, the next pass's); st ST_SHIFT takes one row. */
RG2_AVX512_FN static inline __attribute__((always_inline)) void
seg_pos_cxr_avx512(const double *HT, double c[4][4][BLK], double cx[4][3 * BLK], int cnt, double *dst,
                   size_t stride, size_t ahead, int st, shifter *w, int hw, const int R, const int rev)
{
    const __m512i sel[3] = {_mm512_set_epi64(2, 2, 1, 1, 1, 0, 0, 0), _mm512_set_epi64(5, 4, 4, 4, 3, 3, 3, 2),
                            _mm512_set_epi64(7, 7, 7, 6, 6, 6, 5, 5)};
    __m512d T[4][5];
    for (int k = 0; k < R; k++)
        bcastT(HT + 8 * k, T[k]);
    for (int i = 0; i < cnt; i += 8) {
        __m512d c3[4][1], iw[4], o[4][3];
        for (int r = 0; r < 4; r++)
            c3[r][0] = _mm512_load_pd(&c[r][3][i]);
        for (int k = 0; k < R; k++)
            iw[k] = recip8(RSUM(rev, c3, 0, T[k]), hw);
        for (int j = 0; j < 3; j++) {
            const double *q = &cx[0][3 * i + 8 * j];
            __m512d x[4][1] = {{_mm512_load_pd(q)}, {_mm512_load_pd(q + 3 * BLK)}, {_mm512_load_pd(q + 6 * BLK)},
                               {_mm512_load_pd(q + 9 * BLK)}};
            for (int k = 0; k < R; k++)
                o[k][j] = _mm512_mul_pd(RSUM(rev, x, 0, T[k]), _mm512_permutexvar_pd(sel[j], iw[k]));
        }
        int q = cnt - i < 8 ? cnt - i : 8;
        if (st == ST_SHIFT)
            shift_put8_pos(w, o[0]);
        else
            for (int k = 0; k < R; k++)
                put8a(dst + k * stride + 3 * i, o[k], q, st, ahead);
    }
    if (st == ST_SHIFT)
        shift_end(w);
}

/* Store mode of a patch at most 8 points wide written at dst: streamed when the rows are exactly
 * 8 points, straight from a 64-byte aligned start, and shifted to the cache lines from any other
 * (nshift: the patch's rows follow each other in memory, so only its first and last lines are
 * partial). Such arrays were stored plainly before, every line waiting on its read for ownership:
 * shifted, the free-form mesh's 38809 patches of 8 x 8 points from a start 16 bytes past a line
 * ran 1.07-1.22x (positions, 0.88-0.91 of an aligned start against 0.77-0.83) and 1.02-1.32x with
 * normals (0.88-1.02 against 0.81-0.90; medians of 15-21 calls alternating the three ways, five
 * rounds, Intel machine). */
static inline int narrow_mode(const tables *t, const double *dst)
{
    if (!t->stream || t->m != 8)
        return ST_PLAIN;
    return (uintptr_t)dst & 63 ? ST_SHIFT : ST_STREAM;
}

/* A patch of rows of exactly 8 points, streamed from a start s doubles past a cache line
 * (ST_SHIFT): its n rows are one run of 3 n vectors, shifted by s as a shifter does (lane l of the
 * aligned vector j holds dst[8 j + l - s]) but without the shifter's bookkeeping. Only the first
 * and the last line are partial, stored plainly and shared with the neighbouring patches. */
typedef struct {
    double *a;   /* the 64-byte aligned address at or before the start */
    __m512i idx; /* lanes 8 - s .. 15 - s of (previous, current) */
    __m512d prev;
    unsigned s;
} nshift;

/* A plain store that waits on its read for ownership holds up the streamed ones behind it. So a
 * shifted patch asks for the partial lines of the patch this many on (prefetchw: nshift_init, and
 * grid_range for wider rows), for those reads to be done when their stores come. */
#ifndef RG2_SHIFT_AHEAD
#define RG2_SHIFT_AHEAD 2
#endif

RG2_AVX512_FN static inline __attribute__((always_inline)) void nshift_init(nshift *w, double *dst, int n)
{
    w->s = (unsigned)(((uintptr_t)dst >> 3) & 7);
    w->a = dst - w->s;
    w->idx = _mm512_add_epi64(_mm512_set1_epi64(8 - (long long)w->s), _mm512_set_epi64(7, 6, 5, 4, 3, 2, 1, 0));
    w->prev = _mm512_setzero_pd();
    __builtin_prefetch(dst + RG2_SHIFT_AHEAD * 24 * (size_t)n, 1, 3);
}

/* Row r's 8 points (24 doubles, interleaved in o). */
RG2_AVX512_FN static inline __attribute__((always_inline)) void nshift_row(nshift *w, const __m512d o[3], int r)
{
    __m512d v0 = _mm512_permutex2var_pd(w->prev, w->idx, o[0]);
    double *d = w->a + 24 * r;
    if (r)
        _mm512_stream_pd(d, v0);
    else
        _mm512_mask_store_pd(d, (__mmask8)(0xffu << w->s), v0);
    _mm512_stream_pd(d + 8, _mm512_permutex2var_pd(o[0], w->idx, o[1]));
    _mm512_stream_pd(d + 16, _mm512_permutex2var_pd(o[1], w->idx, o[2]));
    w->prev = o[2];
}

/* After the last of n rows: the lanes of the last vector that fall into the next line (none from
 * an aligned start, whose run ends on a line: no store at the array's end then). */
RG2_AVX512_FN static inline __attribute__((always_inline)) void nshift_end(nshift *w, int n)
{
    if (w->s)
        _mm512_mask_store_pd(w->a + 24 * n, (__mmask8)((1u << w->s) - 1u),
                             _mm512_permutex2var_pd(w->prev, w->idx, w->prev));
}

/* The rows of patch_pos_narrow_avx512 from the column sums c, stored as st or (shift) into one
 * shifted run. */
RG2_AVX512_FN static inline __attribute__((always_inline)) void
pos_narrow_rows(const tables *t, __m512d c[4][4], double *pos, int st, int hw, const int shift)
{
    const int n = t->n, m = t->m;
    nshift w;
    if (shift)
        nshift_init(&w, pos, n);
    for (int a = 0; a < n; a++) {
        __m512d T[5], o[3];
        bcastT(t->ht + 8 * a, T);
        if (a < t->arev)
            pos8(T, c, o, hw, 0);
        else
            pos8(T, c, o, hw, 1);
        if (shift)
            nshift_row(&w, o, a);
        else
            put8(pos + 3 * m * a, o, m, st);
    }
    if (shift)
        nshift_end(&w, n);
}

/* Positions of a patch at most 8 points wide (m <= 8, every row one vector), written at pos: the
 * 16 column sums stay in registers and the rows need no block bookkeeping (small per-patch grids
 * of large meshes). The column sums of vsum_avx512 and pos8 as in seg_pos_avx512: the same bits. */
RG2_AVX512_FN static inline void patch_pos_narrow_avx512(const rg2_patch *P, const tables *t, double *pos,
                                                        int hw)
{
    const int st = narrow_mode(t, pos);
    __m512d c[4][4];
    vsum_narrow(P, t->bv, c);
    if (st == ST_SHIFT)
        pos_narrow_rows(t, c, pos, st, hw, 1);
    else
        pos_narrow_rows(t, c, pos, st, hw, 0);
}

/* The unit normals of 8 points from their cross products c and |c|^2 (unit8r), interleaved (in
 * no; unit_put8: stored at dst as st, q points). */
RG2_AVX512_FN static inline __attribute__((always_inline)) void unit_xyz8(const __m512d c[3], __m512d l2, __m512d no[3],
                                                                          int hw)
{
    __m512d nn[3];
    unit8r(c, l2, nn);
    xyz8(nn[0], nn[1], nn[2], no, hw);
}

RG2_AVX512_FN static inline __attribute__((always_inline)) void unit_put8(const __m512d c[3], __m512d l2, double *dst,
                                                                          int q, int st, int hw)
{
    __m512d no[3];
    unit_xyz8(c, l2, no, hw);
    put8(dst, no, q, st);
}

/* The second phase: the unit normals of the segment from nb, at nd. */
RG2_AVX512_FN static inline void seg_unit_avx512(double (*nb)[32], int cnt, double *nd, int st, int hw)
{
    for (int i = 0; i < cnt; i += 8) {
        const double *b = nb[i / 8];
        __m512d c[3] = {_mm512_load_pd(b), _mm512_load_pd(b + 8), _mm512_load_pd(b + 16)};
        unit_put8(c, _mm512_load_pd(b + 24), nd + 3 * i, cnt - i < 8 ? cnt - i : 8, st, hw);
    }
}

/* The rows of patch_normal_narrow_avx512 with each row's normals after the next row's positions,
 * the cross products kept in registers; stored as st or (shift) into one shifted run an array. */
RG2_AVX512_FN static inline __attribute__((always_inline)) void
normal_narrow_lagged(const tables *t, __m512d c0[4][4], __m512d dc[3][4], __m512d c1[4][4], double *pos,
                     double *nrm, int st, int hw, const int shift)
{
    const int n = t->n, m = t->m;
    const __m512d thr = _mm512_setzero_pd(); /* (unused: every point tested, see cross8r) */
    __m512d pc[3], pl2 = _mm512_setzero_pd(), no[3]; /* the previous row's cross products */
    nshift wp, wn;
    if (shift) {
        nshift_init(&wp, pos, n);
        nshift_init(&wn, nrm, n);
    }
    for (int a = 0; a < n; a++) {
        __m512d T[5], po[3], c[3], l2;
        bcastT(t->ht + 8 * a, T);
        if (a < t->arev)
            l2 = pos_cross8r(T, c0, dc, c1, po, c, thr, 0, 0, hw, 0);
        else
            l2 = pos_cross8r(T, c0, dc, c1, po, c, thr, 0, 0, hw, 1);
        if (shift)
            nshift_row(&wp, po, a);
        else
            put8(pos + 3 * m * a, po, m, st);
        if (a) {
            unit_xyz8(pc, pl2, no, hw);
            if (shift)
                nshift_row(&wn, no, a - 1);
            else
                put8(nrm + 3 * m * (a - 1), no, m, st);
        }
        for (int k = 0; k < 3; k++)
            pc[k] = c[k];
        pl2 = l2;
    }
    unit_xyz8(pc, pl2, no, hw);
    if (shift) {
        nshift_row(&wn, no, n - 1);
        nshift_end(&wp, n);
        nshift_end(&wn, n);
    } else {
        put8(nrm + 3 * m * (n - 1), no, m, st);
    }
}

/* The rows of patch_normal_narrow_avx512 in blocks of up to 8: the block's positions and cross
 * products (pos_cross8, to nb), then its normals (as seg_unit_avx512 does); stored as st or (shift)
 * into one shifted run an array. */
RG2_AVX512_FN static inline __attribute__((always_inline)) void
normal_narrow_blocked(const tables *t, __m512d c0[4][4], __m512d dc[3][4], __m512d c1[4][4], double *pos,
                      double *nrm, int st, int hw, const int shift)
{
    const int n = t->n, m = t->m;
    const __m512d thr = _mm512_setzero_pd(); /* (unused: every point tested, see cross8r) */
    _Alignas(64) double nb[8][32];
    nshift wp, wn;
    if (shift) {
        nshift_init(&wp, pos, n);
        nshift_init(&wn, nrm, n);
    }
    for (int a0 = 0; a0 < n; a0 += 8) {
        int na = n - a0 < 8 ? n - a0 : 8;
        for (int a = a0; a < a0 + na; a++) {
            __m512d T[5], po[3];
            bcastT(t->ht + 8 * a, T);
            if (a < t->arev)
                pos_cross8(T, c0, dc, c1, po, nb[a - a0], thr, 0, 0, hw, 0);
            else
                pos_cross8(T, c0, dc, c1, po, nb[a - a0], thr, 0, 0, hw, 1);
            if (shift)
                nshift_row(&wp, po, a);
            else
                put8(pos + 3 * m * a, po, m, st);
        }
        for (int a = a0; a < a0 + na; a++) {
            const double *b = nb[a - a0];
            __m512d c[3] = {_mm512_load_pd(b), _mm512_load_pd(b + 8), _mm512_load_pd(b + 16)}, no[3];
            unit_xyz8(c, _mm512_load_pd(b + 24), no, hw);
            if (shift)
                nshift_row(&wn, no, a);
            else
                put8(nrm + 3 * m * a, no, m, st);
        }
    }
    if (shift) {
        nshift_end(&wp, n);
        nshift_end(&wn, n);
    }
}

/* Positions and unit normals of a patch at most 8 points wide (as patch_pos_narrow_avx512), by
 * pos_cross8 and seg_unit_avx512 as in seg_cross_avx512 (the same bits): the cross
 * products of up to 8 rows, then their normals (normal_narrow_blocked). Streamed on Intel CPUs
 * (!hw), each row's normals go out after the next row's positions instead (normal_narrow_lagged),
 * the cross products kept in registers, as seg_cross_unit_avx512 does for wide rows: the free-form
 * mesh's 8 x 8 patches (43 and 119 MB) 1.02-1.08x (medians of 31-41 alternating calls, either
 * vCPU, Sapphire Rapids class, fourteenth stop), the same bits. Not with plain stores there
 * (0.90-0.98x at 4 MB), nor on AMD (Zen 5: 0.92-1.10x at 119 MB, 0.93-0.95x at 24 MB). Shifted
 * arrays (nshift) likewise: on AMD blocked, 1.03-1.06x against lagged (Zen 5, 119 MB from 8, 16
 * and 48 bytes past a line; medians of 9-11 alternating calls, six rounds), Intel lagged. */
RG2_AVX512_FN static inline void patch_normal_narrow_avx512(const rg2_patch *P, const tables *t, double *pos,
                                                            double *nrm, int hw)
{
    /* both arrays streamed straight, or both shifted (nshift takes an aligned start too) */
    const int st = narrow_mode(t, pos) == narrow_mode(t, nrm) ? narrow_mode(t, pos) : ST_SHIFT;
    __m512d c0[4][4], dc[3][4], c1[4][4];
    vsum_narrow(P, t->bv, c0);
    cdiff_v(c0, dc);
    vsumh_narrow(P, t->hv, c1);
    if (st == ST_SHIFT && hw)
        normal_narrow_blocked(t, c0, dc, c1, pos, nrm, st, hw, 1);
    else if (st == ST_SHIFT)
        normal_narrow_lagged(t, c0, dc, c1, pos, nrm, st, hw, 1);
    else if (!hw && st == ST_STREAM)
        normal_narrow_lagged(t, c0, dc, c1, pos, nrm, st, hw, 0);
    else
        normal_narrow_blocked(t, c0, dc, c1, pos, nrm, st, hw, 0);
}

/* The first phase of positions and unit normals for one row segment: positions at pd, the cross
 * products to nb (one entry of 32 doubles per 8 points; pos_cross8). */
RG2_AVX512_FN static inline __attribute__((always_inline)) void
seg_cross_avx512(const double *HT, double c0[4][4][BLK], double d0[3][4][BLK], double c1[4][4][BLK], int cnt,
                 double *pd, double (*nb)[32], __m512d thr, int st, int hw, const int rev)
{
    __m512d T[5];
    bcastT(HT, T);
    for (int i = 0; i < cnt; i += 8) {
        __m512d v0[4][4], vd[3][4], v1[4][4], po[3];
        csum_at(c0, i, v0);
        cdiff_at(d0, i, vd);
        csum_at(c1, i, v1);
        pos_cross8(T, v0, vd, v1, po, nb[i / 8], thr, cnt - i < 8 ? (__mmask8)(0xff << (cnt - i)) : 0, 1, hw, rev);
        put8(pd + 3 * i, po, cnt - i < 8 ? cnt - i : 8, st);
    }
}

/* Both phases for one row segment (t->spread), streamed straight out (st ST_STREAM: whole
 * vectors), shifted to the cache lines (ST_SHIFT: shifter) or with plain stores (ST_PLAIN: the
 * last vector masked past cnt): each 8 normals formed and stored after the next 8 positions (the
 * square root's latency still off the next sums' path), so that positions and normals leave at
 * an even rate, and the cross products wait in registers, not in an L1 buffer: plain stores
 * between the streaming ones stall behind them. Against a row's positions, then its normals (AMD
 * Zen 5, medians of 9-101 alternating calls, either vCPU; torus, 48 patches), streamed: 64 x 64
 * per patch (9.4 MB) 1.01-1.08x, 128 x 128 1.09-1.13x, 256 x 256 1.08-1.19x; plain stores, 1
 * thread: 16 x 16 to 48 x 48 1.02-1.16x; 2 threads (a share of 4.7 MB each at 64 x 64, plain
 * stores) 1.00-1.10x, and 1.18-1.23x in a phase where the host's L3 held less; rows not on cache
 * lines (65 x 65 to 257 x 257), both through an L1 buffer, 1.06-1.42x, and shifted instead of
 * through the buffer another 1.03-1.30x. pos_cross8r and unit8r as in the two phases: the same
 * bits. */
RG2_AVX512_FN static inline __attribute__((always_inline)) void
seg_cross_unit_avx512(const double *HT, double c0[4][4][BLK], double d0[3][4][BLK], double c1[4][4][BLK],
                      int cnt, double *pd, double *nd, __m512d thr, int hw, const int rev, const int st,
                      shifter *wp, shifter *wn)
{
    __m512d T[5], pl2 = _mm512_setzero_pd(), pc[3] = {pl2, pl2, pl2}; /* the previous 8 points' cross products */
    bcastT(HT, T);
    int i = 0;
    for (;;) {
        __m512d v0[4][4], vd[3][4], v1[4][4], po[3], no[3], c[3];
        int q = cnt - i < 8 ? cnt - i : 8;
        csum_at(c0, i, v0);
        cdiff_at(d0, i, vd);
        csum_at(c1, i, v1);
        __m512d l2 = pos_cross8r(T, v0, vd, v1, po, c, thr, q < 8 ? (__mmask8)(0xff << q) : 0, 1, hw, rev);
        if (st == ST_SHIFT)
            shift_put8_pos(wp, po);
        else
            put8(pd + 3 * i, po, q, st);
        if (i) {
            unit_xyz8(pc, pl2, no, hw);
            if (st == ST_SHIFT)
                shift_put8(wn, no);
            else
                put8(nd + 3 * (i - 8), no, 8, st);
        }
        for (int k = 0; k < 3; k++)
            pc[k] = c[k];
        pl2 = l2;
        if (i + 8 >= cnt)
            break;
        i += 8;
    }
    __m512d no[3];
    unit_xyz8(pc, pl2, no, hw);
    if (st == ST_SHIFT) {
        shift_put8(wn, no);
        shift_end(wp);
        shift_end(wn);
    } else {
        put8(nd + 3 * i, no, cnt - i, st);
    }
}

/* x, y, z of 8 points (q of them) interleaved at dst, when the output is requested. */
RG2_AVX512_FN static inline __attribute__((always_inline)) void out3(double *dst, const __m512d v[3], int q, int hw)
{
    if (dst) {
        __m512d o[3];
        xyz8(v[0], v[1], v[2], o, hw);
        put8(dst, o, q, ST_PLAIN);
    }
}

/* The column sums of one component k at columns i..i+7 (c[r][k]) and their differences. */
RG2_AVX512_FN static inline void csum_k(double c[4][4][BLK], int k, int i, __m512d v[4][1], __m512d d[3][1])
{
    for (int r = 0; r < 4; r++)
        v[r][0] = _mm512_load_pd(&c[r][k][i]);
    for (int q = 0; q < 3; q++)
        d[q][0] = _mm512_sub_pd(v[q + 1][0], v[q][0]);
}

/* The second-order formulas for all 8-lane vectors covering 0..cnt-1 (the lanes past cnt repeat
 * the last column, tables_make; computed but not stored), each requested output interleaved and
 * stored as soon as it is computed (point index `at` of the outputs). The sums along u are the
 * scaled ones of row_consts (Horner), whose positions and normals are bitwise those of pos8 and
 * pos_cross8; with w = lambda w', hu = mu hu', hv = lambda hv', huv = mu huv', hvv = lambda hvv'
 * (huu: the Bernstein sum itself, DDU) the quotient rule of rg2_patch_eval becomes
 *   Su = a' iw' mu/lambda, Sv = b' iw', Suu = (huu - 2 mu hu'_w Su - huu_w p) iw' / lambda,
 *   Suv = (mu/lambda (huv' - hu'_w Sv - huv'_w p) - hv'_w Su) iw', Svv = (hvv' - 2 hv'_w Sv - hvv'_w p) iw'
 * with a' = hu' - hu'_w p, b' = hv' - hv'_w p and iw' = 1 / w'. */
RG2_AVX512_FN static __attribute__((noinline)) void
full_avx512(const double *HT, const double *DDU, double c0[4][4][BLK], double c1[4][4][BLK], double c2[4][4][BLK],
            int cnt, const rg2_grid_out *o, size_t at, int hw, const int rev)
{
    __m512d T[5], ddu[4];
    bcastT(HT, T);
    bcast4(DDU, ddu);
    const __m512d fu = _mm512_set1_pd(HT[5]), rl = _mm512_set1_pd(HT[6]), m2 = _mm512_set1_pd(HT[7]);
    const __m512d one = _mm512_set1_pd(1.0), two = _mm512_set1_pd(2.0), half = _mm512_set1_pd(0.5);
    for (int i = 0; i < cnt; i += 8) {
        __m512d h[4], hu[4], hv[4], huu[4], huv[4], hvv[4];
        for (int k = 0; k < 4; k++) {
            __m512d v[4][1], d[3][1];
            csum_k(c0, k, i, v, d);
            h[k] = RSUM(rev, v, 0, T);
            hu[k] = RSUMH(rev, d, 0, T);
            huu[k] = _mm512_fmadd_pd(ddu[3], v[3][0],
                                     _mm512_fmadd_pd(ddu[2], v[2][0], _mm512_fmadd_pd(ddu[1], v[1][0], _mm512_mul_pd(ddu[0], v[0][0]))));
            csum_k(c1, k, i, v, d);
            hv[k] = RSUM(rev, v, 0, T);
            huv[k] = RSUMH(rev, d, 0, T);
            for (int r = 0; r < 4; r++)
                v[r][0] = _mm512_load_pd(&c2[r][k][i]);
            hvv[k] = RSUM(rev, v, 0, T);
        }
        __m512d iw = recip8(h[3], hw), iwu = _mm512_mul_pd(iw, fu), iwl = _mm512_mul_pd(iw, rl);
        __m512d m2hu = _mm512_mul_pd(m2, hu[3]), hv2 = _mm512_mul_pd(two, hv[3]);
        __m512d P[3], A[3], B[3], Su[3], Sv[3], Suu[3], Suv[3], Svv[3];
        for (int k = 0; k < 3; k++) {
            P[k] = _mm512_mul_pd(h[k], iw);
            A[k] = _mm512_fnmadd_pd(hu[3], P[k], hu[k]);
            B[k] = _mm512_fnmadd_pd(hv[3], P[k], hv[k]);
            Su[k] = _mm512_mul_pd(A[k], iwu);
            Sv[k] = _mm512_mul_pd(B[k], iw);
            __m512d t = _mm512_fnmadd_pd(m2hu, Su[k], huu[k]);
            Suu[k] = _mm512_mul_pd(_mm512_fnmadd_pd(huu[3], P[k], t), iwl);
            t = _mm512_fnmadd_pd(hu[3], Sv[k], huv[k]);
            t = _mm512_fnmadd_pd(huv[3], P[k], t);
            Suv[k] = _mm512_mul_pd(_mm512_fmsub_pd(fu, t, _mm512_mul_pd(hv[3], Su[k])), iw);
            t = _mm512_fnmadd_pd(hv2, Sv[k], hvv[k]);
            Svv[k] = _mm512_mul_pd(_mm512_fnmadd_pd(hvv[3], P[k], t), iw);
        }
        __m512d nn[3];
        __mmask8 ok = normal8(A, B, nn);
        __m512d E = dot8(Su, Su), F = dot8(Su, Sv), G = dot8(Sv, Sv);
        __m512d L = dot8(Suu, nn), M = dot8(Suv, nn), N = dot8(Svv, nn);
        __m512d det = _mm512_fmsub_pd(E, G, _mm512_mul_pd(F, F)); /* (as in full_soa_rev) */
        ok &= _mm512_cmp_pd_mask(det, _mm512_mul_pd(_mm512_set1_pd(1e-30), _mm512_mul_pd(E, G)), _CMP_GT_OQ);
        det = _mm512_mask_blend_pd(ok, one, det);
        __m512d idet = recip8(det, hw);
        __m512d K = _mm512_mul_pd(_mm512_fmsub_pd(L, N, _mm512_mul_pd(M, M)), idet);
        __m512d Hn = _mm512_fmadd_pd(G, L, _mm512_fnmadd_pd(_mm512_mul_pd(two, F), M, _mm512_mul_pd(E, N)));
        __m512d H = _mm512_mul_pd(Hn, _mm512_mul_pd(half, idet));
        int q = cnt - i < 8 ? cnt - i : 8;
        size_t o3 = 3 * (at + (size_t)i);
        out3(o->pos + o3, P, q, hw);
        out3(o->normal ? o->normal + o3 : NULL, nn, q, hw);
        out3(o->du ? o->du + o3 : NULL, Su, q, hw);
        out3(o->dv ? o->dv + o3 : NULL, Sv, q, hw);
        out3(o->duu ? o->duu + o3 : NULL, Suu, q, hw);
        out3(o->duv ? o->duv + o3 : NULL, Suv, q, hw);
        out3(o->dvv ? o->dvv + o3 : NULL, Svv, q, hw);
        __mmask8 mq = (__mmask8)((1u << q) - 1u);
        if (o->K)
            _mm512_mask_storeu_pd(o->K + at + i, mq, K);
        if (o->H)
            _mm512_mask_storeu_pd(o->H + at + i, mq, H);
    }
}
#endif

/* Order needed by an output set: 0 positions, 1 adds normals, 2 everything else. */
static int out_order(const rg2_grid_out *o)
{
    if (o->du || o->dv || o->duu || o->duv || o->dvv || o->K || o->H)
        return 2;
    return o->normal ? 1 : 0;
}

#if RG2_AVX512
/* How to store a row segment of cnt points at dst (see ST_*). */
static inline int store_mode(const tables *t, const double *dst, int cnt)
{
    if (!t->stream)
        return ST_PLAIN;
    if (!((uintptr_t)dst & 63) && !(cnt & 7))
        return ST_STREAM;
    /* otherwise shifted, streaming only rows of whole cache lines' worth (short rows would leave
     * mostly partial lines, which streaming makes slower). The row, not the segment: the last
     * block of a long row may hold only 9-31 columns, and storing those plainly between streamed
     * ones made the whole row wait on reads for ownership (73-95 points a row, rows not on cache
     * lines: the merged design at 90 x 90 per patch ran at 0.27-0.45x of 88 x 88, Intel machine).
     * Positions from 16 points a row: their rows hand on the lines they share, and grid_range asks
     * for the rest ahead (free-form mesh at 14 to 31 points a row: 1.14-1.46x against plain
     * stores; 10 and 12: 0.68-1.22x; with normals 0.86-0.96x at 16 and 24, Intel machine). On AMD
     * (where the pages are touched ahead) from 24 points: 16-21 points ran at 0.73-1.00x of plain
     * stores, 22 and 23 at 0.96-1.04x, 24-31 at 1.03-1.14x (AMD Zen 5, medians of 7 calls
     * alternating both ways in either order; 0.62-0.82x at 16-31 on a vCPU whose core was busy) */
    return t->m >= 32 || (t->order == 0 && t->m >= (t->pages ? 24 : 16)) ? ST_SHIFT : ST_PLAIN;
}

/* Streaming stores into a page whose address translation the TLB does not hold wait for the
 * page walk, and so do the stores queued behind them. In the Zen 5 guest of docs/performance.md
 * (a virtual machine: two-level walks) that held the streamed kernels with normals up by a
 * quarter and more. So they first touch the pages that a later row segment (RG2_ROWS_AHEAD rows
 * on) or patch (grid_range) will fill, by a prefetch of the first line of each page it touches.
 * Against none (torus, 48 patches; medians of 9-31 alternating calls, either vCPU): with normals
 * 1.05-1.08x at 64 x 64 per patch, 1.05-1.12x at 128 x 128, 1.13-1.46x at 256 x 256, 1.19-1.23x at
 * 257 x 257 (shifted rows); the free-form mesh's 38809 patches of 8 x 8 points 1.40-1.63x with
 * normals, 1.07-1.27x positions alone. Rows of positions streamed several at a time
 * (seg_pos_cxr_avx512, rows of whole lines) went 0.71-0.91x with it, as long as the prefetched
 * line was streamed too: a streaming store to a line that the caches hold evicts it first. With
 * that line stored plain (ST_STREAM_PF) they went 0.93-1.39x against none (medians of 7-61
 * alternating calls, either vCPU; 14 of 16 at 1.02x or more): the merged design's 120 patches
 * of 64 x 64 points (11.8 MB) 0.93-1.23x, the torus at 256 x 256 1.03-1.16x, the merged design
 * at 256 x 256 1.19-1.39x in a slow phase of the host's memory. The spread normals went
 * 1.01-1.06x with it against the prefetched line streamed (torus, 64 x 64 to 256 x 256). The
 * shifted rows and the narrow patches keep streaming it (plain: positions 0.85-0.96x shifted,
 * normals 0.89-0.94x narrow). A shifted segment (shifter) stores its last line with plain
 * stores: that line is asked for too, so that its read for ownership is done before the store
 * (torus, 97 x 97 to 257 x 257 per patch: positions 0.99-1.28x, normals 1.02-1.32x; 1, 2, 4 or 8
 * rows ahead alike). All of this on AMD CPUs only (grid_pages: on Intel's it costs). */
#ifndef RG2_ROWS_AHEAD
#define RG2_ROWS_AHEAD 2
#endif
static inline void prefetch_pages(const double *p, size_t n, int last)
{
    const char *c = (const char *)p, *e = (const char *)(p + n) - 1;
    __builtin_prefetch(c, 1, 3);
    for (uintptr_t q = ((uintptr_t)c | 4095) + 1; q <= (uintptr_t)e; q += 4096)
        __builtin_prefetch((const void *)q, 1, 3);
    if (last)
        __builtin_prefetch(e, 1, 3);
}

/* prefetch_pages for the row segment RG2_ROWS_AHEAD rows after the one at row (row a < a1, cnt
 * points in the segment), stored as st, where the tables say so (tables.pages). */
static inline void prefetch_row(const tables *t, const double *row, int a, int a1, int cnt, int st)
{
    if (t->pages && st != ST_PLAIN && a + RG2_ROWS_AHEAD < a1)
        prefetch_pages(row + 3 * (size_t)RG2_ROWS_AHEAD * (size_t)t->m, 3 * (size_t)cnt, st == ST_SHIFT);
}

/* Rows a0 <= a < a1 of one block of columns (b0, cnt: its column sums c0, c1, c2 and the
 * interleaved cx when use_cx), all of one Horner form (rev). */
RG2_AVX512_FN static inline __attribute__((always_inline)) void
rows_avx512(const tables *t, const rg2_grid_out *o, size_t first, int b0, int cnt, int a0, int a1,
            double c0[4][4][BLK], double d0[3][4][BLK], double c1[4][4][BLK], double c2[4][4][BLK],
            double cx[4][3 * BLK], int use_cx, __m512d thr,
            double *pbuf, double *nbuf, double (*nb)[32], const int hw, const int rev)
{
    const size_t stride = 3 * (size_t)t->m; /* doubles from a row to the next */
    shifter wp, wn; /* shifted rows of positions and normals */
    wp.has_tail = wn.has_tail = 0;
    wp.tail = wn.tail = _mm512_setzero_pd();
    for (int a = a0; a < a1; a++) {
        size_t at = first + (size_t)a * (size_t)t->m + (size_t)b0;
        const double *HT = t->ht + 8 * a;
        double *pos = o->pos + 3 * at;
        /* a shifted row whose next row follows it in memory (the block is the whole row) leaves
         * the line they share to the next row's first vector (shifter; 65 x 65 and 33 x 33 per
         * patch, AMD Zen 5: positions 1.03-1.07x, normals 1.00-1.07x) */
        const int keep = cnt == t->m && a + 1 < a1;
        if (t->order == 0 && use_cx && !t->stream && a + RG2_POS_ROWS <= a1) { /* rows together */
            /* prefetchw: the same columns of the next pass */
            seg_pos_cxr_avx512(HT, c0, cx, cnt, pos, stride, RG2_POS_ROWS * stride, ST_PLAIN, NULL, hw, RG2_POS_ROWS, rev);
            a += RG2_POS_ROWS - 1;
        } else if (t->order == 0 && use_cx && t->pages && a + RG2_POS_ROWS <= a1 &&
                   store_mode(t, pos, cnt) == ST_STREAM && !(t->m & 7)) {
            /* rows together, streamed (each row's start aligned as the first's: 24 m bytes apart),
             * where the pages are touched ahead (AMD); on Intel one row at a time streams faster
             * (merged design and torus at 256 x 256 per patch: 1.03-1.07x in six pairs of medians
             * of 31-41 alternating calls, either vCPU, fourteenth stop) */
            if (a + 2 * RG2_POS_ROWS <= a1) /* the pages of the next pass's rows */
                for (int k = RG2_POS_ROWS; k < 2 * RG2_POS_ROWS; k++)
                    prefetch_pages(pos + k * stride, 3 * (size_t)cnt, 0);
            seg_pos_cxr_avx512(HT, c0, cx, cnt, pos, stride, 0, ST_STREAM_PF, NULL, hw, RG2_POS_ROWS, rev);
            a += RG2_POS_ROWS - 1;
        } else if (t->order == 0) {
            int st = store_mode(t, pos, cnt);
            prefetch_row(t, pos, a, a1, cnt, st);
            if (st == ST_SHIFT)
                shift_init(&wp, pos, 3 * cnt, keep);
            if (use_cx && st == ST_STREAM)
                seg_pos_cxr_avx512(HT, c0, cx, cnt, pos, 0, 0, ST_STREAM, NULL, hw, 1, rev);
            else if (use_cx && st == ST_SHIFT)
                seg_pos_cxr_avx512(HT, c0, cx, cnt, pos, 0, 0, ST_SHIFT, &wp, hw, 1, rev);
            else if (use_cx)
                seg_pos_cxr_avx512(HT, c0, cx, cnt, pos, 0, RG2_PREFETCHW_AHEAD, ST_PLAIN, NULL, hw, 1, rev);
            else if (st == ST_STREAM)
                seg_pos_avx512(HT, c0, cnt, pos, ST_STREAM, NULL, hw, rev);
            else if (st == ST_SHIFT)
                seg_pos_avx512(HT, c0, cnt, pos, ST_SHIFT, &wp, hw, rev);
            else
                seg_pos_avx512(HT, c0, cnt, pos, ST_PLAIN, NULL, hw, rev);
        } else if (t->order == 1) {
            double *nrm = o->normal + 3 * at;
            int sp = store_mode(t, pos, cnt);
            if (t->spread && store_mode(t, nrm, cnt) == sp) { /* this row, both phases */
                prefetch_row(t, pos, a, a1, cnt, sp);
                prefetch_row(t, nrm, a, a1, cnt, sp);
                if (sp == ST_STREAM && t->pages) {
                    seg_cross_unit_avx512(HT, c0, d0, c1, cnt, pos, nrm, thr, hw, rev, ST_STREAM_PF, NULL, NULL);
                } else if (sp == ST_STREAM) {
                    seg_cross_unit_avx512(HT, c0, d0, c1, cnt, pos, nrm, thr, hw, rev, ST_STREAM, NULL, NULL);
                } else if (sp == ST_PLAIN) {
                    seg_cross_unit_avx512(HT, c0, d0, c1, cnt, pos, nrm, thr, hw, rev, ST_PLAIN, NULL, NULL);
                } else {
                    shift_init(&wp, pos, 3 * cnt, keep);
                    shift_init(&wn, nrm, 3 * cnt, keep);
                    seg_cross_unit_avx512(HT, c0, d0, c1, cnt, pos, nrm, thr, hw, rev, ST_SHIFT, &wp, &wn);
                }
                continue;
            }
            /* (spread off, or the arrays stored differently) R rows of at most 8 vectors in all:
             * their positions and cross products, then their normals (see cross8r); each array's
             * rows stored as store_mode says (a shifted row goes through the buffer and out
             * before the next row) */
            int nvec = (cnt + 7) / 8, R = nvec >= 8 ? 1 : 8 / nvec;
            if (R > a1 - a)
                R = a1 - a;
            for (int k = 0; k < R; k++) {
                double *pk = pos + k * stride;
                int st = store_mode(t, pk, cnt);
                double *d = st == ST_SHIFT ? pbuf : pk;
                if (st == ST_STREAM)
                    seg_cross_avx512(HT + 8 * k, c0, d0, c1, cnt, d, nb + k * nvec, thr, ST_STREAM, hw, rev);
                else
                    seg_cross_avx512(HT + 8 * k, c0, d0, c1, cnt, d, nb + k * nvec, thr, ST_PLAIN, hw, rev);
                if (d != pk)
                    stream_copy(pk, d, 3 * cnt);
            }
            for (int k = 0; k < R; k++) {
                double *nk = nrm + k * stride;
                int st = store_mode(t, nk, cnt);
                double *d = st == ST_SHIFT ? nbuf : nk;
                seg_unit_avx512(nb + k * nvec, cnt, d, st == ST_STREAM ? ST_STREAM : ST_PLAIN, hw);
                if (d != nk)
                    stream_copy(nk, d, 3 * cnt);
            }
            a += R - 1;
        } else {
            full_avx512(HT, t->ddu + 4 * a, c0, c1, c2, cnt, o, at, hw, rev);
        }
    }
}

/* grid_patch with the AVX-512 kernels; hw: divisions by the hardware (a
 * constant in both calls of grid_patch_avx512, so each gets kernels of its own). */
RG2_AVX512_FN static inline __attribute__((always_inline)) void
grid_patch_avx512_hw(const rg2_patch *P, const tables *t, const rg2_grid_out *o, size_t first, const int hw)
{
    _Alignas(64) double c0[4][4][BLK];
    _Alignas(64) double c1[4][4][BLK];
    _Alignas(64) double c2[4][4][BLK];
    _Alignas(64) double pbuf[3 * BLK];
    _Alignas(64) double nbuf[3 * BLK];
    _Alignas(64) double cx[4][3 * BLK];
    _Alignas(64) double d0[3][4][BLK];
    _Alignas(64) double nb[BLK / 8][32];
    if (t->m <= 8 && t->order <= 1) { /* narrow patches: whole rows in registers */
        if (t->order == 0)
            patch_pos_narrow_avx512(P, t, o->pos + 3 * first, hw);
        else
            patch_normal_narrow_avx512(P, t, o->pos + 3 * first, o->normal + 3 * first, hw);
        return;
    }
    double dh[4][3][4];
    __m512d thr = _mm512_set1_pd(__builtin_inf());
    if (t->order >= 1)
        hdiff_avx(P, dh);
    if (t->order == 1)
        thr = cross_threshold(P);
    for (int b0 = 0, cnt; b0 < t->m; b0 += cnt) {
        cnt = block_cols(t->m, b0);
        vsum_avx512(P, t->bv, b0, cnt, c0);
        int use_cx = t->order == 0 && t->n >= 16;
        if (use_cx)
            interleave_csum(c0, cnt, cx, hw);
        if (t->order >= 1)
            vsumh_avx512(dh, t->hv, b0, cnt, c1);
        if (t->order == 1)
            cdiff_block(c0, cnt, d0);
        if (t->order >= 2)
            vsum_avx512(P, t->ddv, b0, cnt, c2);
        rows_avx512(t, o, first, b0, cnt, 0, t->arev, c0, d0, c1, c2, cx, use_cx, thr, pbuf, nbuf, nb, hw, 0);
        rows_avx512(t, o, first, b0, cnt, t->arev, t->n, c0, d0, c1, c2, cx, use_cx, thr, pbuf, nbuf, nb, hw, 1);
    }
}

RG2_AVX512_FN static void grid_patch_avx512(const rg2_patch *P, const tables *t, const rg2_grid_out *o,
                                            size_t first)
{
    if (t->hwdiv)
        grid_patch_avx512_hw(P, t, o, first, 1);
    else
        grid_patch_avx512_hw(P, t, o, first, 0);
}
#endif

/* All n x m points of one patch, written at point index `first` of the outputs: blocks of
 * BLK columns, their column sums once, then every row of the block. */
RG2_HOT static void grid_patch(const rg2_patch *P, const tables *t, const rg2_grid_out *o, size_t first)
{
#if RG2_AVX512
    if (t->avx512) {
        grid_patch_avx512(P, t, o, first);
        return;
    }
#endif
    _Alignas(64) double c0[4][4][BLK];
    _Alignas(64) double c1[4][4][BLK];
    _Alignas(64) double c2[4][4][BLK];
    soa_full S[1];
    double dh[4][3][4];
    if (t->order >= 1)
        hdiff(P, dh);
    for (int b0 = 0, cnt; b0 < t->m; b0 += cnt) {
        cnt = block_cols(t->m, b0);
        vsum(P, t->bv, b0, cnt, c0);
        if (t->order >= 1)
            vsumh(dh, t->hv, b0, cnt, c1);
        if (t->order >= 2)
            vsum(P, t->ddv, b0, cnt, c2);
        for (int a = 0; a < t->n; a++) {
            size_t at = first + (size_t)a * (size_t)t->m + (size_t)b0;
            const double *T = t->ht + 8 * a;
            int rev = a >= t->arev;
            if (t->order == 0 && rev)
                seg_pos(T, c0, cnt, o->pos + 3 * at, 1);
            else if (t->order == 0)
                seg_pos(T, c0, cnt, o->pos + 3 * at, 0);
            else if (t->order == 1 && rev)
                seg_pos_normal(T, c0, c1, cnt, o->pos + 3 * at, o->normal + 3 * at, 1);
            else if (t->order == 1)
                seg_pos_normal(T, c0, c1, cnt, o->pos + 3 * at, o->normal + 3 * at, 0);
            else {
                full_soa(T, t->ddu + 4 * a, c0, c1, c2, cnt, S, rev);
                full_out(S, cnt, o, at);
            }
        }
    }
}

/* On a collapsed side Su x Sv is rounding noise, which the fast kernels' relative test cannot
 * tell from a tangent plane; the normal, K and H of the side's points are taken from
 * rg2_patch_eval, whose tests know the noise level (the normal is then 0, K = H = 0, as the
 * header promises), so the grid agrees with it there. Rare (pole patches only). A per-patch
 * test of all four sides cost the 8 x 8 normal kernel 4-7 %, hence only the boundary's. */
static void fix_collapsed(const rg2_patch *P, const tables *t, const rg2_grid_out *o, size_t first, int mask)
{
    int n = t->n, m = t->m, order = o->K || o->H ? 2 : 1;
#if RG2_AVX512
    if (t->stream)
        _mm_sfence(); /* (the streaming stores of this patch before the plain ones over them) */
#endif
    for (int side = 0; side < 4; side++) { /* sides as rg2__xpatch_side: 0 v=0, 1 u=1, 2 v=1, 3 u=0 */
        if (!(mask >> side & 1))
            continue;
        int cnt = side & 1 ? m : n;
        for (int q = 0; q < cnt; q++) {
            int a = side == 1 ? n - 1 : side == 3 ? 0 : q, b = side == 0 ? 0 : side == 2 ? m - 1 : q;
            double u = a == n - 1 ? 1.0 : (double)a / (double)(n - 1);
            double v = b == m - 1 ? 1.0 : (double)b / (double)(m - 1);
            rg2_eval e;
            rg2_patch_eval(P, u, v, order, &e);
            size_t at = first + (size_t)a * (size_t)m + (size_t)b;
            if (o->normal)
                memcpy(o->normal + 3 * at, e.n, sizeof e.n);
            if (o->K)
                o->K[at] = e.K;
            if (o->H)
                o->H[at] = e.H;
        }
    }
}

/* The collapsed sides of patch k (bits as rg2__xpatch_side) among those on the open boundary of
 * the surface S, or among all four for a lone patch (S NULL): the poles of rg2's surfaces lie on
 * the boundary (polar meshes, caps, Moebius maps: every collapsed side of the examples, none
 * inside), so the test costs nothing for the interior patches of a large surface. "Collapsed"
 * as for the exporters and the tessellation (rg2__xpatch_side_collapsed, through rg2__xpatch_collapsed_among), with the tolerance of
 * rg2__collapse_tol taken over this patch alone (the surface's box would cost a pass over all
 * patches per call). */
static int pole_sides(const rg2_surface *S, const rg2_patch *P, size_t k)
{
    int cand = 0xF;
    if (S) {
        int i = (int)(k / (size_t)S->nv), j = (int)(k % (size_t)S->nv), ou = !S->closed_u, ov = !S->closed_v;
        cand = (ov && j == 0) | (ou && i == S->nu - 1) << 1 | (ov && j == S->nv - 1) << 2 | (ou && i == 0) << 3;
    }
    if (!cand)
        return 0;
    rg2_xpatch X; /* (converted once for the four sides) */
    rg2_xpatch_from_patch(P, &X);
    return (int)rg2__xpatch_collapsed_among(&X, (unsigned)cand);
}

/* Patches k0 <= k < k1 of the array P, patch k at point index k * per of the outputs; S is the
 * surface P belongs to (NULL for a lone patch), for its boundary (pole_sides). */
static void grid_range(const rg2_surface *S, const rg2_patch *P, const rg2_xpatch *xp, const rg2__xgrid *xt,
                       const tables *t, const rg2_grid_out *o, size_t k0, size_t k1, size_t per)
{
    const int nrm = o->normal || o->K || o->H;
    for (size_t k = k0; k < k1; k++) {
        if (xp && xp[k].du > 0) { /* a higher-degree patch (xpatch.c) */
            rg2__xgrid_patch(&xp[k], xt, o, k * per);
            continue;
        }
#if RG2_AVX512
        if (k + RG2_PATCH_AHEAD < k1) /* a later patch's 8 cache lines while this one computes */
            for (int q = 0; q < 8; q++)
                _mm_prefetch((const char *)(P + k + RG2_PATCH_AHEAD) + 64 * q, _MM_HINT_T0);
        if (t->stream && !t->pages && t->order == 0 && t->m >= 16 && t->m <= BLK && k + RG2_SHIFT_AHEAD < k1) {
            /* shifted positions in rows of one block: the partial lines of a later patch, where
             * its two runs of rows (the two Horner forms) begin, each handing on the lines inside
             * it (RG2_SHIFT_AHEAD; where the pages are touched ahead, prefetch_row asks for them) */
            const double *b = o->pos + 3 * (k + RG2_SHIFT_AHEAD) * per, *h = b + 3 * (size_t)t->arev * (size_t)t->m;
            if ((uintptr_t)b & 63)
                __builtin_prefetch(b, 1, 3);
            if ((uintptr_t)h & 63)
                __builtin_prefetch(h, 1, 3);
        }
        if (t->pages && t->m <= 8 && t->order <= 1 && per <= 256 && k + RG2_ROWS_AHEAD < k1) {
            /* streamed narrow patches of at most 6 KB an array: the pages of a later one (see
             * prefetch_pages) */
            size_t at = 3 * (k + RG2_ROWS_AHEAD) * per;
            prefetch_pages(o->pos + at, 3 * per, 0);
            if (t->order)
                prefetch_pages(o->normal + at, 3 * per, 0);
        }
#endif
        grid_patch(P + k, t, o, k * per);
        int mask;
        if (nrm && (mask = pole_sides(S, P + k, k)))
            fix_collapsed(P + k, t, o, k * per, mask);
    }
#if RG2_AVX512
    if (t->stream) /* streaming stores are weakly ordered: publish them before returning */
        _mm_sfence();
#endif
}

/* rg2_surface_grid's work for the pool: run c of nrun is patches [c np / nrun, (c+1) np / nrun). */
typedef struct {
    const rg2_surface *s;
    const rg2__xgrid *xt;
    const tables *t;
    const rg2_grid_out *o;
    size_t np, per, nrun;
} grid_job;

static void grid_job_run(void *arg, uint32_t c)
{
    const grid_job *j = arg;
    grid_range(j->s, j->s->patch, j->s->xp, j->xt, j->t, j->o, c * j->np / j->nrun, (c + 1) * j->np / j->nrun,
               j->per);
}

/* How an output of pts points (per thread) at the tables' order goes out: with streaming stores
 * past RG2_STREAM_BYTES (tables.stream); normals spread (tables.spread). */
static void set_stores(tables *t, size_t pts)
{
    t->stream = pts * (t->order ? 48 : 24) > rg2__grid_stream_bytes;
    t->pages = t->stream && grid_pages();
    t->spread = t->order == 1 && rg2__grid_spread;
}

rg2_status rg2__grid_check_args(int n, int m, const rg2_grid_out *out, rg2_error *err)
{
    if (!out)
        return rg2__fail(err, RG2_EINVAL, "grid: no output arrays (out is NULL)");
    if (!out->pos)
        return rg2__fail(err, RG2_EINVAL, "grid: the position array (out->pos) is NULL");
    if (n < 2 || m < 2)
        return rg2__fail(err, RG2_EINVAL, "grid: %d x %d points per patch; need at least 2 x 2", n, m);
    if (n > RG2_GRID_MAX || m > RG2_GRID_MAX)
        return rg2__fail(err, RG2_ELIMIT, "grid: %d x %d points per patch exceeds the limit %d per direction",
                         n, m, RG2_GRID_MAX);
    return RG2_OK;
}

rg2_status rg2_patch_grid(const rg2_patch *P, int n, int m, const rg2_grid_out *out, rg2_error *err)
{
    rg2_status st = rg2__grid_check_args(n, m, out, err);
    if (st)
        return st;
    if (!P)
        return rg2__fail(err, RG2_EINVAL, "grid: the patch is NULL");
    tables t;
    st = tables_get(&t, n, m, out_order(out), err);
    if (st)
        return st;
    set_stores(&t, (size_t)n * (size_t)m);
    grid_range(NULL, P, NULL, NULL, &t, out, 0, 1, 0);
    tables_put(&t);
    rg2__ok(err);
    return RG2_OK;
}

rg2_status rg2_surface_grid(const rg2_surface *s, int n, int m, int threads, const rg2_grid_out *out,
                            rg2_error *err)
{
    rg2_status st = rg2__grid_check_args(n, m, out, err);
    if (st)
        return st;
    if (!s || !s->patch || s->nu < 1 || s->nv < 1)
        return rg2__fail(err, RG2_EINVAL, "grid: the surface is empty (no patches)");
    if (threads < 0)
        return rg2__fail(err, RG2_EINVAL, "grid: thread count %d is negative", threads);
    size_t np = (size_t)s->nu * (size_t)s->nv, per = (size_t)n * (size_t)m;
    if (np > SIZE_MAX / 3 / sizeof(double) / per)
        return rg2__fail(err, RG2_ELIMIT, "grid: %zu patches x %d x %d points exceed the addressable size", np,
                         n, m);
    tables t;
    st = tables_get(&t, n, m, out_order(out), err);
    if (st)
        return st;
    rg2__xgrid xt = {0};
    if (s->xp && (st = rg2__xgrid_make(s, n, m, out, &xt, err))) {
        tables_put(&t);
        return st;
    }
    int nt = threads;
    if (nt == 0) {
#ifdef RG2_HAVE_OPENMP
        nt = omp_get_max_threads(); /* OMP_NUM_THREADS, else the cores */
#else
        nt = 1;
#endif
    }
    if (nt > 64) /* the pool's size */
        nt = 64;
    if ((size_t)nt > np)
        nt = (int)np;
    /* streaming by each thread's share of the output: with 2 threads, outputs of 8-16 MB (with
     * normals) fit the caches' share of both cores, and streaming them to memory instead made 2
     * threads only 1.4x 1 thread (AMD EPYC, 32 MB L3; 1.8-1.9x with plain stores) */
    set_stores(&t, np * per / (size_t)nt);
    /* contiguous runs of patches, RG2_RUNS_PER_THREAD per thread, claimed one at a time by the
     * caller and the pool's workers (a busy core takes fewer, a worker without a core none);
     * prefetching and the closing store fence are per run, not per patch */
#ifndef RG2_RUNS_PER_THREAD
#define RG2_RUNS_PER_THREAD 8
#endif
#ifndef RG2_RUN_POINTS
#define RG2_RUN_POINTS 16384
#endif
    size_t nrun = 1;
    if (nt > 1) { /* at least RG2_RUNS_PER_THREAD per thread, runs of about RG2_RUN_POINTS points */
        nrun = np * per / RG2_RUN_POINTS;
        if (nrun < (size_t)RG2_RUNS_PER_THREAD * (size_t)nt)
            nrun = (size_t)RG2_RUNS_PER_THREAD * (size_t)nt;
        if (nrun > np)
            nrun = np;
    }
    grid_job job = {s, &xt, &t, out, np, per, nrun};
    rg2__pool_run(nt, (uint32_t)nrun, grid_job_run, &job);
    rg2__xgrid_free(&xt);
    tables_put(&t);
    rg2__ok(err);
    return RG2_OK;
}

/* ---- per point ---------------------------------------------------------------------- */

/* Column sums at one v (c[r][k] = sum_s h[r][s][k] B[s]), as in rg2_patch_eval. */
static inline void vsum1(const rg2_patch *P, const double B[4], double c[4][4])
{
    for (int r = 0; r < 4; r++)
        for (int k = 0; k < 4; k++)
            c[r][k] = P->h[r][0][k] * B[0] + P->h[r][1][k] * B[1] + P->h[r][2][k] * B[2] +
                      P->h[r][3][k] * B[3];
}

static inline double usum1(const double U[4], double c[4][4], int k)
{
    return U[0] * c[0][k] + U[1] * c[1][k] + U[2] * c[2][k] + U[3] * c[3][k];
}

RG2_HOT void rg2_patch_point(const rg2_patch *P, double u, double v, double p[3])
{
    double Bu[4], Bv[4], c[4][4];
    rg2__bern3(u, Bu, NULL, NULL);
    rg2__bern3(v, Bv, NULL, NULL);
    vsum1(P, Bv, c);
    double iw = 1.0 / usum1(Bu, c, 3);
    for (int k = 0; k < 3; k++)
        p[k] = usum1(Bu, c, k) * iw;
}

/* rg2_patch_point_normal's normal at a point whose tangents are weak: undefined on a collapsed
 * side (a pole), as rg2_patch_eval's. */
static __attribute__((noinline, cold)) unsigned point_normal_pole(const rg2_patch *P, double u, double v, double nrm[3],
                                                                   unsigned flags)
{
    if (!rg2__on_side(u, v) || !rg2__patch_pole_at(P, u, v))
        return flags;
    nrm[0] = nrm[1] = nrm[2] = 0.0;
    return flags | RG2_EVAL_NORMAL_UNDEFINED | RG2_EVAL_CURVATURE_UNDEFINED;
}

RG2_HOT unsigned rg2_patch_point_normal(const rg2_patch *P, double u, double v, double p[3], double nrm[3])
{
    double Bu[4], Du[4], Bv[4], Dv[4], c0[4][4], c1[4][4];
    rg2__bern3(u, Bu, Du, NULL);
    rg2__bern3(v, Bv, Dv, NULL);
    vsum1(P, Bv, c0);
    vsum1(P, Dv, c1);
    double h[4], hu[4], hv[4];
    for (int k = 0; k < 4; k++) {
        h[k] = usum1(Bu, c0, k);
        hu[k] = usum1(Du, c0, k);
        hv[k] = usum1(Bu, c1, k);
    }
    unsigned flags = h[3] > 0.0 ? 0u : (unsigned)RG2_EVAL_WEIGHT_NONPOSITIVE;
    double iw = 1.0 / h[3], su[3], sv[3];
    for (int k = 0; k < 3; k++) {
        p[k] = h[k] * iw;
        su[k] = hu[k] - hu[3] * p[k];
        sv[k] = hv[k] - hv[3] * p[k];
    }
    /* the test of rg2_patch_eval (su, sv here are w Su, w Sv, and ru, rv carry the same w) */
    double ru = 0.0, rv = 0.0;
    for (int k = 0; k < 3; k++) {
        ru += fabs(hu[k]) + fabs(hu[3] * p[k]);
        rv += fabs(hv[k]) + fabs(hv[3] * p[k]);
    }
    double t = rg2__scale_pair(su, sv), c[3], len;
    int ok = rg2__normal_test_weak(su, sv, ru * t, rv * t, c, &len);
    if (!ok) {
        nrm[0] = nrm[1] = nrm[2] = 0.0;
        return flags | RG2_EVAL_NORMAL_UNDEFINED | RG2_EVAL_CURVATURE_UNDEFINED;
    }
    for (int k = 0; k < 3; k++)
        nrm[k] = c[k] / len;
    /* weak tangents: the pole test (rg2__pole_suspect) out of line, by a tail call (testing u and v
     * on every point, or a call inside this function, cost every point 2-11 %) */
    if (__builtin_expect(ok == 2, 0))
        return point_normal_pole(P, u, v, nrm, flags);
    return flags;
}
