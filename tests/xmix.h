/* xmix.h -- surfaces with patches of mixed degree for the consumer tests (tessellation,
 * render, check): the same geometry with a pattern of patches replaced by their exact degree
 * elevations (rg2t_elevate_some). Header-only: static functions. */
#ifndef RG2_XMIX_H
#define RG2_XMIX_H

#include "harness.h"

#include <stdlib.h>

/* Elevate patch k to (4,3) when k % 5 == 0, (5,3) when 1, (4,4) when 2, (3,5) when 3; k % 5 ==
 * 4 stays bi-3. With nv not a multiple of 5 both the u and v neighbours of most patches have
 * another degree, so every seam kind (bi-3 / higher, higher / higher) occurs. */
static inline rg2_status xmix_elevate(rg2_surface *s, rg2_error *err)
{
    static const int deg[4][2] = {{4, 3}, {5, 3}, {4, 4}, {3, 5}};
    for (int q = 0; q < 4; q++) {
        rg2_status st = rg2t_elevate_some(s, deg[q][0], deg[q][1], 5, q, err);
        if (st)
            return st;
    }
    return RG2_OK;
}

/* How many patches of s are of higher degree than bi-3. */
static inline int xmix_count(const rg2_surface *s)
{
    int n = 0;
    for (int i = 0; i < s->nu; i++)
        for (int j = 0; j < s->nv; j++)
            n += rg2_surface_xpatch(s, i, j) != NULL;
    return n;
}

/* A copy of s with the mixed pattern of elevated patches. */
static inline rg2_status xmix_copy(const rg2_surface *s, rg2_surface *out, rg2_error *err)
{
    rg2_status st = rg2_surface_copy(s, out, err);
    if (!st && (st = xmix_elevate(out, err)))
        rg2_surface_free(out);
    return st;
}

/* A copy of s with every patch (bi-3 or already of higher degree) elevated to at least
 * (du, dv): the same surface at the highest degrees. */
static inline rg2_status xmix_raise_copy(const rg2_surface *s, int du, int dv, rg2_surface *out, rg2_error *err)
{
    rg2_status st = rg2_surface_copy(s, out, err);
    size_t np = (size_t)s->nu * (size_t)s->nv;
    if (!st && !out->xp && !(out->xp = calloc(np, sizeof *out->xp)))
        st = RG2_ENOMEM;
    for (int i = 0; !st && i < s->nu; i++)
        for (int j = 0; !st && j < s->nv; j++) {
            rg2_xpatch X;
            rg2_surface_patch_get(s, i, j, &X);
            st = rg2_xpatch_elevate(&X, X.du > du ? X.du : du, X.dv > dv ? X.dv : dv,
                                    out->xp + (size_t)i * (size_t)s->nv + (size_t)j, err);
        }
    if (st)
        rg2_surface_free(out);
    return st;
}

#endif
