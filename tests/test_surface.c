/* test_surface.c -- the Bi-cubic Construction on random meshes: G2 across every seam,
 * measured geometrically and parametrically, for all closed/open combinations. */
#include "../src/internal.h"
#include "harness.h"
#include "scenes.h"
#include "xmix.h"

#include <float.h>
#include <math.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

static void random_scalars(rg2t_rng *r, rg2_scalars *s)
{
    int nw = rg2_scalars_num_w(s);
    for (int k = 0; k < nw; k++)
        s->w[k] = rg2t_uniform(r, 0.7, 1.4);
    for (int i = 0; i < s->n; i++)
        do { /* resample until K_i > 0, the construction's precondition */
            s->b[i] = rg2t_uniform(r, 0.5, 2.0);
            s->g[i] = rg2t_uniform(r, -0.8, 0.8);
        } while (!(rg2_scalars_K(s, i) > 0.0));
}

static void random_surfaces(void)
{
    rg2t_rng r;
    uint64_t seed = 20261122;
    rg2t_seed(&r, seed);
    printf("random surfaces, seed %llu\n", (unsigned long long)seed);
    rg2t_seams worst = {0};
    for (int trial = 0; trial < 24; trial++) {
        int cu = trial & 1, cv = (trial >> 1) & 1;
        int nu = rg2t_int(&r, cu ? 3 : 4, 8), nv = rg2t_int(&r, cv ? 3 : 4, 8);
        rg2_mesh m;
        rg2_error err;
        CHECK_OK(rg2_mesh_init(&m, nu, nv, cu, cv, &err), &err);
        random_scalars(&r, &m.su);
        random_scalars(&r, &m.sv);
        for (int i = 0; i < nu; i++)
            for (int j = 0; j < nv; j++) {
                double *p = rg2_mesh_at(&m, i, j);
                double W = rg2t_uniform(&r, 0.6, 1.6);
                for (int k = 0; k < 3; k++)
                    p[k] = W * rg2t_uniform(&r, -1, 1);
                p[3] = W;
            }
        rg2_surface s;
        rg2_status st = rg2_surface_build(&m, &s, &err);
        CHECK(st == RG2_OK, "build trial %d: %s", trial, err.msg);
        if (st == RG2_OK) {
            CHECK(s.nu == (cu ? nu : nu - 3) && s.nv == (cv ? nv : nv - 3), "patch counts %d x %d", s.nu,
                  s.nv);
            rg2t_seams g;
            rg2t_surface_seams(&s, 16, &g);
            CHECK(g.pos <= 1e-14, "trial %d position gap %.3g", trial, g.pos);
            CHECK(g.angle <= 1e-12, "trial %d normal angle %.3g", trial, g.angle);
            CHECK(g.curv <= 1e-10, "trial %d curvature jump %.3g at %s", trial, g.curv, g.where);
            CHECK(g.param1 <= 1e-12, "trial %d parametric G1 %.3g", trial, g.param1);
            CHECK(g.param2 <= 1e-12, "trial %d parametric G2 %.3g", trial, g.param2);
            if (g.pos > worst.pos) worst.pos = g.pos;
            if (g.angle > worst.angle) worst.angle = g.angle;
            if (g.curv > worst.curv) worst.curv = g.curv;
            if (g.param1 > worst.param1) worst.param1 = g.param1;
            if (g.param2 > worst.param2) worst.param2 = g.param2;
            worst.seams += g.seams;
            worst.skipped += g.skipped;
            rg2_surface_free(&s);
        }
        rg2_mesh_free(&m);
    }
    printf("  %d seams: position %.2e, normal angle %.2e rad, normal curvature %.2e rel, "
           "parametric %.2e / %.2e, skipped %d\n",
           worst.seams, worst.pos, worst.angle, worst.curv, worst.param1, worst.param2, worst.skipped);
}

/* A deliberately broken surface must be measured as broken (the measurement can fail). */
static void broken_is_detected(void)
{
    rg2_mesh m;
    rg2_error err;
    CHECK_OK(rg2_mesh_init(&m, 6, 6, 0, 0, &err), &err);
    for (int i = 0; i < 6; i++)
        for (int j = 0; j < 6; j++) {
            double *p = rg2_mesh_at(&m, i, j);
            p[0] = i;
            p[1] = j;
            p[2] = 0.3 * sin(i + 2.0 * j);
            p[3] = 1;
        }
    rg2_surface s;
    CHECK_OK(rg2_surface_build(&m, &s, &err), &err);
    s.gu[1] += 0.5; /* claim a different g than the construction used */
    /* move one interior control point of patch (1,1) off the G2 structure */
    s.patch[1 * s.nv + 1].h[1][1][2] += 0.05;
    rg2t_seams g;
    rg2t_surface_seams(&s, 8, &g);
    CHECK(g.param2 > 1e-3, "a broken g is detected: %.3g", g.param2);
    CHECK(g.curv > 1e-3, "a moved control point is detected: %.3g", g.curv);
    rg2_surface_free(&s);
    rg2_mesh_free(&m);
}

/* Construction order: rows then columns equals columns then rows (transpose the mesh). */
static void transpose_symmetry(void)
{
    rg2t_rng r;
    rg2t_seed(&r, 7);
    rg2_mesh m, t;
    rg2_error err;
    CHECK_OK(rg2_mesh_init(&m, 5, 7, 1, 0, &err), &err);
    CHECK_OK(rg2_mesh_init(&t, 7, 5, 0, 1, &err), &err);
    random_scalars(&r, &m.su);
    random_scalars(&r, &m.sv);
    rg2_scalars_free(&t.su);
    rg2_scalars_free(&t.sv);
    rg2_scalars_copy(&m.sv, &t.su, &err);
    rg2_scalars_copy(&m.su, &t.sv, &err);
    for (int i = 0; i < 5; i++)
        for (int j = 0; j < 7; j++) {
            double *p = rg2_mesh_at(&m, i, j), *q = rg2_mesh_at(&t, j, i);
            for (int k = 0; k < 4; k++)
                p[k] = q[k] = (k == 3) ? rg2t_uniform(&r, 0.8, 1.2) : rg2t_uniform(&r, -1, 1);
            q[3] = p[3];
        }
    rg2_surface a, b;
    CHECK_OK(rg2_surface_build(&m, &a, &err), &err);
    CHECK_OK(rg2_surface_build(&t, &b, &err), &err);
    double worst = 0;
    for (int i = 0; i < a.nu; i++)
        for (int j = 0; j < a.nv; j++)
            for (int r2 = 0; r2 < 4; r2++)
                for (int s2 = 0; s2 < 4; s2++)
                    for (int k = 0; k < 4; k++) {
                        double d = fabs(rg2_surface_patch(&a, i, j)->h[r2][s2][k] -
                                        rg2_surface_patch(&b, j, i)->h[s2][r2][k]);
                        if (d > worst) worst = d;
                    }
    CHECK(worst <= 1e-14, "rows-then-columns equals columns-then-rows: %.3g", worst);
    rg2_surface_free(&a);
    rg2_surface_free(&b);
    rg2_mesh_free(&m);
    rg2_mesh_free(&t);
}

/* rg2_surface_copy of an empty surface (what a failed build leaves) is an empty surface; a
 * successful copy clears err; a negative patch count is invalid, not "out of memory". */
static void copy_edge_cases(void)
{
    rg2_surface empty, c, bad;
    memset(&empty, 0, sizeof empty);
    rg2_error err = {RG2_EIO, "stale"};
    CHECK(rg2_surface_copy(&empty, &c, &err) == RG2_OK && c.nu == 0 && !c.patch && err.code == RG2_OK && !err.msg[0],
          "copy of an empty surface: %d '%s'", err.code, err.msg);
    rg2_surface_free(&c);
    memset(&bad, 0, sizeof bad);
    bad.nu = -1;
    bad.nv = 5;
    CHECK(rg2_surface_copy(&bad, &c, &err) == RG2_EINVAL, "negative patch count: %s", err.msg);
    /* a negative count in either direction is invalid whatever the other count or the patch array
     * (not an empty surface when the other count is 0, not "out of memory" when patches are set) */
    rg2_patch one;
    memset(&one, 0, sizeof one);
    const struct {
        int nu, nv, with_patch;
    } neg[] = {{-1, 0, 0}, {0, -1, 0}, {-1, 0, 1}, {0, -1, 1}, {-1, 5, 1}, {5, -1, 1}, {-2, -3, 1}};
    for (size_t q = 0; q < sizeof neg / sizeof neg[0]; q++) {
        memset(&bad, 0, sizeof bad);
        bad.nu = neg[q].nu, bad.nv = neg[q].nv, bad.patch = neg[q].with_patch ? &one : NULL;
        memset(&c, 0, sizeof c);
        rg2_status st = rg2_surface_copy(&bad, &c, &err);
        CHECK(st == RG2_EINVAL && strstr(err.msg, "not a surface") && !c.patch,
              "copy of a %d x %d surface (patches %s): %s '%s'", neg[q].nu, neg[q].nv,
              neg[q].with_patch ? "set" : "NULL", rg2_status_str(st), err.msg);
        if (st == RG2_OK)
            rg2_surface_free(&c);
    }
    /* zero patches in one direction, whatever the other count or the arrays, is an empty surface
     * (rg2.h): its copy is empty, zero by zero patches and no arrays */
    const int zero[][3] = {{5, 0, 1}, {0, 5, 1}, {5, 0, 0}, {0, 5, 0}, {0, 0, 1}};
    double scalars[5] = {1, 1, 1, 1, 1};
    for (size_t q = 0; q < sizeof zero / sizeof zero[0]; q++) {
        memset(&bad, 0, sizeof bad);
        bad.nu = zero[q][0], bad.nv = zero[q][1], bad.patch = zero[q][2] ? &one : NULL;
        bad.bu = bad.gu = bad.bv = bad.gv = scalars;
        memset(&c, 0xA5, sizeof c);
        rg2_status st = rg2_surface_copy(&bad, &c, &err);
        CHECK(st == RG2_OK && c.nu == 0 && c.nv == 0 && !c.patch && !c.bu && !c.gu && !c.bv && !c.gv && !c.tag && !c.xp,
              "copy of a %d x %d surface (patches %s): %s, %d x %d patches, patch array %s", zero[q][0], zero[q][1],
              zero[q][2] ? "set" : "NULL", rg2_status_str(st), c.nu, c.nv, c.patch ? "set" : "NULL");
        if (st == RG2_OK)
            rg2_surface_free(&c);
    }
}

static void mesh_errors(void)
{
    rg2_mesh m;
    rg2_error err;
    CHECK(rg2_mesh_init(&m, 3, 5, 0, 0, &err) == RG2_EINVAL && strstr(err.msg, "at least 4"),
          "open direction with 3 points: %s", err.msg);
    CHECK_OK(rg2_mesh_init(&m, 4, 4, 0, 0, &err), &err);
    for (int k = 0; k < 64; k++)
        m.p[k] = 1.0;
    rg2_mesh_at(&m, 2, 3)[1] = NAN;
    rg2_surface s;
    CHECK(rg2_surface_build(&m, &s, &err) == RG2_ENONFINITE && strstr(err.msg, "[2][3]"),
          "NaN point named: %s", err.msg);
    rg2_mesh_at(&m, 2, 3)[1] = 1.0;
    m.sv.w[2] = -0.5;
    CHECK(rg2_surface_build(&m, &s, &err) == RG2_EWEIGHT && strstr(err.msg, "w[1]") && strstr(err.msg, "mesh v"),
          "negative weight named: %s", err.msg);
    m.sv.w[2] = 1.0;
    m.su.g[1] = -10.0;
    CHECK(rg2_surface_build(&m, &s, &err) == RG2_EWEIGHT && strstr(err.msg, "junction 1") &&
              strstr(err.msg, "K ="),
          "K <= 0 named: %s", err.msg);
    m.su.g[1] = 0.0;
    m.su.b[3] = INFINITY;
    CHECK(rg2_surface_build(&m, &s, &err) == RG2_ENONFINITE && strstr(err.msg, "b[3]"), "inf b named: %s",
          err.msg);
    rg2_mesh_free(&m);
    CHECK(rg2_mesh_init(&m, 5000, 5000, 0, 0, &err) == RG2_ELIMIT, "huge mesh refused: %s", err.msg);
    /* the same count in a mesh made by hand (each direction within the limit, the total past it):
     * rg2_mesh_check, and so rg2_surface_build, took it */
    CHECK_OK(rg2_mesh_init(&m, 4, 4, 1, 1, &err), &err);
    rg2_scalars_free(&m.su);
    rg2_scalars_free(&m.sv);
    free(m.p);
    m.nu = m.nv = 2001;
    m.p = calloc((size_t)m.nu * (size_t)m.nv * 4, sizeof(double)); /* zeros: finite */
    CHECK_OK(rg2_scalars_init(&m.su, m.nu, 1, &err), &err);
    CHECK_OK(rg2_scalars_init(&m.sv, m.nv, 1, &err), &err);
    CHECK(!m.p || (rg2_mesh_check(&m, &err) == RG2_ELIMIT &&
                   !strcmp(err.msg, "mesh: 2001 x 2001 control points exceeds the limit of 4000000")),
          "2001 x 2001 mesh checked: %s", err.msg);
    rg2_mesh_free(&m);
    /* the limit itself is allowed ("past RG2_MAX_POINTS" is refused): 2000 x 2000 control points
     * are RG2_MAX_POINTS exactly, one more column is past it */
    CHECK(RG2_MAX_POINTS == 2000 * 2000, "RG2_MAX_POINTS %d", RG2_MAX_POINTS);
    CHECK_OK(rg2_mesh_init(&m, 2000, 2000, 0, 0, &err), &err);
    CHECK(m.p && m.nu == 2000 && m.nv == 2000, "2000 x 2000 mesh: %d x %d", m.nu, m.nv);
    rg2_mesh_free(&m);
    CHECK(rg2_mesh_init(&m, 2000, 2001, 0, 0, &err) == RG2_ELIMIT && !m.p &&
              !strcmp(err.msg, "mesh: 2000 x 2001 control points exceeds the limit of 4000000"),
          "2000 x 2001 mesh: %s", err.msg);
    /* no mesh, or one without points (all zeros, or freed): "mesh: empty", the points not read */
    CHECK(rg2_mesh_check(&m, &err) == RG2_EINVAL && !strcmp(err.msg, "mesh: empty"), "mesh of zeros: %s", err.msg);
    CHECK(rg2_mesh_check(NULL, &err) == RG2_EINVAL && !strcmp(err.msg, "mesh: empty"), "NULL mesh: %s", err.msg);
    /* the direction that is too small is named, for v as for u */
    CHECK(rg2_mesh_init(&m, 5, 3, 0, 0, &err) == RG2_EINVAL && !m.p && !m.su.w &&
              !strcmp(err.msg, "mesh v: scalars: 3 control points, an open direction needs at least 4"),
          "v with 3 points: %s", err.msg);
    CHECK(rg2_mesh_init(&m, 2, 5, 1, 0, &err) == RG2_EINVAL &&
              !strcmp(err.msg, "mesh u: scalars: 2 control points, a closed direction needs at least 3"),
          "closed u with 2 points: %s", err.msg);
    /* scalars that do not match the points, and a NaN weight */
    CHECK_OK(rg2_mesh_init(&m, 4, 4, 0, 0, &err), &err);
    for (int k = 0; k < 64; k++)
        m.p[k] = 1.0;
    rg2_scalars_free(&m.su);
    CHECK_OK(rg2_scalars_init(&m.su, 5, 0, &err), &err);
    CHECK(rg2_surface_build(&m, &s, &err) == RG2_EINVAL && !strcmp(err.msg, "mesh: 4 x 4 points but scalars for 5 x 4"),
          "mismatched scalars: %s", err.msg);
    rg2_mesh_at(&m, 1, 2)[3] = NAN;
    int wi = -1, wj = -1;
    CHECK(rg2_mesh_check_weights(&m, &wi, &wj, &err) == RG2_ENONFINITE && wi == 1 && wj == 2 &&
              !strcmp(err.msg, "control point [1, 2] has weight W = nan"),
          "NaN weight: (%d, %d) %s", wi, wj, err.msg);
    rg2_mesh_free(&m);
    CHECK(!strcmp(rg2_status_str(RG2_OK), "ok") && !strcmp(rg2_status_str((rg2_status)99), "unknown status") &&
              !strcmp(rg2_status_str(RG2_ELIMIT), "size limit exceeded"),
          "status texts");
}

/* The surfaces a and b are the same bit for bit (patches, junction scalars, counts, closure). */
static int same_surface(const rg2_surface *a, const rg2_surface *b)
{
    size_t np = (size_t)a->nu * (size_t)a->nv;
    return a->nu == b->nu && a->nv == b->nv && a->closed_u == b->closed_u && a->closed_v == b->closed_v &&
           !memcmp(a->patch, b->patch, np * sizeof(rg2_patch)) && !memcmp(a->bu, b->bu, a->nu * sizeof(double)) &&
           !memcmp(a->gu, b->gu, a->nu * sizeof(double)) && !memcmp(a->bv, b->bv, a->nv * sizeof(double)) &&
           !memcmp(a->gv, b->gv, a->nv * sizeof(double)) && !a->tag == !b->tag && !a->xp == !b->xp;
}

/* A random mesh: random scalars, points in [-1, 1]^3, weights in [0.6, 1.6]. */
static void random_mesh(rg2t_rng *r, int nu, int nv, int cu, int cv, rg2_mesh *m)
{
    rg2_error err;
    CHECK_OK(rg2_mesh_init(m, nu, nv, cu, cv, &err), &err);
    random_scalars(r, &m->su);
    random_scalars(r, &m->sv);
    for (int k = 0; k < nu * nv; k++) {
        double W = rg2t_uniform(r, 0.6, 1.6);
        for (int q = 0; q < 3; q++)
            m->p[4 * k + q] = W * rg2t_uniform(r, -1, 1);
        m->p[4 * k + 3] = W;
    }
}

/* rg2.h, rg2_surface_build: patch column i depends on points i-1..i+2 (closed, mod n) or i..i+3
 * (open), junction scalars b, g of those indices, stored weights w[i-2..i+2] (closed) or
 * w[i..i+4] (open); likewise in v. Each datum of a random mesh is changed in turn: every patch
 * outside the documented set keeps its bits, and some patch inside it changes. */
static int in_support(int i, int k, int lo, int hi, int n, int closed)
{
    for (int d = lo; d <= hi; d++) {
        int q = closed ? (((i + d) % n) + n) % n : i + d;
        if (q == k)
            return 1;
    }
    return 0;
}

static void support(void)
{
    rg2t_rng r;
    rg2t_seed(&r, 4242);
    rg2_error err;
    int outside = 0, none = 0, cases = 0;
    for (int trial = 0; trial < 4; trial++) {
        int cu = trial & 1, cv = (trial >> 1) & 1;
        rg2_mesh m;
        random_mesh(&r, 9, 8, cu, cv, &m);
        rg2_surface s0, s;
        memset(&s0, 0, sizeof s0);
        memset(&s, 0, sizeof s);
        CHECK_OK(rg2_surface_build(&m, &s0, &err), &err);
        for (int what = 0; what < 4; what++)     /* point, b, g, w */
            for (int dir = 0; dir < 2; dir++) {  /* scalars of u or v (points: both at once) */
                rg2_scalars *sc = dir ? &m.sv : &m.su;
                int n = sc->n, closed = sc->closed, nw = rg2_scalars_num_w(sc);
                for (int k = 0; k < (what == 3 ? nw : n); k++) {
                    int a = dir ? 3 : k, b = dir ? k : 3; /* the point moved: (k, 3) or (3, k) */
                    double save, *x = what == 0 ? rg2_mesh_at(&m, a, b) : what == 1 ? &sc->b[k]
                                                 : what == 2 ? &sc->g[k] : &sc->w[k];
                    save = *x;
                    *x = what == 2 ? save + 0.01 : save * 1.01;
                    rg2_status st = rg2_surface_rebuild(&m, &s, &err);
                    *x = save;
                    if (st)
                        continue; /* K <= 0 after the change: not a surface */
                    cases++;
                    int changed_inside = 0;
                    for (int i = 0; i < s.nu; i++)
                        for (int j = 0; j < s.nv; j++) {
                            int ch = memcmp(rg2_surface_patch(&s, i, j), rg2_surface_patch(&s0, i, j),
                                            sizeof(rg2_patch)) != 0;
                            int in;
                            if (what == 0) {
                                in = in_support(i, a, cu ? -1 : 0, cu ? 2 : 3, m.nu, cu) &&
                                     in_support(j, b, cv ? -1 : 0, cv ? 2 : 3, m.nv, cv);
                            } else {
                                int idx = dir ? j : i;
                                in = what == 3 ? in_support(idx, k, closed ? -2 : 0, closed ? 2 : 4, n, closed)
                                               : in_support(idx, k, closed ? -1 : 0, closed ? 2 : 3, n, closed);
                            }
                            if (ch && !in)
                                outside++;
                            changed_inside += ch && in;
                        }
                    /* open directions: the end data (junctions 0 and n-1, w[0] and w[n]) only
                     * shape the end patches through their neighbours' stencils, so a change there
                     * may change nothing; elsewhere something inside must change */
                    if (!changed_inside && (what == 0 || closed || (k > 0 && k < (what == 3 ? nw : n) - 1)))
                        none++;
                }
            }
        rg2_surface_free(&s);
        rg2_surface_free(&s0);
        rg2_mesh_free(&m);
    }
    CHECK(cases > 200 && outside == 0 && none == 0,
          "support: %d changes, %d patches changed outside the documented support, %d changes changed nothing", cases,
          outside, none);
}

/* rg2_surface_rebuild: the result of rg2_surface_build bit for bit, into the old memory when the
 * patch counts stay (an editing loop), into new memory otherwise; old tags and higher-degree
 * patches dropped; on failure the surface is left empty (ASan sees any leak). */
static void rebuild(void)
{
    rg2t_rng r;
    rg2t_seed(&r, 77);
    rg2_error err;
    rg2_surface s;
    memset(&s, 0, sizeof s);
    int reused = 0, edits = 0;
    for (int trial = 0; trial < 12; trial++) {
        int cu = trial & 1, cv = (trial >> 1) & 1;
        int nu = rg2t_int(&r, cu ? 3 : 4, 9), nv = rg2t_int(&r, cv ? 3 : 4, 9);
        rg2_mesh m;
        random_mesh(&r, nu, nv, cu, cv, &m);
        if (trial % 3 == 2) { /* the previous surface carries tags and higher-degree slots */
            size_t np = (size_t)s.nu * (size_t)s.nv;
            s.tag = calloc(np ? np : 1, sizeof(int));
            s.xp = calloc(np ? np : 1, sizeof(rg2_xpatch));
        }
        rg2_surface fresh;
        CHECK_OK(rg2_surface_build(&m, &fresh, &err), &err);
        CHECK_OK(rg2_surface_rebuild(&m, &s, &err), &err);
        CHECK(same_surface(&s, &fresh) && !s.tag && !s.xp, "trial %d (%d x %d, closed %d %d): rebuild = build",
              trial, nu, nv, cu, cv);
        /* editing: move one control point, rebuild in place */
        for (int e = 0; e < 3; e++) {
            const rg2_patch *before = s.patch;
            size_t np = (size_t)s.nu * (size_t)s.nv;
            rg2_patch *old = malloc(np * sizeof *old);
            memcpy(old, s.patch, np * sizeof *old);
            double *p = rg2_mesh_at(&m, rg2t_int(&r, 0, nu - 1), rg2t_int(&r, 0, nv - 1));
            p[2] += p[3] * rg2t_uniform(&r, 0.1, 0.5);
            rg2_surface_free(&fresh);
            CHECK_OK(rg2_surface_build(&m, &fresh, &err), &err);
            CHECK_OK(rg2_surface_rebuild(&m, &s, &err), &err);
            CHECK(same_surface(&s, &fresh), "trial %d edit %d: rebuild = build", trial, e);
            reused += s.patch == before;
            edits += memcmp(old, s.patch, np * sizeof *old) != 0; /* the edit reached the patches */
            free(old);
        }
        rg2_surface_free(&fresh);
        rg2_mesh_free(&m);
    }
    CHECK(reused == 36 && edits == 36, "edits rebuild in place: %d of 36 reused the patch memory, %d changed it",
          reused, edits);
    /* a bad mesh: the error of rg2_surface_build, the surface left empty */
    rg2_mesh m;
    CHECK_OK(rg2_mesh_init(&m, 5, 5, 0, 0, &err), &err);
    for (int k = 0; k < 25; k++)
        m.p[4 * k] = k, m.p[4 * k + 1] = k % 5, m.p[4 * k + 2] = 0, m.p[4 * k + 3] = 1;
    rg2_mesh_at(&m, 1, 4)[2] = NAN;
    CHECK(rg2_surface_rebuild(&m, &s, &err) == RG2_ENONFINITE && strstr(err.msg, "[1][4]") && !s.patch &&
              s.nu == 0,
          "bad mesh: %s; surface left empty", err.msg);
    rg2_mesh_at(&m, 1, 4)[2] = 0;
    CHECK_OK(rg2_surface_rebuild(&m, &s, &err), &err); /* from the empty surface */
    CHECK(s.nu == 2 && s.nv == 2, "rebuild after a failure: %d x %d patches", s.nu, s.nv);
    CHECK(rg2_surface_rebuild(&m, NULL, &err) == RG2_EINVAL, "NULL surface: %s", err.msg);
    rg2_surface_free(&s);
    rg2_mesh_free(&m);
    printf("rebuild: 12 meshes x 3 edits equal to rg2_surface_build bit for bit, %d of 36 in place\n", reused);
}

/* A surface of more than 2 MiB of patches (10379 patches, 5.3 MB): its patch array comes from
 * the huge-page allocator (src/alloc.c), 2 MiB-aligned on Linux. The build writes every byte of
 * it: rebuilt over patch memory filled with garbage, it is the fresh build bit for bit; its copy
 * is too. */
static void big_surface(void)
{
    rg2t_rng r;
    rg2t_seed(&r, 4096);
    rg2_error err;
    rg2_mesh m, m2;
    CHECK_OK(rg2_mesh_init(&m, 100, 110, 0, 0, &err), &err);
    CHECK_OK(rg2_mesh_init(&m2, 100, 110, 0, 0, &err), &err);
    random_scalars(&r, &m.su);
    random_scalars(&r, &m.sv);
    for (int k = 0; k < 100 * 110; k++) {
        double W = rg2t_uniform(&r, 0.6, 1.6);
        for (int q = 0; q < 3; q++)
            m.p[4 * k + q] = W * rg2t_uniform(&r, -1, 1);
        m.p[4 * k + 3] = W;
        for (int q = 0; q < 4; q++)
            m2.p[4 * k + q] = q == 3 ? 1.0 : k + q;
    }
    rg2_surface fresh, s, copy;
    CHECK_OK(rg2_surface_build(&m, &fresh, &err), &err);
    size_t np = (size_t)fresh.nu * (size_t)fresh.nv;
    CHECK(fresh.nu == 97 && fresh.nv == 107 && np * sizeof(rg2_patch) > (4u << 20), "%d x %d patches, %zu bytes",
          fresh.nu, fresh.nv, np * sizeof(rg2_patch));
#ifdef __linux__
    CHECK((uintptr_t)fresh.patch % (2u << 20) == 0, "patch array at %p: not on a 2 MiB boundary",
          (void *)fresh.patch);
#endif
    CHECK_OK(rg2_surface_build(&m2, &s, &err), &err);
    memset(s.patch, 0xA7, np * sizeof(rg2_patch)); /* garbage where the rebuild writes */
    const rg2_patch *before = s.patch;
    CHECK_OK(rg2_surface_rebuild(&m, &s, &err), &err);
    CHECK(s.patch == before && same_surface(&s, &fresh), "rebuild over garbage = fresh build (in place %d)",
          s.patch == before);
    CHECK_OK(rg2_surface_copy(&fresh, &copy, &err), &err);
    CHECK(same_surface(&copy, &fresh), "copy of the big surface = the surface");
    rg2_surface_free(&copy);
    rg2_surface_free(&s);
    rg2_surface_free(&fresh);
    rg2_mesh_free(&m2);
    rg2_mesh_free(&m);
    printf("big surface: %zu patches (%.1f MB) on 2 MiB-aligned memory, every byte written by the build\n", np,
           np * sizeof(rg2_patch) * 1e-6);
}

/* Torus from circle products: exact point, normal and curvatures against the implicit
 * geometry (K = cos v / (r (R + r cos v)), H from the principal curvatures 1/r and
 * cos v / (R + r cos v), with cos v = (rho - R) / r read off the point). All errors are
 * relative, so the torus is measured at several sizes: curvatures scale like 1 / size, and at
 * size 20 the principal curvatures are 0.07 and -0.03 .. 0.02 (H^2 - K < 1e-2, where a
 * fixed threshold on the discriminant would merge k1 and k2); at 2^-60 the derivatives are
 * ~1e-18 (a fixed absolute floor in the normal's test would leave the normal undefined). */
static void torus_curvatures(double scale)
{
    const double R = 2.5 * scale, rr = 0.75 * scale;
    double au[7], av[5], cu[14], cv[10];
    rg2t_rng rng;
    rg2t_seed(&rng, 5);
    double su = 0, sv = 0;
    for (int i = 0; i < 7; i++) su += (au[i] = rg2t_uniform(&rng, 0.5, 1.0));
    for (int i = 0; i < 5; i++) sv += (av[i] = rg2t_uniform(&rng, 0.5, 1.0));
    for (int i = 0; i < 7; i++) au[i] *= 2 * M_PI / su;
    for (int i = 0; i < 5; i++) av[i] *= 2 * M_PI / sv;
    rg2_mesh m;
    rg2_error err;
    CHECK_OK(rg2_mesh_init(&m, 7, 5, 1, 1, &err), &err);
    rg2_scalars_free(&m.su);
    rg2_scalars_free(&m.sv);
    CHECK_OK(rg2_scalars_from_angles(&m.su, au, 7, 1, &err), &err);
    CHECK_OK(rg2_scalars_from_angles(&m.sv, av, 5, 1, &err), &err);
    CHECK_OK(rg2_circle_coeffs(au, 7, 1, 0.3, cu, &err), &err);
    CHECK_OK(rg2_circle_coeffs(av, 5, 1, -1.0, cv, &err), &err);
    for (int i = 0; i < 7; i++)
        for (int j = 0; j < 5; j++) {
            double *p = rg2_mesh_at(&m, i, j);
            p[0] = (R + rr * cv[2 * j]) * cu[2 * i];
            p[1] = (R + rr * cv[2 * j]) * cu[2 * i + 1];
            p[2] = rr * cv[2 * j + 1];
            p[3] = 1;
        }
    rg2_surface s;
    CHECK_OK(rg2_surface_build(&m, &s, &err), &err);
    double wpos = 0, wn = 0, wK = 0, wH = 0, wk = 0;
    for (int i = 0; i < s.nu; i++)
        for (int j = 0; j < s.nv; j++)
            for (int a = 0; a <= 10; a++)
                for (int b = 0; b <= 10; b++) {
                    rg2_eval e;
                    rg2_patch_eval(rg2_surface_patch(&s, i, j), a / 10.0, b / 10.0, 2, &e);
                    double rho = hypot(e.p[0], e.p[1]);
                    double cosv = (rho - R) / rr, sinv = e.p[2] / rr;
                    wpos = fmax(wpos, fabs(hypot(rho - R, e.p[2]) - rr) / R);
                    /* outward normal of the tube */
                    double no[3] = {cosv * e.p[0] / rho, cosv * e.p[1] / rho, sinv};
                    double sgn = e.n[0] * no[0] + e.n[1] * no[1] + e.n[2] * no[2] > 0 ? 1.0 : -1.0;
                    wn = fmax(wn, hypot(hypot(e.n[0] - sgn * no[0], e.n[1] - sgn * no[1]), e.n[2] - sgn * no[2]));
                    double k_a = -sgn / rr, k_b = -sgn * cosv / (R + rr * cosv);
                    double K = k_a * k_b, H = 0.5 * (k_a + k_b);
                    wK = fmax(wK, fabs(e.K - K) / (1 / (rr * rr)));
                    wH = fmax(wH, fabs(e.H - H) / (1 / rr));
                    double k1 = fmax(k_a, k_b), k2 = fmin(k_a, k_b);
                    wk = fmax(wk, fmax(fabs(e.k1 - k1), fabs(e.k2 - k2)) * rr);
                    CHECK(e.flags == 0, "torus x %g: flags %u at patch (%d,%d)", scale, e.flags, i, j);
                }
    CHECK(wpos <= 1e-14, "torus x %g: position %.3g", scale, wpos);
    CHECK(wn <= 1e-13, "torus x %g: normal %.3g", scale, wn);
    CHECK(wK <= 1e-12 && wH <= 1e-12 && wk <= 1e-12, "torus x %g: curvature K %.3g H %.3g k1/k2 %.3g", scale, wK,
          wH, wk);
    printf("torus x %g (random arcs): position %.2e, normal %.2e, K %.2e, H %.2e, k1/k2 %.2e (relative)\n", scale,
           wpos, wn, wK, wH, wk);
    rg2_surface_free(&s);
    rg2_mesh_free(&m);
}

/* A sphere band of radius rs (latitudes -90 .. 30 degrees): every point is umbilic, so
 * k1 = k2 = H = -+1 / rs (sign from the normal's orientation) and K = 1 / rs^2, the
 * discriminant H^2 - K being rounding noise of either sign; k1 - k2 is then sqrt(noise) ~ 1e-8
 * of the curvature at most. At the pole (the band's first row of patches starts there) the
 * normal is undefined and flagged so. */
static void sphere_umbilics(void)
{
    static const double radii[] = {1.0, 1e3};
    for (int q = 0; q < 2; q++) {
        const double rs = radii[q];
        rg2_mesh m;
        rg2_surface s;
        rg2_error err;
        CHECK_OK(scene_revolve(0.0, rs, 6, 4, 0, -M_PI / 3, M_PI / 6, &m, &s, &err), &err);
        double wpos = 0, wk = 0, wH = 0, wK = 0;
        int flagged = 0;
        for (int i = 0; i < s.nu; i++)
            for (int j = 0; j < s.nv; j++)
                for (int a = 0; a <= 8; a++)
                    for (int b = 0; b <= 8; b++) {
                        rg2_eval e;
                        rg2_patch_eval(rg2_surface_patch(&s, i, j), a / 8.0, b / 8.0, 2, &e);
                        double d = sqrt(e.p[0] * e.p[0] + e.p[1] * e.p[1] + e.p[2] * e.p[2]);
                        wpos = fmax(wpos, fabs(d - rs) / rs);
                        if (hypot(e.p[0], e.p[1]) <= 1e-12 * rs) { /* the band's pole: no normal */
                            flagged += !(e.flags & RG2_EVAL_NORMAL_UNDEFINED);
                            continue;
                        }
                        double sgn = e.n[0] * e.p[0] + e.n[1] * e.p[1] + e.n[2] * e.p[2] > 0 ? 1.0 : -1.0;
                        double k = -sgn / rs;
                        wk = fmax(wk, fmax(fabs(e.k1 - k), fabs(e.k2 - k)) * rs);
                        wH = fmax(wH, fabs(e.H - k) * rs);
                        wK = fmax(wK, fabs(e.K - k * k) * rs * rs);
                        flagged += e.flags != 0;
                    }
        printf("sphere band r = %g: position %.2e, k1/k2 %.2e, H %.2e, K %.2e (relative), %d samples misflagged\n", rs,
               wpos, wk, wH, wK, flagged);
        CHECK(flagged == 0 && wpos <= 1e-14 && wH <= 1e-11 && wK <= 1e-11,
              "sphere band r = %g: %d misflagged, position %.3g, H %.3g, K %.3g", rs, flagged, wpos, wH, wK);
        CHECK(wk <= 1e-6, "sphere band r = %g: umbilic k1, k2 off 1/r by %.3g (relative)", rs, wk);
        rg2_surface_free(&s);
        rg2_mesh_free(&m);
    }
}

/* A collapsed edge (all u = 0 control points equal) flags the normal as undefined there,
 * and derivatives agree with central differences of positions elsewhere. */
static void degenerate_and_derivatives(void)
{
    rg2_patch P;
    rg2t_rng r;
    rg2t_seed(&r, 11);
    for (int a = 0; a < 4; a++)
        for (int b = 0; b < 4; b++) {
            double W = rg2t_uniform(&r, 0.7, 1.3);
            for (int k = 0; k < 3; k++)
                P.h[a][b][k] = W * (a == 0 ? (k == 2 ? 1.0 : 0.0) : rg2t_uniform(&r, -1, 1));
            P.h[a][b][3] = W;
        }
    rg2_eval e;
    rg2_patch_eval(&P, 0.0, 0.4, 2, &e);
    CHECK(e.flags & RG2_EVAL_NORMAL_UNDEFINED, "collapsed edge flagged: %u", e.flags);
    CHECK(e.K == 0 && e.H == 0, "no curvature where the normal is undefined");
    double h = 1e-5, worst = 0;
    for (int q = 0; q < 20; q++) {
        double u = rg2t_uniform(&r, 0.2, 0.8), v = rg2t_uniform(&r, 0.2, 0.8);
        rg2_eval c, pu, mu, pv, mv;
        rg2_patch_eval(&P, u, v, 2, &c);
        rg2_patch_eval(&P, u + h, v, 1, &pu);
        rg2_patch_eval(&P, u - h, v, 1, &mu);
        rg2_patch_eval(&P, u, v + h, 1, &pv);
        rg2_patch_eval(&P, u, v - h, 1, &mv);
        for (int k = 0; k < 3; k++) {
            worst = fmax(worst, fabs((pu.p[k] - mu.p[k]) / (2 * h) - c.su[k]));
            worst = fmax(worst, fabs((pv.p[k] - mv.p[k]) / (2 * h) - c.sv[k]));
            worst = fmax(worst, fabs((pu.su[k] - mu.su[k]) / (2 * h) - c.suu[k]));
            worst = fmax(worst, fabs((pv.sv[k] - mv.sv[k]) / (2 * h) - c.svv[k]));
            worst = fmax(worst, fabs((pv.su[k] - mv.su[k]) / (2 * h) - c.suv[k]));
        }
    }
    CHECK(worst <= 1e-6, "derivatives vs central differences: %.3g", worst);
}

/* A random rational bi-cubic patch over the unit grid: control point (a, b) moved by up to 0.3 in
 * x and y, height in [-zmax, zmax], weight in [0.5, 2]; with collapse, its u = 0 side is the point
 * (0.5, 0.5, 0) (the same draws, in the same order, either way but for the collapsed x and y). */
static void random_bumpy_patch(rg2t_rng *r, rg2_patch *P, double zmax, int collapse)
{
    for (int a = 0; a < 4; a++)
        for (int b = 0; b < 4; b++) {
            int c = collapse && a == 0;
            double W = rg2t_uniform(r, 0.5, 2.0);
            P->h[a][b][0] = W * (c ? 0.5 : a + rg2t_uniform(r, -0.3, 0.3));
            P->h[a][b][1] = W * (c ? 0.5 : b + rg2t_uniform(r, -0.3, 0.3));
            P->h[a][b][2] = W * rg2t_uniform(r, -zmax, zmax) * (c ? 0 : 1);
            P->h[a][b][3] = W;
        }
}

/* rg2_eval_normal_curvature(e, a, c): the normal curvature along the tangent a su + c sv, against
 * the curve t -> S(u + a t, v + c t) through the point, differentiated here by central
 * differences of positions: S'' . n / |S'|^2. Random patches (weights 0.5 .. 2) and directions
 * with both a and c nonzero, where the mixed term 2 a c suv counts, and tangents far from unit
 * length. */
static void normal_curvature_directions(void)
{
    rg2t_rng r;
    rg2t_seed(&r, 23);
    double worst = 0, big = 0;
    for (int trial = 0; trial < 8; trial++) {
        rg2_patch P;
        random_bumpy_patch(&r, &P, 1.5, 0);
        for (int q = 0; q < 10; q++) {
            double u = rg2t_uniform(&r, 0.2, 0.8), v = rg2t_uniform(&r, 0.2, 0.8);
            double a = rg2t_uniform(&r, 0.3, 2.0) * (q & 1 ? -1 : 1), c = rg2t_uniform(&r, 0.3, 2.0);
            const double h = 1e-4;
            rg2_eval e, ep, em;
            rg2_patch_eval(&P, u, v, 2, &e);
            rg2_patch_eval(&P, u + a * h, v + c * h, 0, &ep);
            rg2_patch_eval(&P, u - a * h, v - c * h, 0, &em);
            double d1[3], d2[3];
            for (int k = 0; k < 3; k++) {
                d1[k] = (ep.p[k] - em.p[k]) / (2 * h);
                d2[k] = (ep.p[k] - 2 * e.p[k] + em.p[k]) / (h * h);
            }
            double own = (d2[0] * e.n[0] + d2[1] * e.n[1] + d2[2] * e.n[2]) / (d1[0] * d1[0] + d1[1] * d1[1] + d1[2] * d1[2]);
            double got = rg2_eval_normal_curvature(&e, a, c);
            worst = fmax(worst, fabs(got - own) / fmax(1.0, fabs(own)));
            big = fmax(big, fabs(own));
            CHECK(e.flags == 0, "normal curvature: patch %d flags %u", trial, e.flags);
        }
    }
    CHECK(worst <= 1e-5 && big > 0.1, "normal curvature along a su + c sv vs central differences: %.3g (largest %.3g)",
          worst, big);
    printf("rg2_eval_normal_curvature: %.2e from central differences along 80 directions (curvatures up to %.2f)\n",
           worst, big);
}

/* A patch far from the origin for its size: su = (Hu - Wu p) / W cancels, and its rounding
 * grows with |p|. The normal is flagged undefined when a derivative is at the level of its
 * rounding (rg2__normal_test's ru, rv: the sums |Hu_k| + |Wu p_k|); where it is not flagged, it
 * must be the normal of the same patch at the origin. The patch (size 1, weights 0.5 .. 2 varying
 * along u only) moved by 10^k along (1, 1, 1), k = 0 .. 17: how many normals were left defined
 * and how far the worst of them turned. */
static void far_from_origin(void)
{
    rg2t_rng r;
    rg2t_seed(&r, 31);
    rg2_patch P0, P;
    double wrow[4];
    for (int a = 0; a < 4; a++)
        wrow[a] = rg2t_uniform(&r, 0.5, 2.0);
    for (int a = 0; a < 4; a++)
        for (int b = 0; b < 4; b++) {
            double W = wrow[a]; /* along u only: sv has no such cancellation, su alone is noise far out */
            P0.h[a][b][0] = W * (a / 3.0 + rg2t_uniform(&r, -0.1, 0.1));
            P0.h[a][b][1] = W * (b / 3.0 + rg2t_uniform(&r, -0.1, 0.1));
            P0.h[a][b][2] = W * rg2t_uniform(&r, -0.5, 0.5);
            P0.h[a][b][3] = W;
        }
    double worst = 0;
    int wrong = 0, defined_near = 0, undefined_far = 0;
    for (int k = 0; k <= 17; k++) {
        double T = pow(10.0, k);
        P = P0;
        for (int a = 0; a < 4; a++)
            for (int b = 0; b < 4; b++)
                for (int d = 0; d < 3; d++)
                    P.h[a][b][d] += P0.h[a][b][3] * T;
        for (int q = 0; q < 25; q++) {
            double u = (q % 5 + 0.5) / 5, v = (q / 5 + 0.5) / 5;
            rg2_eval e0, e;
            rg2_patch_eval(&P0, u, v, 1, &e0);
            rg2_patch_eval(&P, u, v, 1, &e);
            if (e.flags & RG2_EVAL_NORMAL_UNDEFINED) {
                undefined_far += k == 17;
                continue;
            }
            double c = e.n[0] * e0.n[0] + e.n[1] * e0.n[1] + e.n[2] * e0.n[2];
            double ang = acos(fmin(1.0, c));
            defined_near += k == 0;
            worst = fmax(worst, ang);
            wrong += !(ang <= 0.05);
        }
    }
    CHECK(wrong == 0 && defined_near == 25 && undefined_far == 25,
          "a patch moved far from the origin: %d defined normals more than 0.05 off (worst %.3g rad), %d of 25 "
          "defined at the origin, %d of 25 undefined at 1e17",
          wrong, worst, defined_near, undefined_far);
    printf("a patch moved up to 1e17 from the origin: defined normals within %.2e rad of the origin's\n", worst);
}

/* A rational patch is its homogeneous control points up to a common factor: all of them times
 * 2^k (exact) is the same surface, and evaluates to the same bits (position, derivatives,
 * normal, curvatures and flags), k = -40 .. 40 by 10, on random patches (weights 0.5 .. 2) and on
 * one with a collapsed u = 0 side, at its pole too. */
static void projective_scaling(void)
{
    rg2t_rng r;
    rg2t_seed(&r, 37);
    int same = 0, asked = 0, undefined = 0;
    for (int trial = 0; trial < 4; trial++) {
        rg2_patch P, Q;
        random_bumpy_patch(&r, &P, 1.0, trial == 3);
        for (int k = -40; k <= 40; k += 10)
            for (int q = 0; q < 16; q++) {
                double u = q < 4 ? 0.0 : (q % 4 + 0.5) / 4, v = (q / 4 + 0.5) / 4;
                for (int a = 0; a < 4; a++)
                    for (int b = 0; b < 4; b++)
                        for (int d = 0; d < 4; d++)
                            Q.h[a][b][d] = ldexp(P.h[a][b][d], k);
                rg2_eval e, f;
                rg2_patch_eval(&P, u, v, 2, &e);
                rg2_patch_eval(&Q, u, v, 2, &f);
                same += !memcmp(&e, &f, sizeof e);
                undefined += k == 0 && (e.flags & RG2_EVAL_NORMAL_UNDEFINED) != 0;
                asked++;
            }
    }
    CHECK(same == asked && undefined == 4, "homogeneous points times 2^k: %d of %d evaluations the same bits, %d of 4 "
          "on the pole undefined", same, asked, undefined);
}

/* The mesh built on both construction paths: s[0], st[0], e[0] by the default path (AVX-512
 * where the CPU has it), s[1], st[1], e[1] by the portable one. */
static void build_both(const rg2_mesh *m, rg2_surface s[2], rg2_status st[2], rg2_error e[2])
{
    for (int q = 0; q < 2; q++) {
        rg2__surface_portable = q;
        st[q] = rg2_surface_build(m, &s[q], &e[q]);
    }
    rg2__surface_portable = 0;
}

/* build_both that must succeed on both paths: whether the two surfaces hold the same bits. */
static int same_on_both_paths(const rg2_mesh *m, rg2_surface s[2])
{
    rg2_error e[2];
    rg2_status st[2];
    build_both(m, s, st, e);
    for (int q = 0; q < 2; q++)
        CHECK(st[q] == RG2_OK, "%s path: %s", q ? "portable" : "default", e[q].msg);
    size_t np = (size_t)s[0].nu * (size_t)s[0].nv;
    return s[0].patch && s[1].patch && s[1].nu * s[1].nv == (int)np &&
           !memcmp(s[0].patch, s[1].patch, np * sizeof(rg2_patch));
}

/* The construction's two paths (AVX-512 per patch, portable per row; surface.c) give the same
 * bits, the same errors and the same overflowing patch, over open and closed random meshes
 * with weights that need normalizing (1e-40, 1e40), signed zeros, and weights that overflow. */
static void construction_paths(void)
{
    rg2t_rng r;
    rg2t_seed(&r, 2026);
    int compared = 0, overflows = 0;
    for (int t = 0; t < 160; t++) {
        int nu = 4 + (int)rg2t_uniform(&r, 0, 9), nv = 4 + (int)rg2t_uniform(&r, 0, 9);
        rg2_mesh m;
        rg2_error err;
        CHECK_OK(rg2_mesh_init(&m, nu, nv, t % 2, t / 2 % 2, &err), &err);
        random_scalars(&r, &m.su);
        random_scalars(&r, &m.sv);
        double scale = t % 7 == 3 ? 1e-40 : t % 7 == 5 ? 1e40 : 1.0;
        for (int i = 0; i < nu; i++)
            for (int j = 0; j < nv; j++) {
                double *p = rg2_mesh_at(&m, i, j), W = rg2t_uniform(&r, 0.3, 3.0) * scale;
                double x = t % 5 == 1 && j == 2 ? -0.0 : rg2t_uniform(&r, -5, 5);
                if (t % 19 == 7) /* weights at the top of the double range: the construction overflows */
                    W = 1.79e308, x = 0.5;
                p[0] = W * x, p[1] = W * rg2t_uniform(&r, -5, 5), p[2] = W * (t % 13 ? rg2t_uniform(&r, -5, 5) : 0.0);
                p[3] = W;
            }
        rg2_surface s[2] = {{0}, {0}};
        rg2_error e[2];
        rg2_status st[2];
        build_both(&m, s, st, e);
        CHECK(st[0] == st[1] && (st[0] == RG2_OK || !strcmp(e[0].msg, e[1].msg)),
              "mesh %d: statuses %d / %d (%s / %s)", t, st[0], st[1], st[0] ? e[0].msg : "", st[1] ? e[1].msg : "");
        overflows += st[0] == RG2_ENONFINITE;
        if (!st[0] && !st[1]) {
            size_t np = (size_t)s[0].nu * (size_t)s[0].nv;
            CHECK(s[0].nu == s[1].nu && s[0].nv == s[1].nv && !memcmp(s[0].patch, s[1].patch, np * sizeof(rg2_patch)),
                  "mesh %d (%d x %d, closed %d %d): the two construction paths differ", t, nu, nv, t % 2, t / 2 % 2);
            compared++;
        }
        rg2_surface_free(&s[0]);
        rg2_surface_free(&s[1]);
        rg2_mesh_free(&m);
    }
    /* two surfaces past 16 MB of patches, which the AVX-512 path writes with streaming stores */
    for (int t = 0; t < 2; t++) {
        int n = 200 - 8 * t;
        rg2_mesh m;
        rg2_error err;
        CHECK_OK(rg2_mesh_init(&m, n, n, t, t, &err), &err);
        for (int i = 0; i < n; i++)
            for (int j = 0; j < n; j++) {
                double *p = rg2_mesh_at(&m, i, j), W = rg2t_uniform(&r, 0.7, 1.4);
                p[0] = W * i, p[1] = W * j, p[2] = W * rg2t_uniform(&r, -1, 1), p[3] = W;
            }
        rg2_surface s[2] = {{0}, {0}};
        int same = same_on_both_paths(&m, s);
        size_t np = (size_t)s[0].nu * (size_t)s[0].nv;
        CHECK(same && np * sizeof(rg2_patch) > ((size_t)16 << 20),
              "large mesh %d x %d: the two construction paths differ", n, n);
        compared++;
        rg2_surface_free(&s[0]);
        rg2_surface_free(&s[1]);
        rg2_mesh_free(&m);
    }
    CHECK(compared >= 142 && overflows >= 6, "compared %d surfaces, %d overflows", compared, overflows);
    int avx512 = 0; /* (as surface.c decides) */
#if defined(__GNUC__) && defined(__x86_64__) && !defined(RG2_NO_CLONES)
    avx512 = __builtin_cpu_supports("avx512f");
#endif
    printf("construction paths: %d surfaces bitwise equal, %d overflows reported alike (AVX-512 path %s)\n",
           compared, overflows, avx512 ? "on this CPU" : "not in this build or CPU: the portable path twice");
}

/* The ends of the two paths' shared rules (surface.c: normalize_weights and the AVX-512 range and
 * finiteness tests). With unit scalars and one mesh weight W every patch's largest weight is W
 * (to rounding): kept if W lies in [2^-32, 2^32] (both ends included, exactly W), else scaled by a
 * power of two into [1, 2), on both paths alike; W at both ends of the range, one ulp and a half
 * binade past them, and up to DBL_MAX (weights above 1.79e308 were left as they were). Coordinates near the top of the double range with weights of 1: the inner control
 * points (times omega omega' = 1.96) overflow while every weight stays in range; the build must
 * refuse that (ENONFINITE naming patch (0, 0), surface left empty) on both paths, not return
 * patches holding inf. */
static void construction_edges(void)
{
    rg2_error err;
    int kept = 0, patches = 0;
    const double Ws[] = {0x1p-32, 0x1p32, 0x1.fffffffffffffp-33, 0x1.0000000000001p32, 0x1.8p-33, 0x1.8p32,
                         1.795e308, DBL_MAX};
    for (int t = 0; t < 16; t++) {
        int closed = t & 1, inside = Ws[t / 2] >= 0x1p-32 && Ws[t / 2] <= 0x1p32;
        double W = Ws[t / 2];
        rg2_mesh m;
        CHECK_OK(rg2_mesh_init(&m, 7, 6, closed, closed, &err), &err);
        for (int i = 0; i < 7; i++)
            for (int j = 0; j < 6; j++) {
                double *p = rg2_mesh_at(&m, i, j);
                p[0] = W * (i / 8.0), p[1] = W * (j / 8.0), p[2] = W * ((i * j) % 3 / 8.0), p[3] = W;
            }
        rg2_surface s[2] = {{0}, {0}};
        CHECK(same_on_both_paths(&m, s), "weights %a (closed %d): the two construction paths differ", W, closed);
        size_t np = (size_t)s[0].nu * (size_t)s[0].nv;
        for (size_t k = 0; s[0].patch && k < np; k++) {
            double big = 0;
            for (int r = 0; r < 4; r++)
                for (int c = 0; c < 4; c++)
                    big = fmax(big, s[0].patch[k].h[r][c][3]);
            kept += inside ? big == W : big >= 1 && big < 2;
            patches++;
        }
        rg2_surface_free(&s[0]);
        rg2_surface_free(&s[1]);
        rg2_mesh_free(&m);
    }
    CHECK(patches > 0 && kept == patches, "largest weights kept in [2^-32, 2^32], else scaled into [1, 2): %d of %d patches",
          kept, patches);
    for (int closed = 0; closed < 2; closed++) {
        rg2_mesh m;
        CHECK_OK(rg2_mesh_init(&m, 6, 6, closed, closed, &err), &err);
        for (int k = 0; k < 7 - closed; k++) {
            if (k < rg2_scalars_num_w(&m.su))
                m.su.w[k] = 1.4;
            if (k < rg2_scalars_num_w(&m.sv))
                m.sv.w[k] = 1.4;
        }
        for (int i = 0; i < 6; i++)
            for (int j = 0; j < 6; j++) {
                double *p = rg2_mesh_at(&m, i, j);
                p[0] = 1.7e308, p[1] = j, p[2] = i, p[3] = 1.0;
            }
        rg2_surface s[2] = {{0}, {0}};
        rg2_error e[2];
        rg2_status st[2];
        build_both(&m, s, st, e);
        for (int q = 0; q < 2; q++)
            CHECK(st[q] == RG2_ENONFINITE && strstr(e[q].msg, "patch (0, 0) overflows") && !s[q].patch &&
                      s[q].nu == 0,
                  "closed %d, %s path: coordinates 1.7e308 times 1.96 must overflow: %s '%s'", closed,
                  q ? "portable" : "default", rg2_status_str(st[q]), st[q] ? e[q].msg : "");
        rg2_surface_free(&s[0]);
        rg2_surface_free(&s[1]);
        rg2_mesh_free(&m);
    }
}

/* rg2__surface_normalize_weights (a capped design's surfaces, design.c) on a surface of mixed
 * degrees, and on the bi-3 surface it was made from (where bi-3 patches follow each other: in the
 * mixed one each is followed by one of higher degree), whose homogeneous values were all scaled
 * by c: a patch whose largest weight lies outside [2^-32, 2^32] is scaled as a whole, every
 * control value of it (bi-3 or of higher degree) by the same power of two, into a largest weight
 * in [1, 2); one inside is left as it is. */
static void normalize_mixed(void)
{
    rg2t_rng r;
    rg2t_seed(&r, 3232);
    rg2_error err;
    rg2_mesh m;
    random_mesh(&r, 8, 9, 0, 1, &m);
    rg2_surface s;
    CHECK_OK(rg2_surface_build(&m, &s, &err), &err);
    const double cs[] = {0x1p40, 0x1p-40, 0x1p10, 0x1p200};
    int whole = 0, ranged = 0, patches = 0;
    for (int q = 0; q < 8; q++) {
        if (q == 4)
            CHECK_OK(xmix_elevate(&s, &err), &err);
        double c = cs[q % 4], M[16] = {c, 0, 0, 0, 0, c, 0, 0, 0, 0, c, 0, 0, 0, 0, c};
        rg2_surface t;
        CHECK_OK(rg2_surface_copy(&s, &t, &err), &err);
        rg2_surface_transform(&t, M);
        rg2__surface_normalize_weights(&t);
        for (int i = 0; i < s.nu; i++)
            for (int j = 0; j < s.nv; j++) {
                rg2_xpatch X, Y;
                rg2_surface_patch_get(&s, i, j, &X);
                rg2_surface_patch_get(&t, i, j, &Y);
                double big = 0;
                for (int a = 0; a <= X.du; a++)
                    for (int b = 0; b <= X.dv; b++)
                        big = fmax(big, c * X.h[a][b][3]);
                int e2;
                frexp(big, &e2); /* big in [2^(e2-1), 2^e2) */
                double f = big >= 0x1p-32 && big <= 0x1p32 ? c : ldexp(c, 1 - e2);
                int same = X.du == Y.du && X.dv == Y.dv;
                double ybig = 0;
                for (int a = 0; a <= X.du; a++)
                    for (int b = 0; b <= X.dv; b++)
                        for (int k = 0; k < 4; k++) {
                            same &= Y.h[a][b][k] == f * X.h[a][b][k];
                            ybig = k == 3 ? fmax(ybig, Y.h[a][b][3]) : ybig;
                        }
                whole += same;
                ranged += ybig >= 0x1p-32 && ybig <= 0x1p32 && (f == c || (ybig >= 1 && ybig < 2));
                patches++;
            }
        rg2_surface_free(&t);
    }
    CHECK(xmix_count(&s) > 0 && whole == patches && ranged == patches,
          "normalized weights (%d higher-degree patches): %d of %d patches scaled whole, %d of them in range",
          xmix_count(&s), whole, patches, ranged);
    rg2_surface_free(&s);
    rg2_mesh_free(&m);
}

/* rg2_surface_transform: the homogeneous values and derivatives of every patch (bi-3 and, after
 * xmix_elevate, higher degree) become M times the old ones; a bi-3 surface transformed equals the
 * construction of the transformed mesh; a rigid motion keeps K and H and turns the normal. */
static void transform(void)
{
    rg2t_rng r;
    rg2t_seed(&r, 4242);
    rg2_error err;
    double worst_h = 0, worst_build = 0, worst_kh = 0, worst_n = 0;
    int box_same = 0, boxed = 0, box_pts = 0;
    int xpatches = 0;
    for (int trial = 0; trial < 8; trial++) {
        int cu = trial & 1, cv = (trial >> 1) & 1, projective = trial & 4;
        int nu = rg2t_int(&r, cu ? 3 : 5, 9), nv = rg2t_int(&r, cv ? 3 : 5, 9);
        rg2_mesh m, mt;
        random_mesh(&r, nu, nv, cu, cv, &m);
        double M[16], T[16], R[16];
        rg2_xform_rotate(R, rg2t_uniform(&r, -1, 1), rg2t_uniform(&r, -1, 1), 1, rg2t_uniform(&r, -3, 3));
        rg2_xform_translate(T, rg2t_uniform(&r, -5, 5), rg2t_uniform(&r, -5, 5), rg2t_uniform(&r, -5, 5));
        rg2_xform_mul(T, R, M);
        if (projective) /* w' = w + 0.1 x - 0.05 y + 0.08 z stays > 0.6 W (1 - 0.23) */
            M[12] = 0.1, M[13] = -0.05, M[14] = 0.08;
        CHECK_OK(rg2_mesh_copy(&m, &mt, &err), &err);
        rg2_mesh_transform(&mt, M);
        rg2_surface s, st, sb;
        CHECK_OK(rg2_surface_build(&m, &s, &err), &err);
        CHECK_OK(rg2_surface_build(&mt, &sb, &err), &err);
        CHECK_OK(rg2_surface_copy(&s, &st, &err), &err);
        rg2_surface_transform(&st, M);
        size_t np = (size_t)s.nu * (size_t)s.nv;
        double big = 0, diff = 0;
        for (size_t k = 0; k < np; k++)
            for (int a = 0; a < 4; a++)
                for (int b = 0; b < 4; b++)
                    for (int q = 0; q < 4; q++) {
                        big = fmax(big, fabs(sb.patch[k].h[a][b][q]));
                        diff = fmax(diff, fabs(st.patch[k].h[a][b][q] - sb.patch[k].h[a][b][q]));
                    }
        worst_build = fmax(worst_build, diff / big);
        if (trial & 2) { /* higher-degree patches: transformed through their own control points */
            rg2_surface_free(&st);
            CHECK_OK(xmix_elevate(&s, &err), &err);
            CHECK_OK(rg2_surface_copy(&s, &st, &err), &err);
            rg2_surface_transform(&st, M);
            xpatches += xmix_count(&st);
        }
        for (int i = 0; i < s.nu; i++)
            for (int j = 0; j < s.nv; j++) {
                rg2_xpatch X; /* errors relative to the transformed patch's largest control value */
                rg2_surface_patch_get(&st, i, j, &X);
                double cp = 0;
                for (int a = 0; a <= X.du; a++)
                    for (int b = 0; b <= X.dv; b++)
                        for (int q = 0; q < 4; q++)
                            cp = fmax(cp, fabs(X.h[a][b][q]));
                for (int t = 0; t < 4; t++) {
                    double u = rg2t_uniform(&r, 0, 1), v = rg2t_uniform(&r, 0, 1), a[6][4], b[6][4];
                    rg2_surface_eval_h(&s, i, j, u, v, a);
                    rg2_surface_eval_h(&st, i, j, u, v, b);
                    for (int d = 0; d < 6; d++) {
                        for (int q = 0; q < 4; q++) {
                            double want = M[4 * q] * a[d][0] + M[4 * q + 1] * a[d][1] + M[4 * q + 2] * a[d][2] +
                                          M[4 * q + 3] * a[d][3];
                            worst_h = fmax(worst_h, fabs(b[d][q] - want) / cp);
                        }
                    }
                    if (projective)
                        continue;
                    rg2_eval e0, e1;
                    rg2_surface_eval(&s, i, j, u, v, 2, &e0);
                    rg2_surface_eval(&st, i, j, u, v, 2, &e1);
                    if (!isfinite(e0.K) || !isfinite(e0.H) || fabs(e0.K) > 1e6 || fabs(e0.H) > 1e3)
                        continue; /* near a degenerate point of the random surface */
                    worst_kh = fmax(worst_kh, fabs(e1.K - e0.K) / fmax(1, fabs(e0.K)));
                    worst_kh = fmax(worst_kh, fabs(e1.H - e0.H) / fmax(1, fabs(e0.H)));
                    for (int q = 0; q < 3; q++)
                        worst_n = fmax(worst_n, fabs(e1.n[q] - (R[4 * q] * e0.n[0] + R[4 * q + 1] * e0.n[1] +
                                                               R[4 * q + 2] * e0.n[2])));
                }
            }
        /* rg2_surface_box: the box of the positive-weight control points, found independently;
         * the surface inside it where every weight is positive */
        double lo[3], hi[3], wlo[3] = {HUGE_VAL, HUGE_VAL, HUGE_VAL}, whi[3] = {-HUGE_VAL, -HUGE_VAL, -HUGE_VAL};
        double wmin = HUGE_VAL; /* rg2_surface_min_weight: the least weight of the patches' own control points */
        CHECK(rg2_surface_box(&st, lo, hi), "trial %d: the box has points", trial);
        for (int i = 0; i < st.nu; i++)
            for (int j = 0; j < st.nv; j++) {
                rg2_xpatch X;
                rg2_surface_patch_get(&st, i, j, &X);
                for (int a = 0; a <= X.du; a++)
                    for (int b = 0; b <= X.dv; b++) {
                        wmin = fmin(wmin, X.h[a][b][3]);
                        for (int q = 0; q < 3 && X.h[a][b][3] > 0; q++)
                            wlo[q] = fmin(wlo[q], X.h[a][b][q] / X.h[a][b][3]),
                            whi[q] = fmax(whi[q], X.h[a][b][q] / X.h[a][b][3]);
                    }
                for (int t = 0; t < 4 && rg2_surface_min_weight(&st) > 0; t++) {
                    rg2_eval e;
                    rg2_surface_eval(&st, i, j, rg2t_uniform(&r, 0, 1), rg2t_uniform(&r, 0, 1), 0, &e);
                    for (int q = 0; q < 3; q++)
                        boxed += e.p[q] >= lo[q] - 1e-12 * (hi[q] - lo[q]) && e.p[q] <= hi[q] + 1e-12 * (hi[q] - lo[q]),
                            box_pts++;
                }
            }
        for (int q = 0; q < 3; q++)
            box_same += lo[q] == wlo[q] && hi[q] == whi[q];
        CHECK(rg2_surface_min_weight(&st) == wmin, "trial %d (%d higher-degree patches): least weight %.17g, the "
              "control points' own %.17g", trial, xmix_count(&st), rg2_surface_min_weight(&st), wmin);
        rg2_surface_free(&s);
        rg2_surface_free(&st);
        rg2_surface_free(&sb);
        rg2_mesh_free(&m);
        rg2_mesh_free(&mt);
    }
    printf("transform: 8 surfaces (4 projective maps, %d higher-degree patches): homogeneous values and "
           "derivatives %.2e (of the largest control value), against the transformed mesh's construction %.2e; rigid: K, H %.2e, normal %.2e\n",
           xpatches, worst_h, worst_build, worst_kh, worst_n);
    printf("surface box: %d of 24 sides equal to the control points' own, %d of %d surface points inside\n",
           box_same, boxed, box_pts);
    CHECK(box_same == 24 && box_pts > 0 && boxed == box_pts, "rg2_surface_box: %d of 24 sides, %d of %d points inside",
          box_same, boxed, box_pts);
    CHECK(xpatches > 0, "the transformed surfaces hold %d higher-degree patches", xpatches);
    CHECK(worst_h <= 1e-13, "transformed patches: M times the homogeneous values and derivatives to %.3g of the "
          "largest control value", worst_h);
    CHECK(worst_build <= 1e-14, "transformed surface = construction of the transformed mesh to %.3g", worst_build);
    CHECK(worst_kh <= 1e-9 && worst_n <= 1e-10, "rigid motion: K, H kept to %.3g, normal turned to %.3g", worst_kh,
          worst_n);
}

/* rg2.h conventions: a call that fails leaves its output struct zeroed, whatever it held (here
 * garbage bytes), also when it fails after allocating (a non-finite vertex in the
 * tessellation, a cap fit that is rank-deficient). */
static int all_zero(const void *p, size_t n)
{
    const unsigned char *c = p;
    for (size_t k = 0; k < n; k++)
        if (c[k])
            return 0;
    return 1;
}

#define FAILS_ZEROED(obj, call)                                                                \
    do {                                                                                       \
        memset(&(obj), 0xAB, sizeof(obj));                                                     \
        rg2_status st_ = (call);                                                               \
        CHECK(st_ != RG2_OK && all_zero(&(obj), sizeof(obj)), "%s: status %s, output %s", #call, \
              rg2_status_str(st_), all_zero(&(obj), sizeof(obj)) ? "zeroed" : "NOT zeroed");   \
    } while (0)

static void outputs_zeroed_on_failure(void)
{
    rg2_error err;
    rg2_shape t;
    rg2_shape_init(&t, RG2_SHAPE_TORUS);
    t.param[0] = 3, t.param[1] = 1;
    double a[8];
    for (int k = 0; k < 8; k++)
        a[k] = M_PI / 4;
    rg2_partition p = {RG2_PART_ANGLES, 1, 8, a, 0.0};
    rg2_mesh m, bad, mo;
    rg2_surface s, sn, so;
    memset(&m, 0, sizeof m), memset(&bad, 0, sizeof bad), memset(&s, 0, sizeof s), memset(&sn, 0, sizeof sn);
    CHECK_OK(rg2_shape_mesh(&t, &p, &p, &m, &err), &err);
    CHECK_OK(rg2_surface_build(&m, &s, &err), &err);
    CHECK_OK(rg2_mesh_copy(&m, &bad, &err), &err);
    rg2_mesh_at(&bad, 1, 1)[0] = NAN;
    CHECK_OK(rg2_surface_copy(&s, &sn, &err), &err);
    sn.patch[40].h[2][2][1] = NAN;

    FAILS_ZEROED(so, rg2_surface_build(&bad, &so, &err));
    t.param[1] = 5; /* r > R */
    FAILS_ZEROED(so, rg2_shape_surface(&t, &p, &p, &so, NULL, &err));
    FAILS_ZEROED(mo, rg2_shape_mesh(&t, &p, &p, &mo, &err));
    t.param[1] = 1;
    FAILS_ZEROED(mo, rg2_mesh_transpose(&bad, &mo, &err));
    FAILS_ZEROED(mo, rg2_mesh_init(&mo, 2, 2, 0, 0, &err));
    double ab[8];
    memcpy(ab, a, sizeof ab);
    ab[3] = 4; /* an arc past pi */
    rg2_scalars sc;
    FAILS_ZEROED(sc, rg2_scalars_from_angles(&sc, ab, 8, 1, &err));
    rg2_curve c;
    double pts[3 * 5] = {0};
    FAILS_ZEROED(c, rg2_curve_build(0, pts, &m.su, &c, &err));
    rg2_tess tt;
    FAILS_ZEROED(tt, rg2_tessellate(&sn, 4, 1, &tt, &err));
    rg2_check_opts o;
    rg2_check_opts_default(&o);
    o.seam_samples = 0;
    rg2_check_report rep;
    FAILS_ZEROED(rep, rg2_check(&s, 1, NULL, NULL, 0, &o, &rep, &err));
    rg2_render_opts ro;
    rg2_render_opts_default(&ro);
    ro.width = ro.height = 32;
    rg2_image im;
    FAILS_ZEROED(im, rg2_render(&sn, 1, NULL, &ro, &im, &err));
    rg2_crossing_report cr;
    FAILS_ZEROED(cr, rg2_find_crossings(&sn, 1, 2, 1, &cr, &err));
    rg2_shape sp;
    rg2_shape_init(&sp, RG2_SHAPE_SPHERE);
    double v[4] = {0.2, 0.4, 0.6, 0.8}, vbad[4] = {0.2, 0.1, 0.6, 0.8};
    rg2_mesh pm;
    memset(&pm, 0, sizeof pm);
    CHECK_OK(rg2_polar_mesh(&sp, &p, v, 4, &pm, &err), &err);
    FAILS_ZEROED(mo, rg2_polar_mesh(&sp, &p, vbad, 4, &mo, &err));
    rg2_cap_opts co;
    rg2_cap_opts_default(&co);
    co.jet_weight[0] = 0; /* rank-deficient fit, after the body is built */
    FAILS_ZEROED(so, rg2_cap_build(&pm, &co, &so, NULL, &err));
    rg2_design *d;
    FAILS_ZEROED(d, rg2_design_parse("{", 1, NULL, &d, &err));
    rg2_mesh_free(&pm);
    rg2_mesh_free(&m);
    rg2_mesh_free(&bad);
    rg2_surface_free(&s);
    rg2_surface_free(&sn);
}

int main(void)
{
    construction_paths();
    construction_edges();
    normalize_mixed();
    copy_edge_cases();
    torus_curvatures(1.0);
    torus_curvatures(20.0);
    torus_curvatures(0x1p-60);
    torus_curvatures(0x1p-300); /* |Su| |Sv| ~ 1e-180, past the double range of the formulas unless scaled (rg2__scale_pair) */
    torus_curvatures(0x1p300); /* and ~ 1e180 */
    sphere_umbilics();
    degenerate_and_derivatives();
    normal_curvature_directions();
    far_from_origin();
    projective_scaling();
    random_surfaces();
    broken_is_detected();
    transpose_symmetry();
    mesh_errors();
    rebuild();
    support();
    outputs_zeroed_on_failure();
    big_surface();
    transform();
    return rg2t_done("test_surface");
}
