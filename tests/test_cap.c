/* test_cap.c -- bi-3 polar caps: the complete sphere from a polar mesh (exact, G2, one pole
 * point with one limit normal), exact recovery of the cap coefficients on sphere data, exact
 * paraboloid and two-sheeted hyperboloid caps, free-form caps (perturbed spheres, random
 * tubes) with G2 seams and a smooth pole, the output's layout (body patches kept bit for bit,
 * the same bits on 1 and 2 threads), and the errors for degenerate input. */
#define _POSIX_C_SOURCE 200809L /* mkdtemp, rmdir */
#include "poles_testutil.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>
#ifdef _OPENMP
#include <omp.h>
#endif

static void unit(double a[3])
{
    double l = sqrt(a[0] * a[0] + a[1] * a[1] + a[2] * a[2]);
    for (int k = 0; k < 3; k++)
        a[k] /= l;
}

/* Limit normal at a collapsed edge v = v0 (0 or 1) of a patch: su = (v - v0) suv + ..., so
 * n ~ sign(v - v0) suv x sv. */
static void limit_normal(const rg2_surface *s, int i, int j, double u, double v0, double n[3], unsigned *flags)
{
    rg2_eval e;
    rg2_surface_eval(s, i, j, u, v0, 2, &e);
    *flags = e.flags;
    double sg = v0 == 0.0 ? 1.0 : -1.0;
    n[0] = sg * (e.suv[1] * e.sv[2] - e.suv[2] * e.sv[1]);
    n[1] = sg * (e.suv[2] * e.sv[0] - e.suv[0] * e.sv[2]);
    n[2] = sg * (e.suv[0] * e.sv[1] - e.suv[1] * e.sv[0]);
    unit(n);
}

/* Pole measurements of a capped surface for end e (0: v = 0 of row 0, 1: v = 1 of the last
 * row): spread of the pole point, spread of the limit normals over every fan patch, whether
 * the evaluator flags the pole, and the approach of normal and curvature as v -> pole. */
typedef struct {
    double point, normal;   /* max distance between pole evaluations / scale; max normal angle */
    int flagged, samples;   /* evaluations at the pole that set RG2_EVAL_NORMAL_UNDEFINED */
    double nconv[4];        /* max angle between n(u, eps) and the limit normal, eps = 1e-1..1e-4 */
    double kspread[4];      /* spread of K and H over the fan at eps, relative to |k|max */
    double pole[3], n[3];
} pole_meas;

static void measure_pole(const rg2_surface *s, int e, double scale, pole_meas *pm)
{
    memset(pm, 0, sizeof *pm);
    int j = e ? s->nv - 1 : 0;
    double v0 = e ? 1.0 : 0.0;
    int first = 1;
    for (int i = 0; i < s->nu; i++)
        for (int k = 0; k <= 8; k++) {
            double u = k / 8.0, n[3];
            unsigned fl;
            limit_normal(s, i, j, u, v0, n, &fl);
            rg2_eval e0;
            rg2_surface_eval(s, i, j, u, v0, 0, &e0);
            pm->samples++;
            if (fl & RG2_EVAL_NORMAL_UNDEFINED)
                pm->flagged++;
            if (first) {
                memcpy(pm->pole, e0.p, sizeof pm->pole);
                memcpy(pm->n, n, sizeof pm->n);
                first = 0;
            }
            double d = hypot(hypot(e0.p[0] - pm->pole[0], e0.p[1] - pm->pole[1]), e0.p[2] - pm->pole[2]);
            pm->point = fmax(pm->point, d / scale);
            pm->normal = fmax(pm->normal, pt_angle3(n, pm->n));
        }
    for (int q = 0; q < 4; q++) {
        double eps = pow(10.0, -(q + 1)), Kmin = INFINITY, Kmax = -INFINITY, Hmin = INFINITY,
               Hmax = -INFINITY, kmax = 0;
        for (int i = 0; i < s->nu; i++)
            for (int k = 0; k < 8; k++) {
                rg2_eval ev;
                rg2_surface_eval(s, i, j, (k + 0.5) / 8.0, e ? 1.0 - eps : eps, 2, &ev);
                pm->nconv[q] = fmax(pm->nconv[q], pt_angle3(ev.n, pm->n));
                Kmin = fmin(Kmin, ev.K), Kmax = fmax(Kmax, ev.K);
                Hmin = fmin(Hmin, ev.H), Hmax = fmax(Hmax, ev.H);
                kmax = fmax(kmax, fmax(fabs(ev.k1), fabs(ev.k2)));
            }
        pm->kspread[q] = fmax((Kmax - Kmin) / (kmax * kmax), (Hmax - Hmin) / kmax);
    }
}

/* Worst distance from the unit sphere (after undoing placement center c, radius R) over dense
 * samples of every patch. */
static double sphere_dist(const rg2_surface *s, const double c[3], double R)
{
    double worst = 0;
    for (int i = 0; i < s->nu; i++)
        for (int j = 0; j < s->nv; j++)
            for (int a = 0; a <= 8; a++)
                for (int b = 0; b <= 8; b++) {
                    rg2_eval e;
                    rg2_surface_eval(s, i, j, a / 8.0, b / 8.0, 0, &e);
                    double d = hypot(hypot(e.p[0] - c[0], e.p[1] - c[1]), e.p[2] - c[2]);
                    worst = fmax(worst, fabs(d - R) / R);
                }
    return worst;
}

static void print_pole(const char *what, const pole_meas *pm)
{
    printf("  %s pole: point spread %.2e, limit-normal spread %.2e rad, flagged %d/%d\n", what, pm->point,
           pm->normal, pm->flagged, pm->samples);
    printf("    approach eps = 1e-1..1e-4: normal angle to limit %.1e %.1e %.1e %.1e rad; "
           "K/H spread over the fan %.1e %.1e %.1e %.1e\n",
           pm->nconv[0], pm->nconv[1], pm->nconv[2], pm->nconv[3], pm->kspread[0], pm->kspread[1],
           pm->kspread[2], pm->kspread[3]);
}

static void check_seams(const rg2_surface *s, const char *what, double angle_tol, double curv_tol,
                        rg2t_seams *g)
{
    rg2t_surface_seams(s, 12, g);
    CHECK(g->pos <= 1e-13, "%s: position gap %.3g", what, g->pos);
    CHECK(g->angle <= angle_tol, "%s: normal angle %.3g", what, g->angle);
    CHECK(g->curv <= curv_tol, "%s: curvature jump %.3g at %s", what, g->curv, g->where);
    CHECK(g->param1 <= 1e-10 && g->param2 <= 1e-9, "%s: parametric %.3g %.3g", what, g->param1, g->param2);
    printf("  %s: %d seams, position %.2e, normal angle %.2e rad, curvature %.2e rel, "
           "parametric %.2e / %.2e, skipped %d (pole)\n",
           what, g->seams, g->pos, g->angle, g->curv, g->param1, g->param2, g->skipped);
}

/* Largest mismatch (relative to the largest homogeneous coordinate) between the shared
 * boundary control points of neighbouring patches, all taken at the surface's degrees: zero
 * when every seam has one homogeneous form, which a one-B-spline export (STEP/IGES per mesh)
 * needs. */
static double homogeneous_seam_gap(const rg2_surface *s)
{
    int du, dv;
    rg2_surface_degree(s, &du, &dv);
    double gap = 0, big = 0;
    for (int i = 0; i < s->nu; i++)
        for (int j = 0; j < s->nv; j++) {
            rg2_xpatch a, A, b, B;
            rg2_surface_patch_get(s, i, j, &a);
            rg2_xpatch_elevate(&a, du, dv, &A, NULL);
            for (int r = 0; r <= du; r++)
                for (int t = 0; t <= dv; t++)
                    for (int d = 0; d < 4; d++)
                        big = fmax(big, fabs(A.h[r][t][d]));
            if (j + 1 < s->nv || s->closed_v) {
                rg2_surface_patch_get(s, i, (j + 1) % s->nv, &b);
                rg2_xpatch_elevate(&b, du, dv, &B, NULL);
                for (int r = 0; r <= du; r++)
                    for (int d = 0; d < 4; d++)
                        gap = fmax(gap, fabs(A.h[r][dv][d] - B.h[r][0][d]));
            }
            if (i + 1 < s->nu || s->closed_u) {
                rg2_surface_patch_get(s, (i + 1) % s->nu, j, &b);
                rg2_xpatch_elevate(&b, du, dv, &B, NULL);
                for (int t = 0; t <= dv; t++)
                    for (int d = 0; d < 4; d++)
                        gap = fmax(gap, fabs(A.h[du][t][d] - B.h[0][t][d]));
            }
        }
    return gap / big;
}

/* Seams between the cap and the body only: rows (r, r + 1) of a capped surface copied into a
 * 2-row surface whose one v seam is the cap/body seam (bv, gv of row r + 1). */
static void cap_body_seams(const rg2_surface *s, const rg2_cap_info *info, rg2t_seams *worst)
{
    for (int e = 0; e < 2; e++) {
        if (!info->capped[e])
            continue;
        int r = e ? s->nv - 4 : 2; /* south: cap row 2 | body row 3; north: body | cap */
        rg2_surface t = *s;
        rg2_patch *pp = malloc(sizeof(rg2_patch) * 2 * (size_t)s->nu);
        rg2_xpatch *xx = s->xp ? malloc(sizeof(rg2_xpatch) * 2 * (size_t)s->nu) : NULL;
        double bv[2] = {1, s->bv[r + 1]}, gv[2] = {0, s->gv[r + 1]};
        for (int i = 0; i < s->nu; i++)
            for (int q = 0; q < 2; q++) {
                pp[i * 2 + q] = *rg2_surface_patch(s, i, r + q);
                if (xx)
                    xx[i * 2 + q] = s->xp[(size_t)i * s->nv + r + q];
            }
        t.patch = pp;
        t.xp = xx;
        t.nv = 2;
        t.closed_v = 0;
        t.bv = bv;
        t.gv = gv;
        t.tag = NULL;
        rg2t_seams g;
        rg2t_surface_seams(&t, 16, &g);
        worst->pos = fmax(worst->pos, g.pos);
        worst->angle = fmax(worst->angle, g.angle);
        worst->curv = fmax(worst->curv, g.curv);
        worst->param1 = fmax(worst->param1, g.param1);
        worst->param2 = fmax(worst->param2, g.param2);
        worst->seams++;
        free(pp);
        free(xx);
    }
}

/* The complete sphere from polar meshes with random partitions, knots and placement. */
static void sphere_caps(int quadratic)
{
    rg2t_rng r;
    uint64_t seed = 606;
    rg2t_seed(&r, seed);
    printf("sphere from polar mesh + %s caps, seed %llu\n", quadratic ? "general-quadratic" : "bi-3",
           (unsigned long long)seed);
    rg2_cap_opts opts;
    rg2_cap_opts_default(&opts);
    opts.quadratic = quadratic;
    double worst_d = 0, worst_q = 0;
    for (int trial = 0; trial < 6; trial++) {
        int n = rg2t_int(&r, 3, 9), m = rg2t_int(&r, 2, 7);
        double alpha[16], v[16];
        pt_random_arcs(&r, n, alpha);
        pt_random_knots(&r, m, 0.0, 1.0, v);
        double R = trial ? rg2t_uniform(&r, 0.5, 3.0) : 1.0;
        double c[3] = {0, 0, 0};
        if (trial)
            for (int k = 0; k < 3; k++)
                c[k] = rg2t_uniform(&r, -2, 2);
        double M[16] = {R, 0, 0, c[0], 0, R, 0, c[1], 0, 0, R, c[2], 0, 0, 0, 1};
        rg2_mesh mesh;
        rg2_error err;
        CHECK_OK(rg2_polar_sphere_mesh(alpha, n, 0.0, v, m, M, &mesh, &err), &err);
        rg2_surface s;
        rg2_cap_info info;
        CHECK_OK(rg2_cap_build(&mesh, &opts, &s, &info, &err), &err);
        CHECK(s.nv == m - 1 + 6 && s.nu == n, "patch grid %d x %d", s.nu, s.nv);
        /* a sphere's end rings are family-2 rings: the general cap is degree 4 in u, and its
         * quadratic form comes out rotational (c^2 and s^2 equal, no c s) */
        int du_expect = quadratic ? 4 : 3, du, dv;
        rg2_surface_degree(&s, &du, &dv);
        CHECK(info.du[0] == du_expect && info.du[1] == du_expect && du == du_expect && dv == 3,
              "cap degrees %d %d, surface (%d, %d)", info.du[0], info.du[1], du, dv);
        double hg = homogeneous_seam_gap(&s);
        CHECK(hg <= 1e-14, "sphere %d: one homogeneous form across every seam (%.3g)", trial, hg);
        for (int e = 0; e < 2; e++)
            for (int k = 0; k < 4; k++)
                CHECK(fabs(info.quad[e][k][1]) <= 1e-12 && fabs(info.quad[e][k][0] - info.quad[e][k][2]) <= 1e-12,
                      "quadratic form of coordinate %d: %.3g %.3g %.3g", k, info.quad[e][k][0], info.quad[e][k][1],
                      info.quad[e][k][2]);
        CHECK(info.polar[0] && info.polar[1], "both ends recognised as polar");
        double d = sphere_dist(&s, c, R);
        worst_d = fmax(worst_d, d);
        CHECK(d <= 1e-13, "trial %d: capped sphere off the sphere by %.3g", trial, d);
        /* coefficients of eq. (14): south (2x, 2y, 1 - x^2 - y^2, 1 + x^2 + y^2), north z negated,
         * then placed: q_k -> sum_l M_kl q_l */
        for (int e = 0; e < 2; e++) {
            double q0[4][4] = {{0, 2, 0, 0}, {0, 0, 2, 0}, {1, 0, 0, -1}, {1, 0, 0, 1}};
            if (e)
                q0[2][0] = -1, q0[2][3] = 1;
            CHECK(fabs(info.vc[e] - (e ? 1 - v[m - 1] : v[0])) <= 1e-14, "v_c %g", info.vc[e]);
            double dq = 0;
            for (int k = 0; k < 4; k++)
                for (int cc = 0; cc < 4; cc++) {
                    double ex = 0;
                    for (int l = 0; l < 4; l++)
                        ex += M[4 * k + l] * q0[l][cc];
                    dq = fmax(dq, fabs(info.q[e][k][cc] - ex));
                }
            worst_q = fmax(worst_q, dq);
            CHECK(dq <= 1e-12, "trial %d %s: coefficients recovered to %.3g", trial, e ? "north" : "south", dq);
            CHECK(info.residual[e] <= 1e-13, "sphere fit residual %.3g", info.residual[e]);
        }
        if (trial == 0) {
            rg2t_seams g;
            check_seams(&s, "sphere seams", 1e-12, 1e-10, &g);
            for (int e = 0; e < 2; e++) {
                pole_meas pm;
                measure_pole(&s, e, 2 * R, &pm);
                CHECK(pm.point <= 1e-15, "pole is one point: %.3g", pm.point);
                CHECK(pm.normal <= 1e-10, "fan limit normals agree: %.3g rad", pm.normal);
                CHECK(pm.flagged == pm.samples, "pole flagged normal-undefined %d/%d", pm.flagged, pm.samples);
                double expect[3] = {0, 0, e ? 1.0 : -1.0};
                CHECK(pt_angle3(pm.n, expect) <= 1e-12 || pt_angle3(pm.n, expect) >= M_PI - 1e-12,
                      "limit normal is the axis");
                print_pole(e ? "north" : "south", &pm);
            }
        }
        rg2_surface_free(&s);
        rg2_mesh_free(&mesh);
    }
    printf("  6 spheres: distance %.2e, coefficients %.2e\n", worst_d, worst_q);
}

/* A family-2 mesh (u circle, v polynomial): 4-tuple from the circle coefficients (C, S) and the
 * blossoms B1 = blossom(v), B2 = blossom(v^2) at each row. */
typedef void (*family2_fn)(double C, double S, double B1, double B2, const double *prm, double p[4]);

static void family2_mesh(const double *alpha, int n, const double *knots, int nk, family2_fn fn,
                         const double *prm, rg2_mesh *m)
{
    rg2_error err;
    double cs[64];
    int nv = nk - 2;
    CHECK_OK(rg2_mesh_init(m, n, nv, 1, 0, &err), &err);
    rg2_scalars_free(&m->su);
    rg2_scalars_free(&m->sv);
    CHECK_OK(rg2_scalars_from_angles(&m->su, alpha, n, 1, &err), &err);
    CHECK_OK(rg2_scalars_from_knots(&m->sv, knots, nk, 0, &err), &err);
    CHECK_OK(rg2_circle_coeffs(alpha, n, 1, 0.0, cs, &err), &err);
    for (int j = 0; j < nv; j++) {
        double bl[4];
        rg2_blossom_monomials(knots[j], knots[j + 1], knots[j + 2], bl);
        for (int i = 0; i < n; i++)
            fn(cs[2 * i], cs[2 * i + 1], bl[1], bl[2], prm, rg2_mesh_at(m, i, j));
    }
}

/* elliptic paraboloid (A v cu, B v su, v^2, 1): z = x^2 / A^2 + y^2 / B^2 */
static void paraboloid_fn(double C, double S, double B1, double B2, const double *prm, double p[4])
{
    p[0] = prm[0] * B1 * C;
    p[1] = prm[1] * B1 * S;
    p[2] = B2;
    p[3] = 1;
}

/* two-sheeted hyperboloid (2v cu, 2v su, 1 + v^2, 1 - v^2): z^2 - x^2 - y^2 = 1 */
static void hyperboloid2_fn(double C, double S, double B1, double B2, const double *prm, double p[4])
{
    (void)prm;
    p[0] = 2 * B1 * C;
    p[1] = 2 * B1 * S;
    p[2] = 1 + B2;
    p[3] = 1 - B2;
}

/* Worst implicit residual |f| / |grad f| / scale over dense samples. */
static double implicit_dist(const rg2_surface *s, int kind, const double *prm, double scale)
{
    double worst = 0;
    for (int i = 0; i < s->nu; i++)
        for (int j = 0; j < s->nv; j++)
            for (int a = 0; a <= 8; a++)
                for (int b = 0; b <= 8; b++) {
                    rg2_eval e;
                    rg2_surface_eval(s, i, j, a / 8.0, b / 8.0, 0, &e);
                    double x = e.p[0], y = e.p[1], z = e.p[2], f, gx, gy, gz;
                    if (kind == 0) {
                        f = z - x * x / (prm[0] * prm[0]) - y * y / (prm[1] * prm[1]);
                        gx = -2 * x / (prm[0] * prm[0]), gy = -2 * y / (prm[1] * prm[1]), gz = 1;
                    } else {
                        f = z * z - x * x - y * y - 1;
                        gx = -2 * x, gy = -2 * y, gz = 2 * z;
                    }
                    worst = fmax(worst, fabs(f) / sqrt(gx * gx + gy * gy + gz * gz) / scale);
                }
    return worst;
}

/* Polar configurations of the paraboloid and the two-sheeted hyperboloid: symmetric knots
 * t_{-1} = -t_1, t_0 = 0 collapse row 0 (blossom of v vanishes); the cap parameters read from
 * the scalars (v_c = 0, the polynomial chart) make band + cap exact. The open far end gets a
 * free-form cap. */
static void quadric_caps(void)
{
    rg2t_rng r;
    uint64_t seed = 1212;
    rg2t_seed(&r, seed);
    printf("paraboloid and two-sheeted hyperboloid polar configurations, seed %llu\n", (unsigned long long)seed);
    for (int kind = 0; kind < 2; kind++) {
        int n = rg2t_int(&r, 3, 7), m = rg2t_int(&r, 2, 5);
        double alpha[16], t[16] = {0}, knots[20];
        pt_random_arcs(&r, n, alpha);
        pt_random_knots(&r, m + 2, 0.0, kind ? 0.95 : 1.5, t);
        knots[0] = -t[0];
        knots[1] = 0;
        for (int k = 0; k < m + 2; k++)
            knots[k + 2] = t[k];
        double prm[2] = {rg2t_uniform(&r, 0.7, 1.5), rg2t_uniform(&r, 0.7, 1.5)};
        rg2_mesh mesh;
        family2_mesh(alpha, n, knots, m + 4, kind ? hyperboloid2_fn : paraboloid_fn, prm, &mesh);
        /* row 0 collapses to rounding; make it exact like a designer's polar point */
        double pole[4];
        memcpy(pole, rg2_mesh_at(&mesh, 0, 0), sizeof pole);
        pole[0] = pole[1] = 0;
        rg2_error err;
        CHECK_OK(rg2_polar_set_point(&mesh, 0, pole, &err), &err);
        CHECK(rg2_mesh_row_collapsed(&mesh, 0) && !rg2_mesh_row_collapsed(&mesh, m + 1), "row 0 is polar");
        rg2_surface s;
        rg2_cap_info info;
        rg2_cap_opts o;
        rg2_cap_opts_default(&o);
        o.ends = RG2_CAP_SOUTH;
        CHECK_OK(rg2_cap_build(&mesh, &o, &s, &info, &err), &err);
        double scale = rg2t_surface_scale(&s);
        double d = implicit_dist(&s, kind, prm, scale);
        CHECK(info.polar[0] && info.vc[0] == 0.0, "%s: polar with v_c = %g", kind ? "hyperboloid" : "paraboloid",
              info.vc[0]);
        CHECK(d <= 1e-13, "%s: capped surface off by %.3g", kind ? "hyperboloid" : "paraboloid", d);
        rg2t_seams g;
        check_seams(&s, kind ? "hyperboloid cap seams" : "paraboloid cap seams", 1e-12, 1e-10, &g);
        pole_meas pm;
        measure_pole(&s, 0, scale, &pm);
        CHECK(pm.point <= 1e-15 && pm.normal <= 1e-10, "pole point %.3g normal %.3g", pm.point, pm.normal);
        printf("  %s: distance %.2e, fit residual %.2e\n", kind ? "hyperboloid" : "paraboloid", d, info.residual[0]);
        rg2_surface_free(&s);
        /* both ends: the far end is an open ring, capped free-form */
        o.ends = RG2_CAP_SOUTH | RG2_CAP_NORTH;
        CHECK_OK(rg2_cap_build(&mesh, &o, &s, &info, &err), &err);
        CHECK(!info.polar[1], "far end is not polar");
        check_seams(&s, kind ? "hyperboloid both caps" : "paraboloid both caps", 1e-11, 1e-8, &g);
        measure_pole(&s, 1, rg2t_surface_scale(&s), &pm);
        CHECK(pm.point <= 1e-14 && pm.normal <= 1e-10, "free-form pole point %.3g normal %.3g", pm.point,
              pm.normal);
        printf("  far free-form cap: L = %.4g, v_c = %.2g, fit residual %.2e\n", info.length[1], info.vc[1],
               info.residual[1]);
        print_pole("far", &pm);
        rg2_surface_free(&s);
        rg2_mesh_free(&mesh);
    }
}

/* Free-form caps: perturbed polar sphere meshes (interior rows and polar points moved) and
 * tubes from random closed rings; G2 seams (angle <= 1e-11, curvature <= 1e-8) and a smooth
 * pole (one point, one limit normal; curvature spread shrinking towards the pole). */
/* A tube's mesh of n x (m + 2) points (coordinates left zero): u the closed circle partition
 * alpha, v open on the m + 4 knots; cs gets the partition's circle coefficients (cos, sin). */
static void tube_mesh(const double *alpha, int n, const double *knots, int m, rg2_mesh *mesh, double *cs)
{
    rg2_error err;
    CHECK_OK(rg2_mesh_init(mesh, n, m + 2, 1, 0, &err), &err);
    rg2_scalars_free(&mesh->su);
    rg2_scalars_free(&mesh->sv);
    CHECK_OK(rg2_scalars_from_angles(&mesh->su, alpha, n, 1, &err), &err);
    CHECK_OK(rg2_scalars_from_knots(&mesh->sv, knots, m + 4, 0, &err), &err);
    CHECK_OK(rg2_circle_coeffs(alpha, n, 1, 0.0, cs, &err), &err);
}

static void freeform_caps(int quadratic)
{
    rg2t_rng r;
    uint64_t seed = 4242;
    rg2t_seed(&r, seed);
    printf("free-form %s caps, seed %llu\n", quadratic ? "general-quadratic" : "bi-3", (unsigned long long)seed);
    rg2_cap_opts opts;
    rg2_cap_opts_default(&opts);
    opts.quadratic = quadratic;
    rg2t_seams worst = {0}, cb = {0};
    double wpn = 0, wpp = 0;
    for (int trial = 0; trial < 6; trial++) {
        int tube = trial >= 3;
        int n = rg2t_int(&r, 4, 8), m = rg2t_int(&r, 3, 6);
        double alpha[16], v[16];
        pt_random_arcs(&r, n, alpha);
        rg2_mesh mesh;
        rg2_error err;
        if (!tube) {
            pt_random_knots(&r, m, 0.0, 1.0, v);
            CHECK_OK(rg2_polar_sphere_mesh(alpha, n, 0.0, v, m, NULL, &mesh, &err), &err);
            for (int i = 0; i < n; i++)
                for (int j = 1; j <= m; j++) {
                    double *p = rg2_mesh_at(&mesh, i, j);
                    for (int k = 0; k < 3; k++)
                        p[k] += p[3] * rg2t_uniform(&r, -0.15, 0.15);
                }
            for (int e = 0; e < 2; e++) {
                double p[4];
                memcpy(p, rg2_mesh_at(&mesh, 0, e ? m + 1 : 0), sizeof p);
                for (int k = 0; k < 3; k++)
                    p[k] += rg2t_uniform(&r, -0.2, 0.2);
                CHECK_OK(rg2_polar_set_point(&mesh, e, p, &err), &err);
            }
        } else {
            double knots[20], cs[32];
            pt_random_knots(&r, m + 4, 0.0, 4.0, knots);
            tube_mesh(alpha, n, knots, m, &mesh, cs);
            for (int i = 0; i < n; i++)
                for (int j = 0; j < m + 2; j++) {
                    double *p = rg2_mesh_at(&mesh, i, j), rad = rg2t_uniform(&r, 0.7, 1.3);
                    double W = rg2t_uniform(&r, 0.9, 1.1);
                    p[0] = W * (rad * cs[2 * i] + rg2t_uniform(&r, -0.1, 0.1));
                    p[1] = W * (rad * cs[2 * i + 1] + rg2t_uniform(&r, -0.1, 0.1));
                    p[2] = W * (knots[j + 1] + rg2t_uniform(&r, -0.2, 0.2));
                    p[3] = W;
                }
        }
        rg2_surface s;
        rg2_cap_info info;
        CHECK_OK(rg2_cap_build(&mesh, &opts, &s, &info, &err), &err);
        CHECK(info.du[0] == (quadratic ? 5 : 3) && info.du[1] == info.du[0], "free-form cap u-degrees %d %d",
              info.du[0], info.du[1]);
        double hg = homogeneous_seam_gap(&s);
        CHECK(hg <= 1e-14, "free-form %d: one homogeneous form across every seam (%.3g)", trial, hg);
        rg2t_seams g;
        char what[64];
        snprintf(what, sizeof what, "%s %d", tube ? "tube" : "perturbed sphere", trial);
        check_seams(&s, what, 1e-11, 1e-8, &g);
        cap_body_seams(&s, &info, &cb);
        worst.angle = fmax(worst.angle, g.angle);
        worst.curv = fmax(worst.curv, g.curv);
        worst.pos = fmax(worst.pos, g.pos);
        double scale = rg2t_surface_scale(&s);
        for (int e = 0; e < 2; e++) {
            pole_meas pm;
            measure_pole(&s, e, scale, &pm);
            CHECK(pm.point <= 1e-14, "%s: pole is one point (%.3g)", what, pm.point);
            CHECK(pm.normal <= 1e-10, "%s: fan limit normals agree to %.3g rad", what, pm.normal);
            CHECK(pm.flagged == pm.samples, "%s: pole flagged %d/%d", what, pm.flagged, pm.samples);
            /* C2 at the pole: the curvature spread over the fan shrinks like eps */
            CHECK(pm.kspread[2] < 0.2 * pm.kspread[0] + 1e-6, "%s: curvature spread %.3g -> %.3g", what,
                  pm.kspread[0], pm.kspread[2]);
            CHECK(pm.nconv[2] < 0.2 * pm.nconv[0], "%s: normal converges %.3g -> %.3g", what, pm.nconv[0],
                  pm.nconv[2]);
            wpn = fmax(wpn, pm.normal);
            wpp = fmax(wpp, pm.point);
            if (trial == 0 || trial == 3)
                print_pole(e ? "north" : "south", &pm);
        }
        printf("    L = %.4g / %.4g, v_c = %.3g / %.3g, fit residual %.2e / %.2e\n", info.length[0],
               info.length[1], info.vc[0], info.vc[1], info.residual[0], info.residual[1]);
        rg2_surface_free(&s);
        rg2_mesh_free(&mesh);
    }
    printf("  free-form worst: position %.2e, normal angle %.2e rad, curvature %.2e rel; pole point %.2e, "
           "pole normals %.2e rad\n",
           worst.pos, worst.angle, worst.curv, wpp, wpn);
    CHECK(cb.seams == 12 && cb.angle <= 1e-11 && cb.curv <= 1e-8 && cb.pos <= 1e-14,
          "cap/body seams: %d, angle %.3g, curvature %.3g", cb.seams, cb.angle, cb.curv);
    printf("  the 12 cap/body seams alone: position %.2e, normal angle %.2e rad, curvature %.2e rel, "
           "parametric %.2e / %.2e\n",
           cb.pos, cb.angle, cb.curv, cb.param1, cb.param2);
}

static void cap_errors(void)
{
    rg2_error err;
    rg2_mesh m;
    rg2_surface s;
    double alpha[4] = {M_PI / 2, M_PI / 2, M_PI / 2, M_PI / 2}, v[3] = {0.2, 0.5, 0.8};
    CHECK_OK(rg2_polar_sphere_mesh(alpha, 4, 0.0, v, 3, NULL, &m, &err), &err);
    /* non-circle u scalars */
    rg2_mesh b;
    rg2_mesh_copy(&m, &b, &err);
    for (int i = 0; i < 4; i++)
        b.su.w[i] = 1.0, b.su.b[i] = 1.0, b.su.g[i] = 0.0;
    CHECK(rg2_cap_build(&b, NULL, &s, NULL, &err) == RG2_EINCOMPATIBLE && strstr(err.msg, "circle"),
          "non-circle u refused: %s", err.msg);
    rg2_mesh_free(&b);
    /* the u junction scalars must be the circle's to 1e-8 (relative to max(1, value)): those of
     * four 90-degree arcs, b = 1 and g = 2 sin(pi/4) (2 tan(pi/8)), moved by 3e-9 of that are
     * kept, moved by 3e-8 refused, for b and for g */
    double gq = 2.0 * sin(M_PI / 4) * 2.0 * tan(M_PI / 8);
    CHECK(fabs(m.su.b[1] - 1.0) <= 1e-15 && fabs(m.su.g[1] - gq) <= 1e-14, "junction 1: b %.17g, g %.17g vs %.17g",
          m.su.b[1], m.su.g[1], gq);
    for (int k = 0; k < 4; k++) {
        rg2_mesh_copy(&m, &b, &err);
        double *x = k < 2 ? &b.su.b[1] : &b.su.g[1], by = (k % 2 ? 3e-8 : 3e-9) * fmax(1.0, fabs(*x));
        *x += by;
        rg2_status st = rg2_cap_build(&b, NULL, &s, NULL, &err);
        CHECK(k % 2 ? st == RG2_EINCOMPATIBLE && strstr(err.msg, "not a circle partition") : st == RG2_OK,
              "junction 1's %s moved by %.1e: %s %s", k < 2 ? "b" : "g", by, rg2_status_str(st),
              st ? err.msg : "");
        if (st == RG2_OK)
            rg2_surface_free(&s);
        rg2_mesh_free(&b);
    }
    /* collapsed body: every row one point */
    rg2_mesh_copy(&m, &b, &err);
    for (int j = 0; j < b.nv; j++)
        for (int i = 1; i < b.nu; i++)
            memcpy(rg2_mesh_at(&b, i, j), rg2_mesh_at(&b, 0, j), 4 * sizeof(double));
    CHECK(rg2_cap_build(&b, NULL, &s, NULL, &err) == RG2_EDOMAIN && strstr(err.msg, "collapsed"),
          "collapsed body refused: %s", err.msg);
    /* tiny ring: scale the body's x, y to 1e-13 of its height */
    rg2_mesh_free(&b);
    rg2_mesh_copy(&m, &b, &err);
    for (int j = 0; j < b.nv; j++)
        for (int i = 0; i < b.nu; i++)
            rg2_mesh_at(&b, i, j)[0] *= 1e-13, rg2_mesh_at(&b, i, j)[1] *= 1e-13;
    CHECK(rg2_cap_build(&b, NULL, &s, NULL, &err) == RG2_EDOMAIN && strstr(err.msg, "south"),
          "too small ring refused: %s", err.msg);
    rg2_mesh_free(&b);
    /* open u (non-closed end) and closed v */
    CHECK_OK(rg2_mesh_init(&b, 5, 5, 0, 0, &err), &err);
    for (int k = 0; k < 25; k++)
        b.p[4 * k + 3] = 1, b.p[4 * k] = k % 5, b.p[4 * k + 1] = k / 5;
    CHECK(rg2_cap_build(&b, NULL, &s, NULL, &err) == RG2_EINVAL && strstr(err.msg, "open"),
          "open ring refused: %s", err.msg);
    rg2_mesh_free(&b);
    CHECK_OK(rg2_mesh_init(&b, 4, 4, 1, 1, &err), &err);
    CHECK(rg2_cap_build(&b, NULL, &s, NULL, &err) == RG2_EINVAL && strstr(err.msg, "closed"),
          "closed v refused: %s", err.msg);
    rg2_mesh_free(&b);
    /* bad options */
    rg2_cap_opts o;
    rg2_cap_opts_default(&o);
    o.samples = 1;
    CHECK(rg2_cap_build(&m, &o, &s, NULL, &err) == RG2_EDOMAIN && strstr(err.msg, "samples"), "samples: %s",
          err.msg);
    rg2_cap_opts_default(&o);
    o.length[1] = 1.0, o.vc[1] = 1.0;
    /* the options are named, not the body's v scalars (v_c = 1 let through here reaches the later
     * check of the chosen parameters, whose message blames "the body's v scalars") */
    CHECK(rg2_cap_build(&m, &o, &s, NULL, &err) == RG2_EDOMAIN &&
              !strcmp(err.msg, "cap: north cap length 1 and v_c 1: need length > 0 and 0 <= v_c < 1"),
          "v_c: %s", err.msg);
    rg2_cap_opts_default(&o);
    o.ends = 0;
    CHECK(rg2_cap_build(&m, &o, &s, NULL, &err) == RG2_EINVAL, "no ends: %s", err.msg);
    rg2_cap_opts_default(&o);
    o.quadratic = 5; /* was taken as rotational */
    CHECK(rg2_cap_build(&m, &o, &s, NULL, &err) == RG2_EINVAL &&
              !strcmp(err.msg, "cap: quadratic = 5, must be RG2_CAP_ROTATIONAL (0) or RG2_CAP_GENERAL (1)"),
          "quadratic 5: %s", err.msg);
    rg2_cap_opts_default(&o);
    o.jet_weight[1] = -1;
    CHECK(rg2_cap_build(&m, &o, &s, NULL, &err) == RG2_EDOMAIN &&
              !strcmp(err.msg, "cap: jet weight 1 is -1, must be finite and > 0 (a zero weight leaves the "
                               "least-squares fit rank-deficient)"),
          "negative jet weight: %s", err.msg);
    for (int k = 0; k < 3; k++) { /* a zero weight of any order: refused by name, as documented */
        rg2_cap_opts_default(&o);
        o.jet_weight[k] = 0.0;
        char want[64];
        snprintf(want, sizeof want, "cap: jet weight %d is 0, must be finite and > 0", k);
        CHECK(rg2_cap_build(&m, &o, &s, NULL, &err) == RG2_EDOMAIN && strstr(err.msg, want), "zero jet weight %d: %s",
              k, err.msg);
    }
    rg2_cap_opts_default(&o);
    o.jet_weight[1] = NAN;
    CHECK(rg2_cap_build(&m, &o, &s, NULL, &err) == RG2_EDOMAIN && strstr(err.msg, "cap: jet weight 1 is nan"),
          "NaN jet weight: %s", err.msg);
    rg2_mesh none;
    memset(&none, 0, sizeof none);
    CHECK(rg2_cap_build(&none, NULL, &s, NULL, &err) == RG2_EINVAL && !strcmp(err.msg, "cap: empty body mesh"),
          "empty body: %s", err.msg);
    CHECK(s.patch == NULL, "failed builds leave an empty surface");
    rg2_mesh_free(&m);
}

/* The pole of end e of a surface whose end row is a collapsed edge (a cap), or NULL. */
static int surface_pole(const rg2_surface *s, int e, double p[3])
{
    rg2_eval a, b;
    int j = e ? s->nv - 1 : 0;
    rg2_surface_eval(s, 0, j, 0.2, e ? 1.0 : 0.0, 0, &a);
    rg2_surface_eval(s, s->nu / 2, j, 0.7, e ? 1.0 : 0.0, 0, &b);
    memcpy(p, a.p, sizeof a.p);
    return pt_dist3(a.p, b.p) <= 1e-14 * (1 + fabs(a.p[0]) + fabs(a.p[1]) + fabs(a.p[2]));
}

/* Sign changes of the meridian normal curvature and of K along the meridians of the south
 * cap (seam to pole, 4 meridians per patch column), and K next to the pole. */
typedef struct {
    int merid_changes, gauss_changes;
    double pole_K;
} cap_shape;

static void cap_shape_measure(const rg2_surface *s, cap_shape *cs)
{
    memset(cs, 0, sizeof *cs);
    for (int i = 0; i < s->nu; i++)
        for (int a = 0; a < 4; a++) {
            int mc = 0, gc = 0;
            double pk = 0, pK = 0;
            for (int j = 2; j >= 0; j--)
                for (int t = 32; t >= (j == 0); t--) { /* not the pole itself */
                    rg2_eval e;
                    rg2_surface_eval(s, i, j, a / 4.0, t / 32.0, 2, &e);
                    if (e.flags & RG2_EVAL_NORMAL_UNDEFINED)
                        continue;
                    double k = rg2_eval_normal_curvature(&e, 0, 1);
                    if (fabs(k) > 1e-3) {
                        mc += pk * k < 0;
                        pk = k;
                    }
                    if (fabs(e.K) > 1e-3) {
                        gc += pK * e.K < 0;
                        pK = e.K;
                    }
                }
            cs->merid_changes = mc > cs->merid_changes ? mc : cs->merid_changes;
            cs->gauss_changes = gc > cs->gauss_changes ? gc : cs->gauss_changes;
        }
    rg2_eval e;
    rg2_surface_eval(s, 0, 0, 0.3, 1e-3, 2, &e);
    cs->pole_K = e.K;
}

/* Fig. 15: the saddle mesh (a) capped by the rotational form (b) oscillates (curvature sign
 * changes between the saddle ring and the round pole); the general quadratic (c) follows the
 * saddle (no sign change, hyperbolic pole, smaller fit residual) with degree-5 caps. */
static void fig15_compare(const rg2_design *d)
{
    rg2_cap_info info[2];
    cap_shape cs[2];
    for (int q = 0; q < 2; q++) {
        rg2_cap_opts o;
        rg2_cap_opts_default(&o);
        o.ends = RG2_CAP_SOUTH;
        o.quadratic = q ? RG2_CAP_GENERAL : RG2_CAP_ROTATIONAL;
        rg2_surface s;
        rg2_error err;
        CHECK_OK(rg2_cap_build(rg2_design_mesh(d, q), &o, &s, &info[q], &err), &err);
        cap_shape_measure(&s, &cs[q]);
        /* the design's own output is the same surface */
        const rg2_surface *ds = rg2_design_surface(d, q);
        double dd = 0;
        for (int i = 0; i < s.nu; i++)
            for (int j = 0; j < 3; j++) {
                rg2_eval a, b;
                rg2_surface_eval(&s, i, j, 0.37, 0.61, 0, &a);
                rg2_surface_eval(ds, i, j, 0.37, 0.61, 0, &b);
                dd = fmax(dd, pt_dist3(a.p, b.p) - (q ? 3.0 : 0.0));
            }
        CHECK(fabs(dd) <= 1e-12, "Fig. 15 design surface %d is the capped mesh (%.3g)", q, dd);
        rg2_surface_free(&s);
    }
    CHECK(info[0].du[0] == 3 && info[1].du[0] == 5, "cap u-degrees %d (bi-3), %d (general)", info[0].du[0],
          info[1].du[0]);
    CHECK(cs[0].merid_changes >= 1 && cs[0].gauss_changes >= 1,
          "Fig. 15b oscillates: meridian curvature changes sign %d times, K %d times", cs[0].merid_changes,
          cs[0].gauss_changes);
    CHECK(cs[1].merid_changes == 0 && cs[1].gauss_changes == 0,
          "Fig. 15c follows the saddle: meridian curvature changes sign %d times, K %d times", cs[1].merid_changes,
          cs[1].gauss_changes);
    CHECK(cs[1].pole_K < 0, "Fig. 15c has a hyperbolic pole (K = %.3g)", cs[1].pole_K);
    CHECK(info[1].residual[0] < 0.2 * info[0].residual[0], "general fit residual %.3g vs rotational %.3g",
          info[1].residual[0], info[0].residual[0]);
    printf("  Fig. 15 saddle mesh: (b) rotational bi-3 cap: fit residual %.2e, meridian-curvature / K sign changes "
           "along a meridian %d / %d, K at the pole %.3f;\n"
           "                      (c) general quadratic, degree (%d,3): fit residual %.2e, sign changes %d / %d, "
           "K at the pole %.3f\n",
           info[0].residual[0], cs[0].merid_changes, cs[0].gauss_changes, cs[0].pole_K, info[1].du[0],
           info[1].residual[0], cs[1].merid_changes, cs[1].gauss_changes, cs[1].pole_K);
}

/* The example designs of Figs. 9-12 and 14: they build, every seam is G2, every cap has one
 * pole point with one limit normal, they export (STEP, IGES, OBJ), and the figure-specific
 * facts hold (exact spheres with poles where eq. 16 says, exact quadric caps at the vertices). */
static void design_examples(void)
{
    static const char *const files[] = {"examples/fig9_polar_sphere.json", "examples/fig10_sphere_cylinder.json",
                                        "examples/fig11_cube_tube.json",
                                        "examples/fig12_paraboloid_hyperboloid.json", "examples/fig14_mobius.json",
                                        "examples/fig15_saddle_caps.json"};
    char dir[] = "/tmp/rg2_poles_XXXXXX";
    CHECK(mkdtemp(dir) != NULL, "temporary directory");
    printf("pole example designs:\n");
    for (size_t f = 0; f < sizeof files / sizeof *files; f++) {
        rg2_design *d = NULL;
        rg2_error err;
        CHECK_OK(rg2_design_load(files[f], &d, &err), &err);
        if (!d)
            continue;
        for (int o = 0; o < rg2_design_num_surfaces(d); o++) {
            const rg2_surface *s = rg2_design_surface(d, o);
            double scale = rg2t_surface_scale(s);
            rg2t_seams g;
            rg2t_surface_seams(s, 10, &g);
            CHECK(g.pos <= 1e-13 && g.angle <= 1e-11 && g.curv <= 1e-8, "%s %d: seams %.3g %.3g %.3g at %s",
                  files[f], o, g.pos, g.angle, g.curv, g.where);
            int poles = 0;
            double pn = 0, pp = 0;
            for (int e = 0; e < 2; e++) {
                double p[3];
                if (!surface_pole(s, e, p))
                    continue;
                poles++;
                pole_meas pm;
                measure_pole(s, e, scale, &pm);
                CHECK(pm.point <= 1e-14 && pm.normal <= 1e-10, "%s %d: pole %.3g, normals %.3g", files[f], o,
                      pm.point, pm.normal);
                pn = fmax(pn, pm.normal);
                pp = fmax(pp, pm.point);
            }
            char path[256];
            static const char *const ext[] = {"step", "igs", "obj"};
            for (int x = 0; x < 3; x++) {
                snprintf(path, sizeof path, "%s/f%zu_%d.%s", dir, f, o, ext[x]);
                rg2_export_opts eo;
                rg2_export_opts_default(&eo);
                CHECK_OK(rg2_export_file(s, 1, path, &eo, &err), &err);
                FILE *fp = fopen(path, "rb");
                long len = 0;
                if (fp) {
                    fseek(fp, 0, SEEK_END);
                    len = ftell(fp);
                    fclose(fp);
                }
                CHECK(len > 100, "%s written (%ld bytes)", path, len);
                remove(path);
            }
            /* fairness guard: no crease anywhere (curvature relative to the size) */
            double kmax = 0;
            for (int q = 0; q < s->nu * s->nv; q++)
                for (int a = 0; a <= 8; a++)
                    for (int b = 0; b <= 8; b++) {
                        rg2_eval ev;
                        rg2_surface_eval(s, q / s->nv, q % s->nv, a / 8.0, b / 8.0, 2, &ev);
                        if (!(ev.flags & RG2_EVAL_CURVATURE_UNDEFINED))
                            kmax = fmax(kmax, fmax(fabs(ev.k1), fabs(ev.k2)));
                    }
            CHECK(kmax * scale <= 40, "%s %d: max |k| x size %.3g (a crease?)", files[f], o, kmax * scale);
            printf("  %-44s %d: %4d patches, %d pole(s): point %.1e, normals %.1e rad; seams: normal %.1e rad, "
                   "curvature %.1e rel; max |k| x size %.1f\n",
                   files[f], o, s->nu * s->nv, poles, pp, pn, g.angle, g.curv, kmax * scale);
        }
        /* figure-specific facts */
        if (f == 0) {
            double c[3] = {2.5, 0, 0}; /* the capped sphere is shown beside the band */
            double dd = sphere_dist(rg2_design_surface(d, 1), c, 1.0);
            CHECK(dd <= 1e-13, "Fig. 9 capped sphere: %.3g", dd);
        }
        if (f == 3) {
            double p[3], v0[3] = {0, 0, 0}, v1[3] = {0, 0, 2.0};
            CHECK(surface_pole(rg2_design_surface(d, 0), 0, p) && pt_dist3(p, v0) <= 1e-14,
                  "Fig. 12 bowl pole at the vertex");
            CHECK(surface_pole(rg2_design_surface(d, 0), 1, p) && pt_dist3(p, v1) <= 1e-14,
                  "Fig. 12 lid pole at the vertex (%g %g %g)", p[0], p[1], p[2]);
        }
        if (f == 4) {
            double c[3] = {0, 0, 1}, R = 1.5, b = 0.5, B = 1 + b * b;
            /* surface 2 is shown 8 to the right: poles requested at (1.2, 0, 0.1), (0, 0, 2.5) */
            double ex[3][2][3] = {{{c[0] + R * 2 * b / B, 0, c[2] + R * (b * b - 1) / B},
                                   {c[0] - R * 2 * b / B, 0, c[2] + R * (1 - b * b) / B}},
                                  {{0}},
                                  {{9.2, 0, 0.1}, {8, 0, 2.5}}};
            for (int o = 0; o < 3; o += 2) {
                const rg2_surface *s = rg2_design_surface(d, o);
                double co[3] = {o ? 8.0 : 0.0, 0, 1};
                double dd = sphere_dist(s, co, R);
                CHECK(dd <= 1e-13, "Fig. 14 surface %d on the sphere: %.3g", o, dd);
                for (int e = 0; e < 2; e++) {
                    double p[3];
                    CHECK(surface_pole(s, e, p) && pt_dist3(p, ex[o][e]) <= 1e-13,
                          "Fig. 14 surface %d pole %d at (%g %g %g), found (%g %g %g)", o, e, ex[o][e][0],
                          ex[o][e][1], ex[o][e][2], p[0], p[1], p[2]);
                }
            }
        }
        if (f == 5) /* Fig. 15 (b) vs (c): the same saddle mesh capped both ways */
            fig15_compare(d);
        rg2_design_free(d);
    }
    rmdir(dir);
}

/* A body with rational v-scalars (w != 1, g != 0): a half torus, transposed so that the tube
 * circle is u and the open ring arc is v, capped at both ends (a bent sausage). */
static void rational_body_caps(void)
{
    const char *json = "{\"shapes\": {\"t\": {\"kind\": \"torus\", \"R\": 3, \"r\": 1}}, \"meshes\": {"
                       "\"half\": {\"shape\": \"t\", \"u\": {\"arcs\": 6, \"from\": 0, \"to\": 180}, "
                       "\"v\": {\"arcs\": 8}}, \"tube\": {\"transpose\": \"half\"}, \"capped\": {\"cap\": \"tube\"}}}";
    rg2_design *d = NULL;
    rg2_error err;
    CHECK_OK(rg2_design_parse(json, strlen(json), "sausage", &d, &err), &err);
    if (!d)
        return;
    const rg2_surface *s = rg2_design_surface(d, 0);
    const rg2_mesh *m = rg2_design_mesh(d, 0);
    double wmin = INFINITY, wmax = 0, gmax = 0;
    for (int k = 0; k < rg2_scalars_num_w(&m->sv); k++)
        wmin = fmin(wmin, m->sv.w[k]), wmax = fmax(wmax, m->sv.w[k]);
    for (int k = 0; k < m->sv.n; k++)
        gmax = fmax(gmax, fabs(m->sv.g[k]));
    CHECK(wmax < 1 && gmax > 0.1, "the body's v is rational (w %.3g..%.3g, g up to %.3g)", wmin, wmax, gmax);
    rg2t_seams g;
    check_seams(s, "half torus capped", 1e-11, 1e-8, &g);
    double scale = rg2t_surface_scale(s);
    for (int e = 0; e < 2; e++) {
        pole_meas pm;
        measure_pole(s, e, scale, &pm);
        CHECK(pm.point <= 1e-14 && pm.normal <= 1e-10 && pm.kspread[2] < 0.2 * pm.kspread[0],
              "half torus pole %d: point %.3g, normals %.3g, curvature spread %.3g -> %.3g", e, pm.point, pm.normal,
              pm.kspread[0], pm.kspread[2]);
        if (!e)
            print_pole("half torus south", &pm);
    }
    CHECK(rg2_surface_min_weight(s) > 0, "positive weights: %.3g", rg2_surface_min_weight(s));
    rg2_design_free(d);
}

/* Ellipsoid polar configuration through the design format, Moebius-moved on its reference
 * ellipsoid and capped: every patch (band and caps) on the ellipsoid. */
static void ellipsoid_caps(void)
{
    const char *json = "{\"shapes\": {\"e\": {\"kind\": \"ellipsoid\", \"a\": 2, \"b\": 1.5, \"c\": 1, "
                       "\"rotate\": {\"axis\": [1, 1, 0], \"degrees\": 30}, \"translate\": [1, 2, 3]}}, "
                       "\"meshes\": {\"P\": {\"polar\": \"e\", \"u\": {\"arcs\": 7}, \"v\": {\"knots\": [0.1, 0.3, "
                       "0.5, 0.7, 0.9]}}, \"M\": {\"mobius\": \"P\", \"sphere\": \"e\", \"b\": -0.4}, "
                       "\"C\": {\"cap\": \"M\"}}}";
    rg2_design *d = NULL;
    rg2_error err;
    CHECK_OK(rg2_design_parse(json, strlen(json), "ellipsoid", &d, &err), &err);
    if (!d)
        return;
    const rg2_surface *s = rg2_design_surface(d, 0);
    const rg2_shape *e = rg2_design_shape(d, 0);
    double worst = 0, scale = rg2t_surface_scale(s);
    int tagged = 0;
    for (int k = 0; k < s->nu * s->nv; k++) {
        tagged += s->tag[k] >= 0;
        for (int a = 0; a <= 6; a++)
            for (int b = 0; b <= 6; b++) {
                rg2_eval ev;
                rg2_surface_eval(s, k / s->nv, k % s->nv, a / 6.0, b / 6.0, 0, &ev);
                double g[3], F = rg2_shape_implicit(e, ev.p, g);
                worst = fmax(worst, fabs(F) / (sqrt(g[0] * g[0] + g[1] * g[1] + g[2] * g[2]) * scale));
            }
    }
    CHECK(worst <= 1e-13, "Moebius-moved capped ellipsoid off by %.3g", worst);
    CHECK(tagged == s->nu * s->nv, "all %d patches tagged exact (%d)", s->nu * s->nv, tagged);
    rg2t_seams g;
    check_seams(s, "ellipsoid caps", 1e-11, 1e-9, &g);
    printf("  capped ellipsoid (eq. 16, b = -0.4, on its reference ellipsoid): %d patches, distance %.2e\n",
           s->nu * s->nv, worst);
    rg2_design_free(d);
}

/* Moebius poles given in world coordinates must lie on the reference sphere to 1e-9 (relative):
 * 4e-10 off is accepted and the capped sphere's pole lands within that tolerance (times the
 * radius) of the normalized point; 2e-9 off is refused with the pole named. */
static void design_pole_tolerance(void)
{
    const char *fmt = "{\"shapes\": {\"s\": {\"kind\": \"sphere\", \"radius\": 2, \"translate\": [1, 0, 0]}}, "
                      "\"meshes\": {\"P\": {\"polar\": \"s\", \"u\": {\"arcs\": 6}, \"v\": {\"knots\": [0.2, 0.4, 0.6, 0.8]}}, "
                      "\"M\": {\"mobius\": \"P\", \"sphere\": \"s\", \"poles\": {\"south\": [1, 0, -2], \"north\": "
                      "[1, %.17g, %.17g]}}, \"C\": {\"cap\": \"M\"}}}";
    const double off[2] = {4e-10, 2e-9};
    for (int k = 0; k < 2; k++) {
        char json[1024];
        snprintf(json, sizeof json, fmt, 1.2 * (1 + off[k]), 1.6 * (1 + off[k]));
        rg2_design *d = NULL;
        rg2_error err;
        rg2_status st = rg2_design_parse(json, strlen(json), "tolerance", &d, &err);
        if (k == 0) {
            CHECK(st == RG2_OK, "pole %.0e off the sphere refused: %s", off[k], err.msg);
            double p[3], want[3] = {1, 1.2, 1.6}, c[3] = {1, 0, 0};
            if (d) {
                const rg2_surface *s = rg2_design_surface(d, rg2_design_num_surfaces(d) - 1);
                CHECK(surface_pole(s, 1, p) && pt_dist3(p, want) <= 2e-9, "north pole %.3g from (1 1.2 1.6)",
                      pt_dist3(p, want));
                double dd = sphere_dist(s, c, 2.0);
                CHECK(dd <= 1e-13, "capped sphere off by %.3g", dd);
                printf("  Moebius pole 4e-10 off the sphere: accepted, pole %.2e from it, sphere exact to %.2e\n",
                       pt_dist3(p, want), dd);
            }
        } else {
            CHECK(st == RG2_EDOMAIN && strstr(err.msg, "meshes.M.poles.north") && strstr(err.msg, "to 1e-9"),
                  "pole %.0e off the sphere: %s", off[k], err.msg);
        }
        rg2_design_free(d);
    }
}

/* Design-file errors of the poles operations name the item. */
static void design_errors(void)
{
    static const struct {
        const char *json;
        rg2_status code;
        const char *msg;
    } cases[] = {
        {"{\"shapes\": {\"t\": {\"kind\": \"torus\"}}, \"meshes\": {\"P\": {\"polar\": \"t\", \"u\": {\"arcs\": 8},"
         " \"v\": {\"knots\": [0.2, 0.5]}}}}",
         RG2_EINVAL, "meshes.P.polar: 't' is a torus, which has no polar configuration"},
        {"{\"shapes\": {\"s\": {\"kind\": \"sphere\"}}, \"meshes\": {\"P\": {\"polar\": \"s\", \"u\": {\"arcs\": 8},"
         " \"v\": {\"knots\": [0.5, 0.2]}}}}",
         RG2_EDOMAIN, "meshes.P.v.knots: knot 1 = "},
        {"{\"shapes\": {\"s\": {\"kind\": \"sphere\"}}, \"meshes\": {\"P\": {\"polar\": \"s\", \"v\": {\"knots\": "
         "[0.2, 0.5]}}, \"M\": {\"mobius\": \"P\", \"b\": 1, \"poles\": {}}}}",
         RG2_EPARSE, "exactly one of 'b'"},
        {"{\"shapes\": {\"s\": {\"kind\": \"sphere\"}}, \"meshes\": {\"P\": {\"polar\": \"s\", \"v\": {\"knots\": "
         "[0.2, 0.5]}}, \"C\": {\"cap\": \"P\", \"ends\": \"top\"}}}",
         RG2_EPARSE, "meshes.C.ends"},
        {"{\"shapes\": {\"c\": {\"kind\": \"cylinder\"}}, \"meshes\": {\"A\": {\"shape\": \"c\"}, \"E\": {\"edit\": "
         "\"A\", \"points\": [{\"pole\": \"south\", \"move\": [0, 0, 1]}]}}}",
         RG2_EINVAL, "meshes.E.points[0].pole: row 0 (the south end) of mesh 'A' is not a polar point"},
        {"{\"shapes\": {\"c\": {\"kind\": \"cylinder\"}}, \"meshes\": {\"A\": {\"shape\": \"c\", \"u\": {\"arcs\": 4, "
         "\"to\": 90}}, \"C\": {\"cap\": \"A\"}}}",
         RG2_EINVAL, "meshes.C.cap: mesh 'A' cannot be capped: the body's u-direction is open"},
        {"{\"shapes\": {\"s\": {\"kind\": \"sphere\"}}, \"meshes\": {\"P\": {\"polar\": \"s\", \"u\": {\"arcs\": 3}, "
         "\"v\": {\"knots\": [0.2, 0.5, 0.8]}}, \"M\": {\"mobius\": \"P\", \"poles\": {\"south\": [0, 0.999, "
         "-0.0447101778], \"north\": [0, 1, 0]}}}}",
         RG2_EWEIGHT, "meshes.M.poles: the Moebius map gives control point"},
        /* a polar mesh whose u scalars were edited is no longer a circle partition: each way of
         * leaving it is named */
        {"{\"shapes\": {\"s\": {\"kind\": \"sphere\"}}, \"meshes\": {\"P\": {\"polar\": \"s\", \"u\": {\"arcs\": 8},"
         " \"v\": {\"knots\": [0.2, 0.4, 0.6, 0.8]}}, \"E\": {\"edit\": \"P\", \"scalars\": [{\"dir\": \"u\", \"leg\": 0,"
         " \"w\": 0.95}]}, \"C\": {\"cap\": \"E\"}}}",
         RG2_EINCOMPATIBLE, "meshes.C.cap: mesh 'E' cannot be capped: the body's u arcs (from the leg weights) sum to "
                            "6.277308609377089 rad, not 2 pi: the u-direction is not a full circle"},
        {"{\"shapes\": {\"s\": {\"kind\": \"sphere\"}}, \"meshes\": {\"P\": {\"polar\": \"s\", \"u\": {\"arcs\": 8},"
         " \"v\": {\"knots\": [0.2, 0.4, 0.6, 0.8]}}, \"E\": {\"edit\": \"P\", \"scalars\": [{\"dir\": \"u\", \"junction\": 1,"
         " \"b\": 1.1}]}, \"C\": {\"cap\": \"E\"}}}",
         RG2_EINCOMPATIBLE, "body u junction 1 has b = 1.1, g = 0.304481869954853 but its arcs need "
                            "b = 1, g = 0.304481869954853: the u-direction is not a circle partition"},
        {"{\"shapes\": {\"s\": {\"kind\": \"sphere\"}}, \"meshes\": {\"P\": {\"polar\": \"s\", \"u\": {\"arcs\": 8},"
         " \"v\": {\"knots\": [0.2, 0.4, 0.6, 0.8]}}, \"E\": {\"edit\": \"P\", \"scalars\": [{\"dir\": \"u\", \"junction\": 1,"
         " \"g\": 0.1}]}, \"C\": {\"cap\": \"E\"}}}",
         RG2_EINCOMPATIBLE, "body u junction 1 has b = 1, g = 0.1 but its arcs need b = 1, "
                            "g = 0.304481869954853"},
    };
    for (size_t k = 0; k < sizeof cases / sizeof *cases; k++) {
        rg2_design *d = NULL;
        rg2_error err = {0};
        rg2_status st = rg2_design_parse(cases[k].json, strlen(cases[k].json), "poles", &d, &err);
        CHECK(st == cases[k].code && strstr(err.msg, cases[k].msg) && d == NULL,
              "design error %zu: got %s '%s', expected %s with '%s'", k, rg2_status_str(st), err.msg,
              rg2_status_str(cases[k].code), cases[k].msg);
        rg2_design_free(d);
    }
}

/* Explicit cap lengths (length > 0) with v_c = 0, the polynomial chart that rg2.h allows, and
 * with v_c = 0.3, on a free-form tube: each is used as given (rg2_cap_info) and the capped tube
 * is G2 across every seam, the pole one point. */
static void explicit_lengths(void)
{
    double alpha[5] = {1.1, 1.3, 1.2, 1.4, 2 * M_PI - 5.0}, knots[9] = {0, 0.5, 1.1, 1.6, 2.2, 2.9, 3.3, 3.8, 4.5};
    double cs[10];
    const double vcs[2] = {0.0, 0.3};
    rg2_error err;
    for (int k = 0; k < 2; k++) {
        rg2_mesh mesh;
        tube_mesh(alpha, 5, knots, 5, &mesh, cs);
        for (int i = 0; i < 5; i++)
            for (int j = 0; j < 7; j++) {
                double *p = rg2_mesh_at(&mesh, i, j), rad = 1.0 + 0.1 * sin(1.7 * i + j);
                p[0] = rad * cs[2 * i], p[1] = rad * cs[2 * i + 1], p[2] = knots[j + 1], p[3] = 1.0;
            }
        rg2_cap_opts o;
        rg2_cap_opts_default(&o);
        o.length[0] = 1.5, o.length[1] = 0.8, o.vc[0] = o.vc[1] = vcs[k];
        rg2_surface s;
        rg2_cap_info info;
        rg2_status st = rg2_cap_build(&mesh, &o, &s, &info, &err);
        CHECK(st == RG2_OK, "v_c = %g: %s", vcs[k], err.msg);
        if (st == RG2_OK) {
            CHECK(info.length[0] == 1.5 && info.length[1] == 0.8 && info.vc[0] == vcs[k] && info.vc[1] == vcs[k],
                  "v_c = %g: used L = %g / %g, v_c = %g / %g", vcs[k], info.length[0], info.length[1], info.vc[0],
                  info.vc[1]);
            char what[64];
            snprintf(what, sizeof what, "tube capped with L = 1.5 / 0.8, v_c = %g", vcs[k]);
            rg2t_seams g;
            check_seams(&s, what, 1e-11, 1e-8, &g);
            double scale = rg2t_surface_scale(&s);
            for (int e = 0; e < 2; e++) {
                pole_meas pm;
                measure_pole(&s, e, scale, &pm);
                CHECK(pm.point <= 1e-14 && pm.normal <= 1e-10, "%s: pole point %.3g, normals %.3g rad", what, pm.point,
                      pm.normal);
            }
            rg2_surface_free(&s);
        }
        rg2_mesh_free(&mesh);
    }
}

/* The cap options spelled out: "ends": "both" and "quadratic": "rotational" are the defaults
 * (the same patches bit for bit); "south" / "north" add the 3 cap rows at that end only, the
 * body rows unchanged, and their pole patches collapse to that end's pole. */
static void cap_option_values(void)
{
    const char *fmt = "{\"shapes\": {\"s\": {\"kind\": \"sphere\"}}, \"meshes\": {\"P\": {\"polar\": \"s\","
                      " \"u\": {\"arcs\": 6}, \"v\": {\"knots\": [0.2, 0.4, 0.6, 0.8]}}, \"C\": {\"cap\": \"P\"%s}},"
                      " \"output\": [\"P\", \"C\"]}";
    const char *opts[5] = {"", ", \"ends\": \"both\"", ", \"quadratic\": \"rotational\"", ", \"ends\": \"south\"",
                           ", \"ends\": \"north\""};
    rg2_design *d[5] = {NULL};
    for (int k = 0; k < 5; k++) {
        char json[1024];
        snprintf(json, sizeof json, fmt, opts[k]);
        rg2_error err;
        CHECK_OK(rg2_design_parse(json, strlen(json), "caps", &d[k], &err), &err);
    }
    if (!d[0] || !d[1] || !d[2] || !d[3] || !d[4]) {
        for (int k = 0; k < 5; k++)
            rg2_design_free(d[k]);
        return;
    }
    const rg2_surface *band = rg2_design_surface(d[0], 0), *c0 = rg2_design_surface(d[0], 1);
    for (int k = 1; k <= 2; k++) {
        const rg2_surface *c = rg2_design_surface(d[k], 1);
        CHECK(c->nu == c0->nu && c->nv == c0->nv && !c->xp &&
                  !memcmp(c->patch, c0->patch, sizeof(rg2_patch) * (size_t)c->nu * c->nv),
              "cap%s differs from the default cap", opts[k]);
    }
    CHECK(c0->nv == band->nv + 6, "both ends: %d rows for a band of %d", c0->nv, band->nv);
    for (int k = 3; k <= 4; k++) {
        const rg2_surface *c = rg2_design_surface(d[k], 1);
        int south = k == 3, off = south ? 3 : 0, body_same = c->nv == band->nv + 3;
        for (int i = 0; body_same && i < c->nu; i++)
            for (int j = 0; j < band->nv; j++)
                body_same = body_same && !memcmp(rg2_surface_patch(c, i, j + off), rg2_surface_patch(band, i, j),
                                                 sizeof(rg2_patch));
        /* the pole: the capped end's side of its end row is one point, (0, 0, -1) or (0, 0, 1) */
        double worst = 0;
        for (int i = 0; i < c->nu; i++) {
            rg2_eval e;
            rg2_surface_eval(c, i, south ? 0 : c->nv - 1, 0.5, south ? 0.0 : 1.0, 0, &e);
            worst = fmax(worst, fabs(e.p[0]) + fabs(e.p[1]) + fabs(e.p[2] - (south ? -1.0 : 1.0)));
        }
        CHECK(body_same && worst <= 1e-14, "cap%s: %d rows (band %d), body unchanged %d, pole off by %.3g", opts[k],
              c->nv, band->nv, body_same, worst);
    }
    for (int k = 0; k < 5; k++)
        rg2_design_free(d[k]);
}

/* Whether two surfaces hold the same bytes: grid, scalars, patches and higher-degree patches. */
static int surface_bytes_equal(const rg2_surface *a, const rg2_surface *b)
{
    size_t np = (size_t)a->nu * (size_t)a->nv;
    return a->nu == b->nu && a->nv == b->nv && a->closed_u == b->closed_u && a->closed_v == b->closed_v &&
           !memcmp(a->patch, b->patch, np * sizeof(rg2_patch)) && !memcmp(a->bu, b->bu, (size_t)a->nu * sizeof(double)) &&
           !memcmp(a->gu, b->gu, (size_t)a->nu * sizeof(double)) && !memcmp(a->bv, b->bv, (size_t)a->nv * sizeof(double)) &&
           !memcmp(a->gv, b->gv, (size_t)a->nv * sizeof(double)) && !a->xp == !b->xp &&
           (!a->xp || !memcmp(a->xp, b->xp, np * sizeof(rg2_xpatch)));
}

/* The capped surface's layout on a ring large enough for the parallel loops (more than 256
 * patches): the body's rows are rg2_surface_build's patches bit for bit (bi-3 caps; the cap rows
 * are added in the same array, the body moved in place) or those patches times D in xp with
 * NaN bi-3 slots (general caps), for each choice of ends; and the same bytes on 1 and 2 threads. */
static void cap_layout(void)
{
    rg2t_rng r;
    uint64_t seed = 5150;
    rg2t_seed(&r, seed);
    printf("capped layout and threads, seed %llu\n", (unsigned long long)seed);
#ifdef _OPENMP
    int threads = omp_get_max_threads();
#endif
    int n = 24, m = 12, cases = 0;
    double alpha[24], knots[16], cs[48];
    pt_random_arcs(&r, n, alpha);
    pt_random_knots(&r, m + 4, 0.0, 4.0, knots);
    rg2_mesh mesh;
    rg2_error err;
    tube_mesh(alpha, n, knots, m, &mesh, cs);
    for (int freeform = 0; freeform < 2; freeform++) {
        /* circle rings (family-2 rows: general caps of degree 4), then perturbed ones (5) */
        for (int j = 0; j < m + 2; j++) {
            double rad = rg2t_uniform(&r, 0.7, 1.3);
            for (int i = 0; i < n; i++) {
                double *p = rg2_mesh_at(&mesh, i, j), e = freeform ? 0.1 : 0.0;
                p[0] = rad * cs[2 * i] + rg2t_uniform(&r, -e, e);
                p[1] = rad * cs[2 * i + 1] + rg2t_uniform(&r, -e, e);
                p[2] = knots[j + 1];
                p[3] = 1.0;
            }
        }
        rg2_surface body;
        CHECK_OK(rg2_surface_build(&mesh, &body, &err), &err);
        for (int quadratic = 0; quadratic < 2; quadratic++)
            for (int ends = 1; ends <= 3; ends++) {
                rg2_cap_opts o;
                rg2_cap_opts_default(&o);
                o.quadratic = quadratic;
                o.ends = ends;
                rg2_surface s[2];
                rg2_cap_info info;
                memset(s, 0, sizeof s);
                for (int th = 1; th <= 2; th++) {
#ifdef _OPENMP
                    omp_set_num_threads(th);
#endif
                    CHECK_OK(rg2_cap_build(&mesh, &o, &s[th - 1], &info, &err), &err);
                }
                const rg2_surface *c = &s[0];
                int rb = info.rows_before, bad = 0, du = quadratic ? 4 + freeform : 3;
                CHECK(c->nu * c->nv > 256 && c->nv == body.nv + rb + info.rows_after,
                      "%d x %d patches for a body of %d x %d", c->nu, c->nv, body.nu, body.nv);
                CHECK(info.du[0] == (ends & 1 ? du : 0) && info.du[1] == (ends & 2 ? du : 0), "u-degrees %d %d",
                      info.du[0], info.du[1]);
                CHECK(surface_bytes_equal(&s[0], &s[1]), "quadratic %d, ends %d: the same bytes on 1 and 2 threads",
                      quadratic, ends);
                for (int i = 0; i < c->nu; i++)
                    for (int j = 0; j < c->nv; j++) {
                        const rg2_patch *P = rg2_surface_patch(c, i, j);
                        int in_body = j >= rb && j < rb + body.nv;
                        if (!quadratic) {
                            bad += in_body && memcmp(P, rg2_surface_patch(&body, i, j - rb), sizeof *P);
                            continue;
                        }
                        const rg2_xpatch *X = rg2_surface_xpatch(c, i, j);
                        bad += !X || X->du != (in_body ? du : info.du[j >= rb]) || X->dv != 3;
                        for (int k = 0; k < 64; k++)
                            bad += !isnan((&P->h[0][0][0])[k]);
                    }
                CHECK(!bad && !memcmp(c->bu, body.bu, sizeof(double) * (size_t)body.nu),
                      "quadratic %d, ends %d: body rows kept (%d mismatches)", quadratic, ends, bad);
                cases++;
                rg2_surface_free(&s[0]);
                rg2_surface_free(&s[1]);
            }
        rg2_surface_free(&body);
    }
#ifdef _OPENMP
    omp_set_num_threads(threads);
#endif
    printf("  %d capped surfaces: body rows as built, the same bytes on 1 and 2 threads\n", cases);
    rg2_mesh_free(&mesh);
}

/* A cap follows its body: the caps of a body moved and scaled (x -> 10 x + (3, -4, 10), and
 * x -> x / 1000 + (0.002, 0, -0.001)) are the caps of the body, moved and scaled. The fit weighs
 * x, y, z against W, so it runs in the boundary ring's own frame; fitted in world coordinates
 * the dome of a unit cylinder was 1.0625 deep with its ring at the origin and 1.0103 with the
 * ring at z = 10 (one of the two pipe_elbow caps, ends 2.5 from the origin, differed likewise).
 * A body a thousandth the size moves away from its ring at a thousandth the speed: no cap
 * length test may compare that speed, or the ring's radius, with an absolute figure (either
 * against 0.01 refused it: "does not move away from its south boundary ring (speed 0.0005)").
 * Compared by evaluation: 5 x 5 points per patch, bi-3 and general-quadratic caps, on a
 * free-form tube. */
static void moved_body_caps(void)
{
    double alpha[8], knots[8] = {-1.0, -0.5, 0.0, 0.5, 1.0, 1.5, 2.0, 2.5}, cs[16];
    for (int i = 0; i < 8; i++)
        alpha[i] = 2.0 * M_PI / 8;
    rg2_mesh body, moved;
    rg2_error err;
    tube_mesh(alpha, 8, knots, 4, &body, cs);
    for (int i = 0; i < 8; i++)
        for (int j = 0; j < 6; j++) {
            double *p = rg2_mesh_at(&body, i, j), rad = 1.0 + 0.1 * sin(3.0 * i + j);
            p[0] = rad * cs[2 * i];
            p[1] = rad * cs[2 * i + 1];
            p[2] = knots[j + 1];
            p[3] = 1.0;
        }
    const double Ms[2][16] = {{10, 0, 0, 3, 0, 10, 0, -4, 0, 0, 10, 10, 0, 0, 0, 1},
                              {1e-3, 0, 0, 2e-3, 0, 1e-3, 0, 0, 0, 0, 1e-3, -1e-3, 0, 0, 0, 1}};
    for (int t = 0; t < 4; t++) {
        const double *M = Ms[t / 2];
        int quadratic = t % 2 ? RG2_CAP_GENERAL : RG2_CAP_ROTATIONAL;
        CHECK_OK(rg2_mesh_copy(&body, &moved, &err), &err);
        rg2_mesh_transform(&moved, M);
        rg2_cap_opts opts;
        rg2_cap_opts_default(&opts);
        opts.quadratic = quadratic;
        rg2_surface a, b;
        rg2_cap_info ia, ib;
        CHECK_OK(rg2_cap_build(&body, &opts, &a, &ia, &err), &err);
        rg2_status st = rg2_cap_build(&moved, &opts, &b, &ib, &err);
        CHECK(st == RG2_OK, "caps of the body scaled by %g: %s (%s)", M[0], rg2_status_str(st), err.msg);
        if (st) {
            rg2_surface_free(&a);
            rg2_mesh_free(&moved);
            continue;
        }
        double worst = 0.0, scale = rg2t_surface_scale(&b);
        for (int i = 0; i < a.nu; i++)
            for (int j = 0; j < a.nv; j++)
                for (int su = 0; su <= 4; su++)
                    for (int sv = 0; sv <= 4; sv++) {
                        rg2_eval ea, eb;
                        rg2_surface_eval(&a, i, j, su / 4.0, sv / 4.0, 0, &ea);
                        rg2_surface_eval(&b, i, j, su / 4.0, sv / 4.0, 0, &eb);
                        for (int k = 0; k < 3; k++)
                            worst = fmax(worst, fabs(M[0] * ea.p[k] + M[4 * k + 3] - eb.p[k]) / scale);
                    }
        printf("moved body x %g (%s caps): caps of the moved body off the moved caps by %.2e of its size\n", M[0],
               quadratic ? "general-quadratic" : "bi-3", worst);
        CHECK(worst <= 1e-13, "%s caps of a body scaled by %g and moved are its caps scaled and moved: %.3g off",
              quadratic ? "general-quadratic" : "bi-3", M[0], worst);
        rg2_surface_free(&a);
        rg2_surface_free(&b);
        rg2_mesh_free(&moved);
    }
    rg2_mesh_free(&body);
}

/* 4-tuples are defined up to a scalar function (fit_solve's lambda absorbs its 2-jet at the
 * ring): a sphere band whose 4-tuples are multiplied by mu(v) = 1 + v (family 2, cubic in v;
 * the same surface) gets the caps of the band itself, with automatic parameters (bi-3 and
 * general-quadratic) and with the sphere's own chart, which also puts them on the sphere: the
 * band is v in [1/4, 3/4] of the sphere (2v(1 - v) cu, 2v(1 - v) su, 2v - 1, 2v^2 - 2v + 1)
 * (docs/shapes.md) with knot intervals 1/8, so its south cap is v in [0, 1/4]: v_c = 1/4 and
 * length 1/4 / (1/8) = 2 body rings (choose_params' polar formula); the north one the same by
 * symmetry. A fit that left lambda out of the first-derivative rows, or weighed lambda's
 * first derivative by a wrong factor in the second-derivative rows, put the caps of the scaled
 * tuples 4.6e-3 to 3.6e-2 off (1.1e-3 to 2.7e-2 in the sphere's chart, as far off the sphere);
 * a ring radius (the automatic length) that multiplied by the weights instead of dividing moved
 * the automatic caps 5.4e-2. */
static void scaled_tuple_caps(void)
{
    double av[8], kv[8];
    rg2_error err;
    rg2_partition pu, pv;
    CHECK_OK(rg2_partition_equal(&pu, RG2_PART_ANGLES, 1, 0.0, 0.0, 6, av, 8, &err), &err);
    CHECK_OK(rg2_partition_equal(&pv, RG2_PART_KNOTS, 0, 0.25, 0.75, 4, kv, 8, &err), &err);
    rg2_mesh m[2];
    for (int k = 0; k < 2; k++) {
        /* c[coordinate][1, cu, su][v^s]: the sphere, times (1 + v) for k = 1 */
        const double p[4][3][3] = {{{0}, {0, 2, -2}, {0}}, {{0}, {0}, {0, 2, -2}}, {{-1, 2, 0}}, {{1, -2, 2}}};
        double c[4][3][4] = {{{0}}};
        for (int q = 0; q < 4; q++)
            for (int b = 0; b < 3; b++)
                for (int e = 0; e < 3; e++) {
                    c[q][b][e] += p[q][b][e];
                    c[q][b][e + 1] += k * p[q][b][e];
                }
        CHECK_OK(rg2_family2_mesh((const double(*)[3][4])c, &pu, &pv, &m[k], &err), &err);
    }
    const double zero[3] = {0, 0, 0};
    for (int mode = 0; mode < 3; mode++) {
        rg2_cap_opts o;
        rg2_cap_opts_default(&o);
        o.quadratic = mode == 1 ? RG2_CAP_GENERAL : RG2_CAP_ROTATIONAL;
        if (mode == 2)
            for (int e = 0; e < 2; e++)
                o.length[e] = 2.0, o.vc[e] = 0.25;
        rg2_surface s[2];
        int built = 0;
        for (int k = 0; k < 2; k++)
            if (!rg2_cap_build(&m[k], &o, &s[k], NULL, &err))
                built++;
            else
                CHECK(0, "scaled tuples: cap %d: %s", k, err.msg);
        if (built < 2) {
            if (built)
                rg2_surface_free(&s[0]);
            continue;
        }
        double worst = 0.0;
        for (int i = 0; i < s[0].nu; i++)
            for (int j = 0; j < s[0].nv; j++)
                for (int a = 0; a <= 4; a++)
                    for (int b = 0; b <= 4; b++) {
                        rg2_eval e0, e1;
                        rg2_surface_eval(&s[0], i, j, a / 4.0, b / 4.0, 0, &e0);
                        rg2_surface_eval(&s[1], i, j, a / 4.0, b / 4.0, 0, &e1);
                        for (int q = 0; q < 3; q++)
                            worst = fmax(worst, fabs(e0.p[q] - e1.p[q]));
                    }
        double d = mode == 2 ? fmax(sphere_dist(&s[0], zero, 1.0), sphere_dist(&s[1], zero, 1.0)) : 0.0;
        printf("sphere band, 4-tuples times 1 + v (%s): caps off the band's caps by %.2e%s", mode == 2 ? "L = 2, v_c = 1/4"
               : mode ? "automatic, general" : "automatic, bi-3", worst, mode == 2 ? "" : "\n");
        if (mode == 2)
            printf(", off the sphere by %.2e\n", d);
        CHECK(worst <= 1e-13 && d <= 1e-13, "caps of 4-tuples times 1 + v (mode %d): %.3g off the caps of the band, "
              "%.3g off the sphere", mode, worst, d);
        rg2_surface_free(&s[0]);
        rg2_surface_free(&s[1]);
    }
    rg2_mesh_free(&m[0]);
    rg2_mesh_free(&m[1]);
}

int main(void)
{
    cap_option_values();
    sphere_caps(RG2_CAP_ROTATIONAL);
    sphere_caps(RG2_CAP_GENERAL);
    quadric_caps();
    freeform_caps(RG2_CAP_ROTATIONAL);
    freeform_caps(RG2_CAP_GENERAL);
    cap_layout();
    cap_errors();
    design_examples();
    rational_body_caps();
    ellipsoid_caps();
    design_errors();
    design_pole_tolerance();
    explicit_lengths();
    moved_body_caps();
    scaled_tuple_caps();
    return rg2t_done("test_cap");
}
