/* limit.c -- the normal and the curvatures at a pole: on a side of a patch that collapses to a
 * point, Su x Sv vanishes and the evaluators report the normal undefined (rg2.h); the
 * tessellation and rg2_surface_eval_limit give the limit normal and the curvatures next to it. */
#include "xpatch_util.h"

#include <math.h>
#include <string.h>

static void cross3(const double a[3], const double b[3], double c[3])
{
    c[0] = a[1] * b[2] - a[2] * b[1];
    c[1] = a[2] * b[0] - a[0] * b[2];
    c[2] = a[0] * b[1] - a[1] * b[0];
}

/*
 * METHOD: on a side v = 0 that collapses, Su(u, v) = v Suv(u, 0) + O(v^2), so Su x Sv / v ->
 * Suv x Sv: the limit normal is Suv x Sv normalised (the sign flips on v = 1, and u = 0 / 1 use
 * Su x Suv likewise). The curvatures there are taken POLE_STEP inside the patch (they have no
 * value on a collapsed side): the rounding error of curvatures next to a pole grows as about
 * 1e-14 / eps^2 (docs/poles.md) and the step's own error as eps, so eps = 3e-5 balances them near
 * 1e-5 (1e-6 gave K = 1.055 instead of 1 at the poles of the unit sphere; 3e-5 gives 1 to 1e-4,
 * tests/test_tess.c). Where Suv x Sv vanishes too, or points against the normal inside, the
 * normal inside is taken.
 */
#define POLE_STEP 3e-5
void rg2__pole_limit(const rg2_surface *s, int i, int j, double u, double v, int side, int order, rg2_eval *e)
{
    double n[3] = {0, 0, 0};
    if (side == 0 || side == 2) {
        cross3(e->suv, e->sv, n);
        if (side == 2)
            for (int k = 0; k < 3; k++)
                n[k] = -n[k];
    } else {
        cross3(e->su, e->suv, n);
        if (side == 1)
            for (int k = 0; k < 3; k++)
                n[k] = -n[k];
    }
    rg2_eval in;
    double du = u < 0.5 ? POLE_STEP : -POLE_STEP, dv = v < 0.5 ? POLE_STEP : -POLE_STEP;
    rg2_surface_eval(s, i, j, u + du, v + dv, order, &in);
    double l = sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
    if (l > 0.0 && n[0] * in.n[0] + n[1] * in.n[1] + n[2] * in.n[2] > 0.0)
        for (int k = 0; k < 3; k++)
            e->n[k] = n[k] / l;
    else
        memcpy(e->n, in.n, sizeof in.n);
    e->K = in.K;
    e->H = in.H;
    e->k1 = in.k1;
    e->k2 = in.k2;
    /* the limit normal, or the one inside where that is defined: a pole limit; else (a NaN
     * parameter, a degenerate patch) the normal stays undefined, as inside */
    unsigned und = RG2_EVAL_NORMAL_UNDEFINED | RG2_EVAL_CURVATURE_UNDEFINED;
    e->flags = (e->flags & ~und) | (in.flags & und) | (in.flags & RG2_EVAL_NORMAL_UNDEFINED ? 0u : RG2_EVAL_POLE_LIMIT);
}

void rg2_surface_eval_limit(const rg2_surface *s, int i, int j, double u, double v, int order, rg2_eval *out)
{
    rg2_surface_eval(s, i, j, u, v, order, out);
    if (order < 1 || !rg2__on_side(u, v))
        return;
    const rg2_xpatch *x = rg2_surface_xpatch(s, i, j);
    unsigned sides;
    if (x) {
        sides = rg2__xpatch_pole_sides(x, u, v);
    } else {
        rg2_xpatch X;
        rg2_xpatch_from_patch(rg2_surface_patch(s, i, j), &X);
        sides = rg2__xpatch_pole_sides(&X, u, v);
    }
    if (!sides)
        return;
    rg2_eval e = *out;
    if (order < 2)
        rg2_surface_eval(s, i, j, u, v, 2, &e); /* (Suv, for the limit normal) */
    rg2__pole_limit(s, i, j, u, v, __builtin_ctz(sides), order, &e);
    memcpy(out->n, e.n, sizeof e.n); /* (fields beyond the order stay zero: e's curvatures are of that order) */
    out->K = e.K;
    out->H = e.H;
    out->k1 = e.k1;
    out->k2 = e.k2;
    out->flags = e.flags;
}
