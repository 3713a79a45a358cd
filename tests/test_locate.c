/* test_locate.c -- picking (rg2_locator_closest, rg2_locator_ray), measured against answers
 * found without rg2's patches:
 *   - the torus: the nearest point and the distance in closed form, and the first root of the
 *     torus's implicit equation along the ray (sign change on fine steps, then bisection);
 *   - a band of the unit sphere (its poles collapsed rows outside the band): closed forms;
 *   - the same torus with some patches raised to degree (5, 4) (the higher-degree path);
 *   - every example design: dense tessellation vertices for the nearest point (the answer may
 *     not be farther than any of them, and none may be nearer than the proven bound), and ray
 *     hits on the tessellation's triangles (the exact first hit is on the ray and on the
 *     surface, and not after a clear triangle hit);
 *   - feet 0 to 1e-5 from every seam of the torus (the wrapping ones too) against the closed
 *     form, and rays aimed exactly at patch corners and sides against the implicit equation;
 *   - the degenerate queries (a sphere's centre, a torus's core circle and axis) stop with a
 *     true answer and an honest bound (within the proof docs/picking.md gives at the budget);
 *     rays within 1e-300 of an axis, |d| != 1 with a finite tmax; and every refusal names its
 *     item (NaN and infinities, weights 0 and below, no patches in one direction);
 *   - the convexity certificates the nearest-point search rules regions out with, by
 *     themselves: on the torus, the degree-raised torus and every example surface, for random
 *     points, bases, radii and levels c, a certificate's bound over a random rectangle may not
 *     lie above the distance at any of 17 x 17 points of it; based at the true foot, it proves
 *     the distance over its whole rectangle to within the search's tolerance. The rays' likewise:
 *     for rays through one or two chosen points of a patch, no rectangle holding such a point
 *     may be ruled out before its t; at a torus hit, the rectangle is proven to half the
 *     tolerance and the rest of it holds no hit. */
#include "harness.h"
#include "../src/internal.h" /* rg2__locate_cert: the nearest-point search's certificates */

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

static double dot(const double *a, const double *b) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }
static double dist3(const double *a, const double *b)
{
    double d[3] = {a[0] - b[0], a[1] - b[1], a[2] - b[2]};
    return sqrt(dot(d, d));
}

/* ---------------------------------------------------------------- torus */

static const double TR = 2.5, Tr = 0.75;

static double torus_F(const double q[3])
{
    double s = dot(q, q) + TR * TR - Tr * Tr;
    return s * s - 4 * TR * TR * (q[0] * q[0] + q[1] * q[1]);
}

/* First t in [0, T] with F(o + t d) = 0: a sign change over n steps, then bisection; -1 if none. */
static double torus_first_root(const double o[3], const double d[3], double T, int n)
{
    double q[3], tp = 0, fp;
    for (int k = 0; k < 3; k++)
        q[k] = o[k];
    fp = torus_F(q);
    for (int s = 1; s <= n; s++) {
        double t = T * s / n;
        for (int k = 0; k < 3; k++)
            q[k] = o[k] + t * d[k];
        double f = torus_F(q);
        if ((f > 0) != (fp > 0)) {
            double a = tp, b = t;
            for (int it = 0; it < 200 && b - a > 0; it++) {
                double m = 0.5 * (a + b);
                if (m <= a || m >= b)
                    break;
                for (int k = 0; k < 3; k++)
                    q[k] = o[k] + m * d[k];
                if ((torus_F(q) > 0) == (fp > 0))
                    a = m;
                else
                    b = m;
            }
            return 0.5 * (a + b);
        }
        tp = t, fp = f;
    }
    return -1;
}

/* The tolerance the header states for a query from x: 1e-10 of (the diagonal of the surface's
 * control box + the distance from x to the box's centre). */
static double tolerance(const rg2_surface *s, const double x[3])
{
    double lo[3], hi[3], c[3];
    rg2_surface_box(s, lo, hi);
    for (int k = 0; k < 3; k++)
        c[k] = 0.5 * (lo[k] + hi[k]);
    return 1e-10 * (dist3(lo, hi) + dist3(x, c));
}

static void torus_case(const rg2_surface *s, const char *what, int queries, int rays)
{
    rg2_error err;
    rg2_locator *L;
    CHECK_OK(rg2_locator_build(s, &L, &err), &err);
    if (!L)
        return;
    rg2t_rng rng;
    rg2t_seed(&rng, 11);
    const double scale = 2 * (TR + Tr);
    double wd = 0, wp = 0, wn = 0, wb = 0;
    int n = 0;
    while (n < queries) {
        double x[3] = {rg2t_uniform(&rng, -4, 4), rg2t_uniform(&rng, -4, 4), rg2t_uniform(&rng, -2, 2)};
        double rho = hypot(x[0], x[1]), tube = hypot(rho - TR, x[2]);
        if (rho < 0.05 || tube < 0.05)
            continue; /* (equidistant from a circle: the degenerate queries below) */
        n++;
        double c[3] = {TR * x[0] / rho, TR * x[1] / rho, 0}; /* the core circle's nearest point */
        double f[3];
        for (int k = 0; k < 3; k++)
            f[k] = c[k] + Tr * (x[k] - c[k]) / tube;
        rg2_hit h;
        CHECK_OK(rg2_locator_closest(L, x, &h, &err), &err);
        wd = fmax(wd, fabs(h.dist - fabs(tube - Tr)) / scale);
        wp = fmax(wp, dist3(h.p, f) / scale);
        double no[3] = {(f[0] - c[0]) / Tr, (f[1] - c[1]) / Tr, (f[2] - c[2]) / Tr};
        wn = fmax(wn, 1 - fabs(dot(no, h.n)));
        CHECK(h.bound <= h.dist, "%s: bound %.17g above the distance %.17g", what, h.bound, h.dist);
        wb = fmax(wb, (h.dist - h.bound) / tolerance(s, x));
    }
    printf("%s: %d nearest points: distance %.2e, point %.2e, normal 1-|cos| %.2e (relative); proven to %.2f of the "
           "tolerance\n", what,
           queries, wd, wp, wn, wb);
    CHECK(wd <= 1e-14, "%s: nearest distance off by %.3g of the size", what, wd);
    CHECK(wp <= 1e-12, "%s: nearest point off by %.3g of the size", what, wp);
    CHECK(wn <= 1e-12, "%s: normal at the nearest point off by %.3g", what, wn);
    CHECK(wb <= 1, "%s: bound below the distance by %.3g of the tolerance", what, wb);

    double wt = 0, wr = 0, wtb = 0;
    int hits = 0, agree = 0;
    for (int q = 0; q < rays; q++) {
        /* from a point outside toward a random point of the torus's box (some miss) */
        double o[3], tgt[3], d[3];
        double az = rg2t_uniform(&rng, 0, 2 * M_PI), el = rg2t_uniform(&rng, -1.2, 1.2);
        o[0] = 8 * cos(el) * cos(az), o[1] = 8 * cos(el) * sin(az), o[2] = 8 * sin(el);
        tgt[0] = rg2t_uniform(&rng, -3.3, 3.3), tgt[1] = rg2t_uniform(&rng, -3.3, 3.3);
        tgt[2] = rg2t_uniform(&rng, -0.8, 0.8);
        double sc = rg2t_uniform(&rng, 0.25, 4); /* t in units of a direction of any length */
        for (int k = 0; k < 3; k++)
            d[k] = sc * (tgt[k] - o[k]);
        /* the roots lie where the ray is inside the ball of radius TR + Tr */
        double A = dot(d, d), B = dot(o, d), C = dot(o, o) - (TR + Tr) * (TR + Tr), D = B * B - A * C;
        double tref = D > 0 ? torus_first_root(o, d, (-B + sqrt(D)) / A, 40000) : -1;
        rg2_hit h;
        CHECK_OK(rg2_locator_ray(L, o, d, INFINITY, &h, &err), &err);
        if (h.i >= 0) {
            hits++;
            double on[3];
            for (int k = 0; k < 3; k++)
                on[k] = o[k] + h.dist * d[k];
            wr = fmax(wr, dist3(on, h.p) / scale); /* on the ray */
            CHECK(h.bound <= h.dist, "%s ray %d: bound %.17g above t %.17g", what, q, h.bound, h.dist);
            wtb = fmax(wtb, (h.dist - h.bound) * sqrt(dot(d, d)) / tolerance(s, o));
        }
        if ((h.i >= 0) == (tref >= 0)) {
            agree++;
            if (tref >= 0)
                wt = fmax(wt, fabs(h.dist - tref) * sqrt(dot(d, d)) / scale);
        } else
            fprintf(stderr, "%s ray %d: rg2 %s (t %.17g), the implicit equation %s (t %.17g)\n", what, q,
                    h.i >= 0 ? "hits" : "misses", h.dist, tref >= 0 ? "hits" : "misses", tref);
    }
    printf("%s: %d rays, %d hit: first hit t %.2e, on the ray %.2e (relative); proven to %.2f of the tolerance\n",
           what, rays, hits,
           wt, wr, wtb);
    CHECK(agree == rays, "%s: %d of %d rays agree with the implicit equation on hit or miss", what, agree, rays);
    CHECK(hits > rays / 4 && hits < rays, "%s: %d of %d rays hit (the test should have both)", what, hits, rays);
    CHECK(wt <= 1e-13, "%s: first hit off by %.3g of the size", what, wt);
    CHECK(wr <= 1e-14, "%s: hit point off the ray by %.3g of the size", what, wr);
    CHECK(wtb <= 1, "%s: ray bound below the hit by %.3g of the tolerance", what, wtb);

    /* a ray from inside the tube, along +x from the core circle: t = Tr / |d| */
    double o[3] = {TR, 0, 0}, d[3] = {2, 0, 0};
    rg2_hit h;
    CHECK_OK(rg2_locator_ray(L, o, d, INFINITY, &h, &err), &err);
    CHECK(fabs(h.dist - Tr / 2) <= 1e-14 && h.i >= 0, "%s: from inside, t %.17g (want %.17g)", what, h.dist, Tr / 2);
    /* tmax before the hit: a miss, with bound tmax */
    CHECK_OK(rg2_locator_ray(L, o, d, 0.3, &h, &err), &err);
    CHECK(h.i < 0 && h.bound == 0.3 && h.dist == INFINITY, "%s: tmax 0.3 before the hit 0.375: i %d bound %g", what,
          h.i, h.bound);
    /* tmax exactly at the hit: the hit (0 <= t <= tmax); a ray from a surface point with
     * tmax = 0: that point, at t = 0 (the mutation pass's defect: both were misses) */
    CHECK_OK(rg2_locator_ray(L, o, d, Tr / 2, &h, &err), &err);
    CHECK(h.i >= 0 && fabs(h.dist - Tr / 2) <= 1e-14, "%s: tmax = the hit's t 0.375: i %d, t %.17g, bound %.17g", what,
          h.i, h.dist, h.bound);
    /* (the surface's own point at its corner (0, 0), near (R + r, 0, 0): on the torus of 120 x 90
     * patches, x is 3.2499999999999996 there, and from (3.25, 0, 0) the hit lies 4e-16 ahead) */
    rg2_eval ev;
    rg2_surface_eval(s, 0, 0, 0, 0, 0, &ev);
    double on_s[3] = {ev.p[0], ev.p[1], ev.p[2]}, back[3] = {-1, 0, 0};
    CHECK_OK(rg2_locator_ray(L, on_s, back, 0.0, &h, &err), &err);
    CHECK(h.i >= 0 && h.dist == 0 && fabs(h.p[0] - (TR + Tr)) <= 1e-14, "%s: from a surface point, tmax 0: i %d, t %.17g",
          what, h.i, h.dist);
    /* from outside, |d| = 2, tmax just past the hit: the outer equator at t = (8 - R - r) / 2 */
    double o3[3] = {8, 0, 0}, d3[3] = {-2, 0, 0};
    CHECK_OK(rg2_locator_ray(L, o3, d3, 2.4, &h, &err), &err);
    CHECK(h.i >= 0 && fabs(h.dist - (8 - TR - Tr) / 2) <= 1e-14, "%s: |d| = 2, tmax 2.4: i %d t %.17g (want %.17g)",
          what, h.i, h.dist, (8 - TR - Tr) / 2);
    /* tmax one ulp past the hit (within the tolerance of it, where the search must still take
     * the first hit): from inside the tube the hit t = 3 / 8 is exact in binary, and so from
     * outside with |d| = 2: t = 19 / 8 */
    CHECK_OK(rg2_locator_ray(L, o, d, nextafter(Tr / 2, 1), &h, &err), &err);
    CHECK(h.i >= 0 && fabs(h.dist - Tr / 2) <= 1e-14, "%s: tmax an ulp past the hit t %g: i %d t %.17g", what, Tr / 2,
          h.i, h.dist);
    CHECK_OK(rg2_locator_ray(L, o3, d3, nextafter((8 - TR - Tr) / 2, 3), &h, &err), &err);
    CHECK(h.i >= 0 && fabs(h.dist - (8 - TR - Tr) / 2) <= 1e-14,
          "%s: tmax an ulp past the hit t %g from outside: i %d t %.17g", what, (8 - TR - Tr) / 2, h.i, h.dist);
    /* from a point of the surface (the outer equator's patch corner) into the tube: o itself is
     * the first hit, t = 0 */
    double o4[3] = {TR + Tr, 0, 0}, d4[3] = {-1, 0, 0};
    CHECK_OK(rg2_locator_ray(L, o4, d4, INFINITY, &h, &err), &err);
    CHECK(h.i >= 0 && fabs(h.dist) <= 1e-15, "%s: from a surface point: i %d t %.17g (want 0)", what, h.i, h.dist);
    /* tangent to the top circle (z = r) at (-R, 0, r): the ray touches the torus there, t = 5 - R
     * to the conditioning of a touch (rounding puts the surface on the ray over about
     * sqrt(DBL_EPSILON) r); the point on the ray and on the torus */
    double o5[3] = {-5, 0, Tr}, d5[3] = {1, 0, 0};
    CHECK_OK(rg2_locator_ray(L, o5, d5, INFINITY, &h, &err), &err);
    CHECK(h.i >= 0 && fabs(h.dist - (5 - TR)) <= 1e-6 && fabs(h.p[2] - Tr) <= 1e-14 && fabs(h.p[1]) <= 1e-14,
          "%s: a tangent ray: i %d t %.17g (want %g), p (%g, %g, %.17g)", what, h.i, h.dist, 5 - TR, h.p[0], h.p[1],
          h.p[2]);
    /* away from everything: a miss with bound tmax = INFINITY */
    double o2[3] = {0, 0, 5}, d2[3] = {0, 0, 1};
    CHECK_OK(rg2_locator_ray(L, o2, d2, INFINITY, &h, &err), &err);
    CHECK(h.i < 0 && h.bound == INFINITY, "%s: a ray away from the torus: i %d bound %g", what, h.i, h.bound);

    /* degenerate: on the core circle every tube point is at Tr; on the axis every point of the
     * circle nearest the axis is at hypot(TR, 0.3) - Tr. The answer is true, the bound honest. */
    double xs[2][3] = {{0, TR, 0}, {0, 0, 0.3}}, want[2] = {Tr, hypot(TR, 0.3) - Tr};
    for (int k = 0; k < 2; k++) {
        CHECK_OK(rg2_locator_closest(L, xs[k], &h, &err), &err);
        CHECK(fabs(h.dist - want[k]) <= 1e-14 * scale && h.bound <= h.dist && h.bound > 0.99 * want[k],
              "%s: degenerate query %d: distance %.17g (want %.17g), bound %.17g", what, k, h.dist, want[k], h.bound);
        printf("%s: degenerate query %d (%s): distance off by %.2e, proven to %.2e\n", what, k,
               k ? "on the axis" : "on the core circle", fabs(h.dist - want[k]), h.dist - h.bound);
    }
    rg2_locator_free(L);
}

/* ---------------------------------------------------------------- feet next to the patch seams */

/* Query points whose foot lies 0 to 1e-5 (in angle) to either side of every patch seam of the
 * torus, the seams where the closed directions wrap included, inside and outside the tube. The
 * foot is the torus point at those angles (closed form). Newton started in the patch next to the
 * foot's ends on the shared side, a point whose distance is within the tolerance of the answer's
 * (second order) but up to 1e-5 away from it: only the hop into the right neighbour (across the
 * wrap too) finds the foot itself. */
static void seam_feet(void)
{
    rg2_error err;
    rg2_surface s;
    CHECK_OK(rg2t_torus(TR, Tr, 8, 6, NULL, &s, &err), &err);
    rg2_locator *L;
    CHECK_OK(rg2_locator_build(&s, &L, &err), &err);
    const double scale = 2 * (TR + Tr), off[2] = {-0.3, 0.5};
    const double eps[11] = {0, 1e-8, -1e-8, 1e-7, -1e-7, 1e-6, -1e-6, 3e-6, -3e-6, 1e-5, -1e-5};
    double wp = 0, wd = 0;
    int queries = 0;
    for (int dir = 0; dir < 2; dir++) {
        int nseam = dir ? s.nv : s.nu;
        for (int k = 0; k < nseam; k++)
            for (int w = 1; w <= (k ? 3 : 15); w++) { /* (more along the seams that wrap) */
                /* a point of the seam (side u = 0 of patch column k, or v = 0 of patch row k),
                 * and the angle constant along it */
                double t = (k ? 0.25 : 0.0625) * w, pt[2][3];
                for (int e = 0; e < 2; e++) {
                    rg2_eval ev;
                    double t2 = e ? t : 0.5 * t;
                    if (dir)
                        rg2_surface_eval(&s, (k * 5 + w) % s.nu, k, t2, 0, 0, &ev);
                    else
                        rg2_surface_eval(&s, k, (k * 5 + w) % s.nv, 0, t2, 0, &ev);
                    memcpy(pt[e], ev.p, sizeof ev.p);
                }
                double ang[2][2];
                for (int e = 0; e < 2; e++) {
                    ang[e][0] = atan2(pt[e][1], pt[e][0]);
                    ang[e][1] = atan2(pt[e][2], hypot(pt[e][0], pt[e][1]) - TR);
                }
                int along = fabs(ang[0][0] - ang[1][0]) < 1e-12 ? 0 : 1; /* the seam's constant angle */
                CHECK(fabs(ang[0][along] - ang[1][along]) < 1e-12, "seam %d/%d: no constant angle", dir, k);
                for (int q = 0; q < 11; q++)
                    for (int h = 0; h < 2; h++, queries++) {
                        double phi = ang[1][0] + (along ? 0 : eps[q]), th = ang[1][1] + (along ? eps[q] : 0);
                        double f[3] = {(TR + Tr * cos(th)) * cos(phi), (TR + Tr * cos(th)) * sin(phi), Tr * sin(th)};
                        double n[3] = {cos(th) * cos(phi), cos(th) * sin(phi), sin(th)}, x[3];
                        for (int c = 0; c < 3; c++)
                            x[c] = f[c] + off[h] * n[c];
                        rg2_hit hit;
                        CHECK_OK(rg2_locator_closest(L, x, &hit, &err), &err);
                        wp = fmax(wp, dist3(hit.p, f) / scale);
                        wd = fmax(wd, fabs(hit.dist - fabs(off[h])) / scale);
                        CHECK(dist3(hit.p, f) <= 1e-12 * scale && hit.bound <= hit.dist,
                              "seam foot (%s seam %d, angle %+g): point %.3g from the foot, distance %.17g (want "
                              "%.17g)",
                              dir ? "v" : "u", k, eps[q], dist3(hit.p, f), hit.dist, fabs(off[h]));
                    }
            }
    }
    printf("seam feet: %d nearest points 0 to 1e-5 from a seam: point %.2e, distance %.2e (relative)\n", queries, wp,
           wd);
    rg2_locator_free(L);
    rg2_surface_free(&s);
}

/* ---------------------------------------------------------------- rays through patch corners and sides */

/* Rays aimed exactly at a patch corner or at a point of a patch side of the torus (where four or
 * two pieces meet, each with the aimed point on its border): straight down the normal and
 * oblique, from 0.5 outside. The first hit is that point, at t = 1 (the implicit equation's first
 * root agrees): no ray may slip between the pieces through rounding. */
static void seam_rays(int elevate)
{
    rg2_error err;
    rg2_surface s;
    CHECK_OK(rg2t_torus(TR, Tr, 8, 6, NULL, &s, &err), &err);
    if (elevate) /* (neighbours of different degrees) */
        CHECK_OK(rg2t_elevate_some(&s, 5, 4, 3, 1, &err), &err);
    rg2_locator *L;
    CHECK_OK(rg2_locator_build(&s, &L, &err), &err);
    const double uv[3][2] = {{0, 0}, {0, 0.375}, {0.625, 0}}, tilt[3] = {0, 0.3, -0.45};
    double wt = 0;
    int rays = 0;
    for (int i = 0; i < s.nu; i++)
        for (int j = 0; j < s.nv; j++)
            for (int a = 0; a < 3; a++)
                for (int b = 0; b < 3; b++, rays++) {
                    rg2_eval e;
                    rg2_surface_eval(&s, i, j, uv[a][0], uv[a][1], 1, &e);
                    /* the outward normal from the closed form, a tangent across it */
                    double rho = hypot(e.p[0], e.p[1]), c[3] = {TR * e.p[0] / rho, TR * e.p[1] / rho, 0}, n[3], tg[3];
                    for (int k = 0; k < 3; k++)
                        n[k] = (e.p[k] - c[k]) / Tr;
                    tg[0] = -e.p[1] / rho, tg[1] = e.p[0] / rho, tg[2] = 0;
                    double o[3], d[3];
                    for (int k = 0; k < 3; k++) {
                        o[k] = e.p[k] + 0.5 * n[k] + tilt[b] * (b == 2 ? n[(k + 1) % 3] : tg[k]);
                        d[k] = e.p[k] - o[k];
                    }
                    rg2_hit h;
                    CHECK_OK(rg2_locator_ray(L, o, d, INFINITY, &h, &err), &err);
                    double tref = torus_first_root(o, d, 1.5, 3000);
                    CHECK(fabs(tref - 1) <= 1e-9, "corner ray (%d,%d) %d %d: the implicit equation's root %.17g", i, j,
                          a, b, tref);
                    CHECK(h.i >= 0 && fabs(h.dist - 1) <= 1e-13 && dist3(h.p, e.p) <= 1e-13,
                          "ray at patch (%d,%d) (u, v) = (%g, %g), tilt %d: i %d t %.17g (want 1), %.3g from it", i, j,
                          uv[a][0], uv[a][1], b, h.i, h.dist, dist3(h.p, e.p));
                    if (h.i >= 0)
                        wt = fmax(wt, fabs(h.dist - 1));
                }
    printf("seam rays%s: %d rays at patch corners and sides: t %.2e\n",
           elevate ? " (some patches of degree (5, 4))" : "", rays, wt);
    rg2_locator_free(L);
    rg2_surface_free(&s);
}

/* ---------------------------------------------------------------- sphere band */

static void sphere_band(void)
{
    double a[5], v[4] = {0.15, 0.4, 0.6, 0.85};
    for (int k = 0; k < 5; k++)
        a[k] = 2 * M_PI / 5;
    rg2_mesh m;
    rg2_surface s;
    rg2_error err;
    CHECK_OK(rg2_polar_sphere_mesh(a, 5, 0.3, v, 4, NULL, &m, &err), &err);
    CHECK_OK(rg2_surface_build(&m, &s, &err), &err);
    rg2_mesh_free(&m);
    /* the band's z range: its v = 0 and v = 1 sides are circles of constant z */
    rg2_eval e0, e1;
    rg2_surface_eval(&s, 0, 0, 0.3, 0.0, 0, &e0);
    rg2_surface_eval(&s, 0, s.nv - 1, 0.3, 1.0, 0, &e1);
    double zlo = fmin(e0.p[2], e1.p[2]), zhi = fmax(e0.p[2], e1.p[2]);
    rg2_locator *L;
    CHECK_OK(rg2_locator_build(&s, &L, &err), &err);
    rg2t_rng rng;
    rg2t_seed(&rng, 12);
    double wd = 0, wp = 0, wt = 0;
    int n = 0, rays = 0, hits = 0;
    while (n < 1000) {
        double x[3] = {rg2t_uniform(&rng, -2, 2), rg2t_uniform(&rng, -2, 2), rg2t_uniform(&rng, -2, 2)};
        double r = sqrt(dot(x, x));
        if (r < 0.05 || x[2] / r < zlo + 0.02 || x[2] / r > zhi - 0.02)
            continue;
        n++;
        rg2_hit h;
        CHECK_OK(rg2_locator_closest(L, x, &h, &err), &err);
        double f[3] = {x[0] / r, x[1] / r, x[2] / r};
        wd = fmax(wd, fabs(h.dist - fabs(r - 1)));
        wp = fmax(wp, dist3(h.p, f));
    }
    while (rays < 1000) { /* rays from outside through the band's inside */
        double o[3] = {rg2t_uniform(&rng, -3, 3), rg2t_uniform(&rng, -3, 3), rg2t_uniform(&rng, -3, 3)};
        double tg[3] = {rg2t_uniform(&rng, -0.9, 0.9), rg2t_uniform(&rng, -0.9, 0.9), rg2t_uniform(&rng, -0.9, 0.9)};
        double d[3] = {tg[0] - o[0], tg[1] - o[1], tg[2] - o[2]};
        if (dot(o, o) < 1.5)
            continue;
        /* |o + t d|^2 = 1: the two roots; the first whose point is in the band */
        double A = dot(d, d), B = dot(o, d), C = dot(o, o) - 1, D = B * B - A * C;
        if (D <= 0)
            continue;
        double t1 = (-B - sqrt(D)) / A, t2 = (-B + sqrt(D)) / A, want = -1;
        double z1 = o[2] + t1 * d[2], z2 = o[2] + t2 * d[2];
        if (fabs(z1 - zlo) < 1e-6 || fabs(z1 - zhi) < 1e-6 || fabs(z2 - zlo) < 1e-6 || fabs(z2 - zhi) < 1e-6)
            continue;
        if (t1 >= 0 && z1 > zlo && z1 < zhi)
            want = t1;
        else if (t2 >= 0 && z2 > zlo && z2 < zhi)
            want = t2;
        rays++;
        rg2_hit h;
        CHECK_OK(rg2_locator_ray(L, o, d, INFINITY, &h, &err), &err);
        CHECK((h.i >= 0) == (want >= 0), "sphere band ray %d: rg2 t %.17g, closed form %.17g", rays, h.dist, want);
        if (h.i >= 0 && want >= 0) {
            hits++;
            wt = fmax(wt, fabs(h.dist - want) * sqrt(A));
        }
    }
    printf("sphere band: 1000 nearest points: distance %.2e, point %.2e; 1000 rays (%d through the band): t %.2e\n",
           wd, wp, hits, wt);
    CHECK(wd <= 1e-14 && wp <= 1e-12, "sphere band: nearest distance %.3g, point %.3g", wd, wp);
    CHECK(wt <= 1e-13 && hits > 300, "sphere band: ray t %.3g (%d hits)", wt, hits);
    rg2_locator_free(L);
    rg2_surface_free(&s);
}

/* ---------------------------------------------------------------- examples, against a tessellation */

static void tri_hit(const double *A, const double *B, const double *C, const double o[3], const double d[3],
                    double *t, double *cosang)
{
    double e1[3], e2[3], p[3], q[3], s[3];
    for (int k = 0; k < 3; k++)
        e1[k] = B[k] - A[k], e2[k] = C[k] - A[k], s[k] = o[k] - A[k];
    p[0] = d[1] * e2[2] - d[2] * e2[1], p[1] = d[2] * e2[0] - d[0] * e2[2], p[2] = d[0] * e2[1] - d[1] * e2[0];
    double det = dot(e1, p);
    if (fabs(det) < 1e-300)
        return;
    double uu = dot(s, p) / det;
    if (uu < 0 || uu > 1)
        return;
    q[0] = s[1] * e1[2] - s[2] * e1[1], q[1] = s[2] * e1[0] - s[0] * e1[2], q[2] = s[0] * e1[1] - s[1] * e1[0];
    double vv = dot(d, q) / det;
    if (vv < 0 || uu + vv > 1)
        return;
    double tt = dot(e2, q) / det;
    if (tt >= 0 && tt < *t) {
        double nn[3] = {e1[1] * e2[2] - e1[2] * e2[1], e1[2] * e2[0] - e1[0] * e2[2], e1[0] * e2[1] - e1[1] * e2[0]};
        *t = tt;
        *cosang = fabs(dot(nn, d)) / sqrt(dot(nn, nn) * dot(d, d));
    }
}

static void examples(void)
{
    char *names[64];
    int ne = rg2t_example_names(names, 64);
    CHECK(ne >= 10, "examples: %d designs found", ne);
    double wworse = 0, wbelow = 0, wray = 0, wlate = 0;
    int surfaces = 0, queries = 0, nrays = 0, clear = 0;
    for (int k = 0; k < ne; k++) {
        const char *path = names[k];
        rg2_design *d = NULL;
        rg2_error err;
        CHECK_OK(rg2_design_load(path, &d, &err), &err);
        for (int o = 0; d && o < rg2_design_num_surfaces(d); o++) {
            const rg2_surface *s = rg2_design_surface(d, o);
            rg2_tess t;
            rg2_locator *L = NULL;
            if ((long)s->nu * s->nv > 3000)
                continue;
            CHECK_OK(rg2_tessellate(s, 12, 0, &t, &err), &err);
            CHECK_OK(rg2_locator_build(s, &L, &err), &err);
            if (!L) {
                rg2_tess_free(&t);
                continue;
            }
            surfaces++;
            double lo[3], hi[3];
            rg2_surface_box(s, lo, hi);
            double scale = dist3(lo, hi);
            rg2t_rng rng;
            rg2t_seed(&rng, 100 + 7 * k + o);
            for (int q = 0; q < 12; q++, queries++) {
                double x[3];
                for (int c = 0; c < 3; c++)
                    x[c] = rg2t_uniform(&rng, lo[c] - 0.2 * (hi[c] - lo[c]), hi[c] + 0.2 * (hi[c] - lo[c]));
                rg2_hit h;
                CHECK_OK(rg2_locator_closest(L, x, &h, &err), &err);
                double vmin = INFINITY;
                for (int v = 0; v < t.n_vertices; v++)
                    vmin = fmin(vmin, dist3(t.pos + 3 * v, x));
                /* not farther than any vertex (a point of the surface); none nearer than bound */
                wworse = fmax(wworse, (h.dist - vmin) / scale);
                wbelow = fmax(wbelow, (h.bound - vmin) / scale);
                CHECK(h.dist <= vmin + 1e-13 * scale && h.bound <= vmin + 1e-13 * scale,
                      "%s surface %d query %d: distance %.17g, bound %.17g, a vertex at %.17g", names[k], o, q, h.dist,
                      h.bound, vmin);
            }
            for (int q = 0; q < 12; q++, nrays++) {
                double org[3], tg[3], dir[3];
                for (int c = 0; c < 3; c++) {
                    org[c] = rg2t_uniform(&rng, lo[c] - (hi[c] - lo[c]), hi[c] + (hi[c] - lo[c]));
                    tg[c] = rg2t_uniform(&rng, lo[c], hi[c]);
                    dir[c] = tg[c] - org[c];
                }
                rg2_hit h;
                CHECK_OK(rg2_locator_ray(L, org, dir, INFINITY, &h, &err), &err);
                double tt = INFINITY, ca = 0;
                for (int f = 0; f < t.n_triangles; f++)
                    tri_hit(t.pos + 3 * t.tri[3 * f], t.pos + 3 * t.tri[3 * f + 1], t.pos + 3 * t.tri[3 * f + 2], org,
                            dir, &tt, &ca);
                if (h.i >= 0) {
                    double on[3];
                    for (int c = 0; c < 3; c++)
                        on[c] = org[c] + h.dist * dir[c];
                    wray = fmax(wray, dist3(on, h.p) / scale);
                    CHECK(dist3(on, h.p) <= 1e-12 * scale, "%s surface %d ray %d: hit %.3g off the ray", names[k], o,
                          q, dist3(on, h.p));
                }
                if (tt < INFINITY && ca > 0.2) { /* a clear triangle hit: the exact one is not later */
                    clear++;
                    double late = h.i >= 0 ? (h.dist - tt) * sqrt(dot(dir, dir)) / scale : INFINITY;
                    wlate = fmax(wlate, late);
                    CHECK(late <= 2e-3, "%s surface %d ray %d: exact hit %.17g (patch %d), triangle hit %.17g",
                          names[k], o, q, h.dist, h.i, tt);
                }
            }
            rg2_locator_free(L);
            rg2_tess_free(&t);
        }
        rg2_design_free(d);
        free(names[k]);
    }
    printf("examples: %d surfaces, %d nearest points: at most %.2e farther than the nearest vertex (the vertices "
           "at density 12 lie up to their sag farther), bound at most %.2e above it; %d rays: on the ray %.2e, %d clear "
           "triangle hits, exact hit at most %.2e later\n",
           surfaces, queries, wworse, wbelow, nrays, wray, clear, wlate);
    CHECK(clear > nrays / 4, "examples: only %d clear triangle hits of %d rays", clear, nrays);
}

/* ---------------------------------------------------------------- degree (5, 4) patches, the sphere's centre */

static void special(void)
{
    rg2_error err;
    rg2_surface s;
    CHECK_OK(rg2t_torus(TR, Tr, 7, 5, NULL, &s, &err), &err);
    CHECK_OK(rg2t_elevate_some(&s, 5, 4, 3, 1, &err), &err);
    torus_case(&s, "torus, every third patch of degree (5, 4)", 300, 300);
    rg2_surface_free(&s);

    /* the centre of a polar sphere: every point is nearest; the search stops at its limit */
    double a[4] = {M_PI / 2, M_PI / 2, M_PI / 2, M_PI / 2}, v[3] = {0.3, 0.5, 0.7};
    rg2_mesh m;
    CHECK_OK(rg2_polar_sphere_mesh(a, 4, 0.0, v, 3, NULL, &m, &err), &err);
    CHECK_OK(rg2_surface_build(&m, &s, &err), &err);
    rg2_mesh_free(&m);
    rg2_locator *L;
    CHECK_OK(rg2_locator_build(&s, &L, &err), &err);
    double c[3] = {0, 0, 0};
    rg2_hit h;
    CHECK_OK(rg2_locator_closest(L, c, &h, &err), &err);
    CHECK(fabs(h.dist - 1) <= 1e-15 && h.bound <= h.dist && h.bound > 0.9, "sphere centre: distance %.17g bound %.17g",
          h.dist, h.bound);
    /* docs/picking.md: at a sphere's centre the Bernstein bound (|S - x|^2 = N / W, here N = W r^2
     * coefficient by coefficient) proves the distance to its last bits */
    CHECK(h.dist - h.bound <= 1e-15, "sphere centre: proven only to %.3g (at most %d pieces)", h.dist - h.bound,
          RG2_LOCATE_MAX_PIECES);
    printf("sphere centre (every point nearest; at most %d pieces): distance - 1 = %.2e, proven to %.2e\n",
           RG2_LOCATE_MAX_PIECES, h.dist - 1, h.dist - h.bound);

    /* refusals */
    CHECK(rg2_locator_closest(L, NULL, &h, &err) == RG2_EINVAL && strstr(err.msg, "x is NULL"), "NULL x: %s", err.msg);
    double nan3[3] = {0, NAN, 0}, d0[3] = {0, 0, 0}, d1[3] = {1, 0, 0};
    CHECK(rg2_locator_closest(L, nan3, &h, &err) == RG2_ENONFINITE && strstr(err.msg, "x[1] is not a finite"),
          "NaN x: %s", err.msg);
    CHECK(h.i == -1 && h.dist == INFINITY, "a refused query leaves i = -1, dist INFINITY: %d %g", h.i, h.dist);
    CHECK(rg2_locator_ray(L, c, nan3, INFINITY, &h, &err) == RG2_ENONFINITE && strstr(err.msg, "d[1] is not a finite"),
          "NaN d: %s", err.msg);
    CHECK(rg2_locator_ray(L, nan3, d1, INFINITY, &h, &err) == RG2_ENONFINITE && strstr(err.msg, "o[1] is not a finite"),
          "NaN o: %s", err.msg);
    CHECK(rg2_locator_ray(L, c, d0, INFINITY, &h, &err) == RG2_EDOMAIN && strstr(err.msg, "has no length"), "d = 0: %s",
          err.msg);
    CHECK(rg2_locator_ray(L, c, d1, -1, &h, &err) == RG2_EDOMAIN && strstr(err.msg, "tmax is -1"), "tmax -1: %s",
          err.msg);
    CHECK(rg2_locator_ray(L, c, d1, NAN, &h, &err) == RG2_EDOMAIN && strstr(err.msg, "tmax is nan"), "tmax NaN: %s",
          err.msg);
    CHECK(rg2_locator_ray(NULL, c, d1, 1, &h, &err) == RG2_EINVAL && strstr(err.msg, "locator is NULL"),
          "NULL locator: %s", err.msg);
    /* infinities are refused like NaN (the check is "not finite", rg2.h), in x, o and d */
    double inf3[3] = {0, 0, INFINITY}, minf3[3] = {-INFINITY, 0, 0};
    CHECK(rg2_locator_closest(L, inf3, &h, &err) == RG2_ENONFINITE && strstr(err.msg, "x[2] is not a finite"),
          "infinite x: %s", err.msg);
    CHECK(rg2_locator_ray(L, minf3, d1, INFINITY, &h, &err) == RG2_ENONFINITE &&
              strstr(err.msg, "o[0] is not a finite"),
          "infinite o: %s", err.msg);
    CHECK(rg2_locator_ray(L, c, inf3, INFINITY, &h, &err) == RG2_ENONFINITE && strstr(err.msg, "d[2] is not a finite"),
          "infinite d: %s", err.msg);
    /* tmax = 0 is allowed (only o itself is searched): from the centre, a miss proven to 0 */
    CHECK(rg2_locator_ray(L, c, d1, 0, &h, &err) == RG2_OK && h.i == -1 && h.bound == 0 && h.dist == INFINITY,
          "tmax 0 from the centre: %s, i %d, bound %g", err.msg, h.i, h.bound);
    /* from the centre, every ray meets the sphere at t = 1 / |d| */
    CHECK_OK(rg2_locator_ray(L, c, d1, INFINITY, &h, &err), &err);
    CHECK(fabs(h.dist - 1) <= 1e-15 && fabs(h.p[0] - 1) <= 1e-15, "sphere centre ray: t %.17g", h.dist);
    /* directions within 1e-300 of the x or y axis (the frame across the ray must be built on an
     * axis whose cross product with d does not underflow): t = 1, at the unit vector (this sphere
     * is a band about the equator: it does not reach the z axis) */
    for (int k = 0; k < 4; k++) {
        double dk[3] = {0, 0, 0};
        dk[k / 2] = 1;
        dk[k % 2 ? 2 : 1 - k / 2] = 1e-300;
        CHECK_OK(rg2_locator_ray(L, c, dk, INFINITY, &h, &err), &err);
        CHECK(h.i >= 0 && fabs(h.dist - 1) <= 1e-15 && fabs(h.p[k / 2] - 1) <= 1e-15,
              "sphere centre ray (%g, %g, %g): i %d t %.17g", dk[0], dk[1], dk[2], h.i, h.dist);
    }
    /* queries past the numeric range (rg2.h: coordinates up to 1e100, a direction whose largest
     * component lies in [1e-100, 1e100]) are refused, naming the number: a ray from (1e300, 0, 0)
     * along -x through this sphere "proved" a miss (RG2_OK, i = -1, bound = inf), one along
     * (-1e-160, 0, 0) from x = 10 missed it too (RG2_OK), directions of 1e155 and 1e-200 were
     * "has no length", and the nearest point to (1e155, 0, 0) was RG2_ELIMIT, "the search ended
     * before any patch"; within the range, the answers stand (t in units of d) */
    double far[3] = {1e300, 0, 0}, far2[3] = {1e155, 0, 0}, mx[3] = {-1, 0, 0}, ten[3] = {10, 0, 0};
    rg2_status st = rg2_locator_ray(L, far, mx, INFINITY, &h, &err);
    CHECK(st == RG2_EDOMAIN && h.i == -1 && strstr(err.msg, "o[0] = 1e+300 is beyond 1e+100"),
          "a ray from 1e300: %s, i %d, t %g, bound %g: %s", rg2_status_str(st), h.i, h.dist, h.bound, st ? err.msg : "");
    st = rg2_locator_closest(L, far2, &h, &err);
    CHECK(st == RG2_EDOMAIN && strstr(err.msg, "x[0] = 1e+155 is beyond 1e+100"), "the nearest point to 1e155: %s: %s",
          rg2_status_str(st), st ? err.msg : "");
    static const double dl[4] = {1e-160, 1e-200, 1e155, 1e101};
    for (int k = 0; k < 4; k++) {
        double dk[3] = {-dl[k], 0, 0};
        st = rg2_locator_ray(L, ten, dk, INFINITY, &h, &err);
        CHECK(st == RG2_EDOMAIN && strstr(err.msg, dl[k] < 1 ? "is too short" : "is too long") &&
                  strstr(err.msg, "scale it"),
              "a direction of length %g: %s, i %d, t %g: %s", dl[k], rg2_status_str(st), h.i, h.dist, st ? err.msg : "");
    }
    double far3[3] = {1e100, 0, 0}, dmin[3] = {-1e-100, 0, 0}, dmax[3] = {-1e100, 0, 0};
    CHECK_OK(rg2_locator_ray(L, far3, mx, INFINITY, &h, &err), &err);
    CHECK(h.i >= 0, "a ray from 1e100 through the sphere misses it (t %g)", h.dist);
    CHECK_OK(rg2_locator_ray(L, ten, dmin, INFINITY, &h, &err), &err);
    CHECK(h.i >= 0 && fabs(h.dist * 1e-100 - 9) <= 1e-14, "a ray along 1e-100: i %d, t |d| = %.17g (want 9)", h.i,
          h.dist * 1e-100);
    CHECK_OK(rg2_locator_ray(L, ten, dmax, INFINITY, &h, &err), &err);
    CHECK(h.i >= 0 && fabs(h.dist * 1e100 - 9) <= 1e-14, "a ray along 1e100: i %d, t |d| = %.17g (want 9)", h.i,
          h.dist * 1e100);
    rg2_locator_free(L);

    rg2_locator *L2 = (rg2_locator *)&err; /* (overwritten with NULL on failure) */
    s.patch[5].h[1][2][3] = -0.5;
    CHECK(rg2_locator_build(&s, &L2, &err) == RG2_EWEIGHT && L2 == NULL &&
              strstr(err.msg, "patch (2,1) control point [1][2] has weight -0.5"),
          "negative weight: %s", err.msg);
    s.patch[5].h[1][2][3] = 0.0; /* (not > 0: refused too; the hull property needs positive weights) */
    CHECK(rg2_locator_build(&s, &L2, &err) == RG2_EWEIGHT && L2 == NULL &&
              strstr(err.msg, "patch (2,1) control point [1][2] has weight 0;"),
          "zero weight: %s", err.msg);
    s.patch[5].h[1][2][3] = NAN;
    CHECK(rg2_locator_build(&s, &L2, &err) == RG2_ENONFINITE && strstr(err.msg, "patch (2,1)"), "NaN: %s", err.msg);
    CHECK(rg2_locator_build(NULL, &L2, &err) == RG2_EINVAL && strstr(err.msg, "surface is NULL"), "NULL: %s", err.msg);
    rg2_surface z = s; /* (a surface without patches in one direction) */
    z.nu = 0;
    CHECK(rg2_locator_build(&z, &L2, &err) == RG2_EINVAL && L2 == NULL && strstr(err.msg, "has no patches (0 x 2)"),
          "0 x 2 patches: %s", err.msg);
    z.nu = s.nu, z.nv = 0;
    CHECK(rg2_locator_build(&z, &L2, &err) == RG2_EINVAL && L2 == NULL && strstr(err.msg, "has no patches (4 x 0)"),
          "4 x 0 patches: %s", err.msg);
    rg2_surface_free(&s);
}

/* ---------------------------------------------------------------- certificates */

/* One surface: certificates for random (patch, x, base, radius, c), each checked on random
 * rectangles (inside its own, or crossing its edge: no claim then) against the distance at a
 * 17 x 17 grid. Counts what was made and the largest excess of a bound over a sampled distance
 * (in units of the surface's size). */
static void cert_surface(const rg2_surface *s, const char *what, int tries, rg2t_rng *rng, int *made, int *declined,
                         double *excess)
{
    rg2_error err;
    rg2_locator *L;
    CHECK_OK(rg2_locator_build(s, &L, &err), &err);
    if (!L)
        return;
    double lo[3], hi[3];
    rg2_surface_box(s, lo, hi);
    double scale = dist3(lo, hi);
    static const double radii[3] = {0.5, 0.125, 0.03125};
    for (int q = 0; q < tries; q++) {
        int i = rg2t_int(rng, 0, s->nu - 1), j = rg2t_int(rng, 0, s->nv - 1), kind = rg2t_int(rng, 0, 3);
        double x[3], uf = rg2t_uniform(rng, 0, 1), vf = rg2t_uniform(rng, 0, 1), r = radii[rg2t_int(rng, 0, 2)];
        if (kind == 3) /* a base on a side or a corner */
            uf = rg2t_int(rng, 0, 1), vf = rg2t_int(rng, 0, 2) * 0.5;
        for (int c = 0; c < 3; c++)
            x[c] = rg2t_uniform(rng, lo[c] - 0.5 * (hi[c] - lo[c]), hi[c] + 0.5 * (hi[c] - lo[c]));
        rg2_eval e;
        rg2_surface_eval(s, i, j, uf, vf, 0, &e);
        double c = dot(e.p, e.p) + dot(x, x) - 2 * dot(e.p, x); /* |S(base) - x|^2, or near it */
        c = fmax(0.0, c * (kind == 1 ? rg2t_uniform(rng, 0.5, 1.5) : 1));
        double u0 = fmax(0, uf - r), u1 = fmin(1, uf + r), v0 = fmax(0, vf - r), v1 = fmin(1, vf + r);
        double rect[4] = {u0, u1, v0, v1}, b;
        if (!rg2__locate_cert(L, i * s->nv + j, uf, vf, r, x, c, rect, &b)) {
            (*declined)++;
            continue;
        }
        (*made)++;
        for (int t = 0; t < 3; t++) {
            if (t) { /* a random rectangle inside R; or (t = 2, if R is not the whole patch) crossing its edge */
                double a0 = rg2t_uniform(rng, u0, u1), a1 = rg2t_uniform(rng, u0, u1);
                double b0 = rg2t_uniform(rng, v0, v1), b1 = rg2t_uniform(rng, v0, v1);
                rect[0] = fmin(a0, a1), rect[1] = fmax(a0, a1), rect[2] = fmin(b0, b1), rect[3] = fmax(b0, b1);
                if (t == 2 && u1 - u0 < 1) {
                    rect[1] = u0 > 0 ? rect[1] : 1;
                    rect[0] = u0 > 0 ? fmax(0, u0 - 0.01) : rect[0];
                }
                rg2__locate_cert(L, i * s->nv + j, uf, vf, r, x, c, rect, &b);
                if (t == 2 && u1 - u0 < 1)
                    CHECK(b == 0, "%s: a certificate over [%g, %g] claims %g for [%g, %g] in u", what, u0, u1, b,
                          rect[0], rect[1]);
            }
            double dmin = INFINITY;
            for (int a = 0; a <= 16; a++)
                for (int bb = 0; bb <= 16; bb++) {
                    rg2_eval f;
                    rg2_surface_eval(s, i, j, rect[0] + (rect[1] - rect[0]) * a / 16,
                                     rect[2] + (rect[3] - rect[2]) * bb / 16, 0, &f);
                    dmin = fmin(dmin, dist3(f.p, x));
                }
            *excess = fmax(*excess, (b - dmin) / scale);
            CHECK(b <= dmin + 1e-14 * scale, "%s patch (%d,%d): certificate bound %.17g above a distance %.17g "
                  "(x %g %g %g, base %g %g, r %g, c %g)", what, i, j, b, dmin, x[0], x[1], x[2], uf, vf, r, c);
        }
    }
    rg2_locator_free(L);
}

/* Based at the true foot on the torus, a certificate covers its rectangle to within the tolerance
 * (what the search needs to rule it out). */
static void cert_torus_feet(const rg2_surface *s, rg2t_rng *rng)
{
    rg2_error err;
    rg2_locator *L;
    CHECK_OK(rg2_locator_build(s, &L, &err), &err);
    int made = 0, n = 200;
    double worst = 0;
    for (int q = 0; q < n; q++) {
        /* a foot inside patch (i, j) away from its sides, x along its normal (inside and out) */
        double x[3] = {rg2t_uniform(rng, -4, 4), rg2t_uniform(rng, -4, 4), rg2t_uniform(rng, -1.5, 1.5)};
        rg2_hit h;
        CHECK_OK(rg2_locator_closest(L, x, &h, &err), &err);
        if (h.i < 0 || h.u < 0.05 || h.u > 0.95 || h.v < 0.05 || h.v > 0.95)
            continue;
        double rho = hypot(x[0], x[1]), tube = hypot(rho - TR, x[2]), want = fabs(tube - Tr);
        if (rho < 0.3 || tube < 0.3) /* (the foot well defined) */
            continue;
        double rect[4] = {fmax(0, h.u - 0.5), fmin(1, h.u + 0.5), fmax(0, h.v - 0.5), fmin(1, h.v + 0.5)}, b = 0;
        if (rg2__locate_cert(L, h.i * s->nv + h.j, h.u, h.v, 0.5, x, want * want, rect, &b)) {
            made++;
            worst = fmax(worst, (want - b) / tolerance(s, x));
            /* (the search rules a piece out whose bound is within the tolerance of the best) */
            CHECK(b <= want * (1 + 1e-15) && want - b <= tolerance(s, x),
                  "torus: certificate at the foot proves %.17g of %.17g", b, want);
        }
    }
    CHECK(made >= 50, "torus: certificates at the foot made %d times", made);
    printf("certificates at the torus's feet (half-size 1/2): %d made, bound within %.2f of the search's tolerance "
           "below the distance\n",
           made, worst);
    rg2_locator_free(L);
}

/* A ray's certificate may not rule out a hit that is there: rays through a surface point y0 at
 * t0 (kind 0: a random direction, the base near y0; kind 1: through a second point y1 of the
 * patch too, at t0 + 1, the base at y1), on random rectangles holding y0 (or y1). Counts
 * the certificates made and declined, and the largest excess of a bound over the hit's t (in
 * units of the tolerance). */
static void ray_cert_surface(const rg2_surface *s, const char *what, int tries, rg2t_rng *rng, int *made,
                             int *declined, double *excess)
{
    rg2_error err;
    rg2_locator *L;
    CHECK_OK(rg2_locator_build(s, &L, &err), &err);
    if (!L)
        return;
    static const double radii[3] = {0.5, 0.125, 0.03125};
    for (int q = 0; q < tries; q++) {
        int i = rg2t_int(rng, 0, s->nu - 1), j = rg2t_int(rng, 0, s->nv - 1), kind = rg2t_int(rng, 0, 1);
        double y[2][2] = {{rg2t_uniform(rng, 0, 1), rg2t_uniform(rng, 0, 1)}, {0, 0}}, r = radii[rg2t_int(rng, 0, 2)];
        double P[2][3], d[3], o[3], t0 = rg2t_uniform(rng, 0.5, 3), base[2];
        rg2_eval e;
        rg2_surface_eval(s, i, j, y[0][0], y[0][1], 0, &e);
        memcpy(P[0], e.p, sizeof P[0]);
        if (kind == 0) {
            for (int c = 0; c < 3; c++)
                d[c] = rg2t_uniform(rng, -1, 1);
            double jit = rg2t_int(rng, 0, 2) * 1e-3 * r; /* (0: the base at the hit) */
            base[0] = fmin(1, fmax(0, y[0][0] + rg2t_uniform(rng, -jit, jit)));
            base[1] = fmin(1, fmax(0, y[0][1] + rg2t_uniform(rng, -jit, jit)));
        } else {
            for (int k = 0; k < 2; k++)
                y[1][k] = fmin(1, fmax(0, y[0][k] + rg2t_uniform(rng, -0.5 * r, 0.5 * r)));
            rg2_surface_eval(s, i, j, y[1][0], y[1][1], 0, &e);
            memcpy(P[1], e.p, sizeof P[1]);
            for (int c = 0; c < 3; c++)
                d[c] = P[1][c] - P[0][c];
            base[0] = y[1][0], base[1] = y[1][1];
        }
        double dd = sqrt(dot(d, d));
        if (!(dd > 1e-9))
            continue;
        for (int c = 0; c < 3; c++)
            o[c] = P[0][c] - t0 * d[c];
        double rect[4] = {fmax(0, base[0] - r), fmin(1, base[0] + r), fmax(0, base[1] - r), fmin(1, base[1] + r)}, b;
        if (!rg2__locate_ray_cert(L, i * s->nv + j, base[0], base[1], r, o, d, rect, &b)) {
            (*declined)++;
            continue;
        }
        (*made)++;
        double tol = tolerance(s, o) / dd; /* (in t) */
        for (int h = 0; h <= kind; h++) {
            double th = t0 + h; /* the hit at y[h] */
            for (int t = 0; t < 3; t++) {
                /* a rectangle holding y[h]: a point, a random one, R itself */
                double w = t == 0 ? 0 : rg2t_uniform(rng, 0, r);
                double rr[4] = {y[h][0] - w, y[h][0] + w, y[h][1] - w, y[h][1] + w};
                if (t == 2)
                    memcpy(rr, rect, sizeof rr);
                rr[0] = fmax(rr[0], rect[0]), rr[1] = fmin(rr[1], rect[1]);
                rr[2] = fmax(rr[2], rect[2]), rr[3] = fmin(rr[3], rect[3]);
                if (!(y[h][0] >= rr[0] && y[h][0] <= rr[1] && y[h][1] >= rr[2] && y[h][1] <= rr[3]))
                    continue;
                rg2__locate_ray_cert(L, i * s->nv + j, base[0], base[1], r, o, d, rr, &b);
                *excess = fmax(*excess, (b - th) / tol);
                CHECK(b <= th + 1e-3 * tol, "%s patch (%d,%d) ray kind %d: a certificate rules out the hit at "
                      "(%.17g, %.17g), t %.17g, with bound %.17g (base %g %g, r %g)",
                      what, i, j, kind, y[h][0], y[h][1], th, b, base[0], base[1], r);
            }
        }
    }
    rg2_locator_free(L);
}

/* On the torus, a ray's certificate at the hit found proves its whole rectangle: the rectangle
 * holding the hit not before t less the tolerance, the rest nowhere. */
static void ray_cert_torus(const rg2_surface *s, rg2t_rng *rng)
{
    rg2_error err;
    rg2_locator *L;
    CHECK_OK(rg2_locator_build(s, &L, &err), &err);
    int made = 0, rays = 0, nowhere = 0;
    for (int q = 0; q < 300; q++) {
        double o[3] = {rg2t_uniform(rng, -8, 8), rg2t_uniform(rng, -8, 8), rg2t_uniform(rng, -3, 3)}, d[3];
        for (int c = 0; c < 3; c++)
            d[c] = rg2t_uniform(rng, -1.5, 1.5) - o[c];
        rg2_hit h;
        CHECK_OK(rg2_locator_ray(L, o, d, INFINITY, &h, &err), &err);
        if (h.i < 0)
            continue;
        rays++;
        double rect[4] = {fmax(0, h.u - 0.5), fmin(1, h.u + 0.5), fmax(0, h.v - 0.5), fmin(1, h.v + 0.5)}, b;
        if (!rg2__locate_ray_cert(L, h.i * s->nv + h.j, h.u, h.v, 0.5, o, d, rect, &b))
            continue;
        made++;
        double tol = tolerance(s, o) / sqrt(dot(d, d));
        CHECK(b <= h.dist && b >= h.dist - 0.5 * tol, "torus ray %d: the certificate at the hit t %.17g gives %.17g", q,
              h.dist, b);
        /* a corner of R away from the hit: no hit there */
        double cu = h.u < 0.5 ? rect[1] : rect[0], cv = h.v < 0.5 ? rect[3] : rect[2];
        double rc[4] = {fmin(cu, 0.5 * (cu + h.u)), fmax(cu, 0.5 * (cu + h.u)), fmin(cv, 0.5 * (cv + h.v)),
                        fmax(cv, 0.5 * (cv + h.v))};
        rg2__locate_ray_cert(L, h.i * s->nv + h.j, h.u, h.v, 0.5, o, d, rc, &b);
        nowhere += b == INFINITY;
    }
    CHECK(made >= rays / 2 && nowhere >= made * 9 / 10, "torus rays: %d hits, %d certificates, %d corners ruled out",
          rays, made, nowhere);
    printf("rays' certificates at the torus's hits (half-size 1/2): %d of %d hits, a corner quarter of R ruled out in "
           "%d\n",
           made, rays, nowhere);
    rg2_locator_free(L);
}

typedef void (*cert_check)(const rg2_surface *, const char *, int, rg2t_rng *, int *, int *, double *);

/* f on every surface of every example design; the number of surfaces. */
static int for_examples(void (*f)(const rg2_surface *, const char *, void *), void *ctx)
{
    rg2_error err;
    char *names[64];
    int ne = rg2t_example_names(names, 64), surfaces = 0;
    for (int k = 0; k < ne; k++) {
        rg2_design *d = NULL;
        CHECK_OK(rg2_design_load(names[k], &d, &err), &err);
        for (int o = 0; d && o < rg2_design_num_surfaces(d); o++, surfaces++)
            f(rg2_design_surface(d, o), names[k], ctx);
        rg2_design_free(d);
        free(names[k]);
    }
    return surfaces;
}

typedef struct {
    cert_check each;
    rg2t_rng *rng;
    int *made, *declined;
    double *excess;
} cert_ctx;

static void cert_example(const rg2_surface *s, const char *name, void *ctx)
{
    cert_ctx *c = ctx;
    c->each(s, name, 40, c->rng, c->made, c->declined, c->excess);
}

/* One kind of certificate on the torus (first its check at the true answers), the torus of
 * degree (5, 4) in part and every example surface; the number made and declined, the surfaces. */
static int cert_all(cert_check each, void (*at_answers)(const rg2_surface *, rg2t_rng *), rg2t_rng *rng, int *made,
                    int *declined, double *excess)
{
    rg2_error err;
    rg2_surface s;
    *made = *declined = 0;
    *excess = -INFINITY;
    CHECK_OK(rg2t_torus(TR, Tr, 8, 6, NULL, &s, &err), &err);
    at_answers(&s, rng);
    each(&s, "torus", 400, rng, made, declined, excess);
    rg2_surface_free(&s);
    CHECK_OK(rg2t_torus(TR, Tr, 7, 5, NULL, &s, &err), &err);
    CHECK_OK(rg2t_elevate_some(&s, 5, 4, 3, 1, &err), &err);
    each(&s, "torus of degree (5, 4) in part", 400, rng, made, declined, excess);
    rg2_surface_free(&s);
    cert_ctx cx = {each, rng, made, declined, excess};
    return for_examples(cert_example, &cx);
}

static void certificates(void)
{
    rg2t_rng rng;
    rg2t_seed(&rng, 4242);
    int made, declined;
    double excess;
    int surfaces = cert_all(cert_surface, cert_torus_feet, &rng, &made, &declined, &excess);
    printf("certificates: %d made, %d declined (torus, part degree (5, 4), %d example surfaces); no bound above a "
           "sampled distance (at most %.2e of the size below none)\n",
           made, declined, surfaces, excess);
    CHECK(made > 150 && declined > 100, "certificates: %d made, %d declined: the check needs both", made, declined);
    surfaces = cert_all(ray_cert_surface, ray_cert_torus, &rng, &made, &declined, &excess);
    printf("rays' certificates: %d made, %d declined (torus, part degree (5, 4), %d example surfaces); no hit ruled "
           "out (a bound at most %.2e of the tolerance past a hit's t)\n",
           made, declined, surfaces, excess);
    CHECK(made > 300 && declined > 100, "rays' certificates: %d made, %d declined: the check needs both", made,
          declined);
}

/* The tree's slabs (each node's range along a direction near its patches' normal, which rules
 * out nodes the box does not): every exact control point inside its nodes' slabs, on the torus,
 * the torus of degree (5, 4) in part, a torus of 120 x 90 patches (and mirrored) and every
 * example surface. */
static void slab_one(const rg2_surface *s, const char *what, double *worst, int *nodes, int *slabs)
{
    rg2_error err;
    rg2_locator *L;
    CHECK_OK(rg2_locator_build(s, &L, &err), &err);
    if (!L)
        return;
    int k;
    double m = rg2__locate_slab_margin(L, &k);
    CHECK(m >= 0, "%s: a control point %.3g (of its size) outside its node's slab", what, -m);
    *worst = fmin(*worst, m);
    *nodes += 2 * s->nu * s->nv - 1;
    *slabs += k;
    rg2_locator_free(L);
}

typedef struct {
    double *worst;
    int *nodes, *slabs;
} slab_ctx;

static void slab_example(const rg2_surface *s, const char *name, void *ctx)
{
    slab_ctx *c = ctx;
    slab_one(s, name, c->worst, c->nodes, c->slabs);
}

static void slabs(void)
{
    rg2_error err;
    rg2_surface s;
    double worst = INFINITY;
    int nodes = 0, slabs = 0, tnodes, tslabs;
    CHECK_OK(rg2t_torus(TR, Tr, 8, 6, NULL, &s, &err), &err);
    slab_one(&s, "torus", &worst, &nodes, &slabs);
    rg2_surface_free(&s);
    CHECK_OK(rg2t_torus(TR, Tr, 7, 5, NULL, &s, &err), &err);
    CHECK_OK(rg2t_elevate_some(&s, 5, 4, 3, 1, &err), &err);
    slab_one(&s, "torus of degree (5, 4) in part", &worst, &nodes, &slabs);
    rg2_surface_free(&s);
    CHECK_OK(rg2t_torus(TR, Tr, 120, 90, NULL, &s, &err), &err);
    tnodes = nodes, tslabs = slabs;
    slab_one(&s, "torus of 120 x 90 patches", &worst, &nodes, &slabs);
    tnodes = nodes - tnodes, tslabs = slabs - tslabs;
    torus_case(&s, "torus of 120 x 90 patches", 300, 300);
    /* mirrored and moved off the origin (the slabs' normals turn over, and their rounding falls
     * on the other side) */
    static const double M[16] = {-1, 0, 0, 0.3, 0, 1, 0, -0.7, 0, 0, 1, 0.2, 0, 0, 0, 1};
    rg2_surface_transform(&s, M);
    slab_one(&s, "torus of 120 x 90 patches, mirrored", &worst, &nodes, &slabs);
    rg2_surface_free(&s);
    slab_ctx cx = {&worst, &nodes, &slabs};
    int surfaces = for_examples(slab_example, &cx);
    printf("tree slabs: %d of %d nodes have one (torus of 120 x 90 patches: %d of %d; %d example surfaces); every "
           "control point inside, by at least %.2e of its size\n",
           slabs, nodes, tslabs, tnodes, surfaces, worst);
    CHECK(tslabs > tnodes / 2, "torus of 120 x 90 patches: only %d of %d nodes have a slab", tslabs, tnodes);
}

/* The smallest sampled distance from x to s: (n + 1)^2 points a patch (each a point of the
 * surface: no answer may be farther by more than the tolerance, and no bound above it). */
static double sampled_min(const rg2_surface *s, const double x[3], int n)
{
    double best = INFINITY;
    for (int i = 0; i < s->nu; i++)
        for (int j = 0; j < s->nv; j++)
            for (int a = 0; a <= n; a++)
                for (int b = 0; b <= n; b++) {
                    rg2_eval e;
                    rg2_surface_eval(s, i, j, (double)a / n, (double)b / n, 0, &e);
                    best = fmin(best, dist3(e.p, x));
                }
    return best;
}

/* The searches at the ends of the library's numeric range (coordinates up to 1e60, a size of
 * at least 1e-60: docs/robustness.md): a torus of 3 x 7 patches with its control points moved
 * and weighted 1e-3 to 1e3, scaled by 1e59 and 1e-59: every slab holds its control points, no
 * bound lies above a sampled distance, no answer beyond one by more than the tolerance. Past the
 * range, refused (RG2_EDOMAIN, naming it): the same torus at 1e61, 1e-62, 1e150 (a second
 * reader's stress case: N in the Bernstein bound overflowed and ruled the nearest patch out),
 * 1e-161 (an answer 2e-3 of its distance beyond a sampled point) and 1e-300, and two patches
 * spanning +-1e308 (the tolerance infinite: no patch taken). */
static void extreme_scales(void)
{
    static const double scales[] = {1e59, 1e-59, 1e61, 1e-62, 1e150, 1e-161, 1e-300, 0};
    enum { n_scales = sizeof scales / sizeof *scales };
    double worst = -INFINITY, wslab = INFINITY;
    int queries = 0, refused = 0;
    for (int k = 0; k < n_scales; k++) {
        rg2_error err;
        rg2_surface s;
        rg2t_rng g;
        rg2t_seed(&g, 241 + k);
        if (scales[k] > 0) {
            CHECK_OK(rg2t_torus(3, 1.2, 3, 7, NULL, &s, &err), &err);
            for (int p = 0; p < s.nu * s.nv; p++)
                for (int r = 0; r < 4; r++)
                    for (int t = 0; t < 4; t++) {
                        double *h = s.patch[p].h[r][t], w = exp(rg2t_uniform(&g, log(1e-3), log(1e3)));
                        for (int c = 0; c < 3; c++)
                            h[c] = (h[c] / h[3] + rg2t_uniform(&g, -0.3, 0.3)) * w;
                        h[3] = w;
                    }
            const double M[16] = {scales[k], 0, 0, 0, 0, scales[k], 0, 0, 0, 0, scales[k], 0, 0, 0, 0, 1};
            rg2_surface_transform(&s, M);
        } else { /* two flat patches, one from -1e308 to 1e308 along x */
            memset(&s, 0, sizeof s);
            s.nu = 2, s.nv = 1;
            s.patch = calloc(2, sizeof *s.patch);
            s.bu = calloc(2, sizeof *s.bu), s.gu = calloc(2, sizeof *s.gu);
            s.bv = calloc(1, sizeof *s.bv), s.gv = calloc(1, sizeof *s.gv);
            if (!s.patch || !s.bu || !s.gu || !s.bv || !s.gv)
                return;
            const double xs[4] = {-1e308, -1e308 / 3, 1e308 / 3, 1e308};
            for (int r = 0; r < 4; r++)
                for (int t = 0; t < 4; t++) {
                    double *h = s.patch[0].h[r][t];
                    h[0] = xs[r], h[1] = t, h[2] = t / 3.0, h[3] = 1;
                    h = s.patch[1].h[r][t];
                    h[0] = r / 3.0, h[1] = 10 + t / 3.0, h[2] = 0, h[3] = 1;
                }
        }
        char what[64];
        snprintf(what, sizeof what, scales[k] > 0 ? "torus at %g" : "patches spanning +-1e308", scales[k]);
        rg2_locator *L = NULL;
        rg2_status st = rg2_locator_build(&s, &L, &err);
        if (k >= 2) {
            refused += st == RG2_EDOMAIN;
            CHECK(st == RG2_EDOMAIN && !L && strstr(err.msg, "rg2_locator_build") && strstr(err.msg, "scale it"),
                  "%s: not refused (%s): %s", what, rg2_status_str(st), st ? err.msg : "");
        } else
            CHECK_OK(st, &err);
        if (L) {
            int ns;
            double m = rg2__locate_slab_margin(L, &ns);
            CHECK(m >= 0, "%s: a control point %.3g (of its size) outside its node's slab", what, -m);
            wslab = fmin(wslab, m);
            for (int q = 0; q < 12; q++, queries++) {
                double x[3];
                for (int c = 0; c < 3; c++)
                    x[c] = scales[k] * rg2t_uniform(&g, -5, 5);
                rg2_hit h;
                CHECK_OK(rg2_locator_closest(L, x, &h, &err), &err);
                double smin = sampled_min(&s, x, 16), tol = tolerance(&s, x);
                worst = fmax(worst, (h.bound - smin) / smin);
                CHECK(h.bound <= smin && h.dist <= smin + tol,
                      "%s, query %d: distance %.17g, bound %.17g, a sampled point %.17g away (tolerance %.3g)", what, q,
                      h.dist, h.bound, smin, tol);
            }
            rg2_locator_free(L);
        }
        rg2_surface_free(&s);
    }
    printf("numeric range (a moved torus with weights 1e-3 to 1e3): at 1e59 and 1e-59, %d nearest points, no bound above "
           "a sampled distance (the nearest %.2e of it below), slabs holding their points by %.2e of their size; "
           "%d of %d past the range refused\n",
           queries, -worst, wslab, refused, n_scales - 2);
}

/* The Newton runs' work (rg2__locate_closest counts their patch evaluations): 1000 points in
 * the torus's box on the torus of 48 patches and on one of 120 x 90. A Newton run that went
 * back and forth between two points a rounding apart, each taken for the other in turn, took
 * all 60 steps (7 % of the runs on 200 x 200 patches) with the same answers: only the count
 * shows it (22.4 and 92.9 evaluations with that rule back, against 14.4 and 51.0). */
static void newton_work(void)
{
    static const int grid[2][2] = {{8, 6}, {120, 90}};
    double mean[2];
    for (int g = 0; g < 2; g++) {
        rg2_error err;
        rg2_surface s;
        CHECK_OK(rg2t_torus(TR, Tr, grid[g][0], grid[g][1], NULL, &s, &err), &err);
        rg2_locator *L;
        CHECK_OK(rg2_locator_build(&s, &L, &err), &err);
        rg2t_rng rng;
        rg2t_seed(&rng, 77);
        long evals = 0;
        for (int q = 0; L && q < 1000; q++) {
            double a = TR + Tr, x[3] = {rg2t_uniform(&rng, -a, a), rg2t_uniform(&rng, -a, a), rg2t_uniform(&rng, -Tr, Tr)};
            rg2_hit h;
            CHECK_OK(rg2__locate_closest(L, x, &h, &evals, &err), &err);
        }
        mean[g] = evals / 1000.0;
        rg2_locator_free(L);
        rg2_surface_free(&s);
    }
    printf("Newton's work: %.1f patch evaluations a nearest point on 48 patches, %.1f on 120 x 90\n", mean[0], mean[1]);
    CHECK(mean[0] < 18 && mean[1] < 70, "Newton's work: %.1f and %.1f patch evaluations a nearest point", mean[0],
          mean[1]);
}

int main(void)
{
    rg2_error err;
    rg2_surface s;
    CHECK_OK(rg2t_torus(TR, Tr, 8, 6, NULL, &s, &err), &err);
    torus_case(&s, "torus", 2000, 2000);
    rg2_surface_free(&s);
    seam_feet();
    seam_rays(0);
    seam_rays(1);
    sphere_band();
    special();
    examples();
    certificates();
    slabs();
    extreme_scales();
    newton_work();
    return rg2t_done("test_locate");
}
