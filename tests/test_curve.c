/* test_curve.c -- rational cubic G2 spline curves: the G1/G2 relations of Definition 1 at
 * every junction, the polynomial special case against Cox-de Boor, exact circles and arcs,
 * and the error cases. */
#include "harness.h"

#include <limits.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

static double vnorm(const double *a, int d)
{
    double s = 0;
    for (int k = 0; k < d; k++)
        s += a[k] * a[k];
    return sqrt(s);
}

/* curvature in any dimension: |f' ^ f''| / |f'|^3, the wedge summed over coordinate planes
 * (no cancellation, unlike |f'|^2 |f''|^2 - (f'.f'')^2) */
static double curvature(const double *d1, const double *d2, int d)
{
    double a = 0, q = 0;
    for (int k = 0; k < d; k++) {
        a += d1[k] * d1[k];
        for (int l = k + 1; l < d; l++) {
            double x = d1[k] * d2[l] - d1[l] * d2[k];
            q += x * x;
        }
    }
    return sqrt(q) / pow(a, 1.5);
}

/* The G0/G1/G2 relations of Definition 1 and the curvature at every junction between two
 * segments of c (built with scalars s), checked; worst[] the largest G1, G2 and curvature errors
 * (relative). Returns the junctions measured. */
static int junction_relations(const rg2_curve *c, const rg2_scalars *s, int trial, double worst[3])
{
    int dim = c->dim, closed = s->closed, n = 0;
    for (int k = closed ? 0 : 1; k < c->n_segments; k++) {
        int km = (k + c->n_segments - 1) % c->n_segments;
        int j = closed ? k : k + 1; /* junction index */
        double b = s->b[j], g = s->g[j];
        double pL[RG2_MAX_DIM], dL[RG2_MAX_DIM], ddL[RG2_MAX_DIM];
        double pR[RG2_MAX_DIM], dR[RG2_MAX_DIM], ddR[RG2_MAX_DIM];
        rg2_curve_eval(c, km, 1.0, pL, dL, ddL);
        rg2_curve_eval(c, k, 0.0, pR, dR, ddR);
        double e0[RG2_MAX_DIM], e1[RG2_MAX_DIM], e2[RG2_MAX_DIM];
        for (int d = 0; d < dim; d++) {
            e0[d] = pR[d] - pL[d];
            e1[d] = dR[d] - b * dL[d];
            e2[d] = ddR[d] - b * b * ddL[d] - g * dL[d];
        }
        double r0 = vnorm(e0, dim);
        double r1 = vnorm(e1, dim) / vnorm(dR, dim);
        double r2 = vnorm(e2, dim) / (vnorm(ddR, dim) + vnorm(dR, dim));
        double kL = curvature(dL, ddL, dim), kR = curvature(dR, ddR, dim);
        double rk = fabs(kL - kR) / fmax(kL, kR);
        CHECK(r0 <= 1e-15, "trial %d junction %d: G0 gap %.3g", trial, j, r0);
        CHECK(r1 <= 1e-12, "trial %d junction %d: G1 relation %.3g", trial, j, r1);
        CHECK(r2 <= 1e-12, "trial %d junction %d: G2 relation %.3g", trial, j, r2);
        CHECK(rk <= 1e-11, "trial %d junction %d: curvature jump %.3g", trial, j, rk);
        worst[0] = fmax(worst[0], r1);
        worst[1] = fmax(worst[1], r2);
        worst[2] = fmax(worst[2], rk);
        n++;
    }
    return n;
}

static void random_curves(void)
{
    rg2t_rng r;
    uint64_t seed = 1122;
    rg2t_seed(&r, seed);
    printf("random curves, seed %llu\n", (unsigned long long)seed);
    double worst[3] = {0, 0, 0};
    int junctions = 0;
    for (int trial = 0; trial < 60; trial++) {
        int dim = 2 + trial % 3, closed = (trial / 3) % 2;
        int n = rg2t_int(&r, closed ? 3 : 4, 14);
        rg2_scalars s;
        rg2_error err;
        CHECK_OK(rg2_scalars_init(&s, n, closed, &err), &err);
        for (int k = 0; k < rg2_scalars_num_w(&s); k++)
            s.w[k] = rg2t_uniform(&r, 0.7, 1.4);
        for (int i = 0; i < n; i++)
            do { /* resample the junction until K_i > 0 (the construction's precondition) */
                s.b[i] = rg2t_uniform(&r, 0.5, 2.0);
                s.g[i] = rg2t_uniform(&r, -0.8, 0.8);
            } while (!(rg2_scalars_K(&s, i) > 0.0));
        double *p = malloc(sizeof(double) * (size_t)(n * dim));
        for (int k = 0; k < n * dim; k++)
            p[k] = rg2t_uniform(&r, -1, 1);
        rg2_curve c;
        rg2_status st = rg2_curve_build(dim, p, &s, &c, &err);
        CHECK(st == RG2_OK, "trial %d: %s", trial, err.msg);
        if (st == RG2_OK) {
            CHECK(c.n_segments == (closed ? n : n - 3), "segments %d", c.n_segments);
            junctions += junction_relations(&c, &s, trial, worst);
            rg2_curve_free(&c);
        }
        free(p);
        rg2_scalars_free(&s);
    }
    printf("  %d junctions: G1 relation %.2e, G2 relation %.2e, curvature jump %.2e (relative)\n",
           junctions, worst[0], worst[1], worst[2]);
}

/* Weights are valid when positive (rg2_scalars_check, MATH.md section 1), however small: legs of
 * weight 0.01 down to 0.003 (K > 0 by g) give a curve with the G2 relations at every junction. */
static void small_weights(void)
{
    rg2t_rng r;
    rg2t_seed(&r, 601);
    const double ws[] = {0.01, 0.007, 0.005, 0.003};
    double worst[3] = {0, 0, 0};
    int junctions = 0;
    for (int trial = 0; trial < 8; trial++) {
        int closed = trial & 1, n = 7, dim = 3;
        rg2_scalars s;
        rg2_error err;
        CHECK_OK(rg2_scalars_init(&s, n, closed, &err), &err);
        for (int k = 0; k < rg2_scalars_num_w(&s); k++)
            s.w[k] = k % 2 ? ws[trial / 2] : rg2t_uniform(&r, 0.7, 1.4);
        for (int i = 0; i < n; i++) {
            s.b[i] = rg2t_uniform(&r, 0.5, 2.0);
            s.g[i] = 4.0 * (s.b[i] + s.b[i] * s.b[i]) + rg2t_uniform(&r, 0.5, 1.5); /* K >= 0.5 */
        }
        double p[7 * 3];
        for (int k = 0; k < n * dim; k++)
            p[k] = rg2t_uniform(&r, -1, 1);
        rg2_curve c;
        rg2_status st = rg2_scalars_check(&s, "w", &err);
        CHECK(st == RG2_OK, "weights %g (closed %d) refused: %s '%s'", ws[trial / 2], closed, rg2_status_str(st), err.msg);
        st = rg2_curve_build(dim, p, &s, &c, &err);
        CHECK(st == RG2_OK, "a curve with weights %g (closed %d): %s '%s'", ws[trial / 2], closed, rg2_status_str(st),
              err.msg);
        if (st == RG2_OK) {
            junctions += junction_relations(&c, &s, trial, worst);
            rg2_curve_free(&c);
        }
        rg2_scalars_free(&s);
    }
    CHECK(junctions == 4 * 7 + 4 * 3, "%d junctions measured", junctions);
    printf("small weights (0.01 down to 0.003): %d junctions, G1 relation %.2e, G2 relation %.2e, curvature jump %.2e\n",
           junctions, worst[0], worst[1], worst[2]);
}

/* Cox-de Boor / de Boor evaluation of a cubic B-spline with knot vector U (n + 4 values). */
static void de_boor(const double *U, const double *P, int n, int dim, double x, double *out)
{
    int l = 3;
    while (l < n - 1 && x >= U[l + 1])
        l++;
    double d[4][RG2_MAX_DIM];
    for (int j = 0; j < 4; j++)
        memcpy(d[j], P + (l - 3 + j) * dim, sizeof(double) * (size_t)dim);
    for (int rr = 1; rr <= 3; rr++)
        for (int j = 3; j >= rr; j--) {
            int i = l - 3 + j;
            double a = (x - U[i]) / (U[i + 4 - rr] - U[i]);
            for (int k = 0; k < dim; k++)
                d[j][k] = (1 - a) * d[j - 1][k] + a * d[j][k];
        }
    memcpy(out, d[3], sizeof(double) * (size_t)dim);
}

static void polynomial_mode(void)
{
    rg2t_rng r;
    rg2t_seed(&r, 99);
    double worst = 0;
    for (int trial = 0; trial < 20; trial++) {
        int n = rg2t_int(&r, 4, 16), dim = 3;
        double knots[32], U[32], P[16 * 3];
        knots[0] = rg2t_uniform(&r, -2, 2);
        for (int k = 1; k < n + 2; k++)
            knots[k] = knots[k - 1] + rg2t_uniform(&r, 0.05, 2.0);
        U[0] = knots[0] - 1;
        for (int k = 0; k < n + 2; k++)
            U[k + 1] = knots[k];
        U[n + 3] = knots[n + 1] + 1;
        for (int k = 0; k < n * dim; k++)
            P[k] = rg2t_uniform(&r, -1, 1);
        rg2_scalars s;
        rg2_error err;
        rg2_curve c;
        CHECK_OK(rg2_scalars_from_knots(&s, knots, n + 2, 0, &err), &err);
        CHECK_OK(rg2_curve_build(dim, P, &s, &c, &err), &err);
        for (int k = 0; k < c.n_segments; k++) {
            double v0 = knots[k + 2], v1 = knots[k + 3]; /* segment k+1 spans [v_{k+1}, v_{k+2}] */
            for (int q = 0; q <= 20; q++) {
                double t = q / 20.0, a[3], b[3];
                rg2_curve_eval(&c, k, t, a, NULL, NULL);
                de_boor(U, P, n, dim, v0 + t * (v1 - v0), b);
                for (int d = 0; d < dim; d++)
                    worst = fmax(worst, fabs(a[d] - b[d]));
            }
        }
        rg2_curve_free(&c);
        rg2_scalars_free(&s);
    }
    CHECK(worst <= 1e-14, "polynomial mode vs Cox-de Boor: %.3g", worst);
    printf("polynomial mode vs Cox-de Boor: max difference %.2e\n", worst);
}

/* Random partition of total into n arcs each in [lo, pi). */
static void partition(rg2t_rng *r, int n, double total, double lo, double *a)
{
    for (;;) {
        double s = 0;
        for (int k = 0; k < n; k++)
            s += (a[k] = rg2t_uniform(r, 0.02, 1.0));
        int ok = 1;
        for (int k = 0; k < n; k++) {
            a[k] *= total / s;
            if (a[k] < lo || a[k] > M_PI - 1e-3)
                ok = 0;
        }
        if (ok)
            return;
    }
}

static void circles(void)
{
    rg2t_rng r;
    rg2t_seed(&r, 31415);
    double wr = 0, wm = 0;
    for (int trial = 0; trial < 60; trial++) {
        int closed = trial % 2;
        int m = rg2t_int(&r, 3, 12);          /* arcs covered by segments */
        int n = closed ? m : m + 3;           /* control points */
        int na = closed ? m : n + 1;          /* angles given */
        double alpha[16], cs[32];
        double R = pow(10.0, rg2t_uniform(&r, -3, 3));
        double cx = rg2t_uniform(&r, -5, 5) * R, cy = rg2t_uniform(&r, -5, 5) * R;
        double th0 = rg2t_uniform(&r, -M_PI, M_PI);
        if (closed)
            partition(&r, na, 2 * M_PI, trial < 20 ? 0.05 : 0.2, alpha);
        else
            for (int k = 0; k < na; k++)
                alpha[k] = rg2t_uniform(&r, 0.05, 0.9 * 2 * M_PI / na + 0.05);
        rg2_scalars s;
        rg2_error err;
        rg2_curve c;
        CHECK_OK(rg2_scalars_from_angles(&s, alpha, na, closed, &err), &err);
        CHECK_OK(rg2_circle_coeffs(alpha, na, closed, th0, cs, &err), &err);
        for (int i = 0; i < n; i++) {
            cs[2 * i] = cx + R * cs[2 * i];
            cs[2 * i + 1] = cy + R * cs[2 * i + 1];
        }
        CHECK_OK(rg2_curve_build(2, cs, &s, &c, &err), &err);
        double theta = th0 + (closed ? 0.0 : alpha[1]); /* open: segment 0 is arc 1 */
        for (int k = 0; k < c.n_segments; k++) {
            double a = closed ? alpha[k] : alpha[k + 2], be = 0.5 * a;
            for (int q = 0; q <= 64; q++) {
                double t = q / 64.0, p[2];
                rg2_curve_eval(&c, k, t, p, NULL, NULL);
                double dr = fabs(hypot(p[0] - cx, p[1] - cy) - R) / R;
                double th = theta + be + 2 * atan(tan(0.5 * be) * (2 * t - 1));
                double dm = hypot(p[0] - cx - R * cos(th), p[1] - cy - R * sin(th)) / R;
                wr = fmax(wr, dr);
                wm = fmax(wm, dm);
            }
            theta += a;
        }
        CHECK(wr <= 1e-13, "trial %d (%s, %d arcs, R %.3g): radius error %.3g", trial,
              closed ? "closed" : "open", m, R, wr);
        CHECK(wm <= 1e-13, "trial %d: arc-map error %.3g", trial, wm);
        rg2_curve_free(&c);
        rg2_scalars_free(&s);
    }
    printf("circles: radius error %.2e, arc-map error %.2e (relative to R)\n", wr, wm);
}

/* Closed polynomial mode: rg2_scalars_from_knots(closed) on a closed control polygon is the
 * periodic C2 cubic B-spline of those knots. Reference: Cox-de Boor on the periodic extension
 * (control points p^{k mod n}, knots v_{k + n} = v_k + period); closed segment k spans
 * [v_k, v_{k+1}] and is shaped by p^{k-1} .. p^{k+2}. */
static void closed_knots(void)
{
    rg2t_rng r;
    rg2t_seed(&r, 4242);
    double worst = 0;
    for (int trial = 0; trial < 20; trial++) {
        int n = rg2t_int(&r, 3, 12), dim = 3;
        double v[16], P[12 * 3];
        v[0] = rg2t_uniform(&r, -2, 2);
        for (int k = 1; k <= n; k++)
            v[k] = v[k - 1] + rg2t_uniform(&r, 0.05, 2.0);
        double T = v[n] - v[0];
        for (int k = 0; k < n * dim; k++)
            P[k] = rg2t_uniform(&r, -1, 1);
        /* open B-spline over the extension: control points E_m = p^{(m - 1) mod n}, m = 0..n+2,
         * knots U_m = v_{m - 3} (periodic), so span [v_k, v_{k+1}] = [U_{k+3}, U_{k+4}] uses
         * E_{k..k+3} = p^{k-1}..p^{k+2} */
        double E[16 * 3], U[24];
        int ne = n + 3;
        for (int m = 0; m < ne; m++)
            memcpy(E + m * dim, P + ((m - 1 + n) % n) * dim, sizeof(double) * (size_t)dim);
        for (int m = 0; m < ne + 4; m++) {
            int q = m - 3, wrap = 0;
            while (q < 0) q += n, wrap--;
            while (q >= n) q -= n, wrap++;
            U[m] = v[q] + wrap * T;
        }
        rg2_scalars s;
        rg2_error err;
        rg2_curve c;
        CHECK_OK(rg2_scalars_from_knots(&s, v, n + 1, 1, &err), &err);
        CHECK(s.closed && s.n == n, "closed knots: %d points, closed %d", s.n, s.closed);
        for (int i = 0; i < n; i++) {
            double d = v[i + 1] - v[i], dm = i ? v[i] - v[i - 1] : v[n] - v[n - 1];
            CHECK(fabs(s.b[i] - d / dm) <= 1e-15 * (d / dm) && s.g[i] == 0.0, "closed knots: b[%d] = %.17g, g %.3g",
                  i, s.b[i], s.g[i]);
        }
        CHECK_OK(rg2_curve_build(dim, P, &s, &c, &err), &err);
        CHECK(c.n_segments == n, "closed knots: %d segments for %d points", c.n_segments, n);
        for (int k = 0; k < c.n_segments; k++)
            for (int q = 0; q <= 20; q++) {
                double t = q / 20.0, a[3], b[3];
                rg2_curve_eval(&c, k, t, a, NULL, NULL);
                double x = v[k] + t * (v[k + 1] - v[k]); /* (t = 1: the next span, C2 there) */
                de_boor(U, E, ne, dim, x, b);
                for (int d = 0; d < dim; d++)
                    worst = fmax(worst, fabs(a[d] - b[d]));
            }
        rg2_curve_free(&c);
        rg2_scalars_free(&s);
    }
    CHECK(worst <= 1e-13, "closed polynomial mode vs periodic Cox-de Boor: %.3g", worst);
    printf("closed polynomial mode vs periodic Cox-de Boor: max difference %.2e\n", worst);
}

/* rg2_curve_curvature: 1/R on circles of any radius, in the plane and tilted in space; the
 * test's own wedge formula on random curves in 3D; 0 for dimensions other than 2 and 3. */
static void curve_curvature(void)
{
    rg2t_rng r;
    rg2t_seed(&r, 777);
    double wc = 0, wr = 0;
    for (int trial = 0; trial < 12; trial++) {
        int m = rg2t_int(&r, 3, 9), dim = 2 + trial % 2;
        double alpha[16], cs[32], pts[16 * 3];
        partition(&r, m, 2 * M_PI, 0.2, alpha);
        double R = pow(10.0, rg2t_uniform(&r, -3, 3));
        rg2_scalars s;
        rg2_error err;
        rg2_curve c;
        CHECK_OK(rg2_scalars_from_angles(&s, alpha, m, 1, &err), &err);
        CHECK_OK(rg2_circle_coeffs(alpha, m, 1, rg2t_uniform(&r, -M_PI, M_PI), cs, &err), &err);
        /* 3D: the circle in the plane spanned by e1 = (1, 1, 0)/sqrt 2 and e2 = (0, 0, 1) */
        for (int i = 0; i < m; i++) {
            double x = R * cs[2 * i], y = R * cs[2 * i + 1];
            if (dim == 2) {
                pts[2 * i] = x + 5 * R;
                pts[2 * i + 1] = y - 2 * R;
            } else {
                pts[3 * i] = x / sqrt(2.0) + R;
                pts[3 * i + 1] = x / sqrt(2.0);
                pts[3 * i + 2] = y - 3 * R;
            }
        }
        CHECK_OK(rg2_curve_build(dim, pts, &s, &c, &err), &err);
        for (int k = 0; k < c.n_segments; k++)
            for (int q = 0; q <= 16; q++)
                wc = fmax(wc, fabs(rg2_curve_curvature(&c, k, q / 16.0) * R - 1.0));
        rg2_curve_free(&c);
        rg2_scalars_free(&s);
    }
    CHECK(wc <= 1e-12, "circle curvature * R - 1: %.3g", wc);
    /* any size: a pentagon scaled by 2^a has exactly 2^-a times the curvature (|a|^3 overflowed
     * from a radius of 1e78, giving inf, and NaN at 1e103 and 1e-150) */
    {
        double pts[15], pa[15], k1 = 0.0;
        rg2_scalars s;
        rg2_error err;
        CHECK_OK(rg2_scalars_init(&s, 5, 1, &err), &err);
        for (int i = 0; i < 5; i++) {
            pts[3 * i] = cos(i * 2 * M_PI / 5);
            pts[3 * i + 1] = sin(i * 2 * M_PI / 5);
            pts[3 * i + 2] = 0.25 * i;
        }
        int off = 0;
        for (int a = 0, n = 0; n < 41; a = ++n <= 20 ? -50 * n : 50 * (n - 20)) { /* 0 first, then -50.. and 50.. */
            for (int q = 0; q < 15; q++)
                pa[q] = ldexp(pts[q], a);
            rg2_curve c;
            CHECK_OK(rg2_curve_build(3, pa, &s, &c, &err), &err);
            double k = rg2_curve_curvature(&c, 2, 0.3);
            if (a == 0)
                k1 = k;
            rg2_curve_free(&c);
            pa[0] = ldexp(k, a); /* back at size 1 */
            off += !(isfinite(k) && k > 0.0) || (k1 > 0.0 && pa[0] != k1);
        }
        CHECK(k1 > 0.0 && off == 0, "pentagons scaled by 2^-1000 .. 2^1000: %d curvatures off (size 1: %.17g)", off, k1);
        rg2_scalars_free(&s);
    }
    for (int trial = 0; trial < 10; trial++) {
        int n = rg2t_int(&r, 4, 10);
        rg2_scalars s;
        rg2_error err;
        rg2_curve c;
        CHECK_OK(rg2_scalars_init(&s, n, 0, &err), &err);
        for (int k = 0; k < rg2_scalars_num_w(&s); k++)
            s.w[k] = rg2t_uniform(&r, 0.7, 1.4);
        double p[10 * 3];
        for (int k = 0; k < n * 3; k++)
            p[k] = rg2t_uniform(&r, -1, 1);
        CHECK_OK(rg2_curve_build(3, p, &s, &c, &err), &err);
        for (int k = 0; k < c.n_segments; k++)
            for (int q = 0; q <= 8; q++) {
                double d1[3], d2[3], t = q / 8.0;
                rg2_curve_eval(&c, k, t, NULL, d1, d2);
                double own = curvature(d1, d2, 3), got = rg2_curve_curvature(&c, k, t);
                wr = fmax(wr, fabs(got - own) / own);
            }
        rg2_curve_free(&c);
        rg2_scalars_free(&s);
    }
    CHECK(wr <= 1e-12, "random space curves: curvature vs the wedge formula %.3g relative", wr);
    /* dimensions 1 and 4: no curvature (0) */
    double line[5] = {0, 1, 3, 4, 7}, quad[5 * 4] = {0, 0, 0, 0, 1, 0, 0, 1, 1, 1, 0, 0, 0, 1, 1, 0, 2, 2, 2, 2};
    rg2_scalars s;
    rg2_error err;
    rg2_curve c1, c4;
    CHECK_OK(rg2_scalars_init(&s, 5, 0, &err), &err);
    CHECK_OK(rg2_curve_build(1, line, &s, &c1, &err), &err);
    CHECK_OK(rg2_curve_build(4, quad, &s, &c4, &err), &err);
    CHECK(rg2_curve_curvature(&c1, 0, 0.5) == 0.0 && rg2_curve_curvature(&c4, 1, 0.25) == 0.0,
          "curvature of 1-d / 4-d curves: %g, %g", rg2_curve_curvature(&c1, 0, 0.5), rg2_curve_curvature(&c4, 1, 0.25));
    rg2_curve_free(&c1);
    rg2_curve_free(&c4);
    rg2_scalars_free(&s);
    printf("rg2_curve_curvature: circles |k R - 1| %.2e, random space curves %.2e relative\n", wc, wr);
}

/* The closed flag of scalars is 1 or 0 (rg2.h) however closedness was asked for (any nonzero
 * int), through every constructor and copy, and so the mesh's and the built surface's. */
static void closed_flags(void)
{
    rg2_error err;
    const int asked[] = {0, 1, 2, -1, 7};
    double knots[8] = {0, 1, 2, 3.5, 4, 5, 6, 7}, arcs[5] = {M_PI / 2, M_PI / 2, M_PI / 2, M_PI / 2, M_PI / 2};
    int right = 0, made = 0;
    for (int q = 0; q < 5; q++) {
        int want = asked[q] != 0;
        rg2_scalars s[4];
        memset(s, 0, sizeof s);
        CHECK_OK(rg2_scalars_init(&s[0], 5, asked[q], &err), &err);
        CHECK_OK(rg2_scalars_from_knots(&s[1], knots, 8, asked[q], &err), &err);
        CHECK_OK(rg2_scalars_from_angles(&s[2], arcs, 5, asked[q], &err), &err);
        CHECK_OK(rg2_scalars_copy(&s[2], &s[3], &err), &err);
        for (int k = 0; k < 4; k++, made++)
            right += s[k].closed == want;
        for (int k = 0; k < 4; k++)
            rg2_scalars_free(&s[k]);
        rg2_mesh m;
        CHECK_OK(rg2_mesh_init(&m, 6, 5, asked[q], asked[4 - q], &err), &err);
        for (int k = 0; k < 6 * 5; k++)
            m.p[4 * k] = k % 6, m.p[4 * k + 1] = k / 6, m.p[4 * k + 2] = (k * 7) % 3, m.p[4 * k + 3] = 1;
        rg2_surface sf;
        CHECK_OK(rg2_surface_build(&m, &sf, &err), &err);
        right += m.su.closed == want && m.sv.closed == (asked[4 - q] != 0) && sf.closed_u == want &&
                 sf.closed_v == (asked[4 - q] != 0);
        made++;
        rg2_surface_free(&sf);
        rg2_mesh_free(&m);
    }
    CHECK(right == made, "closed flags 0 or 1: %d of %d", right, made);
}

/* Every dimension 1 .. RG2_MAX_DIM is built, RG2_MAX_DIM + 1 refused. The construction is the
 * same linear stencil for every coordinate: coordinate d of a curve of RG2_MAX_DIM dimensions,
 * closed and open, is the 1-D curve of that coordinate alone, position and both derivatives,
 * to the last bit. */
static void dimensions(void)
{
    rg2t_rng r;
    rg2t_seed(&r, 41);
    int built = 0, off = 0;
    for (int closed = 0; closed < 2; closed++) {
        enum { N = 7 };
        rg2_scalars s;
        rg2_error err;
        CHECK_OK(rg2_scalars_init(&s, N, closed, &err), &err);
        for (int k = 0; k < rg2_scalars_num_w(&s); k++)
            s.w[k] = rg2t_uniform(&r, 0.7, 1.4);
        double p[N * (RG2_MAX_DIM + 1)], one[N];
        for (int k = 0; k < N * (RG2_MAX_DIM + 1); k++)
            p[k] = rg2t_uniform(&r, -1, 1);
        rg2_curve c, c1;
        for (int dim = 1; dim <= RG2_MAX_DIM; dim++)
            if (rg2_curve_build(dim, p, &s, &c, &err) == RG2_OK) {
                built++;
                rg2_curve_free(&c);
            }
        CHECK(rg2_curve_build(RG2_MAX_DIM + 1, p, &s, &c, &err) == RG2_EINVAL && strstr(err.msg, "dimension"),
              "dimension %d accepted: %s", RG2_MAX_DIM + 1, err.msg);
        CHECK_OK(rg2_curve_build(RG2_MAX_DIM, p, &s, &c, &err), &err);
        for (int d = 0; d < RG2_MAX_DIM; d++) {
            for (int i = 0; i < N; i++)
                one[i] = p[i * RG2_MAX_DIM + d];
            CHECK_OK(rg2_curve_build(1, one, &s, &c1, &err), &err);
            for (int k = 0; k < c.n_segments; k++)
                for (int q = 0; q <= 4; q++) {
                    double x[3][RG2_MAX_DIM], y[3];
                    rg2_curve_eval(&c, k, q / 4.0, x[0], x[1], x[2]);
                    rg2_curve_eval(&c1, k, q / 4.0, &y[0], &y[1], &y[2]);
                    off += x[0][d] != y[0] || x[1][d] != y[1] || x[2][d] != y[2];
                }
            rg2_curve_free(&c1);
        }
        rg2_curve_free(&c);
        rg2_scalars_free(&s);
    }
    CHECK(built == 2 * RG2_MAX_DIM && off == 0, "dimensions 1 .. %d: %d of %d built, %d coordinates off their 1-D curves",
          RG2_MAX_DIM, built, 2 * RG2_MAX_DIM, off);
}

static void errors(void)
{
    rg2_scalars s;
    rg2_error err;
    rg2_curve c;
    double pts[20] = {0, 0, 1, 0, 1, 1, 0, 1, 0.5, 2};
    CHECK(rg2_scalars_init(&s, 3, 0, &err) == RG2_EINVAL && strstr(err.msg, "at least 4"),
          "too few open points: %s", err.msg);
    CHECK(rg2_scalars_init(&s, 2, 1, &err) == RG2_EINVAL && strstr(err.msg, "at least 3"),
          "too few closed points: %s", err.msg);
    CHECK_OK(rg2_scalars_init(&s, 5, 0, &err), &err);
    s.w[3] = 0.0;
    CHECK(rg2_curve_build(2, pts, &s, &c, &err) == RG2_EWEIGHT && strstr(err.msg, "w[2]"),
          "zero weight named: %s", err.msg);
    s.w[3] = NAN;
    CHECK(rg2_curve_build(2, pts, &s, &c, &err) == RG2_ENONFINITE && strstr(err.msg, "w[2]"),
          "NaN weight named: %s", err.msg);
    s.w[3] = 1.0;
    s.b[4] = -1.0;
    CHECK(rg2_curve_build(2, pts, &s, &c, &err) == RG2_EWEIGHT && strstr(err.msg, "b[4]"),
          "negative b named: %s", err.msg);
    s.b[4] = 1.0;
    s.g[2] = -4.5; /* K = 2 + 2 - 4.5 < 0 */
    CHECK(rg2_curve_build(2, pts, &s, &c, &err) == RG2_EWEIGHT && strstr(err.msg, "junction 2"),
          "K <= 0 named: %s", err.msg);
    s.g[2] = 0.0;
    pts[7] = INFINITY;
    CHECK(rg2_curve_build(2, pts, &s, &c, &err) == RG2_ENONFINITE && strstr(err.msg, "point 3"),
          "infinite point named: %s", err.msg);
    pts[7] = 1.0;
    CHECK(rg2_curve_build(0, pts, &s, &c, &err) == RG2_EINVAL, "dimension 0: %s", err.msg);
    rg2_scalars_free(&s);

    double bad[4] = {1.0, 2.0, M_PI, 0.5};
    CHECK(rg2_scalars_from_angles(&s, bad, 4, 1, &err) == RG2_EDOMAIN && strstr(err.msg, "arc 2"),
          "angle pi refused: %s", err.msg);
    bad[2] = -0.1;
    CHECK(rg2_scalars_from_angles(&s, bad, 4, 1, &err) == RG2_EDOMAIN && strstr(err.msg, "arc 2"),
          "negative angle refused: %s", err.msg);
    double cs[8], q[4] = {1.5, 1.5, 1.5, 1.5};
    CHECK(rg2_circle_coeffs(q, 4, 1, 0.0, cs, &err) == RG2_EDOMAIN && strstr(err.msg, "2 pi"),
          "closed circle not summing to 2 pi: %s", err.msg);
    double knots[7] = {0, 1, 2, 2, 3, 4, 5};
    CHECK(rg2_scalars_from_knots(&s, knots, 7, 0, &err) == RG2_EDOMAIN && strstr(err.msg, "interval 2"),
          "zero-length knot interval named: %s", err.msg);
    /* The message shows each knot with the fewest digits that read back as it (0.45, not
     * 0.45000000000000001; 1e+20 and 90 as such, not 9e+01). */
    double kd[7] = {0, 0.45, 0.45, 90, 1e20, 2e20, 3e20};
    CHECK(rg2_scalars_from_knots(&s, kd, 7, 0, &err) == RG2_EDOMAIN && strstr(err.msg, "interval 1 [0.45, 0.45]"),
          "knots shown shortest: %s", err.msg);
    kd[2] = 90, kd[3] = 90;
    CHECK(rg2_scalars_from_knots(&s, kd, 7, 0, &err) == RG2_EDOMAIN && strstr(err.msg, "interval 2 [90, 90]"),
          "knot 90 shown as 90: %s", err.msg);
    kd[1] = 0.1, kd[2] = 1.0 / 3.0, kd[3] = 1.0 / 3.0;
    CHECK(rg2_scalars_from_knots(&s, kd, 7, 0, &err) == RG2_EDOMAIN &&
              strstr(err.msg, "interval 2 [0.3333333333333333, 0.3333333333333333]"),
          "a third keeps its 16 digits: %s", err.msg);
    knots[3] = NAN;
    CHECK(rg2_scalars_from_knots(&s, knots, 7, 0, &err) == RG2_ENONFINITE && strstr(err.msg, "knot 3"),
          "NaN knot named: %s", err.msg);
    double a4[4] = {M_PI / 2, NAN, M_PI / 2, M_PI / 2};
    CHECK(rg2_scalars_from_angles(&s, a4, 4, 1, &err) == RG2_ENONFINITE &&
              !strcmp(err.msg, "arcs: angle of arc 1 is not finite"),
          "NaN angle named: %s", err.msg);
    a4[1] = M_PI;
    CHECK(rg2_circle_coeffs(a4, 4, 1, 0.0, cs, &err) == RG2_EDOMAIN &&
              strstr(err.msg, "arcs: arc 1 has opening angle 3.141592653589793 rad (180 deg); it must lie in (0, pi)"),
          "circle arc of pi named: %s", err.msg);
    a4[1] = INFINITY; /* as rg2_scalars_from_angles names it */
    CHECK(rg2_circle_coeffs(a4, 4, 1, 0.0, cs, &err) == RG2_ENONFINITE && !strcmp(err.msg, "arcs: angle of arc 1 is not finite"),
          "circle arc of inf named: %s", err.msg);
    /* open arcs (the first and last are the mirrored end arcs): a bad arc gets the same number
     * from rg2_circle_coeffs as from rg2_scalars_from_angles, for each position and kind */
    for (int k = 0; k < 4; k++)
        for (int kind = 0; kind < 2; kind++) {
            double a5[5] = {0.5, 0.6, 0.7, 0.8, 0.9};
            a5[k] = kind ? INFINITY : 3.5;
            rg2_error e1, e2;
            rg2_status s1 = rg2_scalars_from_angles(&s, a5, 5, 0, &e1);
            rg2_status s2 = rg2_circle_coeffs(a5, 5, 0, 0.0, cs, &e2);
            CHECK(s1 != RG2_OK && s1 == s2 && !strcmp(e1.msg, e2.msg) && strstr(e2.msg, "arc "),
                  "open arc %d (%g): from_angles '%s', circle_coeffs '%s'", k, a5[k], e1.msg, e2.msg);
        }
    a4[1] = 80.0 * M_PI / 180.0; /* a closed circle of 350 degrees */
    CHECK(rg2_circle_coeffs(a4, 4, 1, 0.0, cs, &err) == RG2_EDOMAIN &&
              strstr(err.msg, "sum to 2 pi; these sum to 6.1086523819801535 rad (350 deg)"),
          "closed circle short of 2 pi named in degrees: %s", err.msg);
    /* a closed circle's arcs sum to 2 pi to the relative RG2_CLOSED_SUM_TOL (rg2.h): 4 equal arcs
     * off by half of it either way are a circle, off by twice it are refused, and at the bound
     * itself off by 0.995 of it a circle, by 1.005 of it refused (the sum measured here, as the
     * arcs are passed: within 1 % of the bound, on its side) */
    const double by[4] = {0.5, 2.0, 0.995, 1.005};
    for (int t = 0; t < 8; t++) {
        double f = by[t / 2], rel = (t & 1 ? -1 : 1) * f * RG2_CLOSED_SUM_TOL, sum = 0;
        for (int k = 0; k < 4; k++)
            sum += (a4[k] = M_PI / 2 * (1 + rel));
        double off = fabs(sum - 2 * M_PI) / (2 * M_PI), within = t < 4 ? 0.6 * f : 0.005;
        rg2_status st = rg2_circle_coeffs(a4, 4, 1, 0.0, cs, &err);
        CHECK(fabs(off / RG2_CLOSED_SUM_TOL - f) < within && (off > RG2_CLOSED_SUM_TOL) == (f > 1) &&
                  (f > 1 ? st == RG2_EDOMAIN && strstr(err.msg, "sum to 2 pi") : st == RG2_OK),
              "4 arcs summing to 2 pi (1 %+.6g): %s '%s'", (sum - 2 * M_PI) / (2 * M_PI), rg2_status_str(st),
              st ? err.msg : "");
    }
    for (int k = 0; k < 4; k++)
        a4[k] = M_PI / 2;
    CHECK(rg2_circle_coeffs(a4, 4, 1, NAN, cs, &err) == RG2_ENONFINITE && !strcmp(err.msg, "arcs: start angle is not finite"),
          "NaN start angle: %s", err.msg);
    /* too few or too many values: the message tells the count the caller passed and the minimum in
     * the same unit (it spoke of the control points they make: "-3 control points" for n_knots = -1,
     * "0 control points" for 2 knots, "arcs: -4 control points" for n_alpha = -3) */
    static const struct {
        int fn, n, closed; /* fn 0 rg2_scalars_from_knots, 1 rg2_scalars_from_angles, 2 rg2_circle_coeffs */
        rg2_status st;
        const char *msg;
    } counts[] = {
        {0, -1, 0, RG2_EINVAL, "knots: -1 knots given, an open direction needs at least 6 (4 control points, 1 segment)"},
        {0, 2, 0, RG2_EINVAL, "knots: 2 knots given, an open direction needs at least 6 (4 control points, 1 segment)"},
        {0, 5, 0, RG2_EINVAL, "knots: 5 knots given, an open direction needs at least 6 (4 control points, 1 segment)"},
        {0, 3, 1, RG2_EINVAL, "knots: 3 knots given, a closed direction needs at least 4 (3 control points, 3 segments)"},
        {0, INT_MIN, 1, RG2_EINVAL,
         "knots: -2147483648 knots given, a closed direction needs at least 4 (3 control points, 3 segments)"},
        {0, RG2_MAX_POINTS + 3, 0, RG2_ELIMIT, "knots: 4000003 knots given, more than the limit 4000002 (4000000 control points)"},
        {1, 4, 0, RG2_EINVAL, "arcs: 4 arcs given, an open direction needs at least 5 (4 control points, 1 segment)"},
        {1, 0, 1, RG2_EINVAL, "arcs: 0 arcs given, a closed direction needs at least 3 (3 control points, 3 segments)"},
        {1, RG2_MAX_POINTS + 1, 1, RG2_ELIMIT, "arcs: 4000001 arcs given, more than the limit 4000000 (4000000 control points)"},
        {2, -3, 0, RG2_EINVAL, "arcs: -3 arcs given, an open direction needs at least 5 (4 control points, 1 segment)"},
        {2, 2, 1, RG2_EINVAL, "arcs: 2 arcs given, a closed direction needs at least 3 (3 control points, 3 segments)"},
    };
    for (size_t t = 0; t < sizeof counts / sizeof counts[0]; t++) {
        int n = counts[t].n, cl = counts[t].closed;
        rg2_status st = counts[t].fn == 0   ? rg2_scalars_from_knots(&s, knots, n, cl, &err)
                        : counts[t].fn == 1 ? rg2_scalars_from_angles(&s, a4, n, cl, &err)
                                            : rg2_circle_coeffs(a4, n, cl, 0.0, cs, &err);
        CHECK(st == counts[t].st && !strcmp(err.msg, counts[t].msg), "count %d (fn %d, closed %d): %s '%s', want '%s'",
              n, counts[t].fn, cl, rg2_status_str(st), err.msg, counts[t].msg);
    }
    /* counts near INT_MIN are too few points: n_knots - 2 and n_alpha - 1 overflowed to a count
     * past the limit (RG2_ELIMIT, "2147483646 control points") */
    CHECK(rg2_scalars_from_knots(&s, knots, INT_MIN, 0, &err) == RG2_EINVAL && strstr(err.msg, "at least 6"),
          "INT_MIN open knots: %s", err.msg);
    CHECK(rg2_scalars_from_knots(&s, knots, INT_MIN, 1, &err) == RG2_EINVAL && strstr(err.msg, "at least 4"),
          "INT_MIN closed knots: %s", err.msg);
    CHECK(rg2_scalars_from_angles(&s, a4, INT_MIN, 0, &err) == RG2_EINVAL && strstr(err.msg, "at least 5"),
          "INT_MIN open arcs: %s", err.msg);
    CHECK(rg2_circle_coeffs(a4, INT_MIN, 0, 0.0, cs, &err) == RG2_EINVAL && strstr(err.msg, "at least 5"),
          "INT_MIN open circle arcs: %s", err.msg);
    /* finite arcs and knots whose scalars leave the double range: they came back RG2_OK with
     * b = inf (an arc of 1e-320 next to one of 2) or K = inf (intervals 1e-300 and 1) */
    double tiny[3] = {1e-320, 2.0, 2.0}, wide[6] = {0, 1e-300, 1, 2, 3, 4};
    CHECK(rg2_scalars_from_angles(&s, tiny, 3, 1, &err) == RG2_EDOMAIN && !s.b &&
              !strcmp(err.msg, "arcs: arcs 0 and 1 (angles 1e-320 and 2) give junction 1 b = inf, g = inf, "
                               "K = inf: b, g and K are out of the double range"),
          "arc of 1e-320: %s", err.msg);
    CHECK(rg2_scalars_from_knots(&s, wide, 6, 0, &err) == RG2_EDOMAIN && !s.b &&
              !strcmp(err.msg, "knots: the knot intervals knots[0..1] = [0, 1e-300] and knots[1..2] = [1e-300, 1] "
                               "(junction 0) give b = 1e+300, g = 0, K = inf: K is out of the double range"),
          "knot intervals 1e-300 and 1: %s", err.msg);
    CHECK_OK(rg2_scalars_init(&s, 4, 1, &err), &err);
    s.g[1] = NAN;
    CHECK(rg2_scalars_check(&s, "v", &err) == RG2_ENONFINITE && !strcmp(err.msg, "v: scalar g[1] is not finite"),
          "NaN g named: %s", err.msg);
    s.g[1] = 0;
    CHECK(rg2_scalars_check(&s, NULL, &err) == RG2_OK, "a NULL prefix: %s", err.msg);
    rg2_scalars_free(&s);
}

int main(void)
{
    closed_flags();
    random_curves();
    small_weights();
    polynomial_mode();
    circles();
    closed_knots();
    curve_curvature();
    dimensions();
    errors();
    return rg2t_done("test_curve");
}
