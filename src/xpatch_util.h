/* xpatch_util.h -- private helpers that read a patch of a surface whichever kind it is (an
 * ordinary bi-3 rg2_patch or a higher-degree rg2_xpatch in s->xp), for the evaluating
 * consumers (tessellation, rendering, the check report); never installed. */
#ifndef RG2_XPATCH_UTIL_H
#define RG2_XPATCH_UTIL_H

#include "internal.h"

/* Degrees of patch k = i * nv + j of s (3, 3 for a bi-3 patch). */
void rg2__patch_degree(const rg2_surface *s, size_t k, int *du, int *dv);
/* Homogeneous control point (r, t), r <= du, t <= dv, of patch k of s. */
const double *rg2__patch_ctrl(const rg2_surface *s, size_t k, int r, int t);
/* Patch k's homogeneous control net without a copy: point (r, t) at net + 4 (r stride + t), r <=
 * *du, t <= *dv (a bi-3 patch's stride is 4, a higher-degree one's RG2_MAX_DEGREE + 1). */
static inline const double *rg2__patch_net(const rg2_surface *s, size_t k, int *du, int *dv, int *stride)
{
    if (s->xp && s->xp[k].du > 0) {
        *du = s->xp[k].du, *dv = s->xp[k].dv, *stride = RG2_MAX_DEGREE + 1;
        return &s->xp[k].h[0][0][0];
    }
    *du = *dv = 3, *stride = 4;
    return &s->patch[k].h[0][0][0];
}

/* Box of the affine control points of every patch of s (only those of positive weight when
 * positive_only; non-finite coordinates are skipped). Returns 0 when no point counted. */
int rg2__surface_ctrl_box(const rg2_surface *s, int positive_only, double lo[3], double hi[3]);
/* The same, and *overflow: 1 + the index of the first patch with a control point whose h and w
 * are finite, w != 0, but h / w is not (skipped in the box like points at infinity), else 0. */
int rg2__surface_ctrl_box_ex(const rg2_surface *s, int positive_only, double lo[3], double hi[3], size_t *overflow);
/* Whether side `side` (0 v=0, 1 u=1, 2 v=1, 3 u=0) of a patch of any degree collapses to one
 * point (every affine control point of the side within tol of the first, per coordinate; tol
 * from rg2__collapse_tol, export.c, which reads patches of any degree). */
int rg2__xpatch_side_collapsed(const rg2_xpatch *X, int side, double tol);
/* The same for patch (i, j) of s, whichever kind it is. */
int rg2__surface_side_collapsed(const rg2_surface *s, int i, int j, int side, double tol);
/* All four at once: bit k set when side k of patch (i, j) collapses. */
unsigned rg2__surface_collapsed_sides(const rg2_surface *s, int i, int j, double tol);

/* Patch (i, j) of s on an n x m grid in the layout of rg2_patch_grid (point (a, b) at
 * u = a / (n - 1), v = b / (m - 1), index a * m + b): rg2_patch_grid for a bi-3 patch, the
 * higher-degree grid (rg2__xgrid_patch) for a higher-degree one. Errors as rg2_patch_grid. */
rg2_status rg2__surface_patch_grid(const rg2_surface *s, int i, int j, int n, int m, const rg2_grid_out *out,
                                   rg2_error *err);

#endif
