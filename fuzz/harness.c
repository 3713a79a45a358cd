/* harness.c -- the fuzz harnesses (see harness.h): the design path, the NURBS import and the C
 * mesh operations.
 * Compiled into the libFuzzer programs (fuzz/fuzz_*.c) and included by the replay test. */
#include "harness.h"

#include "rg2.h"

#include <float.h>
#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

const char *rg2f_input_name = NULL;

/* A broken library contract: print it and abort, so the fuzzer keeps the input. */
#if defined(__GNUC__)
__attribute__((format(printf, 1, 2), noreturn))
#endif
static void rg2f_violation(const char *fmt, ...)
{
    va_list ap;
    va_start(ap, fmt);
    fprintf(stderr, "rg2 fuzz: contract violated%s%s: ", rg2f_input_name ? " by " : "",
            rg2f_input_name ? rg2f_input_name : "");
    vfprintf(stderr, fmt, ap);
    fprintf(stderr, "\n");
    va_end(ap);
    abort();
}

/* A failed call must report its own status and a non-empty, terminated message. */
static void rg2f_check_error(const char *call, rg2_status st, const rg2_error *err)
{
    if (st == RG2_OK)
        return;
    if ((int)st < 0 || st > RG2_ELIMIT)
        rg2f_violation("%s returned unknown status %d", call, (int)st);
    if (err->code != st)
        rg2f_violation("%s returned %s but err->code is %s", call, rg2_status_str(st),
                       rg2_status_str(err->code));
    if (!memchr(err->msg, 0, sizeof err->msg) || !err->msg[0])
        rg2f_violation("%s failed (%s) without a message", call, rg2_status_str(st));
}

static volatile double rg2f_sink;

/* Checks of a built surface: counts, finite control points, evaluation everywhere (for the
 * sanitizers), and a coarse tessellation of small surfaces. */
/* Picking (src/locate.c): a nearest point and a first ray hit from outside the control box. A
 * refusal names a weight <= 0; a hit lies on the surface side of its bound, on its ray (within
 * the stated tolerance), and no farther than any patch corner (a point of the surface); every
 * control point lies inside the slabs of its tree nodes. */
extern long rg2__locate_max_pieces; /* (src/internal.h) */
int rg2__locate_cert(const rg2_locator *L, int patch, double uf, double vf, double r, const double x[3], double c,
                     const double rect[4], double *bound);
int rg2__locate_ray_cert(const rg2_locator *L, int patch, double uf, double vf, double r, const double o[3],
                         const double d[3], const double rect[4], double *bound);
double rg2__locate_slab_margin(const rg2_locator *L, int *slabs);

/* The searches' certificates by themselves (src/locate.c), on patches 0 and the last, based at
 * the centre and at a corner: a nearest-point certificate's bound over its rectangle may not lie
 * above the distance from x at any of 9 x 9 points of it; the ray from x through the base point
 * S(base) meets the surface there at t = 1, and a ray certificate may not rule that out (both up
 * to rnd, the rounding of the coordinates themselves). */
static void rg2f_check_certs(const rg2_surface *s, const rg2_locator *L, const double x[3], double size,
                             double rnd, const char *what)
{
    int np = s->nu * s->nv;
    for (int k = 0; k < 4; k++) {
        int patch = k < 2 ? 0 : np - 1;
        double uf = k & 1 ? 0.5 : 0, vf = k & 1 ? 0.5 : 1, r = k < 2 ? 0.5 : 0.125, b;
        rg2_eval e;
        rg2_surface_eval(s, patch / s->nv, patch % s->nv, uf, vf, 0, &e);
        double d[3] = {e.p[0] - x[0], e.p[1] - x[1], e.p[2] - x[2]}, c = d[0] * d[0] + d[1] * d[1] + d[2] * d[2];
        double R[4] = {fmax(0, uf - r), fmin(1, uf + r), fmax(0, vf - r), fmin(1, vf + r)};
        if (rg2__locate_cert(L, patch, uf, vf, r, x, c, R, &b))
            for (int a = 0; a <= 8; a++)
                for (int t = 0; t <= 8; t++) {
                    rg2_eval f;
                    rg2_surface_eval(s, patch / s->nv, patch % s->nv, R[0] + (R[1] - R[0]) * a / 8,
                                     R[2] + (R[3] - R[2]) * t / 8, 0, &f);
                    double g = sqrt((f.p[0] - x[0]) * (f.p[0] - x[0]) + (f.p[1] - x[1]) * (f.p[1] - x[1]) +
                                    (f.p[2] - x[2]) * (f.p[2] - x[2]));
                    if (b > g + 1e-9 * (g + size) + rnd)
                        rg2f_violation("%s: patch %d's certificate at (%g, %g), r %g, proves %.17g, but a point of "
                                       "it is %.17g away", what, patch, uf, vf, r, b, g);
                }
        double P[4] = {uf, uf, vf, vf};
        if (rg2__locate_ray_cert(L, patch, uf, vf, r, x, d, P, &b) && b > 1 + 1e-9 + rnd / sqrt(c))
            rg2f_violation("%s: patch %d's ray certificate at (%g, %g), r %g, rules out its own hit at t = 1 (bound "
                           "%.17g)", what, patch, uf, vf, r, b);
    }
}

static void rg2f_check_picking(const rg2_surface *s, const char *what)
{
    rg2__locate_max_pieces = 2000; /* (a degenerate surface stops early, with its bound) */
    rg2_locator *L = (rg2_locator *)&rg2f_sink; /* must be replaced by NULL on failure */
    rg2_error err;
    rg2_status st = rg2_locator_build(s, &L, &err);
    if (st) {
        if (L)
            rg2f_violation("%s: rg2_locator_build failed but left *out set", what);
        if (st != RG2_EWEIGHT && st != RG2_EDOMAIN) /* (a weight <= 0; past the numeric range) */
            rg2f_violation("%s: rg2_locator_build -> %s: %s", what, rg2_status_str(st), err.msg);
        return;
    }
    /* every exact control point inside the tree's slabs, which rule nodes out */
    int slabs;
    double margin = rg2__locate_slab_margin(L, &slabs);
    if (!(margin >= 0))
        rg2f_violation("%s: a control point %.3g (of its size) outside its tree node's slab", what, -margin);
    double lo[3], hi[3], c[3], x[3], d[3], size = 0;
    rg2_surface_box(s, lo, hi);
    for (int k = 0; k < 3; k++) {
        c[k] = 0.5 * (lo[k] + hi[k]);
        size += (hi[k] - lo[k]) * (hi[k] - lo[k]);
    }
    size = sqrt(size);
    for (int k = 0; k < 3; k++) {
        x[k] = c[k] + (0.7 + 0.2 * k) * size;
        d[k] = c[k] - x[k] + 0.01 * size * (k - 1);
    }
    double tol = 1e-10 * (size + sqrt((x[0] - c[0]) * (x[0] - c[0]) + (x[1] - c[1]) * (x[1] - c[1]) +
                                      (x[2] - c[2]) * (x[2] - c[2])));
    /* the rounding of the coordinates themselves: a surface a few ulps across (size 1e-14 at
     * coordinates near 29) has no answer exact beyond it, and its distances are noise there */
    double rnd = 0;
    for (int k = 0; k < 3; k++)
        rnd = fmax(rnd, fmax(fabs(x[k]), fmax(fabs(lo[k]), fabs(hi[k]))));
    rnd *= 64 * DBL_EPSILON;
    rg2_hit h;
    st = rg2_locator_closest(L, x, &h, &err);
    rg2f_check_error("rg2_locator_closest", st, &err);
    if (!st) {
        if (h.i < 0 || h.i >= s->nu || h.j < 0 || h.j >= s->nv || !(h.bound <= h.dist) || !isfinite(h.dist))
            rg2f_violation("%s: nearest point patch (%d,%d), distance %g, bound %g", what, h.i, h.j, h.dist, h.bound);
        rg2_eval e;
        for (int k = 0; k < s->nu * s->nv; k++)
            for (int q = 0; q < 4; q++) {
                rg2_surface_eval(s, k / s->nv, k % s->nv, q & 1, q >> 1, 0, &e);
                double g = sqrt((e.p[0] - x[0]) * (e.p[0] - x[0]) + (e.p[1] - x[1]) * (e.p[1] - x[1]) +
                                (e.p[2] - x[2]) * (e.p[2] - x[2]));
                /* no corner nearer than the bound; none nearer than the answer by more than the
                 * tolerance where the search was not stopped early */
                if (g < h.bound - 1e-12 * (g + size) - rnd || (h.dist - h.bound <= tol && g < h.dist - tol - rnd))
                    rg2f_violation("%s: nearest point %.17g away (bound %.17g, tolerance %.3g), but patch %d's "
                                   "corner %d is %.17g away", what, h.dist, h.bound, tol, k, q, g);
            }
    }
    rg2f_check_certs(s, L, x, size, rnd, what);
    st = rg2_locator_ray(L, x, d, INFINITY, &h, &err);
    rg2f_check_error("rg2_locator_ray", st, &err);
    if (!st && h.i >= 0) {
        double off = 0, dd = d[0] * d[0] + d[1] * d[1] + d[2] * d[2];
        for (int k = 0; k < 3; k++) { /* distance of p from the ray's line */
            double q = h.p[k] - x[k] - (((h.p[0] - x[0]) * d[0] + (h.p[1] - x[1]) * d[1] + (h.p[2] - x[2]) * d[2]) / dd) * d[k];
            off += q * q;
        }
        if (!(sqrt(off) <= 2 * tol + rnd) || !(h.bound <= h.dist) || !(h.dist >= 0))
            rg2f_violation("%s: ray hit %.3g off the ray (tolerance %.3g), t %g, bound %g", what, sqrt(off), tol,
                           h.dist, h.bound);
    }
    rg2_locator_free(L);
}

static void rg2f_check_surface(const rg2_surface *s, const char *what)
{
    if (s->nu < 1 || s->nv < 1 || !s->patch)
        rg2f_violation("%s: %d x %d patches", what, s->nu, s->nv);
    size_t np = (size_t)s->nu * (size_t)s->nv;
    for (size_t k = 0; k < np; k++) {
        const double *h = &s->patch[k].h[0][0][0];
        for (int q = 0; q < 64; q++)
            if (!isfinite(h[q]))
                rg2f_violation("%s: patch %zu control value %d is %g", what, k, q, h[q]);
    }
    double acc = rg2_surface_min_weight(s);
    static const double uv[5][2] = {{0, 0}, {1, 1}, {0.5, 0.5}, {0.25, 0.75}, {1, 0}};
    size_t step = np > 2048 ? np / 2048 : 1;
    for (size_t k = 0; k < np; k += step)
        for (int q = 0; q < 5; q++) {
            rg2_eval e;
            rg2_patch_eval(&s->patch[k], uv[q][0], uv[q][1], 2, &e);
            if (!(e.flags & RG2_EVAL_WEIGHT_NONPOSITIVE) &&
                !(isfinite(e.p[0]) && isfinite(e.p[1]) && isfinite(e.p[2])))
                rg2f_violation("%s: patch %zu at (%g, %g) evaluates to (%g, %g, %g)", what, k, uv[q][0],
                               uv[q][1], e.p[0], e.p[1], e.p[2]);
            acc += e.p[0] + e.K + e.H + e.k1;
        }
    if (np <= 64) {
        rg2_tess t;
        rg2_error err;
        rg2_status st = rg2_tessellate(s, 2, 1, &t, &err);
        rg2f_check_error("rg2_tessellate", st, &err);
        if (!st) {
            if (t.n_vertices < 1 || t.n_triangles < 0)
                rg2f_violation("%s: tessellation with %d vertices, %d triangles", what, t.n_vertices,
                               t.n_triangles);
            for (int k = 0; k < 3 * t.n_triangles; k++)
                if (t.tri[k] < 0 || t.tri[k] >= t.n_vertices)
                    rg2f_violation("%s: triangle vertex %d out of range", what, t.tri[k]);
            for (int k = 0; k < t.n_vertices; k++)
                if (t.patch[k] < 0 || (size_t)t.patch[k] >= np)
                    rg2f_violation("%s: tessellation vertex %d on patch %d", what, k, t.patch[k]);
            acc += t.pos[0];
        }
        rg2_tess_free(&t);
        rg2f_check_picking(s, what);
    }
    rg2f_sink = acc;
}

int rg2f_design(const uint8_t *data, size_t size)
{
    if (size > RG2F_MAX_INPUT)
        return 0;
    rg2_design *d = (rg2_design *)&rg2f_sink; /* must be replaced by NULL on failure */
    rg2_error err;
    rg2_status st = rg2_design_parse((const char *)data, size, "fuzz.json", &d, &err);
    rg2f_check_error("rg2_design_parse", st, &err);
    if (st) {
        if (d)
            rg2f_violation("rg2_design_parse failed but left *out set");
        return 0;
    }
    if (!d)
        rg2f_violation("rg2_design_parse succeeded without a design");
    int ns = rg2_design_num_surfaces(d), nsh = rg2_design_num_shapes(d);
    if (ns < 1)
        rg2f_violation("a built design has %d surfaces", ns);
    if (rg2_design_surface(d, ns) || rg2_design_surface(d, -1) || rg2_design_mesh(d, ns) ||
        rg2_design_shape(d, nsh) || rg2_design_shape_label(d, -1))
        rg2f_violation("accessor out of range returned an object");
    for (int k = 0; k < nsh; k++)
        if (!rg2_design_shape(d, k) || !rg2_design_shape_label(d, k) ||
            !rg2_shape_describe(rg2_design_shape(d, k)->kind))
            rg2f_violation("shape %d of %d missing", k, nsh);
    for (int o = 0; o < ns; o++) {
        const rg2_surface *s = rg2_design_surface(d, o);
        const rg2_mesh *m = rg2_design_mesh(d, o);
        if (!s || !m || !rg2_design_mesh_name(d, o))
            rg2f_violation("output %d missing", o);
        st = rg2_mesh_check(m, &err);
        if (st)
            rg2f_violation("output mesh %d fails its check: %s", o, err.msg);
        /* caps (paper section 5) add patch rows at the ends of an open v direction */
        int segv = rg2_scalars_num_segments(&m->sv);
        if (s->nu != rg2_scalars_num_segments(&m->su) || s->nv < segv ||
            (s->nv != segv && m->sv.closed) || s->closed_u != m->su.closed || s->closed_v != m->sv.closed)
            rg2f_violation("surface %d: %d x %d patches from a %d x %d mesh", o, s->nu, s->nv, m->nu,
                           m->nv);
        if (!s->tag)
            rg2f_violation("surface %d has no tags", o);
        for (size_t k = 0; k < (size_t)s->nu * (size_t)s->nv; k++)
            if (s->tag[k] < -1 || s->tag[k] >= nsh)
                rg2f_violation("surface %d: patch %zu tag %d outside -1..%d", o, k, s->tag[k], nsh - 1);
        if ((size_t)m->nu * (size_t)m->nv <= 4096)
            for (int i = 0; i < m->nu; i++)
                for (int j = 0; j < m->nv; j++) {
                    int t = rg2_design_point_shape(d, o, i, j);
                    if (t < -1 || t >= nsh)
                        rg2f_violation("surface %d: point [%d][%d] shape %d", o, i, j, t);
                }
        rg2f_check_surface(s, "design surface");
    }
    rg2_design_free(d);
    return 0;
}

/* ------------------------------------------------------------------------------------- */
/* NURBS */

typedef struct {
    const uint8_t *p;
    size_t n, at;
    int raw;      /* values are raw 8-byte doubles (else 16-bit fixed point / 256) */
    unsigned fill; /* counter for the values after the end of the input */
} rg2f_reader;

/* Next value from the input; past its end a fixed pattern (so short inputs still build). */
static double rg2f_next(rg2f_reader *r, double dflt)
{
    if (r->raw) {
        if (r->at + 8 <= r->n) {
            double x;
            memcpy(&x, r->p + r->at, 8);
            r->at += 8;
            return x;
        }
    } else if (r->at + 2 <= r->n) {
        int16_t q;
        memcpy(&q, r->p + r->at, 2);
        r->at += 2;
        return q / 256.0;
    }
    r->fill++;
    return dflt;
}

/* De Boor for the span [U_l, U_{l+1}] at local parameter t in [0, 1] on 4 homogeneous
 * points. The knot differences are formed before t enters, so knots that are close in
 * relative terms (a span of a few ulps of large knot values) still give the exact t. */
static void rg2f_deboor(const double *U, int l, double P[4][4], double t, double out[4])
{
    double d[4][4];
    memcpy(d, P, sizeof d);
    for (int r = 1; r <= 3; r++)
        for (int i = 3; i >= r; i--) {
            int gi = l - 3 + i;
            double al = ((U[l] - U[gi]) + t * (U[l + 1] - U[l])) / (U[gi + 4 - r] - U[gi]);
            for (int k = 0; k < 4; k++)
                d[i][k] = (1.0 - al) * d[i - 1][k] + al * d[i][k];
        }
    memcpy(out, d[3], sizeof d[3]);
}

/* The NURBS at local (u, v) of spans lu, lv (independent of the library's construction). */
static void rg2f_nurbs_eval(const rg2_nurbs *nb, int lu, int lv, double u, double v, double x[3])
{
    double rows[4][4];
    for (int a = 0; a < 4; a++) {
        double P[4][4];
        for (int b = 0; b < 4; b++) {
            size_t k = (size_t)(lu - 3 + a) * (size_t)nb->nv + (size_t)(lv - 3 + b);
            double w = nb->weights ? nb->weights[k] : 1.0;
            for (int q = 0; q < 3; q++)
                P[b][q] = w * nb->points[3 * k + q];
            P[b][3] = w;
        }
        rg2f_deboor(nb->knots_v, lv, P, v, rows[a]);
    }
    double h[4];
    rg2f_deboor(nb->knots_u, lu, rows, u, h);
    for (int q = 0; q < 3; q++)
        x[q] = h[q] / h[3];
}

/* Knots: clamped ends (4 equal knots) or free ones; increments from the input (>= 0, so
 * zero intervals occur) or raw values. Returns the ratio of the longest to the shortest
 * non-zero interval, or inf if an interior interval is zero, one is below 2^-960, or the knots
 * decrease. */
static double rg2f_knots(rg2f_reader *r, double *U, int n, int clamp, int incr)
{
    int nk = n + 4;
    U[0] = rg2f_next(r, 0.0);
    for (int k = 1; k < nk; k++)
        U[k] = incr ? U[k - 1] + fabs(rg2f_next(r, 1.0)) : rg2f_next(r, (double)k);
    if (clamp)
        for (int k = 0; k < 3; k++) {
            U[k] = U[3];
            U[nk - 1 - k] = U[n];
        }
    double lo = INFINITY, hi = 0.0;
    for (int k = 1; k < nk; k++) {
        double dd = U[k] - U[k - 1];
        if (!(dd >= 0.0) || (dd == 0.0 && k > 3 && k < nk - 3))
            return INFINITY;
        if (dd > 0.0) {
            lo = fmin(lo, dd);
            hi = fmax(hi, dd);
        }
    }
    /* a subnormal interval (or nearly one: below 2^-960) makes t * (U_{l+1} - U_l) round in the
     * reference de Boor (rg2f_deboor), which then loses up to 1e-7: no reference there */
    return lo < 0x1p-960 ? INFINITY : hi / lo;
}

int rg2f_nurbs(const uint8_t *data, size_t size)
{
    if (size > RG2F_MAX_INPUT)
        return 0;
    if (size < 3)
        return 0;
    rg2f_reader r = {data, size, 3, (data[2] >> 1) & 1, 0};
    int nu = 4 + (data[0] & 7), nv = 4 + (data[1] & 7);
    int weights = data[2] & 1, clu = (data[2] >> 2) & 1, clv = (data[2] >> 3) & 1,
        incr = !((data[2] >> 4) & 1);
    size_t np = (size_t)nu * (size_t)nv;
    double U[16], V[16], *P = malloc(sizeof(double) * np * 4), *W = P + 3 * np;
    if (!P)
        return 0;
    double ru = rg2f_knots(&r, U, nu, clu, incr), rv = rg2f_knots(&r, V, nv, clv, incr);
    double pmax = 0.0, wlo = INFINITY, whi = 0.0;
    for (size_t k = 0; k < np; k++)
        for (int q = 0; q < 3; q++) {
            P[3 * k + q] = rg2f_next(&r, (double)((k * 7 + (size_t)q * 3) % 5));
            pmax = fmax(pmax, fabs(P[3 * k + q]));
        }
    for (size_t k = 0; k < np; k++) {
        W[k] = weights ? rg2f_next(&r, 1.0) : 1.0;
        wlo = fmin(wlo, W[k]);
        whi = fmax(whi, W[k]);
    }
    rg2_nurbs nb = {nu, nv, P, weights ? W : NULL, U, V};
    rg2_mesh m;
    rg2_error err;
    rg2_status st = rg2_nurbs_mesh(&nb, &m, &err);
    rg2f_check_error("rg2_nurbs_mesh", st, &err);
    if (!st) {
        if (m.nu != nu || m.nv != nv)
            rg2f_violation("nurbs: %d x %d points became a %d x %d mesh", nu, nv, m.nu, m.nv);
        rg2_surface s;
        st = rg2_surface_build(&m, &s, &err);
        rg2f_check_error("rg2_surface_build", st, &err);
        if (!st) {
            if (s.nu != nu - 3 || s.nv != nv - 3)
                rg2f_violation("nurbs: %d x %d patches from %d x %d points", s.nu, s.nv, nu, nv);
            rg2f_check_surface(&s, "nurbs surface");
            /* well-conditioned input: the patches are the NURBS (an independent de Boor) */
            if (ru <= 16.0 && rv <= 16.0 && wlo >= 0.25 && whi <= 4.0 && pmax <= 1e3) {
                double tol = 1e-9 * (pmax + 1.0);
                static const double t[3] = {0.0, 0.5, 1.0};
                for (int i = 0; i < s.nu; i++)
                    for (int j = 0; j < s.nv; j++)
                        for (int a = 0; a < 3; a++)
                            for (int b = 0; b < 3; b++) {
                                double x[3];
                                rg2f_nurbs_eval(&nb, i + 3, j + 3, t[a], t[b], x);
                                rg2_eval e;
                                rg2_patch_eval(rg2_surface_patch(&s, i, j), t[a], t[b], 0, &e);
                                double dd = fmax(fabs(x[0] - e.p[0]),
                                                 fmax(fabs(x[1] - e.p[1]), fabs(x[2] - e.p[2])));
                                if (!(dd <= tol))
                                    rg2f_violation("nurbs: patch (%d,%d) at (%g,%g) is %.3g from the "
                                                   "NURBS (tolerance %.3g)",
                                                   i, j, t[a], t[b], dd, tol);
                            }
            }
            rg2_surface_free(&s);
        }
        rg2_mesh_free(&m);
    }
    free(P);
    return 0;
}

/* ------------------------------------------------------------------------------------- */
/* mesh operations */

/* One byte of the input (past its end: 0). */
static unsigned rg2f_byte(rg2f_reader *r) { return r->at < r->n ? r->p[r->at++] : 0u; }

/* A 32-bit index from the input: small most of the time, anywhere in int now and then. */
static int rg2f_index(rg2f_reader *r)
{
    unsigned b = rg2f_byte(r);
    if (b < 0xf0)
        return (int)(b % 24) - 1;
    int32_t x = 0;
    for (int k = 0; k < 4; k++)
        x = (int32_t)((uint32_t)x << 8 | rg2f_byte(r));
    return x;
}

/* An output must be empty after a failure. */
static void rg2f_check_empty(const char *call, const rg2_mesh *m)
{
    if (m->p || m->nu || m->nv || m->su.w || m->su.b || m->sv.w || m->sv.g)
        rg2f_violation("%s failed but left its output set", call);
}

static int rg2f_same_mesh(const rg2_mesh *a, const rg2_mesh *b)
{
    if (a->nu != b->nu || a->nv != b->nv || a->su.closed != b->su.closed || a->sv.closed != b->sv.closed)
        return 0;
    for (int k = 0; k < 2; k++) {
        const rg2_scalars *x = k ? &a->sv : &a->su, *y = k ? &b->sv : &b->su;
        if (memcmp(x->w, y->w, (size_t)rg2_scalars_num_w(x) * sizeof(double)) ||
            memcmp(x->b, y->b, (size_t)x->n * sizeof(double)) || memcmp(x->g, y->g, (size_t)x->n * sizeof(double)))
            return 0;
    }
    return !memcmp(a->p, b->p, (size_t)a->nu * (size_t)a->nv * 4 * sizeof(double));
}

#define RG2F_POOL 6

int rg2f_meshops(const uint8_t *data, size_t size)
{
    if (size > RG2F_MAX_INPUT || size < 3)
        return 0;
    /* bytes: mesh count, value format, the length L of the operations, the values, and the last
     * L bytes the operations (so a short input still runs operations on default meshes) */
    size_t L = data[2] < size - 3 ? data[2] : size - 3;
    rg2f_reader r = {data, size - L, 3, data[1] & 1, 0}, o = {data + size - L, L, 0, 0, 0};
    rg2_mesh pool[RG2F_POOL];
    memset(pool, 0, sizeof pool);
    int n = 0;
    rg2_error err;
    /* 1 to 3 meshes: 4..9 points each way, either closed (3..9), scalars and points from the input */
    for (int t = 0, nm = 1 + data[0] % 3; t < nm; t++) {
        unsigned f = rg2f_byte(&r);
        int cu = f & 1, cv = (f >> 1) & 1, nu = (cu ? 3 : 4) + (int)((f >> 2) % 7), nv = 4 + (int)((f >> 5) % 6);
        rg2_mesh *m = &pool[n];
        if (rg2_mesh_init(m, nu, nv, cu, cv, &err))
            rg2f_violation("rg2_mesh_init %d x %d: %s", nu, nv, err.msg);
        for (int k = 0; k < 2; k++) {
            rg2_scalars *s = k ? &m->sv : &m->su;
            for (int i = 0; i < rg2_scalars_num_w(s); i++)
                s->w[i] = 1.0 + 0.75 * tanh(rg2f_next(&r, 0.0));
            for (int i = 0; i < s->n; i++) {
                s->b[i] = exp(0.5 * tanh(rg2f_next(&r, 0.0)));
                s->g[i] = tanh(rg2f_next(&r, 0.0));
            }
        }
        for (int i = 0; i < nu; i++)
            for (int j = 0; j < nv; j++) {
                double *p = rg2_mesh_at(m, i, j);
                p[3] = 1.0 + 0.5 * tanh(rg2f_next(&r, 0.0));
                p[0] = p[3] * (i + rg2f_next(&r, 0.0));
                p[1] = p[3] * (j + rg2f_next(&r, 0.0));
                p[2] = p[3] * rg2f_next(&r, 0.0);
            }
        n++;
    }
    /* operations on the pool, each output (while there is room) joining it */
    for (int step = 0; step < 8 && o.at < o.n; step++) {
        unsigned op = rg2f_byte(&o);
        const rg2_mesh *a = &pool[rg2f_byte(&o) % (unsigned)n], *b = &pool[rg2f_byte(&o) % (unsigned)n];
        rg2_mesh out;
        memset(&out, 0xab, sizeof out);
        rg2_status st;
        const char *call;
        switch (op % 6) {
        case 0: {
            int first[2], last[2]; /* (read in order: an initializer list's order is unspecified) */
            first[0] = rg2f_index(&o);
            first[1] = rg2f_index(&o);
            last[0] = rg2f_index(&o);
            last[1] = rg2f_index(&o);
            call = "rg2_mesh_cut";
            st = rg2_mesh_cut(a, first, last, &out, &err);
            break;
        }
        case 1:
            call = "rg2_mesh_transpose";
            st = rg2_mesh_transpose(a, &out, &err);
            if (!st) { /* twice: the mesh itself, bit for bit */
                rg2_mesh back;
                if (rg2_mesh_transpose(&out, &back, &err) || !rg2f_same_mesh(&back, a))
                    rg2f_violation("rg2_mesh_transpose twice is not the mesh");
                rg2_mesh_free(&back);
            }
            break;
        case 2:
            call = "rg2_mesh_reverse";
            st = rg2_mesh_reverse(a, (int)(op >> 3) % 3, &out, &err);
            break;
        case 3: {
            const rg2_mesh *in[3] = {a, b, a};
            call = "rg2_mesh_merge";
            st = rg2_mesh_merge(in, 1 + (int)(op >> 3) % 3, (op >> 5) & 1, (op >> 6) & 1,
                                (rg2_seam_rule)((op >> 7) & 1), &out, &err);
            break;
        }
        case 4: {
            int dir = (int)(op >> 3) % 3, by = (int)rg2f_byte(&o) - 128; /* (dir 2: refused) */
            call = "rg2_mesh_roll";
            st = rg2_mesh_roll(a, dir, by, &out, &err);
            if (!st) { /* rolled back: the mesh, bit for bit */
                rg2_mesh back;
                if (!rg2_mesh_roll(&out, dir, -by, &back, &err)) {
                    if (!rg2f_same_mesh(&back, a))
                        rg2f_violation("rg2_mesh_roll by %d and back is not the mesh", by);
                    rg2_mesh_free(&back);
                }
            }
            break;
        }
        default: {
            double t = ((op >> 3) % 12) / 10.0 - 0.05; /* -0.05 .. 1.05 */
            call = "rg2_mesh_morph";
            st = rg2_mesh_morph(a, b, t, &out, &err);
            if (!st && t == 0.0 && !rg2f_same_mesh(&out, a))
                rg2f_violation("rg2_mesh_morph at t = 0 is not the first mesh");
            break;
        }
        }
        rg2f_check_error(call, st, &err);
        if (st) {
            rg2f_check_empty(call, &out);
            continue;
        }
        /* a valid mesh in, a valid mesh out, and its surface builds or says why not */
        if (rg2_mesh_check(&out, &err))
            rg2f_violation("%s gave a mesh that fails its check: %s", call, err.msg);
        { /* the net's normal at a point the input names: a unit vector, or a refusal that says why */
            int ni = (int)(rg2f_byte(&o) % (unsigned)out.nu), nj = (int)(rg2f_byte(&o) % (unsigned)out.nv);
            double nn[3];
            st = rg2_mesh_net_normal(&out, ni, nj, nn, &err);
            rg2f_check_error("rg2_mesh_net_normal", st, &err);
            double n2 = st ? 1.0 : nn[0] * nn[0] + nn[1] * nn[1] + nn[2] * nn[2];
            if (!(fabs(n2 - 1.0) <= 1e-12))
                rg2f_violation("rg2_mesh_net_normal of %s's mesh at [%d, %d]: |n|^2 = %.17g", call, ni, nj, n2);
        }
        if ((size_t)out.nu * (size_t)out.nv <= 4096) {
            rg2_surface s;
            st = rg2_surface_build(&out, &s, &err);
            rg2f_check_error("rg2_surface_build", st, &err);
            if (!st) {
                rg2f_check_surface(&s, call);
                rg2_surface_free(&s);
            }
        }
        if (n < RG2F_POOL)
            pool[n++] = out;
        else
            rg2_mesh_free(&out);
    }
    for (int k = 0; k < n; k++)
        rg2_mesh_free(&pool[k]);
    return 0;
}
