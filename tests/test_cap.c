/* test_cap.c -- bi-3 polar caps: the complete sphere from a polar mesh (exact, G2, one pole
 * point with one limit normal), exact recovery of the cap coefficients on sphere data, exact
 * paraboloid and two-sheeted hyperboloid caps, free-form caps (perturbed spheres, random
 * tubes) with G2 seams and a smooth pole, and the errors for degenerate input. */
#include "harness.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

/* Random closed arc partition of n arcs. */
static void random_arcs(rg2t_rng *r, int n, double *alpha)
{
    double s = 0;
    for (int i = 0; i < n; i++)
        s += (alpha[i] = rg2t_uniform(r, 0.6, 1.0));
    for (int i = 0; i < n; i++)
        alpha[i] *= 2 * M_PI / s;
}

/* m increasing knots in (lo, hi). */
static void random_knots(rg2t_rng *r, int m, double lo, double hi, double *v)
{
    double s = 0, d[64];
    for (int k = 0; k <= m; k++)
        s += (d[k] = rg2t_uniform(r, 0.5, 1.0));
    double acc = 0;
    for (int k = 0; k < m; k++) {
        acc += d[k];
        v[k] = lo + (hi - lo) * acc / s;
    }
}

static double angle3(const double a[3], const double b[3])
{
    double c[3] = {a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]};
    return atan2(sqrt(c[0] * c[0] + c[1] * c[1] + c[2] * c[2]), a[0] * b[0] + a[1] * b[1] + a[2] * b[2]);
}

static void unit(double a[3])
{
    double l = sqrt(a[0] * a[0] + a[1] * a[1] + a[2] * a[2]);
    for (int k = 0; k < 3; k++)
        a[k] /= l;
}

/* Limit normal at a collapsed edge v = v0 (0 or 1) of a patch: su = (v - v0) suv + ..., so
 * n ~ sign(v - v0) suv x sv. */
static void limit_normal(const rg2_patch *P, double u, double v0, double n[3], unsigned *flags)
{
    rg2_eval e;
    rg2_patch_eval(P, u, v0, 2, &e);
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
            const rg2_patch *P = rg2_surface_patch(s, i, j);
            limit_normal(P, u, v0, n, &fl);
            rg2_eval e0;
            rg2_patch_eval(P, u, v0, 0, &e0);
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
            pm->normal = fmax(pm->normal, angle3(n, pm->n));
        }
    for (int q = 0; q < 4; q++) {
        double eps = pow(10.0, -(q + 1)), Kmin = INFINITY, Kmax = -INFINITY, Hmin = INFINITY,
               Hmax = -INFINITY, kmax = 0;
        for (int i = 0; i < s->nu; i++)
            for (int k = 0; k < 8; k++) {
                rg2_eval ev;
                rg2_patch_eval(rg2_surface_patch(s, i, j), (k + 0.5) / 8.0, e ? 1.0 - eps : eps, 2, &ev);
                pm->nconv[q] = fmax(pm->nconv[q], angle3(ev.n, pm->n));
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
                    rg2_patch_eval(rg2_surface_patch(s, i, j), a / 8.0, b / 8.0, 0, &e);
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

/* The complete sphere from polar meshes with random partitions, knots and placement. */
static void sphere_caps(void)
{
    rg2t_rng r;
    uint64_t seed = 606;
    rg2t_seed(&r, seed);
    printf("sphere from polar mesh + caps, seed %llu\n", (unsigned long long)seed);
    double worst_d = 0, worst_q = 0;
    for (int trial = 0; trial < 6; trial++) {
        int n = rg2t_int(&r, 3, 9), m = rg2t_int(&r, 2, 7);
        double alpha[16], v[16];
        random_arcs(&r, n, alpha);
        random_knots(&r, m, 0.0, 1.0, v);
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
        CHECK_OK(rg2_cap_build(&mesh, NULL, &s, &info, &err), &err);
        CHECK(s.nv == m - 1 + 6 && s.nu == n, "patch grid %d x %d", s.nu, s.nv);
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
                CHECK(angle3(pm.n, expect) <= 1e-12 || angle3(pm.n, expect) >= M_PI - 1e-12,
                      "limit normal is the axis");
                print_pole(e ? "north" : "south", &pm);
            }
        }
        rg2_surface_free(&s);
        rg2_mesh_free(&mesh);
    }
    printf("  6 spheres: distance %.2e, coefficients %.2e\n", worst_d, worst_q);
}

int main(void)
{
    sphere_caps();
    return rg2t_done("test_cap");
}
