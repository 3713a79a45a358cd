/* test_nurbs.c -- bi-cubic NURBS import against an independent Cox-de Boor evaluation:
 * random non-uniform knot vectors (clamped, unclamped, partly clamped), random weights and
 * points; knot intervals of extreme ratios (e^16); G2 across the seams; errors for repeated
 * interior knots and bad input. */
#include "expect_err.h"
#include "harness.h"

#include <float.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#define MAXN 12

/* Cox-de Boor: the cubic basis functions N_{l-3..l} at the point u = U_l + t (U_{l+1} - U_l) of
 * span l (0 <= t <= 1), by the recursion N_{i,0} = [U_i <= u < U_{i+1}], N_{i,p} = (u - U_i) /
 * (U_{i+p} - U_i) N_{i,p-1} + (U_{i+p+1} - u) / (U_{i+p+1} - U_{i+1}) N_{i+1,p-1} over the non-zero
 * ones. The distances to u are formed from the local parameter, u - U_i = (U_l - U_i) + t d and
 * U_j - u = (U_j - U_{l+1}) + (1 - t) d (d = U_{l+1} - U_l, sums of non-negative terms), never
 * from u rounded to a double: next to knots of magnitude |U|, that rounding moves u by eps |U|,
 * which on a span much shorter than |U| is a large step in t (extreme_knot_ratios). */
static void cox_de_boor(const double *U, int l, double t, double N[4])
{
    double B[4][5]; /* B[p][k]: N_{l-p+k, p}, k = 0..p */
    double d = U[l + 1] - U[l];
    memset(B, 0, sizeof B);
    B[0][0] = 1.0;
    for (int p = 1; p <= 3; p++)
        for (int k = 0; k <= p; k++) {
            int i = l - p + k;
            double left = 0.0, right = 0.0;
            if (k >= 1 && U[i + p] > U[i]) /* N_{i,p-1} = B[p-1][k-1] */
                left = ((U[l] - U[i]) + t * d) / (U[i + p] - U[i]) * B[p - 1][k - 1];
            if (k <= p - 1 && U[i + p + 1] > U[i + 1]) /* N_{i+1,p-1} = B[p-1][k] */
                right = ((U[i + p + 1] - U[l + 1]) + (1.0 - t) * d) / (U[i + p + 1] - U[i + 1]) * B[p - 1][k];
            B[p][k] = left + right;
        }
    memcpy(N, B[3], sizeof(double) * 4);
}

/* The NURBS point at local parameters (tu, tv) of span (lu, lv). */
static void nurbs_point(const rg2_nurbs *nb, int lu, int lv, double tu, double tv, double out[3])
{
    double Nu[4], Nv[4], acc[4] = {0, 0, 0, 0};
    cox_de_boor(nb->knots_u, lu, tu, Nu);
    cox_de_boor(nb->knots_v, lv, tv, Nv);
    for (int a = 0; a < 4; a++)
        for (int b = 0; b < 4; b++) {
            int i = lu - 3 + a, j = lv - 3 + b;
            size_t k = (size_t)i * (size_t)nb->nv + (size_t)j;
            double w = nb->weights ? nb->weights[k] : 1.0, c = Nu[a] * Nv[b] * w;
            for (int d = 0; d < 3; d++)
                acc[d] += c * nb->points[3 * k + d];
            acc[3] += c;
        }
    for (int d = 0; d < 3; d++)
        out[d] = acc[d] / acc[3];
}

/* style: 0 clamped, 1 unclamped, 2 clamped at the start only, 3 partly clamped (2 equal) */
static void random_knots(rg2t_rng *r, int n, int style, double *U)
{
    double t = rg2t_uniform(r, -3, 3);
    for (int k = 0; k < n + 4; k++) {
        U[k] = t;
        t += rg2t_uniform(r, 0.2, 1.8);
    }
    if (style == 0 || style == 2)
        U[0] = U[1] = U[2] = U[3];
    if (style == 0)
        U[n + 1] = U[n + 2] = U[n + 3] = U[n];
    if (style == 3)
        U[1] = U[2], U[n + 2] = U[n + 1];
}

/* The JSON spec of nb (%.17g: every double round-trips) read by rg2_nurbs_parse gives the mesh
 * of rg2_nurbs_mesh bit for bit. */
static void parse_same(const rg2_nurbs *nb, const rg2_mesh *m, int trial)
{
    size_t np = (size_t)nb->nu * (size_t)nb->nv, cap = np * 160 + 4096, n = 0;
    char *t = malloc(cap);
    n += (size_t)snprintf(t + n, cap - n, "{\"nu\": %d, \"nv\": %d, \"points\": [", nb->nu, nb->nv);
    for (size_t k = 0; k < np; k++)
        n += (size_t)snprintf(t + n, cap - n, "%s[%.17g, %.17g, %.17g]", k ? ", " : "", nb->points[3 * k],
                              nb->points[3 * k + 1], nb->points[3 * k + 2]);
    n += (size_t)snprintf(t + n, cap - n, "]");
    if (nb->weights) {
        n += (size_t)snprintf(t + n, cap - n, ", \"weights\": [");
        for (size_t k = 0; k < np; k++)
            n += (size_t)snprintf(t + n, cap - n, "%s%.17g", k ? ", " : "", nb->weights[k]);
        n += (size_t)snprintf(t + n, cap - n, "]");
    }
    for (int d = 0; d < 2; d++) {
        const double *K = d ? nb->knots_v : nb->knots_u;
        n += (size_t)snprintf(t + n, cap - n, ", \"knots_%c\": [", d ? 'v' : 'u');
        for (int k = 0; k < (d ? nb->nv : nb->nu) + 4; k++)
            n += (size_t)snprintf(t + n, cap - n, "%s%.17g", k ? ", " : "", K[k]);
        n += (size_t)snprintf(t + n, cap - n, "]");
    }
    snprintf(t + n, cap - n, "}");
    rg2_mesh q;
    rg2_error err;
    CHECK_OK(rg2_nurbs_parse(t, strlen(t), "spec", &q, &err), &err);
    int same = q.nu == m->nu && q.nv == m->nv && !memcmp(q.p, m->p, np * 4 * sizeof(double));
    for (int d = 0; d < 2 && same; d++) {
        const rg2_scalars *a = d ? &q.sv : &q.su, *b = d ? &m->sv : &m->su;
        same = a->n == b->n && a->closed == b->closed &&
               !memcmp(a->w, b->w, (size_t)rg2_scalars_num_w(a) * sizeof(double)) &&
               !memcmp(a->b, b->b, (size_t)a->n * sizeof(double)) && !memcmp(a->g, b->g, (size_t)a->n * sizeof(double));
    }
    CHECK(same, "trial %d: the parsed spec gives another mesh", trial);
    rg2_mesh_free(&q);
    if (trial == 0) { /* a cut text names where it ends */
        rg2_status st = rg2_nurbs_parse(t, strlen(t) / 2, "spec", &q, &err);
        CHECK(st == RG2_EPARSE && strstr(err.msg, "spec:1:") && strstr(err.msg, "malformed JSON"), "cut text: %s",
              err.msg);
        /* no text: the output is zeroed as on every other failure (it was left as it was, and a
         * caller's rg2_mesh_free of its uninitialised struct freed garbage) */
        memset(&q, 0x55, sizeof q);
        st = rg2_nurbs_parse(NULL, 0, "spec", &q, &err);
        CHECK(st == RG2_EINVAL && !q.p && !q.nu && !q.su.w, "no text: %s, output %p %d", err.msg, (void *)q.p, q.nu);
        /* each NULL argument named (all three gave "nurbs: no text, name or output"); a NULL name
         * is the default "nurbs", as rg2_design_parse's is "design" */
        CHECK(!strcmp(err.msg, "spec: no text (NULL text)"), "no text: %s", err.msg);
        st = rg2_nurbs_parse(t, strlen(t), "spec", NULL, &err);
        CHECK(st == RG2_EINVAL && !strcmp(err.msg, "nurbs: NULL output mesh"), "no output: %s", err.msg);
        st = rg2_nurbs_parse(t, strlen(t), NULL, &q, &err);
        CHECK(st == RG2_OK && q.nu > 0, "NULL name: %s %s", rg2_status_str(st), st ? err.msg : "");
        rg2_mesh_free(&q);
        st = rg2_nurbs_parse(t, strlen(t) / 2, NULL, &q, &err);
        CHECK(st == RG2_EPARSE && !strncmp(err.msg, "nurbs:1:", 8), "NULL name, cut text: %s", err.msg);
    }
    free(t);
}

static void random_nurbs(void)
{
    rg2t_rng r;
    uint64_t seed = 4242;
    rg2t_seed(&r, seed);
    printf("random NURBS, seed %llu\n", (unsigned long long)seed);
    double worst = 0.0, wang = 0.0, wcurv = 0.0, wpos = 0.0;
    long samples = 0;
    for (int trial = 0; trial < 24; trial++) {
        int nu = rg2t_int(&r, 4, MAXN), nv = rg2t_int(&r, 4, MAXN);
        double P[MAXN * MAXN * 3], W[MAXN * MAXN], U[MAXN + 4], V[MAXN + 4];
        for (int k = 0; k < nu * nv; k++) {
            for (int d = 0; d < 3; d++)
                P[3 * k + d] = rg2t_uniform(&r, -1, 1) + (d == 0 ? k / nv : d == 1 ? k % nv : 0);
            W[k] = rg2t_uniform(&r, 0.3, 3.0);
        }
        random_knots(&r, nu, trial % 4, U);
        random_knots(&r, nv, (trial / 4) % 4, V);
        rg2_nurbs nb = {nu, nv, P, trial % 5 == 4 ? NULL : W, U, V};
        rg2_mesh m;
        rg2_surface s;
        rg2_error err;
        rg2_status st = rg2_nurbs_mesh(&nb, &m, &err);
        CHECK(st == RG2_OK, "trial %d: %s", trial, err.msg);
        if (st)
            continue;
        parse_same(&nb, &m, trial);
        CHECK_OK(rg2_surface_build(&m, &s, &err), &err);
        CHECK(s.nu == nu - 3 && s.nv == nv - 3, "trial %d: %d x %d patches", trial, s.nu, s.nv);
        double L = rg2t_surface_scale(&s);
        for (int i = 0; i < s.nu; i++)
            for (int j = 0; j < s.nv; j++)
                for (int a = 0; a <= 8; a++)
                    for (int b = 0; b <= 8; b++) {
                        double tu = a / 8.0, tv = b / 8.0, q[3];
                        nurbs_point(&nb, i + 3, j + 3, tu, tv, q);
                        rg2_eval e;
                        rg2_patch_eval(rg2_surface_patch(&s, i, j), tu, tv, 0, &e);
                        double d = sqrt((q[0] - e.p[0]) * (q[0] - e.p[0]) + (q[1] - e.p[1]) * (q[1] - e.p[1]) +
                                        (q[2] - e.p[2]) * (q[2] - e.p[2])) / L;
                        if (!(d <= worst)) worst = d;
                        samples++;
                    }
        /* clamped ends interpolate the corner control point */
        if (trial % 4 == 0 && (trial / 4) % 4 == 0) {
            rg2_eval e;
            rg2_patch_eval(rg2_surface_patch(&s, 0, 0), 0, 0, 0, &e);
            double d = fabs(e.p[0] - P[0]) + fabs(e.p[1] - P[1]) + fabs(e.p[2] - P[2]);
            CHECK(d <= 1e-13 * L, "clamped corner interpolated: %.3g", d);
        }
        rg2t_seams g;
        rg2t_surface_seams(&s, 8, &g);
        wang = fmax(wang, g.angle);
        wcurv = fmax(wcurv, g.curv);
        wpos = fmax(wpos, g.pos);
        rg2_surface_free(&s);
        rg2_mesh_free(&m);
    }
    printf("  %ld samples: distance from Cox-de Boor %.2e (relative to size); seams: position %.2e, "
           "angle %.2e, curvature %.2e\n",
           samples, worst, wpos, wang, wcurv);
    CHECK(samples >= 10000, "%ld samples", samples);
    CHECK(worst <= 1e-13, "NURBS import vs Cox-de Boor: %.3g", worst);
    CHECK(wpos <= 1e-14 && wang <= 1e-12 && wcurv <= 1e-10, "NURBS seams: %.3g %.3g %.3g", wpos, wang,
          wcurv);
}


/* Largest distance (max norm) of the built surface from Cox-de Boor over n + 1 x n + 1 samples
 * per patch, relative to the scale max(largest coordinate, bounding-box diagonal) of the
 * control points; *corner: the same at the four domain corners only. Infinity if the surface
 * does not build. */
static double surface_error(const rg2_nurbs *nb, const rg2_surface *s, int n, double *corner);
static double import_error(const rg2_nurbs *nb, const rg2_mesh *m, int n, double *corner)
{
    rg2_surface s;
    rg2_error err;
    *corner = INFINITY;
    if (rg2_surface_build(m, &s, &err))
        return INFINITY;
    double worst = surface_error(nb, &s, n, corner);
    rg2_surface_free(&s);
    return worst;
}

/* The same for a surface built already (patch (i, j) over span (i + 3, j + 3)). */
static double surface_error(const rg2_nurbs *nb, const rg2_surface *s, int n, double *corner)
{
    int np = nb->nu * nb->nv;
    double X = 0.0, lo[3] = {INFINITY, INFINITY, INFINITY}, hi[3] = {-INFINITY, -INFINITY, -INFINITY};
    for (int k = 0; k < 3 * np; k++) {
        X = fmax(X, fabs(nb->points[k]));
        lo[k % 3] = fmin(lo[k % 3], nb->points[k]);
        hi[k % 3] = fmax(hi[k % 3], nb->points[k]);
    }
    double L = fmax(X, sqrt((hi[0] - lo[0]) * (hi[0] - lo[0]) + (hi[1] - lo[1]) * (hi[1] - lo[1]) +
                            (hi[2] - lo[2]) * (hi[2] - lo[2])));
    double worst = 0.0;
    *corner = 0.0;
    for (int i = 0; i < s->nu; i++)
        for (int j = 0; j < s->nv; j++)
            for (int a = 0; a <= n; a++)
                for (int b = 0; b <= n; b++) {
                    double tu = (double)a / n, tv = (double)b / n, q[3], p[3];
                    nurbs_point(nb, i + 3, j + 3, tu, tv, q);
                    rg2_patch_point(rg2_surface_patch(s, i, j), tu, tv, p);
                    double d = fmax(fabs(p[0] - q[0]), fmax(fabs(p[1] - q[1]), fabs(p[2] - q[2]))) / L;
                    if (!(d <= worst))
                        worst = d;
                    int at_corner = ((a == 0 && i == 0) || (a == n && i == s->nu - 1)) &&
                                    ((b == 0 && j == 0) || (b == n && j == s->nv - 1));
                    if (at_corner && !(d <= *corner))
                        *corner = d;
                }
    return worst;
}

/* A refusal names the smallest and the largest weight among the 4 x 4 de Boor points of the patch
 * it names ("weights [a][b] = x and [c][d] = y near a clamped end (patch (i, j))"): x and y are
 * those weights (to the message's 6 digits) and their extremes over the block. */
static int names_extreme_weights(const rg2_nurbs *nb, const char *msg)
{
    const char *at = strstr(msg, "weights [");
    int a, b, c, e, i, j;
    double x, y;
    if (!at || sscanf(at, "weights [%d][%d] = %lg and [%d][%d] = %lg near a clamped end (patch (%d, %d))", &a, &b,
                      &x, &c, &e, &y, &i, &j) != 8)
        return 0;
    if (i < 0 || j < 0 || i + 3 >= nb->nu || j + 3 >= nb->nv || a < i || a > i + 3 || c < i || c > i + 3 || b < j ||
        b > j + 3 || e < j || e > j + 3)
        return 0;
    double lo = INFINITY, hi = -INFINITY;
    for (int p = i; p < i + 4; p++)
        for (int q = j; q < j + 4; q++) {
            lo = fmin(lo, nb->weights[p * nb->nv + q]);
            hi = fmax(hi, nb->weights[p * nb->nv + q]);
        }
    double wa = nb->weights[a * nb->nv + b], wc = nb->weights[c * nb->nv + e];
    return wa == lo && wc == hi && fabs(x - wa) <= 1e-5 * wa && fabs(y - wc) <= 1e-5 * wc;
}

/* Weights that differ much near a clamped end (the numeric review's 5 x 5 NURBS: points
 * (i, j, ((7i + 3j) mod 5) 0.3), weights r where i + j is odd and 1/r where even, and weights
 * r^((i+j)/8)): every NURBS rg2_nurbs_mesh accepts is the NURBS to 1e-10 of its scale (dense
 * samples against Cox-de Boor); the others are refused with RG2_EDOMAIN naming two weights.
 * Unclamped knots need no extrapolation: accepted and exact for every ratio. Before the
 * refusal, r = 1e3 was 8e-10 off, 1e7 0.04, and from 1e10 patch weights were negative. */
static void clamped_weights(void)
{
    double P[75], W[25];
    double Uc[9] = {0, 0, 0, 0, 1, 2, 2, 2, 2}, Uf[9] = {-3, -2, -1, 0, 1, 2, 3, 4, 5};
    for (int i = 0; i < 5; i++)
        for (int j = 0; j < 5; j++) {
            P[(i * 5 + j) * 3] = i;
            P[(i * 5 + j) * 3 + 1] = j;
            P[(i * 5 + j) * 3 + 2] = ((i * 7 + j * 3) % 5) * 0.3;
        }
    printf("weights near clamped ends (5 x 5, error relative to the scale; - = refused)\n");
    for (int style = 0; style < 2; style++) {
        double first_refused = INFINITY;
        printf("  %s:", style ? "r^((i+j)/8)" : "alternating r, 1/r");
        for (int e = 0; e <= 8; e++) {
            double r = pow(10.0, e);
            for (int k = 0; k < 25; k++)
                W[k] = style ? pow(r, (k / 5 + k % 5) / 8.0) : ((k / 5 + k % 5) % 2 ? r : 1.0 / r);
            for (int clamped = 1; clamped >= 0; clamped--) {
                rg2_nurbs nb = {5, 5, P, W, clamped ? Uc : Uf, clamped ? Uc : Uf};
                rg2_mesh m;
                rg2_error err;
                rg2_status st = rg2_nurbs_mesh(&nb, &m, &err);
                if (st) {
                    CHECK(clamped, "unclamped, r = %g refused: %s", r, err.msg);
                    CHECK(st == RG2_EDOMAIN && names_extreme_weights(&nb, err.msg) && strstr(err.msg, "clamped end"),
                          "r = %g: %s %s", r, rg2_status_str(st), err.msg);
                    if (clamped && e <= 1)
                        CHECK(0, "r = %g refused: %s", r, err.msg);
                    first_refused = fmin(first_refused, r);
                    if (clamped)
                        printf(" 1e%d -", e);
                    continue;
                }
                double corner, d = import_error(&nb, &m, 32, &corner);
                rg2_mesh_free(&m);
                if (clamped)
                    printf(" 1e%d %.1e", e, d);
                CHECK(d <= (clamped ? 1e-10 : 1e-13), "%s r = %g: %.3g from Cox-de Boor",
                      clamped ? "clamped" : "unclamped", r, d);
                if (clamped) /* a clamped corner is the corner control point */
                    CHECK(corner <= 1e-10, "r = %g: clamped corner %.3g off", r, corner);
                CHECK(!(r > first_refused && clamped), "r = %g accepted, %g refused", r, first_refused);
            }
        }
        printf("\n");
        if (style) /* gradual growth cancels nothing: accepted and exact up to a ratio of 1e8 */
            CHECK(first_refused == INFINITY, "growing weights refused from r = %g", first_refused);
        else
            CHECK(first_refused < INFINITY, "alternating weights: no ratio refused");
    }

    /* only some ends clamped. One direction clamped (u, v, or the start of u alone): the
     * extrapolated points of one direction cancel little, every ratio accepted and exact. A
     * corner clamped in both directions (the starts of u and v; all of u and the start of v; the
     * end of u and the start of v):
     * refused from some ratio, as when every end is clamped, and the accepted ones are the
     * NURBS to 1e-10 of its scale (the bound ran only where all four ends were clamped: these
     * came back accepted at every ratio) */
    double Us[9] = {0, 0, 0, 0, 1, 2, 3, 4, 5}, Ue[9] = {0, 1, 2, 3, 4, 5, 5, 5, 5};
    const double *part[6][2] = {{Uc, Uf}, {Uf, Uc}, {Us, Uf}, {Us, Us}, {Uc, Us}, {Ue, Us}};
    const char *pname[6] = {"u clamped", "v clamped", "the start of u clamped", "the starts of u and v clamped",
                            "u and the start of v clamped", "the end of u and the start of v clamped"};
    for (int c = 0; c < 6; c++) {
        int refused = 0;
        double worst = 0.0;
        for (int e = 0; e <= 8; e++) {
            double r = pow(10.0, e);
            for (int k = 0; k < 25; k++)
                W[k] = (k / 5 + k % 5) % 2 ? r : 1.0 / r;
            rg2_nurbs nb = {5, 5, P, W, part[c][0], part[c][1]};
            rg2_mesh m;
            rg2_error err;
            rg2_status st = rg2_nurbs_mesh(&nb, &m, &err);
            if (st) {
                CHECK(st == RG2_EDOMAIN && names_extreme_weights(&nb, err.msg) && e > 1, "%s, r = %g: %s %s", pname[c],
                      r, rg2_status_str(st), err.msg);
                refused++;
                continue;
            }
            double corner, d = import_error(&nb, &m, 32, &corner);
            rg2_mesh_free(&m);
            worst = fmax(worst, d);
            CHECK(d <= (c < 3 ? 1e-14 : 1e-10), "%s, alternating r = %g: accepted, %.3g from Cox-de Boor", pname[c],
                  r, d);
        }
        CHECK(c < 3 ? refused == 0 : refused > 0, "%s: %d of 9 ratios up to 1e8 refused (worst accepted %.3g)",
              pname[c], refused, worst);
        printf("  %s: %d of 9 ratios refused, the accepted ones %.1e from Cox-de Boor\n", pname[c], refused, worst);
    }

    /* random clamped NURBS with weights e^U(-L, L): accepted ones are accurate */
    rg2t_rng rng;
    rg2t_seed(&rng, 77);
    int accepted = 0, refused = 0;
    double worst = 0.0;
    for (int trial = 0; trial < 80; trial++) {
        int nu = rg2t_int(&rng, 4, 7), nv = rg2t_int(&rng, 4, 7);
        double L = (trial % 4 == 0) ? 0.5 : (trial % 4 == 1) ? 3.0 : (trial % 4 == 2) ? 8.0 : 20.0;
        double Q[7 * 7 * 3], Wr[7 * 7], U[11], V[11];
        for (int k = 0; k < nu * nv; k++) {
            Q[3 * k] = k / nv + rg2t_uniform(&rng, -0.5, 0.5);
            Q[3 * k + 1] = k % nv + rg2t_uniform(&rng, -0.5, 0.5);
            Q[3 * k + 2] = rg2t_uniform(&rng, -1, 1);
            Wr[k] = exp(rg2t_uniform(&rng, -L, L));
        }
        random_knots(&rng, nu, 0, U);
        random_knots(&rng, nv, 0, V);
        rg2_nurbs nb = {nu, nv, Q, Wr, U, V};
        rg2_mesh m;
        rg2_error err;
        rg2_status st = rg2_nurbs_mesh(&nb, &m, &err);
        if (st) {
            CHECK(st == RG2_EDOMAIN && names_extreme_weights(&nb, err.msg), "trial %d: %s", trial, err.msg);
            CHECK(L > 0.5, "trial %d: weights within e^0.5 refused: %s", trial, err.msg);
            refused++;
            continue;
        }
        double corner, d = import_error(&nb, &m, 16, &corner);
        rg2_mesh_free(&m);
        worst = fmax(worst, d);
        accepted++;
    }
    printf("  random weights e^U(-L, L), L = 0.5 .. 20: %d accepted (worst %.2e of the scale), %d refused\n",
           accepted, worst, refused);
    CHECK(worst <= 1e-10, "accepted random clamped NURBS %.3g from Cox-de Boor", worst);
    CHECK(accepted >= 20 && refused >= 20, "%d accepted, %d refused", accepted, refused);
}

/* The textbook evaluation that the references above replace: Cox-de Boor at the double
 * u = U_l + t (U_{l+1} - U_l), distances to u formed from u. Only to show what it loses. */
static void textbook_point(const rg2_nurbs *nb, int lu, int lv, double tu, double tv, double out[3])
{
    const double *K[2] = {nb->knots_u, nb->knots_v};
    int l[2] = {lu, lv};
    double t[2] = {tu, tv}, N[2][4], acc[4] = {0, 0, 0, 0};
    for (int e = 0; e < 2; e++) {
        const double *U = K[e];
        double u = U[l[e]] + t[e] * (U[l[e] + 1] - U[l[e]]), B[4][5];
        memset(B, 0, sizeof B);
        B[0][0] = 1.0;
        for (int p = 1; p <= 3; p++)
            for (int k = 0; k <= p; k++) {
                int i = l[e] - p + k;
                double left = 0.0, right = 0.0;
                if (k >= 1 && U[i + p] > U[i])
                    left = (u - U[i]) / (U[i + p] - U[i]) * B[p - 1][k - 1];
                if (k <= p - 1 && U[i + p + 1] > U[i + 1])
                    right = (U[i + p + 1] - u) / (U[i + p + 1] - U[i + 1]) * B[p - 1][k];
                B[p][k] = left + right;
            }
        memcpy(N[e], B[3], sizeof N[e]);
    }
    for (int a = 0; a < 4; a++)
        for (int b = 0; b < 4; b++) {
            size_t k = (size_t)(lu - 3 + a) * (size_t)nb->nv + (size_t)(lv - 3 + b);
            double w = nb->weights ? nb->weights[k] : 1.0, c = N[0][a] * N[1][b] * w;
            for (int d = 0; d < 3; d++)
                acc[d] += c * nb->points[3 * k + d];
            acc[3] += c;
        }
    for (int d = 0; d < 3; d++)
        out[d] = acc[d] / acc[3];
}

#if LDBL_MANT_DIG >= 64
/* The NURBS point in long double (11 more bits), u formed in long double: checks the reference. */
static void long_double_point(const rg2_nurbs *nb, int lu, int lv, double tu, double tv, double out[3])
{
    const double *K[2] = {nb->knots_u, nb->knots_v};
    int l[2] = {lu, lv};
    double t[2] = {tu, tv};
    long double N[2][4], acc[4] = {0, 0, 0, 0};
    for (int e = 0; e < 2; e++) {
        const double *U = K[e];
        long double u = U[l[e]] + (long double)t[e] * ((long double)U[l[e] + 1] - U[l[e]]), B[4][5];
        memset(B, 0, sizeof B);
        B[0][0] = 1.0L;
        for (int p = 1; p <= 3; p++)
            for (int k = 0; k <= p; k++) {
                int i = l[e] - p + k;
                long double left = 0.0L, right = 0.0L;
                if (k >= 1 && U[i + p] > U[i])
                    left = (u - U[i]) / ((long double)U[i + p] - U[i]) * B[p - 1][k - 1];
                if (k <= p - 1 && U[i + p + 1] > U[i + 1])
                    right = ((long double)U[i + p + 1] - u) / ((long double)U[i + p + 1] - U[i + 1]) * B[p - 1][k];
                B[p][k] = left + right;
            }
        for (int k = 0; k < 4; k++)
            N[e][k] = B[3][k];
    }
    for (int a = 0; a < 4; a++)
        for (int b = 0; b < 4; b++) {
            size_t k = (size_t)(lu - 3 + a) * (size_t)nb->nv + (size_t)(lv - 3 + b);
            long double w = nb->weights ? nb->weights[k] : 1.0, c = N[0][a] * N[1][b] * w;
            for (int d = 0; d < 3; d++)
                acc[d] += c * nb->points[3 * k + d];
            acc[3] += c;
        }
    for (int d = 0; d < 3; d++)
        out[d] = (double)(acc[d] / acc[3]);
}
#endif

/*
 * Knot intervals of extreme ratios: 6 x 6 points uniform in [0, 1]^3, intervals e^(S U(0, 1))
 * (neighbours up to e^S apart), S = 4, 8, 12, 16, clamped and unclamped, unit and random
 * weights. The import is the NURBS to rounding (a few eps of the size) at every ratio, against
 * the reference with distances from the local parameter. The textbook Cox-de Boor (u rounded
 * to a double first) is 3.2e-11 off at S = 16, 1e-12 at 12, 5e-14 at 8 (200 random unclamped
 * surfaces; clamped 7.9e-10, 1.6e-11, 3.6e-13): its u lies eps |U| away from the point, next
 * to knots up to |U| ~ 1e8 on spans of length ~1. Measured with __float128 (the B-spline at the
 * exact u, rg2's patches evaluated exactly from their doubles), for S = 16: rg2's patch data
 * 2.4e-16 (clamped 4.2e-16) of the size, rg2_patch_point 2.7e-16, this reference 5.7e-16; the
 * textbook one's error is all the B-spline's move from the exact u to the rounded double.
 */
static void extreme_knot_ratios(void)
{
    rg2t_rng r;
    uint64_t seed = 1616;
    rg2t_seed(&r, seed);
    printf("extreme knot ratios (6 x 6, intervals e^(S U(0,1))), seed %llu\n", (unsigned long long)seed);
    double textbook16 = 0.0;
    for (int S = 4; S <= 16; S += 4) {
        double worst = 0.0, wtext = 0.0, wref = 0.0;
        for (int trial = 0; trial < 16; trial++) {
            enum { n = 6 };
            double P[n * n * 3], W[n * n], U[n + 4], V[n + 4];
            int clamped = trial % 2, weighted = trial % 4 == 2; /* weights: unclamped knots only */
            for (int k = 0; k < n * n; k++) {
                for (int d = 0; d < 3; d++)
                    P[3 * k + d] = rg2t_uniform(&r, 0, 1);
                W[k] = exp(rg2t_uniform(&r, -2, 2));
            }
            for (int e = 0; e < 2; e++) {
                double *K = e ? V : U, x = 0.0;
                for (int k = 0; k < n + 4; k++) {
                    K[k] = x;
                    x += exp(S * rg2t_uniform(&r, 0, 1));
                }
                if (clamped)
                    K[0] = K[1] = K[2] = K[3], K[n + 1] = K[n + 2] = K[n + 3] = K[n];
            }
            rg2_nurbs nb = {n, n, P, weighted ? W : NULL, U, V};
            rg2_mesh m;
            rg2_surface s;
            rg2_error err;
            CHECK_OK(rg2_nurbs_mesh(&nb, &m, &err), &err);
            CHECK_OK(rg2_surface_build(&m, &s, &err), &err);
            double L = 0.0, lo[3] = {1, 1, 1}, hi[3] = {0, 0, 0};
            for (int k = 0; k < 3 * n * n; k++) {
                L = fmax(L, fabs(P[k]));
                lo[k % 3] = fmin(lo[k % 3], P[k]);
                hi[k % 3] = fmax(hi[k % 3], P[k]);
            }
            L = fmax(L, sqrt((hi[0] - lo[0]) * (hi[0] - lo[0]) + (hi[1] - lo[1]) * (hi[1] - lo[1]) +
                             (hi[2] - lo[2]) * (hi[2] - lo[2])));
            for (int i = 0; i < s.nu; i++)
                for (int j = 0; j < s.nv; j++)
                    for (int a = 0; a <= 16; a++)
                        for (int b = 0; b <= 16; b++) {
                            double tu = a / 16.0, tv = b / 16.0, p[3], q[3], t[3];
                            rg2_patch_point(rg2_surface_patch(&s, i, j), tu, tv, p);
                            nurbs_point(&nb, i + 3, j + 3, tu, tv, q);
                            textbook_point(&nb, i + 3, j + 3, tu, tv, t);
                            for (int d = 0; d < 3; d++) {
                                worst = fmax(worst, fabs(p[d] - q[d]) / L);
                                wtext = fmax(wtext, fabs(p[d] - t[d]) / L);
                            }
#if LDBL_MANT_DIG >= 64
                            double x[3];
                            long_double_point(&nb, i + 3, j + 3, tu, tv, x);
                            for (int d = 0; d < 3; d++)
                                wref = fmax(wref, fabs(q[d] - x[d]) / L);
#endif
                        }
            rg2_surface_free(&s);
            rg2_mesh_free(&m);
        }
        printf("  S = %2d: import %.2e of the size from the reference (textbook Cox-de Boor: %.2e; "
               "reference vs long double: %.2e)\n",
               S, worst, wtext, wref);
        CHECK(worst <= 2e-15, "knot intervals e^%d apart: import %.3g from Cox-de Boor", S, worst);
        CHECK(wref <= 1e-15, "knot intervals e^%d apart: reference %.3g from long double", S, wref);
        if (S == 16)
            textbook16 = wtext;
    }
    /* the case is ill-conditioned for the textbook evaluation: the test would catch a lost digit */
    CHECK(textbook16 >= 1e-13, "textbook Cox-de Boor at e^16 only %.3g off", textbook16);
}

/* Build the surface of the 5 x 4 NURBS with knots_u U (knots_v 0..7) into *s; 0 on success. */
static int build_5x4(const double *U, rg2_surface *s)
{
    static double pts[5 * 4 * 3];
    for (int i = 0; i < 5; i++)
        for (int j = 0; j < 4; j++) {
            double *p = pts + 3 * (i * 4 + j);
            p[0] = i, p[1] = j, p[2] = (i * j) % 3;
        }
    static const double V[8] = {0, 1, 2, 3, 4, 5, 6, 7};
    rg2_nurbs nb = {5, 4, pts, NULL, U, V};
    rg2_mesh m;
    rg2_error err;
    rg2_status st = rg2_nurbs_mesh(&nb, &m, &err);
    CHECK(st == RG2_OK, "knots_u from %g to %g: %s", U[0], U[8], err.msg);
    if (st)
        return 1;
    st = rg2_surface_build(&m, s, &err);
    rg2_mesh_free(&m);
    CHECK_OK(st, &err);
    return st != RG2_OK;
}

/* The largest distance between two surfaces of the same patch layout at 5 x 5 points a patch. */
static double surface_distance(const rg2_surface *a, const rg2_surface *b)
{
    double md = 0.0;
    for (int i = 0; i < a->nu; i++)
        for (int j = 0; j < a->nv; j++)
            for (int x = 0; x <= 4; x++)
                for (int y = 0; y <= 4; y++) {
                    rg2_eval e1, e2;
                    rg2_surface_eval(a, i, j, 0.25 * x, 0.25 * y, 0, &e1);
                    rg2_surface_eval(b, i, j, 0.25 * x, 0.25 * y, 0, &e2);
                    for (int k = 0; k < 3; k++)
                        md = fmax(md, fabs(e1.p[k] - e2.p[k]));
                }
    return md;
}

/* The 5 x 4 NURBS with knots_u U builds the surface of the one with knots_u Uref to 1e-14. */
static void same_surface(const double *U, const double *Uref, const char *what)
{
    rg2_surface a, b;
    if (build_5x4(U, &a))
        return;
    if (!build_5x4(Uref, &b)) {
        double d = surface_distance(&a, &b);
        CHECK(d <= 1e-14, "%s: %.3g apart", what, d);
        rg2_surface_free(&b);
    }
    rg2_surface_free(&a);
}

/* Knots of magnitude near the double range whose used intervals are finite: the construction
 * reads knots_u[1..n+2] (and the end intervals continued past a clamped end, twice), never
 * knots_u[0] or knots_u[n+3] nor a third continued interval. rg2 refused the first two (RG2_EDOMAIN
 * "knots_u spans ...") for an interval it does not read: knots_u[0..1] of 1.9e308, and the
 * third interval continued past either clamped end, 1.5e308 to 2e308. */
static void knots_near_double_range(void)
{
    const double Uf[9] = {-1.7e308, 2e307, 3e307, 4e307, 5e307, 6e307, 7e307, 8e307, 9e307};
    const double Ufr[9] = {-1, 2, 3, 4, 5, 6, 7, 8, 9};
    const double Uc[9] = {-5e307, -5e307, -5e307, -5e307, 0, 5e307, 5e307, 5e307, 5e307};
    const double Ucr[9] = {-1, -1, -1, -1, 0, 1, 1, 1, 1};
    same_surface(Uf, Ufr, "knots_u[0] = -1.7e308, then 2e307 .. 9e307, against -1, 2 .. 9");
    same_surface(Uc, Ucr, "clamped knots_u +-5e307 against +-1");
    /* clamped at the start, where the blossoms that unclamp it divide by knots_u[5] - knots_u[2]
     * = 1.88e308, beyond the double range: the coefficient was NaN, and the NURBS refused as if
     * its rounding could move the surface "by nan" */
    const double Ub[9] = {-1.79e307, -1.79e307, -1.79e307, -1.79e307, 5.37e307, 1.7e308, 1.72e308, 1.74e308, 1.76e308};
    double Ubq[9];
    for (int k = 0; k < 9; k++)
        Ubq[k] = 0.25 * Ub[k];
    same_surface(Ub, Ubq, "a blossom over 1.88e308 of knots against the knots / 4");
    /* clamped at the start with an end interval of 1.08e308: twice it overflows, but the knot it
     * continues to, 5.4e307 - 2.16e308 = -1.62e308, does not (refused as reaching "-inf") */
    const double Ud[9] = {5.4e307, 5.4e307, 5.4e307, 5.4e307, 1.62e308, 1.65e308, 1.7e308, 1.75e308, 1.78e308};
    double Udq[9];
    for (int k = 0; k < 9; k++)
        Udq[k] = 0.25 * Ud[k];
    same_surface(Ud, Udq, "an end interval of 1.08e308 continued twice against the knots / 4");
    /* and at the bottom: knots whose intervals are subnormal (2^-1060 and 2^-1070 times the
     * reference's, exact) build the same surface; a fuzz input with a clamped span of 1.7e-317
     * found the fuzz harness's reference de Boor losing 1e-7 there, not the library */
    double Us[9], Ucs[9];
    for (int k = 0; k < 9; k++)
        Us[k] = 0x1p-1070 * Ufr[k], Ucs[k] = 0x1p-1060 * Ucr[k];
    same_surface(Us, Ufr, "knots_u of subnormal intervals (2^-1070 x -1, 2 .. 9) against -1, 2 .. 9");
    same_surface(Ucs, Ucr, "clamped knots_u 2^-1060 x (-1, 0, 1) against -1, 0, 1");
}

static void errors(void)
{
    double P[6 * 5 * 3], W[30];
    for (int k = 0; k < 90; k++)
        P[k] = k * 0.1;
    for (int k = 0; k < 30; k++)
        W[k] = 1.0;
    double U[10] = {0, 0, 0, 0, 1, 2, 3, 3, 3, 3}, V[9] = {0, 1, 2, 3, 4, 5, 6, 7, 8};
    rg2_nurbs nb = {6, 5, P, W, U, V};
    rg2_mesh m;
    rg2_error err;
    CHECK_OK(rg2_nurbs_mesh(&nb, &m, &err), &err);
    rg2_mesh_free(&m);
    U[5] = 1.0;
    expect_err(rg2_nurbs_mesh(&nb, &m, &err), RG2_EDOMAIN, &err, "interior knot knots_u[5] = 1 is repeated",
               "repeated interior knot");
    U[5] = 0.5;
    expect_err(rg2_nurbs_mesh(&nb, &m, &err), RG2_EDOMAIN, &err, "knots_u[5] = 0.5 is smaller", "decreasing knot");
    U[5] = 2.0;
    U[4] = 0.0;
    expect_err(rg2_nurbs_mesh(&nb, &m, &err), RG2_EDOMAIN, &err, "zero length", "empty first span");
    U[4] = 1.0;
    W[7] = 0.0;
    expect_err(rg2_nurbs_mesh(&nb, &m, &err), RG2_EWEIGHT, &err, "weight [1][2]", "zero weight");
    W[7] = 1.0;
    P[5] = NAN;
    expect_err(rg2_nurbs_mesh(&nb, &m, &err), RG2_ENONFINITE, &err, "control point [0][1]", "NaN point");
    P[5] = 0.5;
    V[8] = INFINITY;
    expect_err(rg2_nurbs_mesh(&nb, &m, &err), RG2_ENONFINITE, &err, "knots_v[8]", "inf knot");
    V[8] = 8;
    /* knots whose intervals leave the double range, named by the knot vector and the knots: the
     * end interval continued past a clamped end reaches -inf (refused as "knots: knot 0 is not
     * finite"), an interval of the knots themselves, and intervals 1e-300 and 1 give K = inf
     * (taken into the mesh's scalars) */
    double Uw[10] = {-1e308, -1e308, -1e308, -1e308, -5e307, 5e307, 1e308, 1e308, 1e308, 1e308};
    nb.knots_u = Uw;
    expect_err(rg2_nurbs_mesh(&nb, &m, &err), RG2_EDOMAIN, &err,
               "nurbs: the end interval knots_u[3..4] = [-1e+308, -5e+307], continued past the clamped start "
               "as rg2 does to unclamp it, reaches knots_u[3] - 2 (knots_u[4] - knots_u[3]) = -inf",
               "knots continued past the clamped start beyond the double range");
    double Uh[10] = {0, 1, 2, 3, 4, 8e307, 1.6e308, 1.6e308, 1.6e308, 1.6e308};
    nb.knots_u = Uh;
    expect_err(rg2_nurbs_mesh(&nb, &m, &err), RG2_EDOMAIN, &err,
               "nurbs: the end interval knots_u[5..6] = [8e+307, 1.6e+308], continued past the clamped end "
               "as rg2 does to unclamp it, reaches knots_u[6] + 2 (knots_u[6] - knots_u[5]) = inf",
               "knots continued past the clamped end beyond the double range");
    double Ui[10] = {-1.7e308, -1.6e308, -1.5e308, -1.4e308, -1e308, 1e308, 1.1e308, 1.2e308, 1.3e308, 1.4e308};
    nb.knots_u = Ui;
    expect_err(rg2_nurbs_mesh(&nb, &m, &err), RG2_EDOMAIN, &err,
               "nurbs: the interval knots_u[4..5] = [-1e+308, 1e+308] is longer than the double range",
               "a knot interval beyond the double range");
    double Vr[9] = {0, 1e-300, 2e-300, 3e-300, 1, 2, 3, 4, 5};
    nb.knots_u = U;
    nb.knots_v = Vr;
    expect_err(rg2_nurbs_mesh(&nb, &m, &err), RG2_EDOMAIN, &err,
               "nurbs: knots_v: the knot intervals knots_v[2..3] = [2e-300, 3e-300] and knots_v[3..4] = [3e-300, 1] "
               "give b = 1e+300, g = 0, K = inf: K is out of the double range",
               "knot intervals 1e-300 and 1");
    CHECK(!m.p, "a mesh left after the error");
    nb.knots_v = V;
    /* too few points in either direction, the other having enough: named by the NURBS check (a
     * later check of the knots' scalars refused them too, with another message and, for a
     * negative count, reading outside the knots) */
    nb.nv = 3;
    expect_err(rg2_nurbs_mesh(&nb, &m, &err), RG2_EINVAL, &err,
               "nurbs: 6 x 3 control points; a bi-cubic NURBS needs at least 4", "too few points in v");
    nb.nu = 3, nb.nv = 5;
    expect_err(rg2_nurbs_mesh(&nb, &m, &err), RG2_EINVAL, &err,
               "nurbs: 3 x 5 control points; a bi-cubic NURBS needs at least 4", "too few points in u");
    nb.nu = 6, nb.nv = -1;
    expect_err(rg2_nurbs_mesh(&nb, &m, &err), RG2_EINVAL, &err, "nurbs: 6 x -1 control points",
               "a negative count");
    nb.nv = 5;
    nb.knots_v = NULL;
    expect_err(rg2_nurbs_mesh(&nb, &m, &err), RG2_EINVAL, &err, "missing", "no knots");
    /* RG2_MAX_POINTS (4,000,000) control points per direction and in total: 2001 x 2001 (4,004,001,
     * each direction far within it) is refused before a point is read */
    enum { BIG = 2001 };
    double *Pb = calloc((size_t)BIG * BIG * 3, sizeof(double)), *Kb = malloc((BIG + 4) * sizeof(double));
    CHECK(Pb && Kb, "out of memory");
    if (Pb && Kb) {
        for (int k = 0; k < BIG + 4; k++)
            Kb[k] = k;
        rg2_nurbs big = {BIG, BIG, Pb, NULL, Kb, Kb};
        expect_err(rg2_nurbs_mesh(&big, &m, &err), RG2_ELIMIT, &err,
                   "nurbs: 2001 x 2001 control points exceeds the limit 4000000", "4004001 control points");
        CHECK(!m.p, "a mesh left after the error");
    }
    free(Pb);
    free(Kb);
}

/* A clamped NURBS whose end line is one point p (a pole), its weights alternating 1 and r along
 * that line: in exact arithmetic the patches' side there is p at every control point, but the
 * construction forms it from the extrapolated end points, whose rounding spread its points h / w
 * (the 6 x 5 NURBS below: 1.7 to 6.5 roundings of the size at r = 32, 11 to 37 at 200, 116 to 135
 * at 1000). A design's output makes that side p (each point h_w p, keeping its weight), at any of
 * the four ends, through transpose, reverse, cut and transform; every other control point is the
 * construction's, bit for bit, and a line one point only to rounding (a point one ulp off) is left
 * as the construction makes it.
 * The surface stays the NURBS (Cox-de Boor at 17 x 17 samples a patch) and G2 (rg2_check). With
 * the side as the construction makes it 31 checks fail: 11 at the four ends (r = 32 .. 1000), 16
 * through the operations, 4 on the translated pole. */
#define PNU 6
#define PNV 5
static const double pole_p[3] = {0.3, -0.7, 1.1};

/* The pole NURBS at side `side` (0 v = 0, 1 u = 1, 2 v = 1, 3 u = 0): a fan about p, weights 1, r,
 * 1, r ... along the pole line and 1 .. 1.5 elsewhere. var 1: the line's point 1 moved one ulp in
 * x; var 2: the same pole line with the weights r, 1, r, ..., the other lines turned by 0.7 rad about
 * p and 1.1 times as far, their weights shifted. */
static void pole_nurbs(int side, double r, int var, double *P, double *W)
{
    int along_v = side == 0 || side == 2, other = var == 2;
    for (int i = 0; i < PNU; i++)
        for (int j = 0; j < PNV; j++) {
            int a = along_v ? j : i, k = along_v ? i : j, n = along_v ? PNV : PNU;
            int rho = side == 0 || side == 3 ? a : n - 1 - a; /* lines away from the pole */
            double th = 0.4 + 1.1 * k + 0.7 * other, sc = other ? 0.88 : 0.8, *q = P + 3 * (i * PNV + j);
            q[0] = pole_p[0] + sc * rho * cos(th);
            q[1] = pole_p[1] + sc * rho * sin(th);
            q[2] = pole_p[2] + 0.3 * rho * rho + 0.1 * k * rho;
            W[i * PNV + j] = rho ? 1.0 + 0.25 * ((i + 2 * j + other) % 3) : (k + other) % 2 ? r : 1.0;
            if (!rho && var == 1 && k == 1)
                q[0] = nextafter(q[0], 2.0);
        }
}

/* The design entry "name": {"nurbs": ...} of nb written at t + n (room for cap bytes): the new n. */
static size_t nurbs_entry(char *t, size_t n, size_t cap, const char *name, const rg2_nurbs *nb)
{
    n += (size_t)snprintf(t + n, cap - n, "\"%s\": {\"nurbs\": {\"nu\": %d, \"nv\": %d, \"points\": [", name,
                          nb->nu, nb->nv);
    for (int k = 0; k < nb->nu * nb->nv; k++)
        n += (size_t)snprintf(t + n, cap - n, "%s[%.17g, %.17g, %.17g]", k ? ", " : "", nb->points[3 * k],
                              nb->points[3 * k + 1], nb->points[3 * k + 2]);
    n += (size_t)snprintf(t + n, cap - n, "], \"weights\": [");
    for (int k = 0; k < nb->nu * nb->nv; k++)
        n += (size_t)snprintf(t + n, cap - n, "%s%.17g", k ? ", " : "", nb->weights[k]);
    for (int d = 0; d < 2; d++) {
        n += (size_t)snprintf(t + n, cap - n, "], \"knots_%c\": [", d ? 'v' : 'u');
        for (int k = 0; k < (d ? nb->nv : nb->nu) + 4; k++)
            n += (size_t)snprintf(t + n, cap - n, "%s%.17g", k ? ", " : "", (d ? nb->knots_v : nb->knots_u)[k]);
    }
    return n + (size_t)snprintf(t + n, cap - n, "]}}");
}

/* The design of nb ("n") with the output `out` (after the meshes in `more`). */
static rg2_design *pole_design(const rg2_nurbs *nb, const char *more, const char *out, rg2_error *err)
{
    size_t cap = 32768, n = 0;
    char *t = malloc(cap);
    n += (size_t)snprintf(t + n, cap - n, "{\"shapes\": {}, \"meshes\": {");
    n = nurbs_entry(t, n, cap, "n", nb);
    snprintf(t + n, cap - n, "%s}, \"output\": [\"%s\"]}", more, out);
    rg2_design *d = NULL;
    if (rg2_design_parse(t, strlen(t), "pole", &d, err))
        d = NULL;
    free(t);
    return d;
}

/* Control point t (0..3) of the side `side` of s on the k-th patch along it. */
static const double *side_h(const rg2_surface *s, int side, int k, int t)
{
    int along_v = side == 0 || side == 2;
    int i = along_v ? k : side == 1 ? s->nu - 1 : 0, j = along_v ? (side == 2 ? s->nv - 1 : 0) : k;
    const rg2_patch *P = rg2_surface_patch(s, i, j);
    return along_v ? P->h[t][side == 2 ? 3 : 0] : P->h[side == 1 ? 3 : 0][t];
}

/* The largest distance of the points h / w on side `side` of s, on the patches k0 <= k < k1 along
 * it, from ref (NULL: the first of them), relative to size. */
static double side_spread_at(const rg2_surface *s, int side, int k0, int k1, double size, const double *ref)
{
    double x0[3] = {0, 0, 0}, worst = 0.0;
    for (int k = k0; k < k1; k++) {
        for (int t = 0; t < 4; t++) {
            const double *h = side_h(s, side, k, t);
            double x[3] = {h[0] / h[3], h[1] / h[3], h[2] / h[3]};
            if (k == k0 && !t)
                memcpy(x0, ref ? ref : x, sizeof x);
            worst = fmax(worst, sqrt((x[0] - x0[0]) * (x[0] - x0[0]) + (x[1] - x0[1]) * (x[1] - x0[1]) +
                                     (x[2] - x0[2]) * (x[2] - x0[2])));
        }
    }
    return worst / size;
}

/* side_spread_at over the whole side. */
static double side_spread(const rg2_surface *s, int side, double size, const double *ref)
{
    return side_spread_at(s, side, 0, side == 0 || side == 2 ? s->nu : s->nv, size, ref);
}

/* Control points of a and b (equal counts) that differ, off the sides in the bit mask `sides` (bits
 * as the sides: 0 none excepted) or in their weights; *moved: the largest move of those sides'
 * points h / w (relative to size). */
static int pole_diffs(const rg2_surface *a, const rg2_surface *b, unsigned sides, double size, double *moved)
{
    int diff = 0;
    *moved = 0.0;
    for (int i = 0; i < a->nu; i++)
        for (int j = 0; j < a->nv; j++)
            for (int r = 0; r < 4; r++)
                for (int t = 0; t < 4; t++) {
                    const double *p = rg2_surface_patch(a, i, j)->h[r][t], *q = rg2_surface_patch(b, i, j)->h[r][t];
                    int on = (sides & 1u && j == 0 && t == 0) || (sides & 4u && j == a->nv - 1 && t == 3) ||
                             (sides & 8u && i == 0 && r == 0) || (sides & 2u && i == a->nu - 1 && r == 3);
                    diff += on ? p[3] != q[3] : !!memcmp(p, q, 4 * sizeof(double));
                    for (int d = 0; on && d < 3; d++)
                        *moved = fmax(*moved, fabs(p[d] / p[3] - q[d] / q[3]) / size);
                }
    return diff;
}

static void pole_rows(void)
{
    static const double ratios[4] = {1, 32, 200, 1000};
    double U[PNU + 4] = {0, 0, 0, 0, 0.7, 1.9, 3, 3, 3, 3}, V[PNV + 4] = {0, 0, 0, 0, 1.2, 2, 2, 2, 2};
    double P[3 * PNU * PNV], W[PNU * PNV];
    rg2_nurbs nb = {PNU, PNV, P, W, U, V};
    rg2_check_opts o;
    rg2_check_opts_default(&o);
    o.threads = 1;
    double worst_spread = 0.0, worst_moved = 0.0, worst_err = 0.0, g[3] = {0, 0, 0};
    for (int side = 0; side < 4; side++)
        for (int q = 0; q < 4; q++) {
            double r = ratios[q];
            rg2_error err;
            rg2_mesh m;
            rg2_surface plain;
            pole_nurbs(side, r, 0, P, W);
            double size = 0.0, lo[3] = {INFINITY, INFINITY, INFINITY}, hi[3] = {-INFINITY, -INFINITY, -INFINITY};
            for (int k = 0; k < 3 * PNU * PNV; k++)
                lo[k % 3] = fmin(lo[k % 3], P[k]), hi[k % 3] = fmax(hi[k % 3], P[k]);
            size = sqrt((hi[0] - lo[0]) * (hi[0] - lo[0]) + (hi[1] - lo[1]) * (hi[1] - lo[1]) +
                        (hi[2] - lo[2]) * (hi[2] - lo[2]));
            rg2_design *d = pole_design(&nb, "", "n", &err);
            CHECK(d != NULL, "side %d, r = %g: %s", side, r, err.msg);
            if (!d)
                continue;
            CHECK_OK(rg2_nurbs_mesh(&nb, &m, &err), &err);
            CHECK_OK(rg2_surface_build(&m, &plain, &err), &err);
            const rg2_surface *s = rg2_design_surface(d, 0);
            double spread = side_spread(s, side, size, pole_p), before = side_spread(&plain, side, size, NULL);
            rg2_surface ns; /* the C caller's way to the same surface, pole included */
            CHECK_OK(rg2_nurbs_surface(&nb, &ns, &err), &err);
            CHECK(ns.nu == s->nu && ns.nv == s->nv && !memcmp(ns.patch, s->patch, (size_t)s->nu * (size_t)s->nv * sizeof *s->patch),
                  "side %d, r = %g: rg2_nurbs_surface's patches differ from the design's (the pole side %.3g roundings "
                  "from the pole)", side, r, side_spread(&ns, side, size, NULL) / DBL_EPSILON);
            rg2_surface_free(&ns);
            double moved, corner;
            int diff = pole_diffs(s, &plain, 1u << side, size, &moved);
            double e = surface_error(&nb, s, 16, &corner);
            printf("  pole at side %d, weights 1 and %-4g: the side %.3g roundings of the size from the pole (the "
                   "construction's spread %.3g), moved %.3g; Cox-de Boor %.2g\n",
                   side, r, spread / DBL_EPSILON, before / DBL_EPSILON, moved / DBL_EPSILON, e);
            CHECK(spread <= 2 * DBL_EPSILON, "side %d, r = %g: the pole side lies up to %.3g roundings of the size "
                  "from the pole", side, r, spread / DBL_EPSILON);
            CHECK(diff == 0, "side %d, r = %g: %d control values off the pole side or weights changed", side, r, diff);
            CHECK(e <= 1e-12, "side %d, r = %g: %.3g from Cox-de Boor", side, r, e);
            rg2_check_report rep;
            CHECK_OK(rg2_check(s, 1, NULL, NULL, 0, &o, &rep, &err), &err);
            CHECK(rep.pole_samples > 0 && rep.unmeasured == 0 && rep.folds == 0 && rep.singular == 0 &&
                      rep.g0.value <= 1e-15 && rep.g1.value <= 1e-11 && rep.g2.value <= 1e-10 &&
                      !(rep.g1_pole.value > 1) && !(rep.g2_pole.value > 1),
                  "side %d, r = %g: %d pole samples, %d unmeasured, %d folds, %d singular, G0 %.3g, G1 %.3g, G2 %.3g, "
                  "near the pole %.3g %.3g of their limits",
                  side, r, rep.pole_samples, rep.unmeasured, rep.folds, rep.singular, rep.g0.value, rep.g1.value,
                  rep.g2.value, rep.g1_pole.value, rep.g2_pole.value);
            worst_spread = fmax(worst_spread, spread), worst_moved = fmax(worst_moved, moved);
            worst_err = fmax(worst_err, e);
            g[0] = fmax(g[0], rep.g0.value), g[1] = fmax(g[1], rep.g1.value), g[2] = fmax(g[2], rep.g2.value);
            rg2_check_report_free(&rep);
            rg2_design_free(d);
            if (r == 1000) { /* through transpose, reverse, cut and transform; not a line one ulp off */
                const char *more[5] = {
                    ", \"o\": {\"transpose\": \"n\"}", ", \"o\": {\"reverse\": \"n\", \"dir\": \"u\"}",
                    /* (the cut across the pole line keeps it) */
                    side % 2 ? ", \"a\": {\"reverse\": \"n\", \"dir\": \"v\"}, \"o\": {\"cut\": \"a\", \"v\": [1, 4]}"
                             : ", \"a\": {\"reverse\": \"n\", \"dir\": \"v\"}, \"o\": {\"cut\": \"a\", \"u\": [1, 5]}",
                    ", \"o\": {\"transform\": \"n\", \"translate\": [1, 2, 3]}", ""};
                for (int v = 0; v < 5; v++) {
                    if (v == 4)
                        pole_nurbs(side, r, 1, P, W);
                    d = pole_design(&nb, more[v], v == 4 ? "n" : "o", &err);
                    CHECK(d != NULL, "side %d, variant %d: %s", side, v, err.msg);
                    if (!d)
                        continue;
                    s = rg2_design_surface(d, 0);
                    int to = v == 0 ? 3 - side
                             : (v == 1 && side % 2) || (v == 2 && !(side % 2)) ? side ^ 2
                                                                               : side;
                    double sp = side_spread(s, to, size, NULL);
                    if (v < 4)
                        CHECK(sp <= 2 * DBL_EPSILON, "side %d, variant %d: side %d spreads %.3g roundings", side, v,
                              to, sp / DBL_EPSILON);
                    if (v == 3) { /* the translated pole */
                        const rg2_patch *Pp =
                            rg2_surface_patch(s, side == 1 ? s->nu - 1 : 0, side == 2 ? s->nv - 1 : 0);
                        const double *h = Pp->h[side == 1 ? 3 : 0][side == 2 ? 3 : 0];
                        double dx = fabs(h[0] / h[3] - (pole_p[0] + 1)) + fabs(h[1] / h[3] - (pole_p[1] + 2)) +
                                    fabs(h[2] / h[3] - (pole_p[2] + 3));
                        CHECK(dx <= 16 * DBL_EPSILON, "side %d: the translated pole is %.3g off", side, dx);
                    }
                    if (v == 4) { /* one ulp off: the construction's patches as they are */
                        rg2_surface b;
                        rg2_mesh_free(&m);
                        CHECK_OK(rg2_nurbs_mesh(&nb, &m, &err), &err);
                        CHECK_OK(rg2_surface_build(&m, &b, &err), &err);
                        double mv;
                        CHECK(pole_diffs(s, &b, 0, size, &mv) == 0 && sp > 2 * DBL_EPSILON,
                              "side %d: a line one ulp off is not the construction's (spread %.3g roundings)", side,
                              sp / DBL_EPSILON);
                        rg2_surface_free(&b);
                    }
                    rg2_design_free(d);
                }
            }
            rg2_surface_free(&plain);
            rg2_mesh_free(&m);
        }
    printf("  pole sides: at most %.3g roundings from the pole, moved %.3g; Cox-de Boor %.2g; G0 %.2g, G1 %.2g rad, "
           "G2 %.2g\n", worst_spread / DBL_EPSILON, worst_moved / DBL_EPSILON, worst_err, g[0], g[1], g[2]);
    rg2_error err;
    rg2_surface ns = {.nu = 7};
    expect_err(rg2_nurbs_surface(NULL, &ns, &err), RG2_EINVAL, &err, "nurbs: NULL NURBS", "rg2_nurbs_surface(NULL)");
    CHECK(ns.nu == 0 && !ns.patch, "rg2_nurbs_surface(NULL): the output not zeroed");
    expect_err(rg2_nurbs_surface(&nb, NULL, &err), RG2_EINVAL, &err, "nurbs: NULL output surface",
               "rg2_nurbs_surface(.., NULL)");
    rg2_nurbs few = nb;
    few.nu = 3; /* rg2_nurbs_mesh's refusal, passed on; nothing left allocated (sanitizer builds) */
    expect_err(rg2_nurbs_surface(&few, &ns, &err), RG2_EINVAL, &err, "3 x 5 control points", "3 x 5 NURBS");
    W[0] = -1.0;
    expect_err(rg2_nurbs_surface(&nb, &ns, &err), RG2_EWEIGHT, &err, "weight [0][0] = -1", "a negative weight");
    CHECK(ns.nu == 0 && !ns.patch, "a negative weight: the output not left empty");
}

/* The control points on side `side` of a and b that differ in any bit; -1 if the side has another
 * count of patches in b. */
static int side_diffs(const rg2_surface *a, const rg2_surface *b, int side)
{
    int along_v = side == 0 || side == 2, cnt = along_v ? a->nu : a->nv, diff = 0;
    if (cnt != (along_v ? b->nu : b->nv))
        return -1;
    for (int k = 0; k < cnt; k++)
        for (int t = 0; t < 4; t++)
            diff += !!memcmp(side_h(a, side, k, t), side_h(b, side, k, t), 4 * sizeof(double));
    return diff;
}

/* The first point of weight > 0 on line `line` of m (along u for dv = 1, else along v), or the last. */
static int positive_on(const rg2_mesh *m, int dv, int line)
{
    int q = 0, nq = dv ? m->nu : m->nv;
    while (q < nq - 1 && !(rg2_mesh_at(m, dv ? q : line, dv ? line : q)[3] > 0.0))
        q++;
    return q;
}

/* A pole side through the operations that may leave it alone: an edit, a morph, a merge and a cap
 * keep it exactly when the patches along that side read the NURBS's own values across it, bit for
 * bit (the 4 lines, legs -1..3 and junctions 0..3 nearest that end; the scalars along the pole line
 * may differ: pole_along), and leave the construction's side otherwise. At each of the four ends,
 * with weights 1 and 1000 along the pole line, for each kept side (an edit of a point, a junction
 * and a leg at the far end and a second edit of it; a morph with that edit at t = 0.5; a merge with
 * the reversed, translated NURBS, both ends; a cap used uncapped; a morph at t = 1): the side is the
 * pole (2 roundings of the size), every other control value the construction's bit for bit, and the
 * construction's side before the fix-up the NURBS's own bit for bit, spread by more than a rounding.
 * For each dropped one (an edit of line 1, of junction 2, of leg 1; a morph with the line 1 edit; a
 * merge along the pole line with a translated copy, whose pole lies elsewhere (pole_merge: one with
 * the same pole keeps it); an edit of line, leg or junction 3 or of the data-only leg at the pole
 * end) the output is the construction's, its side spread and, but after the edits of line, leg or
 * junction 3, not the NURBS's. With every pole dropped by these operations, as before, 24 checks
 * fail. */
static void pole_ops(void)
{
    double U[PNU + 4] = {0, 0, 0, 0, 0.7, 1.9, 3, 3, 3, 3}, V[PNV + 4] = {0, 0, 0, 0, 1.2, 2, 2, 2, 2};
    double P[3 * PNU * PNV], W[PNU * PNV];
    rg2_nurbs nb = {PNU, PNV, P, W, U, V};
    double worst_spread[2] = {0.0, 0.0}, least_before = INFINITY;
    int kept = 0, dropped = 0, unchanged = 0;
    for (int side = 0; side < 4; side++) {
        pole_nurbs(side, 1000.0, 0, P, W);
        double lo[3] = {INFINITY, INFINITY, INFINITY}, hi[3] = {-INFINITY, -INFINITY, -INFINITY};
        for (int k = 0; k < 3 * PNU * PNV; k++)
            lo[k % 3] = fmin(lo[k % 3], P[k]), hi[k % 3] = fmax(hi[k % 3], P[k]);
        double size = sqrt((hi[0] - lo[0]) * (hi[0] - lo[0]) + (hi[1] - lo[1]) * (hi[1] - lo[1]) +
                           (hi[2] - lo[2]) * (hi[2] - lo[2]));
        int dv = side == 0 || side == 2, hie = side == 1 || side == 2, nd = dv ? PNV : PNU;
        char D = dv ? 'v' : 'u', O = dv ? 'u' : 'v';
        /* point q of the line k lines from the pole (as "[i, j]"), and that line's index */
#define LINE(k) (hie ? nd - 1 - (k) : (k))
        /* the first point of weight > 0 on the far line and on line 3 (an edit needs one: the
         * extrapolated end lines have weights of both signs) */
        rg2_error err0;
        rg2_design *d0 = pole_design(&nb, "", "n", &err0);
        CHECK(d0 != NULL, "side %d: %s", side, err0.msg);
        if (!d0)
            continue;
        char far_pt[32], l3_pt[32], near_pt[32], range[32];
        for (int q = 0; q < 2; q++) {
            int line = LINE(q ? 3 : nd - 1), at = positive_on(rg2_design_mesh(d0, 0), dv, line);
            snprintf(q ? l3_pt : far_pt, sizeof far_pt, "[%d, %d]", dv ? at : line, dv ? line : at);
        }
        rg2_design_free(d0);
        snprintf(near_pt, sizeof near_pt, dv ? "[2, %d]" : "[%d, 2]", LINE(1));
        snprintf(range, sizeof range, "[0, %d]", nd - 1);
        char far_edit[400], near_edit[200], more[14][900];
        snprintf(far_edit, sizeof far_edit,
                 "\"e\": {\"edit\": \"n\", \"points\": [{\"at\": %s, \"move\": [0.01, 0.02, -0.03], \"W\": 1.3}], "
                 "\"scalars\": [{\"dir\": \"%c\", \"junction\": %d, \"g\": 0.1}, {\"dir\": \"%c\", \"leg\": %d, \"w\": 1.2}]}",
                 far_pt, D, LINE(nd - 1), D, hie ? -1 : nd - 1);
        snprintf(near_edit, sizeof near_edit, "\"e\": {\"edit\": \"n\", \"points\": [{\"at\": %s, \"W\": 1.3}]}", near_pt);
        /* kept (the first 5; the merge keeps both its ends: the NURBS's, and its reversed, translated
         * copy's at the other end), then dropped */
        snprintf(more[0], sizeof more[0], ", %s, \"o\": {\"edit\": \"e\", \"points\": [{\"at\": %s, \"to\": [0, 0, 1]}]}",
                 far_edit, far_pt);
        snprintf(more[1], sizeof more[1], ", %s, \"o\": {\"morph\": [\"n\", \"e\"], \"t\": 0.5}", far_edit);
        snprintf(more[2], sizeof more[2],
                 ", \"rv\": {\"reverse\": \"n\", \"dir\": \"%c\"}, \"T\": {\"transform\": \"rv\", \"translate\": [10, 0, 0]}, "
                 "\"o\": {\"merge\": [%s], \"along\": \"%c\"}",
                 D, hie ? "\"T\", \"n\"" : "\"n\", \"T\"", D);
        snprintf(more[3], sizeof more[3], ", \"c\": {\"cap\": \"n\"}, \"o\": {\"cut\": \"c\", \"%c\": %s}", D, range);
        snprintf(more[4], sizeof more[4], ", %s, \"o\": {\"morph\": [\"e\", \"n\"], \"t\": 1}", near_edit);
        snprintf(more[5], sizeof more[5], ", %s, \"o\": {\"cut\": \"e\", \"%c\": %s}", near_edit, D, range);
        snprintf(more[6], sizeof more[6],
                 ", \"o\": {\"edit\": \"n\", \"scalars\": [{\"dir\": \"%c\", \"junction\": %d, \"g\": 0.1}]}", D, LINE(2));
        snprintf(more[7], sizeof more[7], ", \"o\": {\"edit\": \"n\", \"scalars\": [{\"dir\": \"%c\", \"leg\": %d, \"w\": 1.2}]}",
                 D, hie ? nd - 3 : 1); /* (the scalars along the pole line: pole_along) */
        snprintf(more[8], sizeof more[8], ", %s, \"o\": {\"morph\": [\"n\", \"e\"], \"t\": 0.5}", near_edit);
        snprintf(more[9], sizeof more[9],
                 ", \"T\": {\"transform\": \"n\", \"translate\": [0, 0, 10]}, \"o\": {\"merge\": [\"n\", \"T\"], \"along\": \"%c\"}",
                 O);
        /* line 3, leg 3, junction 3 from the pole: read by the end patches' far row and, through the
         * patch's power-of-two weight normalization, by the side */
        snprintf(more[10], sizeof more[10], ", \"o\": {\"edit\": \"n\", \"points\": [{\"at\": %s, \"W\": 1.3}]}", l3_pt);
        snprintf(more[11], sizeof more[11], ", \"o\": {\"edit\": \"n\", \"scalars\": [{\"dir\": \"%c\", \"leg\": %d, \"w\": 1.2}]}",
                 D, hie ? nd - 5 : 3);
        snprintf(more[12], sizeof more[12],
                 ", \"o\": {\"edit\": \"n\", \"scalars\": [{\"dir\": \"%c\", \"junction\": %d, \"g\": 0.1}]}", D, LINE(3));
        /* the data-only leg at the pole end (leg -1 counted from it) */
        snprintf(more[13], sizeof more[13], ", \"o\": {\"edit\": \"n\", \"scalars\": [{\"dir\": \"%c\", \"leg\": %d, \"w\": 1.2}]}",
                 D, hie ? nd - 1 : -1);
#undef LINE
        for (int v = 0; v < 14; v++) {
            int keep = v < 5;
            rg2_error err;
            rg2_design *d = pole_design(&nb, more[v], v == 2 ? "o\", \"n\", \"T" : "o\", \"n", &err);
            CHECK(d != NULL, "side %d, variant %d: %s", side, v, err.msg);
            if (!d)
                continue;
            /* the output o and the NURBS n (and the merge's copy T): as built, and their construction */
            int ns = rg2_design_num_surfaces(d);
            rg2_surface plain[3];
            for (int k = 0; k < ns; k++)
                CHECK_OK(rg2_surface_build(rg2_design_mesh(d, k), &plain[k], &err), &err);
            const rg2_surface *s = rg2_design_surface(d, 0);
            double moved;
            unsigned sides = keep ? 1u << side | (v == 2 ? 1u << (side ^ 2) : 0u) : 0u;
            int others = pole_diffs(s, &plain[0], sides, size, &moved);
            CHECK(others == 0, "side %d, variant %d: %d control values off the kept sides not the construction's", side,
                  v, others);
            for (int q = 0; q < (v == 2 ? 2 : 1); q++) { /* the side of n in o; the merge's: T's too */
                int to = q ? side ^ 2 : side, from = q ? 2 : 1;
                double ref[3] = {pole_p[0] + (q ? 10.0 : 0.0), pole_p[1], pole_p[2]};
                double sp = side_spread(s, to, size, ref), before = side_spread(&plain[0], to, size, NULL);
                int same = side_diffs(&plain[0], &plain[from], to);
                if (keep) {
                    CHECK(sp <= 2 * DBL_EPSILON && same == 0 && before > DBL_EPSILON,
                          "side %d, variant %d: side %d lies %.3g roundings from the pole (the construction's %.3g), "
                          "%d of the construction's points there not the NURBS's",
                          side, v, to, sp / DBL_EPSILON, before / DBL_EPSILON, same);
                    worst_spread[q] = fmax(worst_spread[q], sp), least_before = fmin(least_before, before);
                    kept++;
                } else if (v >= 10 && v <= 12) {
                    CHECK(before > DBL_EPSILON, "side %d, variant %d: the construction's side spreads %.3g roundings",
                          side, v, before / DBL_EPSILON);
                    unchanged += same == 0;
                    dropped++;
                } else {
                    CHECK(before > DBL_EPSILON && same != 0,
                          "side %d, variant %d: the construction's side spreads %.3g roundings, %d of its points not "
                          "the NURBS's", side, v, before / DBL_EPSILON, same);
                    dropped++;
                }
            }
            for (int k = 0; k < ns; k++)
                rg2_surface_free(&plain[k]);
            rg2_design_free(d);
        }
    }
    printf("  pole sides kept through edit, morph, merge and cap: %d, at most %.3g roundings of the size from the "
           "pole (the merge's translated copy's, at x = 10.3: %.3g), the construction's at least %.3g; %d dropped, "
           "%d of them after an edit of line, leg or junction 3 that left the construction's side as it was\n",
           kept, worst_spread[0] / DBL_EPSILON, worst_spread[1] / DBL_EPSILON, least_before / DBL_EPSILON, dropped,
           unchanged);
}

/* Tally a kept pole side: the largest distance sp from the pole, the construction's range. */
static void pole_kept(double sp, double before, double *worst, double *before_lo, double *before_hi, int *kept)
{
    *worst = fmax(*worst, sp), *before_lo = fmin(*before_lo, before), *before_hi = fmax(*before_hi, before);
    ++*kept;
}

/* A dropped pole side (variant v of `what`): the construction's, spread by more than a rounding. */
static void pole_dropped(int side, const char *what, int v, double before, int *dropped)
{
    CHECK(before > DBL_EPSILON, "side %d, %s %d: the construction's side spreads %.3g roundings", side, what, v,
          before / DBL_EPSILON);
    ++*dropped;
}

/* A pole side along a merge: the merge direction runs along the pole line, so the side crosses the
 * seams' new transition patches. Their side is p too in exact arithmetic (design_ops.c, merge), and
 * the construction spreads it by the parts' rounding. At each of the four ends, weights 1 and 1000
 * along the pole line, merged along it: the NURBS with itself, with a part whose other lines and
 * weights along the pole line differ (var 2), three parts, three closed into a ring, that ring rolled
 * on by 2 lines (the same patches, relabelled: roll keeps the pole). The side is the
 * pole to a tenth of a rounding of the size on every patch along it (its points h_w p / h_w are p to
 * an ulp of its coordinates), every other control value the construction's bit for bit, and the
 * construction's side spread by more than a rounding and less than 1000 (a rounding effect), the
 * transitions' own by more than a rounding in some merge at each end. With a part whose pole lies
 * elsewhere (translated by 0.001 in z), that has none (a point one ulp off), or whose scalars across
 * differ (a knot 1e-13 off, which the merge takes as equal) the output is the construction's. With
 * the sides along a merge dropped, as before, 20 checks fail; without the pole or the scalars
 * comparison 8 and 4; with roll dropping the pole, as before, 4. */
static void pole_merge(void)
{
    double U[PNU + 4] = {0, 0, 0, 0, 0.7, 1.9, 3, 3, 3, 3}, V[PNV + 4] = {0, 0, 0, 0, 1.2, 2, 2, 2, 2};
    double P[3][3 * PNU * PNV], W[3][PNU * PNV], Uk[PNU + 4], Vk[PNV + 4];
    memcpy(Uk, U, sizeof U), memcpy(Vk, V, sizeof V);
    Uk[4] *= 1.0 + 1e-13, Vk[4] *= 1.0 + 1e-13; /* knots the merge takes as equal (to 1e-12) */
    double worst = 0.0, before_lo = INFINITY, before_hi = 0.0, trans_lo = INFINITY, trans_hi = 0.0;
    int kept = 0, dropped = 0;
    for (int side = 0; side < 4; side++) {
        int dv = side == 0 || side == 2; /* the pole line runs along u: merged along u */
        char D = dv ? 'u' : 'v', *more = malloc(32768);
        double side_trans = 0.0; /* the transitions' largest spread, in the kept merges */
        size_t n = 0, cap = 32768;
        double lo[3] = {INFINITY, INFINITY, INFINITY}, hi[3] = {-INFINITY, -INFINITY, -INFINITY};
        static const char *const names[3] = {"n", "b", "x"}; /* n again, var 2, var 1 */
        for (int q = 0; q < 3; q++) {
            rg2_nurbs nb = {PNU, PNV, P[q], W[q], U, V};
            pole_nurbs(side, 1000.0, q == 0 ? 0 : q == 1 ? 2 : 1, P[q], W[q]);
            if (q < 2)
                for (int k = 0; k < 3 * PNU * PNV; k++)
                    lo[k % 3] = fmin(lo[k % 3], P[q][k]), hi[k % 3] = fmax(hi[k % 3], P[q][k]);
            if (q) {
                n += (size_t)snprintf(more + n, cap - n, ", ");
                n = nurbs_entry(more, n, cap, names[q], &nb);
            }
        }
        rg2_nurbs nk = {PNU, PNV, P[0], W[0], dv ? U : Uk, dv ? Vk : V}; /* n, its knots across a hair off */
        n += (size_t)snprintf(more + n, cap - n, ", ");
        n = nurbs_entry(more, n, cap, "k", &nk);
        double size = sqrt((hi[0] - lo[0]) * (hi[0] - lo[0]) + (hi[1] - lo[1]) * (hi[1] - lo[1]) +
                           (hi[2] - lo[2]) * (hi[2] - lo[2]));
        static const char *const merges[8] = {"\"n\", \"n\"], ", "\"n\", \"b\"], ", "\"b\", \"n\", \"b\"], ",
                                              "\"n\", \"b\", \"n\"], \"closed\": true, ",
                                              "\"n\", \"T\"], ", "\"n\", \"x\"], ", "\"n\", \"k\"], ",
                                              "\"n\", \"b\", \"n\"], \"closed\": true, "};
        for (int v = 0; v < 8; v++) { /* (7: the ring rolled on by 2 lines) */
            int keep = v < 4 || v == 7, parts = v == 2 || v == 3 || v == 7 ? 3 : 2;
            char *text = malloc(cap + 300), roll[64] = "";
            if (v == 7)
                snprintf(roll, sizeof roll, ", \"r\": {\"roll\": \"o\", \"dir\": \"%c\", \"by\": 2}", D);
            snprintf(text, cap + 300,
                     "%s, \"T\": {\"transform\": \"n\", \"translate\": [0, 0, 0.001]}, "
                     "\"o\": {\"merge\": [%s\"along\": \"%c\"}%s",
                     more, merges[v], D, roll);
            rg2_error err;
            rg2_design *d = pole_design(&(rg2_nurbs){PNU, PNV, P[0], W[0], U, V}, text, v == 7 ? "r" : "o", &err);
            free(text);
            CHECK(d != NULL, "side %d, merge %d: %s", side, v, err.msg);
            if (!d)
                continue;
            rg2_surface plain;
            CHECK_OK(rg2_surface_build(rg2_design_mesh(d, 0), &plain, &err), &err);
            const rg2_surface *s = rg2_design_surface(d, 0);
            double moved, sp = side_spread(s, side, size, pole_p), before = side_spread(&plain, side, size, pole_p);
            int others = pole_diffs(s, &plain, keep ? 1u << side : 0u, size, &moved);
            /* the transitions' own sides: the 3 patches after each part's own (patch 0 of a closed
             * ring is the last seam's: its segments start one line earlier; rolled, 2 lines later) */
            int per = (dv ? PNU : PNV) - 3, cnt = dv ? plain.nu : plain.nv, shift = v == 3 ? -1 : v == 7 ? 1 : 0;
            double trans = 0.0;
            for (int k = 0; k < cnt; k++)
                if ((k + per + 3 + shift) % (per + 3) >= per)
                    trans = fmax(trans, side_spread_at(&plain, side, k, k + 1, size, pole_p));
            CHECK(others == 0, "side %d, merge %d: %d control values off the pole side not the construction's", side, v,
                  others);
            if (keep) {
                CHECK(sp <= 0.1 * DBL_EPSILON && before > DBL_EPSILON && before < 1000 * DBL_EPSILON,
                      "side %d, merge %d (%d parts): the side lies %.3g roundings of the size from the pole (the "
                      "construction's %.3g)",
                      side, v, parts, sp / DBL_EPSILON, before / DBL_EPSILON);
                pole_kept(sp, before, &worst, &before_lo, &before_hi, &kept);
                trans_lo = fmin(trans_lo, trans), trans_hi = fmax(trans_hi, trans);
                side_trans = fmax(side_trans, trans);
            } else
                pole_dropped(side, "merge", v, before, &dropped);
            rg2_surface_free(&plain);
            rg2_design_free(d);
        }
        free(more);
        CHECK(side_trans > DBL_EPSILON, "side %d: the transitions' sides spread %.3g roundings at most", side,
              side_trans / DBL_EPSILON);
    }
    printf("  pole sides along merges kept: %d, at most %.3g roundings of the size from the pole (the "
           "construction's %.3g to %.3g, on the transition patches %.3g to %.3g); %d dropped (a part's pole "
           "elsewhere, none, or its scalars across a knot 1e-13 off)\n",
           kept, worst / DBL_EPSILON, before_lo / DBL_EPSILON, before_hi / DBL_EPSILON, trans_lo / DBL_EPSILON,
           trans_hi / DBL_EPSILON, dropped);
}

/* The diagonal of the box of the points of n NURBS of PNU x PNV points, one after the other at P. */
static double pole_box_size(const double *P, int n)
{
    double lo[3] = {INFINITY, INFINITY, INFINITY}, hi[3] = {-INFINITY, -INFINITY, -INFINITY};
    for (int k = 0; k < 3 * PNU * PNV * n; k++)
        lo[k % 3] = fmin(lo[k % 3], P[k]), hi[k % 3] = fmax(hi[k % 3], P[k]);
    return sqrt((hi[0] - lo[0]) * (hi[0] - lo[0]) + (hi[1] - lo[1]) * (hi[1] - lo[1]) +
                (hi[2] - lo[2]) * (hi[2] - lo[2]));
}

/* A pole side after an edit or a morph of the scalars along the pole line (of the direction the
 * side runs along): the patches along the side are new, but each of their side points is a
 * combination, with coefficients from those scalars, of the end points (w p, w) of the curves
 * across, which read only the 4 lines and the scalars across nearest the end (design_ops.c,
 * end_same): p in exact arithmetic. At each of the four ends, weights 1 and 1000 along the pole
 * line: edits of the legs and junctions along it near its start (the data-only leg -1 too), in its
 * middle, near its end and those two at once, a morph with the edit near the end, every leg and
 * junction along it edited in a merge of the NURBS with a variant along the pole line and in three
 * such parts closed into a ring (the line closed), and the middle edit of that ring. The side is
 * the pole to a tenth of a rounding of the size on every patch along it, every other control value
 * the construction's bit for bit, and the construction's side spread by more than a rounding and
 * less than 1000 (a rounding effect: 3.8 to 174), and not the unedited mesh's (the edit reaches
 * the side). (Edits near both ends of the pole line can spread it less: all its legs and junctions
 * at once 0.08 to 4.3 roundings, the three edits above at once 0.13 to 0.58.) The side's weights
 * reach -6e3 (other scalars weigh the extrapolated end lines' weights, of both signs, otherwise;
 * the ring's merge alone gives -5.9e3): those points are p all the same. With a point of line 1
 * or 2 edited too, or a junction or leg across at the end, the output is the construction's, its
 * side 1e10 roundings and more from the pole. With end_same comparing the scalars along the pole
 * line, as before, 32 checks fail. */
static void pole_along(void)
{
    double U[PNU + 4] = {0, 0, 0, 0, 0.7, 1.9, 3, 3, 3, 3}, V[PNV + 4] = {0, 0, 0, 0, 1.2, 2, 2, 2, 2};
    double P[2][3 * PNU * PNV], W[2][PNU * PNV];
    double worst = 0.0, before_lo = INFINITY, before_hi = 0.0, patch_lo = INFINITY, wmin = INFINITY;
    int kept = 0, dropped = 0;
    for (int side = 0; side < 4; side++) {
        int dv = side == 0 || side == 2, hie = side == 1 || side == 2, nd = dv ? PNV : PNU, na = dv ? PNU : PNV;
        char D = dv ? 'v' : 'u', O = dv ? 'u' : 'v';
        size_t cap = 16384, n = 0;
        char *more = malloc(cap), *text = malloc(cap + 2048);
        for (int q = 0; q < 2; q++)
            pole_nurbs(side, 1000.0, 2 * q, P[q], W[q]);
        n += (size_t)snprintf(more + n, cap - n, ", ");
        n = nurbs_entry(more, n, cap, "b", &(rg2_nurbs){PNU, PNV, P[1], W[1], U, V});
        double size[2] = {pole_box_size(P[0], 1), pole_box_size(P[0], 2)}; /* n; n and b */
        /* the scalar edits along the pole line: near its start (leg -1 is data-only), in its middle,
         * near its end, all of its legs and junctions at once */
        char along[5][600];
        snprintf(along[0], sizeof along[0],
                 "{\"dir\": \"%c\", \"leg\": -1, \"w\": 1.5}, {\"dir\": \"%c\", \"leg\": 0, \"w\": 1.5}, "
                 "{\"dir\": \"%c\", \"junction\": 1, \"b\": 0.6, \"g\": 0.3}", O, O, O);
        snprintf(along[1], sizeof along[1], "{\"dir\": \"%c\", \"junction\": 2, \"g\": 1}, {\"dir\": \"%c\", \"leg\": 2, "
                 "\"w\": 0.9}", O, O);
        snprintf(along[2], sizeof along[2], "{\"dir\": \"%c\", \"leg\": %d, \"w\": 3}, {\"dir\": \"%c\", \"junction\": %d, "
                 "\"b\": 1.8, \"g\": 0.2}", O, na - 2, O, na - 2);
        snprintf(along[3], sizeof along[3], "%.290s, %.290s", along[1], along[2]); /* both at once */
        for (int k = 0, m = 0; k < na - 1; k++) /* every leg and junction that segments read */
            m += snprintf(along[4] + m, sizeof along[4] - (size_t)m, "%s{\"dir\": \"%c\", \"leg\": %d, \"w\": %g}, "
                          "{\"dir\": \"%c\", \"junction\": %d, \"b\": %g, \"g\": %g}", k ? ", " : "", O, k,
                          0.7 + 0.4 * k, O, k + 1, 0.5 + 0.3 * k, 0.05 * k);
        char near_pt[32], l2_pt[32], across[2][200];
        snprintf(near_pt, sizeof near_pt, dv ? "[2, %d]" : "[%d, 2]", hie ? nd - 2 : 1);
        snprintf(l2_pt, sizeof l2_pt, dv ? "[2, %d]" : "[%d, 2]", hie ? nd - 3 : 2);
        snprintf(across[0], sizeof across[0], "{\"dir\": \"%c\", \"junction\": %d, \"g\": 0.1}", D, hie ? nd - 2 : 1);
        snprintf(across[1], sizeof across[1], "{\"dir\": \"%c\", \"leg\": %d, \"w\": 1.2}", D, hie ? nd - 3 : 1);
        for (int v = 0; v < 12; v++) {
            int keep = v < 8, merged = v >= 5 && v < 8;
            char mesh[200] = "";
            if (merged)
                snprintf(mesh, sizeof mesh, ", \"m\": {\"merge\": [%s], \"along\": \"%c\"%s}",
                         v == 5 ? "\"n\", \"b\"" : "\"n\", \"b\", \"n\"", O, v == 5 ? "" : ", \"closed\": true");
            const char *ed = v < 4 ? along[v] : v == 4 ? along[2] : v == 5 || v == 6 ? along[4] : along[1];
            if (v == 4)
                snprintf(text, cap + 2048, "%s, \"e\": {\"edit\": \"n\", \"scalars\": [%s]}, "
                         "\"o\": {\"morph\": [\"n\", \"e\"], \"t\": 0.5}", more, ed);
            else if (v < 10)
                snprintf(text, cap + 2048, "%s%s, \"o\": {\"edit\": \"%s\", \"scalars\": [%s]%s%s%s}", more, mesh,
                         merged ? "m" : "n", ed, v >= 8 ? ", \"points\": [{\"at\": " : "",
                         v == 8 ? near_pt : v == 9 ? l2_pt : "", v >= 8 ? ", \"W\": 1.3}]" : "");
            else
                snprintf(text, cap + 2048, "%s, \"o\": {\"edit\": \"n\", \"scalars\": [%s, %s]}", more, along[1],
                         across[v - 10]);
            rg2_error err;
            rg2_design *d = pole_design(&(rg2_nurbs){PNU, PNV, P[0], W[0], U, V}, text,
                                        merged ? "o\", \"m" : "o\", \"n", &err);
            CHECK(d != NULL, "side %d, variant %d: %s", side, v, err.msg);
            if (!d)
                continue;
            rg2_surface plain, ref;
            CHECK_OK(rg2_surface_build(rg2_design_mesh(d, 0), &plain, &err), &err);
            CHECK_OK(rg2_surface_build(rg2_design_mesh(d, 1), &ref, &err), &err);
            const rg2_surface *s = rg2_design_surface(d, 0);
            double sz = size[merged], moved, sp = side_spread(s, side, sz, pole_p);
            double before = side_spread(&plain, side, sz, pole_p);
            int others = pole_diffs(s, &plain, keep ? 1u << side : 0u, sz, &moved), reach = side_diffs(&plain, &ref, side);
            int cnt = dv ? plain.nu : plain.nv;
            double plo = INFINITY; /* the construction's smallest spread on a patch; the side's smallest weight */
            for (int k = 0; k < cnt; k++) {
                plo = fmin(plo, side_spread_at(&plain, side, k, k + 1, sz, pole_p));
                for (int t = 0; t < 4; t++)
                    wmin = fmin(wmin, side_h(&plain, side, k, t)[3]);
            }
            CHECK(others == 0, "side %d, variant %d: %d control values off the kept side not the construction's", side, v,
                  others);
            if (keep) {
                CHECK(sp <= 0.1 * DBL_EPSILON && before > DBL_EPSILON && before < 1000 * DBL_EPSILON && reach > 0,
                      "side %d, variant %d: the side lies %.3g roundings of the size from the pole (the construction's "
                      "%.3g, %d of its points not the unedited mesh's)",
                      side, v, sp / DBL_EPSILON, before / DBL_EPSILON, reach);
                pole_kept(sp, before, &worst, &before_lo, &before_hi, &kept);
                patch_lo = fmin(patch_lo, plo);
            } else
                pole_dropped(side, "variant", v, before, &dropped);
            rg2_surface_free(&plain);
            rg2_surface_free(&ref);
            rg2_design_free(d);
        }
        free(more);
        free(text);
    }
    printf("  pole sides after edits and a morph along the pole line kept: %d, at most %.3g roundings of the size "
           "from the pole (the construction's %.3g to %.3g, per patch from %.3g; side weights from %.3g); %d dropped "
           "(a point of line 1 or 2, a junction or leg across at the end)\n",
           kept, worst / DBL_EPSILON, before_lo / DBL_EPSILON, before_hi / DBL_EPSILON, patch_lo / DBL_EPSILON, wmin,
           dropped);
}

int main(void)
{
    random_nurbs();
    clamped_weights();
    extreme_knot_ratios();
    knots_near_double_range();
    pole_rows();
    pole_ops();
    pole_merge();
    pole_along();
    errors();
    return rg2t_done("test_nurbs");
}
