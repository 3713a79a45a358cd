/* export.c -- the export dispatcher (format by file extension), the JSON patch dump, and
 * helpers shared by the writers: temporary-file output, STEP/IGES reals, weight checks,
 * collapsed patch sides and the corner/edge topology of a patch grid. */
#define _POSIX_C_SOURCE 200809L
#include "export_internal.h"
#include "xpatch_util.h"

#include <cjson/cJSON.h>
#include <ctype.h>
#include <errno.h>
#include <float.h>
#include <math.h>
#include <stdatomic.h>
#include <stdlib.h>
#include <string.h>
#include <strings.h>
#include <time.h>

static const char default_name[] = "rg2"; /* (rg2_export_opts.name when NULL) */

void rg2_export_opts_default(rg2_export_opts *o)
{
    memset(o, 0, sizeof *o);
    o->layout = RG2_STEP_FACE_PER_PATCH;
    o->ap242 = 0;
    o->density = 16;
    o->name = default_name;
}

/* ---------------------------------------------------------------- numbers and checks */

void rg2__utc_stamp(char *buf, size_t cap, const char *fmt)
{
    time_t now = time(NULL);
    const char *sde = getenv("SOURCE_DATE_EPOCH"); /* reproducible files (reproducible-builds.org) */
    if (sde && *sde) {
        char *end;
        errno = 0;
        long long t = strtoll(sde, &end, 10);
        if (!*end && !errno && t >= 0)
            now = (time_t)t;
    }
    struct tm tmv;
    if (!gmtime_r(&now, &tmv) || strftime(buf, cap, fmt, &tmv) == 0) {
        memset(&tmv, 0, sizeof tmv);
        tmv.tm_year = 100;
        tmv.tm_mday = 1;
        strftime(buf, cap, fmt, &tmv);
    }
}

void rg2__real(char buf[40], double x)
{
    if (x == 0.0)
        x = 0.0; /* no "-0." */
    char tmp[32];
    snprintf(tmp, sizeof tmp, "%.17G", x);
    char *e = strchr(tmp, 'E');
    if (strchr(tmp, '.')) {
        memcpy(buf, tmp, strlen(tmp) + 1);
    } else if (e) {
        size_t k = (size_t)(e - tmp);
        memcpy(buf, tmp, k);
        buf[k] = '.';
        memcpy(buf + k + 1, e, strlen(e) + 1);
    } else {
        snprintf(buf, 40, "%s.", tmp);
    }
}

#define WRITE_ROUND 16 /* blocks formatted per round (8 per thread on the 2-core machines) */

int rg2__write_blocks(FILE *f, int n, int block, rg2__block_fn fn, rg2__block_fix fix, void *ctx)
{
    if (n <= 0)
        return 0;
    if (n <= block && !fix)
        return fn(f, ctx, 0, 0, n);
    char *buf[WRITE_ROUND] = {0};
    size_t len[WRITE_ROUND] = {0};
    FILE *m[WRITE_ROUND] = {0};
    int nblk = (n - 1) / block + 1, bad = 0;
    for (int r = 0; r < WRITE_ROUND && r < nblk; r++)
        if (!(m[r] = open_memstream(&buf[r], &len[r])))
            bad = -1;
    for (int b0 = 0; b0 < nblk && !bad; b0 += WRITE_ROUND) {
        int nb = nblk - b0 < WRITE_ROUND ? nblk - b0 : WRITE_ROUND;
        long used[WRITE_ROUND];
#ifdef RG2_HAVE_OPENMP
#pragma omp parallel for schedule(dynamic, 1)
#endif
        for (int r = 0; r < nb; r++) {
            int b = b0 + r, k0 = b * block, k1 = k0 + block < n ? k0 + block : n;
            void *loc = rg2__c_numeric_begin(); /* this thread's numbers in the C locale */
            int st = fseek(m[r], 0, SEEK_SET) ? -1 : fn(m[r], ctx, b, k0, k1);
            rg2__c_numeric_end(loc);
            if (!st && (fflush(m[r]) || (used[r] = ftell(m[r])) < 0))
                st = -1;
            if (st) {
#ifdef RG2_HAVE_OPENMP
#pragma omp atomic write
#endif
                bad = st;
            }
        }
        for (int r = 0; r < nb && !bad; r++) { /* (buf[r] as of the fflush) */
            if (fix)
                fix(ctx, b0 + r, buf[r], (size_t)used[r]);
            fwrite(buf[r], 1, (size_t)used[r], f);
        }
    }
    for (int r = 0; r < WRITE_ROUND; r++) {
        if (m[r])
            fclose(m[r]);
        free(buf[r]);
    }
    return bad;
}

rg2_status rg2__check_nonempty(const rg2_surface *surfs, int n_surfs, rg2_error *err)
{
    if (!surfs || n_surfs < 1)
        return rg2__fail(err, RG2_EINVAL, "export: no surfaces to write (%s)",
                         !surfs ? "surfs is NULL" : n_surfs == 0 ? "n_surfs = 0: an empty design" : "n_surfs < 0");
    for (int k = 0; k < n_surfs; k++)
        if (surfs[k].nu < 1 || surfs[k].nv < 1 || !surfs[k].patch)
            return rg2__fail(err, RG2_EINVAL, "export: surface %d has no patches (%d x %d)", k,
                             surfs[k].nu, surfs[k].nv);
    return RG2_OK;
}

rg2_status rg2__check_weights(const rg2_surface *surfs, int n_surfs, const char *format,
                              rg2_error *err)
{
    /* two passes: a non-finite value anywhere is named before any weight (the mesh formats
     * refuse only the former; a negative weight first once hid a later NaN from them) */
    for (int pass = 0; pass < 2; pass++)
        for (int k = 0; k < n_surfs; k++) {
            const rg2_surface *s = &surfs[k];
            for (int i = 0; i < s->nu; i++)
                for (int j = 0; j < s->nv; j++) {
                    rg2_xpatch P;
                    rg2_surface_patch_get(s, i, j, &P);
                    for (int r = 0; r <= P.du; r++)
                        for (int t = 0; t <= P.dv; t++) {
                            const double *h = P.h[r][t];
                            if (pass == 0 && !(rg2__finite(h[0]) && rg2__finite(h[1]) && rg2__finite(h[2]) &&
                                               rg2__finite(h[3])))
                                return rg2__fail(err, RG2_ENONFINITE,
                                                 "%s: surface %d patch (%d, %d) control point [%d][%d] "
                                                 "is not finite",
                                                 format, k, i, j, r, t);
                            if (pass == 1 && !(h[3] > 0.0))
                                return rg2__fail(err, RG2_EWEIGHT,
                                                 "%s: surface %d patch (%d, %d) control point [%d][%d] has "
                                                 "weight %g; %s needs every weight > 0 (importers drop "
                                                 "the face or ignore the weights): use more arcs or knots "
                                                 "there (coarse ones can give an exact shape patch weights "
                                                 "<= 0, docs/shapes.md \"Homogeneous weights\"; a merge's "
                                                 "note on a weight <= 0 says which knots to move)",
                                                 format, k, i, j, r, t, h[3], format);
                        }
                }
        }
    return RG2_OK;
}

/* ---------------------------------------------------------------- patch sides */

int rg2__xpatch_side(const rg2_xpatch *X, int side, double out[RG2_MAX_DEGREE + 1][4])
{
    int n = (side & 1) ? X->dv : X->du;
    for (int a = 0; a <= n; a++) {
        const double *h;
        switch (side) {
        case 0: h = X->h[a][0]; break;
        case 1: h = X->h[X->du][a]; break;
        case 2: h = X->h[a][X->dv]; break;
        default: h = X->h[0][a]; break;
        }
        memcpy(out[a], h, sizeof(double[4]));
    }
    return n + 1;
}

int rg2__xpatch_net(const rg2_xpatch *X, double (*out)[4])
{
    for (int r = 0; r <= X->du; r++)
        memcpy(out[r * (X->dv + 1)], X->h[r], sizeof(double[4]) * (size_t)(X->dv + 1));
    return (X->du + 1) * (X->dv + 1);
}

int rg2__patch_side_collapsed(const rg2_patch *P, int side, double tol)
{
    rg2_xpatch X;
    rg2_xpatch_from_patch(P, &X);
    return rg2__xpatch_side_collapsed(&X, side, tol);
}

double rg2__collapse_tol(const rg2_surface *s)
{
    double lo[3], hi[3], diag = 0.0;
    if (!rg2__surface_ctrl_box(s, 0, lo, hi))
        return 0.0;
    for (int d = 0; d < 3; d++)
        diag += (hi[d] - lo[d]) * (hi[d] - lo[d]);
    return 1e-11 * sqrt(diag);
}

/* ---------------------------------------------------------------- topology */

int rg2__uf_find(int *parent, int a)
{
    while (parent[a] != a) {
        parent[a] = parent[parent[a]];
        a = parent[a];
    }
    return a;
}

void rg2__uf_union(int *parent, int a, int b)
{
    a = rg2__uf_find(parent, a);
    b = rg2__uf_find(parent, b);
    if (a < b)
        parent[b] = a;
    else if (b < a)
        parent[a] = b;
}

void rg2__topo_free(rg2__topo *t)
{
    free(t->vert);
    free(t->ue);
    free(t->ve);
    free(t->vcorner);
    free(t->edef);
    free(t->uses);
    free(t->snap);
    free(t->pole);
    memset(t, 0, sizeof *t);
}

/* Side `side` of patch (i, j) as a grid edge: array (0 ue, 1 ve) and index, before (raw)
 * or after (folded) identifying the closing line of a closed direction with line 0. */
static void side_slot(int nu, int nv, int closed_u, int closed_v, int i, int j, int side, int *which,
                      int *idx)
{
    switch (side) {
    case 0: *which = 1; *idx = j * nu + i; break;
    case 1: *which = 0; *idx = (i + 1) * nv + j; break;
    case 2: *which = 1; *idx = (j + 1) * nu + i; break;
    default: *which = 0; *idx = i * nv + j; break;
    }
    if (*which == 0 && closed_u && *idx >= nu * nv)
        *idx -= nu * nv;
    if (*which == 1 && closed_v && *idx >= nv * nu)
        *idx -= nv * nu;
}

/* Degree of patch (i, j) along side `side` (u-degree on sides 0 and 2, v-degree on 1 and 3). */
static int side_degree(const rg2_surface *s, int i, int j, int side)
{
    const rg2_xpatch *x = rg2_surface_xpatch(s, i, j);
    return x ? ((side & 1) ? x->dv : x->du) : 3;
}

/* The vertex whose pole control point (r, q) of patch (i, j) of degrees (du, dv) would be: a
 * corner's vertex, or for a point on a collapsed side the vertex of its ends; -1 for any other
 * point (inside the patch, on a side that is an edge). */
static int pole_vertex(const rg2__topo *t, int i, int j, int r, int q, int du, int dv)
{
    int nv = t->nv, a = r == 0 ? 0 : r == du ? 1 : -1, b = q == 0 ? 0 : q == dv ? 1 : -1, e, f;
    if (a >= 0 && b >= 0)
        return t->vert[(i + a) * (nv + 1) + j + b];
    if (a < 0 && b < 0)
        return -1;
    rg2__topo_side(t, i, j, a >= 0 ? (a ? 1 : 3) : (b ? 2 : 0), &e, &f);
    return e >= 0 ? -1 : t->vert[(i + (a > 0)) * (nv + 1) + j + (b > 0)];
}

/*
 * The poles of a topology (t->snap, t->pole; both NULL without a collapsed edge): the
 * candidates are the vertices of collapsed edges, each with the point h / w of its corner
 * vcorner[v] (the point written for its VERTEX_POINT); a candidate is a pole when every
 * control point it would replace (pole_vertex), h / w, lies within RG2__POLE_ULPS roundings (of
 * the surface's largest coordinate) times the ratio of those points' largest weight to their
 * smallest (at least 1) of that point, coordinate by coordinate. Returns -1 out of memory.
 */
static int topo_poles(const rg2_surface *s, rg2__topo *t)
{
    int nu = t->nu, nv = t->nv, any = 0;
    for (size_t k = 0; k < (size_t)(nu + 1) * (size_t)nv && !any; k++)
        any = t->ue[k] == -1;
    for (size_t k = 0; k < (size_t)(nv + 1) * (size_t)nu && !any; k++)
        any = t->ve[k] == -1;
    if (!any)
        return 0;
    t->snap = rg2__calloc((size_t)t->n_vertices, 1);
    t->pole = rg2__calloc((size_t)t->n_vertices, sizeof(double[3]));
    if (!t->snap || !t->pole)
        return -1;
    /* candidates: the ends of the collapsed edges */
    for (int i = 0; i < nu; i++)
        for (int j = 0; j < nv; j++)
            for (int side = 0; side < 4; side++) {
                int e, f;
                rg2__topo_side(t, i, j, side, &e, &f);
                if (e < 0)
                    t->snap[t->vert[(i + (side == 1)) * (nv + 1) + j + (side == 2)]] = 1;
            }
    double lo[3], hi[3], big = 0.0;
    for (int d = 0; d < 3 && rg2__surface_ctrl_box(s, 0, lo, hi); d++)
        big = fmax(big, fmax(fabs(lo[d]), fabs(hi[d])));
    double tol = RG2__POLE_ULPS * DBL_EPSILON * big;
    for (int v = 0; v < t->n_vertices; v++)
        if (t->snap[v]) {
            int c = t->vcorner[v], I = c / (nv + 1), J = c % (nv + 1);
            int i = I < nu ? I : nu - 1, j = J < nv ? J : nv - 1;
            rg2_xpatch X;
            rg2_surface_patch_get(s, i, j, &X);
            const double *h = X.h[I == i ? 0 : X.du][J == j ? 0 : X.dv];
            for (int d = 0; d < 3; d++)
                t->pole[v][d] = h[d] / h[3];
        }
    /* over the points a candidate would replace: their smallest and largest weight and their
     * largest distance from its point; it is a pole when that distance is within tol times the
     * weights' ratio (the construction's rounding of h / w grows with it) */
    double(*w)[3] = rg2__calloc((size_t)t->n_vertices, sizeof *w);
    if (!w)
        return -1;
    for (int v = 0; v < t->n_vertices; v++)
        w[v][0] = INFINITY;
    for (int i = 0; i < nu; i++)
        for (int j = 0; j < nv; j++) {
            rg2_xpatch X;
            rg2_surface_patch_get(s, i, j, &X);
            for (int r = 0; r <= X.du; r++)
                for (int q = 0; q <= X.dv; q++) {
                    int v = pole_vertex(t, i, j, r, q, X.du, X.dv);
                    const double *h = X.h[r][q];
                    if (v < 0 || !t->snap[v])
                        continue;
                    w[v][0] = fmin(w[v][0], fabs(h[3]));
                    w[v][1] = fmax(w[v][1], fabs(h[3]));
                    for (int d = 0; d < 3; d++) {
                        double e = fabs(h[d] / h[3] - t->pole[v][d]);
                        w[v][2] = e > w[v][2] || isnan(e) ? e : w[v][2]; /* (a NaN stays: no pole) */
                    }
                }
        }
    for (int v = 0; v < t->n_vertices; v++)
        if (t->snap[v]) {
            double ratio = w[v][1] / w[v][0];
            t->snap[v] = w[v][2] <= tol * (ratio > 1.0 && isfinite(ratio) ? ratio : 1.0);
        }
    free(w);
    return 0;
}

/*
 * METHOD: corners (I, J) of the patch grid are vertices, with I = nu identified with I = 0
 * for closed u (likewise v). Every patch side is a grid edge; the two patches meeting at a
 * seam use the same edge. A side whose control points coincide (collapsed, a pole) is no edge:
 * its two corners are merged (union-find), so the patches around a pole share one vertex.
 */
rg2_status rg2__topo_build(const rg2_surface *s, rg2__topo *t, rg2_error *err)
{
    memset(t, 0, sizeof *t);
    int nu = s->nu, nv = s->nv;
    size_t nc = (size_t)(nu + 1) * (size_t)(nv + 1);
    size_t nue = (size_t)(nu + 1) * (size_t)nv, nve = (size_t)(nv + 1) * (size_t)nu;
    t->nu = nu;
    t->nv = nv;
    t->vert = rg2__calloc(nc, sizeof(int));
    t->ue = rg2__calloc(nue, sizeof(int));
    t->ve = rg2__calloc(nve, sizeof(int));
    t->vcorner = rg2__calloc(nc, sizeof(int));
    t->edef = rg2__calloc(2 * (nue + nve), sizeof(int));
    t->uses = rg2__calloc(nue + nve, sizeof(int));
    int *parent = rg2__calloc(nc, sizeof(int));
    int *root_id = rg2__calloc(nc, sizeof(int));
    if (!t->vert || !t->ue || !t->ve || !t->vcorner || !t->edef || !t->uses || !parent || !root_id) {
        free(parent);
        free(root_id);
        rg2__topo_free(t);
        return rg2__fail(err, RG2_ENOMEM, "export: out of memory for the topology of %d x %d patches",
                         nu, nv);
    }
    for (size_t c = 0; c < nc; c++)
        parent[c] = (int)c;
    /* closing seams: corner (nu, J) is (0, J); (I, nv) is (I, 0) */
    for (int I = 0; I <= nu; I++)
        for (int J = 0; J <= nv; J++) {
            int I2 = (s->closed_u && I == nu) ? 0 : I, J2 = (s->closed_v && J == nv) ? 0 : J;
            rg2__uf_union(parent, I * (nv + 1) + J, I2 * (nv + 1) + J2);
        }
    double tol = rg2__collapse_tol(s);
    /* pass 1: a grid edge is collapsed if either patch using it sees its side collapsed */
    for (int i = 0; i < nu; i++)
        for (int j = 0; j < nv; j++)
            for (int side = 0; side < 4; side++) {
                if (!rg2__surface_side_collapsed(s, i, j, side, tol))
                    continue;
                int which, idx;
                side_slot(nu, nv, s->closed_u, s->closed_v, i, j, side, &which, &idx);
                (which == 0 ? t->ue : t->ve)[idx] = -1;
                int a, b;
                if (which == 0) {
                    int I = side == 1 ? i + 1 : i;
                    a = I * (nv + 1) + j;
                    b = I * (nv + 1) + j + 1;
                } else {
                    int J = side == 2 ? j + 1 : j;
                    a = i * (nv + 1) + J;
                    b = (i + 1) * (nv + 1) + J;
                }
                rg2__uf_union(parent, a, b);
            }
    /* pass 2: ids for the others, in patch order. The edge's curve is the side of the patch
     * with the lowest degree along it (the first such patch): between a bi-3 patch and a
     * higher-degree neighbour, the bi-3 side, of which the neighbour's side is the exact degree
     * elevation (the same curve). */
    for (size_t k = 0; k < nue; k++)
        t->ue[k] = t->ue[k] == -1 ? -1 : -2;
    for (size_t k = 0; k < nve; k++)
        t->ve[k] = t->ve[k] == -1 ? -1 : -2;
    for (int i = 0; i < nu; i++)
        for (int j = 0; j < nv; j++)
            for (int side = 0; side < 4; side++) {
                int which, idx;
                side_slot(nu, nv, s->closed_u, s->closed_v, i, j, side, &which, &idx);
                int *slot = which == 0 ? &t->ue[idx] : &t->ve[idx];
                if (*slot == -1)
                    continue;
                if (*slot == -2) {
                    *slot = t->n_edges++;
                    t->edef[2 * *slot] = i * nv + j;
                    t->edef[2 * *slot + 1] = side;
                } else {
                    int p = t->edef[2 * *slot];
                    if (side_degree(s, i, j, side) < side_degree(s, p / nv, p % nv, t->edef[2 * *slot + 1])) {
                        t->edef[2 * *slot] = i * nv + j;
                        t->edef[2 * *slot + 1] = side;
                    }
                }
                t->uses[*slot]++;
            }
    /* the closing lines of closed directions share line 0's ids */
    if (s->closed_u)
        for (int j = 0; j < nv; j++)
            t->ue[nu * nv + j] = t->ue[j];
    if (s->closed_v)
        for (int i = 0; i < nu; i++)
            t->ve[nv * nu + i] = t->ve[i];
    /* compact vertex ids */
    for (size_t c = 0; c < nc; c++)
        root_id[c] = -1;
    for (size_t c = 0; c < nc; c++) {
        int r = rg2__uf_find(parent, (int)c);
        if (root_id[r] < 0) {
            root_id[r] = t->n_vertices;
            t->vcorner[t->n_vertices++] = r;
        }
        t->vert[c] = root_id[r];
    }
    free(root_id);
    free(parent);
    if (topo_poles(s, t)) {
        rg2__topo_free(t);
        return rg2__fail(err, RG2_ENOMEM, "export: out of memory for the poles of %d x %d patches", nu, nv);
    }
    return RG2_OK;
}

/* Control point (r, q) of patch (i, j) of degrees (du, dv), h, in place as written (x, y, z, w). */
static void to_affine(const rg2__topo *t, int i, int j, int r, int q, int du, int dv, double h[4])
{
    int v = t->snap ? pole_vertex(t, i, j, r, q, du, dv) : -1;
    for (int d = 0; d < 3; d++)
        h[d] = v >= 0 && t->snap[v] ? t->pole[v][d] : h[d] / h[3];
}

void rg2__patch_affine(const rg2__topo *t, const rg2_surface *s, int i, int j, rg2_xpatch *X)
{
    rg2_surface_patch_get(s, i, j, X);
    for (int r = 0; r <= X->du; r++)
        for (int q = 0; q <= X->dv; q++)
            to_affine(t, i, j, r, q, X->du, X->dv, X->h[r][q]);
}

void rg2__corner_affine(const rg2__topo *t, const rg2_surface *s, int I, int J, double out[4])
{
    int i = I < s->nu ? I : s->nu - 1, j = J < s->nv ? J : s->nv - 1;
    rg2_xpatch X;
    rg2__patch_affine(t, s, i, j, &X);
    memcpy(out, X.h[I == i ? 0 : X.du][J == j ? 0 : X.dv], sizeof(double[4]));
}

rg2_status rg2__net_affine(const rg2_surface *s, double (*h)[4], int NU, int NV, int du, int dv, rg2_error *err)
{
    rg2__topo t;
    rg2_status st = rg2__topo_build(s, &t, err);
    if (st)
        return st;
    for (int a = 0; a < NU; a++)
        for (int b = 0; b < NV; b++) {
            /* net point (a, b) as point (r, q) of patch (i, j) (on a line between two patches:
             * of the patch after it; on the last line: of the last patch) */
            int i = a / du < s->nu ? a / du : s->nu - 1, j = b / dv < s->nv ? b / dv : s->nv - 1;
            to_affine(&t, i, j, a - du * i, b - dv * j, du, dv, h[(size_t)a * (size_t)NV + (size_t)b]);
        }
    rg2__topo_free(&t);
    return RG2_OK;
}

const int rg2__side_ends[4][2] = {{0, 1}, {1, 2}, {3, 2}, {0, 3}};

int rg2__net_side(rg2__mesh_topo *t, int sd)
{
    int NU = t->NU, NV = t->NV, n = (sd & 1) ? NV : NU;
    for (int a = 0; a < n; a++) {
        size_t k;
        switch (sd) {
        case 0: k = (size_t)a * (size_t)NV; break;
        case 1: k = (size_t)(NU - 1) * (size_t)NV + (size_t)a; break;
        case 2: k = (size_t)a * (size_t)NV + (size_t)(NV - 1); break;
        default: k = (size_t)a; break;
        }
        memcpy(t->side[a], t->h[k], sizeof(double[4]));
    }
    return n;
}

static int curve_collapsed(const double (*h)[4], int n, double tol)
{
    for (int a = 1; a < n; a++)
        for (int d = 0; d < 3; d++)
            if (!(fabs(h[a][d] / h[a][3] - h[0][d] / h[0][3]) <= tol))
                return 0;
    return 1;
}

static int uf4(const int *p, int a)
{
    while (p[a] != a)
        a = p[a];
    return a;
}

static void join4(int *p, int a, int b)
{
    a = uf4(p, a);
    b = uf4(p, b);
    if (a != b)
        p[a > b ? a : b] = a < b ? a : b;
}

void rg2__mesh_topo_free(rg2__mesh_topo *t)
{
    free(t->h);
    free(t->side);
    t->h = t->side = NULL;
}

rg2_status rg2__mesh_topo_build(const rg2_surface *s, rg2__mesh_topo *t, rg2_error *err)
{
    memset(t, 0, sizeof *t);
    t->h = rg2__merged_net(s, &t->NU, &t->NV, &t->du, &t->dv);
    t->side = t->h ? rg2__calloc((size_t)(t->NU > t->NV ? t->NU : t->NV), sizeof(double[4])) : NULL;
    if (!t->h || !t->side) {
        rg2__mesh_topo_free(t);
        return rg2__fail(err, RG2_ENOMEM, "export: out of memory for %d x %d patches", s->nu, s->nv);
    }
    double tol = rg2__collapse_tol(s);
    int parent[4] = {0, 1, 2, 3}, collapsed[4];
    for (int sd = 0; sd < 4; sd++) {
        int n = rg2__net_side(t, sd);
        collapsed[sd] = curve_collapsed((const double(*)[4])t->side, n, tol);
        if (collapsed[sd])
            join4(parent, rg2__side_ends[sd][0], rg2__side_ends[sd][1]);
    }
    rg2_status st = rg2__net_affine(s, t->h, t->NU, t->NV, t->du, t->dv, err);
    if (st) {
        rg2__mesh_topo_free(t);
        return st;
    }
    if (s->closed_u) {
        join4(parent, 0, 1);
        join4(parent, 3, 2);
    }
    if (s->closed_v) {
        join4(parent, 0, 3);
        join4(parent, 1, 2);
    }
    int vof[4] = {-1, -1, -1, -1};
    for (int c = 0; c < 4; c++) {
        int r = uf4(parent, c);
        if (vof[r] < 0) {
            vof[r] = t->n_vertices;
            t->vcorner[t->n_vertices++] = r;
        }
        t->vert[c] = vof[r];
    }
    /* define v = 0 and u = 0 first: the closing sides reuse them */
    static const int order[4] = {0, 3, 1, 2};
    for (int q = 0; q < 4; q++)
        t->edge[q] = -1;
    for (int q = 0; q < 4; q++) {
        int sd = order[q];
        if (collapsed[sd])
            continue;
        if (sd == 1 && s->closed_u)
            t->edge[1] = t->edge[3];
        else if (sd == 2 && s->closed_v)
            t->edge[2] = t->edge[0];
        else {
            t->eside[t->n_edges] = sd;
            t->edge[sd] = t->n_edges++;
        }
    }
    /* closed: in each direction closed, or both its boundary sides collapsed (a pole at one end
     * only leaves the other end's boundary free) */
    t->closed = (s->closed_u || (collapsed[1] && collapsed[3])) && (s->closed_v || (collapsed[0] && collapsed[2]));
    return RG2_OK;
}

void rg2__topo_side(const rg2__topo *t, int i, int j, int side, int *edge, int *forward)
{
    int which, idx;
    side_slot(t->nu, t->nv, 0, 0, i, j, side, &which, &idx);
    *edge = which == 0 ? t->ue[idx] : t->ve[idx];
    *forward = side < 2;
}

/* The whole surface as one net of (du nu + 1) x (dv nv + 1) poles, (du, dv) =
 * rg2_surface_degree: every patch degree-elevated (exactly) to (du, dv); patch boundary rows
 * are shared (taken from the first patch holding them; the closing row of a closed direction
 * is row 0). Caller frees. */
double (*rg2__merged_net(const rg2_surface *s, int *NU, int *NV, int *du, int *dv))[4]
{
    int nu = s->nu, nv = s->nv, Du, Dv;
    rg2_surface_degree(s, &Du, &Dv);
    *du = Du;
    *dv = Dv;
    *NU = Du * nu + 1;
    *NV = Dv * nv + 1;
    double(*h)[4] = rg2__calloc((size_t)*NU * (size_t)*NV, sizeof(double[4]));
    if (!h)
        return NULL;
    for (int i = nu - 1; i >= 0; i--)
        for (int j = nv - 1; j >= 0; j--) {
            rg2_xpatch X, E;
            rg2_surface_patch_get(s, i, j, &X);
            if (rg2_xpatch_elevate(&X, Du, Dv, &E, NULL) != RG2_OK) {
                free(h); /* cannot happen: (Du, Dv) is the maximum over the patches */
                return NULL;
            }
            for (int r = Du; r >= 0; r--)
                for (int t = Dv; t >= 0; t--)
                    memcpy(h[(size_t)(Du * i + r) * (size_t)*NV + (size_t)(Dv * j + t)], E.h[r][t],
                           sizeof(double[4]));
        }
    if (s->closed_u)
        memcpy(h[(size_t)(*NU - 1) * (size_t)*NV], h[0], sizeof(double[4]) * (size_t)*NV);
    if (s->closed_v)
        for (int a = 0; a < *NU; a++)
            memcpy(h[(size_t)a * (size_t)*NV + (size_t)(*NV - 1)], h[(size_t)a * (size_t)*NV], sizeof(double[4]));
    return h;
}

/* ---------------------------------------------------------------- JSON patch dump */

/* The dump is written as it is formatted, in the layout cJSON_Print gave it (the tree of the
 * whole dump and its printed text were both held in memory: 3 times the file's size at the
 * peak, 0.7 GB for a 0.23 GB dump of 250 000 patches). Arrays of doubles are printed with 17
 * significant digits (cJSON's own printing may drop to 15 digits, which does not round-trip
 * exactly), without spaces; integer arrays as cJSON prints them, ", " between items. */
static void json_doubles(FILE *f, const double *x, int n)
{
    fputc('[', f);
    for (int k = 0; k < n; k++)
        fprintf(f, "%s%.17g", k ? "," : "", x[k]);
    fputc(']', f);
}

static void json_ints(FILE *f, const int *x, int n)
{
    fputc('[', f);
    for (int k = 0; k < n; k++)
        fprintf(f, "%s%d", k ? ", " : "", x[k]);
    fputc(']', f);
}

/* The patches' degrees along u (side 0) or v (side 1), patch p = i nv + j */
static void json_degrees(FILE *f, const rg2_surface *s, int side)
{
    fputc('[', f);
    for (int p = 0; p < s->nu * s->nv; p++)
        fprintf(f, "%s%d", p ? ", " : "", side_degree(s, p / s->nv, p % s->nv, side));
    fputc(']', f);
}

/* "key":<TAB> at the depth of a surface's keys (three tabs) */
static void json_key(FILE *f, const char *key, int first)
{
    fprintf(f, "%s\t\t\t\"%s\":\t", first ? "" : ",\n", key);
}

typedef struct {
    const rg2_surface *s;
} json_patches;

/* Patches k0..k1-1 of a surface: one patch of degree (du, dv) is (du + 1)(dv + 1) homogeneous
 * points h[r][s], r (u) outer -- 64 numbers for a bi-3 patch. */
static int json_patch_block(FILE *m, void *ctx, int b, int k0, int k1)
{
    (void)b;
    const rg2_surface *s = ((const json_patches *)ctx)->s;
    for (int p = k0; p < k1; p++) {
        rg2_xpatch X;
        double net[(RG2_MAX_DEGREE + 1) * (RG2_MAX_DEGREE + 1)][4];
        rg2_surface_patch_get(s, p / s->nv, p % s->nv, &X);
        if (p)
            fputs(", ", m);
        json_doubles(m, &net[0][0], 4 * rg2__xpatch_net(&X, net));
    }
    return 0;
}

static rg2_status write_json(const rg2_surface *surfs, int n, const rg2_export_opts *o, rg2__out *out,
                             rg2_error *err)
{
    FILE *f = out->f;
    cJSON *name = cJSON_CreateString(o->name); /* the name as cJSON escapes a string */
    char *qname = name ? rg2__json_print(name, 0) : NULL;
    cJSON_Delete(name);
    if (!qname)
        return rg2__fail(err, RG2_ENOMEM, "%s: out of memory building JSON", out->path);
    fputs("{\n\t\"surfaces\":\t[", f);
    for (int k = 0; k < n; k++) {
        const rg2_surface *s = &surfs[k];
        int np = s->nu * s->nv;
        fputs(k ? ", {\n" : "{\n", f);
        json_key(f, "nu", 1);
        fprintf(f, "%d", s->nu);
        json_key(f, "nv", 0);
        fprintf(f, "%d", s->nv);
        json_key(f, "closed_u", 0);
        fputs(s->closed_u ? "true" : "false", f);
        json_key(f, "closed_v", 0);
        fputs(s->closed_v ? "true" : "false", f);
        json_key(f, "bu", 0);
        json_doubles(f, s->bu, s->nu);
        json_key(f, "gu", 0);
        json_doubles(f, s->gu, s->nu);
        json_key(f, "bv", 0);
        json_doubles(f, s->bv, s->nv);
        json_key(f, "gv", 0);
        json_doubles(f, s->gv, s->nv);
        if (s->tag) {
            json_key(f, "tag", 0);
            json_ints(f, s->tag, np);
        }
        json_key(f, "patches", 0);
        fputc('[', f);
        json_patches jp = {s};
        if (rg2__write_blocks(f, np, 256, json_patch_block, NULL, &jp)) {
            cJSON_free(qname);
            return rg2__fail(err, RG2_ENOMEM, "%s: out of memory building JSON", out->path);
        }
        fputc(']', f);
        json_key(f, "du", 0);
        json_degrees(f, s, 0);
        json_key(f, "dv", 0);
        json_degrees(f, s, 1);
        fputs("\n\t\t}", f);
    }
    fprintf(f, "],\n\t\"format\":\t\"rg2-patches\",\n\t\"version\":\t2,\n\t\"name\":\t%s\n}\n", qname);
    cJSON_free(qname);
    return RG2_OK;
}

/* ---------------------------------------------------------------- dispatcher */

static const char *extension(const char *path)
{
    const char *slash = strrchr(path, '/');
    const char *dot = strrchr(path, '.');
    if (!dot || (slash && dot < slash))
        return "";
    return dot + 1;
}

void rg2__tess_all_free(rg2_tess *t, int n)
{
    if (!t)
        return;
    for (int k = 0; k < n; k++)
        rg2_tess_free(&t[k]);
    free(t);
}

/* rg2__tess_all calls so far (rg2__tess_all_calls, a test hook). */
static atomic_ulong tess_all_calls;

unsigned long rg2__tess_all_calls(void)
{
    return atomic_load(&tess_all_calls);
}

/* The vertices of the surfaces' tessellations at a density. */
static double tess_vertices(const rg2_surface *surfs, int n_surfs, int density)
{
    double total = 0.0;
    for (int k = 0; k < n_surfs; k++)
        total += ((double)surfs[k].nu * density + 1.0) * ((double)surfs[k].nv * density + 1.0);
    return total;
}

rg2_status rg2__tess_all(const rg2_surface *surfs, int n_surfs, int density, int curvature,
                         rg2_tess **out, rg2_error *err)
{
    atomic_fetch_add(&tess_all_calls, 1);
    /* all surfaces together stay within the per-surface vertex limit of rg2_tessellate */
    double total = tess_vertices(surfs, n_surfs, density);
    if (total > RG2_MAX_POINTS) {
        int fits = density - 1; /* the largest density within the limit: what to ask for instead */
        while (fits >= 1 && tess_vertices(surfs, n_surfs, fits) > RG2_MAX_POINTS)
            fits--;
        char hint[64] = "; no density fits";
        if (fits >= 1)
            snprintf(hint, sizeof hint, "; density %d or less fits", fits);
        return rg2__fail(err, RG2_ELIMIT,
                         "export: %d surface%s at density %d need%s %.0f vertices, more than the limit %d%s",
                         n_surfs, n_surfs == 1 ? "" : "s", density, n_surfs == 1 ? "s" : "", total,
                         RG2_MAX_POINTS, hint);
    }
    *out = rg2__calloc((size_t)n_surfs, sizeof(rg2_tess));
    if (!*out)
        return rg2__fail(err, RG2_ENOMEM, "export: out of memory");
    for (int k = 0; k < n_surfs; k++) {
        rg2_status st = rg2_tessellate(&surfs[k], density, curvature, &(*out)[k], err);
        if (st) {
            rg2__tess_all_free(*out, n_surfs);
            *out = NULL;
            return st;
        }
    }
    return RG2_OK;
}

enum { F_STEP, F_IGES, F_BV, F_BEZ, F_OBJ, F_STL, F_PLY, F_GLB, F_JSON };

/* The formats written from a tessellation. */
static int mesh_format(int fmt)
{
    return fmt == F_OBJ || fmt == F_STL || fmt == F_PLY || fmt == F_GLB;
}

/* The export format of a path by its extension (case-insensitive). */
static rg2_status export_format(const char *path, int *fmt, rg2_error *err)
{
    static const struct {
        const char *ext;
        int fmt;
    } table[] = {{"step", F_STEP}, {"stp", F_STEP}, {"igs", F_IGES}, {"iges", F_IGES}, {"bv", F_BV},
                 {"bez", F_BEZ},   {"obj", F_OBJ},  {"stl", F_STL},  {"ply", F_PLY},   {"glb", F_GLB},
                 {"json", F_JSON}};
    if (!path || !*path)
        return rg2__fail(err, RG2_EINVAL, "export: no output path");
    const char *ext = extension(path), *slash = strrchr(path, '/'), *base = slash ? slash + 1 : path;
    for (size_t k = 0; k < sizeof table / sizeof table[0]; k++)
        if (!strcasecmp(ext, table[k].ext)) {
            if (ext == base + 1) /* ".step": the extension alone, a hidden file without a name */
                return rg2__fail(err, RG2_EINVAL,
                                 "%s: the file name is only the extension '.%s' (a hidden file with no name); give "
                                 "it a name, e.g. 'design.%s'",
                                 path, ext, ext);
            *fmt = table[k].fmt;
            return RG2_OK;
        }
    if (!*ext)
        return rg2__fail(err, RG2_EINVAL,
                         "%s: the file name has no extension to choose the export format by (use .step "
                         ".stp .igs .iges .bv .bez .obj .stl .ply .glb .json)",
                         path);
    return rg2__fail(err, RG2_EINVAL,
                     "%s: unknown export format '.%s' (use .step .stp .igs .iges .bv .bez .obj "
                     ".stl .ply .glb .json)",
                     path, ext);
}

rg2_status rg2_export_format_check(const char *path, rg2_error *err)
{
    int fmt;
    return export_format(path, &fmt, err);
}

/* STL, PLY and glTF store float coordinates: a surface beyond FLT_MAX would be written as
 * infinities (and glTF's min/max as null), one spanning less than FLT_MIN / FLT_EPSILON as
 * zeros or a few denormal values. */
static rg2_status check_float_range(const rg2_tess *t, int n, const char *path, const char *format,
                                    rg2_error *err)
{
    rg2__box box;
    rg2__box_init(&box);
    for (int k = 0; k < n; k++)
        for (size_t v = 0; v < (size_t)t[k].n_vertices; v++)
            rg2__box_add(&box, &t[k].pos[3 * v], 1.0);
    double big, diag;
    rg2__box_extent(&box, &big, &diag);
    if (big > FLT_MAX)
        return rg2__fail(err, RG2_EDOMAIN,
                         "%s: %s stores float coordinates, up to %g; the surfaces reach %g (write OBJ, "
                         "STEP or IGES, or scale the design)",
                         path, format, (double)FLT_MAX, big);
    if (diag < FLT_MIN / FLT_EPSILON)
        return rg2__fail(err, RG2_EDOMAIN,
                         "%s: %s stores float coordinates, which resolve sizes from %g; the surfaces span "
                         "%g (write OBJ, STEP or IGES, or scale the design)",
                         path, format, (double)(FLT_MIN / FLT_EPSILON), diag);
    return RG2_OK;
}

/* Write path's temporary file in path's format; on success the complete file waits there in *out for
 * rg2__out_commit, on failure nothing is left. keep: NULL, or where the mesh outputs (OBJ, STL, PLY,
 * glTF) of one rg2_export_files call keep the tessellation they share, made by the first of them
 * (with curvatures when keep_curvature: a PLY among them; the positions, normals and triangles are
 * the same bits with or without, as rg2_grid_out promises and tests/test_grid.c checks); the
 * caller frees it. */
static rg2_status export_staged(const rg2_surface *surfs, int n_surfs, const char *path,
                                const rg2_export_opts *opts, rg2__out *out, rg2_tess **keep, int keep_curvature,
                                int memory, rg2_error *err)
{
    memset(out, 0, sizeof *out);
    rg2_export_opts def;
    if (!opts) {
        rg2_export_opts_default(&def);
        opts = &def;
    } else if (!opts->name || opts->density < 1) {
        def = *opts;
        if (!def.name)
            def.name = default_name;
        if (def.density < 1)
            def.density = 16;
        opts = &def;
    }
    if (opts->layout != RG2_STEP_FACE_PER_PATCH && opts->layout != RG2_STEP_FACE_PER_MESH)
        return rg2__fail(err, RG2_EINVAL,
                         "export: layout %d, must be RG2_STEP_FACE_PER_PATCH (0) or RG2_STEP_FACE_PER_MESH (1)",
                         (int)opts->layout);
    int fmt;
    rg2_status st = export_format(path, &fmt, err);
    if (st)
        return st;
    st = rg2__check_nonempty(surfs, n_surfs, err);
    if (st)
        return st;
    if (fmt == F_STEP || fmt == F_IGES)
        st = rg2__check_weights(surfs, n_surfs, fmt == F_STEP ? "STEP" : "IGES", err);
    else
        st = rg2__check_weights(surfs, n_surfs, "export", err) == RG2_ENONFINITE ? RG2_ENONFINITE : RG2_OK;
    if (st && err) { /* name the file too: "out.step: STEP: surface 0 patch (2, 0) ..." (err is
                        nullable: without a report there is no message to prefix) */
        rg2_error e = *err;
        return rg2__fail(err, st, "%s: %s", path, e.msg);
    }
    if (st)
        return st;
    rg2_tess *tess = NULL, *own = NULL; /* own: the tessellation this call frees */
    if (mesh_format(fmt)) {
        if (keep && *keep)
            tess = *keep;
        else {
            st = rg2__tess_all(surfs, n_surfs, opts->density, keep ? keep_curvature : fmt == F_PLY, &tess, err);
            if (st)
                return st;
            if (keep)
                *keep = tess;
            else
                own = tess;
        }
        if (fmt != F_OBJ)
            st = check_float_range(tess, n_surfs, path, fmt == F_STL ? "STL" : fmt == F_PLY ? "PLY" : "glTF", err);
        if (st) {
            rg2__tess_all_free(own, n_surfs);
            return st;
        }
    }
    /* the name without control characters (a newline would end the OBJ and PLY header comment
     * line) and as UTF-8 (glTF and JSON are UTF-8 text); STEP and IGES write ASCII only, mapping
     * the rest to '_' themselves */
    char *clean = rg2__text_clean(opts->name, '_');
    if (!clean) {
        rg2__tess_all_free(own, n_surfs);
        return rg2__fail(err, RG2_ENOMEM, "export: out of memory");
    }
    if (opts != &def)
        def = *opts;
    def.name = clean;
    opts = &def;
    st = memory ? rg2__out_open_memory(out, path, err) : rg2__out_open(out, path, err);
    if (st) {
        rg2__tess_all_free(own, n_surfs);
        free(clean);
        return st;
    }
    void *loc = rg2__c_numeric_begin(); /* the threads of rg2__write_blocks switch for themselves */
    switch (fmt) {
    case F_STEP: st = rg2__write_step(surfs, n_surfs, opts, out, err); break;
    case F_IGES: st = rg2__write_iges(surfs, n_surfs, opts, out, err); break;
    case F_BV: st = rg2__write_bv(surfs, n_surfs, out, err); break;
    case F_BEZ: st = rg2__write_bez(surfs, n_surfs, out, err); break;
    case F_OBJ: st = rg2__write_obj(tess, n_surfs, opts, out, err); break;
    case F_STL: st = rg2__write_stl(tess, n_surfs, opts, out, err); break;
    case F_PLY: st = rg2__write_ply(tess, n_surfs, opts, out, err); break;
    case F_GLB: st = rg2__write_glb(tess, n_surfs, opts, out, err); break;
    case F_JSON: st = write_json(surfs, n_surfs, opts, out, err); break;
    }
    rg2__c_numeric_end(loc);
    rg2__tess_all_free(own, n_surfs);
    free(clean);
    return rg2__out_finish(out, st, err);
}

rg2_status rg2_export_file(const rg2_surface *surfs, int n_surfs, const char *path,
                           const rg2_export_opts *opts, rg2_error *err)
{
    rg2__out out;
    rg2_status st = export_staged(surfs, n_surfs, path, opts, &out, NULL, 0, 0, err);
    if (st == RG2_OK)
        st = rg2__out_commit(&out, err);
    if (st == RG2_OK)
        rg2__ok(err);
    return st;
}

rg2_status rg2_export_memory(const rg2_surface *surfs, int n_surfs, const char *format, const rg2_export_opts *opts,
                             char **data, size_t *size, rg2_error *err)
{
    if (data)
        *data = NULL;
    if (size)
        *size = 0;
    if (!data || !size)
        return rg2__fail(err, RG2_EINVAL, "rg2_export_memory: %s is NULL", !data ? "data" : "size");
    int fmt;
    char probe[16] = "x.";
    int known = format && *format && strlen(format) <= 8 && !strchr(format, '.') && !strchr(format, '/');
    if (known) {
        strcat(probe, format);
        known = export_format(probe, &fmt, NULL) == RG2_OK;
    }
    if (!known)
        return rg2__fail(err, RG2_EINVAL,
                         "rg2_export_memory: %s%s%s (use step stp igs iges bv bez obj stl ply glb json: an extension "
                         "without its dot)",
                         format ? "unknown format '" : "format is NULL", format ? format : "", format ? "'" : "");
    /* the name the STEP and IGES headers give: "<opts->name>.<format>", '/' made '_' (the headers
     * take a path's last part) */
    const char *nm = opts && opts->name ? opts->name : default_name;
    size_t ln = strlen(nm);
    char *label = malloc(ln + strlen(format) + 2);
    if (!label)
        return rg2__fail(err, RG2_ENOMEM, "rg2_export_memory: out of memory");
    for (size_t k = 0; k < ln; k++)
        label[k] = nm[k] == '/' ? '_' : nm[k];
    label[ln] = '.';
    strcpy(label + ln + 1, format);
    rg2__out out;
    rg2_status st = export_staged(surfs, n_surfs, label, opts, &out, NULL, 0, 1, err);
    if (st == RG2_OK) {
        *data = out.data, *size = out.size;
        out.data = NULL;
        rg2__out_discard(&out);
        rg2__ok(err);
    }
    free(label);
    return st;
}

rg2_status rg2_export_files(const rg2_surface *surfs, int n_surfs, const char *const *paths, int n_paths,
                            const rg2_export_opts *opts, int *failed, rg2_error *err)
{
    if (failed)
        *failed = -1;
    if (n_paths < 1 || !paths)
        return rg2__fail(err, RG2_EINVAL, "export: no output paths (%d)", n_paths);
    int last_mesh = -1, curvature = 0; /* the last mesh output; a PLY among them */
    for (int k = 0; k < n_paths; k++) { /* a mistyped extension fails before anything is written */
        int fmt;
        rg2_status st = export_format(paths[k], &fmt, err);
        if (st) {
            if (failed)
                *failed = k;
            return st;
        }
        if (mesh_format(fmt))
            last_mesh = k;
        curvature |= fmt == F_PLY;
        for (int j = 0; j < k; j++)
            if (!strcmp(paths[j], paths[k])) { /* the second file would replace the first */
                if (failed)
                    *failed = k;
                return rg2__fail(err, RG2_EINVAL, "%s: output path given twice (outputs %d and %d)", paths[k], j, k);
            }
    }
    rg2__out *outs = calloc((size_t)n_paths, sizeof *outs);
    if (!outs) { /* (nothing written: the first output is the one that failed, not -1, success) */
        if (failed)
            *failed = 0;
        return rg2__fail(err, RG2_ENOMEM, "export: out of memory for %d outputs", n_paths);
    }
    rg2_status st = RG2_OK;
    rg2_tess *shared = NULL; /* one tessellation for every mesh output, freed after the last */
    int staged = 0;
    for (; staged < n_paths; staged++) {
        st = export_staged(surfs, n_surfs, paths[staged], opts, &outs[staged], &shared, curvature, 0, err);
        if (st)
            break;
        if (staged == last_mesh) { /* the outputs after it (STEP, IGES, ...) are written without it */
            rg2__tess_all_free(shared, n_surfs);
            shared = NULL;
        }
    }
    rg2__tess_all_free(shared, n_surfs); /* (a failure before the last mesh output) */
    if (st) { /* all or nothing: no path is touched, so files there before stay as they were */
        if (failed)
            *failed = staged;
        for (int k = 0; k < staged; k++)
            rg2__out_discard(&outs[k]);
        free(outs);
        return st;
    }
    for (int k = 0; k < n_paths; k++) { /* every file is complete: rename them */
        if (st) {
            rg2__out_discard(&outs[k]);
            continue;
        }
        st = rg2__out_commit(&outs[k], err);
        if (st && failed)
            *failed = k;
    }
    free(outs);
    if (st == RG2_OK)
        rg2__ok(err);
    return st;
}
