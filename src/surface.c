/* surface.c -- the Bi-cubic Construction (paper section 3, MATH.md section 4): a control
 * mesh of 4-tuples becomes a grid of rational bi-3 Bezier patches. */
#include "internal.h"
#include "xpatch_util.h"

#include <stdlib.h>
#include <string.h>

void rg2_surface_free(rg2_surface *s)
{
    if (!s)
        return;
    free(s->patch);
    free(s->bu);
    free(s->gu);
    free(s->bv);
    free(s->gv);
    free(s->tag);
    free(s->xp);
    memset(s, 0, sizeof *s);
}

static rg2_status surface_alloc(rg2_surface *s, int nu, int nv, int with_tag, rg2_error *err)
{
    memset(s, 0, sizeof *s);
    s->patch = rg2__calloc_big((size_t)nu * (size_t)nv, sizeof(rg2_patch));
    s->bu = rg2__calloc((size_t)nu, sizeof(double));
    s->gu = rg2__calloc((size_t)nu, sizeof(double));
    s->bv = rg2__calloc((size_t)nv, sizeof(double));
    s->gv = rg2__calloc((size_t)nv, sizeof(double));
    if (with_tag)
        s->tag = rg2__calloc((size_t)nu * (size_t)nv, sizeof(int));
    if (!s->patch || !s->bu || !s->gu || !s->bv || !s->gv || (with_tag && !s->tag)) {
        rg2_surface_free(s);
        return rg2__fail(err, RG2_ENOMEM, "surface: out of memory for %d x %d patches", nu, nv);
    }
    s->nu = nu;
    s->nv = nv;
    return RG2_OK;
}

rg2_status rg2_surface_copy(const rg2_surface *src, rg2_surface *dst, rg2_error *err)
{
    if (!src || !dst)
        return rg2__fail(err, RG2_EINVAL, "surface copy: NULL %s", src ? "destination" : "source");
    if (src->nu < 0 || src->nv < 0 || ((size_t)src->nu * (size_t)src->nv > 0 && !src->patch))
        return rg2__fail(err, RG2_EINVAL, "surface copy: the source is not a surface (%d x %d patches, patch array %s)",
                         src->nu, src->nv, src->patch ? "set" : "NULL");
    if (src->nu == 0 || src->nv == 0 || !src->patch) { /* an empty surface (e.g. after a failed build) */
        memset(dst, 0, sizeof *dst);
        rg2__ok(err);
        return RG2_OK;
    }
    rg2_status st = surface_alloc(dst, src->nu, src->nv, src->tag != NULL, err);
    if (st)
        return st;
    size_t np = (size_t)src->nu * (size_t)src->nv;
    dst->closed_u = src->closed_u;
    dst->closed_v = src->closed_v;
    memcpy(dst->patch, src->patch, np * sizeof(rg2_patch));
    memcpy(dst->bu, src->bu, (size_t)src->nu * sizeof(double));
    memcpy(dst->gu, src->gu, (size_t)src->nu * sizeof(double));
    memcpy(dst->bv, src->bv, (size_t)src->nv * sizeof(double));
    memcpy(dst->gv, src->gv, (size_t)src->nv * sizeof(double));
    if (src->tag)
        memcpy(dst->tag, src->tag, np * sizeof(int));
    if (src->xp) {
        dst->xp = rg2__calloc(np, sizeof(rg2_xpatch));
        if (!dst->xp) {
            rg2_surface_free(dst);
            return rg2__fail(err, RG2_ENOMEM, "surface: out of memory for %zu patches", np);
        }
        memcpy(dst->xp, src->xp, np * sizeof(rg2_xpatch));
    }
    rg2__ok(err);
    return RG2_OK;
}

/*
 * METHOD: the curve construction is linear in the points, so it is a stencil per direction
 * (rg2__stencil_make). Rows first: for u-segment k, R[r][j] = sum_a cu[k][r][a] p^{iu+a, j}
 * for every mesh column j; then columns: b_rs = sum_c cv[l][s][c] R[r][jv+c]. Homogeneous
 * control points H_rs = omega_r omega'_s b_rs with omega = (1, w, w, 1).
 *
 * build_into: out holds a surface (or zeros); its arrays are kept when its patch counts are those
 * of m (no fresh memory, so no page faults: an editing loop), else freed and allocated anew. On
 * failure out is left empty.
 */
/* The homogeneous values of n doubles (4-tuples, weight last) times 2^-e, where 2^e <= the largest
 * weight < 2^(e+1), if that weight lies outside [2^-32, 2^32]. */
static void normalize_weights(double *h, int n)
{
    double m = 0.0;
    for (int q = 3; q < n; q += 4)
        m = fmax(m, fabs(h[q]));
    if (!(m > 0.0) || (m >= 0x1p-32 && m <= 0x1p32) || !(m <= 1.79e308))
        return;
    double t = ldexp(1.0, -ilogb(m));
    for (int q = 0; q < n; q++)
        h[q] *= t;
}

static rg2_status build_into(const rg2_mesh *m, rg2_surface *out, rg2_error *err)
{
    rg2__stencil su, sv;
    rg2_status st = rg2_mesh_check(m, err);
    if (!st && !(st = rg2__stencil_make(&m->su, &su, err)) && (st = rg2__stencil_make(&m->sv, &sv, err)))
        rg2__stencil_free(&su);
    if (st) {
        rg2_surface_free(out);
        return st;
    }
    int nsu = su.n_segments, nsv = sv.n_segments;
    if (out->patch && out->bu && out->gu && out->bv && out->gv && out->nu == nsu && out->nv == nsv) {
        free(out->tag); /* a built surface has neither tags nor higher-degree patches */
        free(out->xp);
        out->tag = NULL;
        out->xp = NULL;
    } else {
        rg2_surface_free(out);
        st = surface_alloc(out, nsu, nsv, 0, err);
        if (st)
            goto done;
    }
    out->closed_u = m->su.closed;
    out->closed_v = m->sv.closed;
    for (int k = 0; k < nsu; k++) {
        out->bu[k] = su.bj[k];
        out->gu[k] = su.gj[k];
    }
    for (int l = 0; l < nsv; l++) {
        out->bv[l] = sv.bj[l];
        out->gv[l] = sv.gj[l];
    }
    int nv = m->nv, failed = 0;
#ifdef RG2_HAVE_OPENMP
#pragma omp parallel for schedule(static) if (nsu * nsv > 256)
#endif
    for (int k = 0; k < nsu; k++) {
        double(*R)[4] = malloc(sizeof(double[4]) * 4 * (size_t)nv); /* R[r * nv + j][comp] */
        if (!R) {
#ifdef RG2_HAVE_OPENMP
#pragma omp atomic write
#endif
            failed = 1;
            continue;
        }
        for (int r = 0; r < 4; r++)
            for (int j = 0; j < nv; j++) {
                double acc[4] = {0, 0, 0, 0};
                for (int a = 0; a < 4; a++) {
                    double c = su.c[k][r][a];
                    if (c == 0.0)
                        continue;
                    const double *p = rg2_mesh_at(m, rg2__wrap(su.first[k] + a, m->nu, su.closed), j);
                    for (int q = 0; q < 4; q++)
                        acc[q] += c * p[q];
                }
                memcpy(R[r * nv + j], acc, sizeof acc);
            }
        double omu[4] = {1.0, su.w[k], su.w[k], 1.0};
        for (int l = 0; l < nsv; l++) {
            rg2_patch *P = rg2_surface_patch(out, k, l);
            double omv[4] = {1.0, sv.w[l], sv.w[l], 1.0};
            for (int r = 0; r < 4; r++)
                for (int s = 0; s < 4; s++) {
                    double acc[4] = {0, 0, 0, 0};
                    for (int c = 0; c < 4; c++) {
                        double cc = sv.c[l][s][c];
                        if (cc == 0.0)
                            continue;
                        const double *q = R[r * nv + rg2__wrap(sv.first[l] + c, nv, sv.closed)];
                        for (int d = 0; d < 4; d++)
                            acc[d] += cc * q[d];
                    }
                    double om = omu[r] * omv[s];
                    for (int d = 0; d < 4; d++)
                        P->h[r][s][d] = om * acc[d];
                }
        }
        free(R);
    }
    if (failed) {
        rg2_surface_free(out);
        st = rg2__fail(err, RG2_ENOMEM, "surface: out of memory during construction");
        goto done;
    }
    /* finite control points in, but the construction may overflow: refuse such a surface */
    for (size_t k = 0; k < (size_t)nsu * (size_t)nsv; k++) {
        const double *h = &out->patch[k].h[0][0][0];
        for (int q = 0; q < 64; q++)
            if (!rg2__finite(h[q])) {
                int pi = (int)(k / (size_t)nsv), pj = (int)(k % (size_t)nsv);
                rg2_surface_free(out);
                st = rg2__fail(err, RG2_ENONFINITE,
                               "surface: patch (%d, %d) overflows (a control value is not finite); "
                               "the mesh coordinates or scalars are too large",
                               pi, pj);
                goto done;
            }
        normalize_weights(&out->patch[k].h[0][0][0], 64); /* (while the patch is in cache) */
    }
done:
    rg2__stencil_free(&su);
    rg2__stencil_free(&sv);
    return st;
}

void rg2__surface_normalize_weights(rg2_surface *s)
{
    size_t np = (size_t)s->nu * (size_t)s->nv;
    for (size_t k = 0; k < np; k++) {
        if (s->xp && s->xp[k].du > 0)
            normalize_weights(&s->xp[k].h[0][0][0], (RG2_MAX_DEGREE + 1) * (RG2_MAX_DEGREE + 1) * 4);
        else
            normalize_weights(&s->patch[k].h[0][0][0], 64);
    }
}

rg2_status rg2_surface_build(const rg2_mesh *m, rg2_surface *out, rg2_error *err)
{
    memset(out, 0, sizeof *out); /* out may hold garbage: nothing of it is kept */
    return build_into(m, out, err);
}

rg2_status rg2_surface_rebuild(const rg2_mesh *m, rg2_surface *s, rg2_error *err)
{
    if (!s)
        return rg2__fail(err, RG2_EINVAL, "surface: rebuild into a NULL surface");
    return build_into(m, s, err);
}

double rg2_surface_min_weight(const rg2_surface *s)
{
    double mn = INFINITY;
    size_t np = (size_t)s->nu * (size_t)s->nv;
    for (size_t k = 0; k < np; k++)
        for (int r = 0; r < 4; r++)
            for (int t = 0; t < 4; t++)
                if (s->patch[k].h[r][t][3] < mn)
                    mn = s->patch[k].h[r][t][3];
    if (s->xp)
        for (size_t k = 0; k < np; k++)
            for (int r = 0; r <= s->xp[k].du; r++)
                for (int t = 0; t <= s->xp[k].dv; t++)
                    if (s->xp[k].du > 0 && s->xp[k].h[r][t][3] < mn)
                        mn = s->xp[k].h[r][t][3];
    return mn;
}

rg2_status rg2__surface_check_finite(const rg2_surface *s, const char *what, int index, rg2_error *err)
{
    size_t np = (size_t)s->nu * (size_t)s->nv;
    for (size_t k = 0; k < np; k++) {
        int du, dv;
        rg2__patch_degree(s, k, &du, &dv);
        for (int q = 0; q < 4 * (du + 1) * (dv + 1); q++)
            if (!rg2__finite(rg2__patch_ctrl(s, k, q / 4 / (dv + 1), q / 4 % (dv + 1))[q % 4]))
                return rg2__fail(err, RG2_ENONFINITE, "%s: surface %d patch (%zu,%zu) has a non-finite control point",
                                 what, index, k / (size_t)s->nv, k % (size_t)s->nv);
    }
    return RG2_OK;
}
