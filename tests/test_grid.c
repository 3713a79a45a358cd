/* test_grid.c -- the grid evaluator against the independent per-point evaluator
 * (rg2_patch_eval) on random rational patches and the exact torus; thread-count
 * independence (bitwise); argument errors. */
#include "../src/internal.h"
#include "harness.h"
#include "poles_testutil.h"

#include <math.h>
#include <stddef.h>
#include <pthread.h>
#include <stdlib.h>
#include <string.h>

static double norm3(const double *a) { return sqrt(a[0] * a[0] + a[1] * a[1] + a[2] * a[2]); }

static double dist3(const double *a, const double *b)
{
    double d[3] = {a[0] - b[0], a[1] - b[1], a[2] - b[2]};
    return norm3(d);
}

/* Worst relative differences of a grid evaluation against rg2_patch_eval. */
typedef struct {
    double pos, normal, d1, d2, K, H;
    int undefined; /* points where the reference flags the normal as undefined */
} diffs;

static void worse(double *w, double v)
{
    if (!(v <= *w)) /* NaN counts as worse */
        *w = v;
}

/* Compare n x m grid points starting at point index `first` of `o` with the reference. */
static void compare_patch(const rg2_patch *P, int n, int m, const rg2_grid_out *o, size_t first,
                          double scale, diffs *d)
{
    for (int a = 0; a < n; a++)
        for (int b = 0; b < m; b++) {
            double u = a == n - 1 ? 1.0 : (double)a / (n - 1), v = b == m - 1 ? 1.0 : (double)b / (m - 1);
            rg2_eval e;
            rg2_patch_eval(P, u, v, 2, &e);
            size_t i = first + (size_t)a * m + b;
            worse(&d->pos, dist3(o->pos + 3 * i, e.p) / scale);
            if (e.flags & RG2_EVAL_NORMAL_UNDEFINED) {
                d->undefined++;
                if (o->normal)
                    worse(&d->normal, norm3(o->normal + 3 * i)); /* must be the zero vector */
                if (o->K)
                    worse(&d->K, fabs(o->K[i]));
                if (o->H)
                    worse(&d->H, fabs(o->H[i]));
                continue;
            }
            if (o->normal)
                worse(&d->normal, dist3(o->normal + 3 * i, e.n));
            double s1 = fmax(norm3(e.su), norm3(e.sv));
            double s2 = fmax(fmax(norm3(e.suu), norm3(e.suv)), norm3(e.svv));
            if (o->du)
                worse(&d->d1, dist3(o->du + 3 * i, e.su) / s1);
            if (o->dv)
                worse(&d->d1, dist3(o->dv + 3 * i, e.sv) / s1);
            if (o->duu)
                worse(&d->d2, dist3(o->duu + 3 * i, e.suu) / s2);
            if (o->duv)
                worse(&d->d2, dist3(o->duv + 3 * i, e.suv) / s2);
            if (o->dvv)
                worse(&d->d2, dist3(o->dvv + 3 * i, e.svv) / s2);
            double kmax = fmax(fabs(e.k1), fabs(e.k2));
            if (o->K)
                worse(&d->K, fabs(o->K[i] - e.K) / fmax(kmax * kmax, 1e-300));
            if (o->H)
                worse(&d->H, fabs(o->H[i] - e.H) / fmax(kmax, 1e-300));
        }
}

/* All output arrays for `pts` points (every one allocated). */
typedef struct {
    rg2_grid_out o;
    double *mem;
} grid_buf;

static void buf_alloc(grid_buf *g, size_t pts)
{
    g->mem = calloc(pts * 23, sizeof(double));
    double *q = g->mem;
    double **vec[] = {&g->o.pos, &g->o.normal, &g->o.du, &g->o.dv, &g->o.duu, &g->o.duv, &g->o.dvv};
    for (int k = 0; k < 7; k++, q += 3 * pts)
        *vec[k] = q;
    g->o.K = q;
    g->o.H = q + pts;
}

static void random_patch(rg2t_rng *r, rg2_patch *P)
{
    for (int i = 0; i < 4; i++)
        for (int j = 0; j < 4; j++) {
            double W = rg2t_uniform(r, 0.5, 2.0);
            double x = i + rg2t_uniform(r, -0.3, 0.3), y = j + rg2t_uniform(r, -0.3, 0.3);
            double z = rg2t_uniform(r, -1.0, 1.0);
            P->h[i][j][0] = W * x;
            P->h[i][j][1] = W * y;
            P->h[i][j][2] = W * z;
            P->h[i][j][3] = W;
        }
}

static void random_patches(void)
{
    rg2t_rng r;
    uint64_t seed = 88;
    rg2t_seed(&r, seed);
    printf("random rational patches, seed %llu\n", (unsigned long long)seed);
    const int sizes[][2] = {{2, 2}, {7, 5}, {3, 130}, {17, 64}, {9, 65}, {5, 72}, {4, 137}};
    diffs all = {0};
    for (int trial = 0; trial < 21; trial++) {
        rg2_patch P;
        random_patch(&r, &P);
        int n = sizes[trial % 7][0], m = sizes[trial % 7][1];
        grid_buf g;
        buf_alloc(&g, (size_t)n * m);
        rg2_error err;
        CHECK_OK(rg2_patch_grid(&P, n, m, &g.o, &err), &err);
        diffs d = {0};
        compare_patch(&P, n, m, &g.o, 0, 3.0, &d);
        CHECK(d.pos <= 1e-14 && d.normal <= 1e-14 && d.d1 <= 1e-14 && d.d2 <= 1e-14 && d.K <= 1e-14 &&
                  d.H <= 1e-14,
              "trial %d (%d x %d): pos %.3g normal %.3g d1 %.3g d2 %.3g K %.3g H %.3g", trial, n, m, d.pos,
              d.normal, d.d1, d.d2, d.K, d.H);
        worse(&all.pos, d.pos), worse(&all.normal, d.normal), worse(&all.d1, d.d1);
        worse(&all.d2, d.d2), worse(&all.K, d.K), worse(&all.H, d.H);

        /* position-only and position+normal requests take other kernels: same answers */
        grid_buf h;
        buf_alloc(&h, (size_t)n * m);
        rg2_grid_out o0 = {.pos = h.o.pos}, o1 = {.pos = h.o.pos, .normal = h.o.normal};
        CHECK_OK(rg2_patch_grid(&P, n, m, &o0, &err), &err);
        diffs d0 = {0};
        compare_patch(&P, n, m, &o0, 0, 3.0, &d0);
        CHECK_OK(rg2_patch_grid(&P, n, m, &o1, &err), &err);
        diffs d1 = {0};
        compare_patch(&P, n, m, &o1, 0, 3.0, &d1);
        CHECK(d0.pos <= 1e-14 && d1.pos <= 1e-14 && d1.normal <= 1e-14,
              "trial %d kernels: positions %.3g / %.3g, normals %.3g", trial, d0.pos, d1.pos, d1.normal);
        /* the per-point fast paths */
        double worst_pt = 0, worst_n = 0;
        for (int k = 0; k < 16; k++) {
            double u = rg2t_uniform(&r, 0, 1), v = rg2t_uniform(&r, 0, 1), p[3], nn[3];
            rg2_eval e;
            rg2_patch_eval(&P, u, v, 1, &e);
            rg2_patch_point(&P, u, v, p);
            worse(&worst_pt, dist3(p, e.p) / 3.0);
            unsigned fl = rg2_patch_point_normal(&P, u, v, p, nn);
            worse(&worst_pt, dist3(p, e.p) / 3.0);
            worse(&worst_n, fl == e.flags ? dist3(nn, e.n) : 1.0);
        }
        CHECK(worst_pt <= 1e-14 && worst_n <= 1e-14, "trial %d per point: position %.3g normal %.3g", trial,
              worst_pt, worst_n);
        free(g.mem);
        free(h.mem);
    }
    printf("  grid vs rg2_patch_eval: position %.2e, normal %.2e, d1 %.2e, d2 %.2e, K %.2e, H %.2e\n",
           all.pos, all.normal, all.d1, all.d2, all.K, all.H);
}

/* A patch whose u = 0 edge collapses to a point: normal undefined there, zeros out. */
static void collapsed_edge(void)
{
    rg2t_rng r;
    rg2t_seed(&r, 5);
    rg2_patch P;
    random_patch(&r, &P);
    for (int s = 0; s < 4; s++)
        for (int k = 0; k < 4; k++)
            P.h[0][s][k] = k == 3 ? 1.0 : 0.5;
    grid_buf g;
    buf_alloc(&g, 9 * 9);
    rg2_error err;
    CHECK_OK(rg2_patch_grid(&P, 9, 9, &g.o, &err), &err);
    diffs d = {0};
    compare_patch(&P, 9, 9, &g.o, 0, 3.0, &d);
    CHECK(d.undefined >= 9, "collapsed edge: %d undefined normals", d.undefined);
    CHECK(d.pos <= 1e-14 && d.normal <= 1e-14 && d.K <= 1e-14 && d.H <= 1e-14,
          "collapsed edge: pos %.3g normal %.3g K %.3g H %.3g", d.pos, d.normal, d.K, d.H);
    free(g.mem);
}

/* a and b bit for bit, except that a NaN matches any NaN: the sign and payload of a NaN that
 * arithmetic produces are the compiler's choice (clang's sanitizer build negates a NaN operand
 * where its plain build and GCC's fold the negation into the multiply-add). */
static int same_bits(const double *a, const double *b, size_t count)
{
    for (size_t i = 0; i < count; i++)
        if (memcmp(a + i, b + i, sizeof(double)) && !(isnan(a[i]) && isnan(b[i])))
            return 0;
    return 1;
}

/* The wide normal rows skip the per-point test of an undefined normal where |a x b|^2 is above a
 * bound of the patch (cross_threshold in grid.c); their answers must stay those of the
 * second-order kernel, which tests every point. Nearly degenerate patches (control points on a
 * line, moved off it by delta: |a x b|^2 / (a.b)^2 ~ delta^2 crosses the test's 1e-30), patches
 * whose bound does not apply (a negative weight) or is out of range (huge, tiny coordinates):
 * positions and normals with and without K bitwise the same, and both answers occur. */
/* Patch P on an n x m grid with positions and normals only, and with every output: whether the
 * positions and normals are bitwise the same; counts the zero (undefined) normals. */
static int same_as_second_order(const rg2_patch *P, int n, int m, int *undefined, int *defined)
{
    grid_buf g;
    buf_alloc(&g, (size_t)n * m);
    double *pos = malloc(6 * sizeof(double) * n * m), *nrm = pos + 3 * n * m;
    rg2_grid_out o1 = {.pos = pos, .normal = nrm};
    rg2_error err;
    CHECK_OK(rg2_patch_grid(P, n, m, &g.o, &err), &err);
    CHECK_OK(rg2_patch_grid(P, n, m, &o1, &err), &err);
    int eq = same_bits(pos, g.o.pos, 3 * (size_t)n * m) && same_bits(nrm, g.o.normal, 3 * (size_t)n * m);
    for (int i = 0; i < n * m; i++)
        if (nrm[3 * i] == 0 && nrm[3 * i + 1] == 0 && nrm[3 * i + 2] == 0)
            (*undefined)++;
        else
            (*defined)++;
    free(pos);
    free(g.mem);
    return eq;
}

static void normal_test_bound(void)
{
    rg2t_rng r;
    rg2t_seed(&r, 17);
    const int n = 11, m = 37; /* wide rows (m > 8), a partial last vector */
    const double deltas[] = {1e-2, 1e-8, 1e-14, 3e-15, 1e-15, 3e-16, 1e-16, 0.0};
    const double scales[] = {1.0, 1e100, 1e-100};
    int undefined = 0, defined = 0, cases = 0, same = 1;
    for (int c = 0; c < 4; c++)
        for (size_t di = 0; di < sizeof deltas / sizeof deltas[0]; di++)
            for (size_t si = 0; si < sizeof scales / sizeof scales[0]; si++) {
                rg2_patch P;
                for (int i = 0; i < 4; i++)
                    for (int j = 0; j < 4; j++) {
                        double W = c == 3 && i == 1 && j == 2 ? -0.3 : rg2t_uniform(&r, 0.5, 2.0);
                        double t = i + 3 * j + rg2t_uniform(&r, -0.3, 0.3); /* on the line (1, 2, 3) t */
                        double x[3] = {t, 2 * t, 3 * t};
                        for (int k = 0; k < 3; k++)
                            x[k] += deltas[di] * rg2t_uniform(&r, -1.0, 1.0) * (c == 2 ? t * t : 1.0);
                        for (int k = 0; k < 3; k++)
                            P.h[i][j][k] = W * x[k] * scales[si];
                        P.h[i][j][3] = W;
                    }
                int eq = same_as_second_order(&P, n, m, &undefined, &defined);
                CHECK(eq, "test bound: case %d, delta %g, scale %g: normals differ from the second-order kernel's", c,
                      deltas[di], scales[si]);
                same &= eq;
                cases++;
            }
    CHECK(undefined > 0 && defined > 0, "test bound: %d undefined and %d defined normals", undefined, defined);
    /* non-finite control points: every point fails the bound's comparison, the test decides */
    for (int c = 0; c < 2; c++) {
        rg2_patch P;
        random_patch(&r, &P);
        P.h[1][2][c == 0 ? 0 : 3] = c == 0 ? __builtin_nan("") : __builtin_inf();
        int u = 0, d = 0, eq = same_as_second_order(&P, n, m, &u, &d);
        CHECK(eq, "test bound: %s control point: normals differ from the second-order kernel's", c ? "inf" : "NaN");
        same &= eq;
    }
    printf("  undefined-normal test bound: %d nearly degenerate patches, %d undefined and %d defined normals, "
           "non-finite control points: %s\n",
           cases, undefined, defined, same ? "bitwise as the second-order kernel" : "DIFFERENT");
}

/* The poles of a capped sphere: the pole patches' collapsed sides have Su x Sv at rounding-noise
 * level (not exactly 0), where the kernels' relative test alone would give tangent "normals" and
 * curvatures of 1e31. The grid must agree with rg2_patch_eval there (normal 0, K = H = 0), with
 * and without K, H requested, and rg2_patch_point_normal must return rg2_patch_eval's flags. */
static void capped_poles(void)
{
    rg2_mesh m;
    rg2_surface s;
    rg2_error err;
    CHECK_OK(rg2t_capped_sphere(&m, &s, &err), &err);
    for (int n = 3; n <= 9; n += 6) {
        size_t per = (size_t)n * n, np = (size_t)s.nu * s.nv;
        grid_buf g, h;
        buf_alloc(&g, per * np);
        buf_alloc(&h, per * np);
        rg2_grid_out only = {.pos = h.o.pos, .normal = h.o.normal};
        CHECK_OK(rg2_surface_grid(&s, n, n, 1, &g.o, &err), &err);
        CHECK_OK(rg2_surface_grid(&s, n, n, 1, &only, &err), &err);
        diffs d = {0};
        int flags_off = 0, pts = 0;
        for (size_t k = 0; k < np; k++) {
            if (s.xp && s.xp[k].du > 0)
                continue;
            compare_patch(&s.patch[k], n, n, &g.o, k * per, 1.0, &d);
            for (int q = 0; q < n * n; q++, pts++) {
                double u = q / n == n - 1 ? 1.0 : (double)(q / n) / (n - 1);
                double w = q % n == n - 1 ? 1.0 : (double)(q % n) / (n - 1), p[3], nn[3];
                rg2_eval e;
                rg2_patch_eval(&s.patch[k], u, w, 1, &e);
                flags_off += rg2_patch_point_normal(&s.patch[k], u, w, p, nn) != e.flags;
            }
        }
        printf("capped sphere, %d x %d per patch: %d undefined normals (the poles); vs rg2_patch_eval normal %.2e, "
               "K %.2e, H %.2e; rg2_patch_point_normal flags off at %d of %d points\n",
               n, n, d.undefined, d.normal, d.K, d.H, flags_off, pts);
        CHECK(d.undefined >= 2 * n, "capped sphere: %d undefined normals at the poles", d.undefined);
        /* (at the poles exactly 0 like rg2_patch_eval; next to them the two formulas differ by
         * the poles' conditioning, about 1e-14 / eps^2 at parametric distance eps: docs/poles.md;
         * before the fix the pole samples were off by 1 in the normal and 1e31 in K) */
        CHECK(d.normal <= 1e-13 && d.K <= 1e-10 && d.H <= 1e-10,
              "capped sphere grid at the poles: normal %.3g K %.3g H %.3g", d.normal, d.K, d.H);
        CHECK(memcmp(g.o.normal, h.o.normal, 3 * per * np * sizeof(double)) == 0,
              "capped sphere: normals bitwise the same without K, H");
        CHECK(flags_off == 0, "rg2_patch_point_normal: flags differ from rg2_patch_eval at %d points", flags_off);
        free(g.mem);
        free(h.mem);
    }
    rg2_surface_free(&s);
    rg2_mesh_free(&m);
}

/* The torus's curvatures at sizes 1e-9 and 1e9 (R = 3 s, r = s): K = cos v / (r (R + r cos v))
 * and |H| = (R + 2 r cos v) / (2 r (R + r cos v)) to 1e-13 relative (K s^2, H s). EG - F^2 is
 * about s^4, so a test for its cancellation must compare it with E G (both s^4), not with a
 * fixed figure or with E / G (s^0): against 1e-30 E / G every point of the 1e-9 torus counted
 * as undefined (on the portable kernels), and its K and H came out as their numerators over a
 * denominator of 1, about 0: 0.5 and 0.63 off relative to the exact figures. */
static void torus_sizes(void)
{
    for (int big = 0; big < 2; big++) {
        const double sz = big ? 1e9 : 1e-9, R = 3.0 * sz, r = sz;
        rg2_surface s;
        rg2_error err;
        CHECK_OK(rg2t_torus(R, r, 8, 6, NULL, &s, &err), &err);
        int n = 9, m = 7;
        size_t per = (size_t)n * m, np = (size_t)s.nu * s.nv;
        grid_buf g;
        buf_alloc(&g, per * np);
        CHECK_OK(rg2_surface_grid(&s, n, m, 0, &g.o, &err), &err);
        double kerr = 0, herr = 0;
        for (size_t i = 0; i < per * np; i++) {
            const double *p = g.o.pos + 3 * i;
            double cv = (hypot(p[0], p[1]) - R) / r;
            double K = cv / (r * (R + r * cv)), H = (R + 2 * r * cv) / (2 * r * (R + r * cv));
            worse(&kerr, fabs(g.o.K[i] - K) * sz * sz);
            worse(&herr, fabs(fabs(g.o.H[i]) - H) * sz);
        }
        printf("torus of size %g: K %.2e, H %.2e off the exact torus's (relative)\n", sz, kerr, herr);
        CHECK(kerr <= 1e-13 && herr <= 1e-13, "torus of size %g: grid K %.3g, H %.3g off the exact torus's", sz,
              kerr, herr);
        free(g.mem);
        rg2_surface_free(&s);
    }
}

static void torus(void)
{
    const double R = 3.0, r = 1.0;
    rg2_surface s;
    rg2_error err;
    CHECK_OK(rg2t_torus(R, r, 8, 6, NULL, &s, &err), &err);
    int n = 33, m = 20;
    size_t per = (size_t)n * m, np = (size_t)s.nu * s.nv;
    grid_buf g;
    buf_alloc(&g, per * np);
    CHECK_OK(rg2_surface_grid(&s, n, m, 0, &g.o, &err), &err);
    diffs d = {0};
    for (size_t k = 0; k < np; k++)
        compare_patch(&s.patch[k], n, m, &g.o, k * per, R + r, &d);
    CHECK(d.pos <= 1e-14 && d.normal <= 1e-14 && d.d1 <= 1e-14 && d.d2 <= 1e-14 && d.K <= 1e-14 && d.H <= 1e-14,
          "torus grid vs rg2_patch_eval: pos %.3g normal %.3g d1 %.3g d2 %.3g K %.3g H %.3g", d.pos, d.normal,
          d.d1, d.d2, d.K, d.H);
    /* against the exact torus: distance, normal, K = cos v / (r (R + r cos v)),
     * |H| = (R + 2 r cos v) / (2 r (R + r cos v)) */
    double dist = 0, nerr = 0, kerr = 0, herr = 0;
    for (size_t i = 0; i < per * np; i++) {
        const double *p = g.o.pos + 3 * i, *nn = g.o.normal + 3 * i;
        double rho = hypot(p[0], p[1]), q = rho - R;
        worse(&dist, fabs(hypot(q, p[2]) - r) / (R + r));
        double c[3] = {p[0] / rho * q, p[1] / rho * q, p[2]}; /* exact normal direction */
        double cl = norm3(c);
        worse(&nerr, fmin(dist3((double[3]){c[0] / cl, c[1] / cl, c[2] / cl}, nn),
                          dist3((double[3]){-c[0] / cl, -c[1] / cl, -c[2] / cl}, nn)));
        double cv = q / r;
        double K = cv / (r * (R + r * cv)), H = (R + 2 * r * cv) / (2 * r * (R + r * cv));
        worse(&kerr, fabs(g.o.K[i] - K));
        worse(&herr, fabs(fabs(g.o.H[i]) - H));
    }
    printf("torus, %zu patches x %d x %d: vs rg2_patch_eval pos %.2e normal %.2e K %.2e H %.2e; vs the "
           "exact torus: distance %.2e, normal %.2e, K %.2e, H %.2e\n",
           np, n, m, d.pos, d.normal, d.K, d.H, dist, nerr, kerr, herr);
    CHECK(dist <= 1e-14 && nerr <= 1e-13 && kerr <= 1e-13 && herr <= 1e-13,
          "torus exactness: distance %.3g normal %.3g K %.3g H %.3g", dist, nerr, kerr, herr);

    /* the thread count does not change a single bit */
    grid_buf g1, g2;
    buf_alloc(&g1, per * np);
    buf_alloc(&g2, per * np);
    CHECK_OK(rg2_surface_grid(&s, n, m, 1, &g1.o, &err), &err);
    CHECK_OK(rg2_surface_grid(&s, n, m, 2, &g2.o, &err), &err);
    size_t bytes = per * np * 23 * sizeof(double);
    CHECK(memcmp(g1.mem, g2.mem, bytes) == 0 && memcmp(g1.mem, g.mem, bytes) == 0,
          "1, 2 and default threads give identical bits");
    /* normals spread (each 8 after the next 8 positions, plain stores) vs in two phases: the same
     * bits, for rows of whole vectors, with a partial last one and shorter than one */
    const int sizes[5][2] = {{33, 20}, {17, 9}, {12, 64}, {40, 100}, {9, 13}};
    for (int q = 0; q < 5; q++) {
        size_t c3 = 3 * (size_t)sizes[q][0] * (size_t)sizes[q][1] * np;
        double *sb = malloc(4 * c3 * sizeof(double));
        rg2_grid_out sp = {.pos = sb, .normal = sb + c3}, tp = {.pos = sb + 2 * c3, .normal = sb + 3 * c3};
        CHECK_OK(rg2_surface_grid(&s, sizes[q][0], sizes[q][1], 1, &sp, &err), &err);
        rg2__grid_spread = 0;
        CHECK_OK(rg2_surface_grid(&s, sizes[q][0], sizes[q][1], 1, &tp, &err), &err);
        rg2__grid_spread = 1;
        CHECK(memcmp(sb, sb + 2 * c3, 2 * c3 * sizeof(double)) == 0,
              "%d x %d: spread normals bitwise as in two phases", sizes[q][0], sizes[q][1]);
        free(sb);
    }
    /* the position-only and position+normal kernels (other code paths): 1 vs 3 threads */
    for (int level = 0; level < 2; level++) {
        rg2_grid_out a = {.pos = g1.o.pos, .normal = level ? g1.o.normal : NULL};
        rg2_grid_out b = {.pos = g2.o.pos, .normal = level ? g2.o.normal : NULL};
        CHECK_OK(rg2_surface_grid(&s, n, m, 1, &a, &err), &err);
        CHECK_OK(rg2_surface_grid(&s, n, m, 3, &b, &err), &err);
        CHECK(memcmp(a.pos, b.pos, per * np * 3 * sizeof(double)) == 0 &&
                  (!level || memcmp(a.normal, b.normal, per * np * 3 * sizeof(double)) == 0),
              "level %d: 1 and 3 threads give identical bits", level);
        /* requesting more outputs does not change positions and normals (bitwise) */
        CHECK(memcmp(b.pos, g.o.pos, per * np * 3 * sizeof(double)) == 0 &&
                  (!level || memcmp(b.normal, g.o.normal, per * np * 3 * sizeof(double)) == 0),
              "level %d: the same bits as with every output requested", level);
        diffs dd = {0};
        for (size_t k = 0; k < np; k++)
            compare_patch(&s.patch[k], n, m, &b, k * per, R + r, &dd);
        CHECK(dd.pos <= 1e-14 && dd.normal <= 1e-14, "level %d kernel vs rg2_patch_eval: pos %.3g normal %.3g",
              level, dd.pos, dd.normal);
    }
    free(g.mem);
    free(g1.mem);
    free(g2.mem);
    rg2_surface_free(&s);
}

/* Outputs past 8 MB take the streaming-store paths (straight into 64-byte aligned rows of whole
 * vectors, or shifted to the cache lines): still equal to rg2_patch_eval, and bit for bit to
 * plain stores. */
static void large_output(void)
{
    rg2t_rng r;
    rg2t_seed(&r, 11);
    rg2_patch P;
    random_patch(&r, &P);
    /* 34.6 MB of positions; 34.8 MB of positions + normals (rows misaligned and aligned); then
     * 64-byte aligned arrays with rows of whole vectors (25.2 and 30.7 MB; 800 points a row: 12
     * blocks of 64 and one of 32) */
    const int sizes[4] = {1201, 851, 1024, 800};
    for (int cfg = 0; cfg < 4; cfg++) {
        int n = sizes[cfg], level = cfg & 1;
        size_t pts = (size_t)n * n, bytes = pts * 3 * sizeof(double);
        double *pos = cfg < 2 ? malloc(bytes) : aligned_alloc(64, bytes);
        double *nrm = !level ? NULL : cfg < 2 ? malloc(bytes) : aligned_alloc(64, bytes);
        rg2_grid_out o = {.pos = pos, .normal = nrm};
        rg2_error err;
        CHECK_OK(rg2_patch_grid(&P, n, n, &o, &err), &err);
        double dp = 0, dn = 0;
        for (size_t i = 0; i < pts; i += 97) {
            int a = (int)(i / (size_t)n), b = (int)(i % (size_t)n);
            rg2_eval e;
            rg2_patch_eval(&P, a == n - 1 ? 1.0 : (double)a / (n - 1), b == n - 1 ? 1.0 : (double)b / (n - 1), 1, &e);
            worse(&dp, dist3(pos + 3 * i, e.p) / 3.0);
            if (nrm)
                worse(&dn, dist3(nrm + 3 * i, e.n));
        }
        CHECK(dp <= 1e-14 && dn <= 1e-14, "large output (%d x %d, level %d): position %.3g normal %.3g", n, n, level,
              dp, dn);
        /* the same bits as with plain stores (streaming off), and with normals as with the
         * normals in two phases (spread off; misaligned rows through a buffer) */
        double *pos2 = cfg < 2 ? malloc(bytes) : aligned_alloc(64, bytes);
        double *nrm2 = !level ? NULL : cfg < 2 ? malloc(bytes) : aligned_alloc(64, bytes);
        rg2_grid_out o2 = {.pos = pos2, .normal = nrm2};
        size_t stream_bytes = rg2__grid_stream_bytes;
        rg2__grid_stream_bytes = SIZE_MAX;
        CHECK_OK(rg2_patch_grid(&P, n, n, &o2, &err), &err);
        rg2__grid_stream_bytes = stream_bytes;
        CHECK(memcmp(pos2, pos, bytes) == 0 && (!level || memcmp(nrm2, nrm, bytes) == 0),
              "large output (%d x %d, level %d): streamed bitwise as with plain stores", n, n, level);
        if (level) {
            rg2__grid_spread = 0;
            CHECK_OK(rg2_patch_grid(&P, n, n, &o2, &err), &err);
            rg2__grid_spread = 1;
            CHECK(memcmp(pos2, pos, bytes) == 0 && memcmp(nrm2, nrm, bytes) == 0,
                  "large output (%d x %d): spread normals bitwise as in two phases", n, n);
        }
        free(pos2);
        free(nrm2);
        free(pos);
        free(nrm);
    }
    /* patchworks streamed with rows not on cache lines, bitwise as 1 thread with plain stores: 48
     * patches of 129 x 129 points (two blocks a row; 38 MB with normals) by 2 threads; 120 of 65 x
     * 65 and, from a start 8 bytes past a cache line, of 72 x 72 (one block a row, so each row
     * hands the line it shares to the next: 12-30 MB), by 1; 48 of 90 x 90 (a block of 64 and one
     * of 26 a row, both shifted: 9.3 MB of positions), by 1; rows of 16-31 points, whose positions
     * stream shifted too (from 24 points where the pages are touched ahead, the AMD rule; plain
     * below), at any size (the threshold set to 0): 120 of 20 x 20 from a start 8 bytes past a
     * line, by 1, of 16 x 16 from 24 bytes past, by 2, and of 26 x 26 from 8 bytes past, by 1 */
    const int cases[][6] = {{8, 6, 129, 2, 0, 0}, {12, 10, 65, 1, 0, 0}, {12, 10, 72, 1, 1, 0},
                            {8, 6, 90, 1, 0, 0},  {12, 10, 20, 1, 1, 1}, {12, 10, 16, 2, 3, 1},
                            {12, 10, 26, 1, 1, 1}};
    /* nu nv n threads offset stream-always */
    for (size_t c = 0; c < sizeof cases / sizeof cases[0]; c++) {
        rg2_surface s;
        rg2_error err;
        CHECK_OK(rg2t_torus(3.0, 1.0, cases[c][0], cases[c][1], NULL, &s, &err), &err);
        const int n = cases[c][2], off = cases[c][4];
        size_t pts = (size_t)n * n * (size_t)s.nu * (size_t)s.nv, bytes = pts * 3 * sizeof(double);
        double *buf = aligned_alloc(64, 4 * bytes + 64);
        for (int level = 0; level < 2; level++) {
            rg2_grid_out a = {.pos = buf + off, .normal = level ? buf + off + 3 * pts : NULL};
            rg2_grid_out b = {.pos = buf + 6 * pts + off, .normal = level ? buf + off + 9 * pts : NULL};
            size_t stream_bytes = rg2__grid_stream_bytes;
            if (cases[c][5])
                rg2__grid_stream_bytes = 0;
            CHECK_OK(rg2_surface_grid(&s, n, n, cases[c][3], &a, &err), &err);
            rg2__grid_stream_bytes = SIZE_MAX;
            CHECK_OK(rg2_surface_grid(&s, n, n, 1, &b, &err), &err);
            rg2__grid_stream_bytes = stream_bytes;
            CHECK(memcmp(a.pos, b.pos, bytes) == 0 && (!level || memcmp(a.normal, b.normal, bytes) == 0),
                  "torus %d x %d per patch, level %d, %d threads: streamed bitwise as plain stores", n, n, level,
                  cases[c][3]);
        }
        free(buf);
        rg2_surface_free(&s);
    }
}

/* Patches at most 8 points wide take kernels of their own on AVX-512 (whole rows in registers):
 * against rg2_patch_eval, the same bits as the wide kernels give with every output requested, 1 vs
 * 2 threads; with 64-byte aligned arrays of 8 x 8 patches past the streaming thresholds (17.6 MB of
 * positions, 35 MB with normals: streaming stores straight into the rows), misaligned arrays of the
 * same (streamed, shifted to the cache lines), aligned positions with misaligned normals (both
 * shifted) and rows shorter than a vector (masked stores). */
static void narrow_patches(void)
{
    enum { NP = 11500 };
    rg2t_rng r;
    rg2t_seed(&r, 23);
    rg2_patch *P = malloc(NP * sizeof *P);
    for (int k = 0; k < NP; k++)
        random_patch(&r, &P[k]);
    const struct {
        int n, m, np, misalign, nrm_misalign;
    } cfg[] = {{8, 8, NP, 0, 0},    {8, 8, NP, 1, 0},    {8, 8, NP, 0, 5},
               {9, 5, 700, 1, 0},   {3, 7, 700, 0, 0},   {6, 2, 700, 0, 0}};
    for (size_t c = 0; c < sizeof cfg / sizeof cfg[0]; c++) {
        int n = cfg[c].n, m = cfg[c].m, np = cfg[c].np, nm = cfg[c].nrm_misalign;
        rg2_surface s;
        memset(&s, 0, sizeof s);
        s.nu = np / 100, s.nv = 100, s.patch = P;
        size_t pts = (size_t)s.nu * s.nv * n * m, vec = 3 * pts + 8;
        double *mem = aligned_alloc(64, ((5 * vec + pts + 24 + 7) & ~(size_t)7) * sizeof(double));
        /* (the normal arrays nm doubles further on than the position arrays' alignment) */
        double *pos = mem + cfg[c].misalign, *nrm = pos + vec + nm, *pos2 = nrm + vec - nm;
        double *nrm2 = pos2 + vec + nm, *pos3 = nrm2 + vec - nm, *K = pos3 + vec;
        rg2_error err;
        /* every output the wide kernels give (K asks for the second order) */
        rg2_grid_out full = {.pos = pos, .normal = nrm, .K = K};
        CHECK_OK(rg2_surface_grid(&s, n, m, 1, &full, &err), &err);
        rg2_grid_out o0 = {.pos = pos3}, o1 = {.pos = pos2, .normal = nrm2};
        for (int th = 1; th <= 2; th++) {
            CHECK_OK(rg2_surface_grid(&s, n, m, th, &o0, &err), &err);
            CHECK_OK(rg2_surface_grid(&s, n, m, th, &o1, &err), &err);
            CHECK(memcmp(pos3, pos, 3 * pts * sizeof(double)) == 0 &&
                      memcmp(pos2, pos, 3 * pts * sizeof(double)) == 0 &&
                      memcmp(nrm2, nrm, 3 * pts * sizeof(double)) == 0,
                  "narrow %d x %d, %d patches, %d thread(s): positions and normals bitwise as with every output",
                  n, m, np, th);
        }
        diffs d = {0};
        for (int k = 0; k < s.nu * s.nv; k += 37)
            compare_patch(&P[k], n, m, &o1, (size_t)k * n * m, 3.0, &d);
        CHECK(d.pos <= 1e-14 && d.normal <= 1e-14, "narrow %d x %d vs rg2_patch_eval: position %.3g normal %.3g",
              n, m, d.pos, d.normal);
        printf("  narrow %d x %d per patch, %d patches (%.1f MB of positions%s): vs rg2_patch_eval position "
               "%.2e, normal %.2e\n",
               n, m, np, 24e-6 * (double)pts, cfg[c].misalign ? ", misaligned" : nm ? ", normals misaligned" : "",
               d.pos, d.normal);
        /* past the streaming threshold (set to 0): rows shorter than a vector are stored as below it,
         * the shifted run of whole rows being for rows of exactly 8 points */
        if (m < 8) {
            size_t stream_bytes = rg2__grid_stream_bytes;
            rg2__grid_stream_bytes = 0;
            memset(pos3, 0xff, 3 * pts * sizeof(double)); /* NaN: every value must be stored again */
            memset(pos2, 0xff, 3 * pts * sizeof(double));
            memset(nrm2, 0xff, 3 * pts * sizeof(double));
            CHECK_OK(rg2_surface_grid(&s, n, m, 1, &o0, &err), &err);
            CHECK_OK(rg2_surface_grid(&s, n, m, 1, &o1, &err), &err);
            rg2__grid_stream_bytes = stream_bytes;
            CHECK(memcmp(pos3, pos, 3 * pts * sizeof(double)) == 0 &&
                      memcmp(pos2, pos, 3 * pts * sizeof(double)) == 0 &&
                      memcmp(nrm2, nrm, 3 * pts * sizeof(double)) == 0,
                  "narrow %d x %d, streamed: positions and normals bitwise as with plain stores", n, m);
        }
        /* K without the normals it is made from: the second-order kernel stores only what is asked */
        memset(nrm2, 0, 3 * pts * sizeof(double));
        rg2_grid_out ok = {.pos = pos3, .K = nrm2};
        CHECK_OK(rg2_surface_grid(&s, n, m, 1, &ok, &err), &err);
        CHECK(memcmp(nrm2, K, pts * sizeof(double)) == 0 && memcmp(pos3, pos, 3 * pts * sizeof(double)) == 0,
              "narrow %d x %d: K (and positions) alone bitwise as with the normals", n, m);
        free(mem);
    }
    free(P);
}

static void errors(void)
{
    rg2_patch P;
    memset(&P, 0, sizeof P);
    double pos[3 * 16];
    rg2_grid_out o = {.pos = pos};
    rg2_error err;
    CHECK(rg2_patch_grid(&P, 1, 4, &o, &err) == RG2_EINVAL && strstr(err.msg, "at least 2"), "n = 1: %s",
          err.msg);
    CHECK(rg2_patch_grid(&P, 4, 0, &o, &err) == RG2_EINVAL && strstr(err.msg, "4 x 0"), "m = 0: %s", err.msg);
    CHECK(rg2_patch_grid(&P, RG2_GRID_MAX + 1, 4, &o, &err) == RG2_ELIMIT && strstr(err.msg, "limit"),
          "past RG2_GRID_MAX: %s", err.msg);
    rg2_grid_out none = {0};
    CHECK(rg2_patch_grid(&P, 4, 4, &none, &err) == RG2_EINVAL && strstr(err.msg, "pos"), "NULL pos: %s",
          err.msg);
    CHECK(rg2_patch_grid(&P, 4, 4, NULL, &err) == RG2_EINVAL && !strcmp(err.msg, "grid: no output arrays (out is NULL)"),
          "NULL out: %s", err.msg); /* (it blamed out->pos) */
    CHECK(rg2_patch_grid(NULL, 4, 4, &o, &err) == RG2_EINVAL && strstr(err.msg, "patch"), "NULL patch: %s",
          err.msg);
    rg2_surface s;
    memset(&s, 0, sizeof s);
    CHECK(rg2_surface_grid(&s, 4, 4, 0, &o, &err) == RG2_EINVAL && strstr(err.msg, "empty"), "empty surface: %s",
          err.msg);
    s.nu = s.nv = 1;
    s.patch = &P;
    CHECK(rg2_surface_grid(&s, 4, 4, -1, &o, &err) == RG2_EINVAL && strstr(err.msg, "thread"),
          "negative threads: %s", err.msg);
    s.nu = s.nv = 2000000000; /* never dereferenced: the size check comes first */
    CHECK(rg2_surface_grid(&s, RG2_GRID_MAX, RG2_GRID_MAX, 1, &o, &err) == RG2_ELIMIT &&
              strstr(err.msg, "addressable"),
          "total size past memory sizes: %s", err.msg);
}

/* The tables cache (grid.c): the same bits whether a call's tables were made for it or taken
 * from the cache, for more sizes than the cache keeps (the first 8 are kept, the others made
 * every time), and from three application threads calling at once in different orders. Runs
 * first, so that the cache starts empty. */
#define CACHE_SIZES 12
static const int cache_nm[CACHE_SIZES][2] = {{5, 7}, {8, 8}, {9, 3}, {16, 16}, {17, 33}, {32, 32},
                                              {2, 2}, {64, 64}, {3, 100}, {100, 3}, {40, 41}, {7, 5}};
typedef struct {
    const rg2_patch *P;
    grid_buf *ref;
    int start, bad;
} cache_thread;

static int same_grid(const grid_buf *a, const grid_buf *b, size_t pts)
{
    return !memcmp(a->mem, b->mem, pts * 23 * sizeof(double));
}

static void *cache_worker(void *arg)
{
    cache_thread *c = arg;
    rg2_error err;
    for (int it = 0; it < 30; it++)
        for (int q = 0; q < CACHE_SIZES; q++) {
            int k = (c->start + q * (it % 2 ? 5 : 7)) % CACHE_SIZES, n = cache_nm[k][0], m = cache_nm[k][1];
            size_t pts = (size_t)n * m;
            grid_buf g;
            buf_alloc(&g, pts);
            if (rg2_patch_grid(c->P, n, m, &g.o, &err) || !same_grid(&g, &c->ref[k], pts))
                c->bad++;
            free(g.mem);
        }
    return NULL;
}

static void tables_cache(void)
{
    rg2t_rng r;
    rg2t_seed(&r, 4242);
    rg2_patch P;
    random_patch(&r, &P);
    rg2_error err;
    grid_buf ref[CACHE_SIZES];
    int kept = 0;
    for (int k = 0; k < CACHE_SIZES; k++) {
        int n = cache_nm[k][0], m = cache_nm[k][1];
        size_t pts = (size_t)n * m;
        CHECK(!rg2__grid_tables_cached(n, m), "%d x %d: cached before its first call", n, m);
        buf_alloc(&ref[k], pts);
        CHECK_OK(rg2_patch_grid(&P, n, m, &ref[k].o, &err), &err); /* tables made (and kept) */
        kept += rg2__grid_tables_cached(n, m);
    }
    CHECK(kept == 8, "%d of %d sizes kept, expected the cache's 8", kept, CACHE_SIZES);
    for (int k = 0; k < CACHE_SIZES; k++) { /* from the cache (the first 8), made again (the rest) */
        int n = cache_nm[k][0], m = cache_nm[k][1];
        size_t pts = (size_t)n * m;
        grid_buf g;
        buf_alloc(&g, pts);
        CHECK_OK(rg2_patch_grid(&P, n, m, &g.o, &err), &err);
        CHECK(same_grid(&g, &ref[k], pts), "%d x %d (%s): not the bits of the first call", n, m,
              k < 8 ? "cached tables" : "tables made again");
        free(g.mem);
    }
    cache_thread ct[3];
    pthread_t tid[3];
    for (int t = 0; t < 3; t++) {
        ct[t] = (cache_thread){&P, ref, 4 * t, 0};
        CHECK(!pthread_create(&tid[t], NULL, cache_worker, &ct[t]), "thread %d not started", t);
    }
    for (int t = 0; t < 3; t++) {
        pthread_join(tid[t], NULL);
        CHECK(ct[t].bad == 0, "thread %d: %d of %d calls differ from the first call's bits", t, ct[t].bad,
              30 * CACHE_SIZES);
    }
    for (int k = 0; k < CACHE_SIZES; k++)
        free(ref[k].mem);
    printf("tables cache: %d sizes, 8 kept; the same bits from kept and made tables, and from 3 threads x %d "
           "calls\n", CACHE_SIZES, 30 * CACHE_SIZES);
}

/* Side `side` (0 v=0, 1 u=1, 2 v=1, 3 u=0) of patch X collapsed to a point: its affine control
 * points within 1e-11 of the patch's control box diagonal of the first (rg2.h's poles; computed
 * here from the control points). */
static int side_collapsed(const rg2_xpatch *X, int side)
{
    double lo[3] = {INFINITY, INFINITY, INFINITY}, hi[3] = {-INFINITY, -INFINITY, -INFINITY}, diag = 0.0;
    for (int r = 0; r <= X->du; r++)
        for (int t = 0; t <= X->dv; t++)
            for (int k = 0; k < 3; k++) {
                lo[k] = fmin(lo[k], X->h[r][t][k] / X->h[r][t][3]);
                hi[k] = fmax(hi[k], X->h[r][t][k] / X->h[r][t][3]);
            }
    for (int k = 0; k < 3; k++)
        diag += (hi[k] - lo[k]) * (hi[k] - lo[k]);
    int n = side & 1 ? X->dv : X->du;
    for (int a = 1; a <= n; a++)
        for (int k = 0; k < 3; k++) {
            const double *p = side == 0 ? X->h[a][0] : side == 1 ? X->h[X->du][a] : side == 2 ? X->h[a][X->dv] : X->h[0][a];
            const double *q = side == 0 ? X->h[0][0] : side == 1 ? X->h[X->du][0] : side == 2 ? X->h[0][X->dv] : X->h[0][0];
            if (!(fabs(p[k] / p[3] - q[k] / q[3]) <= 1e-11 * sqrt(diag)))
                return 0;
        }
    return 1;
}

/* The poles of the examples' Moebius-moved spheres and saddle caps (bi-3 and degree-5 patches):
 * at every grid point on a collapsed side the normal is 0 and K = H = 0 (rg2.h), in the grid,
 * rg2_surface_eval and rg2_patch_point_normal. The side's control points are equal only
 * projectively there, and the rounding-level test alone let 10 points of Fig. 14's second sphere
 * (u = 63/128: a normal 77 degrees off, K = -1.5e29) and 8 of Fig. 15's second surface (u = 1/2,
 * every odd grid size) through. */
/* rg2_surface_eval_limit at (u, v) on collapsed side `side` of patch (i, j): the limit normal
 * against one extrapolated from two normals of rg2_surface_eval inside, at distances h and 2h
 * from the side (n(0) = 2 n(h) - n(2h) + O(h^2); their rounding grows like 1e-14 / h), and K, H
 * against those at h (the curvatures converge linearly, docs/poles.md). Returns the angle (the
 * worse of orders 2 and 1), and the curvatures' difference relative to max(|K(h)|, 1) and
 * max(|H(h)|, 1) in *dk. Order 1 and 2 must agree on the flags, and order 1 must leave the
 * curvatures zero (rg2.h: fields beyond the order are zero): else *flags gets ~0u. So must a
 * normal of length other than 1 (the angle alone would not see it). */
static double limit_at_pole(const rg2_surface *s, int i, int j, double u, double v, int side, double *dk,
                            unsigned *flags)
{
    rg2_eval e, e1, a, b;
    rg2_surface_eval_limit(s, i, j, u, v, 2, &e);
    rg2_surface_eval_limit(s, i, j, u, v, 1, &e1);
    *flags = e.flags;
    if (e1.flags != e.flags || e1.K != 0.0 || e1.H != 0.0 || e1.k1 != 0.0 || e1.k2 != 0.0 ||
        !(fabs(norm3(e.n) - 1.0) <= 1e-14 && fabs(norm3(e1.n) - 1.0) <= 1e-14))
        *flags = ~0u;
    const double h = 1e-4;
    double du = side == 1 ? -h : side == 3 ? h : 0.0, dv = side == 0 ? h : side == 2 ? -h : 0.0;
    rg2_surface_eval(s, i, j, u + du, v + dv, 2, &a);
    rg2_surface_eval(s, i, j, u + 2 * du, v + 2 * dv, 2, &b);
    double x[3];
    for (int k = 0; k < 3; k++)
        x[k] = 2 * a.n[k] - b.n[k];
    double l = norm3(x);
    for (int k = 0; k < 3; k++)
        x[k] /= l;
    *dk = fmax(fabs(e.K - a.K) / fmax(fabs(a.K), 1.0), fabs(e.H - a.H) / fmax(fabs(a.H), 1.0));
    return fmax(pt_angle3(e.n, x), pt_angle3(e1.n, x));
}

/* The examples collapse only sides v = 0 and v = 1 (their poles), and their pole normals have
 * no y component: each such patch of Fig. 14, transposed (h[r][t] -> h[t][r], a one-patch
 * surface) and its coordinates rotated, collapses u = 0 or u = 1 (sides 3 and 1) instead, where
 * the limit normal is Su x Suv, its sign flipped on u = 1. limit_at_pole at 9 points of every
 * such side, orders 2 and 1. */
static void limit_on_u_sides(void)
{
    rg2_design *d = NULL;
    rg2_error err;
    CHECK_OK(rg2_design_load("examples/fig14_mobius.json", &d, &err), &err);
    int sides[4] = {0, 0, 0, 0}, bad = 0;
    double worst_ang = 0, worst_k = 0;
    for (int si = 0; d && si < rg2_design_num_surfaces(d); si++) {
        const rg2_surface *s = rg2_design_surface(d, si);
        for (int k = 0; k < s->nu * s->nv; k++) {
            rg2_xpatch X, T;
            rg2_surface_patch_get(s, k / s->nv, k % s->nv, &X);
            memset(&T, 0, sizeof T);
            T.du = X.dv;
            T.dv = X.du;
            for (int r = 0; r <= X.du; r++)
                for (int t = 0; t <= X.dv; t++)
                    for (int c = 0; c < 4; c++) /* (x, y, z) -> (y, z, x): normals with a y component */
                        T.h[t][r][c] = X.h[r][t][c < 3 ? (c + 1) % 3 : 3];
            rg2_patch unused;
            memset(&unused, 0, sizeof unused);
            rg2_surface one = {.nu = 1, .nv = 1, .patch = &unused, .xp = &T};
            for (int side = 0; side < 4; side++) {
                if (!side_collapsed(&T, side))
                    continue;
                sides[side]++;
                for (int q = 0; q <= 8; q++) {
                    double w = q / 8.0, u = side == 1 ? 1.0 : side == 3 ? 0.0 : w;
                    double v = side == 0 ? 0.0 : side == 2 ? 1.0 : w, dk;
                    unsigned fl;
                    worst_ang = fmax(worst_ang, limit_at_pole(&one, 0, 0, u, v, side, &dk, &fl));
                    worst_k = fmax(worst_k, dk);
                    bad += fl != RG2_EVAL_POLE_LIMIT;
                }
            }
        }
    }
    rg2_design_free(d);
    printf("fig14 transposed: collapsed sides %d, %d, %d, %d; rg2_surface_eval_limit: %d points with other flags, "
           "order 1 unlike 2 or |n| != 1; normal vs extrapolated %.2g rad, K and H vs 1e-4 inside %.2g\n",
           sides[0], sides[1], sides[2], sides[3], bad, worst_ang, worst_k);
    CHECK(sides[1] > 0 && sides[3] > 0 && sides[0] == 0 && sides[2] == 0 && bad == 0 && worst_ang <= 1e-6 &&
              worst_k <= 1e-2,
          "fig14 transposed: sides %d %d %d %d, %d bad, normal %.3g rad, K and H %.3g", sides[0], sides[1], sides[2],
          sides[3], bad, worst_ang, worst_k);
}

static void design_poles(void)
{
    static const char *const files[] = {"examples/fig14_mobius.json", "examples/fig15_saddle_caps.json"};
    static const int sizes[] = {3, 129};
    for (int f = 0; f < 2; f++) {
        rg2_design *d = NULL;
        rg2_error err;
        CHECK_OK(rg2_design_load(files[f], &d, &err), &err);
        if (!d)
            continue;
        int pts = 0, bad_grid = 0, bad_eval = 0, bad_point = 0, bad_limit = 0, same = 0, differ = 0;
        double worst_ang = 0, worst_k = 0;
        for (int si = 0; si < rg2_design_num_surfaces(d); si++) {
            const rg2_surface *s = rg2_design_surface(d, si);
            size_t np = (size_t)s->nu * s->nv;
            for (int z = 0; z < 2; z++) {
                int n = sizes[z];
                size_t per = (size_t)n * n;
                grid_buf g;
                buf_alloc(&g, per * np);
                CHECK_OK(rg2_surface_grid(s, n, n, 1, &g.o, &err), &err);
                for (size_t k = 0; k < np; k++) {
                    rg2_xpatch X;
                    rg2_surface_patch_get(s, (int)(k / s->nv), (int)(k % s->nv), &X);
                    /* off the poles, rg2_surface_eval_limit is rg2_surface_eval, bit for bit */
                    for (int a = 0; z == 0 && a < 5; a++)
                        for (int b = 0; b < 5; b++) {
                            double u = a / 4.0, v = b / 4.0;
                            int on = (b == 0 && side_collapsed(&X, 0)) || (a == 4 && side_collapsed(&X, 1)) ||
                                     (b == 4 && side_collapsed(&X, 2)) || (a == 0 && side_collapsed(&X, 3));
                            for (int order = 0; order <= 2; order++) {
                                rg2_eval e, l;
                                rg2_surface_eval(s, (int)(k / s->nv), (int)(k % s->nv), u, v, order, &e);
                                rg2_surface_eval_limit(s, (int)(k / s->nv), (int)(k % s->nv), u, v, order, &l);
                                if (on && order > 0) /* on a pole: only n, the curvatures and flags differ */
                                    memcpy(l.n, e.n, sizeof e.n), l.K = e.K, l.H = e.H, l.k1 = e.k1, l.k2 = e.k2,
                                        l.flags = e.flags;
                                if (memcmp(&e, &l, offsetof(rg2_eval, flags)) == 0 && e.flags == l.flags)
                                    same++;
                                else
                                    differ++;
                            }
                        }
                    for (int side = 0; side < 4; side++) {
                        if (!side_collapsed(&X, side))
                            continue;
                        for (int q = 0; q < n; q++, pts++) {
                            int a = side == 1 ? n - 1 : side == 3 ? 0 : q, b = side == 0 ? 0 : side == 2 ? n - 1 : q;
                            double u = a == n - 1 ? 1.0 : (double)a / (n - 1), v = b == n - 1 ? 1.0 : (double)b / (n - 1);
                            size_t i = k * per + (size_t)a * n + b;
                            bad_grid += !(norm3(g.o.normal + 3 * i) == 0.0 && g.o.K[i] == 0.0 && g.o.H[i] == 0.0);
                            rg2_eval e;
                            rg2_surface_eval(s, (int)(k / s->nv), (int)(k % s->nv), u, v, 2, &e);
                            bad_eval += !(e.flags & RG2_EVAL_NORMAL_UNDEFINED && norm3(e.n) == 0.0 && e.K == 0.0 && e.H == 0.0);
                            unsigned lf;
                            double dk, ang = limit_at_pole(s, (int)(k / s->nv), (int)(k % s->nv), u, v, side, &dk, &lf);
                            bad_limit += lf != RG2_EVAL_POLE_LIMIT;
                            worst_ang = fmax(worst_ang, ang);
                            worst_k = fmax(worst_k, dk);
                            if (!(s->xp && s->xp[k].du > 0)) {
                                double p[3], nn[3];
                                unsigned fl = rg2_patch_point_normal(&s->patch[k], u, v, p, nn);
                                bad_point += !(fl & RG2_EVAL_NORMAL_UNDEFINED && norm3(nn) == 0.0);
                            }
                        }
                    }
                }
                free(g.mem);
            }
        }
        printf("%s: %d grid points on collapsed sides; normal or K, H not 0 at %d (grid), %d (rg2_surface_eval), "
               "%d (rg2_patch_point_normal)\n", files[f], pts, bad_grid, bad_eval, bad_point);
        printf("%s: rg2_surface_eval_limit: flags other than RG2_EVAL_POLE_LIMIT (or order 1 unlike order 2, or |n| != 1) "
               "at %d pole points; limit normal vs "
               "extrapolated %.2g rad, K and H vs 1e-4 inside %.2g; %d of %d evaluations off the poles differ from "
               "rg2_surface_eval\n", files[f], bad_limit, worst_ang, worst_k, differ, same + differ);
        CHECK(bad_limit == 0 && worst_ang <= 1e-6 && worst_k <= 1e-2 && differ == 0 && same > 1000,
              "%s: rg2_surface_eval_limit: flags %d, normal %.3g rad, K and H %.3g, %d of %d differ", files[f], bad_limit,
              worst_ang, worst_k, differ, same + differ);
        CHECK(pts > 1000 && bad_grid == 0 && bad_eval == 0 && bad_point == 0,
              "%s: %d pole points; normal defined at %d (grid), %d (eval), %d (point)", files[f], pts, bad_grid,
              bad_eval, bad_point);
        rg2_design_free(d);
    }
}

/* A flat wedge W[r][t] whose side t = 0 is collapsed to 4e-12 (the tolerance is 1e-11 of its box,
 * 1.4e-11) with a height h: with h = 1e-4 the side's tangent is 5.9e-8 of the other, which the
 * first trigger of the pole test (a ratio below 1e-8) missed (normal defined, K = -1.3e21). The
 * wedge is laid on the patch with its collapsed side on `side` (0 v=0, 1 u=1, 2 v=1, 3 u=0). */
static void flat_wedge(rg2_patch *P, double h, int side)
{
    memset(P, 0, sizeof *P);
    for (int r = 0; r < 4; r++)
        for (int t = 0; t < 4; t++) {
            double x = r / 3.0 - 0.5, y = t / 3.0;
            int a = side == 0 ? r : side == 1 ? 3 - t : side == 2 ? r : t; /* P's indices of W[r][t] */
            int b = side == 0 ? t : side == 1 ? r : side == 2 ? 3 - t : r;
            double *q = P->h[a][b];
            q[0] = t == 0 ? (r == 1 ? 4e-12 : r == 2 ? -4e-12 : 0.0) : t == 3 ? x : x * y;
            q[1] = t == 0 ? 0.0 : h * y;
            q[2] = t == 0 ? 0.0 : (r * 7 + t * 3) % 5 * 0.1 * h * y;
            q[3] = 1.0;
        }
}

/* The wedge's pole on each of the four sides: every evaluator (rg2_patch_eval, rg2_xpatch_eval,
 * rg2_patch_point_normal, rg2_patch_grid) gives the undefined normal at the side's midpoint (before,
 * only poles on v = 0 were tested: the u = 1, v = 1 and u = 0 sides' tests could be lost). With
 * h = 2e-5 the weak side's tangent is 5 times larger, |su x sv| about 3e-7 (|su|^2 + |sv|^2): under
 * the trigger's 1e-6, over a trigger 10 times tighter. */
/* P raised to degree (5, 3) as a one-patch surface, on the 3 x 3 higher-degree grid into o. */
static void raised_grid(const rg2_patch *P, const rg2_grid_out *o)
{
    rg2_xpatch X, Xe;
    rg2_error err;
    rg2_xpatch_from_patch(P, &X);
    CHECK_OK(rg2_xpatch_elevate(&X, 5, 3, &Xe, &err), &err);
    rg2_surface one;
    memset(&one, 0, sizeof one);
    one.nu = one.nv = 1;
    one.patch = (rg2_patch *)P;
    one.xp = &Xe;
    CHECK_OK(rg2_surface_patch_grid(&one, 0, 0, 3, 3, o, &err), &err);
}

static void flat_wedge_pole(void)
{
    static const double mid[4][2] = {{0.5, 0.0}, {1.0, 0.5}, {0.5, 1.0}, {0.0, 0.5}};
    for (int z = 0; z < 8; z++) {
        int side = z % 4;
        double h = z < 4 ? 1e-4 : 2e-5;
        rg2_patch P;
        flat_wedge(&P, h, side);
        double u = mid[side][0], v = mid[side][1];
        rg2_eval e, ex, e1, ex1; /* (order 1 too: the normal without the curvatures) */
        rg2_patch_eval(&P, u, v, 2, &e);
        rg2_patch_eval(&P, u, v, 1, &e1);
        rg2_xpatch X;
        rg2_xpatch_from_patch(&P, &X);
        rg2_xpatch_eval(&X, u, v, 2, &ex);
        rg2_xpatch_eval(&X, u, v, 1, &ex1);
        CHECK(e1.flags & ex1.flags & RG2_EVAL_NORMAL_UNDEFINED && norm3(e1.n) == 0.0 && norm3(ex1.n) == 0.0,
              "flat wedge (h %g) pole on side %d, order 1: eval flags %u, xpatch eval flags %u", h, side, e1.flags,
              ex1.flags);
        double p[3], n[3], pg[27], ng[27], K[9];
        unsigned fl = rg2_patch_point_normal(&P, u, v, p, n);
        rg2_grid_out o = {.pos = pg, .normal = ng, .K = K};
        rg2_error err;
        CHECK_OK(rg2_patch_grid(&P, 3, 3, &o, &err), &err);
        int g = (int)(u * 2) * 3 + (int)(v * 2); /* the grid point (u, v) */
        CHECK(e.flags & RG2_EVAL_NORMAL_UNDEFINED && e.K == 0.0 && ex.flags & RG2_EVAL_NORMAL_UNDEFINED &&
                  ex.K == 0.0 && fl & RG2_EVAL_NORMAL_UNDEFINED && norm3(n) == 0.0 && norm3(ng + 3 * g) == 0.0 &&
                  K[g] == 0.0,
              "flat wedge (h %g) pole on side %d: eval flags %u K %.3g, xpatch eval flags %u K %.3g, point flags %u, "
              "grid normal %.3g K %.3g", h, side, e.flags, e.K, ex.flags, ex.K, fl, norm3(ng + 3 * g), K[g]);
        /* the same patch raised to degree (5, 3), on the higher-degree grid (its own pole fix-up) */
        memset(ng, 0xff, sizeof ng);
        raised_grid(&P, &o);
        CHECK(norm3(ng + 3 * g) == 0.0 && K[g] == 0.0, "flat wedge (h %g) raised to (5,3), pole on side %d: grid normal "
              "%.3g K %.3g", h, side, norm3(ng + 3 * g), K[g]);
    }
}

/* A thin wedge (h = 1e-8): its tangents are weak (|su x sv| below 1e-6 (|su|^2 + |sv|^2)) all over,
 * so every point of its sides is a pole suspect, but only the collapsed side v = 0 is a pole: on
 * the side u = 0 the normal is defined, within 1e-6 rad of the normal just inside (u = 1e-9). */
static void thin_wedge_side(void)
{
    rg2_patch P;
    flat_wedge(&P, 1e-8, 0);
    rg2_eval e, in;
    rg2_patch_eval(&P, 0.0, 0.5, 2, &e);
    rg2_patch_eval(&P, 1e-9, 0.5, 1, &in);
    double p[3], n[3];
    unsigned fl = rg2_patch_point_normal(&P, 0.0, 0.5, p, n);
    double d[3] = {e.n[0] - in.n[0], e.n[1] - in.n[1], e.n[2] - in.n[2]};
    double dp[3] = {n[0] - in.n[0], n[1] - in.n[1], n[2] - in.n[2]};
    CHECK(!(e.flags & RG2_EVAL_NORMAL_UNDEFINED) && !(in.flags & RG2_EVAL_NORMAL_UNDEFINED) && norm3(d) < 1e-6 &&
              !(fl & RG2_EVAL_NORMAL_UNDEFINED) && norm3(dp) < 1e-6,
          "thin wedge, side u = 0 (no pole): eval flags %u, normal %.3g from the inside's, point flags %u, %.3g",
          e.flags, norm3(d), fl, norm3(dp));
    /* raised to degree (5, 3), on the higher-degree grid: the normal at (0, 1/2) is defined too */
    double pg[27], ng[27];
    rg2_grid_out o = {.pos = pg, .normal = ng};
    raised_grid(&P, &o);
    double dg[3] = {ng[3] - in.n[0], ng[4] - in.n[1], ng[5] - in.n[2]}; /* grid point (0, 1) */
    CHECK(norm3(dg) < 1e-6, "thin wedge raised to (5,3), side u = 0 (no pole): grid normal %.3g from the inside's",
          norm3(dg));
}

int main(void)
{
    tables_cache();
    /* every kernel family: the AVX-512 ones (where the CPU has them) with Newton steps and with
     * the hardware's divisions and square roots, then the portable ones */
    for (int family = 0; family < 3; family++) {
        int portable = family == 2;
        rg2__grid_portable = portable;
        rg2__grid_hwdiv = family;
        rg2__grid_pages = family; /* streamed outputs with and without their pages touched ahead */
        printf("-- %s kernels\n", portable       ? "portable"
                                  : family == 0 ? "AVX-512 (where available), Newton steps, pages not touched ahead"
                                                : "AVX-512 (where available), hardware division, pages touched ahead");
        random_patches();
        collapsed_edge();
        normal_test_bound();
        capped_poles();
        design_poles();
        flat_wedge_pole();
        thin_wedge_side();
        torus();
        torus_sizes();
        large_output();
        narrow_patches();
    }
    errors();
    limit_on_u_sides();
    return rg2t_done("test_grid");
}
