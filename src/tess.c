/* tess.c -- watertight triangle meshes of patch surfaces: a uniform (u, v) grid per patch,
 * the grid points on seams stored once (bit-identical on both sides), exact normals and
 * curvatures from the patch evaluation, collapsed sides (poles) merged into one vertex. */
#include "export_internal.h"
#include "xpatch_util.h"

#include <stdatomic.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>
#ifdef RG2_HAVE_OPENMP
#include <omp.h>
#endif

void rg2_tess_free(rg2_tess *t)
{
    if (!t)
        return;
    free(t->pos); /* the one block that holds every array (rg2_tessellate) */
    memset(t, 0, sizeof *t);
}

/*
 * Per-patch sampling of patch (i, j) of s (bi-3 or of higher degree): (d + 1)^2 points at
 * u = a / d, v = b / d, point a * (d + 1) + b of the arrays at `scratch`: positions (3 per
 * point), unit normals (3), then K and H with `curvature`; `scratch` holds 8 (d + 1)^2 doubles.
 * `collapsed` has bit k set when side k (0 v=0, 1 u=1, 2 v=1, 3 u=0) is collapsed. This is the
 * only place that evaluates the surface: the grid evaluator (rg2_patch_grid, grid.c; the
 * separable higher-degree grid of xpatch.c for a higher-degree patch) for every point, then the
 * points on collapsed sides again by rg2_surface_eval and rg2__pole_limit (limit.c). Returns non-zero on
 * failure.
 */
static int sample_patch(const rg2_surface *s, int i, int j, int d, int curvature, unsigned collapsed,
                        double *scratch)
{
    size_t np = (size_t)(d + 1) * (size_t)(d + 1);
    rg2_grid_out go = {.pos = scratch, .normal = scratch + 3 * np};
    if (curvature) {
        go.K = scratch + 6 * np;
        go.H = scratch + 7 * np;
    }
    if (rg2__surface_patch_grid(s, i, j, d + 1, d + 1, &go, NULL))
        return 1;
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
            rg2__pole_limit(s, i, j, u, v, side, curvature ? 2 : 1, &e);
            size_t k = (size_t)a * (size_t)(d + 1) + (size_t)b;
            memcpy(go.pos + 3 * k, e.p, sizeof e.p);
            memcpy(go.normal + 3 * k, e.n, sizeof e.n);
            if (curvature) {
                go.K[k] = e.K;
                go.H[k] = e.H;
            }
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

/* Bytes from which rg2_tessellate's block (and its temporaries) go on huge pages: a mesh's arrays
 * of 0.5-2 MiB took a page fault per 4 KiB page at every call, since glibc gives freed memory of
 * that size back to the kernel (docs/performance.md, "Tessellation in one block"). */
#define TESS_BIG_BYTES ((size_t)512 << 10)

/* Grid points from which the sampling and the triangles run on threads (see tessellate). */
#define TESS_THREADS_FROM 4096

/* Quads whose diagonals are compared at once (a stack array per thread). */
#define TRI_CHUNK 256

/* mk[t] = all ones where quad t of two grid rows (p0: v00, v01; p1: v10, v11, points t and
 * t + 1) has the v00-v11 diagonal no longer than v10-v01 (dist2's arithmetic, vectorized). */
RG2_HOT static void diagonals(const double *restrict p0, const double *restrict p1, int n, int *restrict mk)
{
    for (int t = 0; t < n; t++) {
        const double *a = p0 + 3 * t, *b = p1 + 3 * t;
        double x0 = a[0] - b[3], x1 = a[1] - b[4], x2 = a[2] - b[5]; /* v00 - v11 */
        double y0 = b[0] - a[3], y1 = b[1] - a[4], y2 = b[2] - a[5]; /* v10 - v01 */
        mk[t] = -(int)(x0 * x0 + x1 * x1 + x2 * x2 <= y0 * y0 + y1 * y1 + y2 * y2);
    }
}

/* Round n bytes up to a cache line. */
static size_t line_up(size_t n)
{
    return (n + 63) & ~(size_t)63;
}

static rg2_status check_args(const rg2_surface *s, int density, rg2_error *err)
{
    if (!s)
        return rg2__fail(err, RG2_EINVAL, "tessellate: no surface (s is NULL)");
    if (s->nu < 1 || s->nv < 1 || !s->patch)
        return rg2__fail(err, RG2_EINVAL, "tessellate: surface has no patches");
    if (density < 1)
        return rg2__fail(err, RG2_EINVAL, "tessellate: density %d, must be >= 1", density);
    rg2_status fst = rg2__surface_check_finite(s, "tessellate", 0, err);
    if (!fst)
        fst = rg2__surface_check_range(s, "tessellate", 0, err);
    if (fst)
        return fst;
    int d = density, nu = s->nu, nv = s->nv;
    if ((double)nu * d + 1 > RG2_MAX_POINTS || (double)nv * d + 1 > RG2_MAX_POINTS ||
        ((double)nu * d + 1) * ((double)nv * d + 1) > RG2_MAX_POINTS)
        return rg2__fail(err, RG2_ELIMIT, "tessellate: %d x %d patches at density %d exceed %d vertices",
                         nu, nv, d, RG2_MAX_POINTS);
    return RG2_OK;
}

/* One tessellation's state for the pool's chunks (src/pool.c). */
typedef struct {
    const rg2_surface *s;
    rg2_tess *out;
    const unsigned *coll; /* collapsed sides per patch */
    const int *parent, *id; /* NULL without collapsed sides */
    const double *par;      /* b / d, b = 0..d */
    int *rowcnt;            /* triangles per row of quads */
    int d, nu, nv, cu, cv, GV, nu_d, nv_d, curvature, plain;
    size_t npp;      /* grid points per patch */
    uint32_t nchunk; /* of the current pass */
    _Atomic int failed;
} tess_job;

/* Sample patch p into scratch (8 npp doubles) and write its grid points into the mesh. */
static int sample_into(tess_job *T, int p, double *scratch)
{
    rg2_tess *out = T->out;
    int d = T->d, nu = T->nu, nv = T->nv, i = p / nv, j = p % nv, GV = T->GV;
    size_t npp = T->npp;
    if (sample_patch(T->s, i, j, d, T->curvature, T->coll[p], scratch))
        return 1;
    const double *sp = scratch, *sn = scratch + 3 * npp, *sK = scratch + 6 * npp, *sH = scratch + 7 * npp;
    const int *parent = T->parent, *id = T->id;
    const double *par = T->par;
    int a1 = (i == nu - 1 && !T->cu) ? d : d - 1, b1 = (j == nv - 1 && !T->cv) ? d : d - 1;
    for (int a = 0; a <= a1; a++) {
        size_t k0 = (size_t)(i * d + a) * (size_t)GV + (size_t)(j * d), q0 = (size_t)a * (size_t)(d + 1);
        double ua = par[a];
        if (!parent) { /* vertex k: the row's points at once */
            size_t cnt = (size_t)b1 + 1;
            memcpy(out->pos + 3 * k0, sp + 3 * q0, 3 * cnt * sizeof(double));
            memcpy(out->normal + 3 * k0, sn + 3 * q0, 3 * cnt * sizeof(double));
            if (T->curvature) {
                memcpy(out->K + k0, sK + q0, cnt * sizeof(double));
                memcpy(out->H + k0, sH + q0, cnt * sizeof(double));
            }
            for (int b = 0; b <= b1; b++) {
                out->patch[k0 + (size_t)b] = p;
                out->uv[2 * (k0 + (size_t)b)] = ua;
                out->uv[2 * (k0 + (size_t)b) + 1] = par[b];
            }
            continue;
        }
        for (int b = 0; b <= b1; b++) {
            size_t k = k0 + (size_t)b, q = q0 + (size_t)b;
            if (parent[k] != (int)k) /* merged into another grid point's vertex */
                continue;
            size_t v = (size_t)id[k];
            memcpy(out->pos + 3 * v, sp + 3 * q, 3 * sizeof(double));
            memcpy(out->normal + 3 * v, sn + 3 * q, 3 * sizeof(double));
            if (T->curvature) {
                out->K[v] = sK[q];
                out->H[v] = sH[q];
            }
            out->patch[v] = p;
            out->uv[2 * v] = ua;
            out->uv[2 * v + 1] = par[b];
        }
    }
    return 0;
}

/* Chunk c of the sampling: a contiguous run of patches, with one scratch array. */
static void sample_chunk(void *arg, uint32_t c)
{
    tess_job *T = arg;
    size_t np = (size_t)T->nu * (size_t)T->nv;
    int p0 = (int)(np * c / T->nchunk), p1 = (int)(np * (c + 1) / T->nchunk);
    double *scratch = malloc(sizeof(double) * 8 * T->npp);
    for (int p = p0; p < p1; p++)
        if (!scratch || sample_into(T, p, scratch)) {
            atomic_store(&T->failed, 1);
            break;
        }
    free(scratch);
}

/* The triangles of row I of quads into its slots; rowcnt[I] = how many. */
static void tri_row(tess_job *T, int I)
{
    const rg2_tess *out = T->out;
    int nu_d = T->nu_d, nv_d = T->nv_d, cu = T->cu, cv = T->cv, GV = T->GV;
    int *tri = out->tri + (size_t)6 * (size_t)nv_d * (size_t)I, cnt = 0;
    if (T->plain) { /* the same triangles as below, without branches */
        int r0 = I * GV, r1 = (cu && I + 1 == nu_d ? 0 : I + 1) * GV;
        const double *p0 = out->pos + 3 * (size_t)r0, *p1 = out->pos + 3 * (size_t)r1;
        for (int J0 = 0; J0 < nv_d; J0 += TRI_CHUNK) {
            int n = nv_d - J0 < TRI_CHUNK ? nv_d - J0 : TRI_CHUNK, mk[TRI_CHUNK];
            int nw = cv && J0 + n == nv_d ? n - 1 : n; /* quads whose v01 is not the wrapped one */
            diagonals(p0 + 3 * (size_t)J0, p1 + 3 * (size_t)J0, nw, mk);
            if (nw < n) /* the last quad of a closed row: v01, v11 on grid column 0 */
                mk[nw] = -(int)(dist2(p0 + 3 * (size_t)(J0 + nw), p1) <= dist2(p1 + 3 * (size_t)(J0 + nw), p0));
            for (int t = 0; t < n; t++) {
                int J = J0 + t, J1 = cv && J + 1 == nv_d ? 0 : J + 1, m = mk[t]; /* m all ones: v00-v11 */
                int v00 = r0 + J, v10 = r1 + J, v11 = r1 + J1, v01 = r0 + J1;
                int *o = tri + 6 * J;
                o[0] = v00;
                o[1] = v10;
                o[2] = v01 ^ ((v11 ^ v01) & m);
                o[3] = v10 ^ ((v00 ^ v10) & m);
                o[4] = v11;
                o[5] = v01;
            }
        }
        T->rowcnt[I] = 2 * nv_d;
        return;
    }
    const int *id = T->id;
    for (int J = 0; J < nv_d; J++) {
        int g00 = gidx(I, J, nu_d, nv_d, cu, cv, GV), g10 = gidx(I + 1, J, nu_d, nv_d, cu, cv, GV);
        int g11 = gidx(I + 1, J + 1, nu_d, nv_d, cu, cv, GV), g01 = gidx(I, J + 1, nu_d, nv_d, cu, cv, GV);
        int v00 = id ? id[g00] : g00, v10 = id ? id[g10] : g10, v11 = id ? id[g11] : g11;
        int v01 = id ? id[g01] : g01;
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
            memcpy(tri + 3 * cnt, q[t], sizeof q[t]);
            cnt++;
        }
    }
    T->rowcnt[I] = cnt;
}

/* Chunk c of the triangles: a contiguous run of rows of quads. */
static void tri_chunk(void *arg, uint32_t c)
{
    tess_job *T = arg;
    int I0 = (int)((size_t)T->nu_d * c / T->nchunk), I1 = (int)((size_t)T->nu_d * (c + 1) / T->nchunk);
    for (int I = I0; I < I1; I++)
        tri_row(T, I);
}

/* A surface whose control weights reach 0 may pass through infinity: its vertices there are
 * not finite (a torus with a 4 x 4 block of weight 0 gave 75 of 2304 coordinates NaN, and the
 * mesh formats wrote them with RG2_OK). RG2_EWEIGHT naming the first such vertex's patch. */
static rg2_status infinite_vertex(const rg2_surface *s, const rg2_tess *t, rg2_error *err)
{
    for (int v = 0; v < t->n_vertices; v++) {
        const double *p = t->pos + 3 * (size_t)v, *n = t->normal + 3 * (size_t)v;
        int bad = 0;
        for (int c = 0; c < 3; c++)
            bad |= !rg2__finite(p[c]) || !rg2__finite(n[c]);
        if (bad) {
            int k = t->patch[v];
            return rg2__fail(err, RG2_EWEIGHT,
                             "tessellate: the vertex at patch (%d, %d) u = %.6g, v = %.6g is not finite: the "
                             "surface passes through infinity there (control weights down to %g; a mesh "
                             "needs the patches' weights > 0)",
                             k / s->nv, k % s->nv, t->uv[2 * (size_t)v], t->uv[2 * (size_t)v + 1],
                             rg2_surface_min_weight(s));
        }
    }
    return RG2_OK;
}

/*
 * METHOD: the surface's grid points (I, J), I = 0..nu d, J = 0..nv d, closing lines folded
 * onto line 0, each belong to exactly one patch (the one with i = min(I / d, nu - 1)), which
 * evaluates it; the patch on the other side of a seam uses the same vertex. Sides detected
 * as collapsed (rg2__surface_side_collapsed, patches of any degree) merge their grid points
 * (union-find) into one vertex; triangles that then repeat a vertex are dropped. The vertices
 * are numbered before the sampling (the merging depends on the grid indices only), so each
 * patch writes its points straight into the output, which is one block: every array of the
 * mesh at a page fault per 2 MiB at most, where separate arrays of a few hundred KB cost a fault
 * per 4 KiB page at every call. rg2_retessellate writes into the previous mesh's block when it is
 * large enough: no fresh pages at all (docs/export.md).
 *
 * rg2_tessellate into out (zeroed), taking over old (a previous mesh's block of oldcap bytes, or
 * NULL): the new mesh goes into it when it is large enough, else it is freed.
 */
static rg2_status tessellate(const rg2_surface *s, int density, int curvature, int threads, rg2_tess *out,
                             char *old, size_t oldcap, rg2_error *err)
{
    rg2_status st = check_args(s, density, err);
    if (st) {
        free(old);
        return st;
    }
    int d = density, nu = s->nu, nv = s->nv, cu = s->closed_u != 0, cv = s->closed_v != 0;
    int nu_d = nu * d, nv_d = nv * d;
    int GU = nu_d + (cu ? 0 : 1), GV = nv_d + (cv ? 0 : 1);
    size_t ng = (size_t)GU * (size_t)GV, np = (size_t)nu * (size_t)nv;
    size_t max_tri = 2 * np * (size_t)d * (size_t)d;
    double tol = rg2__collapse_tol(s);
    unsigned *coll = rg2__calloc(np, sizeof *coll);
    int *parent = NULL, *id = NULL, failed = 0, any = 0;
    char *block = NULL;
    if (!coll) {
        failed = 1;
        goto done;
    }
    for (size_t p = 0; p < np; p++) {
        coll[p] = rg2__surface_collapsed_sides(s, (int)(p / (size_t)nv), (int)(p % (size_t)nv), tol);
        any |= coll[p] != 0;
    }
    /* Vertex numbers: grid point k is vertex k, or with collapsed sides, vertex id[k] (the
     * number of its set's root, in the order of the roots). */
    int nvert = (int)ng;
    if (any) {
        parent = rg2__alloc_big(ng, sizeof(int), TESS_BIG_BYTES, 0); /* (both written whole below) */
        id = rg2__alloc_big(ng, sizeof(int), TESS_BIG_BYTES, 0);
        if (!parent || !id) {
            failed = 1;
            goto done;
        }
        for (size_t k = 0; k < ng; k++)
            parent[k] = (int)k;
        for (int i = 0; i < nu; i++)
            for (int j = 0; j < nv; j++)
                for (int side = 0; side < 4; side++) {
                    if (!(coll[(size_t)i * (size_t)nv + (size_t)j] & (1u << side)))
                        continue;
                    for (int t = 0; t <= d; t++) {
                        int I, J, I0, J0;
                        switch (side) {
                        case 0: I = i * d + t; J = j * d; I0 = i * d; J0 = J; break;
                        case 1: I = (i + 1) * d; J = j * d + t; I0 = I; J0 = j * d; break;
                        case 2: I = i * d + t; J = (j + 1) * d; I0 = i * d; J0 = J; break;
                        default: I = i * d; J = j * d + t; I0 = I; J0 = j * d; break;
                        }
                        rg2__uf_union(parent, gidx(I, J, nu_d, nv_d, cu, cv, GV),
                                      gidx(I0, J0, nu_d, nv_d, cu, cv, GV));
                    }
                }
        nvert = 0;
        for (size_t k = 0; k < ng; k++)
            id[k] = rg2__uf_find(parent, (int)k) == (int)k ? nvert++ : -1;
        for (size_t k = 0; k < ng; k++) /* (parent[k] == k still marks the roots) */
            if (id[k] < 0)
                id[k] = id[rg2__uf_find(parent, (int)k)];
    }
    /* The block: pos, normal, [K, H], uv (doubles), patch, tri (ints), each on a cache line. */
    size_t nvs = (size_t)nvert, b_pos = line_up(3 * nvs * sizeof(double)), b_kh = line_up(nvs * sizeof(double));
    size_t b_uv = line_up(2 * nvs * sizeof(double)), b_patch = line_up(nvs * sizeof(int));
    size_t b_tri = line_up(3 * max_tri * sizeof(int));
    size_t total = 2 * b_pos + (curvature ? 2 * b_kh : 0) + b_uv + b_patch + b_tri;
    if (old && oldcap >= total) { /* the previous mesh's block: no fresh pages */
        block = old;
        total = oldcap;
    } else {
        free(old);
        block = rg2__alloc_big(total, 1, TESS_BIG_BYTES, 0); /* every array written below */
    }
    old = NULL;
    out->capacity = total;
    if (!block) {
        failed = 1;
        goto done;
    }
    {
        char *c = block;
        out->pos = (double *)c;
        c += b_pos;
        out->normal = (double *)c;
        c += b_pos;
        if (curvature) {
            out->K = (double *)c;
            c += b_kh;
            out->H = (double *)c;
            c += b_kh;
        }
        out->uv = (double *)c;
        c += b_uv;
        out->patch = (int *)c;
        c += b_patch;
        out->tri = (int *)c;
    }
    out->n_vertices = nvert;
    size_t npp = (size_t)(d + 1) * (size_t)(d + 1);
    /* the parameters b / d, b = 0..d, divided once (a division per vertex took half the copying) */
    double *par = malloc(sizeof(double) * (size_t)(d + 1));
    if (!par) {
        failed = 1;
        goto done;
    }
    for (int b = 0; b <= d; b++)
        par[b] = b == d ? 1.0 : (double)b / d;
    /* Threads: the grid's pool (src/pool.c), whose workers spin a while between calls. An OpenMP
     * region woke its second thread for longer than it saved: the bundled design at density 16
     * (31K vertices) took 0.41-0.49 ms on two OpenMP threads, 0.31-0.33 ms on one, and 0.16-0.17
     * ms on the pool's two (again into the same mesh; docs/performance.md, "Tessellating again,
     * on the pool"). */
    int nth = 1;
    (void)threads; /* (without OpenMP: one) */
#ifdef RG2_HAVE_OPENMP
    if (np * npp > TESS_THREADS_FROM)
        nth = threads > 0 ? threads : omp_get_max_threads();
#endif
    if (nth > 64)
        nth = 64;
    /* Triangles: each row of quads into its own slots (2 nv d triangles), the rows' counts kept;
     * then the rows moved together where triangles were dropped. */
    int *rowcnt = rg2__calloc((size_t)nu_d, sizeof(int));
    if (!rowcnt) {
        free(par);
        failed = 1;
        goto done;
    }
    /* Without merged vertices and with two grid lines at least in a closed direction, a quad's
     * four corners are distinct vertices (their grid indices) and no triangle is dropped. */
    tess_job job = {.s = s, .out = out, .coll = coll, .parent = parent, .id = id, .par = par, .rowcnt = rowcnt,
                    .d = d, .nu = nu, .nv = nv, .cu = cu, .cv = cv, .GV = GV, .nu_d = nu_d, .nv_d = nv_d,
                    .curvature = curvature, .plain = !id && (nu_d > 1 || !cu) && (nv_d > 1 || !cv), .npp = npp};
    job.nchunk = nth == 1 ? 1 : (uint32_t)(np < (size_t)(8 * nth) ? np : (size_t)(8 * nth));
    rg2__pool_run(nth, job.nchunk, sample_chunk, &job);
    free(par);
    if (atomic_load(&job.failed)) {
        free(rowcnt);
        failed = 1;
        goto done;
    }
    job.nchunk = nth == 1 ? 1 : (uint32_t)(nu_d < 8 * nth ? nu_d : 8 * nth);
    rg2__pool_run(nth, job.nchunk, tri_chunk, &job);
    size_t nt = 0;
    for (int I = 0; I < nu_d; I++) {
        size_t at = (size_t)2 * (size_t)nv_d * (size_t)I;
        if (at != nt)
            memmove(out->tri + 3 * nt, out->tri + 3 * at, (size_t)rowcnt[I] * 3 * sizeof(int));
        nt += (size_t)rowcnt[I];
    }
    free(rowcnt);
    out->n_triangles = (int)nt;
    if (rg2_surface_min_weight(s) <= 0.0) { /* (positive weights keep every point finite) */
        st = infinite_vertex(s, out, err);
        if (st) {
            rg2_tess_free(out);
            block = NULL;
        }
    }
done:
    free(old); /* (not yet taken over: failed before the block) */
    free(coll);
    free(parent);
    free(id);
    if (failed) {
        if (block)
            out->pos = (double *)block;
        rg2_tess_free(out);
        return rg2__fail(err, RG2_ENOMEM, "tessellate: out of memory for %d x %d patches at density %d",
                         nu, nv, d);
    }
    if (st)
        return st;
    rg2__ok(err);
    return RG2_OK;
}

rg2_status rg2_tessellate(const rg2_surface *s, int density, int curvature, rg2_tess *out,
                          rg2_error *err)
{
    if (!out)
        return rg2__fail(err, RG2_EINVAL, "tessellate: no output (out is NULL)");
    memset(out, 0, sizeof *out);
    return tessellate(s, density, curvature, 0, out, NULL, 0, err);
}

rg2_status rg2_retessellate(const rg2_surface *s, int density, int curvature, rg2_tess *t, rg2_error *err)
{
    if (!t)
        return rg2__fail(err, RG2_EINVAL, "retessellate: no mesh (t is NULL)");
    char *old = (char *)t->pos; /* (NULL in a zeroed struct) */
    size_t cap = t->capacity;
    memset(t, 0, sizeof *t);
    return tessellate(s, density, curvature, 0, t, old, cap, err);
}

rg2_status rg2__tessellate_threads(const rg2_surface *s, int density, int threads, rg2_tess *out, rg2_error *err)
{
    memset(out, 0, sizeof *out);
    return tessellate(s, density, 0, threads, out, NULL, 0, err);
}
