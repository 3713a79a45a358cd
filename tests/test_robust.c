/* test_robust.c -- numerical robustness at extreme scales and near-degenerate partitions.
 *
 * 1. Every named shape, default partitions, placed at scales 1e-6 .. 1e6 (rotated) and
 *    centred 0, 1e3 and 1e6 away from the origin: the built patches lie on the placed shape's
 *    implicit surface (residual |f| / (|grad f| L) <= 1e-12 with L = size + offset: a double
 *    coordinate of magnitude L carries an absolute error of about eps L, so nothing finer can
 *    be asked of a stored point), and the seams are G2 (measured with rg2t_surface_seams; the
 *    angle, curvature and position figures are divided by rho = L / size, the factor by which
 *    the placement's offset coarsens the coordinates relative to the shape).
 * 2. Near-degenerate circle partitions: arcs of 1e-4 .. 1e-7 rad next to ordinary ones, and
 *    arcs just under pi (pi - 1e-2 .. pi - 1e-9). Each either builds to the same accuracy or is
 *    refused with a message naming the arc; the figures are printed (docs/robustness.md).
 * 3. Power-of-two scalings of a torus and a sphere mesh: the coordinates by 2^a (a up to +-330,
 *    sizes 1e-99 .. 1e99) and all four homogeneous values by 2^b (weights 1e-90 .. 1e90, the
 *    same surface). Scaling by a power of two is exact, so every evaluator must give the
 *    unscaled results times the exact power: positions 2^a, normals the same bits, K 2^-2a,
 *    H 2^-a. rg2_patch_eval and rg2_patch_point_normal over the whole range, the grid over
 *    the design range (|a| <= 190, about 1e57).
 */
#include "harness.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

typedef struct {
    double resid;      /* max |f| / (|grad f| L) */
    double resid_size; /* the same relative to the shape's size */
    double angle, curv, pos; /* seam figures divided by rho */
    double angle_raw, curv_raw;
} fig;

static double dot3(const double *a, const double *b) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }

/* Sample every patch on an ns x ns grid (corners included) against the implicit equation. */
static void residuals(const rg2_shape *sh, const rg2_surface *s, double L, double size, int ns, fig *f)
{
    for (int i = 0; i < s->nu; i++)
        for (int j = 0; j < s->nv; j++)
            for (int a = 0; a < ns; a++)
                for (int b = 0; b < ns; b++) {
                    rg2_eval e;
                    rg2_patch_eval(rg2_surface_patch(s, i, j), (double)a / (ns - 1), (double)b / (ns - 1),
                                   0, &e);
                    double g[3];
                    double v = rg2_shape_implicit(sh, e.p, g);
                    double gn = sqrt(dot3(g, g));
                    if (gn == 0.0)
                        continue; /* a singular point of the implicit form (cone apex) */
                    double r = fabs(v) / (gn * L);
                    if (!(r <= f->resid))
                        f->resid = r;
                    r = fabs(v) / (gn * size);
                    if (!(r <= f->resid_size))
                        f->resid_size = r;
                }
}

static void seams(const rg2_surface *s, double rho, fig *f)
{
    rg2t_seams g;
    rg2t_surface_seams(s, 6, &g);
    f->angle = fmax(f->angle, g.angle / rho);
    f->curv = fmax(f->curv, g.curv / rho);
    f->pos = fmax(f->pos, g.pos / rho);
    f->angle_raw = fmax(f->angle_raw, g.angle);
    f->curv_raw = fmax(f->curv_raw, g.curv);
}

/* The shape's default partition of one direction, kept away from poles and apexes. */
static void default_partition(rg2_shape_kind kind, int dir, double *vals, rg2_partition *p)
{
    const rg2_shape_desc *d = rg2_shape_describe(kind);
    double lo = d->default_range[dir][0], hi = d->default_range[dir][1];
    rg2_error err;
    rg2_status st = rg2_partition_equal(p, d->dir_kind[dir], d->default_closed[dir], lo, hi,
                                        d->default_segments[dir], vals, 64, &err);
    CHECK(st == RG2_OK, "%s default partition %d: %s", d->name, dir, err.msg);
}

/* ------------------------------------------------------------------------------------- */

static void scales(void)
{
    static const double sc[5] = {1e-6, 1e-3, 1.0, 1e3, 1e6};
    static const double off[3] = {0.0, 1e3, 1e6};
    printf("named shapes at scales 1e-6 .. 1e6 and offsets 0, 1e3, 1e6 (default partitions):\n"
           "  residual = |f| / (|grad f| L), L = size + offset; seam figures / rho, rho = L / size\n");
    printf("  %-19s %10s %10s %10s %10s %10s %10s\n", "shape", "residual", "res/size", "angle",
           "curvature", "position", "angle raw");
    fig all;
    memset(&all, 0, sizeof all);
    double grid[5][3] = {{0}}; /* worst residual relative to the size, per scale and offset */
    for (int kind = 0; kind < RG2_SHAPE_COUNT; kind++) {
        const rg2_shape_desc *d = rg2_shape_describe((rg2_shape_kind)kind);
        fig f;
        memset(&f, 0, sizeof f);
        double vu[64], vv[64];
        rg2_partition pu, pv;
        default_partition((rg2_shape_kind)kind, 0, vu, &pu);
        default_partition((rg2_shape_kind)kind, 1, vv, &pv);
        for (int a = 0; a < 5; a++)
            for (int b = 0; b < 3; b++) {
                rg2_shape sh;
                rg2_shape_init(&sh, (rg2_shape_kind)kind);
                double S[16], R[16], T[16];
                rg2_xform_scale(S, sc[a], sc[a], sc[a]);
                rg2_xform_rotate(R, 1.0, 2.0, 3.0, 0.7);
                double u[3] = {1.0 / sqrt(3.0), -1.0 / sqrt(3.0), 1.0 / sqrt(3.0)};
                rg2_xform_translate(T, off[b] * u[0], off[b] * u[1], off[b] * u[2]);
                rg2_xform_mul(R, S, sh.xform);
                rg2_xform_mul(T, sh.xform, sh.xform);
                rg2_surface s;
                rg2_error err;
                rg2_status st = rg2_shape_surface(&sh, &pu, &pv, &s, NULL, &err);
                CHECK(st == RG2_OK, "%s scale %g offset %g: %s", d->name, sc[a], off[b], err.msg);
                if (st)
                    continue;
                double size = rg2t_surface_scale(&s);
                /* the control polygon's box can be much larger than the shape near poles;
                 * the shape's own size is its unit size times the scale */
                size = fmin(size, 10.0 * sc[a] * (d->param_defaults[0] > 0 ? d->param_defaults[0] + 1 : 2));
                double L = size + off[b], rho = L / size;
                fig one;
                memset(&one, 0, sizeof one);
                residuals(&sh, &s, L, size, 5, &one);
                f.resid = fmax(f.resid, one.resid);
                f.resid_size = fmax(f.resid_size, one.resid_size);
                grid[a][b] = fmax(grid[a][b], one.resid_size);
                seams(&s, rho, &f);
                rg2_surface_free(&s);
            }
        printf("  %-19s %10.2e %10.2e %10.2e %10.2e %10.2e %10.2e\n", d->name, f.resid, f.resid_size,
               f.angle, f.curv, f.pos, f.angle_raw);
        CHECK(f.resid <= 1e-12, "%s: residual %.3g over all scales and offsets", d->name, f.resid);
        CHECK(f.angle <= 1e-12, "%s: seam normal angle / rho %.3g", d->name, f.angle);
        CHECK(f.curv <= 1e-10, "%s: seam curvature jump / rho %.3g", d->name, f.curv);
        CHECK(f.pos <= 1e-14, "%s: seam position gap / rho %.3g", d->name, f.pos);
        all.resid = fmax(all.resid, f.resid);
        all.angle = fmax(all.angle, f.angle);
        all.curv = fmax(all.curv, f.curv);
    }
    printf("  worst: residual %.2e, angle %.2e, curvature %.2e\n", all.resid, all.angle, all.curv);
    printf("  residual relative to the shape's size (worst over the shapes), by scale and offset:\n"
           "  %8s %10s %10s %10s\n", "scale", "offset 0", "1e3", "1e6");
    for (int a = 0; a < 5; a++) {
        printf("  %8.0e %10.2e %10.2e %10.2e\n", sc[a], grid[a][0], grid[a][1], grid[a][2]);
        /* coordinates of magnitude L carry eps L: relative to the size that is eps rho */
        for (int b = 0; b < 3; b++)
            CHECK(grid[a][b] <= 1e-15 * (off[b] + sc[a]) / sc[a] + 1e-14,
                  "scale %g offset %g: residual / size %.3g beyond the double precision of the placement",
                  sc[a], off[b], grid[a][b]);
    }
}

/* ------------------------------------------------------------------------------------- */
/* near-degenerate circle partitions on the torus (both directions circles) */

/* The smallest patch of a surface: the bounding-box diagonal of its control points. */
static double smallest_patch(const rg2_surface *s)
{
    double mn = INFINITY;
    for (int k = 0; k < s->nu * s->nv; k++) {
        rg2_surface one = *s;
        one.nu = one.nv = 1;
        one.patch = &s->patch[k];
        mn = fmin(mn, rg2t_surface_scale(&one));
    }
    return mn;
}

/* Build a torus over the u partition (n arcs, closed or open) and 6 closed v arcs; fill f
 * with the residual relative to the surface size and the seam figures divided by
 * rho = surface size / smallest patch size. Returns the status (message in err). */
static rg2_status torus_partition(const double *arcs, int n, int closed, fig *f, rg2_error *err)
{
    rg2_shape sh;
    rg2_shape_init(&sh, RG2_SHAPE_TORUS);
    double vv[8];
    rg2_partition pu = {RG2_PART_ANGLES, closed, n, arcs, 0.3}, pv;
    rg2_status st = rg2_partition_equal(&pv, RG2_PART_ANGLES, 1, 0.0, 0.0, 6, vv, 8, err);
    if (st)
        return st;
    rg2_surface s;
    st = rg2_shape_surface(&sh, &pu, &pv, &s, NULL, err);
    if (st)
        return st;
    double size = rg2t_surface_scale(&s);
    memset(f, 0, sizeof *f);
    residuals(&sh, &s, size, size, 7, f);
    seams(&s, size / smallest_patch(&s), f);
    rg2_surface_free(&s);
    return RG2_OK;
}

/* Near-degenerate partitions must build to the accuracy of the other tests (raw seam
 * figures: angle <= 1e-12, curvature jump <= 1e-10; residual <= 1e-12) or, where `refuse` is
 * set, be refused with RG2_EDOMAIN and a message naming the arc. */
static void report(const char *what, double param, int refuse, rg2_status st, const rg2_error *err,
                   const fig *f)
{
    if (st) {
        printf("  %-30s %8.1e  refused: %.90s...\n", what, param, err->msg);
        CHECK(refuse, "%s %g: refused: %s", what, param, err->msg);
        CHECK(st == RG2_EDOMAIN && strstr(err->msg, "arc"), "%s %g: refusal %s does not name the arc: %s",
              what, param, rg2_status_str(st), err->msg);
        return;
    }
    printf("  %-30s %8.1e  %9.2e %9.2e %9.2e %9.2e %9.2e\n", what, param, f->resid, f->angle, f->curv,
           f->angle_raw, f->curv_raw);
    CHECK(!refuse, "%s %g: accepted, should be refused", what, param);
    CHECK(f->resid <= 1e-12, "%s %g: residual %.3g", what, param, f->resid);
    CHECK(f->angle_raw <= 1e-12, "%s %g: seam angle %.3g", what, param, f->angle_raw);
    CHECK(f->curv_raw <= 1e-10, "%s %g: seam curvature jump %.3g", what, param, f->curv_raw);
}

static void degenerate_partitions(void)
{
    printf("near-degenerate torus u partitions (v: 6 closed arcs); residual relative to the size,\n"
           "seam figures / rho with rho = surface size / smallest patch size, then raw:\n"
           "  %-30s %8s  %9s %9s %9s %9s %9s\n", "partition", "arc", "residual", "angle", "curvature",
           "angle raw", "curv raw");
    rg2_error err;
    fig f;
    /* tiny arcs: an open run of 4 tiny arcs, and 2 tiny arcs inside a closed circle */
    const double min_arc = 5e-3; /* RG2_MIN_ARC (src/internal.h, README "Limits and errors") */
    static const double tiny[] = {1e-2, 5e-3, 4e-3, 3e-3, 2e-3, 1e-3, 1e-4, 1e-5, 1e-7};
    for (size_t q = 0; q < sizeof tiny / sizeof tiny[0]; q++) {
        double t = tiny[q];
        double open4[4] = {t, t, t, t};
        rg2_status st = torus_partition(open4, 4, 0, &f, &err);
        report("open, 4 arcs of", t, t < min_arc, st, &err, &f);
        double closed5[5] = {t, t, (2.0 * M_PI - 2.0 * t) / 3.0, (2.0 * M_PI - 2.0 * t) / 3.0, 0};
        closed5[4] = 2.0 * M_PI - closed5[0] - closed5[1] - closed5[2] - closed5[3];
        st = torus_partition(closed5, 5, 1, &f, &err);
        report("closed, 2 arcs of", t, t < min_arc, st, &err, &f);
    }
    /* arcs just under pi (next to ordinary arcs): open [pi/2, pi - d, pi/2], closed
     * [pi - d, pi/2 + d/2, pi/2 + d/2] */
    static const double under[] = {1e-2, 1e-4, 1e-6, 1e-9, 1e-12, 1e-15, 4.4e-16};
    /* 4.4e-16 is the last double below pi: pi - 4.4e-16 = nextafter(pi, 0) */
    for (size_t q = 0; q < sizeof under / sizeof under[0]; q++) {
        double dd = under[q];
        double open3[3] = {0.5 * M_PI, M_PI - dd, 0.5 * M_PI};
        rg2_status st = torus_partition(open3, 3, 0, &f, &err);
        report("open, 1 arc of pi minus", dd, 0, st, &err, &f);
        double closed3[3] = {M_PI - dd, 0.5 * (M_PI + dd), 0};
        closed3[2] = 2.0 * M_PI - closed3[0] - closed3[1];
        st = torus_partition(closed3, 3, 1, &f, &err);
        report("closed, 1 arc of pi minus", dd, 0, st, &err, &f);
    }
    /* an arc near pi at an open end meets its data-only copy, and two open arcs near pi meet each
     * other: their common control point lies about 4 / (2 pi - sum) away (residual 0.08 for one
     * arc of pi - 4.4e-16, 7e-5 for two of pi - 1.7e-12); refused where the sum leaves less than
     * the smallest arc of the circle */
    static const double end_d[] = {1e-1, 1e-2, 2.6e-3, 2.4e-3, 1e-4, 1e-9, 1.7e-12, 4.4e-16};
    for (size_t q = 0; q < sizeof end_d / sizeof end_d[0]; q++) {
        double dd = end_d[q];
        double one[1] = {M_PI - dd}, two[2] = {M_PI - dd, M_PI - dd}, mid[3] = {0.5, M_PI - dd, 0.5};
        rg2_status st = torus_partition(one, 1, 0, &f, &err);
        report("open, its only arc pi minus", dd, 2 * dd < min_arc, st, &err, &f);
        st = torus_partition(two, 2, 0, &f, &err);
        report("open, 2 arcs of pi minus", dd, 2 * dd < min_arc, st, &err, &f);
        st = torus_partition(mid, 3, 0, &f, &err); /* next to arcs of 0.5: accepted */
        report("open, between 0.5s, pi minus", dd, 0, st, &err, &f);
    }
}

/* ------------------------------------------------------------------------------------- */

/* The surface of a mesh whose points are scaled: xyz by 2^a, all four values by 2^b. */
static int scaled_surface(const rg2_mesh *m0, int a, int b, rg2_surface *s)
{
    rg2_mesh m;
    rg2_error err;
    if (rg2_mesh_copy(m0, &m, &err) != RG2_OK)
        return 0;
    for (size_t k = 0; k < (size_t)m.nu * (size_t)m.nv; k++)
        for (int q = 0; q < 4; q++)
            m.p[4 * k + q] = ldexp(m.p[4 * k + q], (q < 3 ? a : 0) + b);
    rg2_status st = rg2_surface_build(&m, s, &err);
    CHECK(st == RG2_OK, "scaled 2^%d, weights 2^%d: %s", a, b, err.msg);
    rg2_mesh_free(&m);
    return st == RG2_OK;
}

static int same3(const double *x, const double *y, int e)
{
    return x[0] == ldexp(y[0], e) && x[1] == ldexp(y[1], e) && x[2] == ldexp(y[2], e);
}

static void power_scales(void)
{
    static const int as[] = {-330, -250, -190, -100, 0, 100, 190, 250, 330};
    static const int bs[] = {-300, -150, 0, 150, 300};
    printf("power-of-two scalings (coordinates 2^a, weights 2^b): results must be the exact powers\n");
    for (int kind = 0; kind < 2; kind++) {
        rg2_shape_kind sk = kind ? RG2_SHAPE_SPHERE : RG2_SHAPE_TORUS;
        double vu[64], vv[64];
        rg2_partition pu, pv;
        default_partition(sk, 0, vu, &pu);
        default_partition(sk, 1, vv, &pv);
        rg2_shape sh;
        rg2_shape_init(&sh, sk);
        rg2_mesh m0;
        rg2_error err;
        rg2_surface s0;
        if (rg2_shape_mesh(&sh, &pu, &pv, &m0, &err) != RG2_OK || !scaled_surface(&m0, 0, 0, &s0)) {
            CHECK(0, "shape mesh: %s", err.msg);
            continue;
        }
        const int n = 8, per = n * n;
        size_t pts = (size_t)s0.nu * (size_t)s0.nv * (size_t)per;
        double *g0 = calloc(8 * pts, sizeof(double)), *g1 = calloc(8 * pts, sizeof(double));
        rg2_grid_out o0 = {.pos = g0, .normal = g0 + 3 * pts, .K = g0 + 6 * pts, .H = g0 + 7 * pts};
        rg2_grid_out o1 = {.pos = g1, .normal = g1 + 3 * pts, .K = g1 + 6 * pts, .H = g1 + 7 * pts};
        CHECK(rg2_surface_grid(&s0, n, n, 1, &o0, &err) == RG2_OK, "grid: %s", err.msg);
        int bad_eval = 0, bad_point = 0, bad_grid = 0, cases = 0, undefined = 0;
        for (size_t ia = 0; ia < sizeof as / sizeof as[0]; ia++)
            for (size_t ib = 0; ib < sizeof bs / sizeof bs[0]; ib++) {
                int a = as[ia], b = bs[ib];
                rg2_surface s;
                if (!scaled_surface(&m0, a, b, &s))
                    continue;
                cases++;
                for (int i = 0; i < s.nu; i++)
                    for (int j = 0; j < s.nv; j++)
                        for (int q = 0; q < 25; q++) {
                            double u = (q / 5) / 4.0, v = (q % 5) / 4.0;
                            rg2_eval e0, e;
                            rg2_patch_eval(rg2_surface_patch(&s0, i, j), u, v, 2, &e0);
                            rg2_patch_eval(rg2_surface_patch(&s, i, j), u, v, 2, &e);
                            undefined += (e0.flags & RG2_EVAL_NORMAL_UNDEFINED) != 0;
                            if (e.flags != e0.flags || !same3(e.p, e0.p, a) || !same3(e.n, e0.n, 0) ||
                                e.K != ldexp(e0.K, -2 * a) || e.H != ldexp(e0.H, -a)) {
                                if (bad_eval++ < 3)
                                    printf("  rg2_patch_eval 2^%d 2^%d patch (%d,%d) (%g,%g): flags %u/%u "
                                           "n (%g %g %g)/(%g %g %g) K %g/%g\n",
                                           a, b, i, j, u, v, e.flags, e0.flags, e.n[0], e.n[1], e.n[2],
                                           e0.n[0], e0.n[1], e0.n[2], e.K, ldexp(e0.K, -2 * a));
                            }
                            double p0[3], n0[3], p1[3], n1[3];
                            unsigned f0 = rg2_patch_point_normal(rg2_surface_patch(&s0, i, j), u, v, p0, n0);
                            unsigned f1 = rg2_patch_point_normal(rg2_surface_patch(&s, i, j), u, v, p1, n1);
                            if (f0 != f1 || !same3(p1, p0, a) || !same3(n1, n0, 0))
                                bad_point++;
                        }
                if (a >= -190 && a <= 190) {
                    CHECK(rg2_surface_grid(&s, n, n, 1, &o1, &err) == RG2_OK, "grid: %s", err.msg);
                    for (size_t k = 0; k < pts; k++)
                        if (!same3(g1 + 3 * k, g0 + 3 * k, a) || !same3(o1.normal + 3 * k, o0.normal + 3 * k, 0) ||
                            o1.K[k] != ldexp(o0.K[k], -2 * a) || o1.H[k] != ldexp(o0.H[k], -a)) {
                            if (bad_grid++ < 3)
                                printf("  grid 2^%d 2^%d point %zu: n (%g %g %g)/(%g %g %g)\n", a, b, k,
                                       o1.normal[3 * k], o1.normal[3 * k + 1], o1.normal[3 * k + 2],
                                       o0.normal[3 * k], o0.normal[3 * k + 1], o0.normal[3 * k + 2]);
                        }
                }
                rg2_surface_free(&s);
            }
        printf("  %-7s %d scalings: rg2_patch_eval %d, rg2_patch_point_normal %d, grid %d points off "
               "(%d reference samples with an undefined normal, at the poles)\n",
               kind ? "sphere" : "torus", cases, bad_eval, bad_point, bad_grid, undefined);
        CHECK(cases == (int)(sizeof as / sizeof as[0] * sizeof bs / sizeof bs[0]), "%d scalings built", cases);
        CHECK(bad_eval == 0, "rg2_patch_eval: %d samples not the exact powers", bad_eval);
        CHECK(bad_point == 0, "rg2_patch_point_normal: %d samples not the exact powers", bad_point);
        CHECK(bad_grid == 0, "grid: %d points not the exact powers", bad_grid);
        free(g0);
        free(g1);
        rg2_surface_free(&s0);
        rg2_mesh_free(&m0);
    }
}

int main(void)
{
    scales();
    degenerate_partitions();
    power_scales();
    return rg2t_done("test_robust");
}
