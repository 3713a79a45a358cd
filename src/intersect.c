/* intersect.c -- transversal crossings of output surfaces, within one and between them
 * (rg2_find_crossings, rg2 check --intersections).
 *
 * METHOD
 *   1. Tessellate every surface at the density (rg2_tessellate: watertight, seams shared, a
 *      pole one vertex) and weld the vertices of all surfaces that coincide to WELD_TOL of the
 *      size (sorted along a generic direction, a window sweep, union-find): surfaces meeting
 *      along an edge, and closures the tessellation did not share, become one mesh there.
 *   2. Broad phase: a uniform grid of cells about one mean triangle box wide (a dense array of
 *      at most 2 x triangles + 64 cells, coarsened up to 4 mean boxes to fit; past that, the
 *      cells hashed into that many lists: see cell_bucket); each triangle is listed in the
 *      cells its box (float, rounded outwards) overlaps; a pair is tested in the list of the
 *      one cell holding the lower corner of the intersection of the two boxes, so every pair
 *      is met once, in a fixed order.
 *   3. Narrow phase: pairs sharing a welded vertex are skipped (neighbours touch by
 *      construction); the others get the plane-interval test of Moeller (1997): each
 *      triangle's crossing segment with the other's plane, as intervals on the line of the two
 *      planes; the pair crosses when the intervals overlap over a positive length (coplanar
 *      or point contact: no crossing).
 *   4. Confirmation on the exact patches: the midpoint of the overlap, in barycentric
 *      coordinates of each triangle, interpolates the vertices' surface parameters
 *      (U = i + u, V = j + v, unwrapped across closing seams; a pole vertex, whose stored
 *      patch is one of its fan, takes its neighbours' U or V). Gauss-Newton on
 *      F = S1(U1, V1) - S2(U2, V2) with the minimum-norm step J^T (J J^T)^-1 (-F), J the 3x4
 *      Jacobian (Su1, Sv1, -Su2, -Sv2), wrapping closed directions and clamping open ones,
 *      at most NEWTON_ITERS steps. Accepted: |F| <= CONFIRM_TOL of the size, the point within
 *      2 triangle-box diagonals of the start, neither point on an open surface border, both
 *      normals defined, angle >= RG2_CROSSING_MIN_ANGLE.
 */
#include "export_internal.h"
#include "xpatch_util.h"

#include <float.h>
#include <stdlib.h>
#include <string.h>

#define WELD_TOL 1e-10     /* relative to the size: vertices closer than this are one */
#define CONFIRM_TOL 1e-10  /* relative to the size: |S1 - S2| of a confirmed crossing */
#define NEWTON_ITERS 40
#define BORDER_TOL 1e-9    /* parametric: a point this close to an open border lies on it */

static double dot3(const double *a, const double *b) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }
static void sub3(const double *a, const double *b, double *c)
{
    c[0] = a[0] - b[0];
    c[1] = a[1] - b[1];
    c[2] = a[2] - b[2];
}
static void cross3(const double *a, const double *b, double *c)
{
    c[0] = a[1] * b[2] - a[2] * b[1];
    c[1] = a[2] * b[0] - a[0] * b[2];
    c[2] = a[0] * b[1] - a[1] * b[0];
}

/* ------------------------------------------------------------ surface parameters */

/* A point of surface s in global parameters (U, V) = (i + u, j + v): closed directions wrap,
 * open ones clamp to [0, nu] x [0, nv]. Writes the patch and local (u, v); returns whether the
 * point lies on an open border (within BORDER_TOL). */
static int locate(const rg2_surface *s, double *U, double *V, int *pi, int *pj, double *u, double *v)
{
    int border = 0;
    double G[2] = {*U, *V};
    int n[2] = {s->nu, s->nv}, closed[2] = {s->closed_u, s->closed_v}, idx[2];
    double loc[2];
    for (int d = 0; d < 2; d++) {
        double g = G[d];
        if (closed[d]) {
            g = fmod(g, (double)n[d]);
            if (g < 0)
                g += n[d];
        } else {
            g = fmin(fmax(g, 0.0), (double)n[d]);
            border |= g <= BORDER_TOL || g >= n[d] - BORDER_TOL;
        }
        int k = (int)floor(g);
        if (k >= n[d])
            k = n[d] - 1;
        if (k < 0)
            k = 0;
        idx[d] = k;
        loc[d] = g - k;
        G[d] = g;
    }
    *U = G[0];
    *V = G[1];
    *pi = idx[0];
    *pj = idx[1];
    *u = loc[0];
    *v = loc[1];
    return border;
}

typedef struct {
    const rg2_surface *s;
    double U, V;
} sheet;

/* Gauss-Newton on S_a(U_a, V_a) = S_b(U_b, V_b). Returns |F| at the end (HUGE_VAL when J J^T
 * became singular or a value was not finite); e_a, e_b hold the last order-1 evaluations. */
static double newton(sheet *a, sheet *b, rg2_eval *ea, rg2_eval *eb)
{
    double fn = HUGE_VAL;
    for (int it = 0; it <= NEWTON_ITERS; it++) {
        int i, j;
        double u, v;
        locate(a->s, &a->U, &a->V, &i, &j, &u, &v);
        rg2_surface_eval(a->s, i, j, u, v, 1, ea);
        locate(b->s, &b->U, &b->V, &i, &j, &u, &v);
        rg2_surface_eval(b->s, i, j, u, v, 1, eb);
        double F[3];
        sub3(ea->p, eb->p, F);
        double f = sqrt(dot3(F, F));
        if (!isfinite(f))
            return HUGE_VAL;
        fn = f;
        if (f == 0 || it == NEWTON_ITERS)
            break;
        const double *J[4] = {ea->su, ea->sv, eb->su, eb->sv};
        double sg[4] = {1, 1, -1, -1}, M[3][3] = {{0}};
        for (int r = 0; r < 3; r++)
            for (int c = 0; c < 3; c++)
                for (int k = 0; k < 4; k++)
                    M[r][c] += J[k][r] * J[k][c];
        double scale = M[0][0] + M[1][1] + M[2][2]; /* M / its trace: no overflow at any size */
        if (!(scale > 0 && isfinite(scale)))
            return HUGE_VAL;
        for (int r = 0; r < 3; r++)
            for (int c = 0; c < 3; c++)
                M[r][c] /= scale;
        double c0[3], c1[3], c2[3];
        cross3(M[1], M[2], c0);
        cross3(M[2], M[0], c1);
        cross3(M[0], M[1], c2);
        double det = dot3(M[0], c0);
        if (!(fabs(det) > 1e-14))
            return HUGE_VAL; /* the four tangents do not span space: tangential contact */
        double y[3]; /* M y = -F (M symmetric: its inverse is the cofactors / det) */
        for (int r = 0; r < 3; r++)
            y[r] = -(c0[r] * F[0] + c1[r] * F[1] + c2[r] * F[2]) / det / scale;
        double step[4], len = 0;
        for (int k = 0; k < 4; k++) {
            step[k] = sg[k] * dot3(J[k], y);
            len = fmax(len, fabs(step[k]));
        }
        double damp = len > 0.5 ? 0.5 / len : 1.0; /* at most half a patch per step */
        a->U += damp * step[0];
        a->V += damp * step[1];
        b->U += damp * step[2];
        b->V += damp * step[3];
        if (len < 1e-15)
            break;
    }
    return fn;
}

/* ------------------------------------------------------------ the meshes */

typedef struct {
    const rg2_surface *surfs;
    int n;
    rg2_tess *tess;
    int *vbase, *tbase;   /* first global vertex / triangle of each surface (n + 1 entries) */
    int nvert, ntri;
    int *weld;            /* global vertex -> its welded representative */
    float *box;           /* 6 per triangle: lo, hi relative to origin / size (rounded outwards: a
                             float holds every size of the supported range so) */
    double size, origin[3];
} mesh_set;

static int tri_surface(const mesh_set *M, int t)
{
    int s = 0;
    while (t >= M->tbase[s + 1])
        s++;
    return s;
}

static const double *vpos(const mesh_set *M, int s, int local) { return M->tess[s].pos + 3 * (size_t)local; }

static double weld_key(const double *p) { return 0.5773502691896258 * p[0] + 0.6180339887498949 * p[1] + 0.5320888862379561 * p[2]; }

typedef struct {
    double key;
    int idx;
} keyed;

static int cmp_keyed(const void *a, const void *b)
{
    const keyed *x = a, *y = b;
    return x->key < y->key ? -1 : x->key > y->key ? 1 : (x->idx > y->idx) - (x->idx < y->idx);
}

/* Weld coincident vertices of all surfaces (union-find, the smaller index the root). */
static int weld(mesh_set *M)
{
    keyed *k = rg2__calloc((size_t)M->nvert, sizeof *k);
    M->weld = rg2__calloc((size_t)M->nvert, sizeof *M->weld);
    if (!k || !M->weld) {
        free(k);
        return -1;
    }
    double tol = WELD_TOL * M->size;
    for (int s = 0; s < M->n; s++)
        for (int v = 0; v < M->tess[s].n_vertices; v++) {
            int g = M->vbase[s] + v;
            k[g].key = weld_key(vpos(M, s, v));
            k[g].idx = g;
            M->weld[g] = g;
        }
    qsort(k, (size_t)M->nvert, sizeof *k, cmp_keyed);
    int *sof = rg2__calloc((size_t)M->nvert, sizeof *sof); /* global vertex -> surface */
    if (!sof) {
        free(k);
        return -1;
    }
    for (int s = 0; s < M->n; s++)
        for (int v = M->vbase[s]; v < M->vbase[s + 1]; v++)
            sof[v] = s;
    for (int a = 0; a < M->nvert; a++)
        for (int b = a + 1; b < M->nvert && k[b].key - k[a].key <= 2 * tol; b++) {
            int ga = k[a].idx, gb = k[b].idx;
            double d[3];
            sub3(vpos(M, sof[ga], ga - M->vbase[sof[ga]]), vpos(M, sof[gb], gb - M->vbase[sof[gb]]), d);
            if (dot3(d, d) <= tol * tol)
                rg2__uf_union(M->weld, ga, gb);
        }
    for (int g = 0; g < M->nvert; g++)
        M->weld[g] = rg2__uf_find(M->weld, g);
    free(sof);
    free(k);
    return 0;
}

static float round_down(double x)
{
    float f = (float)x;
    return (double)f > x ? nextafterf(f, -INFINITY) : f;
}
static float round_up(double x)
{
    float f = (float)x;
    return (double)f < x ? nextafterf(f, INFINITY) : f;
}

static const int *tri_verts(const mesh_set *M, int s, int t) { return M->tess[s].tri + 3 * (size_t)(t - M->tbase[s]); }

static int boxes(mesh_set *M)
{
    M->box = rg2__alloc_big((size_t)M->ntri, 6 * sizeof *M->box, 1u << 21, 0);
    if (!M->box)
        return -1;
    for (int s = 0; s < M->n; s++)
        for (int t = M->tbase[s]; t < M->tbase[s + 1]; t++) {
            const int *tv = tri_verts(M, s, t);
            float *b = M->box + 6 * (size_t)t;
            for (int d = 0; d < 3; d++) {
                double lo = DBL_MAX, hi = -DBL_MAX;
                for (int c = 0; c < 3; c++) {
                    double x = (vpos(M, s, tv[c])[d] - M->origin[d]) / M->size;
                    lo = fmin(lo, x);
                    hi = fmax(hi, x);
                }
                b[d] = round_down(lo - 1e-12); /* (over the rounding of the quotient) */
                b[3 + d] = round_up(hi + 1e-12);
            }
        }
    return 0;
}

/* ------------------------------------------------------------ triangle pairs */

/* The segment where triangle P crosses the plane (n, o): its two ends (the same point when it
 * only touches). Returns 0 when P lies on one side (or in the plane). */
static int plane_cut(const double *const P[3], const double n[3], const double *o, double e[2][3])
{
    double d[3], w[3];
    for (int k = 0; k < 3; k++) {
        sub3(P[k], o, w);
        d[k] = dot3(n, w);
    }
    if ((d[0] > 0 && d[1] > 0 && d[2] > 0) || (d[0] < 0 && d[1] < 0 && d[2] < 0) ||
        (d[0] == 0 && d[1] == 0 && d[2] == 0))
        return 0;
    int m = 0;
    for (int k = 0; k < 3 && m < 2; k++) {
        int l = (k + 1) % 3;
        if (d[k] == 0)
            memcpy(e[m++], P[k], sizeof e[0]);
        if (m < 2 && ((d[k] < 0 && d[l] > 0) || (d[k] > 0 && d[l] < 0))) {
            double t = d[k] / (d[k] - d[l]);
            for (int c = 0; c < 3; c++)
                e[m][c] = P[k][c] + t * (P[l][c] - P[k][c]);
            m++;
        }
    }
    if (m == 1)
        memcpy(e[1], e[0], sizeof e[0]);
    return m > 0;
}

/* Whether triangles A and B cross (the plane-interval test); X: a point of both. */
static int tri_cross(const double *const A[3], const double *const B[3], double X[3])
{
    double ea[3], eb[3], na[3], nb[3], sa[2][3], sb[2][3], L[3];
    sub3(A[1], A[0], ea);
    sub3(A[2], A[0], eb);
    cross3(ea, eb, na);
    sub3(B[1], B[0], ea);
    sub3(B[2], B[0], eb);
    cross3(ea, eb, nb);
    double la = sqrt(dot3(na, na)), lb = sqrt(dot3(nb, nb)); /* unit normals: no underflow at 1e-60 */
    if (!(la > 0 && lb > 0))
        return 0; /* a degenerate triangle */
    for (int c = 0; c < 3; c++) {
        na[c] /= la;
        nb[c] /= lb;
    }
    if (!plane_cut(A, nb, B[0], sa) || !plane_cut(B, na, A[0], sb))
        return 0;
    cross3(na, nb, L);
    if (!(dot3(L, L) > 0))
        return 0;
    double ta[2] = {dot3(L, sa[0]), dot3(L, sa[1])}, tb[2] = {dot3(L, sb[0]), dot3(L, sb[1])};
    double alo = fmin(ta[0], ta[1]), ahi = fmax(ta[0], ta[1]);
    double lo = fmax(alo, fmin(tb[0], tb[1])), hi = fmin(ahi, fmax(tb[0], tb[1]));
    if (!(lo < hi))
        return 0;
    double mid = 0.5 * (lo + hi), f = ta[1] != ta[0] ? (mid - ta[0]) / (ta[1] - ta[0]) : 0.0;
    for (int c = 0; c < 3; c++)
        X[c] = sa[0][c] + f * (sa[1][c] - sa[0][c]);
    return 1;
}

/* The surface parameters (U, V) of the point X of triangle t (barycentric interpolation of its
 * vertices' parameters, unwrapped across closing seams; a vertex of another patch column more
 * than one away from both others (a pole, stored on one patch of its fan) takes their mean). */
static void tri_params(const mesh_set *M, int s, int t, const double X[3], double *U, double *V)
{
    const rg2_surface *S = &M->surfs[s];
    const rg2_tess *T = &M->tess[s];
    const int *tv = tri_verts(M, s, t);
    double G[3][2];
    for (int c = 0; c < 3; c++) {
        int k = T->patch[tv[c]];
        G[c][0] = k / S->nv + T->uv[2 * (size_t)tv[c]];
        G[c][1] = k % S->nv + T->uv[2 * (size_t)tv[c] + 1];
    }
    int n[2] = {S->nu, S->nv}, closed[2] = {S->closed_u, S->closed_v};
    for (int d = 0; d < 2; d++) {
        for (int c = 1; c < 3 && closed[d]; c++) { /* unwrap next to vertex 0 */
            if (G[c][d] - G[0][d] > 0.5 * n[d])
                G[c][d] -= n[d];
            else if (G[0][d] - G[c][d] > 0.5 * n[d])
                G[c][d] += n[d];
        }
        for (int c = 0; c < 3; c++) {
            int p = (c + 1) % 3, q = (c + 2) % 3;
            if (fabs(G[c][d] - G[p][d]) > 1.5 && fabs(G[c][d] - G[q][d]) > 1.5 && fabs(G[p][d] - G[q][d]) <= 1.5) {
                G[c][d] = 0.5 * (G[p][d] + G[q][d]);
                break;
            }
        }
    }
    const double *P0 = vpos(M, s, tv[0]), *P1 = vpos(M, s, tv[1]), *P2 = vpos(M, s, tv[2]);
    double e1[3], e2[3], w[3];
    sub3(P1, P0, e1);
    sub3(P2, P0, e2);
    sub3(X, P0, w);
    double a = dot3(e1, e1), b = dot3(e1, e2), c = dot3(e2, e2), d = dot3(w, e1), e = dot3(w, e2);
    double det = a * c - b * b, l1 = det > 0 ? (c * d - b * e) / det : 1.0 / 3, l2 = det > 0 ? (a * e - b * d) / det : 1.0 / 3;
    l1 = fmin(fmax(l1, 0.0), 1.0);
    l2 = fmin(fmax(l2, 0.0), 1.0 - l1);
    double l0 = 1.0 - l1 - l2;
    *U = l0 * G[0][0] + l1 * G[1][0] + l2 * G[2][0];
    *V = l0 * G[0][1] + l1 * G[1][1] + l2 * G[2][1];
}

static double box_diag(const float *b)
{
    double d2 = 0;
    for (int d = 0; d < 3; d++)
        d2 += ((double)b[3 + d] - b[d]) * ((double)b[3 + d] - b[d]);
    return sqrt(d2);
}

/* Confirm the crossing of triangles ta < tb at X on the exact surfaces; fills the report's
 * first-crossing fields when it holds (and returns 1). */
static int confirm(const mesh_set *M, int ta, int tb, const double X[3], rg2_crossing_report *r)
{
    int s[2] = {tri_surface(M, ta), tri_surface(M, tb)}, t[2] = {ta, tb};
    sheet sh[2];
    for (int k = 0; k < 2; k++) {
        sh[k].s = &M->surfs[s[k]];
        tri_params(M, s[k], t[k], X, &sh[k].U, &sh[k].V);
    }
    rg2_eval e[2];
    double f = newton(&sh[0], &sh[1], &e[0], &e[1]);
    if (!(f <= CONFIRM_TOL * M->size))
        return 0;
    double P[3], d[3];
    for (int c = 0; c < 3; c++)
        P[c] = 0.5 * (e[0].p[c] + e[1].p[c]);
    sub3(P, X, d);
    double reach = 2 * M->size * (box_diag(M->box + 6 * (size_t)ta) + box_diag(M->box + 6 * (size_t)tb));
    if (!(dot3(d, d) <= reach * reach))
        return 0; /* converged onto another sheet pair far away: not this pair's crossing */
    rg2_crossing_sheet cs[2];
    for (int k = 0; k < 2; k++) {
        if (locate(sh[k].s, &sh[k].U, &sh[k].V, &cs[k].pi, &cs[k].pj, &cs[k].u, &cs[k].v))
            return 0; /* on an open border: the sheets touch along an edge */
        if (e[k].flags & RG2_EVAL_NORMAL_UNDEFINED)
            return 0;
        cs[k].surf = s[k];
    }
    double nx[3];
    cross3(e[0].n, e[1].n, nx);
    double angle = atan2(sqrt(dot3(nx, nx)), fabs(dot3(e[0].n, e[1].n)));
    if (!(angle >= RG2_CROSSING_MIN_ANGLE))
        return 0;
    if (r->crossings == 0) {
        r->a = cs[0];
        r->b = cs[1];
        memcpy(r->p, P, sizeof r->p);
        r->residual = f / M->size;
        r->angle = angle;
    }
    return 1;
}

/* ------------------------------------------------------------ the grid */

typedef struct {
    double lo[3], h;
    int dim[3];
    int hashed;     /* 0: one list per cell (x, y, z) in order; 1: cells hashed into lists */
    size_t buckets; /* lists */
} grid;

/* The list of a cell: its own (a dense array of cells, at most 2 x triangles + 64), or, when the
 * dense array would need cells over 4 mean triangle boxes wide to stay within that, the list
 * its coordinates hash to (cells far apart share lists; a pair is tested only in the list of
 * its home cell). Coarsening alone made the cells huge when the surfaces lie far apart in all
 * three directions (two parts at opposite corners of a large box): each part fell into one
 * cell and was tested pair by pair (two 60 x 40 tori 1000 apart: 4.8 s, side by side 0.12 s). */
static size_t cell_bucket(const grid *g, const int c[3])
{
    if (!g->hashed)
        return ((size_t)c[0] * (size_t)g->dim[1] + (size_t)c[1]) * (size_t)g->dim[2] + (size_t)c[2];
    unsigned long long k = (unsigned long long)(unsigned)c[0] * 0x9E3779B97F4A7C15ull ^
                           (unsigned long long)(unsigned)c[1] * 0xC2B2AE3D27D4EB4Full ^
                           (unsigned long long)(unsigned)c[2] * 0x165667B19E3779F9ull;
    k ^= k >> 29;
    return (size_t)(k % g->buckets);
}

static void cell_range(const grid *g, const float *b, int c0[3], int c1[3])
{
    for (int d = 0; d < 3; d++) {
        double a = floor(((double)b[d] - g->lo[d]) / g->h), z = floor(((double)b[3 + d] - g->lo[d]) / g->h);
        c0[d] = a < 0 ? 0 : a >= g->dim[d] ? g->dim[d] - 1 : (int)a;
        c1[d] = z < 0 ? 0 : z >= g->dim[d] ? g->dim[d] - 1 : (int)z;
    }
}

static int shares_vertex(const mesh_set *M, int ta, int tb)
{
    int sa = tri_surface(M, ta), sb = tri_surface(M, tb);
    const int *va = tri_verts(M, sa, ta), *vb = tri_verts(M, sb, tb);
    for (int p = 0; p < 3; p++)
        for (int q = 0; q < 3; q++)
            if (M->weld[M->vbase[sa] + va[p]] == M->weld[M->vbase[sb] + vb[q]])
                return 1;
    return 0;
}

/* Test the pair (ta < tb) met in list `bucket`, if that is where the pair's home cell is hashed. */
static void test_pair(const mesh_set *M, const grid *g, int ta, int tb, size_t bucket, rg2_crossing_report *r,
                      int *first_a, int *first_b)
{
    const float *ba = M->box + 6 * (size_t)ta, *bb = M->box + 6 * (size_t)tb;
    float lo[6];
    for (int d = 0; d < 3; d++) {
        if (ba[3 + d] < bb[d] || bb[3 + d] < ba[d])
            return;
        lo[d] = lo[3 + d] = fmaxf(ba[d], bb[d]);
    }
    int c0[3], c1[3];
    cell_range(g, lo, c0, c1);
    if (cell_bucket(g, c0) != bucket)
        return;
    if (shares_vertex(M, ta, tb))
        return;
    int sa = tri_surface(M, ta), sb = tri_surface(M, tb);
    const int *va = tri_verts(M, sa, ta), *vb = tri_verts(M, sb, tb);
    const double *A[3] = {vpos(M, sa, va[0]), vpos(M, sa, va[1]), vpos(M, sa, va[2])};
    const double *B[3] = {vpos(M, sb, vb[0]), vpos(M, sb, vb[1]), vpos(M, sb, vb[2])};
    double X[3];
    if (!tri_cross(A, B, X))
        return;
    r->candidates++;
    rg2_crossing_report one = {0};
    if (!confirm(M, ta, tb, X, &one))
        return;
    if (r->crossings == 0 || ta < *first_a || (ta == *first_a && tb < *first_b)) {
        *first_a = ta;
        *first_b = tb;
        r->a = one.a;
        r->b = one.b;
        memcpy(r->p, one.p, sizeof r->p);
        r->residual = one.residual;
        r->angle = one.angle;
    }
    r->crossings++;
}

static int cmp_int(const void *a, const void *b)
{
    int x = *(const int *)a, y = *(const int *)b;
    return (x > y) - (x < y);
}

/* Build the grid lists and test every pair once. Returns -1 out of memory. */
static int sweep(const mesh_set *M, rg2_crossing_report *r)
{
    grid g;
    double hi[3], ext = 0;
    for (int d = 0; d < 3; d++) {
        g.lo[d] = DBL_MAX;
        hi[d] = -DBL_MAX;
    }
    for (int t = 0; t < M->ntri; t++) {
        const float *b = M->box + 6 * (size_t)t;
        double e = 0;
        for (int d = 0; d < 3; d++) {
            g.lo[d] = fmin(g.lo[d], b[d]);
            hi[d] = fmax(hi[d], b[3 + d]);
            e = fmax(e, (double)b[3 + d] - b[d]);
        }
        ext += e;
    }
    g.h = fmax(ext / M->ntri, 1e-300);
    /* at most about two cells per triangle (else coarser cells, up to 4 mean boxes wide; past
     * that, hashed cells, at most 1e6 along each axis), and at most 8 list entries per triangle
     * (a few huge triangles next to many small ones): else coarser cells */
    double mean = g.h;
    g.hashed = 0;
    size_t entries = 0, cells = 0;
    unsigned *start = NULL;
    for (;;) {
        double nc = 1, kmax = 0;
        for (int d = 0; d < 3; d++) {
            double k = floor((hi[d] - g.lo[d]) / g.h) + 1;
            g.dim[d] = k > 1e6 ? 1000000 : (int)k;
            nc *= g.dim[d];
            kmax = fmax(kmax, k);
        }
        if (!g.hashed && nc > 2.0 * M->ntri + 64) {
            if (g.h < 4 * mean) {
                g.h *= 1.26;
                continue;
            }
            g.hashed = 1;
        }
        if (g.hashed && kmax > 1e6) {
            g.h *= 1.26;
            continue;
        }
        cells = g.hashed ? 2 * (size_t)M->ntri + 64 : (size_t)nc;
        g.buckets = cells;
        entries = 0;
        for (int t = 0; t < M->ntri && entries <= 8 * (size_t)M->ntri + 64; t++) {
            int c0[3], c1[3];
            cell_range(&g, M->box + 6 * (size_t)t, c0, c1);
            entries += (size_t)(c1[0] - c0[0] + 1) * (size_t)(c1[1] - c0[1] + 1) * (size_t)(c1[2] - c0[2] + 1);
        }
        if (entries <= 8 * (size_t)M->ntri + 64)
            break;
        g.h *= 1.26;
    }
    start = rg2__calloc(cells + 1, sizeof *start);
    int *list = rg2__alloc_big(entries ? entries : 1, sizeof *list, 1u << 21, 0);
    if (!start || !list) {
        free(start);
        free(list);
        return -1;
    }
    for (int pass = 0; pass < 2; pass++) { /* count, then fill (triangles in order in each cell) */
        for (int t = 0; t < M->ntri; t++) {
            int c0[3], c1[3];
            cell_range(&g, M->box + 6 * (size_t)t, c0, c1);
            for (int x = c0[0]; x <= c1[0]; x++)
                for (int y = c0[1]; y <= c1[1]; y++)
                    for (int z = c0[2]; z <= c1[2]; z++) {
                        size_t c = cell_bucket(&g, (const int[3]){x, y, z});
                        if (pass == 0)
                            start[c + 1]++;
                        else
                            list[start[c]++] = t;
                    }
        }
        if (pass == 0)
            for (size_t c = 0; c < cells; c++)
                start[c + 1] += start[c];
        else /* start[c] moved to the end of cell c: shift back */
            for (size_t c = cells; c > 0; c--)
                start[c] = start[c - 1];
        if (pass == 1)
            start[0] = 0;
    }
    int first_a = -1, first_b = -1;
    for (size_t c = 0; c < cells; c++) {
        int *L = list + start[c];
        unsigned m = start[c + 1] - start[c];
        qsort(L, m, sizeof *L, cmp_int); /* (already in order: filled by ascending t) */
        for (unsigned p = 0; p < m; p++)
            for (unsigned q = p + 1; q < m && (p == 0 || L[p] != L[p - 1]); q++)
                if (L[q] != L[q - 1]) { /* a triangle in two cells hashed to this list: once */
                    r->pairs++;
                    test_pair(M, &g, L[p], L[q], c, r, &first_a, &first_b);
                }
    }
    free(start);
    free(list);
    return 0;
}

/* ------------------------------------------------------------ the call */

rg2_status rg2_find_crossings(const rg2_surface *surfs, int n, int density, rg2_crossing_report *out, rg2_error *err)
{
    if (!out)
        return rg2__fail(err, RG2_EINVAL, "crossings: no report");
    memset(out, 0, sizeof *out);
    if (!surfs || n <= 0)
        return rg2__fail(err, RG2_EINVAL, "crossings: no surfaces (n = %d)", n);
    if (density < 1 || density > 1000)
        return rg2__fail(err, RG2_EINVAL, "crossings: density %d outside 1..1000", density);
    double tris = 0;
    for (int s = 0; s < n; s++) {
        if (surfs[s].nu <= 0 || surfs[s].nv <= 0 || !surfs[s].patch)
            return rg2__fail(err, RG2_EINVAL, "crossings: surface %d has no patches", s);
        tris += 2.0 * surfs[s].nu * surfs[s].nv * density * density;
    }
    if (tris > RG2_MAX_CROSSING_TRIANGLES)
        return rg2__fail(err, RG2_ELIMIT, "crossings: %.0f triangles at density %d exceed the limit of %d: a lower "
                         "density", tris, density, RG2_MAX_CROSSING_TRIANGLES);
    mesh_set M = {0};
    M.surfs = surfs;
    M.n = n;
    M.tess = rg2__calloc((size_t)n, sizeof *M.tess);
    M.vbase = rg2__calloc((size_t)n + 1, sizeof *M.vbase);
    M.tbase = rg2__calloc((size_t)n + 1, sizeof *M.tbase);
    rg2_status st = RG2_OK;
    if (!M.tess || !M.vbase || !M.tbase)
        st = rg2__fail(err, RG2_ENOMEM, "crossings: out of memory for %d surfaces", n);
    double lo[3] = {DBL_MAX, DBL_MAX, DBL_MAX}, hi[3] = {-DBL_MAX, -DBL_MAX, -DBL_MAX};
    for (int s = 0; !st && s < n; s++) {
        double l[3], h[3];
        if (rg2__surface_ctrl_box(&surfs[s], 1, l, h))
            for (int d = 0; d < 3; d++) {
                lo[d] = fmin(lo[d], l[d]);
                hi[d] = fmax(hi[d], h[d]);
            }
        if ((st = rg2_tessellate(&surfs[s], density, 0, &M.tess[s], err))) {
            char what[48];
            snprintf(what, sizeof what, "crossings: surface %d", s);
            rg2__prefix(err, st, what);
            break;
        }
        M.vbase[s + 1] = M.vbase[s] + M.tess[s].n_vertices;
        M.tbase[s + 1] = M.tbase[s] + M.tess[s].n_triangles;
    }
    if (!st) {
        double d2 = 0;
        for (int d = 0; d < 3 && lo[0] <= hi[0]; d++)
            d2 += (hi[d] - lo[d]) * (hi[d] - lo[d]);
        M.size = d2 > 0 ? sqrt(d2) : 1.0;
        for (int d = 0; d < 3; d++)
            M.origin[d] = lo[0] <= hi[0] ? lo[d] : 0.0;
        M.nvert = M.vbase[n];
        M.ntri = M.tbase[n];
        out->density = density;
        out->triangles = M.ntri;
        out->size = M.size;
        if (M.ntri > 0 && (weld(&M) || boxes(&M) || sweep(&M, out)))
            st = rg2__fail(err, RG2_ENOMEM, "crossings: out of memory for %d triangles", M.ntri);
    }
    for (int s = 0; M.tess && s < n; s++)
        rg2_tess_free(&M.tess[s]);
    free(M.tess);
    free(M.vbase);
    free(M.tbase);
    free(M.weld);
    free(M.box);
    if (st) {
        memset(out, 0, sizeof *out);
        return st;
    }
    rg2__ok(err);
    return RG2_OK;
}
