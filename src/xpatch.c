/* xpatch.c -- rational Bezier patches of any degree up to RG2_MAX_DEGREE (the general-quadratic
 * polar caps are degree 4 or 5 in u): Bernstein bases, exact evaluation, degree elevation, and
 * the surface accessors that serve both patch kinds. */
#include "internal.h"

#include <stdlib.h>
#include <string.h>

void rg2__bern(int n, double t, double *B, double *D, double *DD)
{
    if (n == 3) {
        rg2__bern3(t, B, D, DD);
        return;
    }
    /* b[k][i]: Bernstein basis of degree k, by the de Casteljau recurrence */
    double b[RG2_MAX_DEGREE + 1][RG2_MAX_DEGREE + 1];
    double s = 1.0 - t;
    b[0][0] = 1.0;
    for (int k = 1; k <= n; k++) {
        b[k][0] = s * b[k - 1][0];
        for (int i = 1; i < k; i++)
            b[k][i] = s * b[k - 1][i] + t * b[k - 1][i - 1];
        b[k][k] = t * b[k - 1][k - 1];
    }
    for (int i = 0; i <= n; i++)
        B[i] = b[n][i];
    if (D)
        for (int i = 0; i <= n; i++)
            D[i] = n * ((i > 0 ? b[n - 1][i - 1] : 0.0) - (i < n ? b[n - 1][i] : 0.0));
    if (DD)
        for (int i = 0; i <= n; i++) {
            double a = 0.0;
            if (n >= 2) {
                a += i >= 2 ? b[n - 2][i - 2] : 0.0;
                a -= i >= 1 && i - 1 <= n - 2 ? 2.0 * b[n - 2][i - 1] : 0.0;
                a += i <= n - 2 ? b[n - 2][i] : 0.0;
            }
            DD[i] = n * (n - 1) * a;
        }
}

static void xeval_h(const rg2_xpatch *X, double u, double v, int order, double out[6][4])
{
    rg2__eval_hom(&X->h[0][0][0], X->du, X->dv, (RG2_MAX_DEGREE + 1) * 4, 4, u, v, order, out);
}

void rg2_xpatch_eval_h(const rg2_xpatch *X, double u, double v, double out[6][4])
{
    xeval_h(X, u, v, 2, out);
}

void rg2_xpatch_eval(const rg2_xpatch *X, double u, double v, int order, rg2_eval *e)
{
    double H[6][4];
    xeval_h(X, u, v, order, H);
    rg2__eval_from_h(H, order, e);
    if (order >= 1 && !(e->flags & RG2_EVAL_NORMAL_UNDEFINED) && rg2__pole_suspect(u, v, e->su, e->sv) &&
        rg2__xpatch_pole_at(X, u, v))
        rg2__eval_undefine(e);
}

void rg2_xpatch_from_patch(const rg2_patch *P, rg2_xpatch *out)
{
    memset(out, 0, sizeof *out);
    out->du = out->dv = 3;
    for (int r = 0; r < 4; r++)
        for (int s = 0; s < 4; s++)
            memcpy(out->h[r][s], P->h[r][s], sizeof(double[4]));
}

/*
 * METHOD: one degree step n -> n + 1 in a direction is Q_i = (i / (n+1)) P_{i-1} +
 * (1 - i / (n+1)) P_i on the homogeneous points (the same polynomials, so the same rational
 * surface); repeated until the target degree.
 */
rg2_status rg2_xpatch_elevate(const rg2_xpatch *X, int du, int dv, rg2_xpatch *out, rg2_error *err)
{
    if (du < X->du || dv < X->dv || du > RG2_MAX_DEGREE || dv > RG2_MAX_DEGREE)
        return rg2__fail(err, RG2_EINVAL,
                         "degree elevation from (%d, %d) to (%d, %d): targets must be >= the patch's "
                         "degrees and <= %d",
                         X->du, X->dv, du, dv, RG2_MAX_DEGREE);
    rg2_xpatch a = *X;
    while (a.du < du) {
        rg2_xpatch b;
        memset(&b, 0, sizeof b);
        int n = a.du;
        b.du = n + 1;
        b.dv = a.dv;
        for (int i = 0; i <= n + 1; i++) {
            double f = (double)i / (n + 1);
            for (int s = 0; s <= a.dv; s++)
                for (int k = 0; k < 4; k++)
                    b.h[i][s][k] = (i > 0 ? f * a.h[i - 1][s][k] : 0.0) + (i <= n ? (1.0 - f) * a.h[i][s][k] : 0.0);
        }
        a = b;
    }
    while (a.dv < dv) {
        rg2_xpatch b;
        memset(&b, 0, sizeof b);
        int n = a.dv;
        b.du = a.du;
        b.dv = n + 1;
        for (int i = 0; i <= n + 1; i++) {
            double f = (double)i / (n + 1);
            for (int r = 0; r <= a.du; r++)
                for (int k = 0; k < 4; k++)
                    b.h[r][i][k] = (i > 0 ? f * a.h[r][i - 1][k] : 0.0) + (i <= n ? (1.0 - f) * a.h[r][i][k] : 0.0);
        }
        a = b;
    }
    *out = a;
    rg2__ok(err);
    return RG2_OK;
}

void rg2_surface_patch_get(const rg2_surface *s, int i, int j, rg2_xpatch *out)
{
    const rg2_xpatch *x = rg2_surface_xpatch(s, i, j);
    if (x)
        *out = *x;
    else
        rg2_xpatch_from_patch(rg2_surface_patch(s, i, j), out);
}

void rg2_surface_degree(const rg2_surface *s, int *du, int *dv)
{
    int a = 3, b = 3;
    if (s->xp)
        for (size_t k = 0; k < (size_t)s->nu * (size_t)s->nv; k++)
            if (s->xp[k].du > 0) {
                a = s->xp[k].du > a ? s->xp[k].du : a;
                b = s->xp[k].dv > b ? s->xp[k].dv : b;
            }
    if (du)
        *du = a;
    if (dv)
        *dv = b;
}

void rg2_surface_eval(const rg2_surface *s, int i, int j, double u, double v, int order, rg2_eval *out)
{
    const rg2_xpatch *x = rg2_surface_xpatch(s, i, j);
    if (x)
        rg2_xpatch_eval(x, u, v, order, out);
    else
        rg2_patch_eval(rg2_surface_patch(s, i, j), u, v, order, out);
}

void rg2_surface_eval_h(const rg2_surface *s, int i, int j, double u, double v, double out[6][4])
{
    const rg2_xpatch *x = rg2_surface_xpatch(s, i, j);
    if (x)
        rg2_xpatch_eval_h(x, u, v, out);
    else
        rg2_patch_eval_h(rg2_surface_patch(s, i, j), u, v, out);
}

static void put3(double *a, size_t i, const double v[3])
{
    if (a)
        memcpy(a + 3 * i, v, sizeof(double[3]));
}

/* ---- grid of higher-degree patches --------------------------------------------------------
 * Separable as the bi-3 grid evaluator (grid.c): Bernstein values at the grid parameters once per
 * call and degree, column sums once per column, then per point the row sums and the derived
 * quantities. The sums run in the order of rg2__eval_hom, so every value equals rg2_xpatch_eval's
 * bit for bit. */

#define XBLK 32 /* columns per block of column sums */

rg2_status rg2__xgrid_make(const rg2_surface *s, int n, int m, const rg2_grid_out *out, rg2__xgrid *t,
                           rg2_error *err)
{
    memset(t, 0, sizeof *t);
    t->n = n;
    t->m = m;
    t->order = out->du || out->dv || out->normal ? 1 : 0;
    if (out->duu || out->duv || out->dvv || out->K || out->H)
        t->order = 2;
    int need[2][RG2_MAX_DEGREE + 1] = {{0}};
    size_t np = (size_t)s->nu * (size_t)s->nv, total = 0, cnt[2] = {(size_t)n, (size_t)m};
    for (size_t k = 0; k < np; k++)
        if (s->xp[k].du > 0)
            need[0][s->xp[k].du] = need[1][s->xp[k].dv] = 1;
    for (int dir = 0; dir < 2; dir++)
        for (int d = 1; d <= RG2_MAX_DEGREE; d++)
            if (need[dir][d])
                total += cnt[dir] * 3 * (size_t)(d + 1);
    t->mem = rg2__calloc(total ? total : 1, sizeof(double));
    if (!t->mem)
        return rg2__fail(err, RG2_ENOMEM, "grid: out of memory for the Bernstein tables of %d x %d points", n, m);
    double *q = t->mem;
    for (int dir = 0; dir < 2; dir++)
        for (int d = 1; d <= RG2_MAX_DEGREE; d++) {
            if (!need[dir][d])
                continue;
            t->tab[dir][d] = q;
            for (size_t a = 0; a < cnt[dir]; a++, q += 3 * (d + 1)) /* B, D, DD of parameter a */
                rg2__bern(d, (double)a / (double)(cnt[dir] - 1), q, q + d + 1, q + 2 * (d + 1));
        }
    return RG2_OK;
}

void rg2__xgrid_free(rg2__xgrid *t)
{
    free(t->mem);
    memset(t, 0, sizeof *t);
}

void rg2__xgrid_patch(const rg2_xpatch *x, const rg2__xgrid *t, const rg2_grid_out *out, size_t first)
{
    const int du = x->du, dv = x->dv, rows = t->order < 1 ? 1 : t->order < 2 ? 3 : 6;
    const size_t su = 3 * (size_t)(du + 1), sv = 3 * (size_t)(dv + 1);
    double c[XBLK][3][RG2_MAX_DEGREE + 1][4]; /* column sums: value, d/dv, d2/dv2 per row r */
    for (int b0 = 0; b0 < t->m; b0 += XBLK) {
        int cnt = t->m - b0 < XBLK ? t->m - b0 : XBLK;
        for (int bb = 0; bb < cnt; bb++) {
            const double *Bv = t->tab[1][dv] + (size_t)(b0 + bb) * sv, *Dv = Bv + dv + 1, *DDv = Dv + dv + 1;
            for (int r = 0; r <= du; r++) {
                double *c0 = c[bb][0][r], *c1 = c[bb][1][r], *c2 = c[bb][2][r];
                for (int k = 0; k < 4; k++)
                    c0[k] = c1[k] = c2[k] = 0.0;
                for (int s = 0; s <= dv; s++)
                    for (int k = 0; k < 4; k++) {
                        double h = x->h[r][s][k];
                        c0[k] += h * Bv[s];
                        if (rows > 1)
                            c1[k] += h * Dv[s];
                        if (rows > 3)
                            c2[k] += h * DDv[s];
                    }
            }
        }
        for (int a = 0; a < t->n; a++) {
            const double *Bu = t->tab[0][du] + (size_t)a * su, *Du = Bu + du + 1, *DDu = Du + du + 1;
            if (rows == 1) { /* positions only: rg2__eval_from_h's expressions for order 0 */
                double *pos = out->pos + 3 * (first + (size_t)a * (size_t)t->m + (size_t)b0);
                for (int bb = 0; bb < cnt; bb++) {
                    double h[4] = {0};
                    for (int r = 0; r <= du; r++)
                        for (int k = 0; k < 4; k++)
                            h[k] += Bu[r] * c[bb][0][r][k];
                    double iw = 1.0 / h[3];
                    for (int k = 0; k < 3; k++)
                        pos[3 * bb + k] = h[k] * iw;
                }
                continue;
            }
            for (int bb = 0; bb < cnt; bb++) {
                double H[6][4] = {{0}};
                for (int r = 0; r <= du; r++)
                    rg2__hom_row(H, rows, Bu[r], Du[r], DDu[r], c[bb][0][r], c[bb][1][r], c[bb][2][r]);
                rg2_eval e;
                rg2__eval_from_h(H, t->order, &e);
                if (!(e.flags & RG2_EVAL_NORMAL_UNDEFINED) && (a == 0 || a == t->n - 1 || b0 + bb == 0 || b0 + bb == t->m - 1)) {
                    /* (as rg2_xpatch_eval: the grid's parameters are exactly 0 and 1 at the ends) */
                    double u = (double)a / (double)(t->n - 1), v = (double)(b0 + bb) / (double)(t->m - 1);
                    if (rg2__pole_suspect(u, v, e.su, e.sv) && rg2__xpatch_pole_at(x, u, v))
                        rg2__eval_undefine(&e);
                }
                size_t q = first + (size_t)a * (size_t)t->m + (size_t)(b0 + bb);
                put3(out->pos, q, e.p);
                put3(out->normal, q, e.n);
                put3(out->du, q, e.su);
                put3(out->dv, q, e.sv);
                put3(out->duu, q, e.suu);
                put3(out->duv, q, e.suv);
                put3(out->dvv, q, e.svv);
                if (out->K)
                    out->K[q] = e.K;
                if (out->H)
                    out->H[q] = e.H;
            }
        }
    }
}
