/* curve.c -- the rational cubic G2 spline construction (paper section 2, MATH.md eq. 3-4)
 * as a linear stencil, the curve built from it, and exact curve evaluation. */
#include "internal.h"

#include <stdlib.h>
#include <string.h>

void rg2__stencil_free(rg2__stencil *st)
{
    if (!st)
        return;
    free(st->first);
    free(st->c);
    free(st->w);
    free(st->bj);
    free(st->gj);
    memset(st, 0, sizeof *st);
}

/*
 * METHOD: for leg i (p^i -> p^{i+1}) with junction scalars at i and i+1,
 *   A_i = 2 (w_i + b_i w_{i-1}) / (w_{i-1} K_i),  B_i = 2 b_{i+1}^2 (w_{i+1} + b_{i+1} w_i) / (w_{i+1} K_{i+1})
 *   t_i = A_i / (1 + A_i + B_i), s_i = B_i / (1 + A_i + B_i)
 *   b^i_1 = (1 - t_i) p^i + t_i p^{i+1},  b^i_2 = s_i p^i + (1 - s_i) p^{i+1}
 *   x_i = w_i / (w_i + b_i w_{i-1}),  b^i_0 = (1 - x_i) b^{i-1}_2 + x_i b^i_1 = b^{i-1}_3.
 * Segment i thus depends on p^{i-1..i+2}; its stencil rows are over those four points.
 * The scalars must have passed rg2_scalars_check.
 */
rg2_status rg2__stencil_make(const rg2_scalars *s, rg2__stencil *st, rg2_error *err)
{
    memset(st, 0, sizeof *st);
    int n = s->n, closed = s->closed;
    int ns = rg2_scalars_num_segments(s);
    st->n = n;
    st->closed = closed;
    st->n_segments = ns;
    st->first = rg2__calloc((size_t)ns, sizeof(int));
    st->c = rg2__calloc((size_t)ns, sizeof(double[4][4]));
    st->w = rg2__calloc((size_t)ns, sizeof(double));
    st->bj = rg2__calloc((size_t)ns, sizeof(double));
    st->gj = rg2__calloc((size_t)ns, sizeof(double));
    if (!st->first || !st->c || !st->w || !st->bj || !st->gj) {
        rg2__stencil_free(st);
        return rg2__fail(err, RG2_ENOMEM, "construction: out of memory for %d segments", ns);
    }
    for (int k = 0; k < ns; k++) {
        int i = closed ? k : k + 1; /* leg index of this segment */
        double t[3], sv[3];         /* t_{i-1..i+1}, s_{i-1..i+1} */
        for (int d = -1; d <= 1; d++) {
            int l = i + d;
            int jl = rg2__wrap(l, n, closed), jl1 = rg2__wrap(l + 1, n, closed);
            double wl = rg2_scalars_leg_w(s, l), wlm = rg2_scalars_leg_w(s, l - 1),
                   wlp = rg2_scalars_leg_w(s, l + 1);
            double bl = s->b[jl], bl1 = s->b[jl1];
            double A = 2.0 * (wl + bl * wlm) / (wlm * rg2_scalars_K(s, jl));
            double B = 2.0 * bl1 * bl1 * (wlp + bl1 * wl) / (wlp * rg2_scalars_K(s, jl1));
            double L = 1.0 / (1.0 + A + B);
            t[d + 1] = A * L;
            sv[d + 1] = B * L;
        }
        int ji = rg2__wrap(i, n, closed), ji1 = rg2__wrap(i + 1, n, closed);
        double wi = rg2_scalars_leg_w(s, i);
        double x0 = wi / (wi + s->b[ji] * rg2_scalars_leg_w(s, i - 1));
        double wn = rg2_scalars_leg_w(s, i + 1);
        double x1 = wn / (wn + s->b[ji1] * wi);
        double(*c)[4] = st->c[k];
        memset(c, 0, sizeof(double[4][4]));
        /* columns a = 0..3 are p^{i-1}, p^i, p^{i+1}, p^{i+2} */
        /* b1 and b2 of leg i */
        c[1][1] = 1.0 - t[1];
        c[1][2] = t[1];
        c[2][1] = sv[1];
        c[2][2] = 1.0 - sv[1];
        /* b0 = (1 - x0) b^{i-1}_2 + x0 b^i_1 ; b^{i-1}_2 = s_{i-1} p^{i-1} + (1 - s_{i-1}) p^i */
        c[0][0] = (1.0 - x0) * sv[0];
        c[0][1] = (1.0 - x0) * (1.0 - sv[0]) + x0 * (1.0 - t[1]);
        c[0][2] = x0 * t[1];
        /* b3 = (1 - x1) b^i_2 + x1 b^{i+1}_1 ; b^{i+1}_1 = (1 - t_{i+1}) p^{i+1} + t_{i+1} p^{i+2} */
        c[3][1] = (1.0 - x1) * sv[1];
        c[3][2] = (1.0 - x1) * (1.0 - sv[1]) + x1 * (1.0 - t[2]);
        c[3][3] = x1 * t[2];
        st->first[k] = i - 1;
        st->w[k] = wi;
        st->bj[k] = s->b[ji];
        st->gj[k] = s->g[ji];
    }
    rg2__ok(err);
    return RG2_OK;
}

rg2_status rg2_curve_build(int dim, const double *points, const rg2_scalars *s, rg2_curve *out,
                           rg2_error *err)
{
    memset(out, 0, sizeof *out);
    if (dim < 1 || dim > RG2_MAX_DIM)
        return rg2__fail(err, RG2_EINVAL, "curve: dimension %d, must be 1..%d", dim, RG2_MAX_DIM);
    rg2_status st = rg2_scalars_check(s, "curve", err);
    if (st)
        return st;
    for (int i = 0; i < s->n; i++)
        for (int d = 0; d < dim; d++)
            if (!rg2__finite(points[i * dim + d]))
                return rg2__fail(err, RG2_ENONFINITE, "curve: control point %d coordinate %d is not finite",
                                 i, d);
    rg2__stencil sten;
    st = rg2__stencil_make(s, &sten, err);
    if (st)
        return st;
    int ns = sten.n_segments;
    out->bez = rg2__calloc((size_t)ns * 4 * (size_t)dim, sizeof(double));
    out->w = rg2__calloc((size_t)ns, sizeof(double));
    if (!out->bez || !out->w) {
        rg2__stencil_free(&sten);
        rg2_curve_free(out);
        return rg2__fail(err, RG2_ENOMEM, "curve: out of memory for %d segments", ns);
    }
    out->dim = dim;
    out->n_segments = ns;
    out->closed = s->closed;
    for (int k = 0; k < ns; k++) {
        out->w[k] = sten.w[k];
        for (int r = 0; r < 4; r++) {
            double *dst = out->bez + ((size_t)k * 4 + (size_t)r) * (size_t)dim;
            for (int a = 0; a < 4; a++) {
                double c = sten.c[k][r][a];
                if (c == 0.0)
                    continue;
                const double *p = points + (size_t)rg2__wrap(sten.first[k] + a, s->n, s->closed) * (size_t)dim;
                for (int d = 0; d < dim; d++)
                    dst[d] += c * p[d];
            }
        }
    }
    rg2__stencil_free(&sten);
    return RG2_OK;
}

void rg2_curve_free(rg2_curve *c)
{
    if (!c)
        return;
    free(c->bez);
    free(c->w);
    memset(c, 0, sizeof *c);
}

void rg2_curve_eval(const rg2_curve *c, int seg, double t, double *pos, double *d1, double *d2)
{
    double B[4], D[4], DD[4];
    rg2__bern3(t, B, D, DD);
    double om[4] = {1.0, c->w[seg], c->w[seg], 1.0};
    double W = 0, Wt = 0, Wtt = 0;
    for (int r = 0; r < 4; r++) {
        W += om[r] * B[r];
        Wt += om[r] * D[r];
        Wtt += om[r] * DD[r];
    }
    const double *b = c->bez + (size_t)seg * 4 * (size_t)c->dim;
    for (int d = 0; d < c->dim; d++) {
        double X = 0, Xt = 0, Xtt = 0;
        for (int r = 0; r < 4; r++) {
            double h = om[r] * b[r * c->dim + d];
            X += h * B[r];
            Xt += h * D[r];
            Xtt += h * DD[r];
        }
        double p = X / W;
        double p1 = (Xt - Wt * p) / W;
        double p2 = (Xtt - 2.0 * Wt * p1 - Wtt * p) / W;
        if (pos)
            pos[d] = p;
        if (d1)
            d1[d] = p1;
        if (d2)
            d2[d] = p2;
    }
}

double rg2_curve_curvature(const rg2_curve *c, int seg, double t)
{
    if (c->dim < 2 || c->dim > 3)
        return 0.0;
    double a[3] = {0}, b[3] = {0};
    rg2_curve_eval(c, seg, t, NULL, a, b);
    /* the curve scaled by s = 2^-e into the range where |a|^3 and the cross product stay finite
     * (a pentagon of radius 1e78 gave inf, 1e-150 NaN); its curvature is that of the curve / s */
    double s = rg2__scale_pair(a, b);
    double cx = a[1] * b[2] - a[2] * b[1], cy = a[2] * b[0] - a[0] * b[2], cz = a[0] * b[1] - a[1] * b[0];
    double na = sqrt(a[0] * a[0] + a[1] * a[1] + a[2] * a[2]);
    if (na == 0.0)
        return 0.0;
    return sqrt(cx * cx + cy * cy + cz * cz) / (na * na * na) * s;
}
