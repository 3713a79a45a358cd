/* mesh.c -- control meshes: a grid of homogeneous 4-tuples with u and v scalars. */
#include "internal.h"

#include <stdlib.h>
#include <string.h>

rg2_status rg2_mesh_init(rg2_mesh *m, int nu, int nv, int closed_u, int closed_v, rg2_error *err)
{
    memset(m, 0, sizeof *m);
    if (nu > 0 && nv > 0 && (long long)nu * nv > RG2_MAX_POINTS)
        return rg2__fail(err, RG2_ELIMIT, "mesh: %d x %d control points exceeds the limit of %d", nu,
                         nv, RG2_MAX_POINTS);
    rg2_status st = rg2_scalars_init(&m->su, nu, closed_u, err);
    if (st)
        return rg2__prefix(err, st, "mesh u");
    st = rg2_scalars_init(&m->sv, nv, closed_v, err);
    if (st) {
        rg2_mesh_free(m);
        return rg2__prefix(err, st, "mesh v");
    }
    m->p = rg2__calloc((size_t)nu * (size_t)nv * 4, sizeof(double));
    if (!m->p) {
        rg2_mesh_free(m);
        return rg2__fail(err, RG2_ENOMEM, "mesh: out of memory for %d x %d points", nu, nv);
    }
    m->nu = nu;
    m->nv = nv;
    return RG2_OK;
}

void rg2_mesh_free(rg2_mesh *m)
{
    if (!m)
        return;
    free(m->p);
    rg2_scalars_free(&m->su);
    rg2_scalars_free(&m->sv);
    memset(m, 0, sizeof *m);
}

rg2_status rg2_mesh_copy(const rg2_mesh *src, rg2_mesh *dst, rg2_error *err)
{
    if (src == dst) /* (filling dst from scratch zeroed src first: the mesh was lost, its arrays leaked,
                       and the message spoke of "mesh u: scalars: 0 control points") */
        return rg2__fail(err, RG2_EINVAL, "mesh copy: the destination is the source; give a mesh of its own");
    rg2_status st = rg2_mesh_init(dst, src->nu, src->nv, src->su.closed, src->sv.closed, err);
    if (st)
        return st;
    memcpy(dst->p, src->p, sizeof(double) * 4 * (size_t)src->nu * (size_t)src->nv);
    rg2_scalars_free(&dst->su);
    rg2_scalars_free(&dst->sv);
    if ((st = rg2_scalars_copy(&src->su, &dst->su, err)) ||
        (st = rg2_scalars_copy(&src->sv, &dst->sv, err))) {
        rg2_mesh_free(dst);
        return st;
    }
    return RG2_OK;
}

rg2_status rg2_mesh_check(const rg2_mesh *m, rg2_error *err)
{
    if (!m || !m->p)
        return rg2__fail(err, RG2_EINVAL, "mesh: empty");
    if (m->su.n != m->nu || m->sv.n != m->nv)
        return rg2__fail(err, RG2_EINVAL, "mesh: %d x %d points but scalars for %d x %d", m->nu, m->nv,
                         m->su.n, m->sv.n);
    rg2_status st = rg2_scalars_check(&m->su, "mesh u", err);
    if (st)
        return st;
    st = rg2_scalars_check(&m->sv, "mesh v", err);
    if (st)
        return st;
    if ((long long)m->nu * m->nv > RG2_MAX_POINTS) /* (each count is within it: the scalars') */
        return rg2__fail(err, RG2_ELIMIT, "mesh: %d x %d control points exceeds the limit of %d", m->nu, m->nv,
                         RG2_MAX_POINTS);
    for (int i = 0; i < m->nu; i++)
        for (int j = 0; j < m->nv; j++) {
            const double *p = rg2_mesh_at(m, i, j);
            for (int k = 0; k < 4; k++)
                if (!rg2__finite(p[k]))
                    return rg2__fail(err, RG2_ENONFINITE, "mesh: control point [%d][%d] component %d is not finite",
                                     i, j, k);
        }
    rg2__ok(err);
    return RG2_OK;
}

rg2_status rg2_mesh_check_weights(const rg2_mesh *m, int *wi, int *wj, rg2_error *err)
{
    for (int i = 0; m && m->p && i < m->nu; i++)
        for (int j = 0; j < m->nv; j++) {
            double W = rg2_mesh_at(m, i, j)[3];
            if (!(W > 0.0)) {
                if (wi)
                    *wi = i;
                if (wj)
                    *wj = j;
                if (!rg2__finite(W))
                    return rg2__fail(err, RG2_ENONFINITE, "control point [%d, %d] has weight W = %g", i, j, W);
                return rg2__fail(err, RG2_EWEIGHT, "control point [%d, %d] has weight W = %.6g, must be > 0", i,
                                 j, W);
            }
        }
    rg2__ok(err);
    return RG2_OK;
}
