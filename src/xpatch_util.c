/* xpatch_util.c -- reading a patch of a surface whichever kind it is (bi-3 rg2_patch or
 * higher-degree rg2_xpatch): control points, control boxes, collapsed sides and grids, for
 * the tessellator, the renderer and the check report. */
#include "xpatch_util.h"

#include "export_internal.h"

void rg2__patch_degree(const rg2_surface *s, size_t k, int *du, int *dv)
{
    const rg2_xpatch *x = s->xp && s->xp[k].du > 0 ? s->xp + k : 0;
    *du = x ? x->du : 3;
    *dv = x ? x->dv : 3;
}

const double *rg2__patch_ctrl(const rg2_surface *s, size_t k, int r, int t)
{
    if (s->xp && s->xp[k].du > 0)
        return s->xp[k].h[r][t];
    return s->patch[k].h[r][t];
}

int rg2__surface_ctrl_box(const rg2_surface *s, int positive_only, double lo[3], double hi[3])
{
    return rg2__surface_ctrl_box_ex(s, positive_only, lo, hi, NULL);
}

int rg2__surface_ctrl_box_ex(const rg2_surface *s, int positive_only, double lo[3], double hi[3], size_t *overflow)
{
    int any = 0;
    if (overflow)
        *overflow = 0;
    for (int d = 0; d < 3; d++) {
        lo[d] = INFINITY;
        hi[d] = -INFINITY;
    }
    size_t np = (size_t)s->nu * (size_t)s->nv;
    for (size_t k = 0; k < np; k++) {
        int du, dv, st;
        const double *net = rg2__patch_net(s, k, &du, &dv, &st);
        for (int r = 0; r <= du; r++)
            for (int t = 0; t <= dv; t++) {
                const double *h = net + 4 * (r * st + t);
                if (positive_only && !(h[3] > 0))
                    continue;
                for (int d = 0; d < 3; d++) {
                    double x = h[d] / h[3];
                    if (!isfinite(x)) {
                        if (overflow && !*overflow && h[3] != 0.0) /* h and w finite, h / w not */
                            *overflow = k + 1;
                        continue;
                    }
                    lo[d] = x < lo[d] ? x : lo[d];
                    hi[d] = x > hi[d] ? x : hi[d];
                    any = 1;
                }
            }
    }
    return any;
}

int rg2__xpatch_side_collapsed(const rg2_xpatch *X, int side, double tol)
{
    double c[RG2_MAX_DEGREE + 1][4];
    int n = rg2__xpatch_side(X, side, c);
    for (int a = 1; a < n; a++)
        for (int d = 0; d < 3; d++)
            if (!(fabs(c[a][d] / c[a][3] - c[0][d] / c[0][3]) <= tol))
                return 0;
    return 1;
}

unsigned rg2__xpatch_pole_sides(const rg2_xpatch *X, double u, double v)
{
    unsigned on = (unsigned)(v == 0.0) | (unsigned)(u == 1.0) << 1 | (unsigned)(v == 1.0) << 2 | (unsigned)(u == 0.0) << 3;
    if (!on)
        return 0;
    return rg2__xpatch_collapsed_among(X, on);
}

unsigned rg2__xpatch_collapsed_among(const rg2_xpatch *X, unsigned cand)
{
    rg2_surface one = {0}; /* a one-patch view, for the tolerance */
    one.nu = one.nv = 1;
    one.xp = (rg2_xpatch *)X;
    double tol = rg2__collapse_tol(&one);
    unsigned sides = 0;
    for (int side = 0; side < 4; side++)
        if (cand >> side & 1 && rg2__xpatch_side_collapsed(X, side, tol))
            sides |= 1u << side;
    return sides;
}

int rg2__xpatch_pole_at(const rg2_xpatch *X, double u, double v)
{
    return rg2__xpatch_pole_sides(X, u, v) != 0;
}

__attribute__((noinline)) int rg2__patch_pole_at(const rg2_patch *P, double u, double v)
{
    rg2_xpatch X; /* (about 1 KB: out of line, off the per-point evaluators' stack) */
    rg2_xpatch_from_patch(P, &X);
    return rg2__xpatch_pole_at(&X, u, v);
}

int rg2__surface_side_collapsed(const rg2_surface *s, int i, int j, int side, double tol)
{
    const rg2_xpatch *x = rg2_surface_xpatch(s, i, j);
    if (x)
        return rg2__xpatch_side_collapsed(x, side, tol);
    return rg2__patch_side_collapsed(rg2_surface_patch(s, i, j), side, tol);
}

unsigned rg2__surface_collapsed_sides(const rg2_surface *s, int i, int j, double tol)
{
    const rg2_xpatch *x = rg2_surface_xpatch(s, i, j);
    rg2_xpatch X;
    if (!x) { /* a bi-3 patch: converted once for its four sides */
        rg2_xpatch_from_patch(rg2_surface_patch(s, i, j), &X);
        x = &X;
    }
    unsigned c = 0;
    for (int side = 0; side < 4; side++)
        if (rg2__xpatch_side_collapsed(x, side, tol))
            c |= 1u << side;
    return c;
}

rg2_status rg2__surface_patch_grid(const rg2_surface *s, int i, int j, int n, int m, const rg2_grid_out *out,
                                   rg2_error *err)
{
    const rg2_xpatch *x = rg2_surface_xpatch(s, i, j);
    if (!x)
        return rg2_patch_grid(rg2_surface_patch(s, i, j), n, m, out, err);
    rg2_status st = rg2__grid_check_args(n, m, out, err);
    if (st && !err) /* (the tessellation and the renderer pass no err) */
        return st;
    if (st) { /* (rg2_patch_grid's message, naming the patch: it said "%d x %d points, or no position array") */
        rg2_error e = *err;
        return rg2__fail(err, st, "grid: patch (%d, %d) of degree (%d, %d): %s", i, j, x->du, x->dv,
                         rg2__after(e.msg, "grid: "));
    }
    /* a one-patch view of the higher-degree patch for the tables */
    rg2_surface one = {0};
    one.nu = one.nv = 1;
    one.xp = (rg2_xpatch *)x;
    rg2__xgrid t;
    st = rg2__xgrid_make(&one, n, m, out, &t, err);
    if (st)
        return st;
    rg2__xgrid_patch(x, &t, out, 0);
    rg2__xgrid_free(&t);
    rg2__ok(err);
    return RG2_OK;
}

rg2_status rg2_surface_patch_grid(const rg2_surface *s, int i, int j, int n, int m, const rg2_grid_out *out,
                                  rg2_error *err)
{
    if (!s)
        return rg2__fail(err, RG2_EINVAL, "grid: no surface (s is NULL)");
    if (!s->patch || i < 0 || j < 0 || i >= s->nu || j >= s->nv)
        return rg2__fail(err, RG2_EINVAL, "grid: patch (%d, %d) is not a patch of the surface (%d x %d patches)", i, j,
                         s->nu, s->nv);
    return rg2__surface_patch_grid(s, i, j, n, m, out, err);
}
