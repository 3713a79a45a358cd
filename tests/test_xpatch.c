/* test_xpatch.c -- patches of degree up to RG2_MAX_DEGREE: the Bernstein bases (partition of
 * unity, closed form, derivatives against the degree-lowered bases and finite differences),
 * the general evaluator against rg2_patch_eval on bi-3 patches, exact degree elevation
 * (points, normals, K, H over dense samples for every target degree), the surface grid and the
 * per-patch grid on surfaces holding elevated patches, collapsed sides of any degree, and the
 * refusal of bad degrees. */
#include "../src/export_internal.h"
#include "../src/xpatch_util.h"
#include "harness.h"
#include "xmix.h"

#include <stdlib.h>
#include <string.h>

static double binom(int n, int k)
{
    double c = 1.0;
    for (int i = 1; i <= k; i++)
        c = c * (n - k + i) / i;
    return c;
}

/* Bernstein bases of every degree 1..5 at 41 parameters. */
static void bases(void)
{
    double unity = 0, dsum = 0, ddsum = 0, closed = 0, lowered = 0, lowered2 = 0, fd1 = 0, fd2 = 0;
    for (int n = 1; n <= RG2_MAX_DEGREE; n++)
        for (int q = 0; q <= 40; q++) {
            double t = q / 40.0, B[6], D[6], DD[6], s = 0, sd = 0, sdd = 0;
            rg2__bern(n, t, B, D, DD);
            double Bl[6] = {0}, Bll[6] = {0};
            if (n >= 2)
                rg2__bern(n - 1, t, Bl, NULL, NULL); /* n = 4: the cubic rg2__bern3 */
            if (n >= 3)
                rg2__bern(n - 2, t, Bll, NULL, NULL);
            for (int i = 0; i <= n; i++) {
                s += B[i];
                sd += D[i];
                sdd += DD[i];
                closed = fmax(closed, fabs(B[i] - binom(n, i) * pow(t, i) * pow(1 - t, n - i)));
                if (n >= 2) {
                    /* B'_i = n (B^{n-1}_{i-1} - B^{n-1}_i) */
                    double d = n * ((i > 0 ? Bl[i - 1] : 0) - (i < n ? Bl[i] : 0));
                    lowered = fmax(lowered, fabs(D[i] - d) / n);
                }
                if (n >= 3) {
                    /* B''_i = n (n-1) (B^{n-2}_{i-2} - 2 B^{n-2}_{i-1} + B^{n-2}_i) */
                    double d = (i >= 2 ? Bll[i - 2] : 0) - (i >= 1 && i - 1 <= n - 2 ? 2 * Bll[i - 1] : 0) +
                               (i <= n - 2 ? Bll[i] : 0);
                    lowered2 = fmax(lowered2, fabs(DD[i] - n * (n - 1) * d) / (n * (n - 1)));
                }
            }
            unity = fmax(unity, fabs(s - 1));
            dsum = fmax(dsum, fabs(sd));
            ddsum = fmax(ddsum, fabs(sdd));
            /* central differences (inside [0, 1]: one-sided steps are not needed away from the ends) */
            if (q > 0 && q < 40) {
                const double h = 1e-5;
                double Bp[6], Bm[6], Dp[6], Dm[6];
                rg2__bern(n, t + h, Bp, Dp, NULL);
                rg2__bern(n, t - h, Bm, Dm, NULL);
                for (int i = 0; i <= n; i++) {
                    fd1 = fmax(fd1, fabs((Bp[i] - Bm[i]) / (2 * h) - D[i]) / n);
                    fd2 = fmax(fd2, fabs((Dp[i] - Dm[i]) / (2 * h) - DD[i]) / (n * n));
                }
            }
        }
    printf("bases 1..5: unity %.1e, sum B' %.1e, sum B'' %.1e, closed form %.1e, B' vs lowered %.1e, "
           "B'' vs lowered %.1e, finite differences B' %.1e B'' %.1e\n",
           unity, dsum, ddsum, closed, lowered, lowered2, fd1, fd2);
    CHECK(unity <= 1e-15 && dsum <= 1e-14 && ddsum <= 1e-13, "partition of unity %.3g, derivative sums %.3g %.3g",
          unity, dsum, ddsum);
    CHECK(closed <= 4e-16, "closed form t^i (1-t)^(n-i) C(n,i): %.3g", closed);
    CHECK(lowered <= 1e-15 && lowered2 <= 1e-15, "derivatives from the lowered bases: %.3g, %.3g", lowered, lowered2);
    CHECK(fd1 <= 1e-9 && fd2 <= 1e-8, "derivatives vs central differences: %.3g, %.3g", fd1, fd2);
    /* the cubic is rg2__bern3 exactly */
    double B[4], D[4], DD[4], B3[4], D3[4], DD3[4];
    rg2__bern(3, 0.3, B, D, DD);
    rg2__bern3(0.3, B3, D3, DD3);
    CHECK(!memcmp(B, B3, sizeof B) && !memcmp(D, D3, sizeof D) && !memcmp(DD, DD3, sizeof DD),
          "degree 3 is rg2__bern3");
}

/* A random patch of degree (du, dv): points near a gently curved sheet of size ~10, weights in
 * [0.7, 1.4] (homogeneous h = w (x, y, z, 1)). */
static void random_xpatch(rg2t_rng *r, int du, int dv, rg2_xpatch *X)
{
    memset(X, 0, sizeof *X);
    X->du = du;
    X->dv = dv;
    for (int a = 0; a <= du; a++)
        for (int b = 0; b <= dv; b++) {
            double u = (double)a / du, v = (double)b / dv, w = rg2t_uniform(r, 0.7, 1.4);
            double p[3] = {10 * u + rg2t_uniform(r, -1, 1), 10 * v + rg2t_uniform(r, -1, 1),
                           3 * sin(2 * u + v) + rg2t_uniform(r, -1, 1)};
            for (int k = 0; k < 3; k++)
                X->h[a][b][k] = w * p[k];
            X->h[a][b][3] = w;
        }
}

static double dist3(const double *a, const double *b)
{
    return sqrt((a[0] - b[0]) * (a[0] - b[0]) + (a[1] - b[1]) * (a[1] - b[1]) + (a[2] - b[2]) * (a[2] - b[2]));
}

/* Largest differences of two evaluations: position and derivatives relative to the size L
 * (first derivatives ~L, second ~L), normal absolute, K and H relative to the curvature
 * scale max(|k1|, |k2|, 1 / L). */
typedef struct {
    double p, d1, d2, n, K, H;
} evdiff;

static void ev_compare(const rg2_eval *a, const rg2_eval *b, double L, evdiff *o)
{
    o->p = fmax(o->p, dist3(a->p, b->p) / L);
    o->d1 = fmax(o->d1, fmax(dist3(a->su, b->su), dist3(a->sv, b->sv)) / L);
    o->d2 = fmax(o->d2, fmax(dist3(a->suu, b->suu), fmax(dist3(a->suv, b->suv), dist3(a->svv, b->svv))) / L);
    o->n = fmax(o->n, dist3(a->n, b->n));
    double ks = fmax(fmax(fabs(a->k1), fabs(a->k2)), 1.0 / L);
    o->K = fmax(o->K, fabs(a->K - b->K) / (ks * ks));
    o->H = fmax(o->H, fabs(a->H - b->H) / ks);
}

/* rg2_xpatch_eval on a bi-3 patch in the general form equals rg2_patch_eval. */
static void bi3_agreement(void)
{
    rg2t_rng r;
    rg2t_seed(&r, 601);
    printf("bi-3 agreement seed 601\n");
    evdiff d = {0};
    double hdiff = 0;
    for (int trial = 0; trial < 6; trial++) {
        rg2_xpatch X, G;
        random_xpatch(&r, 3, 3, &X);
        rg2_patch P;
        for (int a = 0; a < 4; a++)
            for (int b = 0; b < 4; b++)
                memcpy(P.h[a][b], X.h[a][b], sizeof P.h[a][b]);
        rg2_xpatch_from_patch(&P, &G);
        CHECK(G.du == 3 && G.dv == 3 && !memcmp(G.h, X.h, sizeof G.h), "rg2_xpatch_from_patch copies the patch");
        for (int a = 0; a <= 16; a++)
            for (int b = 0; b <= 16; b++) {
                double u = a / 16.0, v = b / 16.0, H1[6][4], H2[6][4];
                rg2_eval e1, e2;
                rg2_patch_eval(&P, u, v, 2, &e1);
                rg2_xpatch_eval(&X, u, v, 2, &e2);
                ev_compare(&e1, &e2, 10.0, &d);
                rg2_patch_eval_h(&P, u, v, H1);
                rg2_xpatch_eval_h(&X, u, v, H2);
                for (int q = 0; q < 6; q++)
                    for (int k = 0; k < 4; k++)
                        hdiff = fmax(hdiff, fabs(H1[q][k] - H2[q][k]) / 10.0);
            }
    }
    printf("bi-3: xpatch vs patch eval: p %.1e, d1 %.1e, d2 %.1e, n %.1e, K %.1e, H %.1e, homogeneous %.1e\n", d.p,
           d.d1, d.d2, d.n, d.K, d.H, hdiff);
    CHECK(d.p <= 1e-15 && d.d1 <= 1e-15 && d.d2 <= 1e-15 && d.n <= 1e-15 && d.K <= 1e-15 && d.H <= 1e-15 &&
              hdiff <= 1e-15,
          "general evaluator = rg2_patch_eval on bi-3: p %.3g d1 %.3g d2 %.3g n %.3g K %.3g H %.3g h %.3g", d.p, d.d1,
          d.d2, d.n, d.K, d.H, hdiff);
}

/* Exact elevation: from every start degree (1..5)^2 to every target degree >= it, random
 * patches; the elevated patch is the same surface to rounding over 21 x 21 samples. */
static void elevation(void)
{
    rg2t_rng r;
    rg2t_seed(&r, 602);
    printf("elevation seed 602\n");
    evdiff worst = {0};
    int pairs = 0;
    for (int du = 1; du <= RG2_MAX_DEGREE; du++)
        for (int dv = 1; dv <= RG2_MAX_DEGREE; dv++) {
            rg2_xpatch X;
            random_xpatch(&r, du, dv, &X);
            for (int tu = du; tu <= RG2_MAX_DEGREE; tu++)
                for (int tv = dv; tv <= RG2_MAX_DEGREE; tv++) {
                    rg2_xpatch Y;
                    rg2_error err;
                    CHECK_OK(rg2_xpatch_elevate(&X, tu, tv, &Y, &err), &err);
                    CHECK(Y.du == tu && Y.dv == tv, "elevated degree (%d, %d), asked (%d, %d)", Y.du, Y.dv, tu, tv);
                    pairs++;
                    evdiff d = {0};
                    for (int a = 0; a <= 20; a++)
                        for (int b = 0; b <= 20; b++) {
                            rg2_eval e1, e2;
                            rg2_xpatch_eval(&X, a / 20.0, b / 20.0, 2, &e1);
                            rg2_xpatch_eval(&Y, a / 20.0, b / 20.0, 2, &e2);
                            ev_compare(&e1, &e2, 10.0, &d);
                        }
                    /* corners interpolate: the corner control points are kept exactly */
                    int corners = !memcmp(X.h[0][0], Y.h[0][0], sizeof(double[4])) &&
                                  !memcmp(X.h[du][dv], Y.h[tu][tv], sizeof(double[4]));
                    CHECK(corners, "(%d,%d) -> (%d,%d): corner control points kept", du, dv, tu, tv);
                    CHECK(d.p <= 2e-15 && d.n <= 1e-14 && d.K <= 3e-14 && d.H <= 3e-14,
                          "(%d,%d) -> (%d,%d): p %.3g n %.3g K %.3g H %.3g", du, dv, tu, tv, d.p, d.n, d.K, d.H);
                    worst.p = fmax(worst.p, d.p);
                    worst.d1 = fmax(worst.d1, d.d1);
                    worst.d2 = fmax(worst.d2, d.d2);
                    worst.n = fmax(worst.n, d.n);
                    worst.K = fmax(worst.K, d.K);
                    worst.H = fmax(worst.H, d.H);
                }
        }
    printf("elevation, %d (start, target) degree pairs, 441 samples each: p %.1e, d1 %.1e, d2 %.1e, n %.1e, "
           "K %.1e, H %.1e (relative)\n",
           pairs, worst.p, worst.d1, worst.d2, worst.n, worst.K, worst.H);
    /* step by step equals all at once, to rounding */
    rg2_xpatch X, A, B, C;
    rg2_error err;
    random_xpatch(&r, 3, 3, &X);
    CHECK_OK(rg2_xpatch_elevate(&X, 4, 3, &A, &err), &err);
    CHECK_OK(rg2_xpatch_elevate(&A, 5, 5, &B, &err), &err);
    CHECK_OK(rg2_xpatch_elevate(&X, 5, 5, &C, &err), &err);
    double step = 0;
    for (int a = 0; a <= 5; a++)
        for (int b = 0; b <= 5; b++)
            for (int k = 0; k < 4; k++)
                step = fmax(step, fabs(B.h[a][b][k] - C.h[a][b][k]) / 10.0);
    CHECK(step <= 1e-15, "elevation in steps vs at once: %.3g", step);
    /* the identity */
    CHECK_OK(rg2_xpatch_elevate(&X, 3, 3, &A, &err), &err);
    CHECK(!memcmp(&A, &X, sizeof A), "elevation to the same degree is the identity");
}

static void bad_degrees(void)
{
    rg2t_rng r;
    rg2t_seed(&r, 603);
    rg2_xpatch X, Y;
    rg2_error err;
    random_xpatch(&r, 4, 3, &X);
    static const int bad[][2] = {{3, 3}, {4, 2}, {6, 3}, {4, 6}, {0, 0}, {-1, 5}};
    for (int k = 0; k < 6; k++) {
        memset(&err, 0, sizeof err);
        rg2_status st = rg2_xpatch_elevate(&X, bad[k][0], bad[k][1], &Y, &err);
        char want[64];
        snprintf(want, sizeof want, "(4, 3) to (%d, %d)", bad[k][0], bad[k][1]);
        CHECK(st == RG2_EINVAL && strstr(err.msg, want), "elevate (4,3) to (%d,%d): %s, '%s'", bad[k][0], bad[k][1],
              rg2_status_str(st), err.msg);
    }
}

/* Patch (i, j) of s on an n x m per-patch grid (positions): the largest distance from
 * rg2_surface_eval at (a / (n - 1), b / (m - 1)), or -1 when the grid is refused (err says why). */
static double patch_grid_dev(const rg2_surface *s, int i, int j, int n, int m, rg2_error *err)
{
    double *pg = malloc(sizeof(double) * 3 * (size_t)n * (size_t)m), dev = -1.0;
    rg2_grid_out one = {.pos = pg};
    if (pg && rg2__surface_patch_grid(s, i, j, n, m, &one, err) == RG2_OK) {
        dev = 0.0;
        for (int a = 0; a < n; a++)
            for (int b = 0; b < m; b++) {
                rg2_eval e;
                rg2_surface_eval(s, i, j, (double)a / (n - 1), (double)b / (m - 1), 0, &e);
                dev = fmax(dev, dist3(pg + 3 * ((size_t)a * m + b), e.p));
            }
    }
    free(pg);
    return dev;
}

/* Surfaces holding elevated patches: accessors, copy, min weight; rg2_surface_grid and the
 * per-patch grid agree with rg2_surface_eval, the per-patch grid also at 2 and RG2_GRID_MAX
 * points per direction. */
static void surface_grids(void)
{
    rg2_surface s, x;
    rg2_error err;
    CHECK_OK(rg2t_torus(5.0, 2.0, 6, 7, NULL, &s, &err), &err);
    CHECK_OK(xmix_copy(&s, &x, &err), &err);
    int n_x = xmix_count(&x), du, dv;
    rg2_surface_degree(&x, &du, &dv);
    CHECK(n_x == 42 - 42 / 5 && du == 5 && dv == 5, "%d elevated patches, surface degree (%d, %d)", n_x, du, dv);
    rg2_surface_degree(&s, &du, &dv);
    CHECK(du == 3 && dv == 3, "bi-3 surface degree (%d, %d)", du, dv);
    /* patch_get: the general form of either kind */
    rg2_xpatch g;
    rg2_surface_patch_get(&x, 0, 0, &g);
    CHECK(g.du == 4 && g.dv == 3, "patch (0,0) of degree (%d, %d)", g.du, g.dv);
    rg2_surface_patch_get(&x, 0, 4, &g);
    CHECK(g.du == 3 && g.dv == 3 && !memcmp(g.h[1][2], rg2_surface_patch(&x, 0, 4)->h[1][2], sizeof(double[4])),
          "patch (0,4) bi-3 in general form");
    double w0 = rg2_surface_min_weight(&s), w1 = rg2_surface_min_weight(&x);
    CHECK(isfinite(w1) && w1 >= w0 - 1e-15 && w1 <= w0 + 0.2, "min weight %.17g (bi-3 %.17g)", w1, w0);
    rg2_surface c;
    CHECK_OK(rg2_surface_copy(&x, &c, &err), &err);
    CHECK(c.xp && c.xp != x.xp && !memcmp(c.xp, x.xp, 42 * sizeof *c.xp), "copy holds the higher-degree patches");
    rg2_surface_free(&c);

    enum { N = 9, M = 7 };
    size_t tot = (size_t)x.nu * x.nv * N * M;
    double *buf = calloc(tot, 23 * sizeof(double)); /* 7 vector arrays, K, H */
    rg2_grid_out go = {.pos = buf, .normal = buf + 3 * tot, .du = buf + 6 * tot, .dv = buf + 9 * tot,
                       .duu = buf + 12 * tot, .duv = buf + 15 * tot, .dvv = buf + 18 * tot,
                       .K = buf + 21 * tot, .H = buf + 22 * tot};
    CHECK_OK(rg2_surface_grid(&x, N, M, 1, &go, &err), &err);
    evdiff d = {0};
    double dp_patch = 0;
    int xbits = 0; /* higher-degree patch samples not bitwise equal to rg2_surface_eval */
    for (int i = 0; i < x.nu; i++)
        for (int j = 0; j < x.nv; j++) {
            double pg[3 * N * M], ng[3 * N * M];
            rg2_grid_out one = {.pos = pg, .normal = ng};
            CHECK_OK(rg2_surface_patch_grid(&x, i, j, N, M, &one, &err), &err); /* (the public call) */
            for (int a = 0; a < N; a++)
                for (int b = 0; b < M; b++) {
                    size_t q = ((size_t)(i * x.nv + j) * N + a) * M + b, l = (size_t)a * M + b;
                    rg2_eval e, gq;
                    rg2_surface_eval(&x, i, j, (double)a / (N - 1), (double)b / (M - 1), 2, &e);
                    memset(&gq, 0, sizeof gq);
                    memcpy(gq.p, go.pos + 3 * q, sizeof gq.p);
                    memcpy(gq.n, go.normal + 3 * q, sizeof gq.n);
                    memcpy(gq.su, go.du + 3 * q, sizeof gq.su);
                    memcpy(gq.sv, go.dv + 3 * q, sizeof gq.sv);
                    memcpy(gq.suu, go.duu + 3 * q, sizeof gq.suu);
                    memcpy(gq.suv, go.duv + 3 * q, sizeof gq.suv);
                    memcpy(gq.svv, go.dvv + 3 * q, sizeof gq.svv);
                    gq.K = go.K[q];
                    gq.H = go.H[q];
                    /* the separable grid of higher-degree patches sums in rg2__eval_hom's order */
                    if (rg2_surface_xpatch(&x, i, j) &&
                        (memcmp(gq.p, e.p, sizeof e.p) || memcmp(gq.n, e.n, sizeof e.n) ||
                         memcmp(gq.su, e.su, sizeof e.su) || memcmp(gq.sv, e.sv, sizeof e.sv) ||
                         memcmp(gq.suu, e.suu, sizeof e.suu) || memcmp(gq.suv, e.suv, sizeof e.suv) ||
                         memcmp(gq.svv, e.svv, sizeof e.svv) || memcmp(&gq.K, &e.K, sizeof e.K) ||
                         memcmp(&gq.H, &e.H, sizeof e.H)))
                        xbits++;
                    gq.k1 = e.k1;
                    gq.k2 = e.k2;
                    ev_compare(&e, &gq, 14.0, &d);
                    dp_patch = fmax(dp_patch, fmax(dist3(pg + 3 * l, e.p) / 14.0, dist3(ng + 3 * l, e.n)));
                }
        }
    printf("surface grid with %d of 42 patches elevated vs rg2_surface_eval: p %.1e, d1 %.1e, d2 %.1e, n %.1e, "
           "K %.1e, H %.1e; per-patch grid %.1e\n",
           n_x, d.p, d.d1, d.d2, d.n, d.K, d.H, dp_patch);
    CHECK(d.p <= 1e-14 && d.d1 <= 1e-14 && d.d2 <= 1e-13 && d.n <= 1e-14 && d.K <= 1e-12 && d.H <= 1e-12,
          "surface grid = rg2_surface_eval: p %.3g d1 %.3g d2 %.3g n %.3g K %.3g H %.3g", d.p, d.d1, d.d2, d.n, d.K,
          d.H);
    CHECK(dp_patch <= 1e-14, "per-patch grid = rg2_surface_eval: %.3g", dp_patch);
    CHECK(xbits == 0, "%d samples of higher-degree patches differ from rg2_xpatch_eval in some bit", xbits);
    /* threads split the higher-degree patches too: the same bits */
    double *buf2 = calloc(tot, 23 * sizeof(double));
    rg2_grid_out g2 = {.pos = buf2, .normal = buf2 + 3 * tot, .du = buf2 + 6 * tot, .dv = buf2 + 9 * tot,
                       .duu = buf2 + 12 * tot, .duv = buf2 + 15 * tot, .dvv = buf2 + 18 * tot,
                       .K = buf2 + 21 * tot, .H = buf2 + 22 * tot};
    CHECK_OK(rg2_surface_grid(&x, N, M, 3, &g2, &err), &err);
    CHECK(!memcmp(buf, buf2, tot * 23 * sizeof(double)), "mixed-degree surface grid: 1 and 3 threads differ");
    /* positions alone (their own loop) and with normals only: the same bits */
    rg2_grid_out g0 = {.pos = buf2}, g1 = {.pos = buf2 + 3 * tot, .normal = buf2 + 6 * tot};
    CHECK_OK(rg2_surface_grid(&x, N, M, 2, &g0, &err), &err);
    CHECK_OK(rg2_surface_grid(&x, N, M, 1, &g1, &err), &err);
    CHECK(!memcmp(buf2, buf, tot * 3 * sizeof(double)) && !memcmp(buf2 + 3 * tot, buf, tot * 3 * sizeof(double)) &&
              !memcmp(buf2 + 6 * tot, go.normal, tot * 3 * sizeof(double)),
          "mixed-degree surface grid: positions / normals depend on the other outputs requested");
    free(buf2);
    double p1[3 * 4];
    rg2_grid_out bad = {.pos = p1};
    /* the edges of the guard, in either direction: 2 and RG2_GRID_MAX points are grids (of the
     * surface's points); 1 point, RG2_GRID_MAX + 1 points and no position array are refused,
     * the message naming the patch's degrees */
    static const int edge[4][2] = {{2, 5}, {5, 2}, {RG2_GRID_MAX, 2}, {2, RG2_GRID_MAX}};
    for (int k = 0; k < 4; k++) {
        double dev = patch_grid_dev(&x, 0, 0, edge[k][0], edge[k][1], &err);
        CHECK(dev >= 0 && dev <= 14.0 * 1e-14, "%d x %d grid on a higher-degree patch: %.3g from rg2_surface_eval (%s)",
              edge[k][0], edge[k][1], dev, dev < 0 ? err.msg : "");
    }
    static const int refused[5][2] = {{1, 4}, {4, 1}, {RG2_GRID_MAX + 1, 2}, {2, RG2_GRID_MAX + 1}, {4, 4}};
    for (int k = 0; k < 5; k++) {
        rg2_grid_out no_pos = {.normal = p1}, *o = k < 4 ? &bad : &no_pos;
        rg2_status want = k == 2 || k == 3 ? RG2_ELIMIT : RG2_EINVAL;
        CHECK(rg2__surface_patch_grid(&x, 0, 0, refused[k][0], refused[k][1], o, &err) == want &&
                  strstr(err.msg, "degree (4, 3)"),
              "%d x %d grid%s on a higher-degree patch: %s", refused[k][0], refused[k][1],
              k < 4 ? "" : " without positions", err.msg);
    }
    /* the cause named, as rg2_patch_grid names it (it said "4 x 4 points, or no position array" for
     * both), and a NULL surface named as such (it said "(0 x 0 patches)") */
    static const char *const named[3] = {"grid: patch (0, 0) of degree (4, 3): no output arrays (out is NULL)",
                                         "grid: patch (0, 0) of degree (4, 3): the position array (out->pos) is NULL",
                                         "grid: no surface (s is NULL)"};
    rg2_grid_out no_pos = {.normal = p1};
    for (int k = 0; k < 3; k++)
        CHECK((k < 2 ? rg2_surface_patch_grid(&x, 0, 0, 4, 4, k ? &no_pos : NULL, &err)
                     : rg2_surface_patch_grid(NULL, 0, 0, 4, 4, &bad, &err)) == RG2_EINVAL &&
                  !strcmp(err.msg, named[k]),
              "want '%s': %s", named[k], err.msg);
    /* without an error report (as the tessellation and the renderer call it): the status alone (it
     * read the report it had not written) */
    CHECK(rg2_surface_patch_grid(&x, 0, 0, 1, 4, &bad, NULL) == RG2_EINVAL, "1 x 4 grid, no error report");
    /* the public call refuses a patch outside the surface, naming it and the surface's patches */
    static const int outside[4][2] = {{-1, 0}, {0, -1}, {6, 0}, {0, 7}};
    for (int k = 0; k < 4; k++) {
        char want[96];
        snprintf(want, sizeof want, "grid: patch (%d, %d) is not a patch of the surface (6 x 7 patches)", outside[k][0],
                 outside[k][1]);
        CHECK(x.nu == 6 && x.nv == 7 &&
                  rg2_surface_patch_grid(&x, outside[k][0], outside[k][1], 4, 4, &bad, &err) == RG2_EINVAL &&
                  !strcmp(err.msg, want),
              "patch (%d, %d) of a 6 x 7 surface: %s", outside[k][0], outside[k][1], err.msg);
    }
    free(buf);
    rg2_surface_free(&x);
    rg2_surface_free(&s);
}

/* Collapsed sides of any degree: a patch with a side on one point stays collapsed there when
 * elevated, its other sides do not; the collapse tolerance counts the elevated patches; a side
 * whose points lie exactly tol apart collapses at tol. */
static void collapsed_sides(void)
{
    rg2t_rng r;
    rg2t_seed(&r, 604);
    rg2_xpatch X, Y;
    rg2_error err;
    random_xpatch(&r, 3, 3, &X);
    for (int a = 0; a <= 3; a++) /* side 0 (v = 0) on the point (1, 2, 3), weights kept */
        for (int k = 0; k < 3; k++)
            X.h[a][0][k] = X.h[a][0][3] * (k + 1);
    int ok = 1;
    for (int tu = 3; tu <= 5; tu++)
        for (int tv = 3; tv <= 5; tv++) {
            CHECK_OK(rg2_xpatch_elevate(&X, tu, tv, &Y, &err), &err);
            ok &= rg2__xpatch_side_collapsed(&Y, 0, 1e-12);
            for (int side = 1; side < 4; side++)
                ok &= !rg2__xpatch_side_collapsed(&Y, side, 1e-12);
        }
    CHECK(ok, "collapsed side 0 found on every elevation, no other side");
    /* "within tol" includes tol: side 0 of weight 2 on (1, 2, 3) but one point 0.25 off in x
     * (all exact in binary) collapses at tol 0.25, not at 0.125; on one point, at tol 0 */
    random_xpatch(&r, 3, 3, &X);
    for (int a = 0; a <= 3; a++)
        for (int k = 0; k < 4; k++)
            X.h[a][0][k] = 2.0 * (k < 3 ? k + 1 : 1);
    int at0 = rg2__xpatch_side_collapsed(&X, 0, 0.0);
    X.h[2][0][0] = 2.0 * 1.25;
    int at_tol = rg2__xpatch_side_collapsed(&X, 0, 0.25), below = rg2__xpatch_side_collapsed(&X, 0, 0.125);
    CHECK(at0 && at_tol && !below, "side within tol: coincident at tol 0 %d, 0.25 off at tol 0.25 %d, at 0.125 %d", at0,
          at_tol, below);
    rg2_surface s, x;
    CHECK_OK(rg2t_torus(5.0, 2.0, 5, 5, NULL, &s, &err), &err);
    CHECK_OK(rg2_surface_copy(&s, &x, &err), &err);
    CHECK_OK(rg2t_elevate_some(&x, 5, 5, 1, 0, &err), &err); /* every patch */
    double t0 = rg2__collapse_tol(&s), t1 = rg2__collapse_tol(&x);
    CHECK(t1 > 0.8 * t0 && t1 <= t0, "collapse tolerance of the all-elevated torus %.3g (bi-3 %.3g)", t1, t0);
    int none = 0;
    for (int i = 0; i < 5; i++)
        for (int j = 0; j < 5; j++)
            for (int side = 0; side < 4; side++)
                none += rg2__surface_side_collapsed(&x, i, j, side, t1);
    CHECK(none == 0, "no side of the torus collapses (%d found)", none);
    rg2_surface_free(&x);
    rg2_surface_free(&s);
}

int main(void)
{
    bases();
    bi3_agreement();
    elevation();
    bad_degrees();
    surface_grids();
    collapsed_sides();
    return rg2t_done("test_xpatch");
}
