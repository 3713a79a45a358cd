/* render.c -- pictures of the exact surface: shaded (shape tints, patch boundaries, control
 * mesh), mean and Gaussian curvature maps with a colour bar, and zebra / reflection lines.
 *
 * METHOD
 *   1. Camera: perspective, looking at the centre of the bounding sphere of the surfaces from
 *      (azimuth, elevation); "fit" puts the eye where the sphere fills the view.
 *   2. Visibility: each patch is sampled on a grid (density from its projected size), the
 *      triangles are rasterised into a z-buffer that stores (surface, patch, u, v).
 *   3. Exactness: per pixel, Newton on the exact patch moves (u, v) until the exact point lies
 *      on the pixel's centre ray (two residuals orthogonal to the ray); shading, H, K and the
 *      stripe phase are evaluated there with rg2_surface_eval (order 2). The sampling for
 *      the view and the z-buffer uses the grid evaluator (rg2_patch_grid). Patches of higher
 *      degree (s->xp) go through the same steps (their grid: rg2__xgrid_patch, xpatch.c).
 *   4. Colour: per-pixel, then overlays (boundaries, silhouettes, mesh, colour bar).
 *   Threads: the grid sampling and the per-pixel work are split by patch / by row, the
 *   rasteriser by bands of rows; no result depends on the thread count.
 */
#include "internal.h"
#include "xpatch_util.h"

#include <errno.h>
#include <float.h>
#include <png.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#ifdef _OPENMP
#include <omp.h>
#define RG2_PARALLEL_FOR _Pragma("omp parallel for schedule(dynamic, 1) num_threads(nt)")
#else
#define RG2_PARALLEL_FOR
#endif

#define BAR_MARGIN 110     /* pixels on the right for the colour bar */
#define BAR_MIN_HEIGHT 120 /* rows the bar needs: 40 above and below, at least 40 of bar */
#define BOUNDARY_FOOTPRINTS 3.0 /* patch boundaries: neighbours up to this many pixel widths apart */

/* ---------------------------------------------------------------- small vector helpers */

static double dot3(const double *a, const double *b) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }
static void cross3(const double *a, const double *b, double *c)
{
    c[0] = a[1] * b[2] - a[2] * b[1];
    c[1] = a[2] * b[0] - a[0] * b[2];
    c[2] = a[0] * b[1] - a[1] * b[0];
}
static void unit3(double *a)
{
    double l = sqrt(dot3(a, a));
    if (l > 0)
        for (int k = 0; k < 3; k++)
            a[k] /= l;
}
static double clamp01(double x) { return x < 0 ? 0 : (x > 1 ? 1 : x); }

/* ---------------------------------------------------------------- options and camera */

void rg2_render_opts_default(rg2_render_opts *o)
{
    memset(o, 0, sizeof *o);
    o->width = 800;
    o->height = 600;
    o->mode = RG2_RENDER_SHADED;
    o->azimuth = 35.0;
    o->elevation = 25.0;
    o->fov = 30.0;
    o->tint = 1;
    o->colorbar = 1;
    o->percentile = 0.02;
    o->stripes = 12.0;
}

typedef struct {
    double eye[3], f[3], r[3], up[3]; /* eye, forward, right, up (orthonormal) */
    double tx, ty;                    /* tan of the half field of view, x and y */
    int vw, h;                        /* viewport (surface area) width, image height */
    double scale;                     /* bounding-sphere radius */
} camera;

/* Continuous screen coordinates of x (pixel centres at k + 0.5); returns depth (<= 0 behind). */
static double project(const camera *c, const double x[3], double *sx, double *sy)
{
    double q[3] = {x[0] - c->eye[0], x[1] - c->eye[1], x[2] - c->eye[2]};
    double z = dot3(q, c->f);
    if (!(z > 0))
        return z;
    *sx = (dot3(q, c->r) / (z * c->tx) + 1.0) * 0.5 * c->vw;
    *sy = (1.0 - dot3(q, c->up) / (z * c->ty)) * 0.5 * c->h;
    return z;
}

/* The unit direction of the ray through the centre of pixel (px, py). */
static void pixel_ray(const camera *c, int px, int py, double d[3])
{
    double x = (2.0 * (px + 0.5) / c->vw - 1.0) * c->tx;
    double y = (1.0 - 2.0 * (py + 0.5) / c->h) * c->ty;
    for (int k = 0; k < 3; k++)
        d[k] = c->f[k] + x * c->r[k] + y * c->up[k];
    unit3(d);
}

/* Sample points of every patch (7 x 7 each) and, when overlaid, the mesh points: what the
 * view has to show. They are handed to fn in a fixed order (surface by surface, patch by patch,
 * then the surface's mesh points), a block at a time, as they come: the grids of SCENE_CHUNK
 * patches are evaluated on the threads, then passed on in order, so nothing depends on the
 * thread count. (They were all stored first: 1.2 KB a patch, 290 MB for 250 000 patches, more
 * than the surfaces themselves.) No point at all is an error. */
typedef void (*scene_fn)(void *ctx, const double *p, size_t m);
#define SCENE_S 6
#define SCENE_CHUNK 16384

static rg2_status scene_visit(const rg2_surface *surfs, int n, const rg2_mesh *meshes, int with_mesh, int nt,
                              scene_fn fn, void *ctx, rg2_error *err)
{
    enum { Q = (SCENE_S + 1) * (SCENE_S + 1) };
    int most = 1; /* patches a chunk */
    for (int s = 0; s < n; s++)
        if (surfs[s].nu * surfs[s].nv > most)
            most = surfs[s].nu * surfs[s].nv;
    if (most > SCENE_CHUNK)
        most = SCENE_CHUNK;
    double *buf = malloc(sizeof(double) * 3 * Q * (size_t)most);
    unsigned char *ok = malloc((size_t)most);
    if (!buf || !ok) {
        free(buf);
        free(ok);
        return rg2__fail(err, RG2_ENOMEM, "render: out of memory for the view samples");
    }
    size_t total = 0;
    (void)nt;
    for (int s = 0; s < n; s++) {
        const rg2_surface *S = &surfs[s];
        int np = S->nu * S->nv;
        for (int k0 = 0; k0 < np; k0 += SCENE_CHUNK) {
            int m = np - k0 < SCENE_CHUNK ? np - k0 : SCENE_CHUNK;
#ifdef _OPENMP
#pragma omp parallel for schedule(static) num_threads(nt) if (m > 64)
#endif
            for (int q = 0; q < m; q++) {
                rg2_grid_out go = {.pos = buf + (size_t)3 * Q * q};
                ok[q] = rg2__surface_patch_grid(S, (k0 + q) / S->nv, (k0 + q) % S->nv, SCENE_S + 1, SCENE_S + 1,
                                                &go, NULL) == RG2_OK;
            }
            for (int q = 0; q < m; q++) {
                if (!ok[q])
                    continue;
                double *g = buf + (size_t)3 * Q * q;
                size_t c = 0;
                for (int t = 0; t < Q; t++)
                    if (isfinite(g[3 * t]) && isfinite(g[3 * t + 1]) && isfinite(g[3 * t + 2]))
                        memmove(g + 3 * c++, g + 3 * t, 3 * sizeof *g);
                if (c)
                    fn(ctx, g, c);
                total += c;
            }
        }
        if (with_mesh) {
            const rg2_mesh *me = &meshes[s];
            for (int i = 0; i < me->nu; i++)
                for (int j = 0; j < me->nv; j++) {
                    const double *h = rg2_mesh_at(me, i, j);
                    if (h[3] > 0 && isfinite(h[0] / h[3]) && isfinite(h[1] / h[3]) && isfinite(h[2] / h[3])) {
                        double x[3] = {h[0] / h[3], h[1] / h[3], h[2] / h[3]};
                        fn(ctx, x, 1);
                        total++;
                    }
                }
        }
    }
    free(buf);
    free(ok);
    if (total == 0)
        return rg2__fail(err, RG2_EINVAL, "render: no finite surface point to look at");
    return RG2_OK;
}

/* The view: direction from (azimuth, elevation), up = +z. Fit: centre the samples' extent
 * across the view and put the eye at the smallest distance where every sample lies inside
 * 92% of the field (exact for the fixed direction, perspective included). */
static void view_frame(const rg2_render_opts *o, double dir[3], double f[3], double r[3], double up[3])
{
    /* the azimuth reduced first: 1e308 degrees overflowed to an infinite angle, an empty picture */
    double az = fmod(o->azimuth, 360.0) * M_PI / 180.0, el = o->elevation * M_PI / 180.0;
    dir[0] = cos(el) * cos(az), dir[1] = cos(el) * sin(az), dir[2] = sin(el); /* centre -> eye */
    for (int k = 0; k < 3; k++)
        f[k] = -dir[k];
    double z[3] = {0, 0, 1};
    cross3(f, z, r);
    if (dot3(r, r) < 1e-20) {
        /* looking straight up or down: the right vector's limit as the elevation nears +-90 at
         * this azimuth, (-sin A, cos A, 0). (It was f x y, +x or -x whatever the azimuth: the
         * view turned by 90 - A degrees between elevations 89.9999 and 90, and the azimuth did
         * not turn a top view.) */
        r[0] = -sin(az), r[1] = cos(az), r[2] = 0;
    }
    unit3(r);
    cross3(r, f, up);
}

/* camera_setup's two passes over the scene's points: their extent in the camera frame, then
 * the eye distance that fits them all. */
typedef struct {
    const camera *c;
    const double *dir;
    double lo[3], hi[3];   /* pass 1 */
    double cx, cy, cz, dist; /* pass 2 */
} view_fit;

static void fit_extent(void *ctx, const double *pts, size_t npts)
{
    view_fit *v = ctx;
    for (size_t k = 0; k < npts; k++) {
        const double *p = pts + 3 * k;
        double q[3] = {dot3(p, v->c->r), dot3(p, v->c->up), dot3(p, v->dir)};
        for (int d = 0; d < 3; d++) {
            if (q[d] < v->lo[d]) v->lo[d] = q[d];
            if (q[d] > v->hi[d]) v->hi[d] = q[d];
        }
    }
}

static void fit_distance(void *ctx, const double *pts, size_t npts)
{
    view_fit *v = ctx;
    const camera *c = v->c;
    for (size_t k = 0; k < npts; k++) {
        const double *p = pts + 3 * k;
        double x = fabs(dot3(p, c->r) - v->cx), y = fabs(dot3(p, c->up) - v->cy), zz = dot3(p, v->dir) - v->cz;
        double need = zz + fmax(x / (0.92 * c->tx), y / (0.92 * c->ty));
        if (need > v->dist) v->dist = need;
    }
}

static rg2_status camera_setup(camera *c, const rg2_render_opts *o, int vw, const rg2_surface *surfs, int n,
                               const rg2_mesh *meshes, int nt, rg2_error *err)
{
    double dir[3];
    view_frame(o, dir, c->f, c->r, c->up);
    c->vw = vw;
    c->h = o->height;
    c->ty = tan(0.5 * o->fov * M_PI / 180.0);
    c->tx = c->ty * (double)vw / (double)o->height;
    /* extents in the camera frame */
    view_fit v = {c, dir, {DBL_MAX, DBL_MAX, DBL_MAX}, {-DBL_MAX, -DBL_MAX, -DBL_MAX}, 0, 0, 0, 0};
    rg2_status st = scene_visit(surfs, n, meshes, o->mesh, nt, fit_extent, &v, err);
    if (st)
        return st;
    double *lo = v.lo, *hi = v.hi;
    double cx = 0.5 * (lo[0] + hi[0]), cy = 0.5 * (lo[1] + hi[1]), cz = 0.5 * (lo[2] + hi[2]);
    double centre[3], r2 = 0;
    for (int k = 0; k < 3; k++) {
        centre[k] = cx * c->r[k] + cy * c->up[k] + cz * dir[k];
        r2 += 0.25 * (hi[k] - lo[k]) * (hi[k] - lo[k]);
    }
    c->scale = sqrt(r2) > 0 ? sqrt(r2) : 1.0;
    double dist = o->distance;
    if (!(dist > 0)) {
        v.cx = cx, v.cy = cy, v.cz = cz, v.dist = 0;
        if ((st = scene_visit(surfs, n, meshes, o->mesh, nt, fit_distance, &v, err)))
            return st;
        dist = fmax(v.dist, (hi[2] - cz) + 0.05 * c->scale);
    }
    for (int k = 0; k < 3; k++)
        c->eye[k] = centre[k] + dist * dir[k];
    return RG2_OK;
}

/* ---------------------------------------------------------------- rasterisation */

typedef struct {
    float sx, sy;
    double z;
} vtx;

typedef struct {
    double z;
    int surf, patch;
    float u, v;
} zcell;

/* Grid density of patch k of S (any degree): about one sample per 3 pixels of its projected
 * control net. */
static int patch_density(const camera *c, const rg2_surface *S, size_t k)
{
    double ext = 0, sx0 = 0, sy0 = 0;
    double lo[2] = {DBL_MAX, DBL_MAX}, hi[2] = {-DBL_MAX, -DBL_MAX};
    int du, dv;
    rg2__patch_degree(S, k, &du, &dv);
    for (int r = 0; r <= du; r++)
        for (int s = 0; s <= dv; s++) {
            const double *h = rg2__patch_ctrl(S, k, r, s);
            if (!(h[3] > 0))
                return 24;
            double x[3] = {h[0] / h[3], h[1] / h[3], h[2] / h[3]};
            if (!(project(c, x, &sx0, &sy0) > 0))
                return 24;
            if (sx0 < lo[0]) lo[0] = sx0;
            if (sy0 < lo[1]) lo[1] = sy0;
            if (sx0 > hi[0]) hi[0] = sx0;
            if (sy0 > hi[1]) hi[1] = sy0;
        }
    ext = fmax(hi[0] - lo[0], hi[1] - lo[1]);
    int N = (int)ceil(ext / 3.0);
    return N < 4 ? 4 : (N > 96 ? 96 : N);
}

static void raster_tri(zcell *zb, int W, int y0, int y1, int xmax, const vtx *a, const vtx *b, const vtx *d,
                       float (*uv)[2], int surf, int patch)
{
    double minx = fmin(a->sx, fmin(b->sx, d->sx)), maxx = fmax(a->sx, fmax(b->sx, d->sx));
    double miny = fmin(a->sy, fmin(b->sy, d->sy)), maxy = fmax(a->sy, fmax(b->sy, d->sy));
    int ix0 = (int)floor(minx - 0.5), ix1 = (int)ceil(maxx - 0.5);
    int iy0 = (int)floor(miny - 0.5), iy1 = (int)ceil(maxy - 0.5);
    if (ix0 < 0) ix0 = 0;
    if (iy0 < y0) iy0 = y0;
    if (ix1 > xmax - 1) ix1 = xmax - 1;
    if (iy1 > y1 - 1) iy1 = y1 - 1;
    if (ix0 > ix1 || iy0 > iy1)
        return;
    double area = (double)(b->sx - a->sx) * (d->sy - a->sy) - (double)(b->sy - a->sy) * (d->sx - a->sx);
    if (fabs(area) < 1e-12)
        return;
    double ia = 1.0 / area;
    for (int y = iy0; y <= iy1; y++)
        for (int x = ix0; x <= ix1; x++) {
            double px = x + 0.5, py = y + 0.5;
            double w1 = ((px - a->sx) * (d->sy - a->sy) - (py - a->sy) * (d->sx - a->sx)) * ia;
            double w2 = ((b->sx - a->sx) * (py - a->sy) - (b->sy - a->sy) * (px - a->sx)) * ia;
            double w0 = 1.0 - w1 - w2;
            const double eps = -1e-6; /* close the cracks between triangles */
            if (w0 < eps || w1 < eps || w2 < eps)
                continue;
            /* perspective-correct interpolation of 1/z */
            double iz = w0 / a->z + w1 / b->z + w2 / d->z;
            double z = 1.0 / iz;
            zcell *zc = &zb[(size_t)y * W + x];
            if (z < zc->z) {
                double c0 = w0 / a->z * z, c1 = w1 / b->z * z, c2 = w2 / d->z * z;
                zc->z = z;
                zc->surf = surf;
                zc->patch = patch;
                zc->u = (float)(c0 * uv[0][0] + c1 * uv[1][0] + c2 * uv[2][0]);
                zc->v = (float)(c0 * uv[0][1] + c1 * uv[1][1] + c2 * uv[2][1]);
            }
        }
}

/* Per-surface grid densities without T-junctions: patch (i, j) gets du[i] x dv[j] cells, the
 * maxima of patch_density over its patch column / row, so neighbouring patches sample their
 * common edge at the same parameters (no cracks for the far side to show through). dens holds
 * for each surface nu values du then nv values dv, at offsets doff[s]. */
static int *grid_densities(const rg2_surface *surfs, int n, const camera *c, size_t *doff)
{
    size_t tot = 0;
    for (int s = 0; s < n; s++) {
        doff[s] = tot;
        tot += (size_t)surfs[s].nu + (size_t)surfs[s].nv;
    }
    int *dens = rg2__calloc(tot, sizeof *dens);
    if (!dens)
        return NULL;
    for (int s = 0; s < n; s++) {
        int *du = dens + doff[s], *dv = du + surfs[s].nu;
        for (int i = 0; i < surfs[s].nu; i++)
            for (int j = 0; j < surfs[s].nv; j++) {
                int N = patch_density(c, &surfs[s], (size_t)i * (size_t)surfs[s].nv + (size_t)j);
                if (N > du[i]) du[i] = N;
                if (N > dv[j]) dv[j] = N;
            }
    }
    return dens;
}

/* Rasterise every patch of every surface into the z-buffer (rows 0..h-1, columns 0..vw-1). */
static rg2_status rasterise(const rg2_surface *surfs, int n, const camera *c, zcell *zb, int W, int nt,
                            rg2_error *err)
{
    /* A chunk of patches is gridded on the threads, then rasterised by bands of rows on the
     * threads: up to CHUNK patches or RASTER_VERTS grid points a chunk. (At 64 patches a chunk,
     * the tiny patches of a big design (250 000 of them) made thousands of parallel regions, each
     * a few microseconds of work: on a busy machine a thread waiting at their barriers for one
     * descheduled made the picture 6 to 10 times slower than on one thread.) */
    enum { CHUNK = 4096, RASTER_VERTS = 1 << 19 };
    size_t *doff = rg2__calloc((size_t)n, sizeof *doff);
    int *dens = doff ? grid_densities(surfs, n, c, doff) : NULL;
    int *Nu = rg2__calloc(CHUNK, sizeof *Nu), *Nv = rg2__calloc(CHUNK, sizeof *Nv);
    size_t *off = rg2__calloc(CHUNK + 1, sizeof *off);
    int *ps = rg2__calloc(CHUNK, sizeof *ps), *pk = rg2__calloc(CHUNK, sizeof *pk);
    vtx *verts = NULL;
    size_t cap = 0;
    rg2_status st = RG2_OK;
    if (!doff || !dens || !Nu || !Nv || !off || !ps || !pk) {
        st = rg2__fail(err, RG2_ENOMEM, "render: out of memory for the rasteriser");
        goto out;
    }
    int s = 0;
    size_t k = 0;
    while (s < n) {
        /* gather a chunk of patches */
        int m = 0;
        while (m < CHUNK && s < n && (m == 0 || off[m] < RASTER_VERTS)) {
            size_t np = (size_t)surfs[s].nu * (size_t)surfs[s].nv;
            if (k >= np) {
                s++;
                k = 0;
                continue;
            }
            ps[m] = s;
            pk[m] = (int)k;
            Nu[m] = dens[doff[s] + k / (size_t)surfs[s].nv];
            Nv[m] = dens[doff[s] + (size_t)surfs[s].nu + k % (size_t)surfs[s].nv];
            off[m + 1] = off[m] + (size_t)(Nu[m] + 1) * (size_t)(Nv[m] + 1);
            m++;
            k++;
        }
        if (m == 0)
            break;
        if (off[m] > cap) {
            free(verts);
            cap = off[m];
            verts = rg2__calloc(cap, sizeof *verts);
            if (!verts) {
                st = rg2__fail(err, RG2_ENOMEM, "render: out of memory for %zu grid points", cap);
                goto out;
            }
        }
        RG2_PARALLEL_FOR
        for (int q = 0; q < m; q++) {
            int A = Nu[q], B = Nv[q];
            const rg2_surface *S = &surfs[ps[q]];
            int pi = pk[q] / S->nv, pj = pk[q] % S->nv;
            /* positions by the grid evaluator (one Bernstein table per patch), per point as a
             * fallback if its buffer cannot be had */
            double *g = malloc(sizeof(double) * 3 * (size_t)(A + 1) * (size_t)(B + 1));
            rg2_grid_out go = {.pos = g};
            int have_grid = g && rg2__surface_patch_grid(S, pi, pj, A + 1, B + 1, &go, NULL) == RG2_OK;
            for (int a = 0; a <= A; a++)
                for (int b = 0; b <= B; b++) {
                    double pt[3];
                    size_t idx = (size_t)a * (B + 1) + b;
                    if (have_grid)
                        memcpy(pt, g + 3 * idx, sizeof pt);
                    else {
                        rg2_eval e;
                        rg2_surface_eval(S, pi, pj, (double)a / A, (double)b / B, 0, &e);
                        memcpy(pt, e.p, sizeof pt);
                    }
                    vtx *t = &verts[off[q] + idx];
                    double sx = 0, sy = 0;
                    t->z = (isfinite(pt[0]) && isfinite(pt[1]) && isfinite(pt[2])) ? project(c, pt, &sx, &sy) : -1.0;
                    t->sx = (float)sx;
                    t->sy = (float)sy;
                }
            free(g);
        }
        /* bands of rows: each pixel is written by one thread, triangles in a fixed order */
        int bands = nt > 1 ? 4 * nt : 1, h = c->h;
        double znear = 1e-6 * c->scale;
        RG2_PARALLEL_FOR
        for (int band = 0; band < bands; band++) {
            int y0 = (int)((long)h * band / bands), y1 = (int)((long)h * (band + 1) / bands);
            for (int q = 0; q < m; q++) {
                int A = Nu[q], B = Nv[q];
                const vtx *g = &verts[off[q]];
                for (int a = 0; a < A; a++)
                    for (int b = 0; b < B; b++) {
                        const vtx *v00 = &g[a * (B + 1) + b], *v10 = &g[(a + 1) * (B + 1) + b];
                        const vtx *v01 = &g[a * (B + 1) + b + 1], *v11 = &g[(a + 1) * (B + 1) + b + 1];
                        if (v00->z <= znear || v10->z <= znear || v01->z <= znear || v11->z <= znear)
                            continue;
                        /* a quad wholly above or below the band: raster_tri would draw nothing */
                        double qy0 = fmin(fmin(v00->sy, v10->sy), fmin(v01->sy, v11->sy));
                        double qy1 = fmax(fmax(v00->sy, v10->sy), fmax(v01->sy, v11->sy));
                        if (ceil(qy1 - 0.5) < y0 || floor(qy0 - 0.5) > y1 - 1)
                            continue;
                        float u0 = (float)a / A, u1 = (float)(a + 1) / A, w0 = (float)b / B, w1 = (float)(b + 1) / B;
                        float t1[3][2] = {{u0, w0}, {u1, w0}, {u1, w1}};
                        float t2[3][2] = {{u0, w0}, {u1, w1}, {u0, w1}};
                        raster_tri(zb, W, y0, y1, c->vw, v00, v10, v11, t1, ps[q], pk[q]);
                        raster_tri(zb, W, y0, y1, c->vw, v00, v11, v01, t2, ps[q], pk[q]);
                    }
            }
        }
        memset(off, 0, (CHUNK + 1) * sizeof *off);
    }
out:
    free(verts);
    free(doff);
    free(dens);
    free(Nu);
    free(Nv);
    free(off);
    free(ps);
    free(pk);
    return st;
}

/* ---------------------------------------------------------------- exact per-pixel data */

/* Newton: move (u, v) in [0,1]^2 until patch (i, j) of S (any degree) at (u, v) lies on the
 * ray eye + t d. Returns 1 if the residual reached 1e-12 of the scene size. */
static int refine(const rg2_surface *S, int i, int j, const camera *c, const double d[3], double *u, double *v,
                  double *resid)
{
    double e1[3], e2[3];
    for (int k = 0; k < 3; k++)
        e1[k] = c->r[k] - dot3(c->r, d) * d[k];
    unit3(e1);
    cross3(d, e1, e2);
    double tol = 1e-12 * c->scale, best = DBL_MAX, bu = *u, bv = *v;
    for (int it = 0; it < 12; it++) {
        rg2_eval e;
        rg2_surface_eval(S, i, j, *u, *v, 1, &e);
        double q[3] = {e.p[0] - c->eye[0], e.p[1] - c->eye[1], e.p[2] - c->eye[2]};
        double F0 = dot3(q, e1), F1 = dot3(q, e2), res = hypot(F0, F1);
        if (!isfinite(res))
            break;
        if (res < best) {
            best = res;
            bu = *u;
            bv = *v;
        }
        if (res <= tol)
            break;
        double a = dot3(e.su, e1), b = dot3(e.sv, e1), cc = dot3(e.su, e2), dd = dot3(e.sv, e2);
        double det = a * dd - b * cc;
        if (!(fabs(det) > 0))
            break;
        double du = (dd * F0 - b * F1) / det, dv = (a * F1 - cc * F0) / det;
        double nu = *u - du, nv = *v - dv;
        nu = nu < 0 ? 0 : (nu > 1 ? 1 : nu);
        nv = nv < 0 ? 0 : (nv > 1 ? 1 : nv);
        if (nu == *u && nv == *v)
            break;
        *u = nu;
        *v = nv;
    }
    *u = bu;
    *v = bv;
    *resid = best;
    return best <= tol;
}

/* Zebra phase: the reflected view ray's angle about the light-line axis A (the camera's right
 * vector turned 30 degrees towards up): parallel light lines along A, all around the scene,
 * reflect as stripes of constant phase. The phase depends on the normal only through the
 * reflection, so stripes are continuous across G1 seams and smooth (no kink) across G2 seams. */
static double stripe_phase(const camera *c, const double d[3], const double nf[3])
{
    double dn = dot3(d, nf), r[3], C[3];
    const double ca = 0.86602540378443865, sa = 0.5;
    for (int k = 0; k < 3; k++) {
        r[k] = d[k] - 2.0 * dn * nf[k];
        C[k] = -sa * c->r[k] + ca * c->up[k];
    }
    return atan2(dot3(r, c->f), dot3(r, C));
}

static void pixel_exact(const rg2_surface *surfs, const camera *c, const zcell *zc, int px, int py, rg2_pixel *o,
                        int *converged)
{
    memset(o, 0, sizeof *o);
    o->surf = -1;
    o->patch = -1;
    if (zc->surf < 0)
        return;
    const rg2_surface *S = &surfs[zc->surf];
    int i = zc->patch / S->nv, j = zc->patch % S->nv;
    double d[3], u = zc->u, v = zc->v, res;
    pixel_ray(c, px, py, d);
    *converged = refine(S, i, j, c, d, &u, &v, &res);
    /* the limit at a pole: Newton can end on a collapsed side (the pole of a sphere seen from
     * above), where rg2_surface_eval has no normal and K = H = 0: such a pixel was shaded as if
     * facing away from the lights, a dark speck, and coloured as if flat */
    rg2_eval e;
    rg2_surface_eval_limit(S, i, j, u, v, 2, &e);
    if (!isfinite(e.p[0]) || !isfinite(e.p[1]) || !isfinite(e.p[2]))
        return;
    o->surf = zc->surf;
    o->patch = zc->patch;
    o->u = u;
    o->v = v;
    memcpy(o->p, e.p, sizeof o->p);
    memcpy(o->n, e.n, sizeof o->n);
    o->H = e.H;
    o->K = e.K;
    o->resid = res;
    double nf[3] = {e.n[0], e.n[1], e.n[2]};
    if (dot3(nf, d) > 0)
        for (int k = 0; k < 3; k++)
            nf[k] = -nf[k];
    o->phase = stripe_phase(c, d, nf);
}

/* ---------------------------------------------------------------- colours */

/* Piecewise-linear colour map through nc control colours. */
static void colormap(const double (*cm)[3], int nc, double t, double rgb[3])
{
    t = clamp01(t) * (nc - 1);
    int i = (int)floor(t);
    if (i >= nc - 1)
        i = nc - 2;
    double f = t - i;
    for (int k = 0; k < 3; k++)
        rgb[k] = cm[i][k] * (1 - f) + cm[i + 1][k] * f;
}

static const double RAINBOW[][3] = {{0.19, 0.07, 0.55}, {0.12, 0.35, 0.85}, {0.10, 0.70, 0.85},
                                    {0.25, 0.80, 0.35}, {0.85, 0.85, 0.15}, {0.95, 0.50, 0.10},
                                    {0.80, 0.10, 0.08}};
static const double DIVERGING[][3] = {{0.23, 0.30, 0.75}, {0.55, 0.69, 0.99}, {0.87, 0.87, 0.87},
                                      {0.96, 0.60, 0.48}, {0.71, 0.02, 0.15}};

/* Shape tints: golden exact pieces (Fig. 1 of the paper), a different warm tone per shape;
 * transition patches cool grey-blue. */
static void tint_color(const rg2_surface *s, int patch, int tint, double rgb[3])
{
    static const double shapes[][3] = {{0.86, 0.66, 0.22}, {0.80, 0.45, 0.22}, {0.70, 0.72, 0.25},
                                       {0.88, 0.52, 0.45}, {0.78, 0.70, 0.45}, {0.62, 0.50, 0.30}};
    static const double neutral[3] = {0.74, 0.75, 0.78}, transition[3] = {0.58, 0.66, 0.80};
    const double *c = neutral;
    if (tint && s->tag) {
        int t = s->tag[patch];
        c = t < 0 ? transition : shapes[t % 6];
    }
    memcpy(rgb, c, sizeof(double[3]));
}

typedef struct {
    double key[3], fill[3], half[3]; /* light directions (towards the lights), key half-vector */
} lights;

static void lights_setup(const camera *c, lights *L)
{
    for (int k = 0; k < 3; k++) {
        L->key[k] = -c->f[k] + 0.55 * c->up[k] - 0.45 * c->r[k];
        L->fill[k] = -c->f[k] - 0.3 * c->up[k] + 0.8 * c->r[k];
    }
    unit3(L->key);
    unit3(L->fill);
}

/* Diffuse and specular terms at a pixel (normal turned towards the viewer). */
static void lighting(const lights *L, const camera *c, const rg2_pixel *p, int px, int py, double *diff,
                     double *spec)
{
    double d[3], nf[3] = {p->n[0], p->n[1], p->n[2]}, h[3];
    pixel_ray(c, px, py, d);
    if (dot3(nf, d) > 0)
        for (int k = 0; k < 3; k++)
            nf[k] = -nf[k];
    for (int k = 0; k < 3; k++)
        h[k] = L->key[k] - d[k];
    unit3(h);
    double kd = fmax(0, dot3(nf, L->key)), fd = fmax(0, dot3(nf, L->fill));
    *diff = 0.78 * kd + 0.22 * fd;
    *spec = pow(fmax(0, dot3(nf, h)), 48.0);
}

static int cmp_double(const void *a, const void *b)
{
    double x = *(const double *)a, y = *(const double *)b;
    return (x > y) - (x < y);
}

/* Robust colour range: clip the fraction p at each end; Gauss symmetric about 0. */
/* The colour range of the curvature maps; radius: the scene's bounding-sphere radius, the length
 * that makes the smallest span scale with the picture (K in 1 / length^2, H in 1 / length). */
static rg2_status robust_range(const rg2_pixel *px, size_t np, int gauss, double p, double radius, double range[2],
                               rg2_error *err)
{
    size_t m = 0;
    for (size_t k = 0; k < np; k++)
        if (px[k].surf >= 0 && isfinite(gauss ? px[k].K : px[k].H))
            m++;
    if (m == 0) {
        range[0] = -1;
        range[1] = 1;
        return RG2_OK;
    }
    double *v = rg2__calloc(m, sizeof *v);
    if (!v)
        return rg2__fail(err, RG2_ENOMEM, "render: out of memory for the colour range");
    m = 0;
    for (size_t k = 0; k < np; k++)
        if (px[k].surf >= 0 && isfinite(gauss ? px[k].K : px[k].H))
            v[m++] = gauss ? fabs(px[k].K) : px[k].H;
    qsort(v, m, sizeof *v, cmp_double);
    size_t ilo = (size_t)floor(p * (double)(m - 1)), ihi = (size_t)ceil((1.0 - p) * (double)(m - 1));
    if (gauss) {
        range[0] = -v[ihi];
        range[1] = v[ihi];
    } else {
        range[0] = v[ilo];
        range[1] = v[ihi];
    }
    free(v);
    double mid = 0.5 * (range[0] + range[1]), span = range[1] - range[0];
    /* a constant map (sphere, plane) sits mid-bar; the floor in the scene's units (a fixed 1e-9
     * made the K map of a torus scaled by 1e5, |K| <= 5e-11, one flat grey: 539-2642 colours) */
    double minspan = fmax(1e-3 * fabs(mid), 1e-9 / (gauss ? radius * radius : radius));
    if (span < minspan) {
        range[0] = mid - 0.5 * minspan;
        range[1] = mid + 0.5 * minspan;
    }
    return RG2_OK;
}

/* ---------------------------------------------------------------- overlays */

static void blend(unsigned char *px, const double rgb[3], double a)
{
    for (int k = 0; k < 3; k++) {
        double x = px[k] * (1 - a) + 255.0 * rgb[k] * a;
        px[k] = (unsigned char)lround(x < 0 ? 0 : (x > 255 ? 255 : x));
    }
}

/* Clip the segment (x0, y0)-(x1, y1) to the box [-M, W + M] x [-M, H + M] (Liang-Barsky):
 * 0 when none of it is inside, or an end is not finite. A segment inside is left as it is; a
 * clipped one is formed from halves of its ends (their differences stay finite). Mesh points
 * far off the view project to coordinates past the int range, which mask_segment converted
 * to int (undefined; on x86 INT_MIN, so the line from an on-screen point to such a point was
 * not drawn). Pixels that a segment covers lie within 3 of it, inside the box: the mask is
 * the same. */
static int clip_segment(double *x0, double *y0, double *x1, double *y1, int W, int H)
{
    const double M = 16.0, lo[2] = {-M, -M}, hi[2] = {W + M, H + M};
    double a[2] = {*x0, *y0}, b[2] = {*x1, *y1};
    for (int k = 0; k < 2; k++)
        if (!(rg2__finite(a[k]) && rg2__finite(b[k])))
            return 0;
    if (a[0] >= lo[0] && a[0] <= hi[0] && a[1] >= lo[1] && a[1] <= hi[1] && b[0] >= lo[0] && b[0] <= hi[0] &&
        b[1] >= lo[1] && b[1] <= hi[1])
        return 1;
    double t0 = 0.0, t1 = 1.0, ha[2], hd[2];
    for (int k = 0; k < 2; k++) {
        ha[k] = 0.5 * a[k];
        hd[k] = 0.5 * b[k] - ha[k];
        double p[2] = {-hd[k], hd[k]}, q[2] = {ha[k] - 0.5 * lo[k], 0.5 * hi[k] - ha[k]};
        for (int e = 0; e < 2; e++) {
            if (p[e] == 0.0) {
                if (q[e] < 0.0)
                    return 0;
                continue;
            }
            double r = q[e] / p[e];
            if (p[e] < 0.0) {
                if (r > t1)
                    return 0;
                if (r > t0)
                    t0 = r;
            } else {
                if (r < t0)
                    return 0;
                if (r < t1)
                    t1 = r;
            }
        }
    }
    *x0 = 2.0 * (ha[0] + t0 * hd[0]), *y0 = 2.0 * (ha[1] + t0 * hd[1]);
    *x1 = 2.0 * (ha[0] + t1 * hd[0]), *y1 = 2.0 * (ha[1] + t1 * hd[1]);
    return 1;
}

/* Coverage of an anti-aliased segment of half-width hw into mask (max, order independent), rows
 * of W, in columns 0..VW-1 (the view, left of a colour bar). */
static void mask_segment(float *mask, int W, int VW, int H, double x0, double y0, double x1, double y1, double hw)
{
    if (!clip_segment(&x0, &y0, &x1, &y1, VW, H))
        return;
    double dx = x1 - x0, dy = y1 - y0, len2 = dx * dx + dy * dy;
    int ix0 = (int)floor(fmin(x0, x1) - hw - 1), ix1 = (int)ceil(fmax(x0, x1) + hw + 1);
    int iy0 = (int)floor(fmin(y0, y1) - hw - 1), iy1 = (int)ceil(fmax(y0, y1) + hw + 1);
    if (ix0 < 0) ix0 = 0;
    if (iy0 < 0) iy0 = 0;
    if (ix1 > VW - 1) ix1 = VW - 1;
    if (iy1 > H - 1) iy1 = H - 1;
    double len = sqrt(len2);
    /* |dy| where the band is used, > 0 everywhere: clang computes wx and dx / dy before their
     * test, and 0 / 0 of a point's segment raised FE_INVALID */
    double ady = fmax(fabs(dy), 1e-9);
    for (int y = iy0; y <= iy1; y++) {
        /* restrict x to the segment's band on this row */
        int xa = ix0, xb = ix1;
        if (fabs(dy) > 1e-9 && len > 0) {
            double t0 = (y + 0.5 - y0) / dy;
            double xm = x0 + t0 * dx, wx = (hw + 1.5) * len / ady;
            if (fabs(dx) / ady < 1e6) {
                xa = (int)fmax(xa, floor(xm - wx));
                xb = (int)fmin(xb, ceil(xm + wx));
            }
        }
        for (int x = xa; x <= xb; x++) {
            double px = x + 0.5 - x0, py = y + 0.5 - y0;
            double t = len2 > 0 ? (px * dx + py * dy) / len2 : 0;
            t = t < 0 ? 0 : (t > 1 ? 1 : t);
            double ex = px - t * dx, ey = py - t * dy;
            float cov = (float)clamp01(hw + 0.5 - sqrt(ex * ex + ey * ey));
            float *m = &mask[(size_t)y * W + x];
            if (cov > *m)
                *m = cov;
        }
    }
}

/* The mesh in the view's columns only: a line running off the view was drawn across the colour
 * bar and its labels. */
static void mesh_overlay(const rg2_mesh *meshes, int n, const camera *c, rg2_image *img, float *mask)
{
    int W = img->width, H = img->height, VW = c->vw;
    for (int s = 0; s < n; s++) {
        const rg2_mesh *m = &meshes[s];
        int cu = m->su.closed, cv = m->sv.closed;
        for (int i = 0; i < m->nu; i++)
            for (int j = 0; j < m->nv; j++) {
                const double *h = rg2_mesh_at(m, i, j);
                if (!(h[3] > 0))
                    continue;
                double p[3] = {h[0] / h[3], h[1] / h[3], h[2] / h[3]}, x0, y0;
                if (!(project(c, p, &x0, &y0) > 0))
                    continue;
                mask_segment(mask, W, VW, H, x0, y0, x0, y0, 2.2);
                for (int dir = 0; dir < 2; dir++) {
                    int i2 = i + (dir == 0), j2 = j + (dir == 1);
                    if (i2 == m->nu) {
                        if (!cu) continue;
                        i2 = 0;
                    }
                    if (j2 == m->nv) {
                        if (!cv) continue;
                        j2 = 0;
                    }
                    const double *g = rg2_mesh_at(m, i2, j2);
                    double x1, y1, q[3] = {g[0] / g[3], g[1] / g[3], g[2] / g[3]};
                    if (!(g[3] > 0) || !(project(c, q, &x1, &y1) > 0))
                        continue;
                    mask_segment(mask, W, VW, H, x0, y0, x1, y1, 0.6);
                }
            }
    }
    static const double red[3] = {0.85, 0.08, 0.10};
    for (size_t k = 0; k < (size_t)W * H; k++)
        if (mask[k] > 0)
            blend(img->rgb + 3 * k, red, 0.9 * mask[k]);
}

/* A 5x7 bitmap font for the colour-bar labels: digits, sign, point, exponent, H, K. */
static const char *glyph(char ch)
{
    switch (ch) {
    case '0': return "01110100011001110101110011000101110";
    case '1': return "00100011000010000100001000010001110";
    case '2': return "01110100010000100010001000100011111";
    case '3': return "11111000100010000010000011000101110";
    case '4': return "00010001100101010010111110001000010";
    case '5': return "11111100001111000001000011000101110";
    case '6': return "00110010001000011110100011000101110";
    case '7': return "11111000010001000100010000100001000";
    case '8': return "01110100011000101110100011000101110";
    case '9': return "01110100011000101111000010001001100";
    case '-': return "00000000000000011111000000000000000";
    case '+': return "00000001000010011111001000010000000";
    case '.': return "00000000000000000000000000110001100";
    case 'e': return "00000000000111010001111111000001110";
    case 'H': return "10001100011000111111100011000110001";
    case 'K': return "10001100101010011000101001001010001";
    case '=': return "00000000001111100000111110000000000";
    default: return NULL;
    }
}

static void draw_text(rg2_image *img, int x, int y, const char *s, int scale)
{
    static const double ink[3] = {0.08, 0.08, 0.10};
    for (; *s; s++, x += 6 * scale) {
        const char *g = glyph(*s);
        if (!g)
            continue;
        for (int r = 0; r < 7; r++)
            for (int q = 0; q < 5; q++)
                if (g[r * 5 + q] == '1')
                    for (int a = 0; a < scale; a++)
                        for (int b = 0; b < scale; b++) {
                            int X = x + q * scale + b, Y = y + r * scale + a;
                            if (X >= 0 && Y >= 0 && X < img->width && Y < img->height)
                                blend(img->rgb + 3 * ((size_t)Y * img->width + X), ink, 1.0);
                        }
    }
}

/* The colour of the bar at t in [0, 1] (0 the low end). */
static void bar_colour(int gauss, double t, double rgb[3])
{
    if (gauss)
        colormap(DIVERGING, 5, t, rgb);
    else
        colormap(RAINBOW, 7, t, rgb);
}

/* A triangle in the end colour past one end of the bar (columns x0 .. x0 + bw - 1): its base
 * 2 rows off the end, its apex 12 rows off (dir -1 above the top, +1 below the bottom), with a
 * dark rim: pixels beyond the range were drawn in the end colour (the robust range clips the
 * top and bottom 2 %). */
static void bar_arrow(rg2_image *img, int x0, int bw, int end, int dir, const double rgb[3])
{
    static const double ink[3] = {0.08, 0.08, 0.10};
    double cx = x0 + 0.5 * (bw - 1);
    for (int r = 0; r <= 10; r++) { /* r = 0: the base row, 10: the apex */
        int y = end + dir * (2 + r);
        double half = 0.5 * (bw - 1) * (10 - r) / 10.0;
        for (int x = x0; x < x0 + bw; x++) {
            double d = fabs(x - cx);
            if (d > half + 0.5)
                continue;
            int rim = r == 0 || d > half - 1.0 || r == 10;
            blend(img->rgb + 3 * ((size_t)y * img->width + x), rim ? ink : rgb, 1.0);
        }
    }
}

static void colour_bar(rg2_image *img, int x0, int gauss, const double range[2], int below, int above)
{
    int H = img->height, top = 40, bot = H - 40, bw = 22; /* bot - top >= 40: BAR_MIN_HEIGHT */
    for (int y = top; y <= bot; y++) {
        double t = (double)(bot - y) / (bot - top), rgb[3];
        bar_colour(gauss, t, rgb);
        for (int x = x0; x < x0 + bw; x++)
            blend(img->rgb + 3 * ((size_t)y * img->width + x), rgb, 1.0);
    }
    double end[3];
    if (above) { /* (the H or K letter sits above, from top - 28 to top - 15) */
        bar_colour(gauss, 1.0, end);
        bar_arrow(img, x0, bw, top, -1, end);
    }
    if (below) {
        bar_colour(gauss, 0.0, end);
        bar_arrow(img, x0, bw, bot, +1, end);
    }
    /* the labels with 3 significant digits, more (up to 11 characters, the width beside the
     * bar) while two neighbours read the same: a narrow range about a large middle (a sphere's
     * constant H, 1e-3 of it wide) was labelled -1 at four of its five ticks */
    char lab[5][32], b[5][32];
    void *loc = rg2__c_numeric_begin(); /* "1.25": under a host's de_DE the bar read "1 25" (no
                                           glyph for the comma), and the picture's bytes differed */
    for (int prec = 3; prec <= 9; prec++) {
        int same = 0, wide = 0;
        for (int q = 0; q <= 4; q++) {
            double val = range[0] + (range[1] - range[0]) * q / 4.0;
            if (fabs(val) < 1e-12 * fmax(fabs(range[0]), fabs(range[1])))
                val = 0;
            snprintf(b[q], sizeof b[q], "%.*g", prec, val);
            wide |= strlen(b[q]) > 11;
            same |= q > 0 && !strcmp(b[q], b[q - 1]);
        }
        if (prec == 3 || !wide)
            memcpy(lab, b, sizeof lab);
        if (!same || wide)
            break;
    }
    rg2__c_numeric_end(loc);
    draw_text(img, x0, top - 28, gauss ? "K" : "H", 2);
    for (int q = 0; q <= 4; q++) {
        const char *buf = lab[q];
        int y = bot - (bot - top) * q / 4;
        static const double ink[3] = {0.08, 0.08, 0.10};
        for (int x = x0 + bw; x < x0 + bw + 4; x++)
            blend(img->rgb + 3 * ((size_t)y * img->width + x), ink, 1.0);
        draw_text(img, x0 + bw + 7, y - 3, buf, 1);
    }
}

/* ---------------------------------------------------------------- the renderer */

static rg2_status check_input(const rg2_surface *surfs, int n, const rg2_mesh *meshes, const rg2_render_opts *o,
                              rg2_error *err)
{
    if (!surfs || n <= 0)
        return rg2__fail(err, RG2_EINVAL, "render: no surfaces (n = %d)", n);
    if (o->width < 16 || o->height < 16 || o->width > 8192 || o->height > 8192)
        return rg2__fail(err, RG2_EINVAL, "render: image size %d x %d outside 16..8192", o->width, o->height);
    if (o->mode < RG2_RENDER_SHADED || o->mode > RG2_RENDER_ZEBRA)
        return rg2__fail(err, RG2_EINVAL, "render: unknown mode %d", (int)o->mode);
    if (!(o->fov > 1.0 && o->fov < 170.0))
        return rg2__fail(err, RG2_EINVAL, "render: field of view %s outside (1, 170) degrees",
                         rg2__num(o->fov).s);
    const double view[3] = {o->azimuth, o->elevation, o->distance};
    static const char *const view_name[3] = {"azimuth", "elevation", "distance"};
    for (int k = 0; k < 3; k++) /* (it named all three: "azimuth, elevation or distance") */
        if (!isfinite(view[k]))
            return rg2__fail(err, RG2_ENONFINITE, "render: %s %s is not a finite number", view_name[k],
                             rg2__num(view[k]).s);
    if (!(o->elevation >= -90.0 && o->elevation <= 90.0))
        return rg2__fail(err, RG2_EINVAL, "render: elevation %s outside [-90, 90] degrees",
                         rg2__num(o->elevation).s);
    if (o->range_set && !(isfinite(o->range[0]) && isfinite(o->range[1]) && o->range[0] < o->range[1]))
        return rg2__fail(err, RG2_EINVAL, "render: colour range %s,%s is not lo < hi", rg2__num(o->range[0]).s,
                         rg2__num(o->range[1]).s);
    if (o->range_set && !isfinite(o->range[1] - o->range[0])) /* -1e308,1e308 painted all one colour */
        return rg2__fail(err, RG2_EINVAL, "render: colour range %g,%g is wider than the largest double", o->range[0],
                         o->range[1]);
    if (!(o->percentile >= 0 && o->percentile < 0.5))
        return rg2__fail(err, RG2_EINVAL, "render: percentile %g outside [0, 0.5)", o->percentile);
    if (o->mode == RG2_RENDER_ZEBRA && !(o->stripes >= 1 && o->stripes <= 1000))
        return rg2__fail(err, RG2_EINVAL, "render: stripes %g outside 1..1000", o->stripes);
    if (o->mesh && !meshes)
        return rg2__fail(err, RG2_EINVAL, "render: control mesh overlay requested without meshes");
    if (o->threads < 0 || o->threads > 1024) /* 100000 overflowed the stack inside OpenMP */
        return rg2__fail(err, RG2_EINVAL, "render: threads %d outside 0..1024 (0: the OpenMP default)", o->threads);
    for (int s = 0; s < n; s++) {
        if (surfs[s].nu <= 0 || surfs[s].nv <= 0 || !surfs[s].patch)
            return rg2__fail(err, RG2_EINVAL, "render: surface %d has no patches", s);
        rg2_status st = rg2__surface_check_finite(&surfs[s], "render", s, err);
        if (!st) /* as the tessellation: h / w can overflow where h and w are finite */
            st = rg2__surface_check_range(&surfs[s], "render", s, err);
        if (st)
            return st;
    }
    return RG2_OK;
}

static void shade_pixels(const rg2_surface *surfs, const camera *c, const rg2_render_opts *o, const rg2_pixel *pix,
                         const double range[2], rg2_image *img, int nt)
{
    int W = img->width, vw = c->vw;
    (void)nt; /* used by the OpenMP pragma only */
    lights L;
    lights_setup(c, &L);
    int N = (int)lround(o->stripes);
    RG2_PARALLEL_FOR
    for (int y = 0; y < img->height; y++)
        for (int x = 0; x < W; x++) {
            unsigned char *out = img->rgb + 3 * ((size_t)y * W + x);
            double bg = 0.97 - 0.12 * (double)y / img->height, rgb[3] = {bg, bg, bg + 0.01};
            const rg2_pixel *p = &pix[(size_t)y * W + x];
            if (x < vw && p->surf >= 0) {
                double diff, spec, base[3];
                lighting(&L, c, p, x, y, &diff, &spec);
                if (o->mode == RG2_RENDER_SHADED) {
                    tint_color(&surfs[p->surf], p->patch, o->tint, base);
                    for (int k = 0; k < 3; k++)
                        rgb[k] = base[k] * (0.16 + 0.80 * diff) + 0.35 * spec;
                } else if (o->mode == RG2_RENDER_ZEBRA) {
                    /* anti-aliased edge: signed distance in pixels = s / |grad s| */
                    double sv = sin(N * p->phase), g = 0;
                    static const int nb[4][2] = {{1, 0}, {-1, 0}, {0, 1}, {0, -1}};
                    for (int q = 0; q < 4; q++) {
                        int X = x + nb[q][0], Y = y + nb[q][1];
                        if (X < 0 || Y < 0 || X >= vw || Y >= img->height)
                            continue;
                        const rg2_pixel *o2 = &pix[(size_t)Y * W + X];
                        if (o2->surf >= 0)
                            g = fmax(g, fabs(sin(N * o2->phase) - sv));
                    }
                    double cov = g > 0 ? clamp01(0.5 + sv / g) : (sv > 0 ? 1 : 0);
                    double lum = (0.06 + 0.90 * cov) * (0.80 + 0.20 * diff);
                    for (int k = 0; k < 3; k++)
                        rgb[k] = lum;
                } else {
                    int gauss = o->mode == RG2_RENDER_GAUSS;
                    double val = gauss ? p->K : p->H, t = (val - range[0]) / (range[1] - range[0]);
                    if (gauss)
                        colormap(DIVERGING, 5, t, base);
                    else
                        colormap(RAINBOW, 7, t, base);
                    for (int k = 0; k < 3; k++)
                        rgb[k] = base[k] * (0.55 + 0.45 * diff) + 0.15 * spec;
                }
            }
            for (int k = 0; k < 3; k++)
                out[k] = (unsigned char)lround(255.0 * clamp01(rgb[k]));
        }
}

/* Patch boundaries (neighbour in another patch at a similar depth) and silhouettes. */
static void edges(const camera *c, const rg2_pixel *pix, int boundaries, rg2_image *img)
{
    int W = img->width;
    static const double dark[3] = {0.10, 0.10, 0.12};
    for (int y = 0; y < img->height; y++)
        for (int x = 0; x < c->vw; x++) {
            const rg2_pixel *p = &pix[(size_t)y * W + x];
            if (p->surf < 0)
                continue;
            double a = 0;
            static const int nb[4][2] = {{1, 0}, {-1, 0}, {0, 1}, {0, -1}};
            for (int q = 0; q < 4; q++) {
                int X = x + nb[q][0], Y = y + nb[q][1];
                if (X < 0 || Y < 0 || X >= c->vw || Y >= img->height)
                    continue;
                const rg2_pixel *o = &pix[(size_t)Y * W + X];
                if (o->surf < 0) {
                    a = fmax(a, 0.35);
                    continue;
                }
                if (boundaries && (o->surf != p->surf || o->patch != p->patch)) {
                    double dp[3] = {o->p[0] - p->p[0], o->p[1] - p->p[1], o->p[2] - p->p[2]};
                    double gap = sqrt(dot3(dp, dp)), lim = 0.02 * c->scale;
                    if (!(gap < lim)) {
                        /* or 3 pixel footprints at its depth: 2% of the scene alone was less
                         * than a pixel's footprint in small pictures, so neighbours across a
                         * seam never qualified (a 64x48 torus_sphere showed 11% of its seam
                         * pixels as boundary, pipe_elbow none) */
                        double rel[3] = {p->p[0] - c->eye[0], p->p[1] - c->eye[1], p->p[2] - c->eye[2]};
                        lim = fmax(lim, BOUNDARY_FOOTPRINTS * dot3(rel, c->f) * 2.0 * c->ty / c->h);
                    }
                    if (gap < lim)
                        a = fmax(a, 0.75);
                }
            }
            if (a > 0)
                blend(img->rgb + 3 * ((size_t)y * W + x), dark, a);
        }
}

/* opts.apart: moved copies of the surfaces (and meshes), laid out in a grid of cells across the
 * view, ceil(sqrt(n)) columns along the camera's right vector and rows along its up vector,
 * surface 0 top left, each centred at the same depth (so perspective draws them alike). Every
 * cell has the size of the largest surface's extent across the view (from the same samples that
 * fit the view) and a gap of a tenth of it; each surface is moved by a translation, so its
 * shape, normals and curvatures are the same. */
/* render_apart's box of one surface's points along three axes (lo, hi each). */
typedef struct {
    const double *axis[3];
    double *b;
} apart_box;

static void box_add(void *ctx, const double *pts, size_t npts)
{
    apart_box *ab = ctx;
    for (int a = 0; a < 3; a++)
        for (size_t k = 0; k < npts; k++) {
            double x = dot3(pts + 3 * k, ab->axis[a]);
            ab->b[2 * a] = fmin(ab->b[2 * a], x), ab->b[2 * a + 1] = fmax(ab->b[2 * a + 1], x);
        }
}

/* the threads a render uses: the options' count, else OpenMP's; at most RENDER_MAX_THREADS, as
 * the grid, the tessellation and the check (a count the process may not start made libgomp abort
 * it; the bytes are the same for any count) */
#define RENDER_MAX_THREADS 64
static int render_threads(const rg2_render_opts *o)
{
#ifdef _OPENMP
    int nt = o->threads > 0 ? o->threads : omp_get_max_threads();
    return nt < RENDER_MAX_THREADS ? nt : RENDER_MAX_THREADS;
#else
    (void)o;
    return 1;
#endif
}

static rg2_status render_apart(const rg2_surface *surfs, int n, const rg2_mesh *meshes, const rg2_render_opts *o,
                               rg2_image *out, rg2_error *err)
{
    double dir[3], f[3], r[3], up[3];
    view_frame(o, dir, f, r, up);
    double *box = rg2__calloc((size_t)n, 6 * sizeof *box); /* lo, hi along r, up, dir */
    rg2_surface *cs = rg2__calloc((size_t)n, sizeof *cs);
    rg2_mesh *cm = o->mesh ? rg2__calloc((size_t)n, sizeof *cm) : NULL;
    rg2_status st = RG2_OK;
    if (!box || !cs || (o->mesh && !cm)) {
        st = rg2__fail(err, RG2_ENOMEM, "render: out of memory for %d surfaces laid apart", n);
        goto done;
    }
    double cw = 0, ch = 0, depth = 0;
    int nt = render_threads(o);
    for (int s = 0; s < n; s++) {
        double *b = box + 6 * s;
        apart_box ab = {{r, up, dir}, b};
        for (int a = 0; a < 3; a++)
            b[2 * a] = DBL_MAX, b[2 * a + 1] = -DBL_MAX;
        if ((st = scene_visit(surfs + s, 1, meshes ? meshes + s : NULL, o->mesh, nt, box_add, &ab, err)))
            goto done;
        cw = fmax(cw, b[1] - b[0]), ch = fmax(ch, b[3] - b[2]), depth += 0.5 * (b[4] + b[5]) / n;
    }
    double cell = fmax(cw, ch) > 0 ? fmax(cw, ch) : 1.0;
    cw = 1.1 * fmax(cw, 1e-3 * cell), ch = 1.1 * fmax(ch, 1e-3 * cell);
    int cols = (int)ceil(sqrt((double)n));
    for (int s = 0; s < n; s++) {
        if ((st = rg2_surface_copy(&surfs[s], &cs[s], err)))
            goto done;
        /* (an empty mesh, all zeros, has nothing to draw: skipped, as without apart, where the
         * copy refused it with "mesh u: scalars: 0 control points, ...") */
        if (o->mesh && meshes[s].nu > 0 && meshes[s].nv > 0 && meshes[s].p &&
            (st = rg2_mesh_copy(&meshes[s], &cm[s], err))) {
            char what[48];
            snprintf(what, sizeof what, "render: meshes[%d]", s);
            rg2__prefix(err, st, what);
            goto done;
        }
        const double *b = box + 6 * s;
        double dx = (s % cols) * cw - 0.5 * (b[0] + b[1]), dy = -(s / cols) * ch - 0.5 * (b[2] + b[3]);
        double dz = depth - 0.5 * (b[4] + b[5]), t[3], M[16];
        for (int k = 0; k < 3; k++)
            t[k] = dx * r[k] + dy * up[k] + dz * dir[k];
        rg2_xform_translate(M, t[0], t[1], t[2]);
        rg2_surface_transform(&cs[s], M);
        if (o->mesh)
            rg2_mesh_transform(&cm[s], M);
    }
    rg2_render_opts oo = *o;
    oo.apart = 0;
    st = rg2_render(cs, n, cm, &oo, out, err);
done:
    for (int s = 0; s < n && cs; s++) {
        rg2_surface_free(&cs[s]);
        if (cm)
            rg2_mesh_free(&cm[s]);
    }
    free(cs);
    free(cm);
    free(box);
    return st;
}

rg2_status rg2_render(const rg2_surface *surfs, int n, const rg2_mesh *meshes, const rg2_render_opts *o,
                      rg2_image *out, rg2_error *err)
{
    rg2_render_opts def;
    if (!o) {
        rg2_render_opts_default(&def);
        o = &def;
    }
    if (!out)
        return rg2__fail(err, RG2_EINVAL, "render: no output image");
    memset(out, 0, sizeof *out);
    rg2_status st = check_input(surfs, n, meshes, o, err);
    if (st)
        return st;
    if (o->apart && n > 1)
        return render_apart(surfs, n, meshes, o, out, err);
    int nt = render_threads(o);
    int W = o->width, H = o->height, curv = o->mode == RG2_RENDER_MEAN || o->mode == RG2_RENDER_GAUSS;
    /* the bar's margin only where colour_bar draws it (a picture under 120 rows kept 110 empty
     * columns on the right) */
    int vw = (curv && o->colorbar && W > 2 * BAR_MARGIN && H >= BAR_MIN_HEIGHT) ? W - BAR_MARGIN : W;
    camera cam;
    if ((st = camera_setup(&cam, o, vw, surfs, n, meshes, nt, err)))
        return st;

    size_t np = (size_t)W * (size_t)H;
    /* on huge pages (src/alloc.c): at 1600 x 1200 these are 260 MB, whose 4 KiB page faults
     * were a fifth of the render's time on the Zen 5 guest */
    zcell *zb = rg2__alloc_big(np, sizeof *zb, (size_t)2 << 20, 0);
    rg2_pixel *pix = rg2__alloc_big(np, sizeof *pix, (size_t)2 << 20, 0);
    out->rgb = rg2__calloc_big(np, 3);
    float *mask = NULL;
    if (!zb || !pix || !out->rgb) {
        st = rg2__fail(err, RG2_ENOMEM, "render: out of memory for a %d x %d image", W, H);
        goto fail;
    }
    out->width = W;
    out->height = H;
    for (size_t k = 0; k < np; k++) {
        zb[k].z = DBL_MAX;
        zb[k].surf = -1;
    }
    if ((st = rasterise(surfs, n, &cam, zb, W, nt, err)))
        goto fail;

    int fg = 0, conv = 0;
    RG2_PARALLEL_FOR
    for (int y = 0; y < H; y++)
        for (int x = 0; x < W; x++) {
            int ok = 0;
            pixel_exact(surfs, &cam, &zb[(size_t)y * W + x], x, y, &pix[(size_t)y * W + x], &ok);
        }
    for (size_t k = 0; k < np; k++)
        if (pix[k].surf >= 0) {
            fg++;
            conv += pix[k].resid <= 1e-12 * cam.scale;
        }
    out->foreground = fg;
    out->refined = conv;
    free(zb);
    zb = NULL;

    if (curv) {
        if (o->range_set) {
            out->range[0] = o->range[0];
            out->range[1] = o->range[1];
        } else if ((st = robust_range(pix, np, o->mode == RG2_RENDER_GAUSS, o->percentile, cam.scale, out->range, err)))
            goto fail;
        for (size_t k = 0; k < np; k++)
            if (pix[k].surf >= 0) {
                double val = o->mode == RG2_RENDER_GAUSS ? pix[k].K : pix[k].H;
                out->below += val < out->range[0];
                out->above += val > out->range[1];
            }
    }
    shade_pixels(surfs, &cam, o, pix, out->range, out, nt);
    edges(&cam, pix, o->boundaries, out);
    if (o->mesh) {
        mask = rg2__calloc(np, sizeof *mask);
        if (!mask) {
            st = rg2__fail(err, RG2_ENOMEM, "render: out of memory for the mesh overlay");
            goto fail;
        }
        mesh_overlay(meshes, n, &cam, out, mask);
        free(mask);
        mask = NULL;
    }
    if (curv && vw < W)
        colour_bar(out, vw + 12, o->mode == RG2_RENDER_GAUSS, out->range, out->below, out->above);
    if (o->keep_pixels)
        out->pixels = pix;
    else
        free(pix);
    rg2__ok(err);
    return RG2_OK;
fail:
    free(zb);
    free(pix);
    free(mask);
    rg2_image_free(out);
    return st;
}

void rg2_image_free(rg2_image *img)
{
    if (!img)
        return;
    free(img->rgb);
    free(img->pixels);
    memset(img, 0, sizeof *img);
}

/* ---------------------------------------------------------------- PNG */

/* libpng's message and the errno of the failing write, kept for our error (libpng's default
 * handlers would print to stderr; the library never prints). */
typedef struct {
    char msg[160];
    int errnum;
} png_fail;

static void png_on_error(png_structp png, png_const_charp msg)
{
    png_fail *pf = png_get_error_ptr(png);
    if (pf) {
        pf->errnum = errno;
        snprintf(pf->msg, sizeof pf->msg, "%s", msg ? msg : "error");
    }
    png_longjmp(png, 1);
}

static void png_on_warning(png_structp png, png_const_charp msg)
{
    (void)png;
    (void)msg; /* warnings change nothing in the written file */
}

rg2_status rg2_image_write_png(const rg2_image *img, const char *path, rg2_error *err)
{
    if (!img || !img->rgb || img->width <= 0 || img->height <= 0)
        return rg2__fail(err, RG2_EINVAL, "png: empty image");
    if (!path || !*path)
        return rg2__fail(err, RG2_EINVAL, "png: no output path");
    rg2__out out;
    rg2_status ost = rg2__out_open(&out, path, err);
    if (ost)
        return ost;
    FILE *f = out.f;
    png_fail pf = {"", 0};
    errno = 0;
    png_structp png = png_create_write_struct(PNG_LIBPNG_VER_STRING, &pf, png_on_error, png_on_warning);
    png_infop info = png ? png_create_info_struct(png) : NULL;
    png_bytep *rows = malloc((size_t)img->height * sizeof *rows);
    volatile int ok = 0;
    const int allocated = png && info && rows;
    if (allocated) {
        if (setjmp(png_jmpbuf(png)) == 0) {
            png_init_io(png, f);
            png_set_IHDR(png, info, (png_uint_32)img->width, (png_uint_32)img->height, 8, PNG_COLOR_TYPE_RGB,
                         PNG_INTERLACE_NONE, PNG_COMPRESSION_TYPE_DEFAULT, PNG_FILTER_TYPE_DEFAULT);
            png_write_info(png, info);
            for (int y = 0; y < img->height; y++)
                rows[y] = img->rgb + (size_t)y * img->width * 3;
            png_write_image(png, rows);
            png_write_end(png, NULL);
            ok = 1;
        }
    }
    png_destroy_write_struct(&png, &info);
    free(rows);
    if (!allocated) {
        rg2__out_discard(&out);
        return rg2__fail(err, RG2_ENOMEM, "png: out of memory");
    }
    if (!ok) {
        rg2__out_discard(&out);
        char why[256];
        if (pf.msg[0] && pf.errnum)
            snprintf(why, sizeof why, "%s (%s)", pf.msg, strerror(pf.errnum));
        else
            snprintf(why, sizeof why, "%s", pf.msg[0] ? pf.msg : pf.errnum ? strerror(pf.errnum) : "unknown error");
        return rg2__fail(err, RG2_EIO, "png: writing '%s' failed: %s", path, why);
    }
    ost = rg2__out_close(&out, RG2_OK, err); /* flushes: a full disk is reported here */
    if (ost == RG2_OK)
        rg2__ok(err);
    return ost;
}

rg2_status rg2_render_png(const rg2_surface *surfs, int n, const rg2_mesh *meshes, const rg2_render_opts *o,
                          const char *path, rg2_error *err)
{
    rg2_image img;
    rg2_status st = rg2_render(surfs, n, meshes, o, &img, err);
    if (st)
        return st;
    st = rg2_image_write_png(&img, path, err);
    rg2_image_free(&img);
    return st;
}
