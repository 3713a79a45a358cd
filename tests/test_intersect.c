/* test_intersect.c -- rg2_find_crossings and the crossings row of rg2_check: measured
 * properties of the crossings found (the point on both exact sheets, independent implicit
 * equations and normals, the moved point's support) and of those not reported (every example
 * surface, poles and merges, surfaces that meet along an edge, a torus pulled close to its
 * opposite wall), bad arguments, the report on 1 to 4 threads, and the weld on 1 to 5 threads. */
#include "harness.h"
#include "scenes.h"

#include <limits.h>
#include <stdlib.h>
#include <string.h>

static double dist3(const double *a, const double *b)
{
    return sqrt((a[0] - b[0]) * (a[0] - b[0]) + (a[1] - b[1]) * (a[1] - b[1]) + (a[2] - b[2]) * (a[2] - b[2]));
}

/* The two sheets of the first crossing, evaluated again (order 1) at the returned parameters. */
static void sheets_at(const rg2_surface *surfs, const rg2_crossing_report *r, rg2_eval *ea, rg2_eval *eb)
{
    rg2_surface_eval(&surfs[r->a.surf], r->a.pi, r->a.pj, r->a.u, r->a.v, 1, ea);
    rg2_surface_eval(&surfs[r->b.surf], r->b.pi, r->b.pj, r->b.u, r->b.v, 1, eb);
}

/* Every example design (the .json files of examples/, sorted): no output surface crosses itself; all the
 * surfaces of a design together cross only in Fig. 1, whose four outputs are variants of one
 * torus overlaid in place (surface 2 is surface 0 with a point pulled out, 3 is 1 with two
 * lifted: the moved pieces cross the unmoved torus), and there only between different surfaces. */
static void examples(void)
{
    char *names[64];
    int n = rg2t_example_names(names, 64);
    CHECK(n >= 13, "%d example designs", n);
    for (int k = 0; k < n; k++) {
        rg2_design *d = NULL;
        rg2_error err;
        CHECK_OK(rg2_design_load(names[k], &d, &err), &err);
        int ns = d ? rg2_design_num_surfaces(d) : 0, tris = 0;
        rg2_surface *surfs = calloc((size_t)ns + 1, sizeof *surfs);
        for (int s = 0; s < ns; s++) {
            surfs[s] = *rg2_design_surface(d, s);
            rg2_crossing_report r;
            CHECK_OK(rg2_find_crossings(&surfs[s], 1, RG2_CROSSING_DEFAULT_DENSITY, 0, &r, &err), &err);
            CHECK(r.crossings == 0, "%s surface %d crosses itself: %d crossings of %d candidates, first patch (%d,%d) "
                  "x (%d,%d) at (%g, %g, %g), angle %g", names[k], s, r.crossings, r.candidates, r.a.pi, r.a.pj,
                  r.b.pi, r.b.pj, r.p[0], r.p[1], r.p[2], r.angle);
            CHECK(r.triangles > 0 && r.triangles <= 2 * surfs[s].nu * surfs[s].nv * 16,
                  "%s surface %d: %d triangles, at most 2 x 4^2 per patch", names[k], s, r.triangles);
            tris += r.triangles;
        }
        rg2_crossing_report all;
        CHECK_OK(rg2_find_crossings(surfs, ns, RG2_CROSSING_DEFAULT_DENSITY, 0, &all, &err), &err);
        CHECK(all.triangles == tris, "%s: %d triangles together, %d one by one", names[k], all.triangles, tris);
        if (strstr(names[k], "fig1_torus")) {
            CHECK(all.crossings > 0 && all.a.surf != all.b.surf,
                  "%s: the overlaid variants cross each other (%d crossings, surfaces %d, %d)", names[k],
                  all.crossings, all.a.surf, all.b.surf);
            printf("%s: %d surfaces overlaid in place cross each other: %d confirmed of %d candidate pairs; first "
                   "surface %d x %d at (%.4f, %.4f, %.4f), normals %.3g rad apart\n", names[k], ns, all.crossings,
                   all.candidates, all.a.surf, all.b.surf, all.p[0], all.p[1], all.p[2], all.angle);
        } else
            CHECK(all.crossings == 0, "%s: its %d surfaces cross: %d crossings, surfaces %d x %d at (%g, %g, %g)",
                  names[k], ns, all.crossings, all.a.surf, all.b.surf, all.p[0], all.p[1], all.p[2]);
        free(surfs);
        rg2_design_free(d);
        free(names[k]);
    }
}

/* The torus R = 3, r = 1 over 8 x 6 arcs (u = 0 and v = 0 at the outer equator point (4, 0, 0))
 * with control point (0, 0) moved by dx along x (dx = 0: the exact torus). */
static void torus_moved(double dx, rg2_mesh *m, rg2_surface *s)
{
    rg2_error err;
    CHECK_OK(scene_revolve(3, 1, 8, 6, 1, 0, 0, m, s, &err), &err);
    if (dx != 0) {
        rg2_mesh_at(m, 0, 0)[0] += dx * rg2_mesh_at(m, 0, 0)[3];
        rg2_surface_free(s);
        CHECK_OK(rg2_surface_build(m, s, &err), &err);
    }
}

/* Whether patch (i, j) of a differs from b's (the moved point's support, measured). */
static int patch_moved(const rg2_surface *a, const rg2_surface *b, int i, int j)
{
    size_t k = (size_t)i * (size_t)a->nv + (size_t)j;
    return memcmp(&a->patch[k], &b->patch[k], sizeof a->patch[k]) != 0;
}

/* The smallest x over dense samples of the moved patches near the plane y = 0 (|y| < 0.3,
 * |z| < 0.3): how close the bulge, pushed in along -x, comes to the opposite (inner) wall of
 * the tube at x = R - r = 2. */
static double bulge_min_x(const rg2_surface *s, const rg2_surface *ref)
{
    double best = HUGE_VAL;
    for (int i = 0; i < s->nu; i++)
        for (int j = 0; j < s->nv; j++)
            if (patch_moved(s, ref, i, j))
                for (int a = 0; a <= 40; a++)
                    for (int b = 0; b <= 40; b++) {
                        rg2_eval e;
                        rg2_surface_eval(s, i, j, a / 40.0, b / 40.0, 0, &e);
                        if (fabs(e.p[1]) < 0.3 && fabs(e.p[2]) < 0.3)
                            best = fmin(best, e.p[0]);
                    }
    return best;
}

/* A torus with its outer control point (4, 0, 0) pushed in through the tube past the inner
 * wall: crossings found; the point lies on both exact sheets; one sheet is a moved patch. The
 * same point pushed less (the bulge stops short of the inner wall): none. */
static void torus_pushed_through(void)
{
    rg2_mesh m0, m;
    rg2_surface ref, s;
    rg2_error err;
    torus_moved(0, &m0, &ref);
    torus_moved(-6.0, &m, &s);
    double minx = bulge_min_x(&s, &ref);
    CHECK(minx < 1.9, "the pushed bulge reaches x = %.4f, past the inner wall at x = 2", minx);
    rg2_crossing_report r;
    CHECK_OK(rg2_find_crossings(&s, 1, RG2_CROSSING_DEFAULT_DENSITY, 0, &r, &err), &err);
    CHECK(r.crossings > 0, "pushed-through torus: %d crossings of %d candidates", r.crossings, r.candidates);
    if (r.crossings > 0) {
        rg2_eval ea, eb;
        sheets_at(&s, &r, &ea, &eb);
        double gap = dist3(ea.p, eb.p) / r.size;
        CHECK(gap < 1e-9, "the crossing point is on both sheets: gap %.3g of the size", gap);
        CHECK(dist3(ea.p, r.p) < 1e-9 * r.size, "the reported point is S_a there (%.3g)", dist3(ea.p, r.p));
        CHECK(patch_moved(&s, &ref, r.a.pi, r.a.pj) || patch_moved(&s, &ref, r.b.pi, r.b.pj),
              "one of the patches (%d,%d), (%d,%d) is in the moved point's support", r.a.pi, r.a.pj, r.b.pi, r.b.pj);
        double nx = ea.n[1] * eb.n[2] - ea.n[2] * eb.n[1], ny = ea.n[2] * eb.n[0] - ea.n[0] * eb.n[2],
               nz = ea.n[0] * eb.n[1] - ea.n[1] * eb.n[0];
        double ang = atan2(sqrt(nx * nx + ny * ny + nz * nz),
                           fabs(ea.n[0] * eb.n[0] + ea.n[1] * eb.n[1] + ea.n[2] * eb.n[2]));
        CHECK(ang > 0.1 && fabs(ang - r.angle) < 1e-9, "a transversal crossing: normals %.4f rad apart (report %.4f)",
              ang, r.angle);
        printf("torus pushed through (control point moved by -6 in x, bulge to x = %.3f): %d of %d candidate pairs "
               "confirmed; first patch (%d,%d) x (%d,%d), gap %.2e of the size, normals %.3f rad apart\n",
               minx, r.crossings, r.candidates, r.a.pi, r.a.pj, r.b.pi, r.b.pj, gap, r.angle);
    }
    rg2_surface_free(&s);
    rg2_mesh_free(&m);
    /* pulled close to the inner wall, not through (bulge stopping short of x = 2) */
    torus_moved(-4.0, &m, &s);
    minx = bulge_min_x(&s, &ref);
    CHECK(minx > 2.02 && minx < 2.6, "the near-miss bulge stops at x = %.4f, short of the wall at 2", minx);
    for (int dens = 2; dens <= 8; dens *= 2) {
        CHECK_OK(rg2_find_crossings(&s, 1, dens, 0, &r, &err), &err);
        CHECK(r.crossings == 0, "near-miss torus at density %d: %d crossings (first (%d,%d) x (%d,%d))", dens,
              r.crossings, r.a.pi, r.a.pj, r.b.pi, r.b.pj);
    }
    printf("torus pulled to x = %.3f (%.3f from the inner wall): no crossing at densities 2, 4, 8\n", minx,
           minx - 2);
    rg2_surface_free(&s);
    rg2_mesh_free(&m);
    rg2_surface_free(&ref);
    rg2_mesh_free(&m0);
}

/* Two cylinders of radius 1 at right angles (tests/data/crossing_cylinders.json: x^2 + y^2 = 1
 * and y^2 + z^2 = 1) as two output surfaces: they cross; the point satisfies both implicit
 * equations and the angle is that of the exact normals (x, y, 0) and (0, y, z). */
static void crossing_cylinders(void)
{
    rg2_design *d = NULL;
    rg2_error err;
    CHECK_OK(rg2_design_load("tests/data/crossing_cylinders.json", &d, &err), &err);
    if (!d)
        return;
    rg2_surface surfs[2] = {*rg2_design_surface(d, 0), *rg2_design_surface(d, 1)};
    for (int dens = 1; dens <= 16; dens *= 4) {
        rg2_crossing_report r;
        CHECK_OK(rg2_find_crossings(surfs, 2, dens, 0, &r, &err), &err);
        CHECK(r.crossings > 0 && r.a.surf != r.b.surf, "cylinders at density %d: %d crossings, surfaces %d x %d",
              dens, r.crossings, r.a.surf, r.b.surf);
        if (!r.crossings)
            continue;
        const double *p = r.p;
        double f1 = p[0] * p[0] + p[1] * p[1] - 1, f2 = p[1] * p[1] + p[2] * p[2] - 1;
        CHECK(fabs(f1) < 1e-12 && fabs(f2) < 1e-12, "density %d: the point (%.17g, %.17g, %.17g) on both: x^2+y^2-1 "
              "= %.3g, y^2+z^2-1 = %.3g", dens, p[0], p[1], p[2], f1, f2);
        double n1[3] = {p[0], p[1], 0}, n2[3] = {0, p[1], p[2]};
        double c = fabs(n1[1] * n2[1]) / (sqrt(n1[0] * n1[0] + n1[1] * n1[1]) * sqrt(n2[1] * n2[1] + n2[2] * n2[2]));
        double exact = acos(fmin(c, 1.0));
        CHECK(fabs(exact - r.angle) < 1e-9, "density %d: angle %.15g, exact normals give %.15g", dens, r.angle, exact);
        rg2_eval ea, eb;
        sheets_at(surfs, &r, &ea, &eb);
        CHECK(dist3(ea.p, eb.p) < 1e-9 * r.size, "density %d: both sheets at the point (%.3g)", dens,
              dist3(ea.p, eb.p));
        printf("crossing cylinders, density %d: %d of %d candidate pairs confirmed; first at (%.6f, %.6f, %.6f): "
               "residuals %.1e, %.1e; angle %.6f rad (exact normals %.6f)\n", dens, r.crossings, r.candidates, p[0],
               p[1], p[2], f1, f2, r.angle, exact);
    }
    /* the same at sizes 1e-55 and 1e55 (tolerances relative to the size; J J^T, 1e110, cubed would overflow) */
    for (int e = -1; e <= 1; e += 2) {
        double k = pow(10.0, 55 * e), T[16] = {k, 0, 0, 0, 0, k, 0, 0, 0, 0, k, 0, 0, 0, 0, 1};
        rg2_mesh m[2];
        rg2_surface sc[2];
        for (int q = 0; q < 2; q++) {
            CHECK_OK(rg2_mesh_copy(rg2_design_mesh(d, q), &m[q], &err), &err);
            rg2_mesh_transform(&m[q], T);
            CHECK_OK(rg2_surface_build(&m[q], &sc[q], &err), &err);
        }
        rg2_crossing_report r;
        CHECK_OK(rg2_find_crossings(sc, 2, 4, 0, &r, &err), &err);
        double x = r.p[0] / k, y = r.p[1] / k, z = r.p[2] / k;
        CHECK(r.crossings > 0 && fabs(x * x + y * y - 1) < 1e-12 && fabs(y * y + z * z - 1) < 1e-12,
              "cylinders scaled by %g: %d crossings, point / scale (%g, %g, %g)", k, r.crossings, x, y, z);
        for (int q = 0; q < 2; q++) {
            rg2_surface_free(&sc[q]);
            rg2_mesh_free(&m[q]);
        }
    }
    /* each cylinder alone: none */
    for (int s = 0; s < 2; s++) {
        rg2_crossing_report r;
        CHECK_OK(rg2_find_crossings(&surfs[s], 1, 4, 0, &r, &err), &err);
        CHECK(r.crossings == 0, "cylinder %d alone: %d crossings", s, r.crossings);
    }
    rg2_design_free(d);
}

/* A one-patch surface: a straight profile from (x0, z0) to (x1, z1) extruded along y in [0, 2]. */
static void plate(double x0, double z0, double x1, double z1, rg2_surface *s)
{
    double prof[4][3];
    for (int r = 0; r < 4; r++) {
        prof[r][0] = x0 + (x1 - x0) * r / 3.0;
        prof[r][1] = z0 + (z1 - z0) * r / 3.0;
        prof[r][2] = 1.0;
    }
    memset(s, 0, sizeof *s);
    s->nu = s->nv = 1;
    s->patch = calloc(1, sizeof *s->patch);
    s->bu = calloc(1, sizeof(double));
    s->gu = calloc(1, sizeof(double));
    s->bv = calloc(1, sizeof(double));
    s->gv = calloc(1, sizeof(double));
    if (s->patch)
        scene_extrude(prof, 2.0, s->patch);
}

/* Surfaces that meet along an edge touch, they do not cross: two plates at right angles with a
 * common edge (an L), a plate whose edge lies on another's middle (a T), each with its own
 * vertices (the T's edge is not one of the other plate's rows). A plate through the other's
 * middle (an X) does cross: the same test with the border rule removed would report all. */
static void edges_touch(void)
{
    rg2_surface s[2];
    rg2_error err;
    rg2_crossing_report r;
    static const double shapes[3][2][4] = {
        {{0, 0, 1, 0}, {0, 0, 0, 1}},            /* L: common edge x = z = 0 */
        {{-1, 0, 1, 0}, {0.123, 0, 0.123, 1}},   /* T: the second's edge on the first's middle */
        {{-1, 0, 1, 0}, {0.123, -1, 0.123, 1}},  /* X: through it */
    };
    for (int k = 0; k < 3; k++) {
        for (int q = 0; q < 2; q++)
            plate(shapes[k][q][0], shapes[k][q][1], shapes[k][q][2], shapes[k][q][3], &s[q]);
        for (int dens = 1; dens <= 9; dens += 4) {
            CHECK_OK(rg2_find_crossings(s, 2, dens, 0, &r, &err), &err);
            if (k < 2)
                CHECK(r.crossings == 0, "%s at density %d: %d crossings (%d candidates)", k ? "T" : "L", dens,
                      r.crossings, r.candidates);
            else {
                CHECK(r.crossings > 0, "X at density %d: %d crossings", dens, r.crossings);
                CHECK(r.crossings == 0 || (fabs(r.p[0] - 0.123) < 1e-12 && fabs(r.p[2]) < 1e-12 &&
                                           fabs(r.angle - M_PI / 2) < 1e-12),
                      "X: the crossing on the line x = 0.123, z = 0 at right angles: (%g, %g, %g), %g", r.p[0], r.p[1],
                      r.p[2], r.angle);
            }
        }
        rg2_surface_free(&s[0]);
        rg2_surface_free(&s[1]);
    }
}

/* Whether the open segment PQ pierces the inside of triangle T (Moeller-Trumbore, strict); the
 * point in X. Generic position assumed (no edge in the other's plane, no vertex on an edge). */
static int seg_pierces(const double *P, const double *Q, const double *const T[3], double X[3])
{
    double e1[3], e2[3], d[3], h[3], s[3], q[3];
    for (int c = 0; c < 3; c++) {
        e1[c] = T[1][c] - T[0][c];
        e2[c] = T[2][c] - T[0][c];
        d[c] = Q[c] - P[c];
        s[c] = P[c] - T[0][c];
    }
    h[0] = d[1] * e2[2] - d[2] * e2[1], h[1] = d[2] * e2[0] - d[0] * e2[2], h[2] = d[0] * e2[1] - d[1] * e2[0];
    double a = e1[0] * h[0] + e1[1] * h[1] + e1[2] * h[2];
    if (fabs(a) < 1e-300)
        return 0;
    double u = (s[0] * h[0] + s[1] * h[1] + s[2] * h[2]) / a;
    q[0] = s[1] * e1[2] - s[2] * e1[1], q[1] = s[2] * e1[0] - s[0] * e1[2], q[2] = s[0] * e1[1] - s[1] * e1[0];
    double v = (d[0] * q[0] + d[1] * q[1] + d[2] * q[2]) / a, t = (e2[0] * q[0] + e2[1] * q[1] + e2[2] * q[2]) / a;
    if (!(u > 0 && v > 0 && u + v < 1 && t > 0 && t < 1))
        return 0;
    for (int c = 0; c < 3; c++)
        X[c] = P[c] + t * d[c];
    return 1;
}

/* Whether triangles A and B cross: an edge of one pierces the other (brute force, independent
 * of the library's plane-interval test); E: the ends of their common segment (the two piercing
 * points, in generic position). */
static int tris_cross(const double *const A[3], const double *const B[3], double E[2][3])
{
    double X[3];
    int n = 0;
    for (int k = 0; k < 3; k++)
        for (int w = 0; w < 2; w++) {
            const double *const *T = w ? A : B, *const *S = w ? B : A;
            if (seg_pierces(S[k], S[(k + 1) % 3], T, X) && n++ < 2)
                memcpy(E[n - 1], X, sizeof X);
        }
    return n == 2;
}

/* The distance from X to the segment PQ. */
static double seg_dist(const double *X, const double *P, const double *Q)
{
    double d[3] = {Q[0] - P[0], Q[1] - P[1], Q[2] - P[2]}, w[3] = {X[0] - P[0], X[1] - P[1], X[2] - P[2]};
    double t = (w[0] * d[0] + w[1] * d[1] + w[2] * d[2]) / (d[0] * d[0] + d[1] * d[1] + d[2] * d[2]), c[3];
    t = fmin(fmax(t, 0.0), 1.0);
    for (int k = 0; k < 3; k++)
        c[k] = P[k] + t * d[k];
    return dist3(X, c);
}

/* The pairs of triangles of s[0]'s and s[1]'s tessellations at dens (into t, the caller frees)
 * that cross, by brute force (tris_cross); first: the common segment of the first pair (in the
 * order of the triangles of s[0], then of s[1]). */
static int crossing_pairs(const rg2_surface s[2], int dens, rg2_tess t[2], double first[2][3])
{
    rg2_error err;
    int count = 0;
    memset(first, 0, 2 * sizeof first[0]);
    for (int q = 0; q < 2; q++)
        CHECK_OK(rg2_tessellate(&s[q], dens, 0, &t[q], &err), &err);
    for (int a = 0; a < t[0].n_triangles; a++)
        for (int b = 0; b < t[1].n_triangles; b++) {
            const int *va = t[0].tri + 3 * a, *vb = t[1].tri + 3 * b;
            const double *A[3] = {t[0].pos + 3 * va[0], t[0].pos + 3 * va[1], t[0].pos + 3 * va[2]};
            const double *B[3] = {t[1].pos + 3 * vb[0], t[1].pos + 3 * vb[1], t[1].pos + 3 * vb[2]};
            double E[2][3];
            if (tris_cross(A, B, E) && count++ == 0)
                memcpy(first, E, sizeof E);
        }
    return count;
}

/* A flat plate (x = 0.123, z from -0.77 to 1.13, y from 0.37 to 2.37) through another (z = 0, x
 * from -1 to 1, y from 0 to 2), in generic position (no vertex of one on the other, edges of
 * neither along the crossing line): the candidate pairs are exactly the pairs of their
 * tessellations' triangles that cross (all pairs, brute force, by edges piercing triangles),
 * and all are confirmed (flat patches: the meshes are exact); the first crossing reported is
 * the pair of lowest triangle indices, at the midpoint of the two triangles' common segment. */
static void mesh_candidates(void)
{
    for (int dens = 1; dens <= 7; dens += 3) {
        rg2_surface s[2];
        rg2_tess t[2];
        rg2_error err;
        plate(-1, 0, 1, 0, &s[0]);
        plate(0.123, -0.77, 0.123, 1.13, &s[1]);
        for (int r = 0; r < 4; r++) /* the second moved by 0.37 along y */
            for (int c = 0; c < 4; c++)
                s[1].patch[0].h[r][c][1] += 0.37 * s[1].patch[0].h[r][c][3];
        double first[2][3];
        int count = crossing_pairs(s, dens, t, first);
        rg2_crossing_report r;
        CHECK_OK(rg2_find_crossings(s, 2, dens, 0, &r, &err), &err);
        CHECK(count > 0 && r.candidates == count && r.crossings == count,
              "plates at density %d: %d candidates, %d crossings; brute force: %d crossing triangle pairs", dens,
              r.candidates, r.crossings, count);
        CHECK(r.triangles == t[0].n_triangles + t[1].n_triangles && r.a.surf == 0 && r.b.surf == 1 &&
                  seg_dist(r.p, first[0], first[1]) < 1e-12 && fabs(r.p[0] - 0.123) < 1e-12 && fabs(r.p[2]) < 1e-12,
              "plates at density %d: the first crossing (surfaces %d x %d) at (%.15g, %.15g, %.15g), %.3g from the "
              "first pair's common segment, y from %.15g to %.15g", dens, r.a.surf, r.b.surf, r.p[0], r.p[1], r.p[2],
              seg_dist(r.p, first[0], first[1]), first[0][1], first[1][1]);
        for (int q = 0; q < 2; q++) {
            rg2_tess_free(&t[q]);
            rg2_surface_free(&s[q]);
        }
    }
}

/* A plate through another just inside its own border (x = 0.123, z from -0.002 to 1: the
 * crossing line 0.002 / 1.002 of its profile from the border; and mirrored, z from -1 to 0.002):
 * a crossing, though the confirmation starts near the border (only ON it, within 1e-9, the
 * sheets touch). The point on the line x = 0.123, z = 0, the parameter of the second sheet
 * across the profile 0.002 / 1.002 from the border. */
static void near_border(void)
{
    static const double z[2][2] = {{-0.002, 1}, {-1, 0.002}};
    for (int k = 0; k < 2; k++)
        for (int dens = 1; dens <= 9; dens += 4) {
            rg2_surface s[2];
            rg2_error err;
            rg2_crossing_report r;
            plate(-1, 0, 1, 0, &s[0]);
            plate(0.123, z[k][0], 0.123, z[k][1], &s[1]);
            CHECK_OK(rg2_find_crossings(s, 2, dens, 0, &r, &err), &err);
            double from_border = k ? 1 - r.b.u : r.b.u, expect = 0.002 / 1.002; /* (u along the profile) */
            CHECK(r.crossings > 0 && r.b.surf == 1 && fabs(r.p[0] - 0.123) < 1e-12 && fabs(r.p[2]) < 1e-12 &&
                      fabs(from_border - expect) < 1e-9,
                  "plate %s its border at density %d: %d crossings (%d candidates) at (%g, %g, %g), %.12g of the "
                  "profile from the border (expected %.12g)", k ? "ending 0.002 past the other near" : "starting "
                  "0.002 before the other near", dens, r.crossings, r.candidates, r.p[0], r.p[1], r.p[2],
                  from_border, expect);
            rg2_surface_free(&s[0]);
            rg2_surface_free(&s[1]);
        }
}

/* The upright cylinder x^2 + y^2 = 1 of tests/data/crossing_cylinders.json (8 arcs, 4 segments:
 * 32 curved patches) cut by a plate (the plane z = 0.335 + 0.0175 x, y from -0.55 to 1.45),
 * generic: the first crossing reported lies on both (their implicit equations), at the angle of
 * their exact normals (x, y, 0) and (-0.0175, 0, 1), and near the common segment of the first pair
 * of crossing triangles (brute force): no farther than the chord error, which is all Gauss-Newton
 * has to move from its start there. */
static void cylinder_plate(void)
{
    rg2_design *d = NULL;
    rg2_error err;
    CHECK_OK(rg2_design_load("tests/data/crossing_cylinders.json", &d, &err), &err);
    if (!d)
        return;
    for (int dens = 2; dens <= 4; dens += 2) {
        rg2_surface s[2] = {*rg2_design_surface(d, 0), {0}};
        rg2_tess t[2];
        double first[2][3];
        plate(-2, 0.3, 2, 0.37, &s[1]);
        for (int r = 0; r < 4; r++)
            for (int c = 0; c < 4; c++)
                s[1].patch[0].h[r][c][1] -= 0.55 * s[1].patch[0].h[r][c][3];
        int count = crossing_pairs(s, dens, t, first);
        rg2_crossing_report r;
        CHECK_OK(rg2_find_crossings(s, 2, dens, 0, &r, &err), &err);
        const double *p = r.p;
        /* the start is on the chords; Gauss-Newton moves it to the exact sheets, across the chord
         * error of a 45-degree arc in dens steps (its sagitta, radius 1) */
        double sag = 1 - cos(M_PI / 4 / dens / 2), gap = seg_dist(p, first[0], first[1]);
        double n1[3] = {p[0], p[1], 0}, n2[3] = {-0.0175, 0, 1};
        double c = fabs(n1[0] * n2[0]) / (sqrt(n1[0] * n1[0] + n1[1] * n1[1]) * sqrt(n2[0] * n2[0] + 1));
        CHECK(count > 0 && r.crossings > 0 && r.a.surf == 0 && r.b.surf == 1 &&
                  fabs(p[0] * p[0] + p[1] * p[1] - 1) < 1e-12 && fabs(p[2] - 0.335 - 0.0175 * p[0]) < 1e-12 &&
                  fabs(r.angle - acos(fmin(c, 1.0))) < 1e-9,
              "cylinder x plate at density %d: %d crossings (brute force: %d pairs) at (%.15g, %.15g, %.15g), "
              "angle %.15g (exact normals %.15g)", dens, r.crossings, count, p[0], p[1], p[2], r.angle,
              acos(fmin(c, 1.0)));
        CHECK(gap <= 1.2 * sag, "cylinder x plate at density %d: the first crossing %.3g from the first crossing "
              "pair's common segment, more than the chord error %.3g", dens, gap, sag);
        for (int q = 0; q < 2; q++)
            rg2_tess_free(&t[q]);
        rg2_surface_free(&s[1]);
    }
    rg2_design_free(d);
}

/* Two flat plates crossing along the line x = 0.123, z = 0 at an angle t: counted from
 * RG2_CROSSING_MIN_ANGLE up, with the angle t itself; below it (near-tangential) not counted. */
static void shallow_angles(void)
{
    static const double t[4] = {3e-4, 8e-4, 1.5e-3, 1e-2};
    for (int k = 0; k < 4; k++) {
        rg2_surface s[2];
        rg2_error err;
        rg2_crossing_report r;
        plate(-1, 0, 1, 0, &s[0]);
        plate(-1, (-1 - 0.123) * tan(t[k]), 1, (1 - 0.123) * tan(t[k]), &s[1]);
        CHECK_OK(rg2_find_crossings(s, 2, 4, 0, &r, &err), &err);
        if (t[k] < RG2_CROSSING_MIN_ANGLE)
            CHECK(r.crossings == 0 && r.candidates > 0, "plates %.1e rad apart: %d crossings of %d candidates: "
                  "near-tangential, not counted", t[k], r.crossings, r.candidates);
        else
            CHECK(r.crossings > 0 && fabs(r.angle - t[k]) < 1e-12 * t[k] + 1e-15 && fabs(r.p[0] - 0.123) < 1e-12,
                  "plates %.1e rad apart: %d crossings, angle %.17g, at x = %.17g", t[k], r.crossings, r.angle,
                  r.p[0]);
        rg2_surface_free(&s[0]);
        rg2_surface_free(&s[1]);
    }
}

/* Two 60 x 40 tori side by side (30 apart along x) and far apart in all three directions (1000
 * along each axis): no crossing either way, and the broad phase box-tests a few times as many
 * triangle pairs for the far pair as for the near one, not the square of a torus's triangles.
 * Its dense grid, bounded by the triangle count, once coarsened its cells until each torus lay
 * in one cell, tested pair by pair: 3.9e9 pairs against 4.6e6 (39 times the near pair's time).
 * The count of pairs is the work, deterministic where a time is not. */
static void far_apart(void)
{
    double pairs[2];
    for (int far = 0; far < 2; far++) {
        rg2_mesh m;
        rg2_surface s[2];
        rg2_error err;
        CHECK_OK(scene_revolve(3, 1, 60, 40, 1, 0, 0, &m, &s[0], &err), &err);
        for (int k = 0; k < m.nu * m.nv; k++) {
            double *h = m.p + 4 * (size_t)k;
            h[0] += (far ? 1000.0 : 30.0) * h[3];
            h[1] += (far ? 1000.0 : 0.0) * h[3];
            h[2] += (far ? 1000.0 : 0.0) * h[3];
        }
        CHECK_OK(rg2_surface_build(&m, &s[1], &err), &err);
        rg2_crossing_report r;
        CHECK_OK(rg2_find_crossings(s, 2, 4, 0, &r, &err), &err);
        pairs[far] = r.pairs;
        CHECK(r.crossings == 0 && r.triangles == 2 * 2 * 60 * 40 * 16, "%s tori: %d crossings, %d triangles",
              far ? "far" : "near", r.crossings, r.triangles);
        rg2_surface_free(&s[0]);
        rg2_surface_free(&s[1]);
        rg2_mesh_free(&m);
    }
    /* 4.6 and 10.0 million (the hashed lists mix cells); one torus's 76800 triangles tested pair
     * by pair would be 2.9e9 */
    CHECK(pairs[0] > 0 && pairs[1] <= 4 * pairs[0],
          "two tori far apart: %.0f pairs box-tested, side by side %.0f", pairs[1], pairs[0]);
    printf("two 60 x 40 tori, 153600 triangles: pairs box-tested side by side %.0f, 1000 apart in x, y and z %.0f\n",
           pairs[0], pairs[1]);
}

/* Bad arguments: each refused with its code and a message naming it. */
static void bad_arguments(void)
{
    rg2_mesh m;
    rg2_surface s;
    rg2_error err;
    rg2_crossing_report r;
    torus_moved(0, &m, &s);
    static const int dens[3] = {0, -3, 1001};
    for (int k = 0; k < 3; k++) {
        rg2_status st = rg2_find_crossings(&s, 1, dens[k], 0, &r, &err);
        CHECK(st == RG2_EINVAL && strstr(err.msg, "density") && r.density == 0, "density %d: %s (%s)", dens[k],
              rg2_status_str(st), err.msg);
    }
    rg2_status st = rg2_find_crossings(&s, 1, 1000, 0, &r, &err); /* 48 x 2 x 1000^2 triangles */
    CHECK(st == RG2_ELIMIT && strstr(err.msg, "density 1000") && strstr(err.msg, "96000000"), "density 1000: %s (%s)",
          rg2_status_str(st), err.msg);
    st = rg2_find_crossings(NULL, 1, 4, 0, &r, &err);
    CHECK(st == RG2_EINVAL && strstr(err.msg, "no surfaces"), "NULL surfaces: %s (%s)", rg2_status_str(st), err.msg);
    st = rg2_find_crossings(&s, 0, 4, 0, &r, &err);
    CHECK(st == RG2_EINVAL && strstr(err.msg, "no surfaces"), "n = 0: %s (%s)", rg2_status_str(st), err.msg);
    st = rg2_find_crossings(&s, 1, 4, 0, NULL, &err);
    CHECK(st == RG2_EINVAL && strstr(err.msg, "no report"), "NULL report: %s (%s)", rg2_status_str(st), err.msg);
    rg2_surface empty = {0};
    st = rg2_find_crossings(&empty, 1, 4, 0, &r, &err);
    CHECK(st == RG2_EINVAL && strstr(err.msg, "surface 0 has no patches"), "no patches: %s (%s)", rg2_status_str(st),
          err.msg);
    rg2_check_opts o;
    rg2_check_opts_default(&o);
    CHECK(o.crossing_density == 0, "crossings are off by default (%d)", o.crossing_density);
    rg2_check_report cr;
    for (int k = 0; k < 2; k++) {
        o.crossing_density = k ? 1001 : -1;
        st = rg2_check(&s, 1, NULL, NULL, 0, &o, &cr, &err);
        CHECK(st == RG2_EINVAL && strstr(err.msg, "crossing_density"), "check crossing_density %d: %s (%s)",
              o.crossing_density, rg2_status_str(st), err.msg);
    }
    o.crossing_density = 0;
    for (int k = 0; k < 2; k++) { /* surfs[0] named below 0, or surfs[n - 1] beyond INT_MAX */
        o.surface_base = k ? INT_MAX : -1;
        st = rg2_check(&s, 1, NULL, NULL, 0, &o, &cr, &err);
        /* the range given is 0..INT_MAX - 1 for one surface (the whole message) */
        char want[128];
        snprintf(want, sizeof want, "check: surface_base %d outside 0..%d (INT_MAX - 1 surfaces)", o.surface_base,
                 INT_MAX - 1);
        CHECK(st == RG2_EINVAL && !strcmp(err.msg, want), "check surface_base %d: %s (%s)", o.surface_base,
              rg2_status_str(st), err.msg);
    }
    o.surface_base = INT_MAX - 1; /* the largest a single surface may take */
    st = rg2_check(&s, 1, NULL, NULL, 0, &o, &cr, &err);
    CHECK(st == RG2_OK && cr.g1.surf == INT_MAX - 1, "check surface_base INT_MAX - 1: %s (%s)", rg2_status_str(st),
          err.msg);
    if (st == RG2_OK)
        rg2_check_report_free(&cr);
    o.surface_base = 0;
    o.crossing_density = 1000;
    st = rg2_check(&s, 1, NULL, NULL, 0, &o, &cr, &err);
    CHECK(st == RG2_ELIMIT && strstr(err.msg, "check: crossings:"), "check at density 1000: %s (%s)",
          rg2_status_str(st), err.msg);
    rg2_surface_free(&s);
    rg2_mesh_free(&m);
}

/* Whether two crossing reports hold the same values (field by field: padding is not compared). */
static int same_crossings(const rg2_crossing_report *x, const rg2_crossing_report *y)
{
    const rg2_crossing_sheet *s[4] = {&x->a, &y->a, &x->b, &y->b};
    for (int k = 0; k < 4; k += 2)
        if (s[k]->surf != s[k + 1]->surf || s[k]->pi != s[k + 1]->pi || s[k]->pj != s[k + 1]->pj ||
            memcmp(&s[k]->u, &s[k + 1]->u, sizeof(double)) || memcmp(&s[k]->v, &s[k + 1]->v, sizeof(double)))
            return 0;
    return x->density == y->density && x->triangles == y->triangles && x->candidates == y->candidates &&
           x->crossings == y->crossings && !memcmp(x->p, y->p, sizeof x->p) &&
           !memcmp(&x->residual, &y->residual, sizeof(double)) && !memcmp(&x->angle, &y->angle, sizeof(double)) &&
           !memcmp(&x->size, &y->size, sizeof(double));
}

/* rg2_check with crossing_density: the report's crossings equal rg2_find_crossings', the
 * promise fails for the crossing torus and when not searched, holds for the clean torus; the
 * report (struct and text) is the same on 1, 2 and 3 threads; without the option the text has
 * no crossings row. */
static void check_integration(void)
{
    rg2_mesh m;
    rg2_surface s;
    rg2_error err;
    torus_moved(-6.0, &m, &s);
    rg2_crossing_report direct;
    CHECK_OK(rg2_find_crossings(&s, 1, 4, 0, &direct, &err), &err);
    rg2_check_opts o;
    rg2_check_opts_default(&o);
    o.crossing_density = 4;
    char *text[3] = {NULL, NULL, NULL};
    rg2_crossing_report got[3];
    for (int t = 1; t <= 3; t++) {
        rg2_check_report cr;
        o.threads = t;
        CHECK_OK(rg2_check(&s, 1, NULL, NULL, 0, &o, &cr, &err), &err);
        got[t - 1] = cr.crossings;
        CHECK(rg2_check_failures(&cr, RG2_REQUIRE_NO_CROSSINGS) == RG2_REQUIRE_NO_CROSSINGS,
              "%d threads: no-crossings fails for the pushed torus", t);
        CHECK_OK(rg2_check_format(&cr, 0, &text[t - 1], &err), &err);
        rg2_check_report_free(&cr);
    }
    CHECK(same_crossings(&got[0], &direct), "check's crossings equal rg2_find_crossings'");
    /* surface_base 7: the same report, every surface it names (the crossing's two sheets, the
     * worst gaps, the largest |k|) named 7 instead of 0 (rg2 check --surface's test covers the
     * shapes' places) */
    {
        rg2_check_report c0, c7;
        o.threads = 2;
        CHECK_OK(rg2_check(&s, 1, NULL, NULL, 0, &o, &c0, &err), &err);
        o.surface_base = 7;
        CHECK_OK(rg2_check(&s, 1, NULL, NULL, 0, &o, &c7, &err), &err);
        o.surface_base = 0;
        rg2_crossing_report x = c7.crossings;
        CHECK(x.crossings > 0 && x.a.surf == 7 && x.b.surf == 7, "base 7: the crossing's sheets %d, %d", x.a.surf,
              x.b.surf);
        x.a.surf = x.b.surf = 0;
        CHECK(same_crossings(&x, &c0.crossings), "base 7: otherwise the crossings of base 0");
        const rg2_check_gap *g0[3] = {&c0.g0, &c0.g1, &c0.g2}, *g7[3] = {&c7.g0, &c7.g1, &c7.g2};
        for (int k = 0; k < 3; k++)
            CHECK(g0[k]->surf == 0 && g7[k]->surf == 7 && g0[k]->value == g7[k]->value && g0[k]->pi == g7[k]->pi &&
                      g0[k]->t == g7[k]->t,
                  "base 7: G%d gap %g at surface %d (base 0: %g at %d)", k, g7[k]->value, g7[k]->surf, g0[k]->value,
                  g0[k]->surf);
        CHECK(c0.kpeak.surf == 0 && c7.kpeak.surf == 7 && c0.kpeak_k == c7.kpeak_k, "base 7: largest |k| at %d",
              c7.kpeak.surf);
        rg2_check_report_free(&c0);
        rg2_check_report_free(&c7);
    }
    CHECK(same_crossings(&got[0], &got[1]) && same_crossings(&got[0], &got[2]),
          "the crossings report on 1, 2, 3 threads is the same");
    CHECK(text[0] && text[1] && text[2] && !strcmp(text[0], text[1]) && !strcmp(text[0], text[2]) &&
              strstr(text[0], "crossings ") && strstr(text[0], "FAIL"),
          "the text on 1, 2, 3 threads is the same, with a failing crossings row");
    for (int t = 0; t < 3; t++)
        free(text[t]);
    rg2_surface_free(&s);
    rg2_mesh_free(&m);
    torus_moved(0, &m, &s);
    rg2_check_report cr;
    CHECK_OK(rg2_check(&s, 1, NULL, NULL, 0, &o, &cr, &err), &err);
    CHECK(cr.crossings.density == 4 && cr.crossings.crossings == 0 && cr.crossings.triangles == 48 * 32 &&
              !rg2_check_failures(&cr, RG2_REQUIRE_NO_CROSSINGS),
          "the exact torus: %d crossings over %d triangles", cr.crossings.crossings, cr.crossings.triangles);
    rg2_check_report_free(&cr);
    o.crossing_density = 0;
    CHECK_OK(rg2_check(&s, 1, NULL, NULL, 0, &o, &cr, &err), &err);
    char *t0 = NULL, *j0 = NULL;
    CHECK_OK(rg2_check_format(&cr, 0, &t0, &err), &err);
    CHECK_OK(rg2_check_format(&cr, 1, &j0, &err), &err);
    CHECK(cr.crossings.density == 0 && rg2_check_failures(&cr, RG2_REQUIRE_NO_CROSSINGS) &&
              t0 && !strstr(t0, "crossings") && j0 && !strstr(j0, "crossings"),
          "not searched: no row, no JSON object, and the promise fails");
    free(t0);
    free(j0);
    rg2_check_report_free(&cr);
    rg2_surface_free(&s);
    rg2_mesh_free(&m);
}

/* The report of rg2_find_crossings on 1, 2, 3 and 4 threads: identical, field by field (the
 * counts, pairs among them, and the first crossing in the order of the triangles: its sheets,
 * point, residual and angle, bit for bit), for the torus pushed through itself
 * (tests/data/torus_pushed_through.json), the crossing cylinders and a clean example, at two
 * densities, on threads however few the triangles. The threads share the pair tests cell by
 * cell in any order: each keeps its least confirmed pair and the reduction takes the least. */
extern int rg2__crossing_threads_from; /* src/internal.h */

static void threads_identical(void)
{
    int from = rg2__crossing_threads_from;
    rg2__crossing_threads_from = 0; /* threads for these small inputs too */
    static const char *const files[3] = {"tests/data/torus_pushed_through.json", "tests/data/crossing_cylinders.json",
                                         "examples/torus_sphere.json"};
    for (int f = 0; f < 3; f++) {
        rg2_design *d = NULL;
        rg2_error err;
        CHECK_OK(rg2_design_load(files[f], &d, &err), &err);
        if (!d)
            continue;
        int ns = rg2_design_num_surfaces(d);
        rg2_surface surfs[8];
        for (int s = 0; s < ns && s < 8; s++)
            surfs[s] = *rg2_design_surface(d, s);
        for (int dens = 3; dens <= 8; dens += 5) {
            rg2_crossing_report r[4];
            CHECK_OK(rg2_find_crossings(surfs, ns < 8 ? ns : 8, dens, 1, &r[0], &err), &err);
            CHECK(f == 2 ? r[0].crossings == 0 : r[0].crossings > 0, "%s at density %d: %d crossings", files[f], dens,
                  r[0].crossings);
            /* (five times each: which thread meets which cell varies from run to run) */
            for (int t = 2; t <= 4; t++)
                for (int rep = 0; rep < 5; rep++) {
                    CHECK_OK(rg2_find_crossings(surfs, ns < 8 ? ns : 8, dens, t, &r[t - 1], &err), &err);
                    const rg2_crossing_report *x = &r[t - 1], *y = &r[0];
                    CHECK(same_crossings(y, x) && y->pairs == x->pairs,
                          "%s at density %d: the report on %d threads differs from one thread's: %d / %d "
                          "crossings of %d / %d candidates, %.0f / %.0f pairs, first (%d,%d) x (%d,%d) / (%d,%d) x "
                          "(%d,%d), angle %.17g / %.17g", files[f], dens, t, x->crossings, y->crossings,
                          x->candidates, y->candidates, x->pairs, y->pairs, x->a.pi, x->a.pj, x->b.pi, x->b.pj,
                          y->a.pi, y->a.pj, y->b.pi, y->b.pj, x->angle, y->angle);
                }
            printf("%s, density %d: %d triangles, %.0f pairs, %d candidates, %d crossings: the same on 1, 2, 3, 4 "
                   "threads\n", files[f], dens, r[0].triangles, r[0].pairs, r[0].candidates, r[0].crossings);
        }
        rg2_design_free(d);
    }
    rg2__crossing_threads_from = from;
    rg2_mesh m;
    rg2_surface s;
    rg2_error err;
    rg2_crossing_report r;
    torus_moved(0, &m, &s);
    rg2_status st = rg2_find_crossings(&s, 1, 4, -1, &r, &err);
    CHECK(st == RG2_EINVAL && strstr(err.msg, "threads -1") && r.density == 0, "threads -1: %s (%s)",
          rg2_status_str(st), err.msg);
    rg2_surface_free(&s);
    rg2_mesh_free(&m);
}

/* The least confirmed pair when the lowest crossing triangle crosses many others, in many cells:
 * a plate (x from -5 to 5, y from 0 to 2, z = 0.3; at density 1 two triangles, 0 and 1) through
 * the tube of a 60 x 40 torus (R = 3, r = 1): its triangles cross some eighty of the torus's,
 * whose pairs the threads meet in cells of their own, several holding a pair of triangle 0. The
 * first crossing is the least pair (0, b) on any thread count: the report the same bit for bit as
 * one thread's (ten times each: which thread meets which cell varies from run to run). */
static void least_pair_threads(void)
{
    rg2_mesh m;
    rg2_surface s[2];
    rg2_error err;
    plate(-5, 0.3, 5, 0.3, &s[0]);
    CHECK_OK(scene_revolve(3, 1, 60, 40, 1, 0, 0, &m, &s[1], &err), &err);
    int from = rg2__crossing_threads_from;
    rg2__crossing_threads_from = 0;
    rg2_crossing_report one, r;
    CHECK_OK(rg2_find_crossings(s, 2, 1, 1, &one, &err), &err);
    CHECK(one.crossings > 50 && one.a.surf == 0 && one.b.surf == 1 && fabs(one.p[2] - 0.3) < 1e-12,
          "plate through the torus: %d crossings, first surfaces %d x %d at z = %.17g", one.crossings, one.a.surf,
          one.b.surf, one.p[2]);
    for (int t = 2; t <= 4; t++)
        for (int rep = 0; rep < 10; rep++) {
            CHECK_OK(rg2_find_crossings(s, 2, 1, t, &r, &err), &err);
            CHECK(same_crossings(&one, &r) && one.pairs == r.pairs,
                  "plate through the torus on %d threads: first (%d,%d) x (%d,%d) at (%.17g, %.17g, %.17g), one "
                  "thread (%d,%d) x (%d,%d) at (%.17g, %.17g, %.17g); %d / %d crossings", t, r.a.pi, r.a.pj, r.b.pi,
                  r.b.pj, r.p[0], r.p[1], r.p[2], one.a.pi, one.a.pj, one.b.pi, one.b.pj, one.p[0], one.p[1],
                  one.p[2], r.crossings, one.crossings);
        }
    printf("plate through a 60 x 40 torus at density 1: %d crossings of %d candidates, the first the same on 1 to "
           "4 threads\n", one.crossings, one.candidates);
    rg2__crossing_threads_from = from;
    rg2_surface_free(&s[0]);
    rg2_surface_free(&s[1]);
    rg2_mesh_free(&m);
}

/* The triangles of t (a plate of weld_saves) with two vertices on the line x = z = 0: the
 * y-ranges of those edges (lo, hi), their count. */
static int line_edges(const rg2_tess *t, double (*yr)[2], int max)
{
    int n = 0;
    for (int k = 0; k < t->n_triangles && n < max; k++) {
        double y[3];
        int on = 0;
        for (int c = 0; c < 3; c++) {
            const double *p = t->pos + 3 * t->tri[3 * k + c];
            if (p[0] == 0 && p[2] == 0)
                y[on++] = p[1];
        }
        if (on == 2) {
            yr[n][0] = fmin(y[0], y[1]);
            yr[n][1] = fmax(y[0], y[1]);
            n++;
        }
    }
    return n;
}

/* The weld: two plates at right angles meeting along the line x = z = 0 (an L; y from 0 to 2
 * and from `shift` to 2 + shift), each tessellated with its own vertices. A triangle of each
 * with an edge on the line is a candidate pair (the plane-interval test: the two edges overlap
 * on the line over a positive length; confirmed as touching on the border, never a crossing)
 * unless the weld made them share a vertex. Counted here from the tessellations: the pairs of
 * such edges overlapping over a positive length, and of those the pairs with a common
 * vertex (coincident ends). The library's candidates are the first count less the second:
 * with the plates' vertices in line (shift 0) every overlapping pair shares its ends, and the
 * weld saves them all (0 candidates; without the weld, density candidates); shifted by half
 * an edge, none shares a vertex and every overlapping pair is a candidate. One case: density
 * dens, shifted (sh) or not, on `threads` threads; the report in *r, the vertices in *nvert. */
static void weld_case(int dens, int sh, int threads, rg2_crossing_report *r, int *nvert)
{
    enum { MAX_EDGES = 256 };
    rg2_surface s[2];
    rg2_tess t[2];
    rg2_error err;
    double shift = sh ? 1.0 / dens : 0.0; /* half an edge (2 / dens long) */
    plate(0, 0, 1, 0, &s[0]);
    plate(0, 0, 0, 1, &s[1]);
    for (int a = 0; a < 4; a++)
        for (int b = 0; b < 4; b++)
            s[1].patch[0].h[a][b][1] += shift * s[1].patch[0].h[a][b][3];
    static double ya[MAX_EDGES][2], yb[MAX_EDGES][2];
    int na = 0, nb = 0, overlap = 0, shared = 0;
    for (int q = 0; q < 2; q++)
        CHECK_OK(rg2_tessellate(&s[q], dens, 0, &t[q], &err), &err);
    *nvert = t[0].n_vertices + t[1].n_vertices;
    na = line_edges(&t[0], ya, MAX_EDGES);
    nb = line_edges(&t[1], yb, MAX_EDGES);
    for (int i = 0; i < na; i++)
        for (int j = 0; j < nb; j++)
            if (fmin(ya[i][1], yb[j][1]) > fmax(ya[i][0], yb[j][0])) {
                overlap++;
                shared += ya[i][0] == yb[j][0] || ya[i][0] == yb[j][1] || ya[i][1] == yb[j][0] ||
                          ya[i][1] == yb[j][1];
            }
    CHECK_OK(rg2_find_crossings(s, 2, dens, threads, r, &err), &err);
    CHECK(na == dens && nb == dens && overlap > 0 && (sh ? shared == 0 : shared == overlap),
          "L at density %d, shift %g: %d and %d edges on the line, %d overlapping pairs, %d sharing ends",
          dens, shift, na, nb, overlap, shared);
    CHECK(r->crossings == 0 && r->candidates == overlap - shared,
          "L at density %d, shift %g, %d threads: %d candidates (%d crossings); %d edge pairs overlap on the line, "
          "%d of them with welded ends", dens, shift, threads, r->candidates, r->crossings, overlap, shared);
    if (threads == 1)
        printf("L of two plates, density %d, %s: %d edge pairs overlapping on the common line, %d sharing "
               "welded ends (skipped): %d candidates\n", dens, sh ? "shifted by half an edge" : "vertices in line",
               overlap, shared, r->candidates);
    for (int q = 0; q < 2; q++) {
        rg2_tess_free(&t[q]);
        rg2_surface_free(&s[q]);
    }
}

static void weld_saves(void)
{
    for (int dens = 1; dens <= 7; dens += 3)
        for (int sh = 0; sh < 2; sh++) {
            rg2_crossing_report r;
            int nv;
            weld_case(dens, sh, 1, &r, &nv);
        }
}

/* The weld on threads, past one sorted run: the L of weld_saves at densities 64 and 128, over
 * 8192 and 4 x 8192 vertices (the weld sorts them in runs of at least 8192, one per thread,
 * merged pairwise: 2 runs at density 64, 2 to 5 at 128 on 2 to 5 threads). On 1 to 5
 * threads the candidates are those counted on the tessellations (an unmerged or missorted run
 * loses welded pairs: candidates along the common line) and the report is the same bit for bit. */
static void weld_threads(void)
{
    int from = rg2__crossing_threads_from;
    rg2__crossing_threads_from = 0; /* threads for these inputs too */
    for (int dens = 64; dens <= 128; dens *= 2)
        for (int sh = 0; sh < 2; sh++) {
            rg2_crossing_report r[5];
            int nv = 0;
            for (int t = 1; t <= 5; t++) {
                weld_case(dens, sh, t, &r[t - 1], &nv);
                CHECK(same_crossings(&r[0], &r[t - 1]) && r[0].pairs == r[t - 1].pairs,
                      "L at density %d, shift %d: the report on %d threads differs from one thread's: %d / %d "
                      "candidates, %.0f / %.0f pairs", dens, sh, t, r[t - 1].candidates, r[0].candidates,
                      r[t - 1].pairs, r[0].pairs);
            }
            CHECK(nv > (dens == 64 ? 8192 : 4 * 8192), "L at density %d: %d vertices", dens, nv);
        }
    rg2__crossing_threads_from = from;
}

int main(void)
{
    examples();
    torus_pushed_through();
    crossing_cylinders();
    edges_touch();
    shallow_angles();
    mesh_candidates();
    near_border();
    cylinder_plate();
    far_apart();
    bad_arguments();
    check_integration();
    threads_identical();
    weld_saves();
    weld_threads();
    least_pair_threads();
    return rg2t_done("test_intersect");
}
