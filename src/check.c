/* check.c -- the continuity and exactness report behind `rg2 check`.
 *
 * METHOD (MATH.md section 8)
 *   Seams: every interior patch seam of each surface (and the closing seams of closed
 *   directions) is sampled at seam_samples + 1 points; at each point the two patches are
 *   evaluated (order 2) at their common edge and compared: position gap / size, angle between
 *   the unit normals (atan2(|n1 x n2|, n1 . n2)), and the jump of the normal curvature in six
 *   tangent directions (0, 30, ..., 150 degrees from the seam) relative to
 *   max(|k1|, |k2|, 1 / size). size is the diagonal of the surface's control-point box.
 *   Exactness: patches tagged with shape k are sampled on a (patch_samples + 1)^2 grid;
 *   residual = |f(x)| / |grad f(x)| / size_k (a first-order distance to the shape's implicit
 *   surface, relative to the size of that shape's patches).
 *   Weights: the homogeneous weights of all control points, and the denominators at the
 *   samples. Curvature range: k1, k2, H, K over the samples.
 *   Patches of higher degree (s->xp) are read through rg2_surface_eval / rg2_surface_eval_h
 *   and their own control points.
 *   Poles: a sample on a collapsed patch side (all its control points on one point, to 1e-11
 *   of the control box) has no normal or curvature, whatever the evaluator's rounding-level
 *   derivatives say there: its position gap counts, its normal and curvature are skipped (seams)
 *   or left out of the curvature range (patches). The same geometry then gives the same
 *   report in any patch degree.
 *   Threads (opts.threads): the seams and the patches are measured in contiguous chunks, each
 *   into its own partial report, merged in chunk order with the serial comparisons (see
 *   part_merge): the report is the serial one bit for bit, for any thread count.
 */
#include "export_internal.h"
#include "xpatch_util.h"

#include <cjson/cJSON.h>
#include <float.h>
#include <limits.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

void rg2_check_opts_default(rg2_check_opts *o)
{
    o->seam_samples = 16;
    o->patch_samples = 12;
    o->tol_g0 = 1e-12;
    o->tol_g1 = 1e-10;
    o->tol_g2 = 1e-8;
    o->tol_exact = 1e-11;
    o->threads = 0;
    o->crossing_density = 0;
    o->surface_base = 0;
}

static double dot3(const double *a, const double *b) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }
static double norm3(const double *a) { return sqrt(dot3(a, a)); }
static void cross3(const double *a, const double *b, double *c)
{
    c[0] = a[1] * b[2] - a[2] * b[1];
    c[1] = a[2] * b[0] - a[0] * b[2];
    c[2] = a[0] * b[1] - a[1] * b[0];
}

/* Diagonal of the box of the affine control points (positive weights) of a surface. */
static double surface_size(const rg2_surface *s)
{
    double lo[3], hi[3];
    if (!rg2__surface_ctrl_box(s, 1, lo, hi) || lo[0] > hi[0])
        return 1.0;
    double d = sqrt((hi[0] - lo[0]) * (hi[0] - lo[0]) + (hi[1] - lo[1]) * (hi[1] - lo[1]) +
                    (hi[2] - lo[2]) * (hi[2] - lo[2]));
    return d > 0 ? d : 1.0;
}

/* Normal curvature of e in the 3D tangent direction t (projected on the tangent plane). */
static double kn_dir(const rg2_eval *e, const double t[3])
{
    double E = dot3(e->su, e->su), F = dot3(e->su, e->sv), G = dot3(e->sv, e->sv);
    double r1 = dot3(t, e->su), r2 = dot3(t, e->sv), det = E * G - F * F;
    if (!(det > 0))
        return 0;
    return rg2_eval_normal_curvature(e, (G * r1 - F * r2) / det, (E * r2 - F * r1) / det);
}

/* Whether the first fundamental form of e is usable: finite and positive definite (at sizes
 * beyond ~1e77 E G - F^2 overflows and no curvature can be computed). */
static int metric_ok(const rg2_eval *e)
{
    double E = dot3(e->su, e->su), F = dot3(e->su, e->sv), G = dot3(e->sv, e->sv), det = E * G - F * F;
    return det > 0 && isfinite(det);
}

typedef struct {
    int surf, dir, pi, pj, qi, qj;
    double t;
} seam_at;

static void gap_set(rg2_check_gap *g, double value, const seam_at *at, const double p[3])
{
    g->value = value;
    g->surf = at->surf;
    g->seam_dir = at->dir;
    g->pi = at->pi;
    g->pj = at->pj;
    g->qi = at->qi;
    g->qj = at->qj;
    g->t = at->t;
    memcpy(g->p, p, sizeof g->p);
}

static void gap_update(rg2_check_gap *g, double value, const seam_at *at, const double p[3])
{
    if (!isnan(g->value) && !(value <= g->value)) /* NaN sticks: a broken seam cannot hide */
        gap_set(g, value, at, p);
}

/* A sample that is no measurement: counted; the first one's place kept (over: its rounding
 * bound over the measurable limits, +inf for an undefined normal or metric). */
static void unmeasured_note(rg2_check_report *r, const seam_at *at, const double p[3], double over)
{
    if (r->unmeasured++ == 0)
        gap_set(&r->unmeasured_at, over, at, p);
}

/* Whether (u, v) lies on a side of a patch whose collapsed-side bits (0 v=0, 1 u=1, 2 v=1,
 * 3 u=0) are c. */
static int on_collapsed(unsigned c, double u, double v)
{
    return ((c & 1u) && v == 0.0) || ((c & 2u) && u == 1.0) || ((c & 4u) && v == 1.0) || ((c & 8u) && u == 0.0);
}

/* Spread (diagonal of the box) of the affine control points of row `b` (dir 0: the points
 * (a, b), a = 0..du, a u-row) or column `a` (dir 1: (a, b), b = 0..dv) of patch k; +inf when a
 * weight is not positive. */
static double ctrl_line_spread(const rg2_surface *s, size_t k, int dir, int idx)
{
    int du, dv;
    rg2__patch_degree(s, k, &du, &dv);
    double lo[3] = {DBL_MAX, DBL_MAX, DBL_MAX}, hi[3] = {-DBL_MAX, -DBL_MAX, -DBL_MAX};
    int n = dir == 0 ? du : dv;
    for (int m = 0; m <= n; m++) {
        const double *h = dir == 0 ? rg2__patch_ctrl(s, k, m, idx) : rg2__patch_ctrl(s, k, idx, m);
        if (!(h[3] > 0))
            return HUGE_VAL;
        for (int d = 0; d < 3; d++) {
            lo[d] = fmin(lo[d], h[d] / h[3]);
            hi[d] = fmax(hi[d], h[d] / h[3]);
        }
    }
    double d2 = 0;
    for (int d = 0; d < 3; d++)
        d2 += (hi[d] - lo[d]) * (hi[d] - lo[d]);
    return sqrt(d2);
}

/* The genuinely collapsed sides of patch (pi, pj) (bits as on_collapsed): a side is a pole when
 * its control points coincide to 1e-11 of the widest control line parallel to it in the same
 * patch, and that line is longer than 1e-11 of the patch's largest coordinate (rounding). A
 * patch that is thin everywhere (all parallel lines short: a band of height 1e-95) has no pole:
 * its undefined normals are a failure, not a pole. */
static unsigned pole_sides(const rg2_surface *s, int pi, int pj)
{
    size_t k = (size_t)pi * (size_t)s->nv + (size_t)pj;
    int du, dv;
    rg2__patch_degree(s, k, &du, &dv);
    unsigned c = 0;
    /* the parallel lines must be wider than the rounding of the coordinates (a thin band whose
     * width is rounding noise is no fan) */
    double floor = 0;
    for (int a = 0; a <= du; a++)
        for (int b = 0; b <= dv; b++) {
            const double *h = rg2__patch_ctrl(s, k, a, b);
            for (int d = 0; d < 3; d++)
                floor = fmax(floor, fabs(h[d] / h[3]));
        }
    floor *= 1e-11;
    /* sides 0 (v = 0: u-row b = 0) and 2 (v = 1: row b = dv); sides 3 (u = 0: column 0), 1 (u = 1) */
    for (int dir = 0; dir < 2; dir++) {
        int n = dir == 0 ? dv : du;
        double wide = 0;
        for (int m = 1; m < n; m++)
            wide = fmax(wide, ctrl_line_spread(s, k, dir, m));
        double first = ctrl_line_spread(s, k, dir, 0), last = ctrl_line_spread(s, k, dir, n);
        double w0 = fmax(wide, last), w1 = fmax(wide, first); /* parallel lines other than the side */
        if (w0 > floor && w0 < HUGE_VAL && first <= 1e-11 * w0)
            c |= dir == 0 ? 1u : 8u;
        if (w1 > floor && w1 < HUGE_VAL && last <= 1e-11 * w1)
            c |= dir == 0 ? 4u : 2u;
    }
    return c;
}

/* A first-order bound on the rounding error of an evaluation (eval.c's quotient rule): the
 * homogeneous sums carry (du + dv + 3) eps times the sums of the absolute terms, propagated
 * through p, the first and second derivatives and the normal. Next to a pole the derivative
 * along the collapsed side is a difference of O(1) terms that is O(v): this bound grows like
 * 1 / v (normal) and 1 / v^2 (curvature), as the measured seam gaps do there. */
typedef struct {
    double su, sv, suu, suv, svv; /* Euclidean norms of the error bounds */
    double n;                     /* angle error of the unit normal */
} eval_err;

static void eval_bound(const rg2_surface *s, int pi, int pj, double u, double v, const rg2_eval *e, eval_err *out)
{
    size_t k = (size_t)pi * (size_t)s->nv + (size_t)pj;
    int du, dv;
    rg2__patch_degree(s, k, &du, &dv);
    double Bu[RG2_MAX_DEGREE + 1], Du[RG2_MAX_DEGREE + 1], DDu[RG2_MAX_DEGREE + 1];
    double Bv[RG2_MAX_DEGREE + 1], Dv[RG2_MAX_DEGREE + 1], DDv[RG2_MAX_DEGREE + 1];
    rg2__bern(du, u, Bu, Du, DDu);
    rg2__bern(dv, v, Bv, Dv, DDv);
    double H[6][4], A[6][4] = {{0}};
    rg2_surface_eval_h(s, pi, pj, u, v, H);
    for (int a = 0; a <= du; a++)
        for (int b = 0; b <= dv; b++) {
            const double *h = rg2__patch_ctrl(s, k, a, b);
            double f[6] = {fabs(Bu[a] * Bv[b]),  fabs(Du[a] * Bv[b]),  fabs(Bu[a] * Dv[b]),
                           fabs(DDu[a] * Bv[b]), fabs(Du[a] * Dv[b]), fabs(Bu[a] * DDv[b])};
            for (int r = 0; r < 6; r++)
                for (int d = 0; d < 4; d++)
                    A[r][d] += fabs(h[d]) * f[r];
        }
    const double ep = DBL_EPSILON, g = (du + dv + 3) * ep;
    double iW = 1.0 / fabs(H[0][3]), dH[6][4];
    for (int r = 0; r < 6; r++)
        for (int d = 0; d < 4; d++)
            dH[r][d] = g * A[r][d];
    double bsu[3], bsv[3], bsuu[3], bsuv[3], bsvv[3];
    for (int d = 0; d < 3; d++) {
        double p = fabs(e->p[d]), su = fabs(e->su[d]), sv = fabs(e->sv[d]);
        double bp = (dH[0][d] + p * dH[0][3]) * iW + ep * p;
        bsu[d] = (dH[1][d] + fabs(H[1][3]) * bp + p * dH[1][3] + ep * (fabs(H[1][d]) + fabs(H[1][3]) * p)) * iW;
        bsv[d] = (dH[2][d] + fabs(H[2][3]) * bp + p * dH[2][3] + ep * (fabs(H[2][d]) + fabs(H[2][3]) * p)) * iW;
        bsuu[d] = (dH[3][d] + 2 * fabs(H[1][3]) * bsu[d] + 2 * su * dH[1][3] + fabs(H[3][3]) * bp + p * dH[3][3] +
                   ep * (fabs(H[3][d]) + 2 * fabs(H[1][3]) * su + fabs(H[3][3]) * p)) * iW;
        bsuv[d] = (dH[4][d] + fabs(H[1][3]) * bsv[d] + sv * dH[1][3] + fabs(H[2][3]) * bsu[d] + su * dH[2][3] +
                   fabs(H[4][3]) * bp + p * dH[4][3] +
                   ep * (fabs(H[4][d]) + fabs(H[1][3]) * sv + fabs(H[2][3]) * su + fabs(H[4][3]) * p)) * iW;
        bsvv[d] = (dH[5][d] + 2 * fabs(H[2][3]) * bsv[d] + 2 * sv * dH[2][3] + fabs(H[5][3]) * bp + p * dH[5][3] +
                   ep * (fabs(H[5][d]) + 2 * fabs(H[2][3]) * sv + fabs(H[5][3]) * p)) * iW;
    }
    out->su = norm3(bsu);
    out->sv = norm3(bsv);
    out->suu = norm3(bsuu);
    out->suv = norm3(bsuv);
    out->svv = norm3(bsvv);
    double c[3];
    cross3(e->su, e->sv, c);
    double lc = norm3(c);
    out->n = lc > 0 ? (norm3(e->su) * out->sv + norm3(e->sv) * out->su) / lc + 4 * ep : HUGE_VAL;
}

/* Bound on the rounding error of kn_dir(e, t) from the bounds b of e. */
static double kn_bound(const rg2_eval *e, const eval_err *b, const double t[3])
{
    double E = dot3(e->su, e->su), F = dot3(e->su, e->sv), G = dot3(e->sv, e->sv);
    double r1 = dot3(t, e->su), r2 = dot3(t, e->sv), det = E * G - F * F;
    if (!(det > 0))
        return HUGE_VAL;
    double a = (G * r1 - F * r2) / det, c = (E * r2 - F * r1) / det, T[3], d2[3];
    for (int k = 0; k < 3; k++) {
        T[k] = a * e->su[k] + c * e->sv[k];
        d2[k] = a * a * e->suu[k] + 2 * a * c * e->suv[k] + c * c * e->svv[k];
    }
    double tt = dot3(T, T), lt = sqrt(tt);
    if (!(tt > 0))
        return HUGE_VAL;
    double kn = dot3(d2, e->n) / tt, a2 = fabs(a), c2 = fabs(c);
    double dT = (a2 * b->su + c2 * b->sv) / lt + 4 * DBL_EPSILON * (E + G) / sqrt(det); /* direction */
    return (a2 * a2 * b->suu + 2 * a2 * c2 * b->suv + c2 * c2 * b->svv + norm3(d2) * b->n) / tt +
           2 * fabs(kn) * (a2 * b->su + c2 * b->sv) / lt + fabs(e->k1 - e->k2) * dT;
}

/* One side of a seam point: the patch, its parameters, its evaluation and its pole sides. */
typedef struct {
    int i, j;
    double u, v;
    unsigned poles;
    rg2_eval e;
} seam_side;

/* Worst gap / own limit of a sample measured next to a pole against its rounding bound. */
static void near_update(rg2_check_gap *g, double *tol_max, double value, double limit, const seam_at *at,
                        const double p[3])
{
    *tol_max = fmax(*tol_max, limit);
    gap_update(g, value / limit, at, p);
}

/* Parametric distance of a seam side's point to the nearest pole side of its patch (1: none). */
static double pole_distance(const seam_side *x)
{
    double d = 1.0;
    if (x->poles & 1u) d = fmin(d, x->v);
    if (x->poles & 2u) d = fmin(d, 1.0 - x->u);
    if (x->poles & 4u) d = fmin(d, 1.0 - x->v);
    if (x->poles & 8u) d = fmin(d, x->u);
    return d;
}

/* Closer than POLE_BLUR to a pole (parametric), a sample whose rounding bound exceeds the limits
 * below is a floating-point limit (counted, reported, no verdict). So is one further away whose
 * bound is the pole's: the normal's bound grows like 1 / d toward a pole and the curvature's like
 * 1 / d^2 (b d and b d^2 are constant to 1 % along the pole patches of every example and of a
 * sphere of 1200 arcs, measured), and the sample's own bounds, carried out by those laws, are
 * back within the limits by POLE_REACH from the pole. Otherwise a failure. */
#define POLE_BLUR 1e-3
#define POLE_REACH 0.25
/* A G1 limit above this (rad) or a G2 limit above this (relative) is no measurement. */
#define NEAR_POLE_MAX_G1 1e-4
#define NEAR_POLE_MAX_G2 1e-2

/* Away from poles, a patch is ill-conditioned at a sample when the rounding bound exceeds this
 * (rad / relative): about 100 times the bounds of well-conditioned examples (~1e-14). */
#define ILL_MIN_G1 1e-12
#define ILL_MIN_G2 1e-10

/* One seam point: L at the end of its transversal parameter, R at the start. */
static void seam_point(rg2_check_report *r, const rg2_surface *s, const seam_side *Ls, const seam_side *Rs, int dir,
                       double size, const seam_at *at)
{
    const rg2_eval *L = &Ls->e, *R = &Rs->e;
    const rg2_check_opts *o = &r->opts;
    r->seam_samples++;
    double d[3] = {L->p[0] - R->p[0], L->p[1] - R->p[1], L->p[2] - R->p[2]};
    gap_update(&r->g0, norm3(d) / size, at, L->p);
    if (on_collapsed(Ls->poles, Ls->u, Ls->v) || on_collapsed(Rs->poles, Rs->u, Rs->v)) {
        r->skipped++;
        r->pole_samples++;
        return;
    }
    const double *along = dir == 0 ? L->sv : L->su;
    double la = norm3(along);
    if (((L->flags | R->flags) & RG2_EVAL_NORMAL_UNDEFINED) || !(la > 0) || !metric_ok(L) || !metric_ok(R)) {
        r->skipped++;
        unmeasured_note(r, at, L->p, INFINITY);
        return;
    }
    double c[3];
    cross3(L->n, R->n, c);
    double angle = atan2(norm3(c), dot3(L->n, R->n));
    double t1[3] = {along[0] / la, along[1] / la, along[2] / la}, t2[3], dirs[6][3];
    cross3(L->n, t1, t2);
    double kscale = fmax(fmax(fabs(L->k1), fabs(L->k2)), 1.0 / size), worst = 0;
    for (int q = 0; q < 6; q++) {
        double ph = M_PI * q / 6.0;
        for (int k = 0; k < 3; k++)
            dirs[q][k] = cos(ph) * t1[k] + sin(ph) * t2[k];
        double jump = fabs(kn_dir(L, dirs[q]) - kn_dir(R, dirs[q])) / kscale;
        if (!(jump <= worst))
            worst = jump;
    }
    /* the limits are the rounding bounds of the two evaluations where those are larger: next to
     * a pole (the normal loses digits like 1/v, the curvature like 1/v^2) always; elsewhere when
     * a gap exceeds its limit, on an ill-conditioned patch (a shape flattened by its placement,
     * say; a well-conditioned sample within the limits needs no bound) */
    int pole_patch = (Ls->poles | Rs->poles) != 0;
    double round1 = 0, round2 = 0; /* rounding bounds of the two evaluations (0: not needed) */
    if (pole_patch || !(angle <= o->tol_g1) || !(worst <= o->tol_g2)) {
        eval_err bL, bR;
        eval_bound(s, Ls->i, Ls->j, Ls->u, Ls->v, L, &bL);
        eval_bound(s, Rs->i, Rs->j, Rs->u, Rs->v, R, &bR);
        round1 = bL.n + bR.n;
        for (int q = 0; q < 6; q++)
            round2 = fmax(round2, (kn_bound(L, &bL, dirs[q]) + kn_bound(R, &bR, dirs[q])) / kscale);
        if (!pole_patch) { /* a well-conditioned patch keeps the caller's limits, even 0 */
            if (round1 <= ILL_MIN_G1)
                round1 = 0;
            if (round2 <= ILL_MIN_G2)
                round2 = 0;
        }
    }
    /* the rounding bounds decide whether the sample is a measurement at all, whatever limits
     * the caller chose (a looser --tol must not turn measured samples into unmeasured ones) */
    if (!(round1 <= NEAR_POLE_MAX_G1 && round2 <= NEAR_POLE_MAX_G2)) {
        /* rounding hides any gap: within POLE_BLUR of the pole (a floating-point limit, reported),
         * elsewhere a failure */
        r->skipped++;
        double dist = fmin(pole_distance(Ls), pole_distance(Rs));
        /* the distances from the pole at which the bounds are back within the limits, by the
         * pole's laws (a NaN bound: never) */
        double reach1 = dist * (round1 / NEAR_POLE_MAX_G1), reach2 = dist * sqrt(round2 / NEAR_POLE_MAX_G2);
        if (dist < POLE_BLUR || (pole_patch && reach1 <= POLE_REACH && reach2 <= POLE_REACH)) {
            r->pole_unresolved++;
            r->pole_unresolved_dist = fmax(r->pole_unresolved_dist, dist);
        } else {
            unmeasured_note(r, at, L->p,
                            isnan(round1) || isnan(round2)
                                ? NAN
                                : fmax(round1 / NEAR_POLE_MAX_G1, round2 / NEAR_POLE_MAX_G2));
            if (pole_patch) {
                r->unmeasured_pole++;
                r->unmeasured_pole_dist = fmax(r->unmeasured_pole_dist, dist);
            }
        }
        return;
    }
    double lim1 = fmax(o->tol_g1, round1), lim2 = fmax(o->tol_g2, round2);
    if (lim1 > o->tol_g1 || lim2 > o->tol_g2)
        (*(pole_patch ? &r->near_pole : &r->ill_conditioned))++;
    rg2_check_gap *g1r = pole_patch ? &r->g1_pole : &r->g1_ill, *g2r = pole_patch ? &r->g2_pole : &r->g2_ill;
    double *t1r = pole_patch ? &r->near_pole_tol1 : &r->ill_tol1, *t2r = pole_patch ? &r->near_pole_tol2 : &r->ill_tol2;
    if (lim1 > o->tol_g1)
        near_update(g1r, t1r, angle, lim1, at, L->p);
    else
        gap_update(&r->g1, angle, at, L->p);
    if (lim2 > o->tol_g2)
        near_update(g2r, t2r, worst, lim2, at, L->p);
    else
        gap_update(&r->g2, worst, at, L->p);
}

/* The seams of a surface in the order they are measured: per direction (u seams, then v
 * seams), the seam rows a (from 1, or from 0 when the direction is closed; none for one closed
 * patch: its seam is with itself), and b along each row. seam_rows counts the rows of dir. */
static int seam_rows(const rg2_surface *s, int dir)
{
    int nA = dir == 0 ? s->nu : s->nv, closed = dir == 0 ? s->closed_u : s->closed_v;
    return closed ? (nA >= 2 ? nA : 0) : nA - 1;
}

static size_t seam_count(const rg2_surface *s)
{
    return (size_t)seam_rows(s, 0) * (size_t)s->nv + (size_t)seam_rows(s, 1) * (size_t)s->nu;
}

/* Seam k (0 .. seam_count - 1) of surface s: all samples along it. */
static void seam_one(rg2_check_report *r, const rg2_surface *s, int surf, size_t k, double size, int samples)
{
    int dir = 0;
    size_t n0 = (size_t)seam_rows(s, 0) * (size_t)s->nv;
    if (k >= n0) {
        dir = 1;
        k -= n0;
    }
    int nA = dir == 0 ? s->nu : s->nv, nB = dir == 0 ? s->nv : s->nu;
    int closed = dir == 0 ? s->closed_u : s->closed_v;
    int a = (int)(k / (size_t)nB) + (closed ? 0 : 1), b = (int)(k % (size_t)nB), am = (a + nA - 1) % nA;
    r->seams++;
    seam_at at = {surf, dir, dir == 0 ? am : b, dir == 0 ? b : am, dir == 0 ? a : b, dir == 0 ? b : a, 0};
    seam_side L = {.i = at.pi, .j = at.pj, .poles = pole_sides(s, at.pi, at.pj)};
    seam_side R = {.i = at.qi, .j = at.qj, .poles = pole_sides(s, at.qi, at.qj)};
    for (int q = 0; q <= samples; q++) {
        at.t = (double)q / samples;
        L.u = dir == 0 ? 1.0 : at.t;
        L.v = dir == 0 ? at.t : 1.0;
        R.u = dir == 0 ? 0.0 : at.t;
        R.v = dir == 0 ? at.t : 0.0;
        rg2_surface_eval(s, L.i, L.j, L.u, L.v, 2, &L.e);
        rg2_surface_eval(s, R.i, R.j, R.u, R.v, 2, &R.e);
        seam_point(r, s, &L, &R, dir, size, &at);
    }
}

/* Whether the surface folds back between two samples of patch (pi, pj) whose unit normals n0, n1
 * point into opposite half-spaces (n0 . n1 < 0). A smooth bend by more than 90 degrees between
 * the samples splits, on halving, into parts below 90 degrees; a fold (the Jacobian Su x Sv
 * changes sign through zero on the segment) keeps opposite normals across the zero however
 * short the part, or meets the zero itself. Halved FOLD_DEPTH times (a part 1e-12 of the
 * sample spacing): turning by 90 degrees over such a part is a fold for any practical purpose. */
#define FOLD_DEPTH 40
static int folds_between(const rg2_surface *s, int pi, int pj, double u0, double v0, const double n0[3], double u1,
                         double v1, const double n1[3])
{
    double a[3], b[3];
    memcpy(a, n0, sizeof a);
    memcpy(b, n1, sizeof b);
    for (int k = 0; k < FOLD_DEPTH; k++) {
        double um = 0.5 * (u0 + u1), vm = 0.5 * (v0 + v1);
        rg2_eval e;
        rg2_surface_eval(s, pi, pj, um, vm, 1, &e);
        if (e.flags & RG2_EVAL_NORMAL_UNDEFINED)
            return 1; /* the zero of Su x Sv itself */
        if (dot3(a, e.n) < 0) {
            u1 = um;
            v1 = vm;
            memcpy(b, e.n, sizeof b);
        } else if (dot3(e.n, b) < 0) {
            u0 = um;
            v0 = vm;
            memcpy(a, e.n, sizeof a);
        } else
            return 0; /* a bend: both halves turn by less than 90 degrees */
    }
    return 1;
}

/* The sample (u, v) of patch (pi, pj) at point p, into *at. */
static void sample_set(rg2_check_sample *at, int surf, int pi, int pj, double u, double v, const double p[3])
{
    at->surf = surf;
    at->pi = pi;
    at->pj = pj;
    at->u = u;
    at->v = v;
    memcpy(at->p, p, sizeof at->p);
}

/* The sample (u, v) of patch (pi, pj) with principal curvatures k1 >= k2: the report's largest
 * |k| if larger than the one before (strict, so the first in the serial order; a NaN never wins). */
static void kpeak_update(rg2_check_report *r, int surf, int pi, int pj, double u, double v, const double p[3],
                         double k1, double k2)
{
    double k = fabs(k2) > fabs(k1) ? k2 : k1;
    if (fabs(k) > fabs(r->kpeak_k) || (r->kpeak.surf < 0 && !isnan(k))) {
        sample_set(&r->kpeak, surf, pi, pj, u, v, p);
        r->kpeak_k = k;
    }
}

/* A fold or a singular sample at (u, v) of patch (pi, pj): counted, the first one kept. */
static void fold_note(rg2_check_report *r, int *count, int surf, int pi, int pj, double u, double v, const double p[3])
{
    if (r->folds == 0 && r->singular == 0)
        sample_set(&r->fold_at, surf, pi, pj, u, v, p);
    (*count)++;
}

/* Smallest / largest value so far: a NaN sticks (it is reported, never hidden by the values
 * after it). */
static void low_update(double *m, double w)
{
    if (!isnan(*m) && !(w >= *m))
        *m = w;
}

static void high_update(double *m, double w)
{
    if (!isnan(*m) && !(w <= *m))
        *m = w;
}

/* Patch k of s, interior: weights and curvature ranges at the samples, implicit residuals of a
 * tagged patch against its shape, and regularity: a sample away from a pole with no normal
 * (singular), or two neighbouring samples between which the surface folds back (folds_between).
 * nrm holds two rows of S + 1 unit normals (u index a - 1 and a), with a defined-flag each. */
static void patch_one(rg2_check_report *r, const rg2_surface *s, int surf, size_t k,
                      const rg2__implicit *imp, int n_shapes, const double *shape_size, int S, double *nrm,
                      unsigned char *def)
{
    int tag = s->tag ? s->tag[k] : -1;
    r->patches++;
    if (tag < 0)
        r->transitions++;
    else if (tag >= n_shapes)
        r->untagged_bad++;
    else {
        r->exact_patches++;
        r->shapes[tag].patches++;
    }
    int du, dv, pi = (int)(k / (size_t)s->nv), pj = (int)(k % (size_t)s->nv);
    unsigned coll = pole_sides(s, pi, pj);
    rg2__patch_degree(s, k, &du, &dv);
    for (int a = 0; a <= du; a++)
        for (int b = 0; b <= dv; b++) {
            double w = rg2__patch_ctrl(s, k, a, b)[3];
            low_update(&r->wmin, w);
            high_update(&r->wmax, w);
        }
    for (int a = 0; a <= S; a++)
        for (int b = 0; b <= S; b++) {
            double u = (double)a / S, v = (double)b / S, H[6][4];
            rg2_surface_eval_h(s, pi, pj, u, v, H);
            low_update(&r->eval_wmin, H[0][3]);
            rg2_eval e;
            rg2__eval_from_h(H, 2, &e); /* = rg2_surface_eval(s, pi, pj, u, v, 2, &e), from the same H */
            /* regularity: rows a - 1 (slot (a + 1) % 2) and a (slot a % 2) of unit normals */
            double *nc = nrm + 3 * ((size_t)(a % 2) * (size_t)(S + 1) + (size_t)b);
            unsigned char *dc = def + (size_t)(a % 2) * (size_t)(S + 1) + (size_t)b;
            *dc = 0;
            if (!on_collapsed(coll, u, v)) {
                if (e.flags & RG2_EVAL_NORMAL_UNDEFINED)
                    fold_note(r, &r->singular, surf, pi, pj, u, v, e.p);
                else {
                    memcpy(nc, e.n, 3 * sizeof *nc);
                    *dc = 1;
                    const double *nu = nrm + 3 * ((size_t)((a + 1) % 2) * (size_t)(S + 1) + (size_t)b);
                    if (a > 0 && def[(size_t)((a + 1) % 2) * (size_t)(S + 1) + (size_t)b] && dot3(nu, nc) < 0 &&
                        folds_between(s, pi, pj, (double)(a - 1) / S, v, nu, u, v, nc))
                        fold_note(r, &r->folds, surf, pi, pj, u - 0.5 / S, v, e.p);
                    if (b > 0 && dc[-1] && dot3(nc - 3, nc) < 0 &&
                        folds_between(s, pi, pj, u, (double)(b - 1) / S, nc - 3, u, v, nc))
                        fold_note(r, &r->folds, surf, pi, pj, u, v - 0.5 / S, e.p);
                }
            }
            if (!(e.flags & RG2_EVAL_CURVATURE_UNDEFINED) && !on_collapsed(coll, u, v)) {
                r->kmin = fmin(r->kmin, e.k2);
                r->kmax = fmax(r->kmax, e.k1);
                r->Hmin = fmin(r->Hmin, e.H);
                r->Hmax = fmax(r->Hmax, e.H);
                r->Kmin = fmin(r->Kmin, e.K);
                r->Kmax = fmax(r->Kmax, e.K);
                kpeak_update(r, surf, pi, pj, u, v, e.p, e.k1, e.k2);
            }
            if (tag < 0 || tag >= n_shapes)
                continue;
            double g[3], f = rg2__implicit_eval(&imp[tag], e.p, g, NULL), gn = norm3(g);
            if (gn == 0.0)
                continue; /* singular point of the shape (apex): no distance estimate; a NaN point
                             (gradient NaN) goes on and makes the residual NaN, which fails */
            double res = fabs(f) / gn / shape_size[tag];
            rg2_check_shape *cs = &r->shapes[tag];
            if (!isnan(cs->residual) && !(res <= cs->residual)) {
                cs->residual = res;
                void *loc = rg2__c_numeric_begin(); /* "u=0.5", whatever the host's locale (this thread) */
                snprintf(cs->where, sizeof cs->where, "surface %d patch (%d,%d) u=%.3g v=%.3g", surf, pi, pj,
                         u, v);
                rg2__c_numeric_end(loc);
            }
        }
}

/* ---------------------------------------------------------------- threads
 *
 * The seams and the patches of all surfaces form two flat lists, surface by surface in the
 * serial order (seams and patches write disjoint fields of the report, so the serial code's
 * order between them is immaterial). With threads each list is cut into contiguous chunks; a
 * chunk measures its items into its own partial report, and the partials are merged in chunk
 * order with the serial code's own comparisons. The report then equals the serial one bit for
 * bit for any chunking, and so for any thread count:
 *   counts (patches, seams, samples, skipped, near_pole, folds, ...): integer sums;
 *   gaps (g0, g1, g2 and the next-to-a-pole and ill-conditioned ones) and shape residuals: the
 *     partial's worst goes through the serial rule (strict >, a NaN sticks), which keeps the
 *     first worst sample in the serial order, its location with it;
 *   fold_at: the first fold or singular sample of the first chunk that has one;
 *   kpeak: a chunk's largest |k| replaces the one before only if strictly larger (or the first);
 *   largest limits (near_pole_tol*, ill_tol*) and curvature ranges: fmax / fmin as serially
 *     (NaN ignored, each chunk from the serial start value);
 *   weights (wmin, wmax, eval_wmin): low_update / high_update, as serially (a NaN sticks).
 * No floating-point sum is taken anywhere. */
#ifdef _OPENMP
#include <omp.h>
#define CHECK_OMP(x) _Pragma(x)
#else
#define CHECK_OMP(x)
#endif
#define CHECK_MAX_THREADS 64
#define CHECK_CHUNKS_PER_THREAD 8 /* chunks of each list per thread: the dynamic schedule's slack */

typedef struct {
    const rg2_surface *surfs;
    int n, n_shapes, seam_samples, patch_samples;
    int base;                           /* the number the report gives surface 0 (surface_base) */
    const size_t *seam_off, *patch_off; /* first seam / patch of each surface in the flat lists (n + 1) */
    const double *size;                 /* surface_size of each surface */
    const rg2__implicit *imp;
    const double *shape_size;
} check_job;

typedef struct {
    rg2_check_report r; /* the chunk's measurements (patch chunks: r.shapes, their own n_shapes entries) */
    int is_seams;       /* a chunk of the seam list (else of the patch list) */
    size_t lo, hi;      /* its items */
    int oom;            /* its thread had no memory for the normals of a patch */
} check_part;

/* Seams lo .. hi - 1 of the flat list, into r. */
static void run_seams(rg2_check_report *r, const check_job *J, size_t lo, size_t hi)
{
    int s = 0;
    for (size_t g = lo; g < hi; g++) {
        while (g >= J->seam_off[s + 1])
            s++;
        seam_one(r, &J->surfs[s], J->base + s, g - J->seam_off[s], J->size[s], J->seam_samples);
    }
}

/* Patches lo .. hi - 1 of the flat list, into r (nrm, def: patch_one's rows of normals). */
static void run_patches(rg2_check_report *r, const check_job *J, size_t lo, size_t hi, double *nrm,
                        unsigned char *def)
{
    int s = 0;
    for (size_t g = lo; g < hi; g++) {
        while (g >= J->patch_off[s + 1])
            s++;
        patch_one(r, &J->surfs[s], J->base + s, g - J->patch_off[s], J->imp, J->n_shapes, J->shape_size,
                  J->patch_samples, nrm, def);
    }
}

/* A chunk's worst gap after everything before it: gap_update with the chunk's worst. */
static void gap_merge(rg2_check_gap *g, const rg2_check_gap *c)
{
    seam_at at = {c->surf, c->seam_dir, c->pi, c->pj, c->qi, c->qj, c->t};
    gap_update(g, c->value, &at, c->p);
}

/* Merge chunk c into r, the chunks before it already merged (see the comment above). */
static void part_merge(rg2_check_report *r, const check_part *c)
{
    const rg2_check_report *x = &c->r;
    if (c->is_seams) {
        r->seams += x->seams;
        r->seam_samples += x->seam_samples;
        r->skipped += x->skipped;
        r->pole_samples += x->pole_samples;
        if (r->unmeasured == 0 && x->unmeasured > 0) /* the first in seam order */
            r->unmeasured_at = x->unmeasured_at;
        r->unmeasured += x->unmeasured;
        r->unmeasured_pole += x->unmeasured_pole;
        r->unmeasured_pole_dist = fmax(r->unmeasured_pole_dist, x->unmeasured_pole_dist);
        r->near_pole += x->near_pole;
        r->pole_unresolved += x->pole_unresolved;
        r->pole_unresolved_dist = fmax(r->pole_unresolved_dist, x->pole_unresolved_dist);
        r->ill_conditioned += x->ill_conditioned;
        gap_merge(&r->g0, &x->g0);
        gap_merge(&r->g1, &x->g1);
        gap_merge(&r->g2, &x->g2);
        gap_merge(&r->g1_pole, &x->g1_pole);
        gap_merge(&r->g2_pole, &x->g2_pole);
        gap_merge(&r->g1_ill, &x->g1_ill);
        gap_merge(&r->g2_ill, &x->g2_ill);
        r->near_pole_tol1 = fmax(r->near_pole_tol1, x->near_pole_tol1);
        r->near_pole_tol2 = fmax(r->near_pole_tol2, x->near_pole_tol2);
        r->ill_tol1 = fmax(r->ill_tol1, x->ill_tol1);
        r->ill_tol2 = fmax(r->ill_tol2, x->ill_tol2);
        return;
    }
    if (x->patches == 0)
        return;
    r->patches += x->patches;
    r->transitions += x->transitions;
    r->exact_patches += x->exact_patches;
    r->untagged_bad += x->untagged_bad;
    low_update(&r->wmin, x->wmin);
    high_update(&r->wmax, x->wmax);
    low_update(&r->eval_wmin, x->eval_wmin);
    if (r->folds == 0 && r->singular == 0 && (x->folds || x->singular))
        r->fold_at = x->fold_at;
    r->folds += x->folds;
    r->singular += x->singular;
    r->kmin = fmin(r->kmin, x->kmin);
    r->kmax = fmax(r->kmax, x->kmax);
    r->Hmin = fmin(r->Hmin, x->Hmin);
    r->Hmax = fmax(r->Hmax, x->Hmax);
    r->Kmin = fmin(r->Kmin, x->Kmin);
    r->Kmax = fmax(r->Kmax, x->Kmax);
    if (x->kpeak.surf >= 0 && (r->kpeak.surf < 0 || fabs(x->kpeak_k) > fabs(r->kpeak_k))) {
        r->kpeak = x->kpeak;
        r->kpeak_k = x->kpeak_k;
    }
    for (int k = 0; k < r->n_shapes; k++) {
        rg2_check_shape *cs = &r->shapes[k];
        const rg2_check_shape *xs = &x->shapes[k];
        cs->patches += xs->patches;
        if (!isnan(cs->residual) && !(xs->residual <= cs->residual)) {
            cs->residual = xs->residual;
            memcpy(cs->where, xs->where, sizeof cs->where);
        }
    }
}

/* The measurements of J on nt threads (nt > 1) into r (its start values set): chunks, then
 * their merge in order. */
static rg2_status run_threads(rg2_check_report *r, const check_job *J, size_t n_seams, size_t n_patches, int nt,
                              rg2_error *err)
{
    size_t per = (size_t)nt * CHECK_CHUNKS_PER_THREAD;
    size_t cs = n_seams < per ? n_seams : per, cp = n_patches < per ? n_patches : per;
    int nc = (int)(cs + cp);
    if (nt > nc)
        nt = nc;
    check_part *parts = rg2__calloc((size_t)nc, sizeof *parts);
    int oom = !parts;
    /* patch chunks first: they are the heavier items, taken first by the dynamic schedule */
    for (int c = 0; c < nc && !oom; c++) {
        check_part *P = &parts[c];
        P->r.opts = r->opts;
        P->r.n_shapes = r->n_shapes;
        P->is_seams = (size_t)c >= cp;
        size_t q = P->is_seams ? (size_t)c - cp : (size_t)c, m = P->is_seams ? cs : cp;
        size_t items = P->is_seams ? n_seams : n_patches;
        P->lo = items * q / m; /* contiguous, in order, none empty (m <= items) */
        P->hi = items * (q + 1) / m;
        if (!P->is_seams) {
            P->r.shapes = rg2__calloc((size_t)(r->n_shapes > 0 ? r->n_shapes : 1), sizeof *P->r.shapes);
            oom = !P->r.shapes;
            P->r.wmin = P->r.eval_wmin = DBL_MAX; /* as the serial start (rg2_check) */
            P->r.wmax = -DBL_MAX;
            P->r.kmin = P->r.Hmin = P->r.Kmin = DBL_MAX;
            P->r.kmax = P->r.Hmax = P->r.Kmax = -DBL_MAX;
            P->r.kpeak.surf = -1;
            P->r.kpeak_k = 0;
        }
    }
    if (!oom) {
        size_t row = (size_t)J->patch_samples + 1;
        CHECK_OMP("omp parallel num_threads(nt)")
        {
            double *nrm = rg2__calloc(2 * row * 3, sizeof *nrm);
            unsigned char *def = rg2__calloc(2 * row, 1);
            CHECK_OMP("omp for schedule(dynamic, 1)")
            for (int c = 0; c < nc; c++) {
                check_part *P = &parts[c];
                if (P->is_seams)
                    run_seams(&P->r, J, P->lo, P->hi);
                else if (!nrm || !def)
                    P->oom = 1;
                else
                    run_patches(&P->r, J, P->lo, P->hi, nrm, def);
            }
            free(nrm);
            free(def);
        }
        for (int c = 0; c < nc; c++)
            oom |= parts[c].oom;
    }
    /* in the lists' order: the seam chunks, then the patch chunks (disjoint fields) */
    for (int c = 0; c < nc && !oom; c++)
        part_merge(r, &parts[((size_t)c + cp) % (size_t)nc]);
    for (int c = 0; parts && c < nc; c++)
        free(parts[c].r.shapes);
    free(parts);
    if (oom)
        return rg2__fail(err, RG2_ENOMEM, "check: out of memory for the partial reports of %d threads", nt);
    return RG2_OK;
}

rg2_status rg2_check(const rg2_surface *surfs, int n, const rg2_shape *shapes, const char *const *labels,
                     int n_shapes, const rg2_check_opts *o, rg2_check_report *out, rg2_error *err)
{
    rg2_check_opts def;
    if (!o) {
        rg2_check_opts_default(&def);
        o = &def;
    }
    if (!out)
        return rg2__fail(err, RG2_EINVAL, "check: no report");
    memset(out, 0, sizeof *out);
    if (!surfs || n <= 0)
        return rg2__fail(err, RG2_EINVAL, "check: no surfaces (n = %d)", n);
    if (n_shapes < 0 || (n_shapes > 0 && !shapes))
        return rg2__fail(err, RG2_EINVAL, "check: %d shapes without a shape list", n_shapes);
    for (int k = 0; k < n_shapes; k++) /* (an unknown kind measured NaN residuals: loud, but no refusal) */
        if (!rg2_shape_name(shapes[k].kind))
            return rg2__fail(err, RG2_EINVAL, "check: shapes[%d]%s%s%s has an unknown kind %d", k,
                             labels && labels[k] ? " ('" : "", labels && labels[k] ? labels[k] : "",
                             labels && labels[k] ? "')" : "", (int)shapes[k].kind);
    if (o->seam_samples < 1 || o->seam_samples > 10000 || o->patch_samples < 1 || o->patch_samples > 1000)
        return rg2__fail(err, RG2_EINVAL, "check: samples %d per seam / %d per patch outside 1..10000 / 1..1000",
                         o->seam_samples, o->patch_samples);
    if (o->threads < 0)
        return rg2__fail(err, RG2_EINVAL, "check: threads %d < 0 (0: the OpenMP default)", o->threads);
    if (o->crossing_density < 0 || o->crossing_density > 1000)
        return rg2__fail(err, RG2_EINVAL, "check: crossing_density %d outside 0..1000 (0: no crossing search)",
                         o->crossing_density);
    if (o->surface_base < 0 || o->surface_base > INT_MAX - n)
        return rg2__fail(err, RG2_EINVAL, "check: surface_base %d outside 0..%d (INT_MAX - %d surfaces)",
                         o->surface_base, INT_MAX - n, n);
    const double tol[4] = {o->tol_g0, o->tol_g1, o->tol_g2, o->tol_exact};
    static const char *const tol_name[4] = {"tol_g0", "tol_g1", "tol_g2", "tol_exact"};
    for (int k = 0; k < 4; k++) /* (a NaN or negative limit would fail its promise whatever the surface) */
        if (!isfinite(tol[k]) || !(tol[k] >= 0))
            return rg2__fail(err, RG2_EINVAL, "check: %s = %g, must be a finite number >= 0", tol_name[k], tol[k]);
    for (int s = 0; s < n; s++) {
        if (surfs[s].nu <= 0 || surfs[s].nv <= 0 || !surfs[s].patch)
            return rg2__fail(err, RG2_EINVAL, "check: surface %d has no patches", o->surface_base + s);
        if (!surfs[s].bu || !surfs[s].bv)
            return rg2__fail(err, RG2_EINVAL, "check: surface %d has no junction scalars", o->surface_base + s);
    }
    /* the report counts samples in ints: each kind's total (and so every count of it, folds at
       most twice the patch samples) stays below RG2_MAX_CHECK_SAMPLES, minutes of work per thread */
    double seam_total = 0, patch_total = 0;
    for (int s = 0; s < n; s++) {
        seam_total += (double)seam_count(&surfs[s]) * (o->seam_samples + 1.0);
        patch_total += (double)surfs[s].nu * surfs[s].nv * (o->patch_samples + 1.0) * (o->patch_samples + 1.0);
    }
    if (seam_total > RG2_MAX_CHECK_SAMPLES)
        return rg2__fail(err, RG2_ELIMIT, "check: %.0f seam samples (%d per seam) exceed the limit of %d: fewer "
                         "samples per seam (seam_samples; rg2 check --samples)", seam_total, o->seam_samples + 1,
                         RG2_MAX_CHECK_SAMPLES);
    if (patch_total > RG2_MAX_CHECK_SAMPLES)
        return rg2__fail(err, RG2_ELIMIT, "check: %.0f patch samples (%d x %d per patch) exceed the limit of %d: "
                         "fewer samples per patch (patch_samples)", patch_total, o->patch_samples + 1,
                         o->patch_samples + 1, RG2_MAX_CHECK_SAMPLES);
    out->opts = *o;
    out->surfaces = n;
    out->n_shapes = n_shapes;
    out->shapes = rg2__calloc((size_t)(n_shapes > 0 ? n_shapes : 1), sizeof *out->shapes);
    double *shape_size = rg2__calloc((size_t)(n_shapes > 0 ? n_shapes : 1), sizeof *shape_size);
    double *shape_box = rg2__calloc((size_t)(n_shapes > 0 ? n_shapes : 1), 6 * sizeof *shape_box);
    rg2__implicit *imp = rg2__calloc((size_t)(n_shapes > 0 ? n_shapes : 1), sizeof *imp);
    if (!out->shapes || !shape_size || !shape_box || !imp) {
        free(shape_size);
        free(shape_box);
        free(imp);
        rg2_check_report_free(out);
        return rg2__fail(err, RG2_ENOMEM, "check: out of memory for %d shapes", n_shapes);
    }
    for (int k = 0; k < n_shapes; k++) {
        rg2__implicit_prep(&shapes[k], &imp[k]); /* the placement inverted once per shape */
        out->shapes[k].shape = k;
        const char *name = rg2_shape_name(shapes[k].kind);
        if (snprintf(out->shapes[k].label, sizeof out->shapes[k].label, "%s",
                     labels && labels[k] ? labels[k] : (name ? name : "shape")) >= (int)sizeof out->shapes[k].label)
            rg2__utf8_cut(out->shapes[k].label); /* (a long label, cut between UTF-8 characters) */
        snprintf(out->shapes[k].where, sizeof out->shapes[k].where, "-");
        for (int d = 0; d < 3; d++) {
            shape_box[6 * k + d] = INFINITY; /* (not DBL_MAX: -DBL_MAX - DBL_MAX overflows) */
            shape_box[6 * k + 3 + d] = -INFINITY;
        }
    }
    /* the size of each shape: box of its tagged patches' control points */
    double lo[3] = {DBL_MAX, DBL_MAX, DBL_MAX}, hi[3] = {-DBL_MAX, -DBL_MAX, -DBL_MAX};
    for (int s = 0; s < n; s++) {
        size_t np = (size_t)surfs[s].nu * (size_t)surfs[s].nv;
        for (size_t k = 0; k < np; k++) {
            int tag = surfs[s].tag ? surfs[s].tag[k] : -1, du, dv;
            rg2__patch_degree(&surfs[s], k, &du, &dv);
            for (int a = 0; a < (du + 1) * (dv + 1); a++) {
                const double *h = rg2__patch_ctrl(&surfs[s], k, a / (dv + 1), a % (dv + 1));
                if (!(h[3] > 0))
                    continue;
                for (int d = 0; d < 3; d++) {
                    double x = h[d] / h[3];
                    lo[d] = fmin(lo[d], x);
                    hi[d] = fmax(hi[d], x);
                    if (tag >= 0 && tag < n_shapes) {
                        shape_box[6 * tag + d] = fmin(shape_box[6 * tag + d], x);
                        shape_box[6 * tag + 3 + d] = fmax(shape_box[6 * tag + 3 + d], x);
                    }
                }
            }
        }
    }
    out->size = lo[0] <= hi[0] ? sqrt((hi[0] - lo[0]) * (hi[0] - lo[0]) + (hi[1] - lo[1]) * (hi[1] - lo[1]) +
                                      (hi[2] - lo[2]) * (hi[2] - lo[2]))
                               : 1.0;
    for (int k = 0; k < n_shapes; k++) {
        double d2 = 0;
        for (int d = 0; d < 3; d++) { /* a shape without patches: -inf - inf = -inf, exactly */
            double e = shape_box[6 * k + 3 + d] - shape_box[6 * k + d];
            d2 += e > 0 ? e * e : 0;
        }
        shape_size[k] = d2 > 0 ? sqrt(d2) : out->size;
        /* the rounding of the coordinates themselves: a residual relative to the shape's size
         * cannot be below about DBL_EPSILON x |x| / size where the shape lies far from the
         * origin (a cylinder of radius 1e-3 at (100, 100, 0): 1.9e-11 of its size) */
        double mag = 0;
        for (int d = 0; d < 6 && d2 > 0; d++)
            mag = fmax(mag, fabs(shape_box[6 * k + d]));
        /* (only past its own size from the origin: near it, the limit stays tol_exact as given,
         * --tol exact=0 included) */
        double floor_k = !(mag > shape_size[k]) ? 0
                         : mag / 1e100 > shape_size[k] ? 1 /* (no overflow: past 1e100 nothing is measured) */
                                                        : RG2_CHECK_COORD_ROUNDING * DBL_EPSILON * mag / shape_size[k];
        out->shapes[k].limit = floor_k > o->tol_exact ? floor_k : o->tol_exact;
    }
    out->wmin = out->eval_wmin = DBL_MAX;
    out->wmax = -DBL_MAX;
    out->kmin = out->Hmin = out->Kmin = DBL_MAX;
    out->kmax = out->Hmax = out->Kmax = -DBL_MAX;
    out->kpeak.surf = -1;
    out->kpeak_k = 0;
    /* a gap no sample exceeds (0 everywhere) keeps this place: the first surface's number */
    rg2_check_gap *gaps[8] = {&out->g0,      &out->g1,      &out->g2,     &out->g1_pole,
                              &out->g2_pole, &out->g1_ill, &out->g2_ill, &out->unmeasured_at};
    for (int k = 0; k < 8; k++)
        gaps[k]->surf = o->surface_base;
    out->fold_at.surf = o->surface_base;
    /* the flat lists of seams and patches, each surface's size */
    size_t *seam_off = rg2__calloc((size_t)n + 1, sizeof *seam_off);
    size_t *patch_off = rg2__calloc((size_t)n + 1, sizeof *patch_off);
    double *size = rg2__calloc((size_t)n, sizeof *size);
    rg2_status st = RG2_OK;
    if (!seam_off || !patch_off || !size)
        st = rg2__fail(err, RG2_ENOMEM, "check: out of memory for %d surfaces", n);
    for (int s = 0; !st && s < n; s++) {
        seam_off[s + 1] = seam_off[s] + seam_count(&surfs[s]);
        patch_off[s + 1] = patch_off[s] + (size_t)surfs[s].nu * (size_t)surfs[s].nv;
        size[s] = surface_size(&surfs[s]);
    }
    check_job J = {surfs, n, n_shapes, o->seam_samples, o->patch_samples, o->surface_base, seam_off, patch_off, size, imp, shape_size};
    int nt = 1;
#ifdef _OPENMP
    nt = o->threads > 0 ? o->threads : omp_get_max_threads();
#endif
    if (nt > CHECK_MAX_THREADS)
        nt = CHECK_MAX_THREADS;
    if (!st && nt > 1)
        st = run_threads(out, &J, seam_off[n], patch_off[n], nt, err);
    else if (!st) { /* serial: one run of each list, straight into the report */
        size_t row = (size_t)o->patch_samples + 1;
        double *nrm = rg2__calloc(2 * row * 3, sizeof *nrm);
        unsigned char *ndef = rg2__calloc(2 * row, 1);
        if (!nrm || !ndef)
            st = rg2__fail(err, RG2_ENOMEM, "check: out of memory for %d samples per patch", o->patch_samples);
        else {
            run_seams(out, &J, 0, seam_off[n]);
            run_patches(out, &J, 0, patch_off[n], nrm, ndef);
        }
        free(nrm);
        free(ndef);
    }
    free(seam_off);
    free(patch_off);
    free(size);
    if (!st && o->crossing_density > 0)
        st = rg2__prefix(err, rg2_find_crossings(surfs, n, o->crossing_density, o->threads, &out->crossings, err), "check");
    if (!st && out->crossings.crossings > 0) {
        out->crossings.a.surf += o->surface_base;
        out->crossings.b.surf += o->surface_base;
    }
    if (st) {
        free(shape_size);
        free(shape_box);
        free(imp);
        rg2_check_report_free(out);
        return st;
    }
    if (out->kmin > out->kmax)
        out->kmin = out->kmax = out->Hmin = out->Hmax = out->Kmin = out->Kmax = 0;
    for (int k = 0; k < n_shapes; k++) /* a NaN sticks: a later shape's number replaced it */
        if (!isnan(out->worst_residual) && !(out->shapes[k].residual <= out->worst_residual))
            out->worst_residual = out->shapes[k].residual;
    free(shape_size);
    free(shape_box);
    free(imp);
    rg2__ok(err);
    return RG2_OK;
}

/* Which patches lie on a shape, tagged or not: the residual of rg2_check's exact pieces at every
 * sample of every patch, relative to the surface's size (rg2 check --on). */
rg2_status rg2_surface_shape_residuals(const rg2_surface *s, const rg2_shape *shape, int samples, double *res,
                                       rg2_error *err)
{
    if (!s || s->nu <= 0 || s->nv <= 0 || !s->patch)
        return rg2__fail(err, RG2_EINVAL, "shape residuals: the surface has no patches");
    if (!shape || !res)
        return rg2__fail(err, RG2_EINVAL, "shape residuals: no %s", !shape ? "shape" : "residual array (res)");
    if (samples < 1 || samples > 1000)
        return rg2__fail(err, RG2_EINVAL, "shape residuals: samples %d outside 1..1000", samples);
    size_t np = (size_t)s->nu * (size_t)s->nv;
    if ((double)np * (samples + 1.0) * (samples + 1.0) > RG2_MAX_CHECK_SAMPLES)
        return rg2__fail(err, RG2_ELIMIT, "shape residuals: %zu patches x %d x %d samples exceed the limit of %d",
                         np, samples + 1, samples + 1, RG2_MAX_CHECK_SAMPLES);
    rg2__implicit imp;
    rg2__implicit_prep(shape, &imp);
    double size = surface_size(s);
    for (size_t k = 0; k < np; k++) {
        int pi = (int)(k / (size_t)s->nv), pj = (int)(k % (size_t)s->nv);
        double worst = 0.0;
        for (int a = 0; a <= samples && !isnan(worst); a++)
            for (int b = 0; b <= samples; b++) {
                rg2_eval e;
                rg2_surface_eval(s, pi, pj, (double)a / samples, (double)b / samples, 0, &e);
                double g[3], f = rg2__implicit_eval(&imp, e.p, g, NULL), gn = norm3(g);
                if (gn == 0.0)
                    continue; /* a singular point of the shape (a cone's apex): no distance estimate */
                double r = fabs(f) / gn / size;
                if (!(r <= worst)) { /* (a NaN sticks) */
                    worst = r;
                    if (isnan(r))
                        break;
                }
            }
        res[k] = worst;
    }
    rg2__ok(err);
    return RG2_OK;
}

void rg2_check_report_free(rg2_check_report *r)
{
    if (!r)
        return;
    free(r->shapes);
    memset(r, 0, sizeof *r);
}

/* The characters of a UTF-8 text (its bytes but the continuation bytes): a column's width. */
static int utf8_chars(const char *s)
{
    int n = 0;
    for (; *s; s++)
        n += ((unsigned char)*s & 0xC0) != 0x80;
    return n;
}

/* Shape k's pass limit: its own (rg2_check fills it), never below tol_exact (a report made
 * some other way, with limit 0, is held to tol_exact). */
static double shape_limit(const rg2_check_report *r, int k)
{
    double l = r->shapes[k].limit;
    return l > r->opts.tol_exact ? l : r->opts.tol_exact;
}

unsigned rg2_check_failures(const rg2_check_report *r, unsigned require)
{
    unsigned f = 0;
    const rg2_check_opts *o = &r->opts;
    /* no normal compared at all on a surface with seams, or one undefined away from a pole: not G1 */
    int none = r->unmeasured > 0 || (r->seams > 0 && r->seam_samples == r->pole_samples);
    /* a surface that folds back over itself, or has no normal at a point away from a pole, has
     * no continuous tangent plane there, whatever its seams measure: not G1 */
    none = none || r->folds > 0 || r->singular > 0;
    int g0 = !(r->g0.value <= o->tol_g0);
    int g1 = g0 || none || !(r->g1.value <= o->tol_g1) || !(r->g1_pole.value <= 1.0) || !(r->g1_ill.value <= 1.0);
    int g2 = g1 || !(r->g2.value <= o->tol_g2) || !(r->g2_pole.value <= 1.0) || !(r->g2_ill.value <= 1.0);
    if ((require & RG2_REQUIRE_G0) && g0)
        f |= RG2_REQUIRE_G0;
    if ((require & RG2_REQUIRE_G1) && g1)
        f |= RG2_REQUIRE_G1;
    if ((require & RG2_REQUIRE_G2) && g2)
        f |= RG2_REQUIRE_G2;
    /* nothing exact to measure (every patch a transition) does not keep the promise either */
    /* a worst residual past tol_exact fails, unless every shape past it stays within its own
     * limit (the rounding of its coordinates, rg2_check_shape.limit) */
    int off = !(r->worst_residual <= o->tol_exact), past = 0, beyond = 0;
    for (int k = 0; off && k < r->n_shapes && r->shapes; k++)
        if (!(r->shapes[k].residual <= o->tol_exact)) {
            past = 1;
            beyond |= !(r->shapes[k].residual <= shape_limit(r, k));
        }
    off = off && (beyond || !past);
    if ((require & RG2_REQUIRE_EXACT) && (off || r->untagged_bad > 0 || r->exact_patches == 0))
        f |= RG2_REQUIRE_EXACT;
    if ((require & RG2_REQUIRE_WEIGHTS) && !(r->wmin > 0 && r->eval_wmin > 0))
        f |= RG2_REQUIRE_WEIGHTS;
    /* not searched (crossing_density 0) does not keep the promise either */
    if ((require & RG2_REQUIRE_NO_CROSSINGS) && (r->crossings.density == 0 || r->crossings.crossings > 0))
        f |= RG2_REQUIRE_NO_CROSSINGS;
    return f;
}

/* ---------------------------------------------------------------- formatting */

typedef struct {
    char *s;
    size_t len, cap;
    int oom;
    int text; /* what sb_printf writes now is the caller's text (a shape's label): kept as given */
} sbuf;

/* A NaN printed by %g or %e reads "nan" or "-nan" (its sign bit, which means nothing): both
 * become "NaN" (the minus sign a space), the same length, where they stand as a word. */
static int word_char(char c)
{
    return (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9') || c == '_';
}

static void nan_words(char *t, size_t n)
{
    for (size_t k = 0; k + 3 <= n; k++) {
        int before = k == 0 || !word_char(t[k - 1]), after = k + 3 == n || !word_char(t[k + 3]);
        if (!before || !after || strncmp(t + k, "nan", 3) != 0)
            continue;
        memcpy(t + k, "NaN", 3);
        if (k > 0 && t[k - 1] == '-')
            t[k - 1] = ' ';
    }
}

#if defined(__GNUC__)
__attribute__((format(printf, 2, 3)))
#endif
static void sb_printf(sbuf *b, const char *fmt, ...)
{
    if (b->oom)
        return;
    for (;;) {
        va_list ap;
        va_start(ap, fmt);
        int n = vsnprintf(b->s ? b->s + b->len : NULL, b->s ? b->cap - b->len : 0, fmt, ap);
        va_end(ap);
        if (n < 0) {
            b->oom = 1;
            return;
        }
        if (b->s && b->len + (size_t)n < b->cap) {
            if (!b->text)
                nan_words(b->s + b->len, (size_t)n);
            b->len += (size_t)n;
            return;
        }
        size_t cap = (b->cap ? 2 * b->cap : 1024) + (size_t)n;
        char *s = realloc(b->s, cap);
        if (!s) {
            b->oom = 1;
            return;
        }
        b->s = s;
        b->cap = cap;
    }
}

static const char *verdict(double v, double tol) { return v <= tol ? "ok" : "FAIL"; }

static void gap_where(sbuf *b, const rg2_check_gap *g)
{
    sb_printf(b, "  at surface %d %s seam (%d,%d)|(%d,%d) t=%.3g, point (%.6g, %.6g, %.6g)", g->surf,
              g->seam_dir == 0 ? "u" : "v", g->pi, g->pj, g->qi, g->qj, g->t, g->p[0], g->p[1], g->p[2]);
}

/* One gap row; pass: the row's promise holds (-1: no seams, no verdict); why: the reason a row
 * fails whose own value is within its limit (a value below its limit marked FAIL, unexplained,
 * read as a contradiction). */
static void gap_text(sbuf *b, const char *name, const char *unit, const rg2_check_gap *g, double tol, int pass,
                     const char *why)
{
    sb_printf(b, "  %-22s %9.2e %-5s %-4s (limit %.0e%s%s)", name, g->value, unit,
              pass < 0 ? "-" : pass ? "ok" : "FAIL", tol, !pass && g->value <= tol ? "; " : "",
              !pass && g->value <= tol ? why : "");
    if (pass >= 0 && g->value > 0)
        gap_where(b, g);
    sb_printf(b, "\n");
}

/* The samples measured against their own rounding bound (next to a pole, or ill-conditioned):
 * how many, their largest limits, the worst gap / limit and where. */
static void rounded_text(sbuf *b, const char *what, int n, double lim1, double lim2, const rg2_check_gap *g1,
                         const rg2_check_gap *g2)
{
    sb_printf(b, "  %s %d samples measured against their rounding bound (limits up to %.1e rad G1, %.1e G2)\n", what, n,
              lim1, lim2);
    sb_printf(b, "    worst gap / limit    G1 %.2g %s, G2 %.2g %s", g1->value, verdict(g1->value, 1.0), g2->value,
              verdict(g2->value, 1.0));
    if (g2->value > 0)
        gap_where(b, g2->value >= g1->value ? g2 : g1);
    sb_printf(b, "\n");
}

static void format_text(const rg2_check_report *r, sbuf *b)
{
    const rg2_check_opts *o = &r->opts;
    sb_printf(b, "surfaces %d, patches %d: %d exact, %d transition%s", r->surfaces, r->patches, r->exact_patches,
              r->transitions, r->untagged_bad ? "" : "\n");
    if (r->untagged_bad)
        sb_printf(b, ", %d tagged with an unknown shape\n", r->untagged_bad);
    if (r->n_shapes > 0) {
        int wl = 24; /* the label column: as wide as the longest label (never cut), in characters
                        (UTF-8: a label "kugel_ä" padded by bytes put its row's columns one left) */
        for (int k = 0; k < r->n_shapes; k++)
            if (utf8_chars(r->shapes[k].label) > wl)
                wl = utf8_chars(r->shapes[k].label);
        /* the header's columns over the rows' "  %2d %-*s %7d  %14.2e  %-7s  %s": the index and
         * label take wl + 5 characters, the right-aligned counts and residuals end under their names */
        sb_printf(b, "%-*s patches  worst residual  verdict  where\n", wl + 5, "exact pieces");
        for (int k = 0; k < r->n_shapes; k++) {
            const rg2_check_shape *s = &r->shapes[k];
            sb_printf(b, "  %2d ", k);
            b->text = 1; /* (a label "nan" or "pipe-nan" is no number: nan_words leaves it) */
            sb_printf(b, "%s%*s", s->label, wl - utf8_chars(s->label), "");
            b->text = 0;
            sb_printf(b, " %7d  %14.2e  %-7s  %s\n", s->patches, s->residual,
                      s->patches ? verdict(s->residual, shape_limit(r, k)) : "-", s->where);
            if (s->patches && shape_limit(r, k) > o->tol_exact)
                sb_printf(b, "       (limit %.2e, not %g: its coordinates round by about DBL_EPSILON x "
                             "|x| / size, a small shape far from the origin)\n", shape_limit(r, k), o->tol_exact);
        }
    }
    if (r->exact_patches == 0 && !r->untagged_bad)
        sb_printf(b, "  NO EXACT PATCH         no patch lies on a shape (every patch is a transition): "
                     "the exact promise FAILS\n");
    else if (r->exact_patches == 0) /* (tags beyond the shapes given: none given, say) */
        sb_printf(b, "  NO EXACT PATCH         no patch lies on a shape given (%d given; %d patches tagged with a "
                     "shape beyond them): the exact promise FAILS\n",
                  r->n_shapes, r->untagged_bad);
    unsigned f = rg2_check_failures(r, RG2_REQUIRE_G0 | RG2_REQUIRE_G1 | RG2_REQUIRE_G2);
    sb_printf(b, "seams %d, %d samples (%d per seam): %d at a pole (no normal there), %d not measured\n", r->seams,
              r->seam_samples, o->seam_samples + 1, r->pole_samples, r->unmeasured);
    int has = r->seams > 0;
    const char *rounded = "a sample over its rounding bound, below";
    const char *why1 = (f & RG2_REQUIRE_G0)                              ? "G0 fails, so G1 cannot hold"
                       : r->unmeasured || r->seam_samples == r->pole_samples ? "samples not measured, below"
                       : r->folds || r->singular                        ? "not regular, below"
                                                                         : rounded;
    gap_text(b, "G0 position gap", "rel", &r->g0, o->tol_g0, has ? !(f & RG2_REQUIRE_G0) : -1, "");
    gap_text(b, "G1 normal angle", "rad", &r->g1, o->tol_g1, has ? !(f & RG2_REQUIRE_G1) : -1, why1);
    gap_text(b, "G2 curvature jump", "rel", &r->g2, o->tol_g2, has ? !(f & RG2_REQUIRE_G2) : -1,
             (f & RG2_REQUIRE_G1) ? "G1 fails, so G2 cannot hold" : rounded);
    if (r->near_pole)
        rounded_text(b, "next to a pole        ", r->near_pole, fmax(r->near_pole_tol1, o->tol_g1),
                     fmax(r->near_pole_tol2, o->tol_g2), &r->g1_pole, &r->g2_pole);
    if (r->ill_conditioned)
        rounded_text(b, "ill-conditioned       ", r->ill_conditioned, fmax(r->ill_tol1, o->tol_g1),
                     fmax(r->ill_tol2, o->tol_g2), &r->g1_ill, &r->g2_ill);
    if (r->pole_unresolved)
        sb_printf(b, "  too close to a pole    %d samples up to %.3g from a pole (parametric) whose rounding bound "
                     "exceeds %.0e rad / %.0e: not compared (floating-point limit: within %.0e of the pole, or a "
                     "bound growing like 1/d and 1/d^2 toward it that is within those limits by %.3g from it)\n",
                  r->pole_unresolved, r->pole_unresolved_dist, NEAR_POLE_MAX_G1, NEAR_POLE_MAX_G2, POLE_BLUR,
                  POLE_REACH);
    if (r->unmeasured)
        sb_printf(b, "  NOT MEASURED           %d samples away from any pole could not be measured (further than %.0e "
                     "from one, and a rounding bound the pole does not explain; an undefined normal: a degenerate or "
                     "ill-conditioned patch; or a metric out of floating-point range): G1 and G2 FAIL\n",
                  r->unmeasured, POLE_BLUR);
    if (r->unmeasured) {
        const rg2_check_gap *u = &r->unmeasured_at;
        sb_printf(b, "    the first at surface %d %s seam (%d,%d)|(%d,%d) t=%.3g, point (%.6g, %.6g, %.6g)", u->surf,
                  u->seam_dir == 0 ? "u" : "v", u->pi, u->pj, u->qi, u->qj, u->t, u->p[0], u->p[1], u->p[2]);
        if (isinf(u->value))
            sb_printf(b, ": an undefined normal or metric\n");
        else if (isnan(u->value))
            sb_printf(b, ": a rounding bound that is not a number\n");
        else
            sb_printf(b, ": rounding bound %.3g times the measurable limit\n", u->value);
    }
    if (r->unmeasured_pole)
        sb_printf(b, "    %d of them on patches with a pole side, up to %.3g from the pole (parametric): their rounding "
                     "bounds exceed %.0e rad / %.0e, and would still exceed them %.3g from it if they grew only like "
                     "1/d and 1/d^2 toward it (a very thin pole patch: docs/render.md)\n",
                  r->unmeasured_pole, r->unmeasured_pole_dist, NEAR_POLE_MAX_G1, NEAR_POLE_MAX_G2, POLE_REACH);
    else if (has && r->seam_samples == r->pole_samples)
        sb_printf(b, "  NOT MEASURED           every sample lies on a pole: G1 and G2 FAIL\n");
    if (r->folds || r->singular) {
        sb_printf(b, "  NOT REGULAR            ");
        if (r->folds)
            sb_printf(b, "the surface folds back over itself (its normal reverses) between %d pairs of neighbouring "
                         "patch samples%s", r->folds, r->singular ? "; " : "");
        if (r->singular)
            sb_printf(b, "%d patch samples away from any pole have no normal (Su x Sv = 0)", r->singular);
        sb_printf(b, "; first at surface %d patch (%d,%d) u=%.3g v=%.3g, point (%.6g, %.6g, %.6g): G1 and G2 FAIL\n",
                  r->fold_at.surf, r->fold_at.pi, r->fold_at.pj, r->fold_at.u, r->fold_at.v, r->fold_at.p[0],
                  r->fold_at.p[1], r->fold_at.p[2]);
    }
    sb_printf(b, "homogeneous weights  control points [%.6g, %.6g], at samples min %.6g %s\n", r->wmin, r->wmax,
              r->eval_wmin, r->wmin > 0 ? "(all > 0)" : "(NON-POSITIVE)");
    sb_printf(b, "curvature            k [%.6g, %.6g]  H [%.6g, %.6g]  K [%.6g, %.6g]\n", r->kmin, r->kmax, r->Hmin,
              r->Hmax, r->Kmin, r->Kmax);
    if (r->kpeak.surf >= 0 && r->kpeak_k != 0) {
        /* an infinite |k| is a bend too sharp for doubles (the metric rounds away: a ruled
         * hyperboloid with c = 1e-9 bends by a / c^2 = 1e18 at its waist), not a radius of 0 */
        if (isinf(r->kpeak_k))
            sb_printf(b, "  largest |k|        inf: a bend too sharp for double precision to resolve (its radius rounds "
                         "to 0)");
        else
            sb_printf(b, "  largest |k|        %.6g (radius %.6g)", fabs(r->kpeak_k), 1 / fabs(r->kpeak_k));
        sb_printf(b, " at surface %d patch (%d,%d) u=%.3g v=%.3g, point (%.6g, %.6g, %.6g)\n", r->kpeak.surf,
                  r->kpeak.pi, r->kpeak.pj, r->kpeak.u, r->kpeak.v, r->kpeak.p[0], r->kpeak.p[1], r->kpeak.p[2]);
    }
    sb_printf(b, "size                 %.6g (box diagonal)\n", r->size);
    const rg2_crossing_report *c = &r->crossings;
    if (c->density > 0) {
        sb_printf(b, "crossings            %d of %d triangle pairs crossing in the mesh confirmed (%d triangles, "
                     "density %d) %s\n", c->crossings, c->candidates, c->triangles, c->density,
                  c->crossings ? "FAIL" : "ok");
        if (c->crossings)
            sb_printf(b, "  first at surface %d patch (%d,%d) u=%.6g v=%.6g x surface %d patch (%d,%d) u=%.6g v=%.6g, "
                         "point (%.6g, %.6g, %.6g), normals %.3g rad apart, gap %.1e\n", c->a.surf, c->a.pi, c->a.pj,
                      c->a.u, c->a.v, c->b.surf, c->b.pi, c->b.pj, c->b.u, c->b.v, c->p[0], c->p[1], c->p[2],
                      c->angle, c->residual);
    }
}

/* The report's numbers as the shortest digits that read back to the same double (a point
 * copied from the JSON into a design's "to" or `rg2 info --near` is the sample's own; cJSON's
 * 15 digits could be an ulp off). */
static void add_num(cJSON *o, const char *name, double x)
{
    cJSON_AddItemToObject(o, name, rg2__json_double(x));
}

static cJSON *sheet_json(const rg2_crossing_sheet *s)
{
    cJSON *j = cJSON_CreateObject();
    int p[2] = {s->pi, s->pj};
    double uv[2] = {s->u, s->v};
    add_num(j, "surface", s->surf);
    cJSON_AddItemToObject(j, "patch", cJSON_CreateIntArray(p, 2));
    cJSON_AddItemToObject(j, "uv", rg2__json_doubles(uv, 2));
    return j;
}

/* A seam sample's place (surface, seam, the two patches, t, point) as members of j. */
static void seam_place_json(cJSON *j, const rg2_check_gap *g)
{
    add_num(j, "surface", g->surf);
    cJSON_AddStringToObject(j, "seam", g->seam_dir == 0 ? "u" : "v");
    int a[2] = {g->pi, g->pj}, c[2] = {g->qi, g->qj};
    cJSON_AddItemToObject(j, "patch_a", cJSON_CreateIntArray(a, 2));
    cJSON_AddItemToObject(j, "patch_b", cJSON_CreateIntArray(c, 2));
    add_num(j, "t", g->t);
    cJSON_AddItemToObject(j, "point", rg2__json_doubles(g->p, 3));
}

static cJSON *gap_json(const rg2_check_gap *g, double tol)
{
    cJSON *j = cJSON_CreateObject();
    add_num(j, "value", g->value);
    add_num(j, "limit", tol);
    cJSON_AddBoolToObject(j, "ok", g->value <= tol);
    seam_place_json(j, g);
    return j;
}

/* A sample's surface, patch, u, v and point as members of o. */
static void sample_json(cJSON *o, const rg2_check_sample *at)
{
    add_num(o, "surface", at->surf);
    int ij[2] = {at->pi, at->pj};
    cJSON_AddItemToObject(o, "patch", cJSON_CreateIntArray(ij, 2));
    add_num(o, "u", at->u);
    add_num(o, "v", at->v);
    cJSON_AddItemToObject(o, "point", rg2__json_doubles(at->p, 3));
}

static char *format_json(const rg2_check_report *r)
{
    const rg2_check_opts *o = &r->opts;
    cJSON *j = cJSON_CreateObject();
    if (!j)
        return NULL;
    add_num(j, "surfaces", r->surfaces);
    add_num(j, "patches", r->patches);
    add_num(j, "exact_patches", r->exact_patches);
    add_num(j, "transitions", r->transitions);
    add_num(j, "unknown_tags", r->untagged_bad);
    cJSON *sh = cJSON_AddArrayToObject(j, "shapes");
    for (int k = 0; k < r->n_shapes; k++) {
        cJSON *s = cJSON_CreateObject();
        add_num(s, "index", k);
        cJSON_AddStringToObject(s, "label", r->shapes[k].label);
        add_num(s, "patches", r->shapes[k].patches);
        add_num(s, "residual", r->shapes[k].residual);
        add_num(s, "limit", shape_limit(r, k));
        cJSON_AddBoolToObject(s, "ok", r->shapes[k].residual <= shape_limit(r, k));
        cJSON_AddStringToObject(s, "where", r->shapes[k].where);
        cJSON_AddItemToArray(sh, s);
    }
    add_num(j, "worst_residual", r->worst_residual);
    add_num(j, "exact_limit", o->tol_exact);
    add_num(j, "seams", r->seams);
    add_num(j, "seam_samples", r->seam_samples);
    add_num(j, "skipped", r->skipped);
    add_num(j, "pole_samples", r->pole_samples);
    add_num(j, "unmeasured", r->unmeasured);
    add_num(j, "unmeasured_near_pole", r->unmeasured_pole);
    add_num(j, "unmeasured_pole_distance", r->unmeasured_pole_dist);
    if (r->unmeasured) { /* the first unmeasured sample */
        const rg2_check_gap *u = &r->unmeasured_at;
        cJSON *ua = cJSON_AddObjectToObject(j, "unmeasured_at");
        seam_place_json(ua, u);
        cJSON_AddStringToObject(ua, "reason", isinf(u->value)   ? "undefined normal or metric"
                                              : isnan(u->value) ? "rounding bound not a number"
                                                                : "rounding bound");
        add_num(ua, "bound_over_limit", u->value); /* (null unless a finite bound) */
    }
    cJSON *rg = cJSON_AddObjectToObject(j, "regularity");
    add_num(rg, "folds", r->folds);
    add_num(rg, "singular", r->singular);
    if (r->folds || r->singular) {
        sample_json(rg, &r->fold_at);
    }
    unsigned fg = rg2_check_failures(r, RG2_REQUIRE_G0 | RG2_REQUIRE_G1 | RG2_REQUIRE_G2);
    cJSON *g;
    cJSON_AddItemToObject(j, "g0_position", g = gap_json(&r->g0, o->tol_g0));
    cJSON_ReplaceItemInObject(g, "ok", cJSON_CreateBool(!(fg & RG2_REQUIRE_G0)));
    cJSON_AddItemToObject(j, "g1_normal_angle", g = gap_json(&r->g1, o->tol_g1));
    cJSON_ReplaceItemInObject(g, "ok", cJSON_CreateBool(!(fg & RG2_REQUIRE_G1)));
    cJSON_AddItemToObject(j, "g2_curvature_jump", g = gap_json(&r->g2, o->tol_g2));
    cJSON_ReplaceItemInObject(g, "ok", cJSON_CreateBool(!(fg & RG2_REQUIRE_G2)));
    cJSON *np = cJSON_AddObjectToObject(j, "near_pole");
    add_num(np, "samples", r->near_pole);
    add_num(np, "unresolved", r->pole_unresolved);
    add_num(np, "unresolved_distance", r->pole_unresolved_dist);
    add_num(np, "g1_limit_max", fmax(r->near_pole_tol1, o->tol_g1));
    add_num(np, "g2_limit_max", fmax(r->near_pole_tol2, o->tol_g2));
    cJSON_AddItemToObject(np, "g1_gap_over_limit", gap_json(&r->g1_pole, 1.0));
    cJSON_AddItemToObject(np, "g2_gap_over_limit", gap_json(&r->g2_pole, 1.0));
    cJSON *ic = cJSON_AddObjectToObject(j, "ill_conditioned");
    add_num(ic, "samples", r->ill_conditioned);
    add_num(ic, "g1_limit_max", fmax(r->ill_tol1, o->tol_g1));
    add_num(ic, "g2_limit_max", fmax(r->ill_tol2, o->tol_g2));
    cJSON_AddItemToObject(ic, "g1_gap_over_limit", gap_json(&r->g1_ill, 1.0));
    cJSON_AddItemToObject(ic, "g2_gap_over_limit", gap_json(&r->g2_ill, 1.0));
    double w[3] = {r->wmin, r->wmax, r->eval_wmin}, k[6] = {r->kmin, r->kmax, r->Hmin, r->Hmax, r->Kmin, r->Kmax};
    cJSON_AddItemToObject(j, "weights", rg2__json_doubles(w, 2));
    add_num(j, "min_weight_at_samples", w[2]);
    cJSON_AddItemToObject(j, "principal_curvature", rg2__json_doubles(k, 2));
    cJSON_AddItemToObject(j, "mean_curvature", rg2__json_doubles(k + 2, 2));
    cJSON_AddItemToObject(j, "gauss_curvature", rg2__json_doubles(k + 4, 2));
    if (r->kpeak.surf >= 0) {
        cJSON *kp = cJSON_AddObjectToObject(j, "largest_curvature");
        add_num(kp, "k", r->kpeak_k);
        sample_json(kp, &r->kpeak);
    }
    add_num(j, "size", r->size);
    const rg2_crossing_report *c = &r->crossings;
    if (c->density > 0) { /* (only when searched: the report without it is unchanged) */
        cJSON *x = cJSON_AddObjectToObject(j, "crossings");
        add_num(x, "density", c->density);
        add_num(x, "triangles", c->triangles);
        add_num(x, "pairs", c->pairs);
        add_num(x, "candidates", c->candidates);
        add_num(x, "crossings", c->crossings);
        cJSON_AddBoolToObject(x, "ok", c->crossings == 0);
        if (c->crossings) {
            cJSON_AddItemToObject(x, "a", sheet_json(&c->a));
            cJSON_AddItemToObject(x, "b", sheet_json(&c->b));
            cJSON_AddItemToObject(x, "point", rg2__json_doubles(c->p, 3));
            add_num(x, "angle", c->angle);
            add_num(x, "residual", c->residual);
        }
    }
    unsigned f = rg2_check_failures(r, RG2_REQUIRE_G2 | RG2_REQUIRE_EXACT | RG2_REQUIRE_WEIGHTS);
    cJSON_AddBoolToObject(j, "g2", !(f & RG2_REQUIRE_G2));
    cJSON_AddBoolToObject(j, "exact", !(f & RG2_REQUIRE_EXACT));
    cJSON_AddBoolToObject(j, "positive_weights", !(f & RG2_REQUIRE_WEIGHTS));
    char *txt = rg2__json_print(j, 1);
    cJSON_Delete(j);
    return txt;
}

rg2_status rg2_check_format(const rg2_check_report *r, int json, char **text, rg2_error *err)
{
    if (!r || !text)
        return rg2__fail(err, RG2_EINVAL, "check: nothing to format");
    *text = NULL;
    /* the table's numbers in the "C" locale, as in the files rg2 writes: under a German locale
     * "(0,5, 1,5, 2)" was no longer a point of three coordinates (cJSON writes its numbers so) */
    void *loc = rg2__c_numeric_begin();
    if (json) {
        char *c = format_json(r);
        if (!c) {
            rg2__c_numeric_end(loc);
            return rg2__fail(err, RG2_ENOMEM, "check: out of memory formatting JSON");
        }
        /* hand out memory from malloc (cJSON may use its own allocator hooks) */
        size_t len = strlen(c);
        *text = malloc(len + 2);
        if (*text) {
            memcpy(*text, c, len);
            (*text)[len] = '\n';
            (*text)[len + 1] = '\0';
        }
        cJSON_free(c);
    } else {
        sbuf b = {0};
        format_text(r, &b);
        if (b.oom) {
            rg2__c_numeric_end(loc);
            free(b.s);
            return rg2__fail(err, RG2_ENOMEM, "check: out of memory formatting the table");
        }
        *text = b.s;
    }
    rg2__c_numeric_end(loc);
    if (!*text)
        return rg2__fail(err, RG2_ENOMEM, "check: out of memory formatting the report");
    rg2__ok(err);
    return RG2_OK;
}
