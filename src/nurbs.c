/* nurbs.c -- bi-cubic NURBS import (MATH.md sections 1 and 5): the control 4-tuples (w P, w)
 * in polynomial mode with the knot-ratio scalars; clamped ends unclamped by blossoming. */
#include "internal.h"

#include <float.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

/* The blossom f(a[0], a[1], a[2]) of the polynomial piece on span [U_l, U_{l+1}] of a cubic
 * B-spline with 4-tuple de Boor points P (stride `stride` doubles between consecutive
 * points, P pointing at P_{l-3}): the de Boor algorithm with one argument per level.
 * With `absval` the same combination with the absolute values of its coefficients: applied
 * to absolute values it bounds the magnitudes that the rounding errors are relative to.
 * Knots up to 1e308 can lie farther apart than the largest double over the up to three
 * intervals a coefficient spans (clamped at -1.79e307, then 5.37e307 and 1.7e308): that
 * coefficient is formed from the halves of its knots (exact, the same ratio). */
static void span_blossom(const double *U, int l, const double *P, size_t stride, const double a[3],
                         int absval, double out[4])
{
    double d[4][4];
    for (int i = 0; i < 4; i++)
        memcpy(d[i], P + stride * (size_t)i, sizeof d[i]);
    for (int r = 1; r <= 3; r++)
        for (int i = 3; i >= r; i--) { /* d[i] holds de Boor point l - 3 + i */
            int gi = l - 3 + i;
            double num = a[r - 1] - U[gi], den = U[gi + 4 - r] - U[gi];
            if (!(rg2__finite(num) && rg2__finite(den))) /* (halves: their differences are finite) */
                num = 0.5 * a[r - 1] - 0.5 * U[gi], den = 0.5 * U[gi + 4 - r] - 0.5 * U[gi];
            double al = num / den, be = 1.0 - al;
            if (absval)
                al = fabs(al), be = fabs(be);
            for (int k = 0; k < 4; k++)
                d[i][k] = be * d[i - 1][k] + al * d[i][k];
        }
    memcpy(out, d[3], sizeof d[3]);
}

/*
 * Validate a knot vector of n + 4 values and produce the construction's knots Unew (n + 4
 * values, Unew[1..n+2] = v_{-1}..v_n). Ends with zero intervals among U_1..U_3 (or
 * U_n..U_{n+2}) get virtual knots U_3 - k d (U_n + k d'), d = U_4 - U_3 (d' = U_n - U_{n-1}).
 * *fix_lo / *fix_hi tell whether the first / last two de Boor points must be re-blossomed.
 */
static rg2_status knots_prepare(const double *U, int n, const char *what, double *Unew, int *fix_lo,
                                int *fix_hi, rg2_error *err)
{
    int nk = n + 4;
    for (int k = 0; k < nk; k++)
        if (!rg2__finite(U[k]))
            return rg2__fail(err, RG2_ENONFINITE, "nurbs: %s[%d] is not finite", what, k);
    for (int k = 1; k < nk; k++)
        if (U[k] < U[k - 1])
            return rg2__fail(err, RG2_EDOMAIN,
                             "nurbs: %s[%d] = %s is smaller than %s[%d] = %s; knots must not "
                             "decrease",
                             what, k, rg2__num(U[k]).s, what, k - 1, rg2__num(U[k - 1]).s);
    for (int k = 4; k <= n; k++)
        if (!(U[k] > U[k - 1])) {
            if (k == 4 || k == n)
                return rg2__fail(err, RG2_EDOMAIN,
                                 "nurbs: %s[%d] = %s[%d] = %s: the first or last span of the "
                                 "domain [%s[3], %s[%d]] has zero length",
                                 what, k - 1, what, k, rg2__num(U[k]).s, what, what, n);
            return rg2__fail(err, RG2_EDOMAIN,
                             "nurbs: interior knot %s[%d] = %s is repeated (equals %s[%d]); "
                             "rg2 needs distinct interior knots (a repeated knot lowers the "
                             "continuity): split the NURBS into pieces at this knot",
                             what, k, rg2__num(U[k]).s, what, k - 1);
        }
    memcpy(Unew, U, sizeof(double) * (size_t)nk);
    *fix_lo = !(U[1] < U[2] && U[2] < U[3]);
    *fix_hi = !(U[n] < U[n + 1] && U[n + 1] < U[n + 2]);
    /* U[3] - k d; where k d alone overflows (d past half the largest double) but the knot does
     * not, one more step from the last knot (the same bits wherever k d is finite) */
    if (*fix_lo) {
        double d = U[4] - U[3];
        for (int k = 1; k <= 3; k++)
            Unew[3 - k] = rg2__finite(k * d) ? U[3] - k * d : Unew[4 - k] - d;
    }
    if (*fix_hi) {
        double d = U[n] - U[n - 1];
        for (int k = 1; k <= 3; k++)
            Unew[n + k] = rg2__finite(k * d) ? U[n] + k * d : Unew[n + k - 1] + d;
    }
    /* The construction reads Unew[1..n+2] (the scalars of rg2_nurbs_mesh; the blossoms of
     * unclamp_line and check_clamped_rounding), never Unew[0] or Unew[n+3]: the intervals
     * Unew[k-1..k], k = 2..n+2, must be finite. Those of the user's knots first (k = 3..n+2 or
     * 2..n, k-1 >= 3 and k <= n where an end is continued), then the continued ones. */
    for (int k = 2; k <= n + 2; k++)
        if (!(*fix_lo && k <= 3) && !(*fix_hi && k > n) && !rg2__finite(Unew[k] - Unew[k - 1]))
            return rg2__fail(err, RG2_EDOMAIN,
                             "nurbs: the interval %s[%d..%d] = [%s, %s] is longer than the double range", what,
                             k - 1, k, rg2__num(U[k - 1]).s, rg2__num(U[k]).s);
    if (*fix_lo && !(rg2__finite(Unew[1]) && rg2__finite(Unew[2])))
        return rg2__fail(err, RG2_EDOMAIN,
                         "nurbs: the end interval %s[3..4] = [%s, %s], continued past the clamped start as "
                         "rg2 does to unclamp it, reaches %s[3] - 2 (%s[4] - %s[3]) = %s, beyond the double "
                         "range",
                         what, rg2__num(U[3]).s, rg2__num(U[4]).s, what, what, what, rg2__num(Unew[1]).s);
    if (*fix_hi && !(rg2__finite(Unew[n + 1]) && rg2__finite(Unew[n + 2])))
        return rg2__fail(err, RG2_EDOMAIN,
                         "nurbs: the end interval %s[%d..%d] = [%s, %s], continued past the clamped end as "
                         "rg2 does to unclamp it, reaches %s[%d] + 2 (%s[%d] - %s[%d]) = %s, beyond the double "
                         "range",
                         what, n - 1, n, rg2__num(U[n - 1]).s, rg2__num(U[n]).s, what, n, what, n, what, n - 1,
                         rg2__num(Unew[n + 2]).s);
    return RG2_OK;
}

/* Re-blossom the end de Boor points of one direction in place: points P_0, P_1 (fix_lo) and
 * P_{n-2}, P_{n-1} (fix_hi) along a line of n points with the given stride. */
static void unclamp_line(double *P, size_t stride, int n, const double *U, const double *Unew,
                         int fix_lo, int fix_hi, int absval)
{
    double q[4][4];
    if (fix_lo) {
        for (int i = 0; i < 2; i++) {
            double a[3] = {Unew[i + 1], Unew[i + 2], Unew[i + 3]};
            span_blossom(U, 3, P, stride, a, absval, q[i]);
        }
    }
    if (fix_hi) {
        for (int i = n - 2; i < n; i++) {
            double a[3] = {Unew[i + 1], Unew[i + 2], Unew[i + 3]};
            span_blossom(U, n - 1, P + stride * (size_t)(n - 4), stride, a, absval, q[2 + i - (n - 2)]);
        }
    }
    if (fix_lo)
        for (int i = 0; i < 2; i++)
            memcpy(P + stride * (size_t)i, q[i], sizeof q[i]);
    if (fix_hi)
        for (int i = n - 2; i < n; i++)
            memcpy(P + stride * (size_t)i, q[2 + i - (n - 2)], sizeof q[0]);
}

/* The 4 x 4 Bezier 4-tuples of the piece over span (lu, lv) of a bi-cubic B-spline whose de
 * Boor 4-tuples (lu - 3 + a, lv - 3 + b) are P[a][b]: Bezier point (r, s) is the blossom at
 * (U_lu^(3-r) U_{lu+1}^r ; V_lv^(3-s) V_{lv+1}^s), by knot insertion (de Boor with arguments
 * in the span: only convex combinations). */
static void span_bezier(double P[4][4][4], const double *U, int lu, const double *V, int lv, int absval,
                        double out[4][4][4])
{
    double rows[4][4][4]; /* rows[a][s]: Bezier point s in v of u row a */
    for (int a = 0; a < 4; a++)
        for (int s = 0; s < 4; s++) {
            double arg[3];
            for (int k = 0; k < 3; k++)
                arg[k] = k < 3 - s ? V[lv] : V[lv + 1];
            span_blossom(V, lv, &P[a][0][0], 4, arg, absval, rows[a][s]);
        }
    for (int r = 0; r < 4; r++)
        for (int s = 0; s < 4; s++) {
            double arg[3];
            for (int k = 0; k < 3; k++)
                arg[k] = k < 3 - r ? U[lu] : U[lu + 1];
            span_blossom(U, lu, &rows[0][s][0], 16, arg, absval, out[r][s]);
        }
}

static void bernstein3(double t, double b[4])
{
    double s = 1.0 - t;
    b[0] = s * s * s;
    b[1] = 3.0 * t * s * s;
    b[2] = 3.0 * t * t * s;
    b[3] = t * t * t;
}

/* Samples per patch direction of the error estimate (a ratio of two positive polynomials). */
#define NURBS_SAMPLES 8
/* Rounding error of the construction's patches from an unclamped mesh, per unit of the
 * magnitudes below. Calibrated on 12,000 random clamped NURBS (4..8 points per direction,
 * weights e^U(-15, 15) random, alternating or growing, knot intervals up to 55 apart): the
 * measured errors (17 x 17 samples per patch against Cox-de Boor) were 1/15000 to 1/4 of the
 * estimate; tests/test_nurbs.c `clamped_weights` checks it. */
#define NURBS_ROUNDING (8.0 * DBL_EPSILON)
/* The largest estimated position error accepted, relative to the coordinates' scale. */
#define NURBS_MAX_ERROR 1e-10

/*
 * A clamped end is continued by de Boor points extrapolated to virtual knots (unclamp_line).
 * Where the weights near the end differ much, these are large 4-tuples of both signs whose
 * combinations in the construction cancel to the small end values: the construction's patches
 * then carry rounding errors of the size of the extrapolated points, not of the result (with
 * weights alternating r, 1/r near a corner the error grows like r^2 eps). No mesh in rg2's form
 * avoids it: the end scalars (those of the end interval continued, so that the NURBS merges
 * with shapes of equal intervals) fix the extrapolated points, which the mesh holds as doubles.
 * (Unclamped knot vectors need no extrapolation: the construction then forms only convex
 * combinations of positive weights and is accurate for any weights.)
 * Estimate the error: A holds the absolute values of the unclamped mesh's 4-tuples computed
 * with absolute coefficients (the magnitudes that the rounding errors are relative to). For
 * every patch within two spans of a clamped end, the exact Bezier 4-tuples B (knot insertion
 * from the input (w P, w): convex combinations) and the magnitudes M (the same from A on the
 * unclamped knots), E = |M_xyz|_inf + X M_w per Bezier point (X the largest coordinate), give
 * the position error NURBS_ROUNDING sum(E b_rs) / sum(B_w b_rs) (b_rs the Bernstein products)
 * at 9 x 9 samples. Refuse the NURBS when its largest exceeds NURBS_MAX_ERROR of max(X, size).
 */
static rg2_status check_clamped_rounding(const rg2_nurbs *nb, const double *A, const double *Uu,
                                         const double *Uv, const int fl[4], rg2_error *err)
{
    int nu = nb->nu, nv = nb->nv;
    size_t np = (size_t)nu * (size_t)nv;
    rg2__box box;
    rg2__box_init(&box);
    for (size_t k = 0; k < np; k++)
        rg2__box_add(&box, &nb->points[3 * k], 1.0);
    double X, size;
    rg2__box_extent(&box, &X, &size);
    double worst = 0.0;
    int wi = 0, wj = 0;
    for (int i = 0; i < nu - 3; i++)
        for (int j = 0; j < nv - 3; j++) {
            if (!((fl[0] && i < 2) || (fl[1] && i >= nu - 5) || (fl[2] && j < 2) || (fl[3] && j >= nv - 5)))
                continue; /* no unclamped point in reach: convex combinations of positive weights */
            double H[4][4][4], M[4][4][4], B[4][4][4], Bm[4][4][4];
            for (int a = 0; a < 4; a++)
                for (int c = 0; c < 4; c++) {
                    size_t k = (size_t)(i + a) * (size_t)nv + (size_t)(j + c);
                    double w = nb->weights ? nb->weights[k] : 1.0;
                    for (int d = 0; d < 3; d++)
                        H[a][c][d] = w * nb->points[3 * k + d];
                    H[a][c][3] = w;
                    memcpy(M[a][c], A + 4 * k, sizeof M[a][c]);
                }
            span_bezier(H, nb->knots_u, i + 3, nb->knots_v, j + 3, 0, B);
            span_bezier(M, Uu, i + 3, Uv, j + 3, 1, Bm);
            double E[4][4]; /* the bound of the 4-tuple's error, in units of the rounding */
            for (int r = 0; r < 4; r++)
                for (int s = 0; s < 4; s++) {
                    const double *m = Bm[r][s];
                    E[r][s] = fmax(m[0], fmax(m[1], m[2])) + X * m[3];
                }
            for (int a = 0; a <= NURBS_SAMPLES; a++)
                for (int c = 0; c <= NURBS_SAMPLES; c++) {
                    double bu[4], bv[4], num = 0.0, den = 0.0;
                    bernstein3((double)a / NURBS_SAMPLES, bu);
                    bernstein3((double)c / NURBS_SAMPLES, bv);
                    for (int r = 0; r < 4; r++)
                        for (int s = 0; s < 4; s++) {
                            num += bu[r] * bv[s] * E[r][s];
                            den += bu[r] * bv[s] * B[r][s][3];
                        }
                    double e = NURBS_ROUNDING * num / den;
                    if (!(e <= worst)) { /* NaN counts as worst */
                        worst = e;
                        wi = i;
                        wj = j;
                    }
                }
        }
    double scale = fmax(X, size);
    if (worst <= NURBS_MAX_ERROR * scale)
        return RG2_OK;
    /* name the extreme weights among the offending patch's 4 x 4 de Boor points */
    double wlo = INFINITY, whi = -INFINITY;
    int ai = wi, aj = wj, bi = wi, bj = wj;
    for (int i = wi; i < wi + 4; i++)
        for (int j = wj; j < wj + 4; j++) {
            double w = nb->weights ? nb->weights[(size_t)i * (size_t)nv + (size_t)j] : 1.0;
            if (w < wlo)
                wlo = w, ai = i, aj = j;
            if (w > whi)
                whi = w, bi = i, bj = j;
        }
    if (!(whi > 2.0 * wlo)) /* not met in the tests: knot intervals alone */
        return rg2__fail(err, RG2_EDOMAIN,
                         "nurbs: the knot intervals near a clamped end (patch (%d, %d)) make rg2's "
                         "extrapolated de Boor points cancel: their rounding could move the surface "
                         "by %.3g (%.3g of its scale %.6g, limit %g)",
                         wi, wj, worst, worst / scale, scale, NURBS_MAX_ERROR);
    return rg2__fail(err, RG2_EDOMAIN,
                     "nurbs: weights [%d][%d] = %.6g and [%d][%d] = %.6g near a clamped end (patch (%d, "
                     "%d)) differ too much: rg2 continues clamped ends by extrapolated de Boor points "
                     "whose rounding could move the surface by %.3g (%.3g of its scale %.6g, limit %g); "
                     "bring the weights near clamped ends closer together",
                     ai, aj, wlo, bi, bj, whi, wi, wj, worst, worst / scale, scale, NURBS_MAX_ERROR);
}

/*
 * METHOD: the NURBS with de Boor points P_ij and weights w_ij is the polynomial B-spline of
 * the 4-tuples (w P, w). In rg2's polynomial mode (MATH.md section 1) point i of a direction
 * is the blossom at (v_{i-1}, v_i, v_{i+1}) = (U_{i+1}, U_{i+2}, U_{i+3}), exactly the de Boor
 * point of the same knot vector; so the 4-tuples are the mesh as they are, with the scalars
 * of the knots U_1..U_{n+2}. Clamped ends have zero intervals there: the end de Boor points
 * are replaced by the blossoms of the end pieces at virtual knots (the piece is unchanged,
 * and only the first/last two points depend on U_1, U_2 / U_{n+1}, U_{n+2}). Those points
 * are extrapolations: check_clamped_rounding refuses weights for which they cancel.
 */
rg2_status rg2_nurbs_mesh(const rg2_nurbs *nb, rg2_mesh *out, rg2_error *err)
{
    memset(out, 0, sizeof *out);
    if (!nb || !nb->points || !nb->knots_u || !nb->knots_v)
        return rg2__fail(err, RG2_EINVAL, "nurbs: points or knot vectors missing (NULL)");
    if (nb->nu < 4 || nb->nv < 4)
        return rg2__fail(err, RG2_EINVAL,
                         "nurbs: %d x %d control points; a bi-cubic NURBS needs at least 4 in each "
                         "direction",
                         nb->nu, nb->nv);
    int nu = nb->nu, nv = nb->nv;
    if (nu > RG2_MAX_POINTS || nv > RG2_MAX_POINTS || (long long)nu * nv > RG2_MAX_POINTS)
        return rg2__fail(err, RG2_ELIMIT, "nurbs: %d x %d control points exceeds the limit %d", nu, nv,
                         RG2_MAX_POINTS);
    double *Uu = rg2__calloc((size_t)nu + 4, sizeof(double));
    double *Uv = rg2__calloc((size_t)nv + 4, sizeof(double));
    double *A = NULL; /* magnitudes of the unclamped mesh (clamped ends) */
    rg2_status st = RG2_OK;
    int flu = 0, fhu = 0, flv = 0, fhv = 0;
    if (!Uu || !Uv) {
        st = rg2__fail(err, RG2_ENOMEM, "nurbs: out of memory");
        goto fail;
    }
    if ((st = knots_prepare(nb->knots_u, nu, "knots_u", Uu, &flu, &fhu, err)) ||
        (st = knots_prepare(nb->knots_v, nv, "knots_v", Uv, &flv, &fhv, err)))
        goto fail;
    for (int i = 0; i < nu; i++)
        for (int j = 0; j < nv; j++) {
            size_t k = (size_t)i * (size_t)nv + (size_t)j;
            for (int d = 0; d < 3; d++)
                if (!rg2__finite(nb->points[3 * k + d])) {
                    st = rg2__fail(err, RG2_ENONFINITE,
                                   "nurbs: control point [%d][%d] coordinate %d is not finite", i, j, d);
                    goto fail;
                }
            if (nb->weights && !(nb->weights[k] > 0.0 && rg2__finite(nb->weights[k]))) {
                st = rg2__fail(err, RG2_EWEIGHT, "nurbs: weight [%d][%d] = %s must be finite and > 0",
                               i, j, rg2__num(nb->weights[k]).s);
                goto fail;
            }
        }
    if ((st = rg2_mesh_init(out, nu, nv, 0, 0, err)))
        goto fail;
    rg2_scalars_free(&out->su);
    rg2_scalars_free(&out->sv);
    /* (the scalars' knots are Unew[1..n+2]: knots_u[1..n+2] where no end is continued; a
     * junction whose intervals leave the double range reads none of the continued ones, whose
     * ratios are 1) */
    if ((st = rg2__scalars_from_knots_named(&out->su, Uu + 1, nu + 2, 0, "nurbs: knots_u", "knots_u", 1, err)) ||
        (st = rg2__scalars_from_knots_named(&out->sv, Uv + 1, nv + 2, 0, "nurbs: knots_v", "knots_v", 1, err)))
        goto fail;
    for (int i = 0; i < nu; i++)
        for (int j = 0; j < nv; j++) {
            size_t k = (size_t)i * (size_t)nv + (size_t)j;
            double w = nb->weights ? nb->weights[k] : 1.0;
            double *p = rg2_mesh_at(out, i, j);
            for (int d = 0; d < 3; d++)
                p[d] = w * nb->points[3 * k + d];
            p[3] = w;
        }
    if (flu || fhu)
        for (int j = 0; j < nv; j++)
            unclamp_line(rg2_mesh_at(out, 0, j), 4 * (size_t)nv, nu, nb->knots_u, Uu, flu, fhu, 0);
    if (flv || fhv)
        for (int i = 0; i < nu; i++)
            unclamp_line(rg2_mesh_at(out, i, 0), 4, nv, nb->knots_v, Uv, flv, fhv, 0);
    if (flu || fhu || flv || fhv) { /* the magnitudes of the unclamped mesh, and the bound */
        size_t np = (size_t)nu * (size_t)nv;
        if (!(A = rg2__calloc(np * 4, sizeof(double)))) {
            st = rg2__fail(err, RG2_ENOMEM, "nurbs: out of memory");
            goto fail;
        }
        for (size_t k = 0; k < np; k++) {
            double w = nb->weights ? nb->weights[k] : 1.0;
            for (int d = 0; d < 3; d++)
                A[4 * k + d] = fabs(w * nb->points[3 * k + d]);
            A[4 * k + 3] = w;
        }
        if (flu || fhu)
            for (int j = 0; j < nv; j++)
                unclamp_line(A + 4 * (size_t)j, 4 * (size_t)nv, nu, nb->knots_u, Uu, flu, fhu, 1);
        if (flv || fhv)
            for (int i = 0; i < nu; i++)
                unclamp_line(A + 4 * (size_t)i * (size_t)nv, 4, nv, nb->knots_v, Uv, flv, fhv, 1);
        const int fl[4] = {flu, fhu, flv, fhv};
        if ((st = check_clamped_rounding(nb, A, Uu, Uv, fl, err)))
            goto fail;
    }
    free(A);
    free(Uu);
    free(Uv);
    rg2__ok(err);
    return RG2_OK;
fail:
    rg2_mesh_free(out);
    free(A);
    free(Uu);
    free(Uv);
    return st;
}

/*
 * A clamped end whose control line is one point p (a pole: the NURBS's boundary curve there is
 * the curve of that line's 4-tuples (w_i p, w_i), p at every parameter) gives the construction's
 * patches a side that is p in exact arithmetic, but the construction forms it from the
 * extrapolated end points (unclamp_line), whose rounding is of the size of their magnitudes: the
 * side's points h / w spread by a number of roundings of the size that grows with the weights'
 * ratio r (a 4 x 4 NURBS with weights alternating 1 and r along the line: 4 to 13 at r = 32, 88 to
 * 298 at r = 1000). rg2_nurbs_surface and a design's output make such a side the point itself
 * (rg2__surface_set_poles). Only lines whose points have the same x, y and z exactly qualify; a line one point only to
 * rounding is left as the construction makes it.
 */
unsigned rg2__nurbs_pole_ends(const rg2_nurbs *nb, double p[4][3])
{
    unsigned sides = 0;
    for (int side = 0; side < 4; side++) {
        int along_v = side == 0 || side == 2, hi = side == 1 || side == 2; /* a line of u (j fixed) or of v */
        int n = along_v ? nb->nv : nb->nu, cnt = along_v ? nb->nu : nb->nv;
        const double *U = along_v ? nb->knots_v : nb->knots_u;
        if (hi ? !(U[n] == U[n + 1] && U[n + 1] == U[n + 2]) : !(U[1] == U[2] && U[2] == U[3]))
            continue; /* not clamped: the line is no patch side */
        int line = hi ? n - 1 : 0, one = 1;
        const double *q0 = NULL;
        for (int k = 0; k < cnt && one; k++) {
            int i = along_v ? k : line, j = along_v ? line : k;
            const double *q = nb->points + 3 * ((size_t)i * (size_t)nb->nv + (size_t)j);
            if (!q0)
                q0 = q;
            one = q[0] == q0[0] && q[1] == q0[1] && q[2] == q0[2];
        }
        if (one) {
            sides |= 1u << side;
            memcpy(p[side], q0, 3 * sizeof(double));
        }
    }
    return sides;
}

void rg2__surface_set_poles(rg2_surface *s, unsigned sides, const double p[4][3])
{
    for (int side = 0; side < 4; side++) {
        int along_v = side == 0 || side == 2;
        if (!(sides >> side & 1u) || (along_v ? s->closed_v : s->closed_u) || s->xp)
            continue;
        int cnt = along_v ? s->nu : s->nv;
        for (int k = 0; k < cnt; k++) {
            int i = along_v ? k : side == 1 ? s->nu - 1 : 0, j = along_v ? (side == 2 ? s->nv - 1 : 0) : k;
            rg2_patch *P = &s->patch[(size_t)i * (size_t)s->nv + (size_t)j];
            for (int t = 0; t < 4; t++) {
                double *h = along_v ? P->h[t][side == 2 ? 3 : 0] : P->h[side == 1 ? 3 : 0][t];
                for (int d = 0; d < 3; d++)
                    h[d] = h[3] * p[side][d];
            }
        }
    }
}

rg2_status rg2_nurbs_surface(const rg2_nurbs *nb, rg2_surface *out, rg2_error *err)
{
    if (out)
        memset(out, 0, sizeof *out);
    if (!nb || !out)
        return rg2__fail(err, RG2_EINVAL, "nurbs: NULL %s", nb ? "output surface" : "NURBS");
    rg2_mesh m;
    rg2_status st = rg2_nurbs_mesh(nb, &m, err);
    if (st)
        return st;
    st = rg2_surface_build(&m, out, err);
    rg2_mesh_free(&m);
    if (!st) {
        double p[4][3];
        unsigned sides = rg2__nurbs_pole_ends(nb, p);
        rg2__surface_set_poles(out, sides, (const double(*)[3])p);
    }
    return st;
}
