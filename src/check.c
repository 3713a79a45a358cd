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
 */
#include "export_internal.h"
#include "xpatch_util.h"

#include <cjson/cJSON.h>
#include <float.h>
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

typedef struct {
    int surf, dir, pi, pj, qi, qj;
    double t;
} seam_at;

static void gap_update(rg2_check_gap *g, double value, const seam_at *at, const double p[3])
{
    if (!isnan(g->value) && !(value <= g->value)) { /* NaN sticks: a broken seam cannot hide */
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
}

/* Whether (u, v) lies on a side of a patch whose collapsed-side bits (0 v=0, 1 u=1, 2 v=1,
 * 3 u=0; rg2__surface_collapsed_sides) are c. */
static int on_collapsed(unsigned c, double u, double v)
{
    return ((c & 1u) && v == 0.0) || ((c & 2u) && u == 1.0) || ((c & 4u) && v == 1.0) || ((c & 8u) && u == 0.0);
}

/* One seam point: L at the end of its transversal parameter, R at the start; pole: the point
 * lies on a collapsed side of either patch. */
static void seam_point(rg2_check_report *r, const rg2_eval *L, const rg2_eval *R, int dir, double size,
                       const seam_at *at, int pole)
{
    r->seam_samples++;
    double d[3] = {L->p[0] - R->p[0], L->p[1] - R->p[1], L->p[2] - R->p[2]};
    gap_update(&r->g0, norm3(d) / size, at, L->p);
    if (pole || ((L->flags | R->flags) & RG2_EVAL_NORMAL_UNDEFINED)) {
        r->skipped++;
        return;
    }
    double c[3];
    cross3(L->n, R->n, c);
    gap_update(&r->g1, atan2(norm3(c), dot3(L->n, R->n)), at, L->p);
    const double *along = dir == 0 ? L->sv : L->su;
    double la = norm3(along);
    if (!(la > 0)) {
        r->skipped++;
        return;
    }
    double t1[3] = {along[0] / la, along[1] / la, along[2] / la}, t2[3];
    cross3(L->n, t1, t2);
    double kscale = fmax(fmax(fabs(L->k1), fabs(L->k2)), 1.0 / size), worst = 0;
    for (int q = 0; q < 6; q++) {
        double ph = M_PI * q / 6.0, t[3];
        for (int k = 0; k < 3; k++)
            t[k] = cos(ph) * t1[k] + sin(ph) * t2[k];
        double jump = fabs(kn_dir(L, t) - kn_dir(R, t)) / kscale;
        if (!(jump <= worst))
            worst = jump;
    }
    gap_update(&r->g2, worst, at, L->p);
}

static void seams(rg2_check_report *r, const rg2_surface *s, int surf, int samples)
{
    double size = surface_size(s), tol = rg2__collapse_tol(s);
    for (int dir = 0; dir < 2; dir++) {
        int nA = dir == 0 ? s->nu : s->nv, nB = dir == 0 ? s->nv : s->nu;
        int closed = dir == 0 ? s->closed_u : s->closed_v;
        for (int a = closed ? 0 : 1; a < nA; a++) {
            int am = (a + nA - 1) % nA;
            if (am == a)
                continue; /* one closed patch: its seam is with itself */
            for (int b = 0; b < nB; b++) {
                r->seams++;
                seam_at at = {surf, dir, dir == 0 ? am : b, dir == 0 ? b : am, dir == 0 ? a : b, dir == 0 ? b : a, 0};
                unsigned cL = rg2__surface_collapsed_sides(s, at.pi, at.pj, tol);
                unsigned cR = rg2__surface_collapsed_sides(s, at.qi, at.qj, tol);
                for (int k = 0; k <= samples; k++) {
                    at.t = (double)k / samples;
                    rg2_eval L, R;
                    double uL = dir == 0 ? 1.0 : at.t, vL = dir == 0 ? at.t : 1.0;
                    double uR = dir == 0 ? 0.0 : at.t, vR = dir == 0 ? at.t : 0.0;
                    rg2_surface_eval(s, at.pi, at.pj, uL, vL, 2, &L);
                    rg2_surface_eval(s, at.qi, at.qj, uR, vR, 2, &R);
                    seam_point(r, &L, &R, dir, size, &at, on_collapsed(cL, uL, vL) || on_collapsed(cR, uR, vR));
                }
            }
        }
    }
}

/* Patch interiors: weights and curvature ranges at the samples, implicit residuals of tagged
 * patches against their shapes. */
static void patches(rg2_check_report *r, const rg2_surface *s, int surf, const rg2_shape *shapes, int n_shapes,
                    const double *shape_size, int S)
{
    size_t np = (size_t)s->nu * (size_t)s->nv;
    double tol = rg2__collapse_tol(s);
    for (size_t k = 0; k < np; k++) {
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
        unsigned coll = rg2__surface_collapsed_sides(s, pi, pj, tol);
        rg2__patch_degree(s, k, &du, &dv);
        for (int a = 0; a <= du; a++)
            for (int b = 0; b <= dv; b++) {
                double w = rg2__patch_ctrl(s, k, a, b)[3];
                if (!(w >= r->wmin)) r->wmin = w;
                if (!(w <= r->wmax)) r->wmax = w;
            }
        for (int a = 0; a <= S; a++)
            for (int b = 0; b <= S; b++) {
                double u = (double)a / S, v = (double)b / S, H[6][4];
                rg2_surface_eval_h(s, pi, pj, u, v, H);
                if (!(H[0][3] >= r->eval_wmin))
                    r->eval_wmin = H[0][3];
                rg2_eval e;
                rg2_surface_eval(s, pi, pj, u, v, 2, &e);
                if (!(e.flags & RG2_EVAL_CURVATURE_UNDEFINED) && !on_collapsed(coll, u, v)) {
                    r->kmin = fmin(r->kmin, e.k2);
                    r->kmax = fmax(r->kmax, e.k1);
                    r->Hmin = fmin(r->Hmin, e.H);
                    r->Hmax = fmax(r->Hmax, e.H);
                    r->Kmin = fmin(r->Kmin, e.K);
                    r->Kmax = fmax(r->Kmax, e.K);
                }
                if (tag < 0 || tag >= n_shapes)
                    continue;
                double g[3], f = rg2_shape_implicit(&shapes[tag], e.p, g), gn = norm3(g);
                if (!(gn > 0))
                    continue; /* singular point of the shape (apex): no distance estimate */
                double res = fabs(f) / gn / shape_size[tag];
                rg2_check_shape *cs = &r->shapes[tag];
                if (!isnan(cs->residual) && !(res <= cs->residual)) {
                    cs->residual = res;
                    snprintf(cs->where, sizeof cs->where, "surface %d patch (%d,%d) u=%.3g v=%.3g", surf, pi, pj,
                             u, v);
                }
            }
    }
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
    if (o->seam_samples < 1 || o->seam_samples > 10000 || o->patch_samples < 1 || o->patch_samples > 1000)
        return rg2__fail(err, RG2_EINVAL, "check: samples %d per seam / %d per patch outside 1..10000 / 1..1000",
                         o->seam_samples, o->patch_samples);
    for (int s = 0; s < n; s++) {
        if (surfs[s].nu <= 0 || surfs[s].nv <= 0 || !surfs[s].patch)
            return rg2__fail(err, RG2_EINVAL, "check: surface %d has no patches", s);
        if (!surfs[s].bu || !surfs[s].bv)
            return rg2__fail(err, RG2_EINVAL, "check: surface %d has no junction scalars", s);
    }
    out->opts = *o;
    out->surfaces = n;
    out->n_shapes = n_shapes;
    out->shapes = rg2__calloc((size_t)(n_shapes > 0 ? n_shapes : 1), sizeof *out->shapes);
    double *shape_size = rg2__calloc((size_t)(n_shapes > 0 ? n_shapes : 1), sizeof *shape_size);
    double *shape_box = rg2__calloc((size_t)(n_shapes > 0 ? n_shapes : 1), 6 * sizeof *shape_box);
    if (!out->shapes || !shape_size || !shape_box) {
        free(shape_size);
        free(shape_box);
        rg2_check_report_free(out);
        return rg2__fail(err, RG2_ENOMEM, "check: out of memory for %d shapes", n_shapes);
    }
    for (int k = 0; k < n_shapes; k++) {
        out->shapes[k].shape = k;
        const char *name = rg2_shape_name(shapes[k].kind);
        snprintf(out->shapes[k].label, sizeof out->shapes[k].label, "%s",
                 labels && labels[k] ? labels[k] : (name ? name : "shape"));
        snprintf(out->shapes[k].where, sizeof out->shapes[k].where, "-");
        for (int d = 0; d < 3; d++) {
            shape_box[6 * k + d] = DBL_MAX;
            shape_box[6 * k + 3 + d] = -DBL_MAX;
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
        for (int d = 0; d < 3; d++) {
            double e = shape_box[6 * k + 3 + d] - shape_box[6 * k + d];
            d2 += e > 0 ? e * e : 0;
        }
        shape_size[k] = d2 > 0 ? sqrt(d2) : out->size;
    }
    out->wmin = out->eval_wmin = DBL_MAX;
    out->wmax = -DBL_MAX;
    out->kmin = out->Hmin = out->Kmin = DBL_MAX;
    out->kmax = out->Hmax = out->Kmax = -DBL_MAX;
    for (int s = 0; s < n; s++) {
        seams(out, &surfs[s], s, o->seam_samples);
        patches(out, &surfs[s], s, shapes, n_shapes, shape_size, o->patch_samples);
    }
    if (out->kmin > out->kmax)
        out->kmin = out->kmax = out->Hmin = out->Hmax = out->Kmin = out->Kmax = 0;
    for (int k = 0; k < n_shapes; k++)
        if (!(out->shapes[k].residual <= out->worst_residual))
            out->worst_residual = out->shapes[k].residual;
    free(shape_size);
    free(shape_box);
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

unsigned rg2_check_failures(const rg2_check_report *r, unsigned require)
{
    unsigned f = 0;
    const rg2_check_opts *o = &r->opts;
    int g0 = !(r->g0.value <= o->tol_g0), g1 = g0 || !(r->g1.value <= o->tol_g1), g2 = g1 || !(r->g2.value <= o->tol_g2);
    if ((require & RG2_REQUIRE_G0) && g0)
        f |= RG2_REQUIRE_G0;
    if ((require & RG2_REQUIRE_G1) && g1)
        f |= RG2_REQUIRE_G1;
    if ((require & RG2_REQUIRE_G2) && g2)
        f |= RG2_REQUIRE_G2;
    if ((require & RG2_REQUIRE_EXACT) && (!(r->worst_residual <= o->tol_exact) || r->untagged_bad > 0))
        f |= RG2_REQUIRE_EXACT;
    if ((require & RG2_REQUIRE_WEIGHTS) && !(r->wmin > 0 && r->eval_wmin > 0))
        f |= RG2_REQUIRE_WEIGHTS;
    return f;
}

/* ---------------------------------------------------------------- formatting */

typedef struct {
    char *s;
    size_t len, cap;
    int oom;
} sbuf;

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

static void gap_text(sbuf *b, const char *name, const char *unit, const rg2_check_gap *g, double tol, int seams)
{
    sb_printf(b, "  %-22s %9.2e %-5s %-4s (limit %.0e)", name, g->value, unit, seams ? verdict(g->value, tol) : "-",
              tol);
    if (seams && g->value > 0)
        sb_printf(b, "  at surface %d %s seam (%d,%d)|(%d,%d) t=%.3g, point (%.6g, %.6g, %.6g)", g->surf,
                  g->seam_dir == 0 ? "u" : "v", g->pi, g->pj, g->qi, g->qj, g->t, g->p[0], g->p[1], g->p[2]);
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
        sb_printf(b, "exact pieces                 patches  worst residual  verdict  where\n");
        for (int k = 0; k < r->n_shapes; k++) {
            const rg2_check_shape *s = &r->shapes[k];
            sb_printf(b, "  %2d %-24.24s %7d  %14.2e  %-7s  %s\n", k, s->label, s->patches, s->residual,
                      s->patches ? verdict(s->residual, o->tol_exact) : "-", s->where);
        }
    }
    sb_printf(b, "seams %d, %d samples (%d with an undefined normal)\n", r->seams, r->seam_samples, r->skipped);
    gap_text(b, "G0 position gap", "rel", &r->g0, o->tol_g0, r->seams);
    gap_text(b, "G1 normal angle", "rad", &r->g1, o->tol_g1, r->seams);
    gap_text(b, "G2 curvature jump", "rel", &r->g2, o->tol_g2, r->seams);
    sb_printf(b, "homogeneous weights  control points [%.6g, %.6g], at samples min %.6g %s\n", r->wmin, r->wmax,
              r->eval_wmin, r->wmin > 0 ? "(all > 0)" : "(NON-POSITIVE)");
    sb_printf(b, "curvature            k [%.6g, %.6g]  H [%.6g, %.6g]  K [%.6g, %.6g]\n", r->kmin, r->kmax, r->Hmin,
              r->Hmax, r->Kmin, r->Kmax);
    sb_printf(b, "size                 %.6g (box diagonal)\n", r->size);
}

static cJSON *gap_json(const rg2_check_gap *g, double tol)
{
    cJSON *j = cJSON_CreateObject();
    cJSON_AddNumberToObject(j, "value", g->value);
    cJSON_AddNumberToObject(j, "limit", tol);
    cJSON_AddBoolToObject(j, "ok", g->value <= tol);
    cJSON_AddNumberToObject(j, "surface", g->surf);
    cJSON_AddStringToObject(j, "seam", g->seam_dir == 0 ? "u" : "v");
    int a[2] = {g->pi, g->pj}, c[2] = {g->qi, g->qj};
    cJSON_AddItemToObject(j, "patch_a", cJSON_CreateIntArray(a, 2));
    cJSON_AddItemToObject(j, "patch_b", cJSON_CreateIntArray(c, 2));
    cJSON_AddNumberToObject(j, "t", g->t);
    cJSON_AddItemToObject(j, "point", cJSON_CreateDoubleArray(g->p, 3));
    return j;
}

static char *format_json(const rg2_check_report *r)
{
    const rg2_check_opts *o = &r->opts;
    cJSON *j = cJSON_CreateObject();
    if (!j)
        return NULL;
    cJSON_AddNumberToObject(j, "surfaces", r->surfaces);
    cJSON_AddNumberToObject(j, "patches", r->patches);
    cJSON_AddNumberToObject(j, "exact_patches", r->exact_patches);
    cJSON_AddNumberToObject(j, "transitions", r->transitions);
    cJSON_AddNumberToObject(j, "unknown_tags", r->untagged_bad);
    cJSON *sh = cJSON_AddArrayToObject(j, "shapes");
    for (int k = 0; k < r->n_shapes; k++) {
        cJSON *s = cJSON_CreateObject();
        cJSON_AddNumberToObject(s, "index", k);
        cJSON_AddStringToObject(s, "label", r->shapes[k].label);
        cJSON_AddNumberToObject(s, "patches", r->shapes[k].patches);
        cJSON_AddNumberToObject(s, "residual", r->shapes[k].residual);
        cJSON_AddBoolToObject(s, "ok", r->shapes[k].residual <= o->tol_exact);
        cJSON_AddStringToObject(s, "where", r->shapes[k].where);
        cJSON_AddItemToArray(sh, s);
    }
    cJSON_AddNumberToObject(j, "worst_residual", r->worst_residual);
    cJSON_AddNumberToObject(j, "exact_limit", o->tol_exact);
    cJSON_AddNumberToObject(j, "seams", r->seams);
    cJSON_AddNumberToObject(j, "seam_samples", r->seam_samples);
    cJSON_AddNumberToObject(j, "skipped", r->skipped);
    cJSON_AddItemToObject(j, "g0_position", gap_json(&r->g0, o->tol_g0));
    cJSON_AddItemToObject(j, "g1_normal_angle", gap_json(&r->g1, o->tol_g1));
    cJSON_AddItemToObject(j, "g2_curvature_jump", gap_json(&r->g2, o->tol_g2));
    double w[3] = {r->wmin, r->wmax, r->eval_wmin}, k[6] = {r->kmin, r->kmax, r->Hmin, r->Hmax, r->Kmin, r->Kmax};
    cJSON_AddItemToObject(j, "weights", cJSON_CreateDoubleArray(w, 2));
    cJSON_AddNumberToObject(j, "min_weight_at_samples", w[2]);
    cJSON_AddItemToObject(j, "principal_curvature", cJSON_CreateDoubleArray(k, 2));
    cJSON_AddItemToObject(j, "mean_curvature", cJSON_CreateDoubleArray(k + 2, 2));
    cJSON_AddItemToObject(j, "gauss_curvature", cJSON_CreateDoubleArray(k + 4, 2));
    cJSON_AddNumberToObject(j, "size", r->size);
    unsigned f = rg2_check_failures(r, RG2_REQUIRE_G2 | RG2_REQUIRE_EXACT | RG2_REQUIRE_WEIGHTS);
    cJSON_AddBoolToObject(j, "g2", !(f & RG2_REQUIRE_G2));
    cJSON_AddBoolToObject(j, "exact", !(f & RG2_REQUIRE_EXACT));
    cJSON_AddBoolToObject(j, "positive_weights", !(f & RG2_REQUIRE_WEIGHTS));
    char *txt = cJSON_Print(j);
    cJSON_Delete(j);
    return txt;
}

rg2_status rg2_check_format(const rg2_check_report *r, int json, char **text, rg2_error *err)
{
    if (!r || !text)
        return rg2__fail(err, RG2_EINVAL, "check: nothing to format");
    *text = NULL;
    if (json) {
        char *c = format_json(r);
        if (!c)
            return rg2__fail(err, RG2_ENOMEM, "check: out of memory formatting JSON");
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
            free(b.s);
            return rg2__fail(err, RG2_ENOMEM, "check: out of memory formatting the table");
        }
        *text = b.s;
    }
    if (!*text)
        return rg2__fail(err, RG2_ENOMEM, "check: out of memory formatting the report");
    rg2__ok(err);
    return RG2_OK;
}
