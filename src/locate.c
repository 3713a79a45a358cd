/* locate.c -- picking on the exact surface: the surface point closest to a given point, and the
 * first point where a ray meets the surface. Each is searched over the whole surface, not only
 * near a guess, and polished by Newton on the exact patch.
 *
 * METHOD (branch and bound on Bezier subdivision)
 *   A rational Bezier patch whose weights are all positive lies in the convex hull of its affine
 *   control points, and so does every piece of it that de Casteljau subdivision cuts out. A box
 *   around those points therefore bounds what the piece can hold:
 *   - closest point: the distance from x to the piece's box along its own frame (its corner
 *     differences; its thickness along the normal shrinks like the square of its size) is a
 *     lower bound of the distance from x to the piece; where that does not rule the piece out,
 *     the Bernstein form of the squared distance gives another (bern_bound), which closes in
 *     on the distance with the distance's own second derivative: far from the surface, where
 *     the distance changes slowly along it, much faster than the box (39 % fewer pieces);
 *   - ray o + t d: the piece can meet the ray only where its box in the ray's frame (two axes
 *     across the ray) holds the ray, not before the smallest t of its control points, and only
 *     inside the slab of its own frame along its normal (thin: where the ray crosses it
 *     obliquely it bounds t closely).
 *   Above the patches, a tree of boxes over the patch grid (each node halves its longer index
 *   range) leads the search down to the patches near the query: the heap holds tree nodes
 *   (keyed by their box's bound) as well as pieces. A node also holds a slab: the range of its
 *   control points along a direction near its patches' normal (a leaf's own frame normal, an
 *   inner node's the sum of its children's), thin where its patches are nearly flat, so that a
 *   nearest-point search rules out the patches beside the answer, whose axis-aligned boxes
 *   reach out towards the query (a torus of 200 x 200 patches: 24 whole patches taken a
 *   query instead of 42, 113 nodes instead of 167); a ray must cross it as well.
 *   Around a nearest point found, a certificate rules a whole rectangle of its patch out at once
 *   (half-size 1/2 in the patch's parameters, else 1/8, else 1/32; on the patch and on the
 *   neighbours whose side or corner the point lies on): the numerator g = N - c W of
 *   |S - x|^2 - c (c the best squared distance) shown convex there by the Bernstein coefficients
 *   of its second derivatives lies above its tangent plane at the point, so no point of the
 *   rectangle is nearer than the plane says (cert_make). A ray's hit has its own: the ray's two
 *   residuals across it, shown one-to-one on the rectangle by the Bernstein ranges of their
 *   derivatives (every determinant away from 0), vanish nowhere there but within a small
 *   rectangle Q around the hit, whose box bounds t (ray_cert_make). Without them, the pieces
 *   around the answer are cut down to the tolerance, one or two a level (13 levels on the
 *   benchmark's torus: a nearest point took 26 patch pieces, now 5; a ray 14.5, now 2.6).
 *   Pieces wait in a heap ordered by that bound. The smallest is taken, its centre is evaluated
 *   and, if that improves on the best so far, Newton runs from there on the whole patch
 *   (closest: the Newton step of |S - x|^2 kept in the square, a side where the distance falls
 *   outward holding its parameter, halved until the distance drops, and carried into the
 *   neighbouring patch when it ends on a shared side; ray: the two residuals across the ray, as
 *   the renderer does per pixel); then the piece is split in four and the quarters whose
 *   bounds can still beat the best by more than the tolerance go back in the heap. A frame
 *   box's distance is divided by sqrt(1 + 3 g), g the frame's departure from orthonormal (a
 *   piece with nearly parallel sides). The search ends when the heap's smallest bound is within the tolerance of the best.
 *   What stays certain is reported: bound, a distance (a ray parameter) below which no point
 *   of the surface lies (meets the ray); normally within the tolerance of the answer.
 *   Tolerance: 1e-10 of (the surface's box diagonal + the query point's distance from the box
 *   centre). Pieces smaller than it are not split again (a ray's keeps its centre as a hit in
 *   case Newton finds none; their bound counts in the proven one), and a
 *   query stops after RG2_LOCATE_MAX_PIECES pieces (a point equidistant from a whole region,
 *   such as a sphere's centre, or a ray along a surface line): the bound then says how far the
 *   answer is proven.
 *   Memory: the heap keeps a piece as its patch and parameter rectangle; its control net is cut
 *   again from the patch when it is taken (two de Casteljau steps per direction).
 */
#include "internal.h"
#include "xpatch_util.h"

#include <float.h>
#include <stdlib.h>

/* A tree of boxes over the patch grid: a node covers the patches (i, j), i0 <= i < i1,
 * j0 <= j < j1, and halves its longer index range for its two children (kid, kid + 1); a leaf
 * (kid = -1) is one patch, its box that of the patch's affine control points. */
typedef struct {
    double lo[3], hi[3];
    double n[3], a, b; /* a slab: a <= n . P <= b for every control point P of its patches (n
                          unit, or 0 with a = -INFINITY, b = INFINITY where it has none) */
    int i0, i1, j0, j1, kid;
} node;

long rg2__locate_max_pieces = RG2_LOCATE_MAX_PIECES; /* (the fuzz harness lowers it) */

struct rg2_locator {
    const rg2_surface *s;
    size_t n;    /* patches */
    node *tree;  /* 2 n - 1 nodes, tree[0] the root */
    double centre[3], diag;
};

typedef struct {
    double key; /* lower bound: a distance (closest) or a ray parameter (ray) */
    int node;   /* a tree node, or -1: a piece of patch `patch` */
    int patch;
    double u0, u1, v0, v1;
    int known;        /* t1 (ray) and size were found when the piece was made */
    double t1, size;  /* ray: the largest t where the piece can meet the ray, and its size across
                         it; closest: the diagonal of its box */
} piece;

typedef struct {
    piece *a;
    size_t n, cap;
    int nomem;
} heap;

static void heap_push(heap *h, const piece *p)
{
    if (h->n == h->cap) {
        size_t cap = h->cap ? 2 * h->cap : 256;
        piece *a = realloc(h->a, cap * sizeof *a);
        if (!a) {
            h->nomem = 1;
            return;
        }
        h->a = a;
        h->cap = cap;
    }
    size_t k = h->n++;
    while (k > 0 && h->a[(k - 1) / 2].key > p->key) {
        h->a[k] = h->a[(k - 1) / 2];
        k = (k - 1) / 2;
    }
    h->a[k] = *p;
}

static piece heap_pop(heap *h)
{
    piece top = h->a[0], last = h->a[--h->n];
    size_t k = 0;
    for (;;) {
        size_t c = 2 * k + 1;
        if (c >= h->n)
            break;
        if (c + 1 < h->n && h->a[c + 1].key < h->a[c].key)
            c++;
        if (!(h->a[c].key < last.key))
            break;
        h->a[k] = h->a[c];
        k = c;
    }
    if (h->n)
        h->a[k] = last;
    return top;
}

static double dot3(const double *a, const double *b) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }

static int unit3(double *a)
{
    double l = sqrt(dot3(a, a));
    int ok = l > 0 && isfinite(l);
    double inv = 1.0 / (ok ? l : 1.0); /* (a divisor that cannot trap, even where a compiler
                                          computes the division ahead of the test) */
    if (!ok)
        return 0;
    for (int k = 0; k < 3; k++)
        a[k] *= inv;
    return 1;
}

static void cross3(const double *a, const double *b, double *c)
{
    c[0] = a[1] * b[2] - a[2] * b[1];
    c[1] = a[2] * b[0] - a[0] * b[2];
    c[2] = a[0] * b[1] - a[1] * b[0];
}

/* ---------------------------------------------------------------- control nets of pieces */

/* The Bezier points of the part [a, 1] (right = 1) or [0, a] (right = 0) of a curve of degree d
 * whose d + 1 homogeneous points are c[0], c[st], c[2 st], ... (in place; de Casteljau). */
static void cut(double *c, int d, size_t st, double a, int right)
{
    for (int l = 1; l <= d; l++) {
        if (right)
            for (int r = 0; r <= d - l; r++)
                for (int k = 0; k < 4; k++)
                    c[r * st + k] = (1 - a) * c[r * st + k] + a * c[(r + 1) * st + k];
        else
            for (int r = d; r >= l; r--)
                for (int k = 0; k < 4; k++)
                    c[r * st + k] = (1 - a) * c[(r - 1) * st + k] + a * c[r * st + k];
    }
}

/* Restrict a curve to [a, b] of its parameter. */
static void cut_range(double *c, int d, size_t st, double a, double b)
{
    if (a > 0) {
        cut(c, d, st, a, 1);
        b = (b - a) / (1 - a);
    }
    if (b < 1)
        cut(c, d, st, b, 0);
}

/* The control net of piece p: patch p->patch restricted to its rectangle. */
static void piece_net(const rg2_locator *L, const piece *p, rg2_xpatch *X)
{
    rg2_surface_patch_get(L->s, p->patch / L->s->nv, p->patch % L->s->nv, X);
    size_t row = (RG2_MAX_DEGREE + 1) * 4;
    if (p->u0 > 0 || p->u1 < 1)
        for (int t = 0; t <= X->dv; t++)
            cut_range(&X->h[0][t][0], X->du, row, p->u0, p->u1);
    if (p->v0 > 0 || p->v1 < 1)
        for (int r = 0; r <= X->du; r++)
            cut_range(&X->h[r][0][0], X->dv, 4, p->v0, p->v1);
}

/* Both halves of a curve of degree d (points a[0], a[st], ...; de Casteljau at 1/2): the first
 * half stays in a, the second goes to b (the same layout). */
static void halve(double *a, double *b, int d, size_t st)
{
    double t[RG2_MAX_DEGREE + 1][4];
    for (int r = 0; r <= d; r++)
        memcpy(t[r], a + r * st, sizeof t[r]);
    memcpy(b + d * st, t[d], sizeof t[d]);
    for (int l = 1; l <= d; l++) {
        for (int r = 0; r <= d - l; r++)
            for (int k = 0; k < 4; k++)
                t[r][k] = 0.5 * (t[r][k] + t[r + 1][k]);
        memcpy(a + l * st, t[0], sizeof t[0]);
        memcpy(b + (d - l) * st, t[d - l], sizeof t[0]);
    }
}

/* The four quarters of a net (split at the middle of both parameters); q[0] = [lo u, lo v],
 * q[1] = [hi u, lo v], q[2] = [lo u, hi v], q[3] = [hi u, hi v]. Only the entries of the net's
 * degrees are written. */
static void quarters(const rg2_xpatch *X, rg2_xpatch q[4])
{
    size_t row = (RG2_MAX_DEGREE + 1) * 4;
    for (int c = 0; c < 4; c++)
        q[c].du = X->du, q[c].dv = X->dv;
    for (int r = 0; r <= X->du; r++)
        memcpy(q[0].h[r], X->h[r], (size_t)(X->dv + 1) * sizeof X->h[r][0]);
    for (int t = 0; t <= X->dv; t++)
        halve(&q[0].h[0][t][0], &q[1].h[0][t][0], X->du, row);
    for (int h = 0; h < 2; h++)
        for (int r = 0; r <= X->du; r++)
            halve(&q[h].h[r][0][0], &q[h + 2].h[r][0][0], X->dv, 4);
}

/* The affine control points of a net, and its corners. */
typedef struct {
    int n;
    double p[(RG2_MAX_DEGREE + 1) * (RG2_MAX_DEGREE + 1)][3];
    const double *c00, *c10, *c01, *c11;
} points;

static void net_points_at(const double *net, int du, int dv, int st, points *P)
{
    P->n = 0;
    for (int r = 0; r <= du; r++)
        for (int t = 0; t <= dv; t++) {
            const double *h = net + 4 * (r * st + t);
            double w = 1.0 / h[3];
            for (int k = 0; k < 3; k++)
                P->p[P->n][k] = h[k] * w;
            P->n++;
        }
    P->c00 = P->p[0];
    P->c01 = P->p[dv];
    P->c10 = P->p[du * (dv + 1)];
    P->c11 = P->p[P->n - 1];
}

static void net_points(const rg2_xpatch *X, points *P)
{
    net_points_at(&X->h[0][0][0], X->du, X->dv, RG2_MAX_DEGREE + 1, P);
}

static double lesser(double a, double b) { return a < b ? a : b; }
static double greater(double a, double b) { return a > b ? a : b; }

/* Box of the points relative to o along the orthonormal axes e[0..2] (the coordinate axes
 * when e is NULL): lo[k], hi[k] of e[k] . (P - o). Returns the largest |P - o| (1-norm). */
static double pts_box(const points *P, const double o[3], const double (*e)[3], double lo[3], double hi[3])
{
    double mag = 0;
    for (int k = 0; k < 3; k++)
        lo[k] = INFINITY, hi[k] = -INFINITY;
    for (int q = 0; q < P->n; q++) {
        double d[3] = {P->p[q][0] - o[0], P->p[q][1] - o[1], P->p[q][2] - o[2]};
        mag = greater(mag, fabs(d[0]) + fabs(d[1]) + fabs(d[2]));
        for (int k = 0; k < 3; k++) {
            double c = e ? dot3(e[k], d) : d[k];
            lo[k] = lesser(lo[k], c);
            hi[k] = greater(hi[k], c);
        }
    }
    return mag;
}

static double box_dist(const double lo[3], const double hi[3], const double c[3])
{
    double e = 0;
    for (int k = 0; k < 3; k++) {
        double g = greater(0.0, greater(lo[k] - c[k], c[k] - hi[k]));
        e += g * g;
    }
    return sqrt(e);
}

static double box_diag(const double lo[3], const double hi[3])
{
    return sqrt((hi[0] - lo[0]) * (hi[0] - lo[0]) + (hi[1] - lo[1]) * (hi[1] - lo[1]) +
                (hi[2] - lo[2]) * (hi[2] - lo[2]));
}

/* The piece's own frame: e[0] along its u sides, e[1] along its v sides (made orthogonal),
 * e[2] = e[0] x e[1], near its normal. 0 where a side pair has no direction (a pole). */
static int piece_frame(const points *P, double e[3][3])
{
    for (int k = 0; k < 3; k++) {
        e[0][k] = P->c10[k] - P->c00[k] + P->c11[k] - P->c01[k];
        e[1][k] = P->c01[k] - P->c00[k] + P->c11[k] - P->c10[k];
    }
    if (!unit3(e[0]))
        return 0;
    double s = dot3(e[1], e[0]);
    for (int k = 0; k < 3; k++)
        e[1][k] -= s * e[0][k];
    if (!unit3(e[1]))
        return 0;
    cross3(e[0], e[1], e[2]);
    return 1;
}

/* Lower bound of the distance from x to the piece of points P: from its box along its own frame
 * (along the axes where it has none, at a pole); *size gets the box's diagonal. */
static double closest_bound(const points *P, const double x[3], double *size)
{
    static const double zero[3] = {0, 0, 0};
    double lo[3], hi[3], e[3][3];
    if (piece_frame(P, e)) {
        /* a distance measured along e is a lower bound only as far as e is orthonormal: for a
         * Gram matrix within g of the identity, |E y| <= sqrt(1 + 3 g) |y| (a piece with nearly
         * parallel sides leaves its frame's rounding far above the last bit) */
        double g = 0;
        for (int a = 0; a < 3; a++)
            for (int b = a; b < 3; b++)
                g = greater(g, fabs(dot3(e[a], e[b]) - (a == b)));
        if (g < 1e-3) {
            pts_box(P, x, (const double(*)[3])e, lo, hi);
            *size = box_diag(lo, hi);
            return box_dist(lo, hi, zero) / sqrt(1 + 3 * g + 4 * DBL_EPSILON);
        }
    }
    pts_box(P, zero, NULL, lo, hi);
    *size = box_diag(lo, hi);
    return box_dist(lo, hi, x);
}

enum { M2 = 2 * RG2_MAX_DEGREE + 1 }; /* (the squared distance's coefficients per direction) */

static const double binom[M2][M2] = {
    {1}, {1, 1}, {1, 2, 1}, {1, 3, 3, 1}, {1, 4, 6, 4, 1}, {1, 5, 10, 10, 5, 1}, {1, 6, 15, 20, 15, 6, 1},
    {1, 7, 21, 35, 35, 21, 7, 1}, {1, 8, 28, 56, 70, 56, 28, 8, 1}, {1, 9, 36, 84, 126, 126, 84, 36, 9, 1},
    {1, 10, 45, 120, 210, 252, 210, 120, 45, 10, 1}};

/* N and W of a net (the weights > 0) in the Bernstein basis of degree (2 du, 2 dv), each
 * coefficient times its binomials C(2 du, k) C(2 dv, l). */
static void sq_dist_form(const rg2_xpatch *X, const double x[3], double N[M2][M2], double W[M2][M2])
{
    int du = X->du, dv = X->dv;
    double q[RG2_MAX_DEGREE + 1][RG2_MAX_DEGREE + 1][4];
    for (int r = 0; r <= du; r++)
        for (int t = 0; t <= dv; t++) {
            double w = X->h[r][t][3], f = binom[du][r] * binom[dv][t];
            for (int k = 0; k < 3; k++)
                q[r][t][k] = f * (X->h[r][t][k] - x[k] * w);
            q[r][t][3] = f * w;
        }
    for (int k = 0; k <= 2 * du; k++)
        for (int l = 0; l <= 2 * dv; l++)
            N[k][l] = W[k][l] = 0;
    for (int r = 0; r <= du; r++)
        for (int t = 0; t <= dv; t++)
            for (int r2 = 0; r2 <= du; r2++)
                for (int t2 = 0; t2 <= dv; t2++) {
                    const double *a = q[r][t], *b = q[r2][t2];
                    N[r + r2][t + t2] += a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
                    W[r + r2][t + t2] += a[3] * b[3];
                }
}

/* Lower bound of the distance from x to a piece from the Bernstein form of its squared distance:
 * |S - x|^2 = N / W with N = |H - x w|^2 and W = w^2 (H the homogeneous xyz, w the weight), both
 * of degree (2 du, 2 dv); where every coefficient of W is positive, N / W lies between the
 * smallest and largest of the coefficient ratios N_kl / W_kl (a weighted mean of them). Near a
 * nearest point the ratios close in on the distance with the distance's own second derivative,
 * which is small where the distance changes slowly along the surface (a point far from it). */
static double bern_bound(const rg2_xpatch *X, const double x[3])
{
    double N[M2][M2], W[M2][M2];
    sq_dist_form(X, x, N, W);
    double lb = INFINITY;
    for (int k = 0; k <= 2 * X->du; k++)
        for (int l = 0; l <= 2 * X->dv; l++) { /* (the binomials of degree 2d cancel in the ratio) */
            double q = N[k][l] / W[k][l];
            /* (no bound where N is past the largest double, at coordinates near 1e150 with large
             * weights, or where its products fall below the normal doubles and lose their digits,
             * at distances near 1e-155) */
            if (!(q < INFINITY) || N[k][l] < 0x1p-900)
                return 0.0;
            lb = lesser(lb, q);
        }
    return lb > 0 ? sqrt(lb) : 0.0;
}

/* ---------------------------------------------------------------- convexity certificates */

/* Around a nearest point found, the subdivision alone would prove it only by cutting pieces
 * down to the tolerance (two pieces a level, 13 levels at 1e-10). A certificate rules out a
 * whole rectangle R of one patch at once. With c = best^2, g = N - c W (the numerator of
 * |S - x|^2 - c, a polynomial of degree (2 du, 2 dv) in R's own parameters (s, t)) is convex on
 * R where its Hessian is positive semidefinite everywhere there, which the Bernstein
 * coefficients of its second derivatives show: g_ss >= A > 0, g_tt >= C > 0 and
 * |g_st| <= B with A C >= B^2. Then on R, g(y) >= g(y0) + grad g(y0) . (y - y0) for the point
 * y0 of R nearest the foot, so |S - x|^2 >= c + min(0, that) / min W over any piece inside R:
 * near c, and the piece is ruled out. Every coefficient carries a bound of its rounding (the
 * net's cut, x subtracted, the products and sums), which the tests of A, B, C and the linear
 * bound take off. */
typedef struct {
    int patch, ray;        /* ray: a ray's certificate (ray_cert_make) */
    double u0, u1, v0, v1; /* R */
    double sf, tf;         /* the base point y0 in R's own parameters */
    double g0, gs, gt;     /* g(y0) less its error; its gradient (in s, t) */
    double es, et;         /* the gradient's error bounds */
    double c, wmin;        /* c; the smallest Bernstein coefficient of W, less its error */
    double q0, q1, r0, r1; /* ray: the only part of R where the ray can meet the patch, Q */
    double tq;             /* ray: the smallest t where the ray can meet Q (INFINITY: nowhere) */
} cert;

/* What a certificate is made for: the point x and the squared distance c (closest), or the ray
 * o + t d with its frame e (ray). */
typedef struct {
    int ray;
    const double *x, *o, *d;
    double c;
    const double (*e)[3];
} query;

/* p(s, t) of Bernstein coefficients b[k][l], 0 <= k <= n, 0 <= l <= m (de Casteljau). */
static double bern2(double b[][M2], int n, int m, double s, double t)
{
    double row[M2];
    for (int k = 0; k <= n; k++) {
        double a[M2];
        memcpy(a, b[k], (size_t)(m + 1) * sizeof a[0]);
        for (int l = 1; l <= m; l++)
            for (int q = 0; q <= m - l; q++)
                a[q] = (1 - t) * a[q] + t * a[q + 1];
        row[k] = a[0];
    }
    for (int l = 1; l <= n; l++)
        for (int q = 0; q <= n - l; q++)
            row[q] = (1 - s) * row[q] + s * row[q + 1];
    return row[0];
}

/* The largest |h|_1 and weight of patch `patch`'s own control points: the cut of a rectangle's
 * net rounds relative to these, which can be far larger than the cut net's points where the
 * patch's control points cancel. */
static void net_size(const rg2_locator *L, int patch, double *hmax, double *wmax)
{
    rg2_xpatch X;
    rg2_surface_patch_get(L->s, patch / L->s->nv, patch % L->s->nv, &X);
    *hmax = *wmax = 0;
    for (int a = 0; a <= X.du; a++)
        for (int b = 0; b <= X.dv; b++) {
            const double *h = X.h[a][b];
            *hmax = greater(*hmax, fabs(h[0]) + fabs(h[1]) + fabs(h[2]));
            *wmax = greater(*wmax, h[3]);
        }
}

/* A certificate's rectangle R = [uf - r, uf + r] x [vf - r, vf + r] within patch `patch`: into
 * C (patch, R), its net into X, and the base (uf, vf) in R's own parameters into *sf, *tf. */
static void cert_rect(const rg2_locator *L, int patch, double uf, double vf, double r, cert *C, rg2_xpatch *X,
                      double *sf, double *tf)
{
    piece p = {0, -1, patch, fmax(0.0, uf - r), fmin(1.0, uf + r), fmax(0.0, vf - r), fmin(1.0, vf + r), 0, 0, 0};
    piece_net(L, &p, X); /* (r > 0 and uf, vf in [0, 1]: R is not empty) */
    C->patch = patch;
    C->u0 = p.u0, C->u1 = p.u1, C->v0 = p.v0, C->v1 = p.v1;
    *sf = fmin(1.0, fmax(0.0, (uf - p.u0) / (p.u1 - p.u0)));
    *tf = fmin(1.0, fmax(0.0, (vf - p.v0) / (p.v1 - p.v0)));
}

/* A certificate over R = [uf - r, uf + r] x [vf - r, vf + r] (within the patch) based at the
 * foot (uf, vf), for the point qy->x and the squared distance qy->c; 0 where g is not shown
 * convex on R. */
static int cert_make(const rg2_locator *L, int patch, double uf, double vf, double r, const query *qy, cert *C)
{
    const double *x = qy->x;
    double c = qy->c, sf, tf;
    rg2_xpatch X;
    cert_rect(L, patch, uf, vf, r, C, &X, &sf, &tf);
    int du = X.du, dv = X.dv, n = 2 * du, m = 2 * dv;
    double G[M2][M2], W[M2][M2];
    double amax = 0, pmax = 0, xm = fabs(x[0]) + fabs(x[1]) + fabs(x[2]), hmax, wmax, wcut = INFINITY;
    net_size(L, patch, &hmax, &wmax);
    for (int a = 0; a <= du; a++)
        for (int b = 0; b <= dv; b++) {
            double w = X.h[a][b][3], pa = 0, da = 0;
            if (!(w > 0))
                return 0;
            for (int k = 0; k < 3; k++) {
                pa += fabs(X.h[a][b][k]) / w;
                da += fabs(X.h[a][b][k] / w - x[k]);
            }
            pmax = greater(pmax, pa), amax = greater(amax, da), wcut = lesser(wcut, w);
        }
    pmax = greater(pmax, hmax / wcut); /* (the cut's rounding, in the cut net's units) */
    sq_dist_form(&X, x, G, W); /* (N, then G = N - c W below) */
    /* the rounding, per unit of W's coefficient: a control point's offset from x is off by
     * up to d (the cut of the net and the subtraction; relative to the coordinates' size), and
     * N's products and sums by 32 eps of their size */
    double d = 64 * DBL_EPSILON * (pmax + xm), rel = 2 * (2 * amax * d + d * d + 32 * DBL_EPSILON * (amax * amax + c));
    double wmin = INFINITY, emax = 0, gmax = 0;
    for (int k = 0; k <= n; k++)
        for (int l = 0; l <= m; l++) {
            double f = binom[n][k] * binom[m][l];
            W[k][l] /= f;
            G[k][l] = G[k][l] / f - c * W[k][l];
            wmin = lesser(wmin, W[k][l]);
            emax = greater(emax, rel * W[k][l]);
            gmax = greater(gmax, fabs(G[k][l]));
        }
    wmin *= 1 - 64 * DBL_EPSILON;
    emax += 1e-290; /* (rounding below the normal range is absolute: such a tiny g is not certified) */
    if (!(wmin > 0) || !(gmax < 1e290) || !(emax < 1e290))
        return 0;
    double slack = 8 * emax + 16 * DBL_EPSILON * gmax; /* of a second difference */
    double ass = INFINITY, att = INFINITY, bst = 0;
    for (int k = 0; k <= n; k++)
        for (int l = 0; l <= m; l++) {
            if (k + 2 <= n)
                ass = lesser(ass, G[k + 2][l] - 2 * G[k + 1][l] + G[k][l]);
            if (l + 2 <= m)
                att = lesser(att, G[k][l + 2] - 2 * G[k][l + 1] + G[k][l]);
            if (k < n && l < m)
                bst = greater(bst, fabs(G[k + 1][l + 1] - G[k + 1][l] - G[k][l + 1] + G[k][l]));
        }
    double A = n * (n - 1) * (ass - slack), Cc = m * (m - 1) * (att - slack), B = n * m * (bst + slack);
    if (!(A > 0 && Cc > 0 && A * Cc > B * B * (1 + 1e-12)) || !isfinite(A * Cc))
        return 0;
    /* g and its gradient at the foot (its differences' Bernstein forms) */
    double Ds[M2][M2], Dt[M2][M2];
    for (int k = 0; k <= n; k++)
        for (int l = 0; l <= m; l++) {
            if (k < n)
                Ds[k][l] = G[k + 1][l] - G[k][l];
            if (l < m)
                Dt[k][l] = G[k][l + 1] - G[k][l];
        }
    C->ray = 0;
    C->sf = sf, C->tf = tf;
    double ev = (n + m + 2) * 4 * DBL_EPSILON * gmax; /* a de Casteljau evaluation's rounding */
    C->g0 = bern2(G, n, m, C->sf, C->tf) - (emax + ev);
    C->gs = n * bern2(Ds, n - 1, m, C->sf, C->tf);
    C->gt = m * bern2(Dt, n, m - 1, C->sf, C->tf);
    C->es = n * (2 * emax + 2 * ev) + 8 * DBL_EPSILON * fabs(C->gs);
    C->et = m * (2 * emax + 2 * ev) + 8 * DBL_EPSILON * fabs(C->gt);
    C->c = c;
    C->wmin = wmin;
    return 1;
}

/* The certificate's lower bound of the distance over the piece [u0, u1] x [v0, v1] of its
 * patch (0 where the piece is not inside R). */
static double cert_bound(const cert *C, const piece *p)
{
    if (!(p->u0 >= C->u0 && p->u1 <= C->u1 && p->v0 >= C->v0 && p->v1 <= C->v1))
        return 0;
    if (C->ray) /* (a ray's: t from Q, where the piece reaches it; elsewhere in R no hit) */
        return p->u0 <= C->q1 && p->u1 >= C->q0 && p->v0 <= C->r1 && p->v1 >= C->r0 ? C->tq : INFINITY;
    double hu = C->u1 - C->u0, hv = C->v1 - C->v0;
    double sa = (p->u0 - C->u0) / hu - C->sf, sb = (p->u1 - C->u0) / hu - C->sf;
    double ta = (p->v0 - C->v0) / hv - C->tf, tb = (p->v1 - C->v0) / hv - C->tf;
    double lin = C->g0 + lesser(C->gs * sa, C->gs * sb) - C->es * greater(fabs(sa), fabs(sb)) +
                 lesser(C->gt * ta, C->gt * tb) - C->et * greater(fabs(ta), fabs(tb)) -
                 4 * DBL_EPSILON * (fabs(C->gs) + fabs(C->gt)); /* (sa, ta: absolute rounding) */
    double val = lin >= 0 ? C->c : C->c + lin / C->wmin;
    return val > 0 ? sqrt(val) * (1 - 4 * DBL_EPSILON) : 0.0;
}

/* The foot (patch bp at (bu, bv)) as a point of patch P's closure: (*uf, *vf), or 0 where P
 * does not hold it (P the foot's patch, or its neighbour across the side or corner it lies on). */
static int foot_in(const rg2_surface *s, int bp, double bu, double bv, int P, double *uf, double *vf)
{
    int bi = bp / s->nv, bj = bp % s->nv, pi = P / s->nv, pj = P % s->nv;
    for (int dir = 0; dir < 2; dir++) {
        int b = dir ? bj : bi, q = dir ? pj : pi, nn = dir ? s->nv : s->nu, cl = dir ? s->closed_v : s->closed_u;
        double t = dir ? bv : bu, *o = dir ? vf : uf;
        if (q == b)
            *o = t;
        else if (t == 1 && (q == b + 1 || (cl && b == nn - 1 && q == 0)))
            *o = 0;
        else if (t == 0 && (q == b - 1 || (cl && b == 0 && q == nn - 1)))
            *o = 1;
        else
            return 0;
    }
    return 1;
}

/* A query's certificates (the latest CERTS; older ones stay true, for an earlier c), the
 * patches tried for the latest answer, and the attempts left (an answer that a whole region
 * gives nearly equally well, such as a torus's axis point, moves on and on, and no certificate
 * holds there: the attempts stop after CERT_TRIES). */
enum { CERTS = 8, CERT_TRIES = 24 };
typedef struct {
    cert c[CERTS];
    int n, next, tried[CERTS], ntried, version, left;
} certset;

/* The certificates' best lower bound of the distance over piece p (0: none covers it). */
static double certs_bound(const certset *cs, const piece *p)
{
    double b = 0;
    for (int k = 0; k < cs->n; k++)
        if (cs->c[k].patch == p->patch)
            b = greater(b, cert_bound(&cs->c[k], p));
    return b;
}

static int ray_cert_make(const rg2_locator *L, int patch, double uf, double vf, double r, const query *qy, cert *C);

/* A certificate on patch `patch` around the nearest point or the hit found (version counts those
 * found), once per point and patch, where the point lies on the patch: over R of half-size 1/2,
 * else 1/8, else 1/32. Returns 1 if one was made. */
static int certs_try(certset *cs, const rg2_locator *L, int patch, int bp, double bu, double bv, int version,
                     const query *qy)
{
    if (bp < 0)
        return 0;
    if (cs->version != version)
        cs->version = version, cs->ntried = 0;
    for (int k = 0; k < cs->ntried; k++)
        if (cs->tried[k] == patch)
            return 0;
    if (cs->ntried == CERTS)
        return 0;
    cs->tried[cs->ntried++] = patch;
    double uf, vf;
    if (!foot_in(L->s, bp, bu, bv, patch, &uf, &vf))
        return 0;
    int slot = cs->n < CERTS ? cs->n : cs->next;
    for (double r = 0.5; r > 0.01 && cs->left > 0; r *= 0.25, cs->left--)
        if ((qy->ray ? ray_cert_make : cert_make)(L, patch, uf, vf, r, qy, &cs->c[slot])) {
            if (cs->n < CERTS)
                cs->n++;
            else
                cs->next = (cs->next + 1) % CERTS;
            return 1;
        }
    return 0;
}

/* (internal.h; test_locate's check of the certificates themselves) */
int rg2__locate_cert(const rg2_locator *L, int patch, double uf, double vf, double r, const double x[3], double c,
                     const double rect[4], double *bound)
{
    cert C;
    query qy = {0, x, NULL, NULL, c, NULL};
    if (!cert_make(L, patch, uf, vf, r, &qy, &C))
        return 0;
    piece p = {0, -1, patch, rect[0], rect[1], rect[2], rect[3], 0, 0, 0};
    *bound = cert_bound(&C, &p);
    return 1;
}

/* ---------------------------------------------------------------- the locator */

static void slab_none(node *nd)
{
    nd->n[0] = nd->n[1] = nd->n[2] = 0;
    nd->a = -INFINITY, nd->b = INFINITY;
}

/* A leaf's slab: along its patch's own normal direction (piece_frame), the range of n . P over
 * its control points, widened by the rounding of each product (3 terms: within 4 eps of the
 * sum of their sizes). */
static void slab_leaf(node *nd, const points *P)
{
    double e[3][3];
    /* (e[2] made unit again: where the sides' squares are subnormal, a piece near 1e-155 across,
     * unit3 leaves e[0] and e[1] up to 37 % off unit, and slab_dist takes n for unit) */
    if (!piece_frame(P, e) || !unit3(e[2])) {
        slab_none(nd);
        return;
    }
    double a = INFINITY, b = -INFINITY, m = 0;
    for (int q = 0; q < P->n; q++) {
        double s = dot3(e[2], P->p[q]);
        a = lesser(a, s), b = greater(b, s);
        m = greater(m, fabs(e[2][0] * P->p[q][0]) + fabs(e[2][1] * P->p[q][1]) + fabs(e[2][2] * P->p[q][2]));
    }
    memcpy(nd->n, e[2], sizeof nd->n);
    /* (and 2^-1060, far above the absolute rounding of products and sums among the subnormal
     * numbers, at coordinates below 1e-308) */
    nd->a = a - 4 * DBL_EPSILON * m - 0x1p-1060, nd->b = b + 4 * DBL_EPSILON * m + 0x1p-1060;
    if (!(isfinite(nd->a) && isfinite(nd->b))) /* (past the largest double) */
        slab_none(nd);
}

/* An inner node's slab, along the sum of its children's directions: for a child with direction
 * m, n = al m + r (r = n - al m, al = n . m), so n . P = al (m . P) + r . P, the first in the
 * child's slab and the second within r's support over the child's box; the rounding of r (within
 * 2 eps (|n| + |al m|) a coordinate) and of the sums is added. Where the children's directions
 * nearly cancel, none. */
static void slab_inner(node *nd, const node *c0, const node *c1)
{
    double n[3];
    for (int k = 0; k < 3; k++)
        n[k] = c0->n[k] + c1->n[k];
    if (!(dot3(n, n) > 0.25) || !unit3(n)) { /* (children without one have n = 0) */
        slab_none(nd);
        return;
    }
    double a = INFINITY, b = -INFINITY;
    for (int c = 0; c < 2; c++) {
        const node *ch = c ? c1 : c0;
        double al = dot3(n, ch->n), r[3], ctr = 0, half = 0, big = 0, err = 0;
        for (int k = 0; k < 3; k++) {
            r[k] = n[k] - al * ch->n[k];
            double mid = 0.5 * (ch->lo[k] + ch->hi[k]), hw = 0.5 * (ch->hi[k] - ch->lo[k]);
            ctr += r[k] * mid;
            half += fabs(r[k]) * hw;
            big = greater(big, greater(fabs(ch->lo[k]), fabs(ch->hi[k])));
            err += fabs(r[k]) * (fabs(mid) + hw);
        }
        double sa = 0, sb = 0; /* (a child without a slab has n = 0: al = 0, r = n) */
        if (isfinite(ch->a) && isfinite(ch->b))
            sa = al * (al >= 0 ? ch->a : ch->b), sb = al * (al >= 0 ? ch->b : ch->a);
        /* the rounding: r's own (2 eps (1 + |al|) a coordinate, times |P| <= 3 big), the box's
         * centre and half-width (a few eps of big each), the products and the sums */
        double m = 8 * DBL_EPSILON * (3 * big * (1 + fabs(al)) + err + fabs(sa) + fabs(sb)) + 0x1p-1060;
        double lo = sa + ctr - half - m, hi = sb + ctr + half + m;
        if (!(isfinite(lo) && isfinite(hi))) { /* (a NaN, 0 r[k] times a box's infinite half-width
                                                  near 1e308, would drop out of lesser and leave the
                                                  other child's range alone) */
            slab_none(nd);
            return;
        }
        a = lesser(a, lo);
        b = greater(b, hi);
    }
    memcpy(nd->n, n, sizeof nd->n);
    nd->a = a, nd->b = b;
    if (!(isfinite(a) && isfinite(b)))
        slab_none(nd);
}

/* The distance from x to a node's slab: a lower bound of the distance to its patches. */
static double slab_dist(const node *nd, const double x[3])
{
    double s = dot3(nd->n, x);
    double m = 4 * DBL_EPSILON * (fabs(nd->n[0] * x[0]) + fabs(nd->n[1] * x[1]) + fabs(nd->n[2] * x[2])) + 0x1p-1060;
    double g = greater(0.0, greater(nd->a - s - m, s - m - nd->b));
    if (!(g < INFINITY)) /* (n . x past the largest double: inf - inf; no bound) */
        return 0.0;
    return g / (1 + 8 * DBL_EPSILON); /* (n unit to rounding) */
}

/* The leaf of patch k: the box of its affine control points and its slab. */
static void leaf_make(const rg2_surface *s, size_t k, node *nd)
{
    static const double zero[3] = {0, 0, 0};
    int du, dv, st;
    const double *net = rg2__patch_net(s, k, &du, &dv, &st);
    points P;
    net_points_at(net, du, dv, st, &P);
    pts_box(&P, zero, NULL, nd->lo, nd->hi);
    slab_leaf(nd, &P);
    nd->kid = -1;
}

/* Node k over [i0, i1) x [j0, j1); its children go to the next free slots (*used). */
static void tree_build(rg2_locator *L, size_t k, int i0, int i1, int j0, int j1, size_t *used)
{
    node *nd = L->tree + k;
    nd->i0 = i0, nd->i1 = i1, nd->j0 = j0, nd->j1 = j1;
    if (i1 - i0 == 1 && j1 - j0 == 1) {
        leaf_make(L->s, (size_t)i0 * (size_t)L->s->nv + (size_t)j0, nd);
        return;
    }
    size_t kid = *used;
    *used += 2;
    nd->kid = (int)kid;
    if (i1 - i0 >= j1 - j0) {
        tree_build(L, kid, i0, (i0 + i1) / 2, j0, j1, used);
        tree_build(L, kid + 1, (i0 + i1) / 2, i1, j0, j1, used);
    } else {
        tree_build(L, kid, i0, i1, j0, (j0 + j1) / 2, used);
        tree_build(L, kid + 1, i0, i1, (j0 + j1) / 2, j1, used);
    }
    nd = L->tree + k; /* (the same array: no reallocation) */
    for (int c = 0; c < 3; c++) {
        nd->lo[c] = lesser(L->tree[kid].lo[c], L->tree[kid + 1].lo[c]);
        nd->hi[c] = greater(L->tree[kid].hi[c], L->tree[kid + 1].hi[c]);
    }
    slab_inner(nd, L->tree + kid, L->tree + kid + 1);
}

rg2_status rg2_locator_build(const rg2_surface *s, rg2_locator **out, rg2_error *err)
{
    if (out)
        *out = NULL;
    if (!s || !out)
        return rg2__fail(err, RG2_EINVAL, "rg2_locator_build: %s is NULL", !s ? "surface" : "out");
    if (s->nu < 1 || s->nv < 1 || !s->patch)
        return rg2__fail(err, RG2_EINVAL, "rg2_locator_build: the surface has no patches (%d x %d)", s->nu, s->nv);
    rg2_status st = rg2__surface_check_finite(s, "rg2_locator_build", 0, err);
    if (st)
        return st;
    size_t n = (size_t)s->nu * (size_t)s->nv;
    for (size_t k = 0; k < n; k++) {
        int du, dv, sr, ok = 1;
        const double *net = rg2__patch_net(s, k, &du, &dv, &sr);
        for (int r = 0; r <= du; r++)
            for (int t = 0; t <= dv; t++)
                ok &= net[4 * (r * sr + t) + 3] > 0;
        for (int r = 0; !ok && r <= du; r++)
            for (int t = 0; t <= dv; t++)
                if (!(net[4 * (r * sr + t) + 3] > 0))
                    return rg2__fail(err, RG2_EWEIGHT,
                                     "rg2_locator_build: patch (%zu,%zu) control point [%d][%d] has weight %g; the "
                                     "search needs weights > 0 (the patch inside its control points' hull)",
                                     k / (size_t)s->nv, k % (size_t)s->nv, r, t, net[4 * (r * sr + t) + 3]);
    }
    /* the library's numeric range (docs/robustness.md): past it the searches' squared distances
     * and Newton's determinants (fourth powers of the size) leave the double range; a torus at
     * 1e-161 gave an answer 2e-3 of its distance farther than a sampled point */
    st = rg2__surface_check_range(s, "rg2_locator_build", 0, err);
    if (st)
        return st;
    rg2_locator *L = rg2__calloc(1, sizeof *L);
    if (L)
        L->tree = rg2__calloc(2 * n - 1, sizeof(node));
    if (!L || !L->tree) {
        rg2_locator_free(L);
        return rg2__fail(err, RG2_ENOMEM, "rg2_locator_build: out of memory for %zu patches", n);
    }
    L->s = s;
    L->n = n;
    size_t used = 1;
    tree_build(L, 0, 0, s->nu, 0, s->nv, &used);
    const node *r = L->tree;
    for (int c = 0; c < 3; c++)
        L->centre[c] = 0.5 * (r->lo[c] + r->hi[c]);
    L->diag = box_diag(r->lo, r->hi);
    *out = L;
    return RG2_OK;
}

void rg2_locator_free(rg2_locator *L)
{
    if (!L)
        return;
    free(L->tree);
    free(L);
}

/* (internal.h; test_locate's and the fuzz harness's check of the tree's slabs) */
double rg2__locate_slab_margin(const rg2_locator *L, int *slabs)
{
    long double worst = INFINITY;
    *slabs = 0;
    for (size_t k = 0; k < 2 * L->n - 1; k++) {
        const node *nd = L->tree + k;
        if (!isfinite(nd->a) || !isfinite(nd->b))
            continue;
        ++*slabs;
        long double size = 0, lo = INFINITY, hi = -INFINITY;
        for (int i = nd->i0; i < nd->i1; i++)
            for (int j = nd->j0; j < nd->j1; j++) {
                rg2_xpatch X;
                rg2_surface_patch_get(L->s, i, j, &X);
                for (int r = 0; r <= X.du; r++)
                    for (int t = 0; t <= X.dv; t++) {
                        long double sp = 0;
                        for (int c = 0; c < 3; c++) {
                            long double p = (long double)X.h[r][t][c] / X.h[r][t][3];
                            sp += (long double)nd->n[c] * p;
                            size = size > fabsl(p) ? size : fabsl(p);
                        }
                        lo = lo < sp ? lo : sp;
                        hi = hi > sp ? hi : sp;
                    }
            }
        long double m = (lo - nd->a < nd->b - hi ? lo - nd->a : nd->b - hi) / (size > 0 ? size : 1);
        worst = worst < m ? worst : m;
    }
    return (double)worst;
}

static void hit_init(rg2_hit *h)
{
    memset(h, 0, sizeof *h);
    h->i = h->j = -1;
    h->dist = h->bound = INFINITY;
}

/* The hit's point, its limit normal and its patch (i, j) at (u, v). */
static void hit_fill(const rg2_locator *L, int patch, double u, double v, rg2_hit *h)
{
    rg2_eval e;
    h->i = patch / L->s->nv;
    h->j = patch % L->s->nv;
    h->u = u;
    h->v = v;
    rg2_surface_eval_limit(L->s, h->i, h->j, u, v, 1, &e);
    memcpy(h->p, e.p, sizeof h->p);
    h->flags = e.flags;
    if (!(e.flags & RG2_EVAL_NORMAL_UNDEFINED))
        memcpy(h->n, e.n, sizeof h->n);
    else
        memset(h->n, 0, sizeof h->n);
}

static double dist3(const double *a, const double *b)
{
    double d[3] = {a[0] - b[0], a[1] - b[1], a[2] - b[2]};
    return sqrt(dot3(d, d));
}

/* Newton on min |S(u, v) - x|^2 over patch (pi, pj)'s [0,1]^2 from (u, v): the Newton step
 * where the Hessian is positive definite, else the Gauss-Newton one, kept in the square and
 * halved until the distance drops. Returns the distance at the final (u, v). */
static double foot(const rg2_surface *s, int pi, int pj, const double x[3], double *u, double *v, long *evals)
{
    rg2_eval e;
    rg2_surface_eval(s, pi, pj, *u, *v, 2, &e);
    ++*evals;
    double r[3] = {e.p[0] - x[0], e.p[1] - x[1], e.p[2] - x[2]}, d = sqrt(dot3(r, r));
    /* the rounding of d: of the differences p - x */
    double slack = 16 * DBL_EPSILON * (fabs(x[0]) + fabs(x[1]) + fabs(x[2]) + d);
    double gmin = INFINITY; /* the smallest gradient (squared) of the points taken */
    for (int it = 0; it < 60 && isfinite(d) && d > 0; it++) {
        double g0 = dot3(e.su, r), g1 = dot3(e.sv, r);
        /* a side of the square where the distance falls outward holds the parameter there (the
         * active set): the step runs along the side, and at such a corner the foot is found */
        int hu = (*u == 0 && g0 > 0) || (*u == 1 && g0 < 0), hv = (*v == 0 && g1 > 0) || (*v == 1 && g1 < 0);
        if (hu && hv)
            break;
        if (hu)
            g0 = 0;
        if (hv)
            g1 = 0;
        double gg = g0 * g0 + g1 * g1;
        gmin = lesser(gmin, gg);
        double a = dot3(e.su, e.su), b = dot3(e.su, e.sv), c = dot3(e.sv, e.sv);
        double A = a + dot3(e.suu, r), B = b + dot3(e.suv, r), C = c + dot3(e.svv, r);
        if (hu || hv) /* (one parameter moves: its own second derivative, Newton or Gauss-Newton) */
            B = 0, A = hu ? 1 : (A > 0 ? A : a), C = hv ? 1 : (C > 0 ? C : c);
        double det = A * C - B * B;
        if (!(A > 0 && det > 1e-14 * (fabs(A * C) + B * B))) { /* not positive definite: Gauss-Newton */
            A = hu ? 1 : a, B = hu || hv ? 0 : b, C = hv ? 1 : c;
            det = A * C - B * B;
            if (!(det > 1e-30 * (A * C)) || !isfinite(det)) {
                if (a > 0 && !hu) /* along u only (a pole side: Sv = 0) */
                    A = a, B = 0, C = 1, det = a, g1 = 0;
                else if (c > 0 && !hv)
                    A = 1, B = 0, C = c, det = c, g0 = 0;
                else
                    break;
            }
        }
        det = det > 0 ? det : 1.0; /* (positive here; the guard keeps a hoisted division harmless) */
        double du = -(C * g0 - B * g1) / det, dv = -(A * g1 - B * g0) / det;
        int better = 0;
        for (int half = 0; half < 40 && !better; half++, du *= 0.5, dv *= 0.5) {
            double nu = fmin(1.0, fmax(0.0, *u + du)), nv = fmin(1.0, fmax(0.0, *v + dv));
            if (nu == *u && nv == *v)
                break;
            rg2_eval f;
            rg2_surface_eval(s, pi, pj, nu, nv, 2, &f);
            ++*evals;
            double q[3] = {f.p[0] - x[0], f.p[1] - x[1], f.p[2] - x[2]}, dq = sqrt(dot3(q, q));
            /* nearer; or, where the distance is flat to rounding near the foot, as near with a
             * gradient under half the smallest met so far (the point then still moves to its
             * last bits). Against the smallest met, not the current one's: two points a rounding
             * apart, one nearer by its last bits and the other with the smaller gradient, took
             * each other in turn for all 60 steps; now the second can be taken only once. (Taking
             * only steps nearer by more than rounding, as a first version did, stopped the crawl
             * along a side near a focal point short: 9e-12 of the size off.) */
            double h0 = dot3(f.su, q), h1 = dot3(f.sv, q);
            if ((nu == 0 && h0 > 0) || (nu == 1 && h0 < 0))
                h0 = 0;
            if ((nv == 0 && h1 > 0) || (nv == 1 && h1 < 0))
                h1 = 0;
            if (dq < d || (dq <= d + slack && h0 * h0 + h1 * h1 < 0.25 * gmin)) {
                better = 1;
                *u = nu, *v = nv, d = dq, e = f;
                memcpy(r, q, sizeof r);
            }
        }
        if (!better)
            break;
    }
    return d;
}

/* foot, then across patch sides: where it ends on a side that another patch shares, from the
 * same point of that patch; its result is taken when it leaves the side as near (a foot on the
 * other side of a seam, which the first patch could only approach up to its side). */
static double foot_across(const rg2_surface *s, int *pi, int *pj, const double x[3], double *u, double *v,
                          long *evals)
{
    double d = foot(s, *pi, *pj, x, u, v, evals);
    /* (as near: within the rounding of the distances, which foot's slack bounds; a foot 1e-8
     * past a seam is 1e-17 nearer than the side point, and the two computed distances differ
     * by their rounding, either way) */
    double slack = 16 * DBL_EPSILON * (fabs(x[0]) + fabs(x[1]) + fabs(x[2]) + d);
    for (int hop = 0; hop < 4; hop++) {
        int i = *pi, j = *pj, side = *u == 0 ? 0 : *u == 1 ? 1 : *v == 0 ? 2 : *v == 1 ? 3 : -1;
        if (side < 0)
            break;
        double nu = *u, nv = *v;
        if (side < 2) {
            i += side ? 1 : -1;
            if (i < 0 || i >= s->nu) {
                if (!s->closed_u)
                    break;
                i = (i + s->nu) % s->nu;
            }
            nu = side ? 0 : 1;
        } else {
            j += side == 3 ? 1 : -1;
            if (j < 0 || j >= s->nv) {
                if (!s->closed_v)
                    break;
                j = (j + s->nv) % s->nv;
            }
            nv = side == 3 ? 0 : 1;
        }
        double a = nu, b = nv, dn = foot(s, i, j, x, &a, &b, evals);
        if ((side < 2 ? a == nu : b == nv) || !(dn <= d + slack))
            break;
        *pi = i, *pj = j, *u = a, *v = b, d = dn;
    }
    return d;
}

static rg2_status query_check(const rg2_locator *L, const char *who, const char *what, const double *x, int n,
                              rg2_hit *out, rg2_error *err)
{
    if (!L || !x || !out)
        return rg2__fail(err, RG2_EINVAL, "%s: %s is NULL", who, !L ? "locator" : !x ? what : "out");
    for (int k = 0; k < n; k++)
        if (!isfinite(x[k]))
            return rg2__fail(err, RG2_ENONFINITE, "%s: %s[%d] is not a finite number", who, k < 3 ? what : "d",
                             k % 3);
    /* a point past the numeric range: the squared distances overflow past about 1e154 (the
     * nearest point at 1e155 was "the search ended before any patch", RG2_ELIMIT; a ray from
     * (1e300, 0.1, 0.05) along -x "proved" a miss, bound = inf, through a torus at the origin) */
    for (int k = 0; k < n && strcmp(what, "d"); k++)
        if (fabs(x[k]) > RG2_DESIGN_MAX_ABS)
            return rg2__fail(err, RG2_EDOMAIN,
                             "%s: %s[%d] = %g is beyond %g, the numeric range of the searches (docs/robustness.md)",
                             who, what, k, x[k], RG2_DESIGN_MAX_ABS);
    return RG2_OK;
}

/* A tree node taken from the heap: its patch, as one piece with the node's bound, or its two
 * children, each with the larger of the node's bound and key(child) (INFINITY: the query cannot
 * reach it); those whose bound is not below limit are set aside, their bound kept in *floor. */
static void descend(const rg2_locator *L, heap *h, const piece *p, double (*key)(const node *, const void *),
                    const void *ctx, double limit, double *floor)
{
    const node *nd = L->tree + p->node;
    if (nd->kid < 0) {
        piece q = {p->key, -1, nd->i0 * L->s->nv + nd->j0, 0, 1, 0, 1, 0, 0, 0};
        heap_push(h, &q);
        return;
    }
    for (int c = 0; c < 2; c++) {
        double k = key(L->tree + nd->kid + c, ctx);
        if (k == INFINITY)
            continue;
        piece q = {greater(p->key, k), nd->kid + c, 0, 0, 1, 0, 1, 0, 0, 0};
        if (q.key < limit)
            heap_push(h, &q);
        else
            *floor = lesser(*floor, q.key);
    }
}

/* The distance from x to a node's box, or to its slab where that is farther. */
static double closest_key(const node *nd, const void *x)
{
    return greater(box_dist(nd->lo, nd->hi, x), slab_dist(nd, x));
}

/* rg2_locator_closest; *evals counts the patch evaluations of its Newton runs (internal.h). */
rg2_status rg2__locate_closest(const rg2_locator *L, const double x[3], rg2_hit *out, long *evals, rg2_error *err)
{
    if (out)
        hit_init(out);
    rg2_status st = query_check(L, "rg2_locator_closest", "x", x, 3, out, err);
    if (st)
        return st;
    const rg2_surface *s = L->s;
    double tol = 1e-10 * (L->diag + dist3(x, L->centre));
    double best = INFINITY, bu = 0, bv = 0;
    int bp = -1;
    heap h = {0};
    double floor = INFINITY; /* smallest bound of what was set aside unsplit */
    piece root = {box_dist(L->tree[0].lo, L->tree[0].hi, x), 0, 0, 0, 1, 0, 1, 0, 0, 0};
    heap_push(&h, &root);
    long taken = 0;
    certset cs;
    cs.n = cs.ntried = cs.next = 0, cs.version = -1, cs.left = CERT_TRIES;
    int version = 0; /* counts the feet found */
    while (h.n && !h.nomem) {
        piece p = heap_pop(&h);
        if (!(p.key < best - tol) || ++taken > rg2__locate_max_pieces) {
            floor = fmin(floor, p.key);
            break;
        }
        if (p.node >= 0) { /* a node of the tree: its children, or its patch */
            descend(L, &h, &p, closest_key, x, best - tol, &floor);
            continue;
        }
        /* ruled out by a certificate (before its centre is evaluated) */
        double kc = fmax(p.key, certs_bound(&cs, &p));
        if (!(kc < best - tol)) {
            floor = fmin(floor, kc);
            continue;
        }
        rg2_xpatch X, q[4];
        piece_net(L, &p, &X);
        points P;
        double size = p.size;
        if (!p.known) { /* a whole patch from the tree (keyed by its box): its own bounds first */
            net_points(&X, &P);
            kc = fmax(kc, closest_bound(&P, x, &size));
            if (kc < best - tol)
                kc = fmax(kc, bern_bound(&X, x));
            if (!(kc < best - tol)) {
                floor = fmin(floor, kc);
                continue;
            }
        }
        int pi = p.patch / s->nv, pj = p.patch % s->nv;
        double u = 0.5 * (p.u0 + p.u1), v = 0.5 * (p.v0 + p.v1);
        rg2_eval e;
        rg2_surface_eval(s, pi, pj, u, v, 0, &e);
        if (dist3(e.p, x) < best) {
            int fi = pi, fj = pj;
            double d = foot_across(s, &fi, &fj, x, &u, &v, evals);
            if (d < best)
                best = d, bp = fi * s->nv + fj, bu = u, bv = v, version++;
        }
        query qy = {0, x, NULL, NULL, best * best, NULL};
        if (certs_try(&cs, L, p.patch, bp, bu, bv, version, &qy)) {
            kc = fmax(kc, certs_bound(&cs, &p));
            if (!(kc < best - tol)) {
                floor = fmin(floor, kc);
                continue;
            }
        }
        if (!(size > tol)) { /* smaller than the tolerance: its centre stands for it */
            floor = fmin(floor, p.key);
            continue;
        }
        quarters(&X, q);
        for (int c = 0; c < 4; c++) {
            double um = 0.5 * (p.u0 + p.u1), vm = 0.5 * (p.v0 + p.v1);
            net_points(&q[c], &P);
            double size_c;
            piece ch = {closest_bound(&P, x, &size_c), -1, p.patch, c & 1 ? um : p.u0, c & 1 ? p.u1 : um,
                        c & 2 ? vm : p.v0, c & 2 ? p.v1 : vm, 1, 0, 0};
            ch.size = size_c;
            ch.key = fmax(ch.key, p.key);
            if (ch.key < best - tol)
                ch.key = fmax(ch.key, certs_bound(&cs, &ch));
            if (ch.key < best - tol)
                ch.key = fmax(ch.key, bern_bound(&q[c], x));
            if (ch.key < best - tol)
                heap_push(&h, &ch);
            else
                floor = fmin(floor, ch.key);
        }
    }
    if (h.n)
        floor = fmin(floor, h.a[0].key);
    free(h.a);
    if (h.nomem)
        return rg2__fail(err, RG2_ENOMEM, "rg2_locator_closest: out of memory for the search's pieces");
    if (bp < 0) /* (the first patch piece taken sets it; a limit of at least one piece) */
        return rg2__fail(err, RG2_ELIMIT, "rg2_locator_closest: the search ended before any patch");
    hit_fill(L, bp, bu, bv, out);
    out->dist = dist3(out->p, x);
    out->bound = fmin(floor, out->dist);
    return RG2_OK;
}

rg2_status rg2_locator_closest(const rg2_locator *L, const double x[3], rg2_hit *out, rg2_error *err)
{
    long evals = 0;
    return rg2__locate_closest(L, x, out, &evals, err);
}

/* The ray's frame: e[0], e[1] unit and across the ray, e[2] = d / |d|^2 (idd = 1 / |d|^2); dn
 * (d on entry) made unit. */
static void ray_frame(const double d[3], double idd, double dn[3], double e[3][3])
{
    int m = fabs(d[0]) <= fabs(d[1]) && fabs(d[0]) <= fabs(d[2]) ? 0 : fabs(d[1]) <= fabs(d[2]) ? 1 : 2;
    double a[3] = {0, 0, 0};
    a[m] = 1;
    unit3(dn);
    cross3(dn, a, e[0]);
    unit3(e[0]);
    cross3(dn, e[0], e[1]);
    for (int k = 0; k < 3; k++)
        e[2][k] = d[k] * idd;
}

/* Newton on the two residuals across the ray (e1 . (S - o), e2 . (S - o)) over patch (pi, pj)'s
 * [0,1]^2 from (u, v), as the renderer's per-pixel step. Returns the residual at the final
 * (u, v), the best one met. */
static double ray_newton(const rg2_surface *s, int pi, int pj, const double o[3], const double (*e)[3], double *u,
                         double *v)
{
    double best = INFINITY, bu = *u, bv = *v;
    for (int it = 0; it < 40; it++) {
        rg2_eval f;
        rg2_surface_eval(s, pi, pj, *u, *v, 1, &f);
        double q[3] = {f.p[0] - o[0], f.p[1] - o[1], f.p[2] - o[2]};
        double F0 = dot3(q, e[0]), F1 = dot3(q, e[1]), res = sqrt(F0 * F0 + F1 * F1);
        if (!isfinite(res))
            break;
        if (!(res < best)) /* no more progress (rounding) */
            break;
        best = res, bu = *u, bv = *v;
        double a = dot3(f.su, e[0]), b = dot3(f.sv, e[0]), c = dot3(f.su, e[1]), d = dot3(f.sv, e[1]);
        double det = a * d - b * c;
        int ok = fabs(det) > 0 && isfinite(det);
        det = ok ? det : 1.0; /* (a divisor that cannot trap: see unit3) */
        if (!ok)
            break;
        double nu = fmin(1.0, fmax(0.0, *u - (d * F0 - b * F1) / det));
        double nv = fmin(1.0, fmax(0.0, *v - (a * F1 - c * F0) / det));
        if (nu == *u && nv == *v)
            break;
        *u = nu, *v = nv;
    }
    *u = bu, *v = bv;
    return best;
}

/* Box of a piece in the ray's frame: across the ray (e[0], e[1], relative to o) and along it
 * (e[2] = d / |d|^2, giving ray parameters), narrowed by the slab of the piece's own frame.
 * Returns 0 when the piece cannot meet the ray; else [*t0, *t1] holds the t where it can, and
 * *diag is the box's size across the ray. */
static int ray_box(const rg2_xpatch *X, const double o[3], const double d[3], const double (*e)[3], double *t0,
                   double *t1, double *diag)
{
    points P;
    net_points(X, &P);
    double lo[3], hi[3], mag = pts_box(&P, o, e, lo, hi);
    /* a margin for the rounding of these projections (a ray through a patch side or a corner
     * must not slip between the patches) */
    double m = 16 * DBL_EPSILON * mag, mt = m * sqrt(dot3(e[2], e[2]));
    *t0 = lo[2] - mt;
    *t1 = hi[2] + mt;
    *diag = hypot(hi[0] - lo[0], hi[1] - lo[1]);
    if (!(lo[0] <= m && hi[0] >= -m && lo[1] <= m && hi[1] >= -m))
        return 0;
    /* the slab of the piece's own frame across its normal: thin (its thickness shrinks like the
     * square of the piece's size), so where the ray crosses it obliquely it bounds t closely */
    double f[3][3];
    if (!piece_frame(&P, f))
        return 1;
    pts_box(&P, o, (const double(*)[3])f, lo, hi);
    double slo = lo[2] - m, shi = hi[2] + m;
    double sd = dot3(f[2], d); /* (P relative to o: the ray's t where it crosses the slab) */
    int across = fabs(sd) * 1e250 > greater(fabs(slo), fabs(shi));
    sd = across ? sd : 1.0; /* (a divisor that cannot trap: see unit3) */
    if (!across) /* along the slab */
        return slo <= 0 && shi >= 0;
    double ta = slo / sd, tb = shi / sd;
    *t0 = greater(*t0, lesser(ta, tb));
    *t1 = lesser(*t1, greater(ta, tb));
    return *t0 <= *t1;
}

/* A ray's certificate over R = [uf - r, uf + r] x [vf - r, vf + r] (within the patch), based at a
 * hit (uf, vf): F = (e0 . (H - o w), e1 . (H - o w)), zero where the patch meets the ray's line,
 * is one-to-one on R where every matrix of the Bernstein ranges of its partial derivatives has
 * a determinant away from 0 (F(y) - F(y0) = J (y - y0), J within those ranges); then the only
 * zero in R lies within |J^-1| |F(y0)| of y0, in Q, and no point of R outside Q meets the ray.
 * The coefficients carry the rounding of the net's cut and of o w (which also covers the true
 * ray's departure from the frame's line, a few ulps of |S - o|). 0 where F is not shown
 * one-to-one, or Q is not small. */
static int ray_cert_make(const rg2_locator *L, int patch, double uf, double vf, double r, const query *qy, cert *C)
{
    rg2_xpatch X;
    double sf, tf;
    cert_rect(L, patch, uf, vf, r, C, &X, &sf, &tf);
    int du = X.du, dv = X.dv;
    const double *o = qy->o, (*e)[3] = qy->e;
    double F[2][M2][M2], om = fabs(o[0]) + fabs(o[1]) + fabs(o[2]), errf = 0, fmag = 0, hmax, wmax;
    net_size(L, patch, &hmax, &wmax);
    errf = 64 * DBL_EPSILON * (hmax + om * wmax); /* (the cut's rounding: see net_size) */
    for (int a = 0; a <= du; a++)
        for (int b = 0; b <= dv; b++) {
            const double *h = X.h[a][b];
            if (!(h[3] > 0))
                return 0;
            double q[3] = {h[0] - o[0] * h[3], h[1] - o[1] * h[3], h[2] - o[2] * h[3]};
            errf = greater(errf, 64 * DBL_EPSILON * (fabs(h[0]) + fabs(h[1]) + fabs(h[2]) + om * h[3]));
            for (int k = 0; k < 2; k++) {
                F[k][a][b] = dot3(e[k], q);
                fmag = greater(fmag, fabs(F[k][a][b]));
            }
        }
    /* the ranges of F0_s, F0_t, F1_s, F1_t over R (Bernstein coefficients of the derivatives) */
    double lo[4], hi[4];
    for (int k = 0; k < 4; k++) {
        int f = k / 2, alongs = k % 2 == 0, n = alongs ? du : dv;
        lo[k] = INFINITY, hi[k] = -INFINITY;
        for (int a = 0; a + alongs <= du; a++)
            for (int b = 0; b + !alongs <= dv; b++) {
                double c = n * (F[f][a + alongs][b + !alongs] - F[f][a][b]);
                lo[k] = lesser(lo[k], c), hi[k] = greater(hi[k], c);
            }
        double m = n * (2 * errf + 4 * DBL_EPSILON * fmag);
        lo[k] -= m, hi[k] += m;
    }
    /* det J = F0_s F1_t - F0_t F1_s over the ranges (the entries independent) */
    double ad[4] = {lo[0] * lo[3], lo[0] * hi[3], hi[0] * lo[3], hi[0] * hi[3]};
    double bc[4] = {lo[1] * lo[2], lo[1] * hi[2], hi[1] * lo[2], hi[1] * hi[2]};
    double adlo = INFINITY, adhi = -INFINITY, bclo = INFINITY, bchi = -INFINITY;
    for (int k = 0; k < 4; k++) {
        adlo = lesser(adlo, ad[k]), adhi = greater(adhi, ad[k]);
        bclo = lesser(bclo, bc[k]), bchi = greater(bchi, bc[k]);
    }
    double dlo = adlo - bchi, dhi = adhi - bclo, rnd = 8 * DBL_EPSILON * (fabs(adlo) + fabs(adhi) + fabs(bclo) + fabs(bchi));
    double dmin = dlo > 0 ? dlo - rnd : dhi < 0 ? -dhi - rnd : 0;
    if (!(dmin > 0) || !isfinite(dmin + fmag))
        return 0;
    /* |y0 - hit| <= |adj J|_inf |F(y0)|_inf / |det J| (in R's own parameters) */
    double ev = errf + (du + dv + 2) * 4 * DBL_EPSILON * fmag;
    double f0 = fabs(bern2(F[0], du, dv, sf, tf)) + ev, f1 = fabs(bern2(F[1], du, dv, sf, tf)) + ev;
    double mag[4];
    for (int k = 0; k < 4; k++)
        mag[k] = greater(fabs(lo[k]), fabs(hi[k]));
    double rho = greater(mag[3] + mag[1], mag[2] + mag[0]) * greater(f0, f1) / (dmin > 0 ? dmin : 1.0) * (1 + 1e-9) +
                 1e-15; /* (a divisor that cannot trap: see unit3) */
    if (!(rho < 0.125))
        return 0;
    C->ray = 1;
    C->q0 = fmax(C->u0, uf - rho * (C->u1 - C->u0)), C->q1 = fmin(C->u1, uf + rho * (C->u1 - C->u0));
    C->r0 = fmax(C->v0, vf - rho * (C->v1 - C->v0)), C->r1 = fmin(C->v1, vf + rho * (C->v1 - C->v0));
    /* t over Q: its control points' range along the ray, with a margin for their own rounding
     * as well as the projection's (|P| <= |P - o| + |o|); Q is not ruled out across the ray */
    piece pq = {0, -1, patch, C->q0, C->q1, C->r0, C->r1, 0, 0, 0};
    points P;
    double plo[3], phi[3];
    piece_net(L, &pq, &X);
    net_points(&X, &P);
    double mt = 16 * DBL_EPSILON * (pts_box(&P, o, e, plo, phi) + om) * sqrt(dot3(e[2], e[2]));
    C->tq = phi[2] + mt < 0 ? INFINITY : fmax(0.0, plo[2] - mt);
    return 1;
}

/* (internal.h; test_locate's check of the rays' certificates) */
int rg2__locate_ray_cert(const rg2_locator *L, int patch, double uf, double vf, double r, const double o[3],
                         const double d[3], const double rect[4], double *bound)
{
    double e[3][3], dn[3] = {d[0], d[1], d[2]}, dd = dot3(d, d);
    int ok = dd > 0 && isfinite(dd);
    double idd = 1.0 / (ok ? dd : 1.0); /* (see unit3) */
    if (!ok)
        return 0;
    ray_frame(d, idd, dn, e);
    query qy = {1, NULL, o, d, 0, (const double(*)[3])e};
    cert C;
    if (!ray_cert_make(L, patch, uf, vf, r, &qy, &C))
        return 0;
    piece p = {0, -1, patch, rect[0], rect[1], rect[2], rect[3], 0, 0, 0};
    *bound = cert_bound(&C, &p);
    return 1;
}

/* Slab test of a node's box and of its own slab, widened by tol, against the ray o + s dn (dn
 * unit), 0 <= s <= smax (a filter: the ray frame test of the pieces decides). 1 and *s0, where
 * the ray enters both. */
static int slab(const node *nd, const double o[3], const double dn[3], double smax, double tol, double *s0)
{
    double t0 = 0, t1 = smax;
    for (int c = 0; c < 3 && t0 <= t1; c++) {
        int along = fabs(dn[c]) < 1e-200; /* parallel to this axis (within 1e-200) */
        double den = along ? 1.0 : dn[c]; /* (a divisor that cannot trap: see unit3) */
        if (along) {
            if (o[c] < nd->lo[c] - tol || o[c] > nd->hi[c] + tol)
                return 0;
            continue;
        }
        double ta = (nd->lo[c] - tol - o[c]) / den, tb = (nd->hi[c] + tol - o[c]) / den;
        t0 = greater(t0, lesser(ta, tb));
        t1 = lesser(t1, greater(ta, tb));
    }
    if (t0 <= t1 && isfinite(nd->a)) { /* the node's own slab along n, widened the same way and by
                                          the rounding of n . o */
        double no = dot3(nd->n, o), nd_ = dot3(nd->n, dn);
        double m = tol + 4 * DBL_EPSILON * (fabs(nd->n[0] * o[0]) + fabs(nd->n[1] * o[1]) + fabs(nd->n[2] * o[2])) +
                   0x1p-1060;
        double lo = nd->a - m - no, hi = nd->b + m - no;
        if (fabs(nd_) < 1e-200) {
            if (lo > 0 || hi < 0)
                return 0;
        } else {
            double ta = lo / nd_, tb = hi / nd_;
            t0 = greater(t0, lesser(ta, tb));
            t1 = lesser(t1, greater(ta, tb));
        }
    }
    *s0 = t0;
    return t0 <= t1;
}

/* The ray's t where it enters a node's box (slab), INFINITY where it misses it. */
typedef struct {
    const double *o, *dn;
    double smax, tol, len;
} ray_ctx;

static double ray_key(const node *nd, const void *ctx)
{
    const ray_ctx *r = ctx;
    double s0;
    return slab(nd, r->o, r->dn, r->smax, r->tol, &s0) ? s0 / r->len : INFINITY;
}

rg2_status rg2_locator_ray(const rg2_locator *L, const double o[3], const double d[3], double tmax, rg2_hit *out,
                           rg2_error *err)
{
    if (out)
        hit_init(out);
    rg2_status st = query_check(L, "rg2_locator_ray", "o", o, 3, out, err);
    if (!st)
        st = query_check(L, "rg2_locator_ray", "d", d, 3, out, err);
    if (st)
        return st;
    if (isnan(tmax) || !(tmax >= 0))
        return rg2__fail(err, RG2_EDOMAIN, "rg2_locator_ray: tmax is %g; it must be >= 0 (INFINITY for no limit)",
                         tmax);
    double dd = dot3(d, d), e[3][3];
    int dok = dd > 0 && isfinite(dd);
    double idd = 1.0 / (dok ? dd : 1.0); /* (a divisor that cannot trap: see unit3) */
    double dmax = fmax(fabs(d[0]), fmax(fabs(d[1]), fabs(d[2])));
    if (!(dmax > 0))
        return rg2__fail(err, RG2_EDOMAIN, "rg2_locator_ray: the direction d = (%g, %g, %g) has no length", d[0],
                         d[1], d[2]);
    /* a length outside the numeric range: d . d left the double range (1e155 and 1e-200 were
     * "has no length"), or its subnormal digits lost the ray (|d| = 1e-160 missed a torus it
     * goes through, RG2_OK) */
    if (!dok || dmax > RG2_DESIGN_MAX_ABS || dmax < RG2_DESIGN_MIN_ABS)
        return rg2__fail(err, RG2_EDOMAIN,
                         "rg2_locator_ray: the direction d = (%g, %g, %g) is %s: its largest component must lie "
                         "in [%g, %g]; scale it (d need not be unit, t is in units of d)",
                         d[0], d[1], d[2], dmax > 1.0 ? "too long" : "too short", RG2_DESIGN_MIN_ABS,
                         RG2_DESIGN_MAX_ABS);
    double dn[3] = {d[0], d[1], d[2]};
    ray_frame(d, idd, dn, e);
    const rg2_surface *s = L->s;
    double len = sqrt(dd), tol = 1e-10 * (L->diag + dist3(o, L->centre)), ttol = tol / len;
    double best = tmax, bu = 0, bv = 0, floor = tmax, near_t = INFINITY, nu = 0, nv = 0;
    int bp = -1, np = -1;
    heap h = {0};
    /* tmax along dn; past half the largest double, no limit (the division cannot overflow, even
     * computed ahead of a test: its divisor is at least 1) */
    double tlen = tmax > 0.5 * (DBL_MAX / fmax(len, 1.0)) ? INFINITY : tmax * len;
    double t0;
    if (slab(L->tree, o, dn, tlen, tol, &t0)) {
        piece root = {t0 / len, 0, 0, 0, 1, 0, 1, 0, 0, 0};
        heap_push(&h, &root);
    }
    long taken = 0;
    certset cs;
    cs.n = cs.ntried = cs.next = 0, cs.version = -1, cs.left = CERT_TRIES;
    int version = 0; /* counts the hits found */
    query qy = {1, NULL, o, d, 0, (const double(*)[3])e};
    while (h.n && !h.nomem) {
        piece p = heap_pop(&h);
        /* (before the first hit, a piece may still hold one at t = tmax exactly) */
        if (!(bp >= 0 ? p.key < best - ttol : p.key <= best) || ++taken > rg2__locate_max_pieces) {
            floor = fmin(floor, p.key);
            break;
        }
        if (p.node >= 0) { /* a node of the tree: its children, or its patch */
            ray_ctx rc = {o, dn, tlen, tol, len};
            descend(L, &h, &p, ray_key, &rc, bp >= 0 ? best - ttol : nextafter(best, INFINITY), &floor);
            continue;
        }
        /* ruled out by a certificate (no hit of its patch's rectangle before that) */
        double kc = bp >= 0 ? fmax(p.key, certs_bound(&cs, &p)) : p.key;
        if (!(bp >= 0 ? kc < best - ttol : kc <= best)) {
            floor = fmin(floor, kc);
            continue;
        }
        rg2_xpatch X, q[4];
        piece_net(L, &p, &X);
        double t1 = p.t1, diag = p.size;
        t0 = p.key;
        if (!p.known && (!ray_box(&X, o, d, (const double(*)[3])e, &t0, &t1, &diag) || t0 > best || t1 < 0))
            continue; /* the piece misses the ray, or meets it only after the best or behind o */
        int pi = p.patch / s->nv, pj = p.patch % s->nv;
        double u = 0.5 * (p.u0 + p.u1), v = 0.5 * (p.v0 + p.v1);
        rg2_eval f;
        /* Newton from the centre, except in a piece that holds the best hit itself (from there
         * it returns to that hit; an earlier hit in the piece is still found by the splitting) */
        if (!(bp == p.patch && bu >= p.u0 && bu <= p.u1 && bv >= p.v0 && bv <= p.v1)) {
            double res = ray_newton(s, pi, pj, o, (const double(*)[3])e, &u, &v);
            rg2_surface_eval(s, pi, pj, u, v, 0, &f);
            double q0[3] = {f.p[0] - o[0], f.p[1] - o[1], f.p[2] - o[2]}, t = dot3(e[2], q0);
            /* on the ray, not behind o (but for rounding: a ray from a surface point meets it
             * at t = 0), not after the best (before the first: not after tmax) */
            if (res <= 1e-2 * tol && t >= -1e-2 * ttol && (bp >= 0 ? t < best : t <= best))
                best = t, bp = p.patch, bu = u, bv = v, version++;
        }
        if (certs_try(&cs, L, p.patch, bp, bu, bv, version, &qy)) {
            kc = fmax(kc, certs_bound(&cs, &p));
            if (!(kc < best - ttol)) {
                floor = fmin(floor, kc);
                continue;
            }
        }
        if (!(diag > tol)) { /* within the tolerance of the ray: not split again. Its centre is a
                                hit within the tolerance, kept in case Newton finds none */
            u = 0.5 * (p.u0 + p.u1), v = 0.5 * (p.v0 + p.v1);
            rg2_surface_eval(s, pi, pj, u, v, 0, &f);
            double qc[3] = {f.p[0] - o[0], f.p[1] - o[1], f.p[2] - o[2]}, tc = dot3(e[2], qc);
            if (tc >= 0 && tc < near_t)
                near_t = tc, np = p.patch, nu = u, nv = v;
            floor = fmin(floor, fmax(0.0, t0));
            continue;
        }
        quarters(&X, q);
        for (int c = 0; c < 4; c++) {
            double um = 0.5 * (p.u0 + p.u1), vm = 0.5 * (p.v0 + p.v1), c0, c1, cd;
            if (!ray_box(&q[c], o, d, (const double(*)[3])e, &c0, &c1, &cd) || c0 > best || c1 < 0)
                continue;
            piece ch = {fmax(p.key, fmax(0.0, c0)), -1, p.patch, c & 1 ? um : p.u0, c & 1 ? p.u1 : um,
                        c & 2 ? vm : p.v0, c & 2 ? p.v1 : vm, 1, c1, cd};
            if (bp >= 0 && ch.key < best - ttol)
                ch.key = fmax(ch.key, certs_bound(&cs, &ch));
            if (bp >= 0 ? ch.key < best - ttol : ch.key <= best)
                heap_push(&h, &ch);
            else
                floor = fmin(floor, ch.key);
        }
    }
    if (h.n)
        floor = fmin(floor, h.a[0].key);
    free(h.a);
    if (h.nomem)
        return rg2__fail(err, RG2_ENOMEM, "rg2_locator_ray: out of memory for the search's pieces");
    if (bp < 0 && np >= 0 && near_t <= tmax) /* no Newton hit: the nearest piece within the tolerance */
        bp = np, bu = nu, bv = nv;
    if (bp >= 0) {
        hit_fill(L, bp, bu, bv, out);
        double q0[3] = {out->p[0] - o[0], out->p[1] - o[1], out->p[2] - o[2]};
        out->dist = dot3(e[2], q0);
        if (out->dist < 0) /* (a hit at o, behind it by rounding) */
            out->dist = 0;
        out->bound = fmin(floor, out->dist);
    } else
        out->bound = floor;
    return RG2_OK;
}
