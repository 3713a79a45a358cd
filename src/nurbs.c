/* nurbs.c -- bi-cubic NURBS import (MATH.md sections 1 and 5): the control 4-tuples (w P, w)
 * in polynomial mode with the knot-ratio scalars; clamped ends unclamped by blossoming. */
#include "internal.h"

#include <stdlib.h>
#include <string.h>

/* The blossom f(a[0], a[1], a[2]) of the polynomial piece on span [U_l, U_{l+1}] of a cubic
 * B-spline with 4-tuple de Boor points P (stride `stride` doubles between consecutive
 * points, P pointing at P_{l-3}): the de Boor algorithm with one argument per level. */
static void span_blossom(const double *U, int l, const double *P, size_t stride, const double a[3],
                         double out[4])
{
    double d[4][4];
    for (int i = 0; i < 4; i++)
        memcpy(d[i], P + stride * (size_t)i, sizeof d[i]);
    for (int r = 1; r <= 3; r++)
        for (int i = 3; i >= r; i--) { /* d[i] holds de Boor point l - 3 + i */
            int gi = l - 3 + i;
            double al = (a[r - 1] - U[gi]) / (U[gi + 4 - r] - U[gi]);
            for (int k = 0; k < 4; k++)
                d[i][k] = (1.0 - al) * d[i - 1][k] + al * d[i][k];
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
                             "nurbs: %s[%d] = %.17g is smaller than %s[%d] = %.17g; knots must not "
                             "decrease",
                             what, k, U[k], what, k - 1, U[k - 1]);
    for (int k = 4; k <= n; k++)
        if (!(U[k] > U[k - 1])) {
            if (k == 4 || k == n)
                return rg2__fail(err, RG2_EDOMAIN,
                                 "nurbs: %s[%d] = %s[%d] = %.17g: the first or last span of the "
                                 "domain [%s[3], %s[%d]] has zero length",
                                 what, k - 1, what, k, U[k], what, what, n);
            return rg2__fail(err, RG2_EDOMAIN,
                             "nurbs: interior knot %s[%d] = %.17g is repeated (equals %s[%d]); "
                             "rg2 needs distinct interior knots (a repeated knot lowers the "
                             "continuity): split the NURBS into pieces at this knot",
                             what, k, U[k], what, k - 1);
        }
    memcpy(Unew, U, sizeof(double) * (size_t)nk);
    *fix_lo = !(U[1] < U[2] && U[2] < U[3]);
    *fix_hi = !(U[n] < U[n + 1] && U[n + 1] < U[n + 2]);
    if (*fix_lo) {
        double d = U[4] - U[3];
        for (int k = 1; k <= 3; k++)
            Unew[3 - k] = U[3] - k * d;
    }
    if (*fix_hi) {
        double d = U[n] - U[n - 1];
        for (int k = 1; k <= 3; k++)
            Unew[n + k] = U[n] + k * d;
    }
    return RG2_OK;
}

/* Re-blossom the end de Boor points of one direction in place: points P_0, P_1 (fix_lo) and
 * P_{n-2}, P_{n-1} (fix_hi) along a line of n points with the given stride. */
static void unclamp_line(double *P, size_t stride, int n, const double *U, const double *Unew,
                         int fix_lo, int fix_hi)
{
    double q[4][4];
    if (fix_lo) {
        for (int i = 0; i < 2; i++) {
            double a[3] = {Unew[i + 1], Unew[i + 2], Unew[i + 3]};
            span_blossom(U, 3, P, stride, a, q[i]);
        }
    }
    if (fix_hi) {
        for (int i = n - 2; i < n; i++) {
            double a[3] = {Unew[i + 1], Unew[i + 2], Unew[i + 3]};
            span_blossom(U, n - 1, P + stride * (size_t)(n - 4), stride, a, q[2 + i - (n - 2)]);
        }
    }
    if (fix_lo)
        for (int i = 0; i < 2; i++)
            memcpy(P + stride * (size_t)i, q[i], sizeof q[i]);
    if (fix_hi)
        for (int i = n - 2; i < n; i++)
            memcpy(P + stride * (size_t)i, q[2 + i - (n - 2)], sizeof q[0]);
}

/*
 * METHOD: the NURBS with de Boor points P_ij and weights w_ij is the polynomial B-spline of
 * the 4-tuples (w P, w). In rg2's polynomial mode (MATH.md section 1) point i of a direction
 * is the blossom at (v_{i-1}, v_i, v_{i+1}) = (U_{i+1}, U_{i+2}, U_{i+3}), exactly the de Boor
 * point of the same knot vector; so the 4-tuples are the mesh as they are, with the scalars
 * of the knots U_1..U_{n+2}. Clamped ends have zero intervals there: the end de Boor points
 * are replaced by the blossoms of the end pieces at virtual knots (the piece is unchanged,
 * and only the first/last two points depend on U_1, U_2 / U_{n+1}, U_{n+2}).
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
                st = rg2__fail(err, RG2_EWEIGHT, "nurbs: weight [%d][%d] = %.17g must be finite and > 0",
                               i, j, nb->weights[k]);
                goto fail;
            }
        }
    if ((st = rg2_mesh_init(out, nu, nv, 0, 0, err)))
        goto fail;
    rg2_scalars_free(&out->su);
    rg2_scalars_free(&out->sv);
    if ((st = rg2_scalars_from_knots(&out->su, Uu + 1, nu + 2, 0, err)) ||
        (st = rg2_scalars_from_knots(&out->sv, Uv + 1, nv + 2, 0, err)))
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
            unclamp_line(rg2_mesh_at(out, 0, j), 4 * (size_t)nv, nu, nb->knots_u, Uu, flu, fhu);
    if (flv || fhv)
        for (int i = 0; i < nu; i++)
            unclamp_line(rg2_mesh_at(out, i, 0), 4, nv, nb->knots_v, Uv, flv, fhv);
    free(Uu);
    free(Uv);
    rg2__ok(err);
    return RG2_OK;
fail:
    rg2_mesh_free(out);
    free(Uu);
    free(Uv);
    return st;
}
