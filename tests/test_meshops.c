/* test_meshops.c -- the mesh operations of the C API (rg2_mesh_cut, _transpose, _reverse,
 * _merge, _morph): each equals, bit for bit, what a design file makes of the same meshes; the
 * merged surface is measured on its own (G2 gaps at every seam, the patches on the torus and on
 * the sphere against their implicit equations); bad input gets an error naming it and leaves
 * the output empty. */
#include "expect_err.h"
#include "harness.h"

#include <limits.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* Fig. 8 / Fig. 13 (examples/torus_sphere.json, fig13_morph.json) with every step an output. */
static const char *design_json =
    "{\"format\": \"rg2 design 1\","
    " \"shapes\": {\"ring\": {\"kind\": \"torus\", \"R\": 3, \"r\": 0.6},"
    "  \"ball\": {\"kind\": \"sphere\", \"radius\": 1.3, \"matrix\": [0.5, 0, 0.8660254037844386, 1.5,"
    "   -0.8660254037844386, 0, 0.5, -2.598076211353316, 0, 1, 0, 0, 0, 0, 0, 1]}},"
    " \"meshes\": {"
    "  \"ring_mesh\": {\"shape\": \"ring\", \"u\": {\"arcs\": [30, 30, 30, 30, 30, 30, 30, 30,"
    "   17.142857142857142, 17.142857142857142, 17.142857142857142, 17.142857142857142,"
    "   17.142857142857142, 17.142857142857142, 17.142857142857146]}, \"v\": {\"arcs\": 8}},"
    "  \"tube\": {\"cut\": \"ring_mesh\", \"u\": [0, 8]},"
    "  \"wrap\": {\"cut\": \"ring_mesh\", \"u\": [11, 19], \"v\": [2, 7]},"
    "  \"opened\": {\"cut\": \"ring_mesh\", \"v\": {\"open_at\": 3}},"
    "  \"ball_mesh\": {\"shape\": \"ball\", \"u\": {\"arcs\": 8}, \"v\": {\"knots\": [0.35, 0.45, 0.55, 0.65]}},"
    "  \"ball_band\": {\"transpose\": \"ball_mesh\"},"
    "  \"joined\": {\"merge\": [\"tube\", \"ball_band\"], \"along\": \"u\", \"closed\": true},"
    "  \"joined_plain\": {\"merge\": [\"tube\", \"ball_band\"], \"along\": \"u\", \"closed\": true, \"seam\": \"plain\"},"
    "  \"row\": {\"merge\": [\"tube\", \"ball_band\", \"tube\"], \"along\": \"u\"},"
    "  \"halfway\": {\"morph\": [\"joined\", \"ring_mesh\"], \"t\": 0.5},"
    "  \"backwards\": {\"reverse\": \"joined\", \"dir\": \"v\"},"
    "  \"backwards_u\": {\"reverse\": \"row\", \"dir\": \"u\"}"
    " },"
    " \"output\": [\"ring_mesh\", \"tube\", \"wrap\", \"opened\", \"ball_mesh\", \"ball_band\", \"joined\","
    "  \"joined_plain\", \"row\", \"halfway\", \"backwards\", \"backwards_u\"]}";

enum { RING, TUBE, WRAP, OPENED, BALL, BAND, JOINED, JOINED_PLAIN, ROW, HALFWAY, BACK, BACK_U, N_OUT };

static int scalars_same(const rg2_scalars *a, const rg2_scalars *b)
{
    return a->n == b->n && a->closed == b->closed &&
           !memcmp(a->w, b->w, (size_t)rg2_scalars_num_w(a) * sizeof(double)) &&
           !memcmp(a->b, b->b, (size_t)a->n * sizeof(double)) && !memcmp(a->g, b->g, (size_t)a->n * sizeof(double));
}

/* Bit for bit: counts, closedness, 4-tuples, scalars. */
static void same_mesh(const rg2_mesh *got, const rg2_mesh *want, const char *what)
{
    int ok = got->p && got->nu == want->nu && got->nv == want->nv && scalars_same(&got->su, &want->su) &&
             scalars_same(&got->sv, &want->sv) &&
             !memcmp(got->p, want->p, (size_t)want->nu * (size_t)want->nv * 4 * sizeof(double));
    CHECK(ok, "%s: the C API's mesh (%d x %d) differs from the design file's (%d x %d)", what, got->nu, got->nv,
          want->nu, want->nv);
}

/* Patches of s whose 9 x 9 samples all lie on shape sh (|F| / |grad F| <= tol * size). */
static int patches_on(const rg2_surface *s, const rg2_shape *sh, double size, double tol)
{
    int count = 0;
    for (int i = 0; i < s->nu; i++)
        for (int j = 0; j < s->nv; j++) {
            double worst = 0.0;
            for (int a = 0; a <= 8; a++)
                for (int b = 0; b <= 8; b++) {
                    rg2_eval e;
                    double g[3];
                    rg2_surface_eval(s, i, j, a / 8.0, b / 8.0, 0, &e);
                    double f = rg2_shape_implicit(sh, e.p, g);
                    worst = fmax(worst, fabs(f) / sqrt(g[0] * g[0] + g[1] * g[1] + g[2] * g[2]));
                }
            count += worst <= tol * size;
        }
    return count;
}

/* The surface of m: G2 at every seam (measured), and how many patches lie on each shape. */
static void measure(const rg2_mesh *m, const rg2_shape *ring, const rg2_shape *ball, int want_ring,
                    int want_ball, int want_patches, const char *what)
{
    rg2_error err;
    rg2_surface s;
    rg2_status st = rg2_surface_build(m, &s, &err);
    CHECK(st == RG2_OK, "%s: build: %s", what, err.msg);
    if (st)
        return;
    double size = rg2t_surface_scale(&s);
    rg2t_seams g;
    rg2t_surface_seams(&s, 9, &g);
    int on_ring = patches_on(&s, ring, size, 1e-14), on_ball = patches_on(&s, ball, size, 1e-14);
    printf("%s: %d x %d patches, %d on the torus, %d on the sphere; %d seams: position %.2e, normal angle %.2e, "
           "curvature %.2e\n",
           what, s.nu, s.nv, on_ring, on_ball, g.seams, g.pos, g.angle, g.curv);
    CHECK(s.nu * s.nv == want_patches, "%s: %d patches, want %d", what, s.nu * s.nv, want_patches);
    CHECK(on_ring == want_ring && on_ball == want_ball, "%s: %d patches on the torus (want %d), %d on the sphere "
          "(want %d)", what, on_ring, want_ring, on_ball, want_ball);
    CHECK(g.pos < 1e-14 && g.angle < 1e-12 && g.curv < 1e-9,
          "%s: seam gaps position %.3g, angle %.3g, curvature %.3g (worst at %s)", what, g.pos, g.angle, g.curv,
          g.where);
    rg2_surface_free(&s);
}

static void results_match(const rg2_mesh *M, const rg2_shape *ring, const rg2_shape *ball)
{
    rg2_error err;
    rg2_mesh r;
    const int keep[2] = {-1, -1};

    /* cut: a range, a wrapping range in both directions, a closed direction opened */
    int f1[2] = {0, -1}, l1[2] = {8, 0};
    CHECK_OK(rg2_mesh_cut(&M[RING], f1, l1, &r, &err), &err);
    same_mesh(&r, &M[TUBE], "cut u [0, 8]");
    rg2_mesh_free(&r);
    int f2[2] = {11, 2}, l2[2] = {19, 7};
    CHECK_OK(rg2_mesh_cut(&M[RING], f2, l2, &r, &err), &err);
    same_mesh(&r, &M[WRAP], "cut u [11, 19] (wrapping) v [2, 7]");
    rg2_mesh_free(&r);
    int f3[2] = {-1, 3}, l3[2] = {0, 3 + 8 - 1};
    CHECK_OK(rg2_mesh_cut(&M[RING], f3, l3, &r, &err), &err);
    same_mesh(&r, &M[OPENED], "cut v open at 3");
    rg2_mesh_free(&r);
    CHECK_OK(rg2_mesh_cut(&M[RING], keep, keep, &r, &err), &err);
    same_mesh(&r, &M[RING], "cut keeping both directions");
    rg2_mesh_free(&r);

    /* transpose; twice is the mesh itself */
    rg2_mesh t2;
    CHECK_OK(rg2_mesh_transpose(&M[BALL], &r, &err), &err);
    same_mesh(&r, &M[BAND], "transpose");
    CHECK_OK(rg2_mesh_transpose(&r, &t2, &err), &err);
    same_mesh(&t2, &M[BALL], "transpose twice");
    rg2_mesh_free(&r);
    rg2_mesh_free(&t2);

    /* merge: closed ring of two, both seam rules; an open row of three */
    const rg2_mesh *two[2] = {&M[TUBE], &M[BAND]};
    rg2_mesh joined;
    CHECK_OK(rg2_mesh_merge(two, 2, 0, 1, RG2_SEAM_PRESERVE, &joined, &err), &err);
    same_mesh(&joined, &M[JOINED], "merge (preserve)");
    measure(&joined, ring, ball, 48, 24, 120, "merge closed (preserve)");
    CHECK_OK(rg2_mesh_merge(two, 2, 0, 1, RG2_SEAM_PLAIN, &r, &err), &err);
    same_mesh(&r, &M[JOINED_PLAIN], "merge (plain)");
    rg2_mesh_free(&r);
    const rg2_mesh *three[3] = {&M[TUBE], &M[BAND], &M[TUBE]};
    rg2_mesh row;
    CHECK_OK(rg2_mesh_merge(three, 3, 0, 0, RG2_SEAM_PRESERVE, &row, &err), &err);
    same_mesh(&row, &M[ROW], "merge of three (open)");
    /* 9 + 6 + 9 points open in u: 21 patch columns; 6 + 6 on the torus, 3 on the sphere; 8 rows */
    measure(&row, ring, ball, (6 + 6) * 8, 3 * 8, 21 * 8, "merge of three, open");

    /* morph and reverse */
    CHECK_OK(rg2_mesh_morph(&joined, &M[RING], 0.5, &r, &err), &err);
    same_mesh(&r, &M[HALFWAY], "morph t = 0.5");
    rg2_mesh_free(&r);
    CHECK_OK(rg2_mesh_morph(&joined, &M[RING], 1.0, &r, &err), &err);
    same_mesh(&r, &M[RING], "morph t = 1");
    rg2_mesh_free(&r);
    CHECK_OK(rg2_mesh_reverse(&joined, 1, &r, &err), &err);
    same_mesh(&r, &M[BACK], "reverse v");
    measure(&r, ring, ball, 48, 24, 120, "reverse v");
    rg2_mesh_free(&r);
    CHECK_OK(rg2_mesh_reverse(&row, 0, &r, &err), &err);
    same_mesh(&r, &M[BACK_U], "reverse u");
    rg2_mesh_free(&r);

    /* roll: the ring (closed in both directions) started 3 points further in u and 2 in v; each
     * point, junction's b, g and leg weight is the one that many steps on, and rolling back
     * restores the mesh bit for bit; an open direction is refused */
    for (int dir = 0; dir < 2; dir++) {
        const rg2_mesh *a = &M[RING];
        int k = dir ? 2 : 3, n = dir ? a->nv : a->nu, moved = 1;
        rg2_mesh back;
        CHECK_OK(rg2_mesh_roll(a, dir, k, &r, &err), &err);
        for (int i = 0; r.p && i < a->nu; i++)
            for (int j = 0; j < a->nv; j++)
                moved &= !memcmp(rg2_mesh_at(&r, i, j),
                                 rg2_mesh_at(a, dir ? i : (i + k) % n, dir ? (j + k) % n : j), 4 * sizeof(double));
        const rg2_scalars *sa = dir ? &a->sv : &a->su, *sr = dir ? &r.sv : &r.su;
        for (int j = 0; r.p && j < n; j++)
            moved &= sr->b[j] == sa->b[(j + k) % n] && sr->g[j] == sa->g[(j + k) % n] &&
                     sr->w[j] == sa->w[(j + k) % n];
        CHECK(moved, "roll %s by %d: points and scalars %d steps on", dir ? "v" : "u", k, k);
        CHECK_OK(rg2_mesh_roll(&r, dir, -k + 5 * n, &back, &err), &err); /* (-k modulo n) */
        same_mesh(&back, a, dir ? "roll v back" : "roll u back");
        rg2_mesh_free(&back);
        rg2_mesh_free(&r);
    }

    /* one mesh closed on itself: the tube's 9 points become a closed ring of 9 patch columns,
     * G2 across the new seam; the 3 columns straddling it are transitions */
    const rg2_mesh *one[1] = {&M[TUBE]};
    CHECK_OK(rg2_mesh_merge(one, 1, 0, 1, RG2_SEAM_PRESERVE, &r, &err), &err);
    CHECK(r.su.closed && r.nu == 9, "merge of one, closed: %d points, closed %d", r.nu, r.su.closed);
    measure(&r, ring, ball, 6 * 8, 0, 9 * 8, "tube closed on itself");
    rg2_mesh_free(&r);

    rg2_mesh_free(&joined);
    rg2_mesh_free(&row);
}

/* The status and message; and *out left empty. */
static void bad(rg2_status got, rg2_status want, const rg2_error *err, const rg2_mesh *out, const char *needle,
                const char *what)
{
    expect_err(got, want, err, needle, what);
    CHECK(!out || (out->p == NULL && out->nu == 0 && out->su.w == NULL), "%s: the output is not empty", what);
}

/* A big nu x nv mesh of distinct points (i, j, 0) with weight 1 and uniform scalars. */
static rg2_status grid_mesh(rg2_mesh *m, int nu, int nv, int closed_u, int closed_v, rg2_error *err)
{
    rg2_status st = rg2_mesh_init(m, nu, nv, closed_u, closed_v, err);
    for (int i = 0; !st && i < nu; i++)
        for (int j = 0; j < nv; j++) {
            double *p = rg2_mesh_at(m, i, j);
            p[0] = i;
            p[1] = j;
            p[3] = 1.0;
        }
    return st;
}

static int finite_k(double x) { return x - x == 0.0; }

/* A preserve seam's left stencil quantity B = 2 b^2 ((w + b w_p) / w) / K, in ratios so that
 * b near 1e150 and K near 1e300 do not overflow it. */
static double stencil_B(double b, double wp, double w, double K) { return 2.0 * b * (b / K) * ((w + b * wp) / w); }
/* Its right quantity A = K w / (w_n + b w) (w the end weight or w_s, K the junction's). */
static double stencil_A(double b, double wn, double w, double K) { return (K / (wn + b * w)) * w; }

static void errors(const rg2_mesh *M)
{
    rg2_error err;
    rg2_mesh r, t;
    int f[2] = {0, -1}, l[2] = {8, 0};

    const rg2_mesh *closed_first[2] = {&M[RING], &M[BAND]};
    memset(&r, 0xab, sizeof r); /* (bad() requires it emptied) */
    bad(rg2_mesh_merge(closed_first, 2, 0, 0, RG2_SEAM_PRESERVE, &r, &err), RG2_EINCOMPATIBLE, &err, &r,
        "rg2_mesh_merge.merge[0]: mesh 'in[0]' is closed in u", "merge of a closed mesh");
    const rg2_mesh *unlike[2] = {&M[TUBE], &M[WRAP]};
    memset(&r, 0xab, sizeof r); /* (bad() requires it emptied) */
    bad(rg2_mesh_merge(unlike, 2, 0, 0, RG2_SEAM_PRESERVE, &r, &err), RG2_EINCOMPATIBLE, &err, &r,
        "rg2_mesh_merge.merge[1]: meshes 'in[0]' and 'in[1]' do not agree in v (the direction that must match "
        "when merging along u): 8 control points, closed, vs 6, open", "merge of unlike meshes");
    memset(&r, 0xab, sizeof r); /* (bad() requires it emptied) */
    bad(rg2_mesh_roll(&M[TUBE], 0, 1, &r, &err), RG2_EINCOMPATIBLE, &err, &r,
        "rg2_mesh_roll: mesh 'in' is open in u; roll turns a closed direction", "roll of an open direction");
    memset(&r, 0xab, sizeof r); /* (bad() requires it emptied) */
    bad(rg2_mesh_roll(&M[TUBE], 2, 1, &r, &err), RG2_EINVAL, &err, &r, "rg2_mesh_roll: dir = 2", "roll dir 2");
    const rg2_mesh *two[2] = {&M[TUBE], &M[BAND]};
    memset(&r, 0xab, sizeof r); /* (bad() requires it emptied) */
    bad(rg2_mesh_merge(two, 2, 2, 0, RG2_SEAM_PRESERVE, &r, &err), RG2_EINVAL, &err, &r, "dir = 2", "merge dir 2");
    memset(&r, 0xab, sizeof r); /* (bad() requires it emptied) */
    bad(rg2_mesh_merge(two, 2, 0, 0, (rg2_seam_rule)7, &r, &err), RG2_EINVAL, &err, &r, "rule = 7", "merge rule 7");
    /* the output is emptied by every failure, the first checks' too (rg2_mesh_free of it is safe) */
    memset(&r, 0xab, sizeof r);
    memset(&r, 0xab, sizeof r); /* (bad() requires it emptied) */
    bad(rg2_mesh_merge(two, 0, 0, 0, RG2_SEAM_PRESERVE, &r, &err), RG2_EINVAL, &err, &r, "no meshes", "merge of 0");
    memset(&r, 0xab, sizeof r);
    memset(&r, 0xab, sizeof r); /* (bad() requires it emptied) */
    bad(rg2_mesh_merge(NULL, 2, 0, 0, RG2_SEAM_PRESERVE, &r, &err), RG2_EINVAL, &err, &r, "in is NULL",
        "merge of NULL");
    for (int k = 0; k < 5; k++) {
        memset(&r, 0xab, sizeof r);
        rg2_status st = RG2_OK;
        int fk[2] = {0, 0}, lk[2] = {2, 2};
        switch (k) {
        case 0: st = rg2_mesh_cut(&M[TUBE], fk, lk, &r, &err); break;
        case 1: st = rg2_mesh_transpose(NULL, &r, &err); break;
        case 2: st = rg2_mesh_reverse(&M[TUBE], 5, &r, &err); break;
        case 3: st = rg2_mesh_merge(two, 2, 1, 0, RG2_SEAM_PRESERVE, &r, &err); break;
        default: st = rg2_mesh_morph(&M[TUBE], &M[RING], -1.0, &r, &err); break;
        }
        CHECK(st != RG2_OK && r.p == NULL && r.nu == 0 && r.su.w == NULL && r.sv.b == NULL,
              "operation %d: failed (%s) but left the output unemptied", k, rg2_status_str(st));
        rg2_mesh_free(&r);
    }
    memset(&r, 0xab, sizeof r); /* (bad() requires it emptied) */
    bad(rg2_mesh_merge(two, 2, 0, 0, RG2_SEAM_PRESERVE, NULL, &err), RG2_EINVAL, &err, NULL, "out is NULL",
        "merge into NULL");
    const rg2_mesh *with_null[2] = {&M[TUBE], NULL};
    memset(&r, 0xab, sizeof r); /* (bad() requires it emptied) */
    bad(rg2_mesh_merge(with_null, 2, 0, 0, RG2_SEAM_PRESERVE, &r, &err), RG2_EINVAL, &err, &r,
        "rg2_mesh_merge: in[1] is NULL", "merge with a NULL mesh");

    /* the count limit at its edge, before any input is read: RG2_MAX_POINTS + 1 meshes refused by
     * it, naming n; RG2_MAX_POINTS pass it and reach the next check (dir 2). One mesh repeated:
     * the pointer array (32 MB) is all that is allocated. */
    const rg2_mesh **many = malloc(((size_t)RG2_MAX_POINTS + 1) * sizeof *many);
    CHECK(many != NULL, "merge limit: out of memory for the input array");
    if (many) {
        for (size_t q = 0; q <= (size_t)RG2_MAX_POINTS; q++)
            many[q] = &M[TUBE];
        char want[96];
        snprintf(want, sizeof want, "rg2_mesh_merge: n = %d meshes, more than the limit of %d points",
                 RG2_MAX_POINTS + 1, RG2_MAX_POINTS);
        memset(&r, 0xab, sizeof r); /* (bad() requires it emptied) */
        bad(rg2_mesh_merge(many, RG2_MAX_POINTS + 1, 2, 0, RG2_SEAM_PRESERVE, &r, &err), RG2_ELIMIT, &err, &r, want,
            "merge of RG2_MAX_POINTS + 1 meshes");
        memset(&r, 0xab, sizeof r); /* (bad() requires it emptied) */
        bad(rg2_mesh_merge(many, RG2_MAX_POINTS, 2, 0, RG2_SEAM_PRESERVE, &r, &err), RG2_EINVAL, &err, &r,
            "rg2_mesh_merge: dir = 2", "merge of RG2_MAX_POINTS meshes (past the limit check)");
        free(many);
    }

    /* out aliasing an input is refused before anything is touched */
    rg2_mesh c;
    CHECK_OK(rg2_mesh_copy(&M[TUBE], &c, &err), &err);
    const rg2_mesh *self[2] = {&c, &M[BAND]};
    expect_err(rg2_mesh_merge(self, 2, 0, 0, RG2_SEAM_PRESERVE, &c, &err), RG2_EINVAL, &err, "out is also an input",
               "merge into an input");
    same_mesh(&c, &M[TUBE], "an input refused as the output");
    /* the copies likewise: each filled its output from scratch, which zeroed the source first:
     * rg2_mesh_copy(&c, &c) left c empty (its arrays leaked) with the message "mesh u: scalars: 0
     * control points, ...", rg2_scalars_copy and rg2_surface_copy returned RG2_OK with uniform
     * scalars and all-zero patches */
    expect_err(rg2_mesh_copy(&c, &c, &err), RG2_EINVAL, &err, "destination is the source", "mesh copied onto itself");
    same_mesh(&c, &M[TUBE], "a mesh refused as its own copy");
    if (!c.p) /* (zeroed: made again for the checks below) */
        CHECK_OK(rg2_mesh_copy(&M[TUBE], &c, &err), &err);
    rg2_scalars sc;
    CHECK_OK(rg2_scalars_copy(&c.su, &sc, &err), &err);
    expect_err(rg2_scalars_copy(&sc, &sc, &err), RG2_EINVAL, &err, "destination is the source",
               "scalars copied onto themselves");
    CHECK(sc.w && c.su.w && scalars_same(&sc, &c.su), "scalars refused as their own copy changed");
    rg2_scalars_free(&sc);
    rg2_surface sf, sf0;
    CHECK_OK(rg2_surface_build(&c, &sf, &err), &err);
    CHECK_OK(rg2_surface_copy(&sf, &sf0, &err), &err);
    expect_err(rg2_surface_copy(&sf, &sf, &err), RG2_EINVAL, &err, "destination is the source",
               "surface copied onto itself");
    CHECK(sf.nu == sf0.nu && sf.nv == sf0.nv && sf.patch && sf0.patch &&
              !memcmp(sf.patch, sf0.patch, (size_t)sf0.nu * (size_t)sf0.nv * sizeof(rg2_patch)),
          "a surface refused as its own copy changed (%d x %d patches)", sf.nu, sf.nv);
    /* a source that is no surface: the output zeroed, as every failed call leaves it */
    rg2_surface bogus = {0};
    bogus.nu = -1;
    rg2_surface_free(&sf);
    memset(&sf, 0xab, sizeof sf); /* (garbage: the failed call must not read it) */
    expect_err(rg2_surface_copy(&bogus, &sf, &err), RG2_EINVAL, &err, "not a surface", "copy of a bogus surface");
    CHECK(sf.patch == NULL && sf.nu == 0 && sf.bu == NULL, "a failed surface copy left its output %d x %d", sf.nu, sf.nv);
    /* a NULL source: refused, the output zeroed; a NULL destination: refused */
    memset(&sf, 0xab, sizeof sf);
    expect_err(rg2_surface_copy(NULL, &sf, &err), RG2_EINVAL, &err, "NULL source", "copy of a NULL surface");
    CHECK(sf.patch == NULL && sf.nu == 0, "a copy of a NULL surface left its output %d x %d", sf.nu, sf.nv);
    expect_err(rg2_surface_copy(&sf0, NULL, &err), RG2_EINVAL, &err, "NULL destination", "surface copied to NULL");
    rg2_surface_free(&sf0);

    /* a bad input mesh: its check's message, prefixed with the function and the input */
    rg2_mesh_at(&c, 2, 3)[1] = NAN;
    const rg2_mesh *nan_in[2] = {&M[TUBE], &c};
    memset(&r, 0xab, sizeof r); /* (bad() requires it emptied) */
    bad(rg2_mesh_merge(nan_in, 2, 0, 0, RG2_SEAM_PRESERVE, &r, &err), RG2_ENONFINITE, &err, &r,
        "rg2_mesh_merge: in[1]: mesh: control point [2][3] component 1 is not finite", "merge of a NaN mesh");
    memset(&r, 0xab, sizeof r); /* (bad() requires it emptied) */
    bad(rg2_mesh_transpose(&c, &r, &err), RG2_ENONFINITE, &err, &r, "rg2_mesh_transpose: in: mesh: control point",
        "transpose of a NaN mesh");
    rg2_mesh_free(&c);
    CHECK_OK(rg2_mesh_copy(&M[TUBE], &c, &err), &err);
    c.su.b[4] = -1.0;
    memset(&r, 0xab, sizeof r); /* (bad() requires it emptied) */
    bad(rg2_mesh_reverse(&c, 0, &r, &err), RG2_EWEIGHT, &err, &r, "rg2_mesh_reverse: in: mesh u", "reverse b < 0");
    rg2_mesh_free(&c);

    /* scalars that leave the double range: named, as the input's junction */
    CHECK_OK(rg2_mesh_copy(&M[TUBE], &c, &err), &err);
    c.sv.b[2] = 1e-310;
    memset(&r, 0xab, sizeof r); /* (bad() requires it emptied) */
    bad(rg2_mesh_reverse(&c, 1, &r, &err), RG2_EDOMAIN, &err, &r,
        "rg2_mesh_reverse: v junction 2 (b = 1e-310, g = 0.304481869954853) cannot be reversed: b' = 1 / b is not a "
        "finite number", "reverse b = 1e-310");
    /* each of b', g' alone out of range names itself: b = 1e-310, g = 0 (b' = 1e310, g' = 0); b = 1e-110,
     * g = 1e300 (b' = 1e110, g' = 1e630); b = 5.6e-309, g = 0.3 (b' = 1.8e308, g' = 1.7e924) */
    static const struct {
        double b, g;
        const char *needle;
    } one_out[] = {
        {1e-310, 0.0, "rg2_mesh_reverse: v junction 2 (b = 1e-310, g = 0) cannot be reversed: b' = 1 / b is not a "
                      "finite number"},
        {1e-110, 1e300, "rg2_mesh_reverse: v junction 2 (b = 1e-110, g = 1e+300) cannot be reversed: g' = g / b^3 is "
                        "not a finite number"},
        /* (1 / b = 1.8e308 is finite, though b' = 1.01 / b would not be) */
        {5.6e-309, 0.3, "rg2_mesh_reverse: v junction 2 (b = 5.6e-309, g = 0.3) cannot be reversed: g' = g / b^3 is "
                        "not a finite number"},
    };
    for (size_t k = 0; k < sizeof one_out / sizeof one_out[0]; k++) {
        c.sv.b[2] = one_out[k].b;
        c.sv.g[2] = one_out[k].g;
        memset(&r, 0xab, sizeof r); /* (bad() requires it emptied) */
        bad(rg2_mesh_reverse(&c, 1, &r, &err), RG2_EDOMAIN, &err, &r, one_out[k].needle, "reverse, b' or g' alone");
    }
    c.sv.b[2] = 1e-160; /* b' = 1e160 and g' = 0 are finite, K' = K / b^3 is not */
    c.sv.g[2] = 0.0;
    memset(&r, 0xab, sizeof r);
    bad(rg2_mesh_reverse(&c, 1, &r, &err), RG2_EDOMAIN, &err, &r,
        "rg2_mesh_reverse: v junction 2 (b = 1e-160, g = 0) cannot be reversed: K' = K / b^3 is not "
        "a finite number", "reverse b = 1e-160");
    c.sv.b[2] = 1e110; /* b^3 = inf: g' = g / b / b / b = 1e-30, not g / inf = 0 */
    c.sv.g[2] = 1e300;
    CHECK_OK(rg2_mesh_reverse(&c, 1, &r, &err), &err);
    CHECK(r.p && fabs(r.sv.g[5] / 1e-30 - 1.0) < 1e-14, "reverse b = 1e110, g = 1e300: g' = %g, want 1e-30",
          r.p ? r.sv.g[5] : 0.0);
    rg2_mesh_free(&r);
    /* b = 1e-110 reverses (b' = 1e110, g' = g / b^3 = 0 / 1e-330): b^3 underflows, g' may not */
    c.sv.b[2] = 1e-110;
    c.sv.g[2] = 0.0;
    CHECK_OK(rg2_mesh_reverse(&c, 1, &r, &err), &err);
    CHECK(r.p && r.sv.b[8 - 1 - 2] == 1.0 / 1e-110 && r.sv.g[8 - 1 - 2] == 0.0,
          "reverse b = 1e-110: b' = %g, g' = %g", r.p ? r.sv.b[5] : 0.0, r.p ? r.sv.g[5] : 0.0);
    rg2_mesh_free(&r);
    c.sv.g[2] = 1e-300; /* g' = 1e30, though b^3 = 0 */
    CHECK_OK(rg2_mesh_reverse(&c, 1, &r, &err), &err);
    CHECK(r.p && fabs(r.sv.g[5] / 1e30 - 1.0) < 1e-14, "reverse b = 1e-110, g = 1e-300: g' = %g, want 1e30",
          r.p ? r.sv.g[5] : 0.0);
    rg2_mesh_free(&r);
    rg2_mesh_free(&c);

    /* an input whose K leaves the double range is refused by the input check */
    CHECK_OK(rg2_mesh_copy(&M[TUBE], &c, &err), &err);
    c.su.w[c.su.n] = 1e308;
    const rg2_mesh *huge[2] = {&c, &M[BAND]};
    memset(&r, 0xab, sizeof r); /* (bad() requires it emptied) */
    bad(rg2_mesh_merge(huge, 2, 0, 0, RG2_SEAM_PRESERVE, &r, &err), RG2_ENONFINITE, &err, &r,
        "rg2_mesh_merge: in[0]: mesh u: junction 8 has K = inf (from w[7] = 0.977284, w[8] = 1e+308, b = 0.575855, "
        "g = 0.0354623); K must be a finite number > 0 (the scalars leave the double range)", "input K = inf");
    rg2_mesh_free(&c);

    /* seams (u junctions 8 and 9 of tube + band): */
    const int jl = 8, jr = 9;
    CHECK_OK(rg2_mesh_copy(&M[TUBE], &c, &err), &err);
    CHECK_OK(rg2_mesh_copy(&M[BAND], &t, &err), &err);
    const rg2_mesh *pair[2] = {&c, &t};
    /* preserve with end weights 1e300 and 2e300: the re-solved K = 6e300 is finite (its
     * intermediate product overflowed, 'K = -nan'), and the left part's stencil quantity
     * B = 2 b^2 ((w_j + b w_{j-1}) / w_j) / K_j stays the part's own */
    c.su.w[c.su.n] = 1e300;
    t.su.w[0] = 2e300;
    CHECK_OK(rg2_mesh_merge(pair, 2, 0, 0, RG2_SEAM_PRESERVE, &r, &err), &err);
    if (r.p) {
        double b = c.su.b[jl], wp = rg2_scalars_leg_w(&c.su, jl - 1);
        double Bpart = stencil_B(b, wp, 1e300, rg2_scalars_K(&c.su, jl));
        double ws = rg2_scalars_leg_w(&r.su, jl), Bmerged = stencil_B(b, wp, ws, rg2_scalars_K(&r.su, jl));
        CHECK(ws == 1.5e300 && finite_k(rg2_scalars_K(&r.su, jl)) && finite_k(rg2_scalars_K(&r.su, jr)) &&
                  fabs(Bmerged / Bpart - 1.0) < 1e-14,
              "preserve at end weights 1e300, 2e300: w_s = %g, K = %g, %g, B %g vs %g", ws, rg2_scalars_K(&r.su, jl),
              rg2_scalars_K(&r.su, jr), Bmerged, Bpart);
    }
    rg2_mesh_free(&r);
    /* preserve with b = 5.3e102 at the left end and end weights 1 and 3: K (w_s + b w_p) = 1.8 b^3
     * overflows, K ((w_s + b w_p) / w_s) = 0.9 b^3 does not; b w_p outweighs w_s, and B keeps the part's
     * own value only if b w_p is weighed right */
    c.su.w[c.su.n] = 1.0;
    t.su.w[0] = 3.0;
    c.su.b[jl] = 5.3e102;
    c.su.g[jl] = 0.0;
    CHECK_OK(rg2_mesh_check(&c, &err), &err);
    CHECK_OK(rg2_mesh_merge(pair, 2, 0, 0, RG2_SEAM_PRESERVE, &r, &err), &err);
    if (r.p) {
        double b = 5.3e102, wp = rg2_scalars_leg_w(&c.su, jl - 1);
        double Bpart = stencil_B(b, wp, 1.0, rg2_scalars_K(&c.su, jl)), Bmerged = stencil_B(b, wp, 2.0, rg2_scalars_K(&r.su, jl));
        CHECK(fabs(Bmerged / Bpart - 1.0) < 1e-13, "preserve with b = 5.3e102: B %.17g vs %.17g", Bmerged, Bpart);
    }
    rg2_mesh_free(&r);
    /* b = 1e150 (K = 1.9e300): K ((w_s + b w_p) / w_s) overflows too, the product of the ratios does not */
    c.su.b[jl] = 1e150;
    CHECK_OK(rg2_mesh_check(&c, &err), &err);
    CHECK_OK(rg2_mesh_merge(pair, 2, 0, 0, RG2_SEAM_PRESERVE, &r, &err), &err);
    if (r.p) {
        double wp = rg2_scalars_leg_w(&c.su, jl - 1);
        double Bpart = stencil_B(1e150, wp, 1.0, rg2_scalars_K(&c.su, jl)),
               Bmerged = stencil_B(1e150, wp, 2.0, rg2_scalars_K(&r.su, jl));
        CHECK(fabs(Bmerged / Bpart - 1.0) < 1e-13, "preserve with b = 1e150: B %.17g vs %.17g", Bmerged, Bpart);
    }
    rg2_mesh_free(&r);
    /* the right end likewise, b = 1e120 (K wvr (w_n + b w_s) = 1e361): A = K w / (w_n + b w) stays the part's */
    double tb = t.su.b[0], tg = t.su.g[0];
    c.su.b[jl] = 1.0;
    t.su.b[0] = 1e120;
    t.su.g[0] = 0.0;
    CHECK_OK(rg2_mesh_check(&c, &err), &err);
    CHECK_OK(rg2_mesh_check(&t, &err), &err);
    CHECK_OK(rg2_mesh_merge(pair, 2, 0, 0, RG2_SEAM_PRESERVE, &r, &err), &err);
    if (r.p) {
        double b = 1e120, wn = rg2_scalars_leg_w(&t.su, 0), ws = rg2_scalars_leg_w(&r.su, jl);
        double Apart = stencil_A(b, wn, 3.0, rg2_scalars_K(&t.su, 0)), Amerged = stencil_A(b, wn, ws, rg2_scalars_K(&r.su, jr));
        CHECK(ws == 2.0 && fabs(Amerged / Apart - 1.0) < 1e-13, "preserve with b = 1e120 on the right: w_s = %g, A %.17g vs %.17g",
              ws, Amerged, Apart);
    }
    rg2_mesh_free(&r);
    t.su.b[0] = tb;
    t.su.g[0] = tg;
    /* plain keeps b and g: end weights 10 and 0.5 (w_s = 5.25) with g = -40 leave K < 0 */
    c.su.w[c.su.n] = 10.0;
    t.su.w[0] = 0.5;
    c.su.b[jl] = 1.0;
    c.su.g[jl] = -40.0;
    CHECK_OK(rg2_mesh_check(&c, &err), &err);
    memset(&r, 0xab, sizeof r); /* (bad() requires it emptied) */
    bad(rg2_mesh_merge(pair, 2, 0, 0, RG2_SEAM_PLAIN, &r, &err), RG2_EWEIGHT, &err, &r,
        "rg2_mesh_merge: at a seam, u junction 8 has K = ", "plain seam K < 0");
    CHECK(strstr(err.msg, "K must be > 0") != NULL, "plain seam K < 0: %s", err.msg);
    CHECK_OK(rg2_mesh_merge(pair, 2, 0, 0, RG2_SEAM_PRESERVE, &r, &err), &err); /* (K rescaled, > 0) */
    rg2_mesh_free(&r);
    /* plain, end weights 1 and 5e307 (w_s = 2.5e307) with b = 2: K = 3e308 = inf */
    c.su.w[c.su.n] = 1.0;
    c.su.b[jl] = 2.0;
    c.su.g[jl] = 0.0;
    t.su.w[0] = 5e307;
    t.su.b[0] = 0.5;
    CHECK_OK(rg2_mesh_check(&t, &err), &err);
    memset(&r, 0xab, sizeof r); /* (bad() requires it emptied) */
    bad(rg2_mesh_merge(pair, 2, 0, 0, RG2_SEAM_PLAIN, &r, &err), RG2_ENONFINITE, &err, &r,
        "K must be a finite number > 0 (the scalars leave the double range)", "plain seam K = inf");
    rg2_mesh_free(&c);
    rg2_mesh_free(&t);

    /* a wrapping cut past the point limit: 1000003 x 4 of a closed 1000000 x 4 */
    CHECK_OK(grid_mesh(&c, 1000000, 4, 1, 0, &err), &err);
    int fw[2] = {0, -1}, lw[2] = {1000002, 0};
    memset(&r, 0xab, sizeof r); /* (bad() requires it emptied) */
    bad(rg2_mesh_cut(&c, fw, lw, &r, &err), RG2_ELIMIT, &err, &r,
        "rg2_mesh_cut: u (first[0], last[0]): mesh: 1000003 x 4 control points exceeds the limit of 4000000",
        "wrapping cut past the limit");
    rg2_mesh_free(&c);
    CHECK_OK(grid_mesh(&c, 4, 1000000, 0, 1, &err), &err); /* the same in v: the message names v */
    int fv[2] = {0, 0}, lv[2] = {3, 1000002};
    memset(&r, 0xab, sizeof r);
    bad(rg2_mesh_cut(&c, fv, lv, &r, &err), RG2_ELIMIT, &err, &r,
        "rg2_mesh_cut: v (first[1], last[1]): mesh: 4 x 1000003 control points exceeds the limit", "wrapping v cut");
    rg2_mesh_free(&c);

    /* two meshes within the point limit whose merge is not: the message starts with the function */
    CHECK_OK(grid_mesh(&c, 4, 600000, 0, 0, &err), &err);
    const rg2_mesh *big[2] = {&c, &c};
    memset(&r, 0xab, sizeof r); /* (bad() requires it emptied) */
    bad(rg2_mesh_merge(big, 2, 0, 0, RG2_SEAM_PRESERVE, &r, &err), RG2_ELIMIT, &err, &r,
        "rg2_mesh_merge: mesh: 8 x 600000 control points exceeds the limit of 4000000", "merge past the limit");
    rg2_mesh_free(&c);

    /* cut ranges */
    int fa[2] = {10, -1}, la[2] = {8, 0};
    memset(&r, 0xab, sizeof r); /* (bad() requires it emptied) */
    bad(rg2_mesh_cut(&M[TUBE], fa, la, &r, &err), RG2_EINVAL, &err, &r,
        "rg2_mesh_cut: u (first[0], last[0]): range [10, 8] is outside the 9 control points", "cut backwards");
    /* an open direction ends at its last point (a closed one may wrap: the heap over-read of a
     * range [3, 9] of 6 points was accepted when the wrap rule applied to both) */
    int fo[2] = {-1, 0}, lo[2] = {0, 7};
    memset(&r, 0xab, sizeof r); /* (bad() requires it emptied) */
    bad(rg2_mesh_cut(&M[WRAP], fo, lo, &r, &err), RG2_EINVAL, &err, &r,
        "rg2_mesh_cut: v (first[1], last[1]): range [0, 7] is outside the 6 control points of mesh 'in' in v (open; "
        "need 0 <= first < 6, first <= last <= 5)", "cut past an open end");
    int fb[2] = {-1, 0}, lb[2] = {0, 2};
    memset(&r, 0xab, sizeof r); /* (bad() requires it emptied) */
    bad(rg2_mesh_cut(&M[TUBE], fb, lb, &r, &err), RG2_EINVAL, &err, &r, "keeps 3 control points", "cut of 3");
    int fc[2] = {-2, -1}, lc[2] = {0, 0};
    memset(&r, 0xab, sizeof r); /* (bad() requires it emptied) */
    bad(rg2_mesh_cut(&M[TUBE], fc, lc, &r, &err), RG2_EINVAL, &err, &r, "first[0] = -2 is negative", "cut from -2");
    /* indices anywhere in int: no overflow (UBSan) in the range checks */
    int fd[2] = {0, -1}, ld[2] = {INT_MAX, 0};
    memset(&r, 0xab, sizeof r); /* (bad() requires it emptied) */
    bad(rg2_mesh_cut(&M[RING], fd, ld, &r, &err), RG2_EINVAL, &err, &r,
        "range [0, 2147483647] is outside the 15 control points", "cut to INT_MAX");
    int fe[2] = {INT_MAX, -1}, le[2] = {INT_MAX, 0};
    memset(&r, 0xab, sizeof r); /* (bad() requires it emptied) */
    bad(rg2_mesh_cut(&M[RING], fe, le, &r, &err), RG2_EINVAL, &err, &r, "first <= last <= 31)",
        "cut from INT_MAX");
    /* first = n, the first index past a closed direction: the bound named is that of first = n - 1 */
    {
        int n = M[RING].su.n, ff[2] = {n, -1}, lf[2] = {n, 0};
        char want[200];
        snprintf(want, sizeof want, "range [%d, %d] is outside the %d control points of mesh 'in' in u (closed, last may "
                 "wrap; need 0 <= first < %d, first <= last <= %d)", n, n, n, n, (n - 1) + n + 2);
        memset(&r, 0xab, sizeof r); /* (bad() requires it emptied) */
        bad(rg2_mesh_cut(&M[RING], ff, lf, &r, &err), RG2_EINVAL, &err, &r, want, "cut from n");
    }
    memset(&r, 0xab, sizeof r); /* (bad() requires it emptied) */
    bad(rg2_mesh_cut(&M[TUBE], NULL, l, &r, &err), RG2_EINVAL, &err, &r, "first is NULL", "cut, NULL first");
    memset(&r, 0xab, sizeof r); /* (bad() requires it emptied) */
    bad(rg2_mesh_cut(NULL, f, l, &r, &err), RG2_EINVAL, &err, &r, "rg2_mesh_cut: in is NULL", "cut of NULL");

    /* reverse, morph */
    memset(&r, 0xab, sizeof r); /* (bad() requires it emptied) */
    bad(rg2_mesh_reverse(&M[TUBE], 2, &r, &err), RG2_EINVAL, &err, &r, "dir = 2", "reverse dir 2");
    memset(&r, 0xab, sizeof r); /* (bad() requires it emptied) */
    bad(rg2_mesh_morph(&M[JOINED], &M[RING], 2.0, &r, &err), RG2_EDOMAIN, &err, &r, "rg2_mesh_morph.t: t = 2,",
        "morph t = 2");
    memset(&r, 0xab, sizeof r); /* (bad() requires it emptied) */
    bad(rg2_mesh_morph(&M[JOINED], &M[RING], NAN, &r, &err), RG2_EDOMAIN, &err, &r, "must lie in [0, 1]",
        "morph t = NaN");
    memset(&r, 0xab, sizeof r); /* (bad() requires it emptied) */
    bad(rg2_mesh_morph(&M[TUBE], &M[RING], 0.5, &r, &err), RG2_EINCOMPATIBLE, &err, &r,
        "meshes 'a' (9 control points, open) and 'b' (15 control points, closed) differ in u; a morph needs meshes "
        "of equal structure", "morph of unlike meshes");
    CHECK(!strstr(err.msg, "transposed"), "morph of unlike meshes: a transpose suggested: %s", err.msg);
    /* a mesh and its transpose (the ball's band, 8 closed x 6 open, and 6 open x 8 closed) */
    CHECK(M[BALL].su.n == M[BAND].sv.n && M[BALL].sv.n == M[BAND].su.n && M[BALL].su.n != M[BALL].sv.n,
          "ball and band: %d x %d and %d x %d", M[BALL].su.n, M[BALL].sv.n, M[BAND].su.n, M[BAND].sv.n);
    memset(&r, 0xab, sizeof r); /* (bad() requires it emptied) */
    bad(rg2_mesh_morph(&M[BALL], &M[BAND], 0.5, &r, &err), RG2_EINCOMPATIBLE, &err, &r,
        "differ in u; a morph needs meshes of equal structure ('b' transposed would match)",
        "morph of a mesh and its transpose");
    memset(&r, 0xab, sizeof r); /* (bad() requires it emptied) */
    bad(rg2_mesh_morph(&M[TUBE], NULL, 0.5, &r, &err), RG2_EINVAL, &err, &r, "rg2_mesh_morph: b is NULL",
        "morph with NULL");
}

/* Polar configurations: rg2_polar_mesh against the design file's `polar`, bit for bit, and the
 * band it builds on its shape; then its bad input. */
static const char *polar_json =
    "{\"format\": \"rg2 design 1\","
    " \"shapes\": {\"ball\": {\"kind\": \"sphere\", \"radius\": 1.5, \"translate\": [1, 2, 3]},"
    "  \"egg\": {\"kind\": \"ellipsoid\", \"a\": 2, \"b\": 1.5, \"c\": 1, \"rotate\": {\"axis\": [1, 1, 0], \"degrees\": 30}},"
    "  \"bowl\": {\"kind\": \"paraboloid\", \"A\": 1, \"B\": 0.8},"
    "  \"lid\": {\"kind\": \"hyperboloid2\", \"a\": 0.8, \"c\": 0.6, \"scale\": [1, 0.8, -1], \"translate\": [0, 0, 2.6]}},"
    " \"meshes\": {"
    "  \"B\": {\"polar\": \"ball\", \"u\": {\"arcs\": 8}, \"v\": {\"knots\": [0.15, 0.3, 0.42, 0.58, 0.7, 0.85]}},"
    "  \"E\": {\"polar\": \"egg\", \"u\": {\"arcs\": 6}, \"v\": {\"knots\": [0.2, 0.5, 0.8]}},"
    "  \"P\": {\"polar\": \"bowl\", \"u\": {\"arcs\": 8}, \"v\": {\"knots\": [0.3, 0.6, 0.9, 1.0]}},"
    "  \"H\": {\"polar\": \"lid\", \"u\": {\"arcs\": 8, \"from\": 180}, \"v\": {\"knots\": [-0.5, -0.45, -0.3, -0.15]}},"
    "  \"P2\": {\"polar\": \"bowl\", \"u\": {\"arcs\": 8}, \"v\": {\"knots\": [0.004, 0.008]}},"
    "  \"H2\": {\"polar\": \"lid\", \"u\": {\"arcs\": 8}, \"v\": {\"knots\": [-0.5, -0.25]}}"
    " },"
    " \"output\": [\"B\", \"E\", \"P\", \"H\", \"P2\", \"H2\"]}";

/* A one-pole polar mesh (paraboloid, hyperboloid2) against rg2_shape_mesh over the knots rg2.h
 * documents, built here: above the pole -v_1, 0, v_1..v_m, v_m + d, v_m + 2d (d = v_m - v_{m-1}),
 * below v_1 - 2d, v_1 - d, v_1..v_m, 0, -v_m (d = v_2 - v_1); every point bit for bit, the pole
 * row every point its first. */
static void one_pole_knots_match(const rg2_mesh *r, const rg2_shape *sh, const rg2_partition *pu, const double *v,
                                 int m, const char *what)
{
    double k[16];
    if (m + 4 > 16)
        return;
    int below = v[m - 1] < 0.0;
    double d = below ? v[1] - v[0] : v[m - 1] - v[m - 2];
    memcpy(k + 2, v, (size_t)m * sizeof(double));
    k[0] = below ? v[0] - 2.0 * d : -v[0];
    k[1] = below ? v[0] - d : 0.0;
    k[m + 2] = below ? 0.0 : v[m - 1] + d;
    k[m + 3] = below ? -v[m - 1] : v[m - 1] + 2.0 * d;
    rg2_partition pv = {RG2_PART_KNOTS_FULL, 0, m + 4, k, 0.0};
    rg2_mesh ref;
    rg2_error err;
    CHECK_OK(rg2_shape_mesh(sh, pu, &pv, &ref, &err), &err);
    if (ref.p == NULL)
        return;
    int pole = below ? ref.nv - 1 : 0, ok = ref.nu == r->nu && ref.nv == r->nv && scalars_same(&ref.su, &r->su) &&
                                            scalars_same(&ref.sv, &r->sv);
    for (int i = 0; ok && i < ref.nu; i++)
        for (int j = 0; j < ref.nv; j++)
            ok = ok && !memcmp(rg2_mesh_at(r, i, j), rg2_mesh_at(&ref, j == pole ? 0 : i, j),
                               4 * sizeof(double));
    CHECK(ok, "%s: differs from the shape's mesh over the documented knots", what);
    rg2_mesh_free(&ref);
}

static void polar(void)
{
    rg2_error err;
    rg2_design *d = NULL;
    rg2_status st = rg2_design_parse(polar_json, strlen(polar_json), "polar", &d, &err);
    CHECK(st == RG2_OK && rg2_design_num_surfaces(d) == 6, "polar design: %s", err.msg);
    if (st)
        return;
    /* (P2, H2: the fewest knots a one-pole shape takes, 2: one patch row, 4 points in v; P2 both knots
     * close to the pole) */
    static const double kb[] = {0.15, 0.3, 0.42, 0.58, 0.7, 0.85}, ke[] = {0.2, 0.5, 0.8},
                        kp[] = {0.3, 0.6, 0.9, 1.0}, kh[] = {-0.5, -0.45, -0.3, -0.15}, kp2[] = {0.004, 0.008},
                        kh2[] = {-0.5, -0.25};
    const double *kv[6] = {kb, ke, kp, kh, kp2, kh2};
    const int m[6] = {6, 3, 4, 4, 2, 2}, arcs[6] = {8, 6, 8, 8, 8, 8}, shape[6] = {0, 1, 2, 3, 2, 3};
    const double start[6] = {0, 0, 0, 180 * M_PI / 180.0, 0, 0}; /* (the design's own formula for "from") */
    const int poles[6] = {3, 3, 1, 2, 1, 2}; /* bit 0: row 0 collapsed, bit 1: the last row */
    for (int k = 0; k < 6; k++) {
        double au[8];
        for (int a = 0; a < arcs[k]; a++)
            au[a] = 2.0 * M_PI / arcs[k];
        rg2_partition pu = {RG2_PART_ANGLES, 1, arcs[k], au, start[k]};
        const rg2_shape *sh = rg2_design_shape(d, shape[k]);
        rg2_mesh r;
        CHECK_OK(rg2_polar_mesh(sh, &pu, kv[k], m[k], &r, &err), &err);
        CHECK(r.nu == arcs[k] && r.nv == m[k] + 2, "polar mesh %d: %d x %d points, want %d x %d", k, r.nu, r.nv,
              arcs[k], m[k] + 2);
        char what[64];
        snprintf(what, sizeof what, "rg2_polar_mesh of '%s' (%d knots)", rg2_design_shape_label(d, shape[k]), m[k]);
        same_mesh(&r, rg2_design_mesh(d, k), what);
        if (k >= 2)
            one_pole_knots_match(&r, sh, &pu, kv[k], m[k], what);
        CHECK(rg2_mesh_row_collapsed(&r, 0) == (poles[k] & 1) && rg2_mesh_row_collapsed(&r, r.nv - 1) == poles[k] >> 1,
              "%s: collapsed rows %d, %d, want %d, %d", what, rg2_mesh_row_collapsed(&r, 0),
              rg2_mesh_row_collapsed(&r, r.nv - 1), poles[k] & 1, poles[k] >> 1);
        rg2_surface s;
        CHECK_OK(rg2_surface_build(&r, &s, &err), &err);
        int on = patches_on(&s, sh, rg2t_surface_scale(&s), 1e-14);
        CHECK(on == s.nu * s.nv, "%s: %d of %d patches on the shape", what, on, s.nu * s.nv);
        rg2_surface_free(&s);
        rg2_mesh_free(&r);
    }

    double au[8];
    for (int a = 0; a < 8; a++)
        au[a] = M_PI / 4;
    rg2_partition pu = {RG2_PART_ANGLES, 1, 8, au, 0.0};
    rg2_mesh r;
    rg2_shape torus;
    rg2_shape_init(&torus, RG2_SHAPE_TORUS);
    memset(&r, 0xab, sizeof r); /* (bad() requires it emptied) */
    bad(rg2_polar_mesh(&torus, &pu, kb, 6, &r, &err), RG2_EINVAL, &err, &r,
        "rg2_polar_mesh: a torus has no polar configuration", "polar torus");
    memset(&r, 0xab, sizeof r); /* (bad() requires it emptied) */
    bad(rg2_polar_mesh(rg2_design_shape(d, 0), &pu, kb, 1, &r, &err), RG2_EINVAL, &err, &r,
        "rg2_polar_mesh: 1 interior knots given", "polar of 1 knot");
    memset(&r, 0xab, sizeof r); /* (bad() requires it emptied) */
    bad(rg2_polar_mesh(rg2_design_shape(d, 0), &pu, kb, -7, &r, &err), RG2_EINVAL, &err, &r,
        "rg2_polar_mesh: -7 interior knots given", "polar of -7 knots");
    const double across[3] = {-0.2, 0.3, 0.5}, outside[2] = {0.5, 1.2};
    memset(&r, 0xab, sizeof r); /* (bad() requires it emptied) */
    bad(rg2_polar_mesh(rg2_design_shape(d, 2), &pu, across, 3, &r, &err), RG2_EDOMAIN, &err, &r,
        "rg2_polar_mesh: polar knots: knot 0 = -0.2: the knots must increase and all lie on one side of the pole",
        "paraboloid knots on both sides");
    /* one-pole knots must lie strictly on one side of the pole v = 0 and strictly increase */
    static const struct {
        int shape;
        double v[3];
        const char *needle;
    } one_side[] = {
        {2, {0.0, 0.5, 0.9}, "rg2_polar_mesh: polar knots: knot 0 = 0: the knots must increase"},
        {2, {0.3, 0.3, 0.9}, "rg2_polar_mesh: polar knots: knot 1 = 0.3: the knots must increase"},
        {3, {-0.5, -0.5, -0.2}, "rg2_polar_mesh: polar knots: knot 1 = -0.5: the knots must increase"},
        {3, {-0.5, 0.0, -0.2}, "rg2_polar_mesh: polar knots: knot 1 = 0: the knots must increase"},
        {3, {-0.5, -0.2, 0.0}, "rg2_polar_mesh: polar knots: knot 0 = -0.5: the knots must increase"},
    };
    for (size_t c = 0; c < sizeof one_side / sizeof one_side[0]; c++) {
        memset(&r, 0xab, sizeof r); /* (bad() requires it emptied) */
        bad(rg2_polar_mesh(rg2_design_shape(d, one_side[c].shape), &pu, one_side[c].v, 3, &r, &err), RG2_EDOMAIN,
            &err, &r, one_side[c].needle, "one-pole knots at the pole or repeated");
    }
    memset(&r, 0xab, sizeof r); /* (bad() requires it emptied) */
    bad(rg2_polar_mesh(rg2_design_shape(d, 0), &pu, outside, 2, &r, &err), RG2_EDOMAIN, &err, &r,
        "rg2_polar_mesh: polar knots: knot 1 = 1.2 must lie strictly between the poles 0 and 1", "sphere knot 1.2");
    memset(&r, 0xab, sizeof r); /* (bad() requires it emptied) */
    bad(rg2_polar_mesh(rg2_design_shape(d, 0), NULL, kb, 6, &r, &err), RG2_EINVAL, &err, &r, "pu is NULL",
        "polar of a NULL partition");
    memset(&r, 0xab, sizeof r); /* (bad() requires it emptied) */
    bad(rg2_polar_mesh(rg2_design_shape(d, 0), &pu, kb, 6, NULL, &err), RG2_EINVAL, &err, NULL, "out is NULL",
        "polar into NULL");
    const double nan_knots[3] = {0.2, NAN, 0.6};
    memset(&r, 0xab, sizeof r); /* (bad() requires it emptied) */
    bad(rg2_polar_mesh(rg2_design_shape(d, 2), &pu, nan_knots, 3, &r, &err), RG2_ENONFINITE, &err, &r,
        "rg2_polar_mesh: polar knots: knot 1 is not finite", "paraboloid NaN knot");
    memset(&r, 0xab, sizeof r); /* (bad() requires it emptied) */
    bad(rg2_polar_mesh(rg2_design_shape(d, 0), &pu, kb, INT_MAX, &r, &err), RG2_ELIMIT, &err, &r,
        "rg2_polar_mesh: 2147483647 interior knots give 2147483651 knots with the 4 data-only ones, more than the "
        "limit of 4000000", "polar of INT_MAX knots");
    /* the largest refused: m + 4 = RG2_MAX_POINTS + 1 knots (it passed the check and failed in the
     * partition's, naming 'v partition: 4000002 values') */
    memset(&r, 0xab, sizeof r);
    bad(rg2_polar_mesh(rg2_design_shape(d, 2), &pu, kb, RG2_MAX_POINTS - 3, &r, &err), RG2_ELIMIT, &err, &r,
        "rg2_polar_mesh: 3999997 interior knots give 4000001 knots", "polar of RG2_MAX_POINTS - 3 knots");

    const double far[3] = {1e307, 1e308, 1.7e308}; /* v_m + 2d = 3.1e308 */
    memset(&r, 0xab, sizeof r);
    bad(rg2_polar_mesh(rg2_design_shape(d, 2), &pu, far, 3, &r, &err), RG2_EDOMAIN, &err, &r,
        "rg2_polar_mesh: polar knots: the data-only end knots v_m + d, v_m + 2d leave the double range (d = 6.999999999999999e+307)",
        "paraboloid knots near the double range");

    /* a merge cannot join at a pole: the paraboloid's pole row 0 is the second mesh's first */
    rg2_mesh P;
    CHECK_OK(rg2_polar_mesh(rg2_design_shape(d, 2), &pu, kp, 4, &P, &err), &err);
    const rg2_mesh *two[2] = {&P, &P};
    memset(&r, 0xab, sizeof r); /* (bad() requires it emptied) */
    bad(rg2_mesh_merge(two, 2, 1, 0, RG2_SEAM_PRESERVE, &r, &err), RG2_EINCOMPATIBLE, &err, &r,
        "rg2_mesh_merge.merge[1]: mesh 'in[1]' has a polar point at its first end", "merge at a pole");
    rg2_mesh_free(&P);
    rg2_design_free(d);
}

/* Moebius maps about a placed reference: rg2_mesh_mobius_shape against the design file's `mobius`,
 * bit for bit, every band patch still on its shape; then its bad input, the mesh left as it was. */
static const char *mobius_json =
    "{\"format\": \"rg2 design 1\","
    " \"shapes\": {\"ball\": {\"kind\": \"sphere\", \"radius\": 1.5, \"translate\": [0, 0, 1]},"
    "  \"egg\": {\"kind\": \"ellipsoid\", \"a\": 2, \"b\": 1.5, \"c\": 1, \"rotate\": {\"axis\": [1, 1, 0], \"degrees\": 30},"
    "   \"translate\": [0.5, -1, 2]},"
    "  \"unit\": {\"kind\": \"sphere\"}, \"ring\": {\"kind\": \"torus\", \"R\": 2, \"r\": 0.5}},"
    " \"meshes\": {"
    "  \"B\": {\"polar\": \"ball\", \"u\": {\"arcs\": 8}, \"v\": {\"knots\": [0.15, 0.3, 0.42, 0.58, 0.7, 0.85]}},"
    "  \"E\": {\"polar\": \"egg\", \"u\": {\"arcs\": 6}, \"v\": {\"knots\": [0.2, 0.5, 0.8]}},"
    "  \"U\": {\"polar\": \"unit\", \"u\": {\"arcs\": 5}, \"v\": {\"knots\": [0.25, 0.5, 0.75]}},"
    "  \"T\": {\"polar\": \"unit\", \"u\": {\"arcs\": 3}, \"v\": {\"knots\": [0.2, 0.5, 0.8]}},"
    "  \"Bb\": {\"mobius\": \"B\", \"sphere\": \"ball\", \"b\": 0.5},"
    "  \"Bp\": {\"mobius\": \"B\", \"sphere\": \"ball\", \"poles\": {\"south\": [1.2, 0, 0.1], \"north\": [0, 0, 2.5]}},"
    "  \"Eb\": {\"mobius\": \"E\", \"sphere\": \"egg\", \"b\": -0.3},"
    "  \"Up\": {\"mobius\": \"U\", \"poles\": {\"south\": [0, 0.6, -0.8], \"north\": [0.6, 0, 0.8]}}"
    " },"
    " \"output\": [\"B\", \"E\", \"U\", \"Bb\", \"Bp\", \"Eb\", \"Up\", \"T\"]}";

/* The largest difference of moved's 4-tuples from in's mapped by rg2_mobius_poles_matrix about the
 * reference sphere (a translated sphere of radius param[0]; NULL: the unit sphere at the origin): the
 * poles taken to the unit sphere, M applied to (p - c w) / R, then back; relative to the 4-tuple. */
static double poles_map_error(const rg2_mesh *in, const rg2_mesh *moved, const rg2_shape *ref, const double *south,
                              const double *north)
{
    double c[3] = {0.0, 0.0, 0.0}, R = ref ? ref->param[0] : 1.0, ls[3], ln[3], M[16], worst = 0.0;
    for (int k = 0; ref && k < 3; k++)
        c[k] = ref->xform[4 * k + 3];
    for (int k = 0; k < 3; k++) {
        ls[k] = (south[k] - c[k]) / R;
        ln[k] = (north[k] - c[k]) / R;
    }
    rg2_error err;
    if (rg2_mobius_poles_matrix(ls, ln, M, &err))
        return INFINITY;
    for (size_t i = 0; i < (size_t)in->nu * (size_t)in->nv; i++) {
        const double *p = in->p + 4 * i, *got = moved->p + 4 * i;
        double loc[4] = {(p[0] - c[0] * p[3]) / R, (p[1] - c[1] * p[3]) / R, (p[2] - c[2] * p[3]) / R, p[3]}, q[4],
               size = 0.0, d = 0.0;
        for (int r = 0; r < 4; r++)
            q[r] = M[4 * r] * loc[0] + M[4 * r + 1] * loc[1] + M[4 * r + 2] * loc[2] + M[4 * r + 3] * loc[3];
        for (int r = 0; r < 4; r++) {
            double want = r < 3 ? R * q[r] + c[r] * q[3] : q[3];
            d = fmax(d, fabs(got[r] - want));
            size = fmax(size, fabs(want));
        }
        worst = fmax(worst, d / size);
    }
    return worst;
}

static void mobius(void)
{
    rg2_error err;
    rg2_design *d = NULL;
    rg2_status st = rg2_design_parse(mobius_json, strlen(mobius_json), "mobius", &d, &err);
    CHECK(st == RG2_OK && rg2_design_num_surfaces(d) == 8, "mobius design: %s", err.msg);
    if (st)
        return;
    const rg2_shape *ball = rg2_design_shape(d, 0), *egg = rg2_design_shape(d, 1), *ring = rg2_design_shape(d, 3);
    static const double bb = 0.5, be = -0.3, south[3] = {1.2, 0, 0.1}, north[3] = {0, 0, 2.5},
                        su[3] = {0, 0.6, -0.8}, nu[3] = {0.6, 0, 0.8};
    const struct {
        int in, out;
        const rg2_shape *ref, *on;
        const double *b, *s, *n;
        int patches;
    } c[4] = {{0, 3, ball, ball, &bb, NULL, NULL, 40}, {0, 4, ball, ball, NULL, south, north, 40},
              {1, 5, egg, egg, &be, NULL, NULL, 12}, {2, 6, NULL, rg2_design_shape(d, 2), NULL, su, nu, 10}};
    for (int k = 0; k < 4; k++) {
        rg2_mesh m;
        CHECK_OK(rg2_mesh_copy(rg2_design_mesh(d, c[k].in), &m, &err), &err);
        if (!m.p)
            continue;
        char what[96];
        snprintf(what, sizeof what, "rg2_mesh_mobius_shape of design mesh %d (%s)", c[k].in, c[k].b ? "b" : "poles");
        CHECK_OK(rg2_mesh_mobius_shape(&m, c[k].ref, c[k].b, c[k].s, c[k].n, &err), &err);
        same_mesh(&m, rg2_design_mesh(d, c[k].out), what);
        if (c[k].s) /* the poles' map from rg2_mobius_poles_matrix about the sphere's centre and radius */
            CHECK(poles_map_error(rg2_design_mesh(d, c[k].in), &m, c[k].ref, c[k].s, c[k].n) < 1e-13,
                  "%s: %.3g from rg2_mobius_poles_matrix's map", what,
                  poles_map_error(rg2_design_mesh(d, c[k].in), &m, c[k].ref, c[k].s, c[k].n));
        CHECK(memcmp(m.p, rg2_design_mesh(d, c[k].in)->p, (size_t)m.nu * (size_t)m.nv * 4 * sizeof(double)) != 0,
              "%s: the mesh did not move", what);
        rg2_surface s;
        if (rg2_surface_build(&m, &s, &err) == RG2_OK) {
            int on = patches_on(&s, c[k].on, rg2t_surface_scale(&s), 1e-14);
            CHECK(s.nu * s.nv == c[k].patches && on == c[k].patches, "%s: %d of %d patches on the shape, want %d",
                  what, on, s.nu * s.nv, c[k].patches);
            rg2_surface_free(&s);
        } else
            CHECK(0, "%s: build: %s", what, err.msg);
        rg2_mesh_free(&m);
    }

    /* one row (1 x nv) or one column (nu x 1) of a mesh is not empty: mapped point by point, the
     * same bits as the whole mesh's first points; no points in either direction is empty. 4-tuples
     * scaled by 0.005 (the same points, weights below 0.01) map to the scaled 4-tuples, and a point
     * at infinity (weight 0, kept 0 by b's rotation) is refused, named */
    rg2_mesh whole, part;
    CHECK_OK(rg2_mesh_copy(rg2_design_mesh(d, 0), &whole, &err), &err);
    CHECK_OK(rg2_mesh_copy(rg2_design_mesh(d, 0), &part, &err), &err);
    if (whole.p && part.p) {
        CHECK_OK(rg2_mesh_mobius_shape(&whole, ball, &bb, NULL, NULL, &err), &err);
        int n_u = part.nu, n_v = part.nv;
        size_t n4 = (size_t)n_u * (size_t)n_v * 4;
        const int shape[4][2] = {{1, n_v}, {n_u, 1}, {n_u, 0}, {0, n_v}};
        for (int k = 0; k < 4; k++) {
            memcpy(part.p, rg2_design_mesh(d, 0)->p, n4 * sizeof(double));
            part.nu = shape[k][0], part.nv = shape[k][1];
            st = rg2_mesh_mobius_shape(&part, ball, &bb, NULL, NULL, &err);
            if (k < 2)
                CHECK(st == RG2_OK && !memcmp(part.p, whole.p, (size_t)part.nu * (size_t)part.nv * 4 * sizeof(double)),
                      "a %d x %d mesh: not mapped as the whole mesh's first points (%s)", part.nu, part.nv, err.msg);
            else
                expect_err(st, RG2_EINVAL, &err, "rg2_mesh_mobius_shape: empty mesh", k == 2 ? "nu x 0" : "0 x nv");
        }
        part.nu = n_u, part.nv = n_v;
        memcpy(part.p, rg2_design_mesh(d, 0)->p, n4 * sizeof(double));
        for (size_t q = 0; q < n4; q++)
            part.p[q] *= 0.005;
        CHECK_OK(rg2_mesh_mobius_shape(&part, ball, &bb, NULL, NULL, &err), &err);
        double worst = 0.0;
        for (size_t q = 0; q < n4; q++)
            worst = fmax(worst, fabs(part.p[q] - 0.005 * whole.p[q]) / fabs(0.005 * whole.p[q | 3]));
        CHECK(worst <= 1e-15, "4-tuples scaled by 0.005: %.3g from the scaled map", worst);
        double *at = rg2_mesh_at(&part, 1, 2);
        at[0] = 1.0, at[1] = at[2] = at[3] = 0.0;
        expect_err(rg2_mesh_mobius_shape(&part, ball, &bb, NULL, NULL, &err), RG2_EWEIGHT, &err,
                   "rg2_mesh_mobius_shape.b: the Moebius map gives control point [1, 2] the weight 0,", "weight 0");
    }
    rg2_mesh_free(&whole);
    rg2_mesh_free(&part);

    /* bad input: the status, a message naming the argument, and the mesh as it was */
    rg2_mesh m, keep;
    CHECK_OK(rg2_mesh_copy(rg2_design_mesh(d, 0), &m, &err), &err);
    CHECK_OK(rg2_mesh_copy(&m, &keep, &err), &err);
    const double nan3[3] = {0, NAN, 1}, nanb = NAN, off[3] = {1.2, 0, 0.1001};
    const struct {
        const rg2_shape *ref;
        const double *b, *s, *n;
        rg2_status want;
        const char *needle;
    } bad_in[] = {
        {ring, &bb, NULL, NULL, RG2_EINVAL, "rg2_mesh_mobius_shape.ref: the reference shape is a torus; it must be a sphere or an ellipsoid"},
        {ball, &bb, south, north, RG2_EINVAL, "rg2_mesh_mobius_shape: give either b or the poles south and north, not both"},
        {ball, NULL, NULL, NULL, RG2_EINVAL, "rg2_mesh_mobius_shape: give either b or the poles south and north, not neither"},
        {ball, NULL, south, NULL, RG2_EINVAL, "rg2_mesh_mobius_shape: the north pole is NULL (give both poles)"},
        {ball, &nanb, NULL, NULL, RG2_ENONFINITE, "rg2_mesh_mobius_shape.b is not a finite number"},
        {ball, NULL, south, nan3, RG2_ENONFINITE, "rg2_mesh_mobius_shape.north: coordinate 1 is not finite"},
        {ball, NULL, off, north, RG2_EDOMAIN, "rg2_mesh_mobius_shape.south: (1.2, 0, 0.1001) is not on the reference sphere ("},
        {ball, NULL, north, north, RG2_EDOMAIN, "rg2_mesh_mobius_shape.poles: "},
    };
    for (size_t k = 0; k < sizeof bad_in / sizeof bad_in[0]; k++) {
        char what[48];
        snprintf(what, sizeof what, "rg2_mesh_mobius_shape bad input %zu", k);
        expect_err(rg2_mesh_mobius_shape(&m, bad_in[k].ref, bad_in[k].b, bad_in[k].s, bad_in[k].n, &err), bad_in[k].want,
                   &err, bad_in[k].needle, what);
        CHECK(m.p && !memcmp(m.p, keep.p, (size_t)m.nu * (size_t)m.nv * 4 * sizeof(double)), "%s: the mesh changed",
              what);
    }
    { /* a pole off the sphere in all three coordinates: the nearest point named is c + R (p - c) / |p - c| */
        static const double p[3] = {0.3, 0.4, 0.1};
        double cen[3] = {ball->xform[3], ball->xform[7], ball->xform[11]}, R = ball->param[0], dir[3], l;
        double got[3] = {0, 0, 0};
        for (int k = 0; k < 3; k++)
            dir[k] = p[k] - cen[k];
        l = sqrt(dir[0] * dir[0] + dir[1] * dir[1] + dir[2] * dir[2]);
        expect_err(rg2_mesh_mobius_shape(&m, ball, NULL, p, north, &err), RG2_EDOMAIN, &err,
                   "rg2_mesh_mobius_shape.south: (0.3, 0.4, 0.1) is not on the reference sphere (", "pole off the sphere");
        const char *at = strstr(err.msg, "the nearest point on it is (");
        int n = at ? sscanf(at + strlen("the nearest point on it is ("), "%lf, %lf, %lf", &got[0], &got[1], &got[2]) : 0;
        double worst = 0.0;
        for (int k = 0; k < 3; k++)
            worst = fmax(worst, fabs(got[k] - (cen[k] + R * dir[k] / l)));
        CHECK(n == 3 && worst < 1e-14, "pole off the sphere: nearest point %.3g from c + R (p - c) / |p - c|: %s", worst,
              err.msg);
    }
    { /* a pole at the sphere's centre: no nearest point to name (the direction is undefined), the
       * unit sphere's message of the pole as the placement maps it, |p| = 0 */
        const double cen[3] = {ball->xform[3], ball->xform[7], ball->xform[11]};
        expect_err(rg2_mesh_mobius_shape(&m, ball, NULL, cen, north, &err), RG2_EDOMAIN, &err,
                   "rg2_mesh_mobius_shape.poles: south pole (0, 0, 0) is not on the unit sphere (|p| = 0)",
                   "pole at the centre");
        CHECK(!strstr(err.msg, "nan"), "pole at the centre: %s", err.msg);
    }
    /* a boost that sends control points through infinity (tests/bad/mobius_through_infinity.json; b
     * alone is a rotation times 1 + b^2 and keeps every weight > 0) */
    rg2_mesh t, tkeep;
    CHECK_OK(rg2_mesh_copy(rg2_design_mesh(d, 7), &t, &err), &err);
    CHECK_OK(rg2_mesh_copy(&t, &tkeep, &err), &err);
    static const double ts[3] = {0, 0.999, -0.0447101778}, tn[3] = {0, 1, 0};
    expect_err(rg2_mesh_mobius_shape(&t, NULL, NULL, ts, tn, &err), RG2_EWEIGHT, &err,
               "rg2_mesh_mobius_shape.poles: the Moebius map gives control point [", "a map through infinity");
    { /* the weight it names: row 3 of rg2_mobius_poles_matrix's M (the unit sphere) times that 4-tuple, <= 0 */
        int ci = -1, cj = -1;
        double w = 1.0, M[16], want = NAN;
        const char *at = strstr(err.msg, "control point [");
        if (at && sscanf(at, "control point [%d, %d] the weight %lf", &ci, &cj, &w) == 3 && ci >= 0 && ci < tkeep.nu &&
            cj >= 0 && cj < tkeep.nv && rg2_mobius_poles_matrix(ts, tn, M, &err) == RG2_OK) {
            const double *p = tkeep.p + 4 * ((size_t)ci * (size_t)tkeep.nv + (size_t)cj);
            want = M[12] * p[0] + M[13] * p[1] + M[14] * p[2] + M[15] * p[3];
        }
        CHECK(want <= 0.0 && fabs(w - want) <= 1e-5 * fabs(want), "a map through infinity: control point [%d, %d], "
              "weight %.6g named, %.6g computed", ci, cj, w, want);
    }
    CHECK(t.p && !memcmp(t.p, tkeep.p, (size_t)t.nu * (size_t)t.nv * 4 * sizeof(double)),
          "a map through infinity: the mesh changed");
    rg2_mesh_free(&t);
    rg2_mesh_free(&tkeep);
    rg2_shape nanball = *ball; /* (it named an entry of the product placement x scale) */
    nanball.param[0] = NAN;
    expect_err(rg2_mesh_mobius_shape(&m, &nanball, &bb, NULL, NULL, &err), RG2_ENONFINITE, &err,
               "rg2_mesh_mobius_shape.ref: parameter 0 is not finite", "NaN radius");
    nanball = *ball;
    nanball.xform[3] = NAN;
    expect_err(rg2_mesh_mobius_shape(&m, &nanball, &bb, NULL, NULL, &err), RG2_ENONFINITE, &err,
               "rg2_mesh_mobius_shape.ref: placement entry 3 is not finite", "NaN placement");
    CHECK(!memcmp(m.p, keep.p, (size_t)m.nu * (size_t)m.nv * 4 * sizeof(double)), "NaN reference: the mesh changed");
    rg2_mesh empty = {0};
    expect_err(rg2_mesh_mobius_shape(&empty, ball, &bb, NULL, NULL, &err), RG2_EINVAL, &err,
               "rg2_mesh_mobius_shape: empty mesh", "rg2_mesh_mobius_shape of an empty mesh");
    rg2_mesh_free(&m);
    rg2_mesh_free(&keep);
    rg2_design_free(d);
}

int main(void)
{
    rg2_error err;
    rg2_design *d = NULL;
    rg2_status st = rg2_design_parse(design_json, strlen(design_json), "meshops", &d, &err);
    CHECK(st == RG2_OK && rg2_design_num_surfaces(d) == N_OUT, "design: %s (%d outputs)", err.msg,
          rg2_design_num_surfaces(d));
    if (st == RG2_OK && rg2_design_num_surfaces(d) == N_OUT) {
        rg2_mesh M[N_OUT];
        for (int k = 0; k < N_OUT; k++)
            M[k] = *rg2_design_mesh(d, k);
        const rg2_shape *ring = rg2_design_shape(d, 0), *ball = rg2_design_shape(d, 1);
        CHECK(!strcmp(rg2_design_shape_label(d, 0), "ring") && !strcmp(rg2_design_shape_label(d, 1), "ball"),
              "shape labels %s, %s", rg2_design_shape_label(d, 0), rg2_design_shape_label(d, 1));
        results_match(M, ring, ball);
        errors(M);
    }
    rg2_design_free(d);
    polar();
    mobius();
    return rg2t_done("test_meshops");
}
