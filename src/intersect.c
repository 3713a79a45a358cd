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

/* Threads (OpenMP, as rg2_check): the tessellation on the grid's pool, then the weld, the boxes,
 * the grid's lists and the pair tests in parallel loops. The result is the same for any thread
 * count: the weld's sort has a total order and its union-find roots are the least index of each
 * class whatever the order of the unions; the boxes, the cell counts and the mean box are formed
 * serially or as integer sums; each grid list is sorted before its pairs are tested; and the
 * pair tests count into per-thread tallies (integer sums) and keep the least confirmed pair
 * (ta, tb), whose report depends on that pair only. */
#ifdef _OPENMP
#include <omp.h>
#define XS_OMP(x) _Pragma(x)
static int xs_thread(void) { return omp_get_thread_num(); }
#else
#define XS_OMP(x)
static int xs_thread(void) { return 0; }
#endif
#define XS_MAX_THREADS 64 /* as rg2_check */
/* Fewer triangles run on one thread: each parallel loop ends at a barrier that waits for every
 * thread of the team, and when another process holds the second core a thread reaches it only
 * at its next time slice. With threads from the first triangle, every example took 0.13-0.25 s
 * on two threads of this shared 2-core VM against 0.01-0.05 s on one. */
int rg2__crossing_threads_from = 200000; /* (tests lower it to run small inputs on threads) */

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
    int nt;               /* threads */
} mesh_set;

/* The s with base[s] <= x < base[s + 1], s < n (bisection): the surface of a global vertex or
 * triangle. */
static int surface_of(const int *base, int n, int x)
{
    int lo = 0, hi = n - 1;
    while (lo < hi) {
        int mid = lo + (hi - lo) / 2;
        if (x >= base[mid + 1])
            lo = mid + 1;
        else
            hi = mid;
    }
    return lo;
}

static int tri_surface(const mesh_set *M, int t) { return surface_of(M->tbase, M->n, t); }

static const double *vpos(const mesh_set *M, int s, int local) { return M->tess[s].pos + 3 * (size_t)local; }

static double weld_key(const double *p) { return 0.5773502691896258 * p[0] + 0.6180339887498949 * p[1] + 0.5320888862379561 * p[2]; }

typedef struct {
    double key;
    int idx, surf; /* global vertex, its surface */
} keyed;

static int cmp_keyed(const void *a, const void *b)
{
    const keyed *x = a, *y = b;
    return x->key < y->key ? -1 : x->key > y->key ? 1 : (x->idx > y->idx) - (x->idx < y->idx);
}

/* The runs sort_keyed sorts n entries in on nt threads (one: no merge, no second array). */
static int sort_runs(size_t n, int nt) { return n / 8192 + 1 < (size_t)nt ? (int)(n / 8192 + 1) : nt; }

/* Sort k (n entries) by (key, index) on nt threads: runs sorted at once, then merged pairwise
 * into tmp and back. The order is total, so the result is the same array for any nt. Returns
 * the sorted array (k or tmp; tmp may be NULL for one run). */
static keyed *sort_keyed(keyed *k, keyed *tmp, size_t n, int nt)
{
    int runs = sort_runs(n, nt);
    size_t bound[XS_MAX_THREADS + 1];
    for (int c = 0; c <= runs; c++)
        bound[c] = n * (size_t)c / (size_t)runs;
    XS_OMP("omp parallel for num_threads(nt) schedule(static, 1)")
    for (int c = 0; c < runs; c++)
        qsort(k + bound[c], bound[c + 1] - bound[c], sizeof *k, cmp_keyed);
    keyed *src = k, *dst = tmp;
    for (int w = 1; w < runs; w *= 2) {
        XS_OMP("omp parallel for num_threads(nt) schedule(static, 1)")
        for (int c = 0; c < runs; c += 2 * w) {
            size_t i = bound[c], mid = bound[c + w < runs ? c + w : runs];
            size_t j = mid, hi = bound[c + 2 * w < runs ? c + 2 * w : runs], o = i;
            while (i < mid && j < hi)
                dst[o++] = cmp_keyed(&src[j], &src[i]) < 0 ? src[j++] : src[i++];
            while (i < mid)
                dst[o++] = src[i++];
            while (j < hi)
                dst[o++] = src[j++];
        }
        keyed *x = src;
        src = dst;
        dst = x;
    }
    return src;
}

/* Weld coincident vertices of all surfaces (union-find, the smaller index the root: each
 * vertex ends at the least index of its class, whatever the order of the unions). The pairs
 * within the tolerance are found on the threads into lists of their own, then united. */
static int weld(mesh_set *M)
{
    size_t nv = (size_t)M->nvert;
    int merge = sort_runs(nv, M->nt) > 1;
    keyed *k = rg2__alloc_big(nv, sizeof *k, 1u << 21, 0);
    keyed *tmp = merge ? rg2__alloc_big(nv, sizeof *tmp, 1u << 21, 0) : NULL;
    M->weld = rg2__alloc_big(nv, sizeof *M->weld, 1u << 21, 0);
    if (!k || (merge && !tmp) || !M->weld) {
        free(k);
        free(tmp);
        return -1;
    }
    double tol = WELD_TOL * M->size;
    XS_OMP("omp parallel for num_threads(M->nt) schedule(static)")
    for (int g = 0; g < M->nvert; g++) {
        int s = surface_of(M->vbase, M->n, g);
        k[g].key = weld_key(vpos(M, s, g - M->vbase[s]));
        k[g].idx = g;
        k[g].surf = s;
        M->weld[g] = g;
    }
    const keyed *K = sort_keyed(k, tmp, nv, M->nt);
    int *pairs[XS_MAX_THREADS] = {NULL};
    size_t np[XS_MAX_THREADS] = {0};
    int oom = 0;
    XS_OMP("omp parallel num_threads(M->nt)")
    {
        int me = xs_thread(), *L = NULL;
        size_t n = 0, c = 0;
        XS_OMP("omp for schedule(dynamic, 4096)")
        for (int a = 0; a < M->nvert; a++)
            for (int b = a + 1; b < M->nvert && K[b].key - K[a].key <= 2 * tol; b++) {
                int ga = K[a].idx, gb = K[b].idx;
                double d[3];
                sub3(vpos(M, K[a].surf, ga - M->vbase[K[a].surf]), vpos(M, K[b].surf, gb - M->vbase[K[b].surf]), d);
                if (!(dot3(d, d) <= tol * tol))
                    continue;
                if (n == c) {
                    size_t c2 = c ? 2 * c : 64;
                    int *L2 = realloc(L, c2 * 2 * sizeof *L2);
                    if (!L2) {
                        XS_OMP("omp atomic write")
                        oom = 1;
                        break;
                    }
                    L = L2;
                    c = c2;
                }
                L[2 * n] = ga;
                L[2 * n + 1] = gb;
                n++;
            }
        pairs[me] = L;
        np[me] = n;
    }
    for (int t = 0; t < M->nt; t++) {
        for (size_t q = 0; q < np[t] && !oom; q++)
            rg2__uf_union(M->weld, pairs[t][2 * q], pairs[t][2 * q + 1]);
        free(pairs[t]);
    }
    free(k);
    free(tmp);
    if (oom)
        return -1;
    for (int g = 0; g < M->nvert; g++)
        M->weld[g] = rg2__uf_find(M->weld, g);
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
    XS_OMP("omp parallel for num_threads(M->nt) schedule(static)")
    for (int t = 0; t < M->ntri; t++) {
        int s = tri_surface(M, t);
        const int *tv = tri_verts(M, s, t);
        float *b = M->box + 6 * (size_t)t;
        for (int d = 0; d < 3; d++) {
            double lo = DBL_MAX, hi = -DBL_MAX; /* (the vertices are finite: rg2_tessellate) */
            for (int c = 0; c < 3; c++) {
                double x = (vpos(M, s, tv[c])[d] - M->origin[d]) / M->size;
                lo = x < lo ? x : lo;
                hi = x > hi ? x : hi;
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

/* One thread's share of the pair tests: its counts and its least confirmed pair (ta, tb). */
typedef struct {
    double pairs;
    int candidates, crossings, first_a, first_b, oom;
    rg2_crossing_report first; /* that pair's sheets, point, residual, angle */
} sweep_part;

/* Test the pair (ta < tb) met in list `bucket`, if that is where the pair's home cell is hashed:
 * the cell of the lower corner of the intersection of their boxes, which is the componentwise
 * greater of the cells of their lower corners ca, cb (a cell's coordinate is monotonic in the
 * point's, clamping included). */
static void test_pair(const mesh_set *M, const grid *g, int ta, int tb, const int ca[3], const int cb[3],
                      size_t bucket, sweep_part *P)
{
    const float *ba = M->box + 6 * (size_t)ta, *bb = M->box + 6 * (size_t)tb;
    for (int d = 0; d < 3; d++)
        if (ba[3 + d] < bb[d] || bb[3 + d] < ba[d])
            return;
    int home[3] = {ca[0] > cb[0] ? ca[0] : cb[0], ca[1] > cb[1] ? ca[1] : cb[1], ca[2] > cb[2] ? ca[2] : cb[2]};
    if (cell_bucket(g, home) != bucket)
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
    P->candidates++;
    rg2_crossing_report one = {0};
    if (!confirm(M, ta, tb, X, &one))
        return;
    if (P->crossings == 0 || ta < P->first_a || (ta == P->first_a && tb < P->first_b)) {
        P->first_a = ta;
        P->first_b = tb;
        P->first = one;
    }
    P->crossings++;
}

/* The cells (x, y, z) of triangle t's box (clamped to the grid), their count, and each cell's list. */
#define FOR_CELLS(g, b, x, y, z)                                                                                    \
    int c0_[3], c1_[3];                                                                                             \
    cell_range(g, b, c0_, c1_);                                                                                     \
    for (int x = c0_[0]; x <= c1_[0]; x++)                                                                          \
        for (int y = c0_[1]; y <= c1_[1]; y++)                                                                      \
            for (int z = c0_[2]; z <= c1_[2]; z++)

/* Sort a cell's list (short: insertion; the lists are in order already when one thread filled them). */
static void sort_list(int *L, unsigned m)
{
    for (unsigned p = 1; p < m; p++) {
        int x = L[p];
        unsigned q = p;
        for (; q > 0 && L[q - 1] > x; q--)
            L[q] = L[q - 1];
        L[q] = x;
    }
}

/* The pair tests of list c into P (cc: scratch for *cap triangles' cells, grown). */
static void sweep_lists(const mesh_set *M, const grid *g, const unsigned *start, int *list, size_t c, int **cc,
                        size_t *cap, sweep_part *P)
{
    int *L = list + start[c];
    unsigned m = start[c + 1] - start[c];
    if (m < 2)
        return;
    sort_list(L, m);
    if (m > *cap) {
        int *x = realloc(*cc, 3 * (size_t)m * sizeof *x);
        if (!x) {
            P->oom = 1;
            return;
        }
        *cc = x;
        *cap = m;
    }
    int *C = *cc;
    for (unsigned p = 0; p < m; p++) { /* each triangle's lower cell, once per list */
        int c1[3];
        cell_range(g, M->box + 6 * (size_t)L[p], C + 3 * (size_t)p, c1);
    }
    for (unsigned p = 0; p < m; p++)
        for (unsigned q = p + 1; q < m && (p == 0 || L[p] != L[p - 1]); q++)
            if (L[q] != L[q - 1]) { /* a triangle in two cells hashed to this list: once */
                P->pairs++;
                test_pair(M, g, L[p], L[q], C + 3 * (size_t)p, C + 3 * (size_t)q, c, P);
            }
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
    for (int t = 0; t < M->ntri; t++) { /* (serial: the sum ext in one order) */
        const float *b = M->box + 6 * (size_t)t;
        double e = 0;
        for (int d = 0; d < 3; d++) {
            double l = b[d], h = b[3 + d];
            g.lo[d] = l < g.lo[d] ? l : g.lo[d];
            hi[d] = h > hi[d] ? h : hi[d];
            e = h - l > e ? h - l : e;
        }
        ext += e;
    }
    g.h = fmax(ext / M->ntri, 1e-300);
    /* at most about two cells per triangle (else coarser cells, up to 4 mean boxes wide; past
     * that, hashed cells, at most 1e6 along each axis), and at most 8 list entries per triangle
     * (a few huge triangles next to many small ones): else coarser cells */
    double mean = g.h;
    g.hashed = 0;
    size_t entries = 0, cells = 0, most = 8 * (size_t)M->ntri + 64;
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
        XS_OMP("omp parallel for num_threads(M->nt) schedule(static) reduction(+ : entries)")
        for (int t = 0; t < M->ntri; t++) {
            int c0[3], c1[3];
            cell_range(&g, M->box + 6 * (size_t)t, c0, c1);
            size_t e = (size_t)(c1[0] - c0[0] + 1) * (size_t)(c1[1] - c0[1] + 1) * (size_t)(c1[2] - c0[2] + 1);
            entries += e < most ? e : most + 1; /* (no overflow) */
        }
        if (entries <= most)
            break;
        g.h *= 1.26;
    }
    unsigned *start = rg2__calloc(cells + 1, sizeof *start);
    int *list = rg2__alloc_big(entries ? entries : 1, sizeof *list, 1u << 21, 0);
    if (!start || !list) {
        free(start);
        free(list);
        return -1;
    }
    /* count, then fill; the threads' triangles meet in a list in any order (sorted before use) */
    XS_OMP("omp parallel for num_threads(M->nt) schedule(static)")
    for (int t = 0; t < M->ntri; t++) {
        FOR_CELLS(&g, M->box + 6 * (size_t)t, x, y, z) {
            size_t c = cell_bucket(&g, (const int[3]){x, y, z});
            XS_OMP("omp atomic")
            start[c + 1]++;
        }
    }
    for (size_t c = 0; c < cells; c++)
        start[c + 1] += start[c];
    XS_OMP("omp parallel for num_threads(M->nt) schedule(static)")
    for (int t = 0; t < M->ntri; t++) {
        FOR_CELLS(&g, M->box + 6 * (size_t)t, x, y, z) {
            size_t c = cell_bucket(&g, (const int[3]){x, y, z});
            unsigned at;
            XS_OMP("omp atomic capture")
            at = start[c]++;
            list[at] = t;
        }
    }
    for (size_t c = cells; c > 0; c--) /* start[c] moved to the end of cell c: shift back */
        start[c] = start[c - 1];
    start[0] = 0;
    sweep_part part[XS_MAX_THREADS];
    for (int k = 0; k < XS_MAX_THREADS; k++)
        part[k] = (sweep_part){0, 0, 0, -1, -1, 0, {0}};
    XS_OMP("omp parallel num_threads(M->nt)")
    {
        sweep_part P = {0, 0, 0, -1, -1, 0, {0}};
        int *cc = NULL;
        size_t cap = 0;
        XS_OMP("omp for schedule(dynamic, 512)")
        for (size_t c = 0; c < cells; c++)
            sweep_lists(M, &g, start, list, c, &cc, &cap, &P);
        free(cc);
        part[xs_thread()] = P;
    }
    free(start);
    free(list);
    /* the threads' tallies: integer sums (pairs too, exact to 2^53), and the least pair */
    int oom = 0, first_a = -1, first_b = -1;
    for (int k = 0; k < M->nt; k++) {
        const sweep_part *P = &part[k];
        oom |= P->oom;
        r->pairs += P->pairs;
        r->candidates += P->candidates;
        if (P->crossings && (first_a < 0 || P->first_a < first_a || (P->first_a == first_a && P->first_b < first_b))) {
            first_a = P->first_a;
            first_b = P->first_b;
            r->a = P->first.a;
            r->b = P->first.b;
            memcpy(r->p, P->first.p, sizeof r->p);
            r->residual = P->first.residual;
            r->angle = P->first.angle;
        }
        r->crossings += P->crossings;
    }
    return oom ? -1 : 0;
}

/* ------------------------------------------------------------ the call */

rg2_status rg2_find_crossings(const rg2_surface *surfs, int n, int density, int threads, rg2_crossing_report *out,
                              rg2_error *err)
{
    if (!out)
        return rg2__fail(err, RG2_EINVAL, "crossings: no report");
    memset(out, 0, sizeof *out);
    if (!surfs || n <= 0)
        return rg2__fail(err, RG2_EINVAL, "crossings: no surfaces (n = %d)", n);
    if (density < 1 || density > 1000)
        return rg2__fail(err, RG2_EINVAL, "crossings: density %d outside 1..1000", density);
    if (threads < 0)
        return rg2__fail(err, RG2_EINVAL, "crossings: threads %d < 0 (0: the OpenMP default)", threads);
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
    M.nt = 1;
#ifdef _OPENMP
    M.nt = threads > 0 ? threads : omp_get_max_threads();
#endif
    if (M.nt > XS_MAX_THREADS)
        M.nt = XS_MAX_THREADS;
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
        if ((st = rg2__tessellate_threads(&surfs[s], density, M.nt, &M.tess[s], err))) {
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
        if (M.ntri < rg2__crossing_threads_from)
            M.nt = 1;
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
