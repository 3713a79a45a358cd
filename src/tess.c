/* tess.c -- watertight triangle meshes of patch surfaces: a uniform (u, v) grid per patch,
 * the grid points on seams stored once (bit-identical on both sides), exact normals and
 * curvatures from the patch evaluation, collapsed sides (poles) merged into one vertex. */
#include "export_internal.h"
#include "xpatch_util.h"

#include <stdlib.h>
#include <string.h>

void rg2_tess_free(rg2_tess *t)
{
    if (!t)
        return;
    free(t->pos);
    free(t->normal);
    free(t->K);
    free(t->H);
    free(t->patch);
    free(t->uv);
    free(t->tri);
    memset(t, 0, sizeof *t);
}

typedef struct {
    double p[3], n[3], K, H;
} tess_sample;

static void normalize3(double v[3])
{
    double l = sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
    if (l > 0.0)
        for (int k = 0; k < 3; k++)
            v[k] /= l;
}

static void cross3(const double a[3], const double b[3], double c[3])
{
    c[0] = a[1] * b[2] - a[2] * b[1];
    c[1] = a[2] * b[0] - a[0] * b[2];
    c[2] = a[0] * b[1] - a[1] * b[0];
}

/*
 * Normal and curvatures on a collapsed side (0 v=0, 1 u=1, 2 v=1, 3 u=0), where Su x Sv
 * vanishes (up to rounding noise, so the evaluator's flag cannot be trusted). METHOD: on a side v = 0
 * that collapses, Su(u, v) = v Suv(u, 0) + O(v^2), so Su x Sv / v -> Suv x Sv: the limit normal
 * is Suv x Sv normalised (the sign flips on v = 1, and u = 0 / 1 use Su x Suv likewise). The
 * curvatures there are taken EPS inside the patch (they have no value on a collapsed side): the
 * rounding error of curvatures next to a pole grows as about 1e-14 / eps^2 (docs/poles.md) and
 * the step's own error as eps, so eps = 3e-5 balances them near 1e-5 (1e-6 gave K = 1.055
 * instead of 1 at the poles of the unit sphere; 3e-5 gives 1 to 1e-4, tests/test_tess.c).
 */
#define POLE_STEP 3e-5
static void degenerate_point(const rg2_surface *s, int i, int j, double u, double v, int side, int curvature,
                             rg2_eval *e)
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
    rg2_surface_eval(s, i, j, u + du, v + dv, curvature ? 2 : 1, &in);
    double l = sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
    if (l > 0.0 && n[0] * in.n[0] + n[1] * in.n[1] + n[2] * in.n[2] > 0.0) {
        normalize3(n);
        memcpy(e->n, n, sizeof n);
    } else {
        memcpy(e->n, in.n, sizeof in.n);
    }
    e->K = in.K;
    e->H = in.H;
}

/*
 * Per-patch sampling of patch (i, j) of s (bi-3 or of higher degree): (d + 1)^2 points at
 * u = a / d, v = b / d, stored at a * (d + 1) + b. `collapsed` has bit k set when side k
 * (0 v=0, 1 u=1, 2 v=1, 3 u=0) is collapsed. This is the only place that evaluates the
 * surface: the grid evaluator (rg2_patch_grid, grid.c; the separable higher-degree grid of
 * xpatch.c for a higher-degree patch) for every point, then the points on collapsed sides again by rg2_surface_eval
 * and degenerate_point. `scratch` holds 8 (d + 1)^2 doubles. Returns non-zero on failure.
 */
static int sample_patch(const rg2_surface *s, int i, int j, int d, int curvature, unsigned collapsed,
                        double *scratch, tess_sample *out)
{
    size_t np = (size_t)(d + 1) * (size_t)(d + 1);
    rg2_grid_out go = {.pos = scratch, .normal = scratch + 3 * np};
    if (curvature) {
        go.K = scratch + 6 * np;
        go.H = scratch + 7 * np;
    }
    if (rg2__surface_patch_grid(s, i, j, d + 1, d + 1, &go, NULL))
        return 1;
    for (size_t k = 0; k < np; k++) {
        memcpy(out[k].p, go.pos + 3 * k, sizeof out[k].p);
        memcpy(out[k].n, go.normal + 3 * k, sizeof out[k].n);
        out[k].K = curvature ? go.K[k] : 0.0;
        out[k].H = curvature ? go.H[k] : 0.0;
    }
    if (!collapsed)
        return 0;
    for (int a = 0; a <= d; a++) {
        double u = a == d ? 1.0 : (double)a / d;
        for (int b = 0; b <= d; b++) {
            double v = b == d ? 1.0 : (double)b / d;
            int side = -1;
            if (b == 0 && (collapsed & 1u))
                side = 0;
            else if (a == d && (collapsed & 2u))
                side = 1;
            else if (b == d && (collapsed & 4u))
                side = 2;
            else if (a == 0 && (collapsed & 8u))
                side = 3;
            if (side < 0)
                continue;
            rg2_eval e;
            rg2_surface_eval(s, i, j, u, v, 2, &e);
            degenerate_point(s, i, j, u, v, side, curvature, &e);
            tess_sample *o = &out[a * (d + 1) + b];
            memcpy(o->p, e.p, sizeof e.p);
            memcpy(o->n, e.n, sizeof e.n);
            o->K = curvature ? e.K : 0.0;
            o->H = curvature ? e.H : 0.0;
        }
    }
    return 0;
}

/* Global grid index of patch-grid point (I, J), folding the closing lines. */
static int gidx(int I, int J, int nu_d, int nv_d, int cu, int cv, int GV)
{
    if (cu && I == nu_d)
        I = 0;
    if (cv && J == nv_d)
        J = 0;
    return I * GV + J;
}

static double dist2(const double *a, const double *b)
{
    double d0 = a[0] - b[0], d1 = a[1] - b[1], d2 = a[2] - b[2];
    return d0 * d0 + d1 * d1 + d2 * d2;
}

/*
 * METHOD: the surface's grid points (I, J), I = 0..nu d, J = 0..nv d, closing lines folded
 * onto line 0, each belong to exactly one patch (the one with i = min(I / d, nu - 1)), which
 * evaluates it; the patch on the other side of a seam uses the same vertex. Sides detected
 * as collapsed (rg2__surface_side_collapsed, patches of any degree) merge their grid points
 * (union-find) into one vertex; triangles that then repeat a vertex are dropped.
 */
rg2_status rg2_tessellate(const rg2_surface *s, int density, int curvature, rg2_tess *out,
                          rg2_error *err)
{
    memset(out, 0, sizeof *out);
    if (!s || s->nu < 1 || s->nv < 1 || !s->patch)
        return rg2__fail(err, RG2_EINVAL, "tessellate: surface has no patches");
    if (density < 1)
        return rg2__fail(err, RG2_EINVAL, "tessellate: density %d, must be >= 1", density);
    rg2_status fst = rg2__surface_check_finite(s, "tessellate", 0, err);
    if (fst)
        return fst;
    int d = density, nu = s->nu, nv = s->nv, cu = s->closed_u != 0, cv = s->closed_v != 0;
    if ((double)nu * d + 1 > RG2_MAX_POINTS || (double)nv * d + 1 > RG2_MAX_POINTS ||
        ((double)nu * d + 1) * ((double)nv * d + 1) > RG2_MAX_POINTS)
        return rg2__fail(err, RG2_ELIMIT, "tessellate: %d x %d patches at density %d exceed %d vertices",
                         nu, nv, d, RG2_MAX_POINTS);
    int nu_d = nu * d, nv_d = nv * d;
    int GU = nu_d + (cu ? 0 : 1), GV = nv_d + (cv ? 0 : 1);
    size_t ng = (size_t)GU * (size_t)GV;
    tess_sample *g = rg2__calloc_big(ng, sizeof *g);
    int *gpatch = rg2__calloc_big(ng, sizeof(int));
    int *parent = rg2__calloc_big(ng, sizeof(int));
    int *id = rg2__calloc_big(ng, sizeof(int));
    size_t max_tri = 2 * (size_t)nu * (size_t)nv * (size_t)d * (size_t)d;
    out->tri = rg2__calloc_big(3 * max_tri, sizeof(int));
    int failed = 0;
    if (!g || !gpatch || !parent || !id || !out->tri) {
        failed = 1;
        goto done;
    }
    double tol = rg2__collapse_tol(s);
#ifdef RG2_HAVE_OPENMP
#pragma omp parallel for schedule(dynamic) if (nu * nv > 16)
#endif
    for (int p = 0; p < nu * nv; p++) {
        int i = p / nv, j = p % nv;
        size_t npp = (size_t)(d + 1) * (size_t)(d + 1);
        tess_sample *buf = malloc(sizeof(tess_sample) * npp);
        double *scratch = malloc(sizeof(double) * 8 * npp);
        if (!buf || !scratch ||
            sample_patch(s, i, j, d, curvature, rg2__surface_collapsed_sides(s, i, j, tol), scratch, buf)) {
            free(buf);
            free(scratch);
#ifdef RG2_HAVE_OPENMP
#pragma omp atomic write
#endif
            failed = 1;
            continue;
        }
        int a1 = (i == nu - 1 && !cu) ? d : d - 1, b1 = (j == nv - 1 && !cv) ? d : d - 1;
        for (int a = 0; a <= a1; a++)
            for (int b = 0; b <= b1; b++) {
                size_t k = (size_t)(i * d + a) * (size_t)GV + (size_t)(j * d + b);
                g[k] = buf[a * (d + 1) + b];
                gpatch[k] = p;
            }
        free(buf);
        free(scratch);
    }
    if (failed)
        goto done;
    for (size_t k = 0; k < ng; k++)
        parent[k] = (int)k;
    for (int i = 0; i < nu; i++)
        for (int j = 0; j < nv; j++)
            for (int side = 0; side < 4; side++) {
                if (!rg2__surface_side_collapsed(s, i, j, side, tol))
                    continue;
                for (int t = 0; t <= d; t++) {
                    int I, J, I0, J0;
                    switch (side) {
                    case 0: I = i * d + t; J = j * d; I0 = i * d; J0 = J; break;
                    case 1: I = (i + 1) * d; J = j * d + t; I0 = I; J0 = j * d; break;
                    case 2: I = i * d + t; J = (j + 1) * d; I0 = i * d; J0 = J; break;
                    default: I = i * d; J = j * d + t; I0 = I; J0 = j * d; break;
                    }
                    rg2__uf_union(parent, gidx(I, J, nu_d, nv_d, cu, cv, GV), gidx(I0, J0, nu_d, nv_d, cu, cv, GV));
                }
            }
    int nvert = 0;
    for (size_t k = 0; k < ng; k++)
        id[k] = rg2__uf_find(parent, (int)k) == (int)k ? nvert++ : -1;
    out->pos = rg2__calloc_big(3 * (size_t)nvert, sizeof(double));
    out->normal = rg2__calloc_big(3 * (size_t)nvert, sizeof(double));
    out->patch = rg2__calloc_big((size_t)nvert, sizeof(int));
    out->uv = rg2__calloc_big(2 * (size_t)nvert, sizeof(double));
    if (curvature) {
        out->K = rg2__calloc_big((size_t)nvert, sizeof(double));
        out->H = rg2__calloc_big((size_t)nvert, sizeof(double));
    }
    if (!out->pos || !out->normal || !out->patch || !out->uv || (curvature && (!out->K || !out->H))) {
        failed = 1;
        goto done;
    }
    out->n_vertices = nvert;
    for (size_t k = 0; k < ng; k++) {
        if (id[k] < 0)
            continue;
        int v = id[k], I = (int)(k / (size_t)GV), J = (int)(k % (size_t)GV);
        memcpy(out->pos + 3 * v, g[k].p, sizeof g[k].p);
        memcpy(out->normal + 3 * v, g[k].n, sizeof g[k].n);
        if (curvature) {
            out->K[v] = g[k].K;
            out->H[v] = g[k].H;
        }
        int p = gpatch[k], a = I - (p / nv) * d, b = J - (p % nv) * d;
        out->patch[v] = p;
        out->uv[2 * v] = a == d ? 1.0 : (double)a / d;
        out->uv[2 * v + 1] = b == d ? 1.0 : (double)b / d;
    }
    for (size_t k = 0; k < ng; k++)
        if (id[k] < 0)
            id[k] = id[rg2__uf_find(parent, (int)k)];
    size_t nt = 0;
    for (int I = 0; I < nu_d; I++)
        for (int J = 0; J < nv_d; J++) {
            int v00 = id[gidx(I, J, nu_d, nv_d, cu, cv, GV)];
            int v10 = id[gidx(I + 1, J, nu_d, nv_d, cu, cv, GV)];
            int v11 = id[gidx(I + 1, J + 1, nu_d, nv_d, cu, cv, GV)];
            int v01 = id[gidx(I, J + 1, nu_d, nv_d, cu, cv, GV)];
            int q[2][3];
            if (dist2(out->pos + 3 * v00, out->pos + 3 * v11) <= dist2(out->pos + 3 * v10, out->pos + 3 * v01)) {
                int t0[2][3] = {{v00, v10, v11}, {v00, v11, v01}};
                memcpy(q, t0, sizeof q);
            } else {
                int t1[2][3] = {{v00, v10, v01}, {v10, v11, v01}};
                memcpy(q, t1, sizeof q);
            }
            for (int t = 0; t < 2; t++) {
                if (q[t][0] == q[t][1] || q[t][1] == q[t][2] || q[t][0] == q[t][2])
                    continue;
                memcpy(out->tri + 3 * nt, q[t], sizeof q[t]);
                nt++;
            }
        }
    out->n_triangles = (int)nt;
done:
    free(g);
    free(gpatch);
    free(parent);
    free(id);
    if (failed) {
        rg2_tess_free(out);
        return rg2__fail(err, RG2_ENOMEM, "tessellate: out of memory for %d x %d patches at density %d",
                         nu, nv, d);
    }
    rg2__ok(err);
    return RG2_OK;
}
