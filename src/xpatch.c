/* xpatch.c -- rational Bezier patches of any degree up to RG2_MAX_DEGREE (the general-quadratic
 * polar caps are degree 4 or 5 in u): Bernstein bases, exact evaluation, degree elevation, and
 * the surface accessors that serve both patch kinds. */
#include "internal.h"

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

void rg2__grid_xpatches(const rg2_surface *s, int n, int m, const rg2_grid_out *out)
{
    int order = out->du || out->dv || out->normal ? 1 : 0;
    if (out->duu || out->duv || out->dvv || out->K || out->H)
        order = 2;
    size_t per = (size_t)n * (size_t)m;
    for (int i = 0; i < s->nu; i++)
        for (int j = 0; j < s->nv; j++) {
            const rg2_xpatch *x = rg2_surface_xpatch(s, i, j);
            if (!x)
                continue;
            size_t base = ((size_t)i * (size_t)s->nv + (size_t)j) * per;
            for (int a = 0; a < n; a++)
                for (int b = 0; b < m; b++) {
                    rg2_eval e;
                    rg2_xpatch_eval(x, (double)a / (n - 1), (double)b / (m - 1), order, &e);
                    size_t q = base + (size_t)a * (size_t)m + (size_t)b;
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
