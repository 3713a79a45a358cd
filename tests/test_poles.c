/* test_poles.c -- polar configurations and Moebius pole placement: polar knots, the polar
 * sphere mesh (collapsed rows, eq. 13 polar points, the band [v_1, v_m] reproduced exactly with
 * its parameterization), Moebius maps (eq. 16 and general pole pairs) keeping the sphere exact
 * with the poles where MATH.md section 7 says, and errors. */
#include "poles_testutil.h"

#include <limits.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

static void polar_knots(void)
{
    double v[3] = {0.25, 0.5, 0.8}, k[7];
    rg2_error err;
    CHECK_OK(rg2_polar_knots(v, 3, k, &err), &err);
    CHECK(fabs(k[0] - 0.25 / (0.25 - 1)) < 1e-16 && k[1] == 0 && k[2] == 0.25 && k[4] == 0.8 && k[5] == 1 &&
              fabs(k[6] - 1 / 0.8) < 1e-16,
          "polar knot vector");
    /* the blossoms of v and v^2 agree at both polar rows: x, y of the sphere vanish */
    double b0[4], b1[4];
    rg2_blossom_monomials(k[0], k[1], k[2], b0);
    rg2_blossom_monomials(k[4], k[5], k[6], b1);
    CHECK(fabs(b0[1] - b0[2]) < 1e-16 && fabs(b1[1] - b1[2]) < 1e-15, "rows collapse: %.3g %.3g", b0[1] - b0[2],
          b1[1] - b1[2]);
    double bad1[2] = {0.5, 0.4}, bad2[2] = {0.0, 0.5}, bad3[2] = {0.5, 1.0};
    CHECK(rg2_polar_knots(bad1, 2, k, &err) == RG2_EDOMAIN && strstr(err.msg, "knot 1 = 0.4"), "%s", err.msg);
    CHECK(rg2_polar_knots(bad2, 2, k, &err) == RG2_EDOMAIN && strstr(err.msg, "knot 0 = 0"), "%s", err.msg);
    CHECK(rg2_polar_knots(bad3, 2, k, &err) == RG2_EDOMAIN && strstr(err.msg, "knot 1 = 1"), "%s", err.msg);
    CHECK(rg2_polar_knots(v, 1, k, &err) == RG2_EINVAL && strstr(err.msg, "at least 2"), "%s", err.msg);
}

/* Arc parameter map (MATH.md section 2): angle of local parameter t on arc [theta_a, +alpha]. */
static double arc_angle(double theta_a, double alpha, double t)
{
    double be = 0.5 * alpha;
    return theta_a + be + 2 * atan(tan(0.5 * be) * (2 * t - 1));
}

/* The band of the polar sphere mesh: collapsed rows with the eq. 13 points, exact sphere, the
 * sphere's own parameterization on [v_1, v_m] (arc map in u, affine in v), and G2 seams. */
static void polar_sphere_band(void)
{
    rg2t_rng r;
    uint64_t seed = 1313;
    rg2t_seed(&r, seed);
    printf("polar sphere band, seed %llu\n", (unsigned long long)seed);
    double wd = 0, wp = 0;
    rg2t_seams worst = {0};
    for (int trial = 0; trial < 8; trial++) {
        int n = rg2t_int(&r, 3, 9), m = rg2t_int(&r, 2, 8);
        double alpha[16], v[16], th0 = rg2t_uniform(&r, -1, 1);
        pt_random_arcs(&r, n, alpha);
        pt_random_knots(&r, m, 0.0, 1.0, v);
        rg2_mesh mesh;
        rg2_error err;
        CHECK_OK(rg2_polar_sphere_mesh(alpha, n, th0, v, m, NULL, &mesh, &err), &err);
        CHECK(mesh.nu == n && mesh.nv == m + 2, "mesh %d x %d", mesh.nu, mesh.nv);
        for (int j = 0; j < m + 2; j++)
            CHECK(rg2_mesh_row_collapsed(&mesh, j) == (j == 0 || j == m + 1), "row %d collapsed = %d", j,
                  rg2_mesh_row_collapsed(&mesh, j));
        double Zs = (3 - 3 * v[0] + 2 * v[0] * v[0]) / (3 * (v[0] - 1));
        double Zn = (2 - v[m - 1] + 2 * v[m - 1] * v[m - 1]) / (3 * v[m - 1]);
        const double *ps = rg2_mesh_at(&mesh, 1, 0), *pn = rg2_mesh_at(&mesh, 0, m + 1);
        CHECK(ps[0] == 0 && ps[1] == 0 && fabs(ps[2] / ps[3] - Zs) < 1e-15, "south polar point");
        CHECK(pn[0] == 0 && pn[1] == 0 && fabs(pn[2] / pn[3] - Zn) < 1e-15, "north polar point");
        CHECK(fabs(mesh.sv.b[0] - (1 - v[0])) < 1e-15 && fabs(mesh.sv.b[m + 1] - 1 / v[m - 1]) < 1e-14,
              "polar scalars b_0 = 1 - v_1, b_{m+1} = 1 / v_m");
        rg2_surface s;
        CHECK_OK(rg2_surface_build(&mesh, &s, &err), &err);
        CHECK(s.nu == n && s.nv == m - 1, "band %d x %d patches", s.nu, s.nv);
        double theta = th0;
        for (int i = 0; i < n; i++) {
            for (int j = 0; j < m - 1; j++)
                for (int a = 0; a <= 6; a++)
                    for (int b = 0; b <= 6; b++) {
                        rg2_eval e;
                        rg2_patch_eval(rg2_surface_patch(&s, i, j), a / 6.0, b / 6.0, 0, &e);
                        double rr = sqrt(e.p[0] * e.p[0] + e.p[1] * e.p[1] + e.p[2] * e.p[2]);
                        wd = fmax(wd, fabs(rr - 1));
                        double th = arc_angle(theta, alpha[i], a / 6.0);
                        double vv = v[j] + (v[j + 1] - v[j]) * b / 6.0;
                        double W = 2 * vv * vv - 2 * vv + 1;
                        double h[3] = {2 * vv * (1 - vv) * cos(th) / W, 2 * vv * (1 - vv) * sin(th) / W,
                                       (2 * vv - 1) / W};
                        wp = fmax(wp, pt_dist3(e.p, h));
                    }
            theta += alpha[i];
        }
        rg2t_seams g;
        rg2t_surface_seams(&s, 8, &g);
        worst.angle = fmax(worst.angle, g.angle);
        worst.curv = fmax(worst.curv, g.curv);
        worst.pos = fmax(worst.pos, g.pos);
        CHECK(g.pos <= 1e-14 && g.angle <= 1e-12 && g.curv <= 1e-10, "band seams %.3g %.3g %.3g", g.pos, g.angle,
              g.curv);
        rg2_surface_free(&s);
        rg2_mesh_free(&mesh);
    }
    CHECK(wd <= 1e-13, "band on the sphere: %.3g", wd);
    CHECK(wp <= 1e-13, "band reproduces the parameterization: %.3g", wp);
    printf("  8 bands: distance %.2e, parameterization %.2e, seams: position %.2e, normal %.2e rad, "
           "curvature %.2e rel\n",
           wd, wp, worst.pos, worst.angle, worst.curv);
}

/* A start angle of many turns: rg2_circle_coeffs (and so rg2_polar_sphere_mesh) takes it within
 * one turn, so theta0 = 1e20 gives the mesh of its reduction atan2(sin, cos), bit for bit, on the
 * sphere. Unreduced, every junction angle theta0 + alpha_0 + ... rounded to theta0 (1e20 is
 * 1.6e4 ulps of 2 pi apart): the control points of each ring lay on one ray. */
static void polar_start_turns(void)
{
    double alpha[5] = {1.1, 1.3, 1.2, 1.4, 0}, v[3] = {0.2, 0.5, 0.8};
    alpha[4] = 2 * M_PI - alpha[0] - alpha[1] - alpha[2] - alpha[3];
    const double starts[3] = {1e20, -7.5e9, 4 * M_PI + 0.25};
    for (int k = 0; k < 3; k++) {
        double red = atan2(sin(starts[k]), cos(starts[k]));
        rg2_mesh a, b;
        rg2_error err;
        CHECK_OK(rg2_polar_sphere_mesh(alpha, 5, starts[k], v, 3, NULL, &a, &err), &err);
        CHECK_OK(rg2_polar_sphere_mesh(alpha, 5, red, v, 3, NULL, &b, &err), &err);
        int same = a.nu == b.nu && a.nv == b.nv, distinct = 1;
        for (int i = 0; same && i < a.nu; i++)
            for (int j = 0; j < a.nv; j++)
                same &= !memcmp(rg2_mesh_at(&a, i, j), rg2_mesh_at(&b, i, j), 4 * sizeof(double));
        for (int i = 1; i < a.nu; i++) { /* the ring's junction points differ in angle */
            const double *p = rg2_mesh_at(&a, i, 2), *q = rg2_mesh_at(&a, 0, 2);
            distinct &= fabs(atan2(p[1], p[0]) - atan2(q[1], q[0])) > 0.5;
        }
        double wd = 0;
        rg2_surface s;
        CHECK_OK(rg2_surface_build(&a, &s, &err), &err);
        for (int i = 0; i < s.nu; i++)
            for (int j = 0; j < s.nv; j++)
                for (int q = 0; q <= 4; q++) {
                    rg2_eval e;
                    rg2_patch_eval(rg2_surface_patch(&s, i, j), q / 4.0, 0.5, 0, &e);
                    wd = fmax(wd, fabs(sqrt(e.p[0] * e.p[0] + e.p[1] * e.p[1] + e.p[2] * e.p[2]) - 1));
                }
        CHECK(same && distinct && wd <= 1e-14,
              "start %.17g: the mesh of its reduction %.17g %s, junctions %s, %.3g off the sphere", starts[k], red,
              same ? "bit for bit" : "DIFFERS", distinct ? "apart" : "ON ONE RAY", wd);
        rg2_surface_free(&s);
        rg2_mesh_free(&a);
        rg2_mesh_free(&b);
    }
}

/* Lorentz check: M^T J M = c J with J = diag(1, 1, 1, -1), c > 0 (maps the sphere to itself). */
static double lorentz_defect(const double M[16])
{
    double J[4] = {1, 1, 1, -1}, c = 0, d = 0;
    double T[4][4];
    for (int a = 0; a < 4; a++)
        for (int b = 0; b < 4; b++) {
            double s = 0;
            for (int k = 0; k < 4; k++)
                s += M[4 * k + a] * J[k] * M[4 * k + b];
            T[a][b] = s;
        }
    c = T[0][0];
    for (int a = 0; a < 4; a++)
        for (int b = 0; b < 4; b++)
            d = fmax(d, fabs(T[a][b] - (a == b ? c * J[a] : 0)));
    return c > 0 ? d / c : INFINITY;
}

static void apply(const double M[16], const double p[4], double q[4])
{
    for (int r = 0; r < 4; r++)
        q[r] = M[4 * r] * p[0] + M[4 * r + 1] * p[1] + M[4 * r + 2] * p[2] + M[4 * r + 3] * p[3];
}

/* How far M takes the unit sphere's poles (0, 0, -+1) from south and north (the larger distance;
 * NaN compares false, so a non-finite M fails the callers' bounds). */
static double poles_mapped_off(const double M[16], const double south[3], const double north[3])
{
    double S4[4] = {0, 0, -1, 1}, N4[4] = {0, 0, 1, 1}, x[4], y[4];
    apply(M, S4, x);
    apply(M, N4, y);
    double xs[3] = {x[0] / x[3], x[1] / x[3], x[2] / x[3]}, yn[3] = {y[0] / y[3], y[1] / y[3], y[2] / y[3]};
    double a = pt_dist3(xs, south), b = pt_dist3(yn, north);
    return a != a || b != b ? NAN : fmax(a, b);
}

/* Worst distance from the sphere (center c, radius R) over a capped surface, and its poles. */
static double capped_sphere(const rg2_mesh *mesh, const double c[3], double R, double pole[2][3],
                            rg2t_seams *g)
{
    rg2_surface s;
    rg2_error err;
    rg2_cap_info info;
    double worst = INFINITY;
    CHECK_OK(rg2_cap_build(mesh, NULL, &s, &info, &err), &err);
    if (!s.patch)
        return worst;
    worst = 0;
    for (int i = 0; i < s.nu; i++)
        for (int j = 0; j < s.nv; j++)
            for (int a = 0; a <= 6; a++)
                for (int b = 0; b <= 6; b++) {
                    rg2_eval e;
                    rg2_patch_eval(rg2_surface_patch(&s, i, j), a / 6.0, b / 6.0, 0, &e);
                    worst = fmax(worst, fabs(pt_dist3(e.p, c) - R) / R);
                }
    for (int e = 0; e < 2; e++) {
        rg2_eval ev;
        rg2_patch_eval(rg2_surface_patch(&s, 0, e ? s.nv - 1 : 0), 0.3, e ? 1.0 : 0.0, 0, &ev);
        memcpy(pole[e], ev.p, sizeof ev.p);
        CHECK(pt_dist3(ev.p, info.pole[e]) <= 1e-14 * R, "info pole");
    }
    rg2t_surface_seams(&s, 8, g);
    rg2_surface_free(&s);
    return worst;
}

/* Eq. (16): the Moebius mesh is exact; its polar points and poles are where MATH.md says, and
 * the band is the eq. (16) parameterization. */
static void mobius_b(void)
{
    rg2t_rng r;
    uint64_t seed = 1616;
    rg2t_seed(&r, seed);
    printf("Moebius pole placement (eq. 16), seed %llu\n", (unsigned long long)seed);
    const double bs[5] = {0.0, 0.2, -0.5, 1.0, 3.0};
    double wd = 0, wpole = 0, wpp = 0, wpar = 0, wl = 0;
    for (int t = 0; t < 5; t++) {
        double b = bs[t];
        int n = rg2t_int(&r, 3, 8), m = rg2t_int(&r, 2, 6);
        double alpha[16], v[16];
        pt_random_arcs(&r, n, alpha);
        pt_random_knots(&r, m, 0.0, 1.0, v);
        rg2_mesh mesh;
        rg2_error err;
        CHECK_OK(rg2_polar_sphere_mesh(alpha, n, 0.0, v, m, NULL, &mesh, &err), &err);
        double M[16];
        rg2_mobius_matrix(b, NULL, M);
        wl = fmax(wl, lorentz_defect(M));
        double c0[3] = {0, 0, 0};
        CHECK_OK(rg2_mesh_mobius(&mesh, c0, 1.0, M, &err), &err);
        double Zs = (3 - 3 * v[0] + 2 * v[0] * v[0]) / (3 * (v[0] - 1));
        double Zn = (2 - v[m - 1] + 2 * v[m - 1] * v[m - 1]) / (3 * v[m - 1]);
        double B2 = 1 + b * b;
        double es[3] = {-2 * b * Zs / B2, 0, (1 - b * b) * Zs / B2}, en[3] = {-2 * b * Zn / B2, 0, (1 - b * b) * Zn / B2};
        for (int i = 0; i < n; i++) {
            const double *ps = rg2_mesh_at(&mesh, i, 0), *pn = rg2_mesh_at(&mesh, i, m + 1);
            double a[3] = {ps[0] / ps[3], ps[1] / ps[3], ps[2] / ps[3]}, c[3] = {pn[0] / pn[3], pn[1] / pn[3], pn[2] / pn[3]};
            wpp = fmax(wpp, fmax(pt_dist3(a, es), pt_dist3(c, en)));
        }
        /* band against eq. (16) at the sphere's (u, v) */
        rg2_surface band;
        CHECK_OK(rg2_surface_build(&mesh, &band, &err), &err);
        double theta = 0;
        for (int i = 0; i < n; i++) {
            for (int j = 0; j < m - 1; j++)
                for (int a = 0; a <= 4; a++)
                    for (int bb = 0; bb <= 4; bb++) {
                        rg2_eval e;
                        rg2_patch_eval(rg2_surface_patch(&band, i, j), a / 4.0, bb / 4.0, 0, &e);
                        double th = arc_angle(theta, alpha[i], a / 4.0), cu = cos(th), su = sin(th);
                        double vv = v[j] + (v[j + 1] - v[j]) * bb / 4.0, q = vv * (1 - vv);
                        double h[4] = {2 * (b * (1 - 2 * vv) + (1 - b * b) * q * cu), 2 * (1 + b * b) * q * su,
                                       (b * b - 1) * (1 - 2 * vv) + 4 * b * q * cu,
                                       (1 + b * b) * (2 * vv * vv - 2 * vv + 1)};
                        double x[3] = {h[0] / h[3], h[1] / h[3], h[2] / h[3]};
                        wpar = fmax(wpar, pt_dist3(e.p, x));
                    }
            theta += alpha[i];
        }
        rg2_surface_free(&band);
        double pole[2][3];
        rg2t_seams g;
        double d = capped_sphere(&mesh, c0, 1.0, pole, &g);
        wd = fmax(wd, d);
        CHECK(g.angle <= 1e-12 && g.curv <= 1e-10, "b = %g: seams %.3g %.3g", b, g.angle, g.curv);
        double s_ex[3] = {2 * b / B2, 0, (b * b - 1) / B2}, n_ex[3] = {-2 * b / B2, 0, (1 - b * b) / B2};
        wpole = fmax(wpole, fmax(pt_dist3(pole[0], s_ex), pt_dist3(pole[1], n_ex)));
        rg2_mesh_free(&mesh);
    }
    CHECK(wd <= 1e-13, "Moebius spheres exact: %.3g", wd);
    CHECK(wpole <= 1e-14, "poles at (2b, 0, b^2 - 1) / (1 + b^2) and (-2b, 0, 1 - b^2) / (1 + b^2): %.3g", wpole);
    CHECK(wpp <= 1e-14, "polar points of eq. 16: %.3g", wpp);
    CHECK(wpar <= 1e-13, "band is the eq. 16 parameterization: %.3g", wpar);
    CHECK(wl <= 1e-15, "eq. 16 is a Lorentz map: %.3g", wl);
    printf("  b in {0, 0.2, -0.5, 1, 3}: distance %.2e, poles %.2e, polar points %.2e, parameterization %.2e\n", wd,
           wpole, wpp, wpar);
}

/* General pole pairs (not antipodal): a boost composed with a rotation; placed sphere. */
static void mobius_general(void)
{
    rg2t_rng r;
    uint64_t seed = 1717;
    rg2t_seed(&r, seed);
    printf("general Moebius pole placement, seed %llu\n", (unsigned long long)seed);
    double wd = 0, wpole = 0, wl = 0;
    for (int t = 0; t < 6; t++) {
        double s[3], nn[3];
        for (int k = 0; k < 3; k++)
            s[k] = rg2t_uniform(&r, -1, 1), nn[k] = rg2t_uniform(&r, -1, 1);
        if (t == 0)
            for (int k = 0; k < 3; k++)
                nn[k] = -s[k]; /* antipodal */
        double ls = sqrt(s[0] * s[0] + s[1] * s[1] + s[2] * s[2]), ln = sqrt(nn[0] * nn[0] + nn[1] * nn[1] + nn[2] * nn[2]);
        for (int k = 0; k < 3; k++)
            s[k] /= ls, nn[k] /= ln;
        /* keep the poles >= 90 deg apart: a strong boost sends control points outside the
         * sphere through infinity (tested in errors()) */
        if (s[0] * nn[0] + s[1] * nn[1] + s[2] * nn[2] > 0.0) {
            t--;
            continue;
        }
        double M[16];
        rg2_error err;
        CHECK_OK(rg2_mobius_poles_matrix(s, nn, M, &err), &err);
        wl = fmax(wl, lorentz_defect(M));
        double off = poles_mapped_off(M, s, nn);
        CHECK(off <= 1e-14, "poles mapped %.3g off", off);
        /* placed sphere: center c, radius R */
        double c[3] = {rg2t_uniform(&r, -1, 1), rg2t_uniform(&r, -1, 1), rg2t_uniform(&r, -1, 1)}, R = rg2t_uniform(&r, 0.5, 2);
        double P[16] = {R, 0, 0, c[0], 0, R, 0, c[1], 0, 0, R, c[2], 0, 0, 0, 1};
        int n = rg2t_int(&r, 6, 9), m = rg2t_int(&r, 3, 6);
        double alpha[16], v[16];
        pt_random_arcs(&r, n, alpha);
        pt_random_knots(&r, m, 0.0, 1.0, v);
        rg2_mesh mesh;
        CHECK_OK(rg2_polar_sphere_mesh(alpha, n, 0.0, v, m, P, &mesh, &err), &err);
        rg2_status st = rg2_mesh_mobius(&mesh, c, R, M, &err);
        CHECK(st == RG2_OK, "general Moebius on mesh: %s", err.msg);
        if (st == RG2_OK) {
            double pole[2][3];
            rg2t_seams g;
            double d = capped_sphere(&mesh, c, R, pole, &g);
            wd = fmax(wd, d);
            CHECK(g.angle <= 1e-12 && g.curv <= 1e-9, "general Moebius seams %.3g %.3g at %s (trial %d)", g.angle,
                  g.curv, g.where, t);
            double ps[3], pn[3];
            for (int k = 0; k < 3; k++)
                ps[k] = c[k] + R * s[k], pn[k] = c[k] + R * nn[k];
            wpole = fmax(wpole, fmax(pt_dist3(pole[0], ps), pt_dist3(pole[1], pn)) / R);
        }
        rg2_mesh_free(&mesh);
    }
    CHECK(wd <= 1e-13, "general Moebius spheres exact: %.3g", wd);
    CHECK(wpole <= 1e-13, "poles at the requested points: %.3g", wpole);
    CHECK(wl <= 1e-13, "Lorentz maps: %.3g", wl);
    printf("  6 pole pairs (1 antipodal): distance %.2e, poles %.2e, Lorentz defect %.2e\n", wd, wpole, wl);
}

static void errors(void)
{
    rg2_error err;
    double s[3] = {0, 0, -1}, nb[3] = {0, 0, 1.1}, M[16];
    CHECK(rg2_mobius_poles_matrix(s, nb, M, &err) == RG2_EDOMAIN && strstr(err.msg, "north"), "%s", err.msg);
    CHECK(rg2_mobius_poles_matrix(s, s, M, &err) == RG2_EDOMAIN && strstr(err.msg, "coincide"), "%s", err.msg);
    /* close poles (but not coincident): a finite matrix taking the poles where asked. 1e-8 apart
     * gave c = 1 and an infinite boost; 1e-6 apart 1 - c kept four digits (poles 1e-12 off) */
    const double seps[8] = {1e-2, 1e-3, 1e-4, 1e-5, 1e-6, 1e-7, 1e-8, 2e-9}; /* (2e-9: just past the limit) */
    for (int t = 0; t < 8; t++) {
        double a = seps[t], sp[3] = {0, 0, -1}, np_[3] = {sin(a), 0, -cos(a)}, Mc[16];
        CHECK_OK(rg2_mobius_poles_matrix(sp, np_, Mc, &err), &err);
        double e = poles_mapped_off(Mc, sp, np_);
        CHECK(e <= 1e-15, "poles %.0e rad apart mapped %.3g off", a, e);
    }
    /* nearly opposite poles, tilted by a from (0, 0, 1) towards x and towards y: the small boost
     * must push along n + s (another direction perpendicular to the pole axis put the images up to
     * a / sqrt 2 off, 6.4e-7 at a = 9e-7; 1 + c formed from c put them 1e-11 to 4e-11 off) */
    /* then exactly opposite poles on each axis (the frame's perpendicular built from an axis
     * whose components are 0): a rotation taking them where asked */
    const double tilts[7] = {2e-6, 1.5e-6, 9e-7, 5e-7, 1e-7, 1e-8, 1e-12};
    for (int t = 0; t < 17; t++) {
        double a = t < 14 ? tilts[t / 2] : 0.0, sp[3] = {0, 0, -1}, np_[3] = {0, 0, cos(a)}, Mo[16];
        np_[t % 2] = sin(a);
        if (t >= 14) /* the axis t - 14 */
            for (int k = 0; k < 3; k++)
                np_[k] = k == t - 14, sp[k] = -np_[k];
        CHECK_OK(rg2_mobius_poles_matrix(sp, np_, Mo, &err), &err);
        double e = poles_mapped_off(Mo, sp, np_), dl = lorentz_defect(Mo);
        CHECK(e <= 1e-15 && dl <= 1e-15, "case %d: poles %.1e rad from opposite: images %.3g off, Lorentz defect %.3g",
              t, a, e, dl);
    }
    /* closer than the points' own tolerance (1e-9) they count as one point: 5e-10 apart refused */
    double s5[3] = {0, 0, -1}, n5[3] = {5e-10, 0, -1};
    CHECK(rg2_mobius_poles_matrix(s5, n5, M, &err) == RG2_EDOMAIN && strstr(err.msg, "coincide"),
          "poles 5e-10 apart: %s", err.msg);
    /* coincident poles off every axis, named (the test must see each coordinate's difference) */
    double q3[3] = {2.0 / 3, -1.0 / 3, 2.0 / 3};
    CHECK(rg2_mobius_poles_matrix(q3, q3, M, &err) == RG2_EDOMAIN &&
              strstr(err.msg, "coincide at (0.666667, -0.333333, 0.666667)"),
          "coincident poles (2, -1, 2) / 3: %s", err.msg);
    double alpha[3] = {2 * M_PI / 3, 2 * M_PI / 3, 2 * M_PI / 3}, v[2] = {0.3, 0.7};
    rg2_mesh m;
    CHECK_OK(rg2_polar_sphere_mesh(alpha, 3, 0.0, v, 2, NULL, &m, &err), &err);
    /* a Lorentz map that sends a control point through infinity: boost towards the polar point */
    double c0[3] = {0, 0, 0};
    double sn[3] = {0, 0.999999, -sqrt(1 - 0.999999 * 0.999999)}, nn[3] = {0, 1, 0};
    rg2_status st = rg2_mobius_poles_matrix(sn, nn, M, &err);
    CHECK(st == RG2_OK, "nearly coincident poles accepted: %s", err.msg);
    double before = m.p[3];
    st = rg2_mesh_mobius(&m, c0, 1.0, M, &err);
    CHECK(st == RG2_EWEIGHT && strstr(err.msg, "weight") && m.p[3] == before, "weight through zero: %s", err.msg);
    /* the weight test's edges, with maps written here: a weight row of 0 gives every point the
     * weight 0 exactly, refused naming the first; 0.005 I (the same points, weights 0.005 w) and
     * the identity about a sphere of radius 0.005 (any radius > 0) are taken */
    double Mz[16] = {1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 0}, Ms[16] = {0}, I4[16] = {0};
    for (int k = 0; k < 4; k++)
        Ms[5 * k] = 0.005, I4[5 * k] = 1.0;
    st = rg2_mesh_mobius(&m, c0, 1.0, Mz, &err);
    CHECK(st == RG2_EWEIGHT && strstr(err.msg, "control point [0][0] gets weight 0;") && m.p[3] == before,
          "weight exactly 0: %s", err.msg);
    rg2_mesh ms, mr;
    CHECK_OK(rg2_mesh_copy(&m, &ms, &err), &err);
    CHECK_OK(rg2_mesh_copy(&m, &mr, &err), &err);
    CHECK_OK(rg2_mesh_mobius(&ms, c0, 1.0, Ms, &err), &err);
    CHECK_OK(rg2_mesh_mobius(&mr, c0, 0.005, I4, &err), &err);
    double dw = 0.0, dp = 0.0, dr = 0.0;
    for (int k = 0; k < 4 * m.nu * m.nv; k++) {
        double w = m.p[4 * (k / 4) + 3];
        if (k % 4 == 3)
            dw = fmax(dw, fabs(ms.p[k] - 0.005 * w) / w);
        else
            dp = fmax(dp, fabs(ms.p[k] / ms.p[4 * (k / 4) + 3] - m.p[k] / w));
        dr = fmax(dr, fabs(mr.p[k] - m.p[k]));
    }
    CHECK(dw <= 1e-15 && dp <= 1e-15 && dr <= 1e-15, "0.005 I: weights %.3g, points %.3g off; identity about radius 0.005: %.3g",
          dw, dp, dr);
    rg2_mesh_free(&ms);
    rg2_mesh_free(&mr);
    CHECK(rg2_mesh_mobius(&m, c0, 0.0, M, &err) == RG2_EDOMAIN, "radius 0: %s", err.msg);
    CHECK(rg2_mesh_mobius(&m, c0, NAN, M, &err) == RG2_ENONFINITE && !strcmp(err.msg, "moebius: sphere radius is not finite"),
          "radius NaN: %s", err.msg);
    double p[4] = {0, 0, 1, 0};
    CHECK(rg2_polar_set_point(&m, 0, p, &err) == RG2_EWEIGHT, "polar weight 0: %s", err.msg);
    CHECK(rg2_polar_set_point(&m, 2, p, &err) == RG2_EINVAL, "end 2: %s", err.msg);
    p[3] = 2;
    CHECK_OK(rg2_polar_set_point(&m, 1, p, &err), &err);
    CHECK(rg2_mesh_row_collapsed(&m, m.nv - 1) && rg2_mesh_at(&m, 2, m.nv - 1)[2] == 1, "whole row moved");
    double bad[2] = {0.7, 0.3};
    rg2_mesh b;
    CHECK(rg2_polar_sphere_mesh(alpha, 3, 0.0, bad, 2, NULL, &b, &err) == RG2_EDOMAIN, "knots: %s", err.msg);
    double a2[3] = {1, 1, 1};
    CHECK(rg2_polar_sphere_mesh(a2, 3, 0.0, v, 2, NULL, &b, &err) == RG2_EDOMAIN && strstr(err.msg, "2 pi"),
          "arcs: %s", err.msg);
    CHECK(rg2_polar_sphere_mesh(alpha, 2, 0.0, v, 2, NULL, &b, &err) == RG2_EINVAL &&
              !strcmp(err.msg, "polar sphere: 2 arcs given, a closed circle needs at least 3"),
          "2 arcs: %s", err.msg);
    /* a NULL alpha is not "0 arcs" (it was, whatever n_alpha said) */
    CHECK(rg2_polar_sphere_mesh(NULL, 8, 0.0, v, 2, NULL, &b, &err) == RG2_EINVAL &&
              !strcmp(err.msg, "polar sphere: no arcs (NULL alpha)"),
          "NULL arcs: %s", err.msg);
    for (int mm = 1; mm >= -6; mm -= 7) /* m <= -5 was refused as out of memory */
        CHECK(rg2_polar_sphere_mesh(alpha, 3, 0.0, v, mm, NULL, &b, &err) == RG2_EINVAL &&
                  strstr(err.msg, mm == 1 ? "polar knots: 1 interior knots given; a polar configuration needs at least 2"
                                          : "polar knots: -6 interior knots given;") && b.p == NULL,
              "m = %d: %s", mm, err.msg);
    /* m + 2 control points in v past the limit: refused before v is read, both counts named */
    {
        char want[160];
        snprintf(want, sizeof want, "polar sphere: %d interior knots give %lld control points in v, more than the limit of %d",
                 INT_MAX, (long long)INT_MAX + 2, RG2_MAX_POINTS);
        CHECK(rg2_polar_sphere_mesh(alpha, 3, 0.0, v, INT_MAX, NULL, &b, &err) == RG2_ELIMIT && !strcmp(err.msg, want) &&
                  b.p == NULL,
              "m = INT_MAX: %s", err.msg);
        /* the bound itself: m + 2 = RG2_MAX_POINTS + 1 points refused by it, m + 2 = RG2_MAX_POINTS
         * passes it (and 3 x RG2_MAX_POINTS points are the mesh's limit, refused there) */
        int top = RG2_MAX_POINTS - 1;
        double *vt = malloc((size_t)top * sizeof *vt);
        CHECK(vt != NULL, "no memory for %d knots", top);
        if (vt) {
            for (int k = 0; k < top; k++)
                vt[k] = (k + 1.0) / (top + 1.0);
            snprintf(want, sizeof want, "polar sphere: %d interior knots give %lld control points in v, more than the limit of %d",
                     top, (long long)top + 2, RG2_MAX_POINTS);
            CHECK(rg2_polar_sphere_mesh(alpha, 3, 0.0, vt, top, NULL, &b, &err) == RG2_ELIMIT && !strcmp(err.msg, want) &&
                      b.p == NULL,
                  "m = RG2_MAX_POINTS - 1: %s", err.msg);
            CHECK(rg2_polar_sphere_mesh(alpha, 3, 0.0, vt, top - 1, NULL, &b, &err) == RG2_ELIMIT &&
                      !strstr(err.msg, "polar sphere:") && strstr(err.msg, "4000000") && b.p == NULL,
                  "m = RG2_MAX_POINTS - 2: %s", err.msg);
            free(vt);
        }
    }
    double P[16] = {1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1};
    P[6] = NAN;
    CHECK(rg2_polar_sphere_mesh(alpha, 3, 0.0, v, 2, P, &b, &err) == RG2_ENONFINITE &&
              !strcmp(err.msg, "polar sphere: placement entry 6 is not finite"),
          "NaN placement: %s", err.msg);
    double vn[2] = {0.3, NAN}, kn[8];
    CHECK(rg2_polar_knots(vn, 2, kn, &err) == RG2_ENONFINITE && !strcmp(err.msg, "polar knots: knot 1 is not finite"),
          "NaN knot: %s", err.msg);
    CHECK(rg2_polar_knots(NULL, 2, kn, &err) == RG2_EINVAL && !strcmp(err.msg, "polar knots: no interior knots (NULL v)"),
          "no knots: %s", err.msg);
    CHECK(rg2_polar_knots(kn, 2, NULL, &err) == RG2_EINVAL && !strcmp(err.msg, "polar knots: NULL output knots"),
          "no output: %s", err.msg);
    p[1] = INFINITY;
    CHECK(rg2_polar_set_point(&m, 0, p, &err) == RG2_ENONFINITE && !strcmp(err.msg, "polar point: component 1 is not finite"),
          "infinite polar point: %s", err.msg);
    p[1] = 0;
    rg2_mesh closed;
    CHECK_OK(rg2_mesh_init(&closed, 4, 4, 1, 1, &err), &err);
    CHECK(rg2_polar_set_point(&closed, 0, p, &err) == RG2_EINVAL && strstr(err.msg, "v-direction is closed"), "%s",
          err.msg);
    rg2_mesh_free(&closed);
    rg2_mesh none = {0};
    CHECK(rg2_polar_set_point(&none, 0, p, &err) == RG2_EINVAL && !strcmp(err.msg, "polar point: empty mesh"), "%s",
          err.msg);
    CHECK(rg2_mesh_mobius(&none, c0, 1.0, M, &err) == RG2_EINVAL && !strcmp(err.msg, "moebius: empty mesh"), "%s",
          err.msg);
    double cn[3] = {0, NAN, 0};
    CHECK(rg2_mesh_mobius(&m, cn, 1.0, M, &err) == RG2_ENONFINITE && !strcmp(err.msg, "moebius: center component 1 is not finite"),
          "%s", err.msg);
    /* any finite b: past 1e150 b^2 overflowed (b = 1e300 gave a NaN matrix); the rotation's
     * entries stay those of eq. (16), which tend to -1 and 2 / b */
    const double huge[4] = {1e151, -1e200, 1e300, 1e308};
    for (int k = 0; k < 4; k++) {
        double Mh[16];
        rg2_mobius_matrix(huge[k], NULL, Mh);
        int fin = 1;
        for (int q = 0; q < 16; q++)
            fin &= isfinite(Mh[q]);
        CHECK(fin && Mh[0] == -1.0 && Mh[10] == -1.0 && fabs(Mh[8] - 2.0 / huge[k]) <= 1e-15 * fabs(2.0 / huge[k]) &&
                  lorentz_defect(Mh) < 1e-15,
              "moebius b = %g: M[0] %g, M[8] %g (2 / b = %g)", huge[k], Mh[0], Mh[8], 2.0 / huge[k]);
    }
    double Mn[16];
    rg2_mobius_matrix(0.5, NULL, Mn);
    Mn[3] = INFINITY;
    CHECK(rg2_mesh_mobius(&m, c0, 1.0, Mn, &err) == RG2_ENONFINITE && !strcmp(err.msg, "moebius: matrix entry 3 is not finite"),
          "%s", err.msg);
    double sp[3] = {0, 0, -1}, np_[3] = {0, NAN, 1};
    CHECK(rg2_mobius_poles_matrix(sp, np_, M, &err) == RG2_ENONFINITE &&
              !strcmp(err.msg, "moebius: north pole component 1 is not finite"),
          "%s", err.msg);
    rg2_mesh_free(&m);
}

/* rg2_mobius_matrix with a rotation R applied after eq. (16): the poles go to R times their
 * eq. (16) images, and the map stays a Lorentz map of the sphere's 4-tuples. */
static void mobius_rotated(void)
{
    const double b = 0.4, c = cos(0.7), s = sin(0.7);
    const double R[9] = {c, -s, 0, s, c, 0, 0, 0, 1}; /* 0.7 rad about z */
    double M[16];
    rg2_mobius_matrix(b, R, M);
    double B2 = 1 + b * b, e = 0;
    const double pole[2][4] = {{0, 0, -1, 1}, {0, 0, 1, 1}};
    const double img[2][3] = {{2 * b / B2, 0, (b * b - 1) / B2}, {-2 * b / B2, 0, (1 - b * b) / B2}};
    for (int k = 0; k < 2; k++) {
        double q[4], want[3];
        apply(M, pole[k], q);
        for (int r = 0; r < 3; r++)
            want[r] = R[3 * r] * img[k][0] + R[3 * r + 1] * img[k][1] + R[3 * r + 2] * img[k][2];
        for (int r = 0; r < 3; r++)
            e = fmax(e, fabs(q[r] / q[3] - want[r]));
    }
    double ld = lorentz_defect(M);
    CHECK(e <= 1e-15 && ld <= 1e-15, "rotated Moebius matrix: poles off by %.3g, Lorentz defect %.3g", e, ld);
    printf("rotated Moebius matrix: poles %.2e from R times eq. (16), Lorentz defect %.2e\n", e, ld);
}

/* Collapse is a property of the affine control points: scaling each 4-tuple by its own factor
 * (weights 0.01, 1, 3.7, 100, ...) keeps every row's verdict, and a polar point moved by 1e-10
 * of the mesh size (100 times the 1e-12 tolerance) is no longer collapsed, whatever the scaling.
 * Equal knots leave a band interval of length 0 and are refused like decreasing ones. */
static void collapse_projective(void)
{
    double alpha[5] = {1.1, 1.3, 1.2, 1.4, 2 * M_PI - 5.0}, v[3] = {0.2, 0.55, 0.85};
    static const double wts[4] = {0.01, 1.0, 3.7, 100.0};
    rg2_error err;
    int bad = 0, n_rows = 0;
    for (int sc = 0; sc < 5; sc++) /* 0..3: every point by wts[sc]; 4: each point its own */
        for (int moved = 0; moved < 2; moved++) {
            rg2_mesh m;
            CHECK_OK(rg2_polar_sphere_mesh(alpha, 5, 0.3, v, 3, NULL, &m, &err), &err);
            if (moved) /* the mesh size is Zn / 1 = the north polar point's height, > 1 */
                for (int j = 0; j < m.nv; j += m.nv - 1) {
                    double *p = rg2_mesh_at(&m, 3, j), size = fabs(rg2_mesh_at(&m, 0, m.nv - 1)[2]);
                    p[0] += 1e-10 * size * p[3];
                }
            for (int i = 0; i < m.nu; i++)
                for (int j = 0; j < m.nv; j++) {
                    double *p = rg2_mesh_at(&m, i, j), f = sc < 4 ? wts[sc] : wts[(i + 3 * j) % 4];
                    for (int k = 0; k < 4; k++)
                        p[k] *= f;
                }
            for (int j = 0; j < m.nv; j++) {
                int want = (j == 0 || j == m.nv - 1) && !moved, got = rg2_mesh_row_collapsed(&m, j);
                n_rows++;
                if (got != want) {
                    bad++;
                    CHECK(0, "scaling %d, moved %d: row %d collapsed = %d, expected %d", sc, moved, j, got, want);
                }
            }
            CHECK(!rg2_mesh_row_collapsed(&m, -1) && !rg2_mesh_row_collapsed(&m, m.nv),
                  "rows -1 and %d do not exist", m.nv);
            rg2_mesh_free(&m);
        }
    printf("collapse detection under projective scaling: %d rows, %d wrong\n", n_rows, bad);
    double eq[3] = {0.3, 0.3, 0.6}, k[7];
    CHECK(rg2_polar_knots(eq, 3, k, &err) == RG2_EDOMAIN &&
              !strcmp(err.msg, "polar knots: knot 1 = 0.3 is not above knot 0 = 0.3"),
          "equal knots: %s", err.msg);
    rg2_mesh b;
    CHECK(rg2_polar_sphere_mesh(alpha, 5, 0.0, eq, 3, NULL, &b, &err) == RG2_EDOMAIN && b.p == NULL,
          "equal knots, sphere mesh: %s", err.msg);
}

/* A Moebius map that sends control points through infinity names one of them: the named point
 * [i][j] exists, and the map (applied here) really gives it the weight printed, <= 0. The map's
 * weight row depends only on the pole separation (a boost along x, then a rotation), so the mesh
 * is turned instead (its circle starts at theta0 = 0.3 + q pi / 4): the offending points move to
 * other columns. */
static void mobius_weight_message(void)
{
    double alpha[6] = {1, 1, 1, 1, 1, 2 * M_PI - 5}, v[3] = {0.25, 0.5, 0.75}, c0[3] = {0, 0, 0}, a = 1e-3;
    double nn[3] = {0, 1, 0}, sn[3] = {0, cos(a), -sin(a)}, M[16];
    rg2_error err;
    CHECK_OK(rg2_mobius_poles_matrix(sn, nn, M, &err), &err);
    int named = 0, later = 0, cols = 0;
    for (int q = 0; q < 8; q++) {
        rg2_mesh m;
        CHECK_OK(rg2_polar_sphere_mesh(alpha, 6, 0.3 + q * M_PI / 4, v, 3, NULL, &m, &err), &err);
        rg2_status st = rg2_mesh_mobius(&m, c0, 1.0, M, &err);
        int i = -1, j = -1;
        double w = NAN;
        const char *at = strstr(err.msg, "control point [");
        CHECK(st == RG2_EWEIGHT && at && sscanf(at, "control point [%d][%d] gets weight %lf", &i, &j, &w) == 3,
              "turn %d: %s", q, err.msg);
        if (i >= 0 && i < m.nu && j >= 0 && j < m.nv) {
            double img[4];
            apply(M, rg2_mesh_at(&m, i, j), img);
            CHECK(img[3] <= 0 && fabs(img[3] - w) <= 1e-5 * fabs(img[3]),
                  "turn %d: point [%d][%d] gets weight %.6g, the message says %g", q, i, j, img[3], w);
            named++;
            later += i * m.nv + j > 0;
            cols |= 1 << i;
        } else {
            CHECK(0, "turn %d: the message names point [%d][%d] of a %d x %d mesh", q, i, j, m.nu, m.nv);
        }
        rg2_mesh_free(&m);
    }
    int ncols = 0;
    for (int i = 0; i < 6; i++)
        ncols += cols >> i & 1;
    CHECK(named == 8 && later >= 4 && ncols >= 3,
          "%d of 8 messages name a point sent through infinity (%d past [0][0], in %d columns)", named, later, ncols);
    printf("Moebius through infinity: 8 turned meshes, %d messages name the right control point (%d past [0][0], "
           "%d columns)\n",
           named, later, ncols);
}

/* Poles must lie on the unit sphere to 1e-9 (rg2.h): 4e-10 off is accepted, and the map takes
 * the unit sphere's poles to the normalized points, to rounding (6.7e-11 off when the frame's
 * pole axis was taken from the points as given); 2e-9 off is refused. */
static void mobius_pole_tolerance(void)
{
    const double off[2] = {4e-10, 2e-9};
    for (int k = 0; k < 2; k++) {
        double f = 1 + off[k], s[3] = {0, 0, -(1 - off[k] / 2)}, n[3] = {0, 0.6 * f, 0.8 * f}, M[16];
        rg2_error err;
        rg2_status st = rg2_mobius_poles_matrix(s, n, M, &err);
        if (k == 0) {
            CHECK(st == RG2_OK, "pole %.0e off the sphere refused: %s", off[k], err.msg);
            double N4[4] = {0, 0, 1, 1}, y[4];
            apply(M, N4, y);
            double want[3] = {0, 0.6, 0.8}, got[3] = {y[0] / y[3], y[1] / y[3], y[2] / y[3]};
            double S4[4] = {0, 0, -1, 1}, x[4];
            apply(M, S4, x);
            double gots[3] = {x[0] / x[3], x[1] / x[3], x[2] / x[3]}, e = fmax(pt_dist3(got, want), pt_dist3(gots, (double[3]){0, 0, -1}));
            CHECK(st || e <= 4e-16, "pole %.0e off mapped %.3g from its normalized point", off[k], e);
            printf("poles %.0e off the unit sphere: their images %.2e from the normalized points\n", off[k], e);
        } else {
            CHECK(st == RG2_EDOMAIN && strstr(err.msg, "north pole") && strstr(err.msg, "not on the unit sphere"),
                  "pole %.0e off the sphere: %s", off[k], err.msg);
        }
    }
}

int main(void)
{
    mobius_rotated();
    polar_knots();
    collapse_projective();
    polar_sphere_band();
    polar_start_turns();
    mobius_b();
    mobius_general();
    errors();
    mobius_weight_message();
    mobius_pole_tolerance();
    return rg2t_done("test_poles");
}
