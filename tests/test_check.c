/* test_check.c -- the continuity/exactness report: agrees with the test harness's own seam
 * measurement, reports exact shapes as exact, and reports deliberately broken surfaces
 * (moved control points, a G1 join) as failures at the right seam. Every check runs again on
 * the same surfaces with a mixed pattern of patches replaced by their exact degree elevations
 * (xmix.h); the reports of the two forms are compared. */
#include "harness.h"
#include "scenes.h"
#include "xmix.h"

#include <cjson/cJSON.h>
#include <stdlib.h>
#include <string.h>

static double rel(double a, double b) { return fabs(a - b) / fmax(fmax(fabs(a), fabs(b)), 1e-300); }

/* rg2_check's own seam measurement equals rg2t_surface_seams (same definitions). */
static void agrees_with_harness(const rg2_surface *s, const char *name)
{
    rg2_check_opts o;
    rg2_check_opts_default(&o);
    rg2_check_report r;
    rg2_error err;
    CHECK_OK(rg2_check(s, 1, NULL, NULL, 0, &o, &r, &err), &err);
    rg2t_seams t;
    rg2t_surface_seams(s, o.seam_samples, &t);
    printf("%s: %d seams, G0 %.2e (harness %.2e), G1 %.2e (%.2e), G2 %.2e (%.2e)\n", name, r.seams, r.g0.value, t.pos,
           r.g1.value, t.angle, r.g2.value, t.curv);
    CHECK(r.seams == t.seams && r.seam_samples == t.samples && r.skipped == t.skipped, "%s: seams %d/%d samples %d/%d",
          name, r.seams, t.seams, r.seam_samples, t.samples);
    /* tiny gaps are rounding noise: compare them absolutely, larger ones relatively */
    CHECK(fabs(r.g0.value - t.pos) <= 1e-15 || rel(r.g0.value, t.pos) < 1e-9, "%s: G0 %.17g vs %.17g", name,
          r.g0.value, t.pos);
    CHECK(fabs(r.g1.value - t.angle) <= 1e-15 || rel(r.g1.value, t.angle) < 1e-9, "%s: G1 %.17g vs %.17g", name,
          r.g1.value, t.angle);
    CHECK(fabs(r.g2.value - t.curv) <= 1e-13 || rel(r.g2.value, t.curv) < 1e-9, "%s: G2 %.17g vs %.17g", name,
          r.g2.value, t.curv);
    rg2_check_report_free(&r);
}

/* The report of a surface with elevated patches against the bi-3 original's: the same counts
 * and failures, gaps equal to rounding (absolute 1e-13 for G0 / G1, 1e-11 relative or
 * absolute for the curvature jump), the same residuals, curvature ranges (relative to
 * max(|value|, 1 / size)) and sampled denominators to 1e-12; control weights within the
 * original's range (elevated weights are convex combinations). Next to a pole (surfaces with
 * skipped pole samples) |Su| ~ v |Suv|: normals and curvatures at the samples 1/16 from the
 * pole amplify the rounding of either form by ~1e3 - 1e5, so there G1 agrees to 1e-11 and G2
 * and the curvature ranges to 1e-8 (the G2 promise) only. */
static void same_report(const rg2_check_report *a, const rg2_check_report *b, const char *name)
{
    CHECK(a->seams == b->seams && a->seam_samples == b->seam_samples && a->skipped == b->skipped &&
              a->patches == b->patches && a->exact_patches == b->exact_patches && a->transitions == b->transitions,
          "%s: counts differ (seams %d/%d, skipped %d/%d, exact %d/%d)", name, a->seams, b->seams, a->skipped,
          b->skipped, a->exact_patches, b->exact_patches);
    double d0 = fabs(a->g0.value - b->g0.value), d1 = fabs(a->g1.value - b->g1.value);
    double d2 = fabs(a->g2.value - b->g2.value) / fmax(1.0, fabs(b->g2.value));
    double dr = fabs(a->worst_residual - b->worst_residual);
    double dc = 0;
    const double ra[6] = {a->kmin, a->kmax, a->Hmin, a->Hmax, a->Kmin, a->Kmax};
    const double rb[6] = {b->kmin, b->kmax, b->Hmin, b->Hmax, b->Kmin, b->Kmax};
    for (int k = 0; k < 6; k++) {
        double floor = k < 4 ? 1.0 / b->size : 1.0 / (b->size * b->size);
        dc = fmax(dc, fabs(ra[k] - rb[k]) / fmax(fmax(fabs(ra[k]), fabs(rb[k])), floor));
    }
    double dw = rel(a->eval_wmin, b->eval_wmin);
    int wok = a->wmin >= b->wmin * (1 - 1e-15) && a->wmax <= b->wmax * (1 + 1e-15);
    int pole = b->skipped > 0;
    printf("%s: elevated vs bi-3 report%s: G0 %.1e, G1 %.1e, G2 %.1e (G2 %.2e vs %.2e), residual %.1e, curvature "
           "ranges %.1e, denominators %.1e, weights [%.4g, %.4g] in [%.4g, %.4g]\n",
           name, pole ? " (poles)" : "", d0, d1, d2, a->g2.value, b->g2.value, dr, dc, dw, a->wmin, a->wmax, b->wmin,
           b->wmax);
    double t1 = pole ? 1e-11 : 1e-13, t2 = pole ? 1e-8 : 1e-11, tc = pole ? 1e-8 : 1e-12;
    CHECK(d0 <= 1e-13 && d1 <= t1 && d2 <= t2 && dr <= 1e-14 && dc <= tc && dw <= 1e-12 && wok,
          "%s: reports differ: G0 %.3g G1 %.3g G2 %.3g residual %.3g curvature %.3g denominators %.3g weights %d", name,
          d0, d1, d2, dr, dc, dw, wok);
    CHECK(rg2_check_failures(a, ~0u) == rg2_check_failures(b, ~0u), "%s: failures %#x vs %#x", name,
          rg2_check_failures(a, ~0u), rg2_check_failures(b, ~0u));
}

/* rg2_check of s and of s with mixed-degree patches: same report. */
static void mixed_same(const rg2_surface *s, const rg2_shape *shapes, const char *const *labels, int ns,
                       const char *name)
{
    rg2_surface x;
    rg2_error err;
    CHECK_OK(xmix_copy(s, &x, &err), &err);
    rg2_check_report a, b;
    CHECK_OK(rg2_check(&x, 1, shapes, labels, ns, NULL, &a, &err), &err);
    CHECK_OK(rg2_check(s, 1, shapes, labels, ns, NULL, &b, &err), &err);
    same_report(&a, &b, name);
    rg2_check_report_free(&a);
    rg2_check_report_free(&b);
    rg2_surface_free(&x);
}

/* The text and JSON reports of rg2_check(surfs, ...) with o at `threads` threads (malloc'd;
 * NULL when the check fails). */
static char *report_text(const rg2_surface *surfs, int n, const rg2_shape *shapes, const char *const *labels, int ns,
                         const rg2_check_opts *o, int threads, char **json)
{
    rg2_check_opts t = *o;
    t.threads = threads;
    rg2_check_report r;
    rg2_error err;
    char *text = NULL;
    *json = NULL;
    CHECK_OK(rg2_check(surfs, n, shapes, labels, ns, &t, &r, &err), &err);
    CHECK_OK(rg2_check_format(&r, 0, &text, &err), &err);
    CHECK_OK(rg2_check_format(&r, 1, json, &err), &err);
    rg2_check_report_free(&r);
    return text;
}

/* The first line where two reports differ (for the failure message). */
static void first_difference(const char *a, const char *b, char *out, size_t size)
{
    size_t k = 0, back = 0;
    while (a[k] && a[k] == b[k])
        k++;
    while (back < k && back < 40 && a[k - back - 1] != '\n')
        back++;
    snprintf(out, size, "at byte %zu: '%.120s' vs '%.120s'", k, a + k - back, b + k - back);
}

/* rg2_check's report is the same, byte for byte in text and JSON, on 1, 2, 3 and 8 threads
 * (different chunkings of the seams and patches: the partial reports' merge must keep the
 * serial order's first worst sample, first fold, counts and ranges). o NULL: the defaults. */
static void same_on_threads(const rg2_surface *surfs, int n, const rg2_shape *shapes, const char *const *labels,
                            int ns, const rg2_check_opts *o, const char *name)
{
    static const int threads[] = {2, 3, 8};
    rg2_check_opts def;
    if (!o) {
        rg2_check_opts_default(&def);
        o = &def;
    }
    char *j1, *t1 = report_text(surfs, n, shapes, labels, ns, o, 1, &j1);
    int same = t1 && j1;
    for (size_t k = 0; k < sizeof threads / sizeof *threads && t1 && j1; k++) {
        char *jt, *tt = report_text(surfs, n, shapes, labels, ns, o, threads[k], &jt);
        char where[400] = "";
        if (tt && strcmp(t1, tt))
            first_difference(t1, tt, where, sizeof where);
        else if (jt && strcmp(j1, jt))
            first_difference(j1, jt, where, sizeof where);
        CHECK(tt && jt && !where[0], "%s: the report on %d threads differs from 1 thread's %s", name, threads[k],
              where);
        same &= tt && jt && !where[0];
        free(tt);
        free(jt);
    }
    if (same)
        printf("%s: the same report on 1, 2, 3 and 8 threads (%zu bytes of text, %zu of JSON)\n", name, strlen(t1),
               strlen(j1));
    free(t1);
    free(j1);
}

static void harness_agreement(void)
{
    rg2_mesh m;
    rg2_surface s, x;
    rg2_error err;
    CHECK_OK(scene_revolve(3.0, 1.0, 8, 6, 1, 0, 0, &m, &s, &err), &err);
    agrees_with_harness(&s, "torus");
    CHECK_OK(xmix_copy(&s, &x, &err), &err);
    agrees_with_harness(&x, "torus, mixed degrees");
    mixed_same(&s, NULL, NULL, 0, "torus");
    rg2_surface_free(&x);
    rg2_surface_free(&s);
    rg2_mesh_free(&m);
    CHECK_OK(scene_cyl_plane(1.0, 1.5, 2.0, &s, &err), &err);
    agrees_with_harness(&s, "cylinder+plane (G1)");
    rg2_surface_free(&s);
    /* a random mesh, open x closed, seed printed */
    rg2t_rng r;
    rg2t_seed(&r, 4711);
    printf("random mesh seed 4711\n");
    CHECK_OK(rg2_mesh_init(&m, 7, 5, 0, 1, &err), &err);
    for (int i = 0; i < 7; i++)
        for (int j = 0; j < 5; j++) {
            double *p = rg2_mesh_at(&m, i, j), W = rg2t_uniform(&r, 0.7, 1.4);
            for (int k = 0; k < 3; k++)
                p[k] = W * (rg2t_uniform(&r, -1, 1) + (k == 0 ? i : 0));
            p[3] = W;
        }
    CHECK_OK(rg2_surface_build(&m, &s, &err), &err);
    agrees_with_harness(&s, "random");
    mixed_same(&s, NULL, NULL, 0, "random");
    s.patch[1 * s.nv + 2].h[2][1][2] += 0.03;
    agrees_with_harness(&s, "random, broken");
    CHECK_OK(xmix_copy(&s, &x, &err), &err);
    agrees_with_harness(&x, "random, broken, mixed degrees");
    mixed_same(&s, NULL, NULL, 0, "random, broken");
    rg2_surface_free(&x);
    rg2_surface_free(&s);
    rg2_mesh_free(&m);
}

/* The surface of torus shape sh over 8 x 6 equal arcs, every patch tagged with shape 0 (by
 * rg2_shape_surface, as rg2.h says: the tags were NULL, and a check against the shape found no
 * exact patch). */
static void torus_8x6(const rg2_shape *sh, rg2_surface *s)
{
    double au[9], av[7];
    rg2_partition pu, pv;
    rg2_error err;
    CHECK_OK(rg2_partition_equal(&pu, RG2_PART_ANGLES, 1, 0, 0, 8, au, 9, &err), &err);
    CHECK_OK(rg2_partition_equal(&pv, RG2_PART_ANGLES, 1, 0, 0, 6, av, 7, &err), &err);
    CHECK_OK(rg2_shape_surface(sh, &pu, &pv, s, NULL, &err), &err);
    int zero = s->tag != NULL;
    for (int k = 0; zero && k < s->nu * s->nv; k++)
        zero = s->tag[k] == 0;
    CHECK(zero, "rg2_shape_surface: every patch tagged 0");
}

/* Column (0-based) where the n-th run of non-blank characters of line starts (from 0) or ends
 * (one past it); -1 if the line has fewer runs. */
static int run_col(const char *line, int n, int end)
{
    int k = 0, run = -1, col = 0; /* col: the characters before byte k (UTF-8 labels) */
    while (line[k] && line[k] != '\n') {
        if (line[k] != ' ' && (k == 0 || line[k - 1] == ' ') && ++run == n && !end)
            return col;
        if (line[k] != ' ' && (line[k + 1] == ' ' || line[k + 1] == '\n' || !line[k + 1]) && run == n && end)
            return col + (((unsigned char)line[k] & 0xC0) != 0x80);
        col += ((unsigned char)line[k] & 0xC0) != 0x80;
        k++;
    }
    return -1;
}

/* The text report's table of exact pieces lines up under its header: the patch counts and
 * residuals end where "patches" and "worst residual" end, the verdicts and places start where
 * "verdict" and "where" start, and every label is whole, for labels shorter and longer than the
 * 24-character column. */
/* The NO EXACT PATCH line says why: every patch a transition, or (a shape surface checked with
 * no shapes given) tags beyond the shapes given; it said "every patch is a transition" of a
 * surface with 0 transitions. With the shape given, the same surface is exact. */
static void no_exact_patch_reason(void)
{
    rg2_shape sh;
    rg2_shape_init(&sh, RG2_SHAPE_TORUS);
    rg2_surface s;
    torus_8x6(&sh, &s);
    rg2_check_opts o;
    rg2_check_opts_default(&o);
    o.seam_samples = 2;
    o.patch_samples = 2;
    for (int n = 0; n < 2; n++) {
        char *json = NULL, *txt = report_text(&s, 1, &sh, NULL, n, &o, 1, &json);
        const char *line = txt ? strstr(txt, "NO EXACT PATCH") : NULL;
        if (n == 0)
            CHECK(line && strstr(line, "no patch lies on a shape given (0 given; 48 patches tagged with a shape beyond "
                                       "them): the exact promise FAILS") &&
                      !strstr(txt, "every patch is a transition"),
                  "no shapes given: %s", txt ? txt : "(no report)");
        else
            CHECK(txt && !line && strstr(txt, "48 exact"), "the shape given: %s", txt ? txt : "(no report)");
        free(txt);
        free(json);
    }
    rg2_surface_free(&s);
}

static void shape_table_layout(void)
{
    rg2_shape sh[2];
    rg2_shape_init(&sh[0], RG2_SHAPE_TORUS);
    rg2_shape_init(&sh[1], RG2_SHAPE_SPHERE);
    rg2_surface s;
    torus_8x6(&sh[0], &s);
    static const char *const sets[4][2] = {{"ring", "ball"},
                                           {"ring", "a_label_of_forty_characters_1234567890ab"},
                                           {"ring", "kugel_\xc3\xa4"}, /* UTF-8: columns count characters */
                                           {"ring", "kugel_\xc3\xa4\xc3\xb6\xc3\xbc\xc3\xa4\xc3\xb6\xc3\xbc\xc3\xa4\xc3\xb6\xc3\xbc"
                                                    "\xc3\xa4\xc3\xb6\xc3\xbc\xc3\xa4\xc3\xb6\xc3\xbc\xc3\xa4\xc3\xb6\xc3\xbc"}};
    rg2_check_opts o;
    rg2_check_opts_default(&o);
    o.seam_samples = 2;
    o.patch_samples = 2;
    for (int set = 0; set < 4 && s.tag; set++) {
        char *json = NULL, *txt = report_text(&s, 1, sh, sets[set], 2, &o, 1, &json);
        const char *head = txt ? strstr(txt, "exact pieces") : NULL;
        CHECK(head != NULL, "text report without the table of exact pieces");
        if (head) {
            /* header runs: "exact" "pieces" "patches" "worst" "residual" "verdict" "where" */
            int h_pat = run_col(head, 2, 1), h_res = run_col(head, 4, 1), h_ver = run_col(head, 5, 0),
                h_whr = run_col(head, 6, 0);
            const char *row = strchr(head, '\n');
            for (int k = 0; k < 2 && row; k++, row = strchr(row + 1, '\n')) {
                row++;
                char want[64];
                snprintf(want, sizeof want, "%2d %s ", k, sets[set][k]);
                CHECK(strncmp(row + 2, want, strlen(want)) == 0, "row %d does not hold the whole label '%s': %.80s", k,
                      sets[set][k], row);
                /* row runs: index, label, count, residual, verdict, where... (shape 1 has no patch: "-") */
                int r_pat = run_col(row, 2, 1), r_res = run_col(row, 3, 1), r_ver = run_col(row, 4, 0),
                    r_whr = run_col(row, 5, 0);
                CHECK(r_pat == h_pat && r_res == h_res && r_ver == h_ver && (k == 1 || r_whr == h_whr),
                      "labels %s, %s: row %d's columns end/start at %d %d %d %d, the header's at %d %d %d %d", sets[set][0],
                      sets[set][1], k, r_pat, r_res, r_ver, r_whr, h_pat, h_res, h_ver, h_whr);
            }
        }
        free(txt);
        free(json);
    }
    printf("check report: the table of exact pieces lines up under its header for labels of 4 and 40 characters, "
           "and of 7 and 24 characters in UTF-8\n");
    rg2_surface_free(&s);
}

/* A torus from the shapes module, tagged 0: exact, G2, passes every promise; a moved control
 * point breaks exactness and the continuity of that patch's seams. */
static void exact_and_broken(int mixed)
{
    rg2_shape sh;
    rg2_shape_init(&sh, RG2_SHAPE_TORUS);
    sh.param[0] = 3;
    sh.param[1] = 1;
    double M[16];
    rg2_xform_rotate(M, 1, 2, 3, 0.7);
    memcpy(sh.xform, M, sizeof M);
    rg2_error err;
    rg2_surface s;
    torus_8x6(&sh, &s);
    if (mixed) {
        CHECK_OK(xmix_elevate(&s, &err), &err);
        printf("torus (tilted) with %d of %d patches elevated:\n", xmix_count(&s), s.nu * s.nv);
    }
    const char *labels[1] = {"ring"};
    rg2_check_opts o;
    rg2_check_opts_default(&o);
    rg2_check_report r;
    CHECK_OK(rg2_check(&s, 1, &sh, labels, 1, &o, &r, &err), &err);
    printf("torus (tilted): residual %.2e at %s; G0 %.2e, G1 %.2e, G2 %.2e; weights [%.4g, %.4g]; H [%.4g, %.4g]\n",
           r.worst_residual, r.shapes[0].where, r.g0.value, r.g1.value, r.g2.value, r.wmin, r.wmax, r.Hmin, r.Hmax);
    CHECK(r.patches == 48 && r.exact_patches == 48 && r.transitions == 0 && r.shapes[0].patches == 48,
          "patch counts %d/%d/%d", r.patches, r.exact_patches, r.transitions);
    CHECK(r.worst_residual <= 1e-13, "torus patches on the torus: %.3g", r.worst_residual);
    CHECK(rg2_check_failures(&r, RG2_REQUIRE_G2 | RG2_REQUIRE_EXACT | RG2_REQUIRE_WEIGHTS) == 0,
          "every promise holds: %#x", rg2_check_failures(&r, RG2_REQUIRE_G2 | RG2_REQUIRE_EXACT | RG2_REQUIRE_WEIGHTS));
    /* torus curvature: k1 = 1 / r on the tube (in magnitude), H between the outer and inner
     * values (R + 2 r cos v) / (2 r (R + r cos v)) */
    double Hout = (3.0 + 2.0) / (2.0 * 4.0), Hin = (3.0 - 2.0) / (2.0 * 2.0);
    CHECK(fabs(fmax(fabs(r.Hmin), fabs(r.Hmax)) - Hout) < 1e-9 && fabs(fmin(fabs(r.Hmin), fabs(r.Hmax)) - Hin) < 1e-9,
          "H range [%.12g, %.12g] vs torus %.12g, %.12g", r.Hmin, r.Hmax, Hout, Hin);
    char *txt = NULL;
    CHECK_OK(rg2_check_format(&r, 0, &txt, &err), &err);
    CHECK(txt && strstr(txt, "ring") && strstr(txt, "G2 curvature jump") && !strstr(txt, "FAIL"), "text:\n%s", txt);
    if (txt)
        fputs(txt, stdout);
    free(txt);
    /* the JSON curvature ranges are the torus's (R = 3, r = 1; the samples include v = 0 and
     * v = pi): K = cos v / (R + cos v) in [-1/2, 1/4]; |H| between Hin and Hout; principal
     * curvatures +-1 on the tube and cos v / (R + cos v), so {kmin, kmax} = {-1/2, 1} or
     * {-1, 1/2} with the orientation */
    char *js0 = NULL;
    CHECK_OK(rg2_check_format(&r, 1, &js0, &err), &err);
    cJSON *j0 = js0 ? cJSON_Parse(js0) : NULL;
    cJSON *jk = cJSON_GetObjectItem(j0, "principal_curvature"), *jh = cJSON_GetObjectItem(j0, "mean_curvature");
    cJSON *jg = cJSON_GetObjectItem(j0, "gauss_curvature");
    CHECK(cJSON_GetArraySize(jk) == 2 && cJSON_GetArraySize(jh) == 2 && cJSON_GetArraySize(jg) == 2,
          "JSON curvature ranges: two numbers each");
    if (cJSON_GetArraySize(jk) == 2 && cJSON_GetArraySize(jh) == 2 && cJSON_GetArraySize(jg) == 2) {
        double k0 = cJSON_GetArrayItem(jk, 0)->valuedouble, k1 = cJSON_GetArrayItem(jk, 1)->valuedouble;
        double h0 = cJSON_GetArrayItem(jh, 0)->valuedouble, h1 = cJSON_GetArrayItem(jh, 1)->valuedouble;
        double g0 = cJSON_GetArrayItem(jg, 0)->valuedouble, g1 = cJSON_GetArrayItem(jg, 1)->valuedouble;
        double kbig = fmax(fabs(k0), fabs(k1)), ksmall = fmin(fabs(k0), fabs(k1));
        CHECK(fabs(g0 + 0.5) < 1e-9 && fabs(g1 - 0.25) < 1e-9, "JSON K range [%.12g, %.12g] vs torus [-1/2, 1/4]", g0,
              g1);
        CHECK(fabs(fmax(fabs(h0), fabs(h1)) - Hout) < 1e-9 && fabs(fmin(fabs(h0), fabs(h1)) - Hin) < 1e-9,
              "JSON H range [%.12g, %.12g] vs torus %.12g, %.12g", h0, h1, Hout, Hin);
        CHECK(k0 < 0 && k1 > 0 && fabs(kbig - 1) < 1e-9 && fabs(ksmall - 0.5) < 1e-9,
              "JSON k range [%.12g, %.12g] vs torus {-1/2, 1} or {-1, 1/2}", k0, k1);
    }
    cJSON_Delete(j0);
    free(js0);
    rg2_check_report_free(&r);

    /* an inner control point of patch (3, 2) moved: every inner point sits next to an edge, so
     * a seam of that patch loses G1 (and G2); positions still meet */
    double *h = rg2_surface_xpatch(&s, 3, 2) ? s.xp[3 * s.nv + 2].h[2][1] : rg2_surface_patch(&s, 3, 2)->h[2][1];
    CHECK(!mixed || rg2_surface_xpatch(&s, 3, 2), "patch (3,2) of higher degree in the mixed torus");
    for (int k = 0; k < 3; k++)
        h[k] += 0.02 * h[3];
    CHECK_OK(rg2_check(&s, 1, &sh, labels, 1, &o, &r, &err), &err);
    unsigned f = rg2_check_failures(&r, RG2_REQUIRE_G0 | RG2_REQUIRE_G1 | RG2_REQUIRE_G2 | RG2_REQUIRE_EXACT);
    printf("moved point: G0 %.2e, G1 %.2e, G2 %.2e at surface %d %c seam (%d,%d)|(%d,%d); residual %.2e; "
           "failures %#x\n",
           r.g0.value, r.g1.value, r.g2.value, r.g2.surf, r.g2.seam_dir ? 'v' : 'u', r.g2.pi, r.g2.pj, r.g2.qi,
           r.g2.qj, r.worst_residual, f);
    CHECK(f == (RG2_REQUIRE_G1 | RG2_REQUIRE_G2 | RG2_REQUIRE_EXACT), "G1, G2 and exactness fail, G0 holds: %#x", f);
    int at32 = (r.g2.pi == 3 && r.g2.pj == 2) || (r.g2.qi == 3 && r.g2.qj == 2);
    int g1at32 = (r.g1.pi == 3 && r.g1.pj == 2) || (r.g1.qi == 3 && r.g1.qj == 2);
    CHECK(r.g2.value > 1e-3 && r.g1.value > 1e-3 && at32 && g1at32, "worst gaps %.3g, %.3g located at patch (3,2)",
          r.g1.value, r.g2.value);
    CHECK(strstr(r.shapes[0].where, "patch (3,2)") != NULL, "worst residual located: %s", r.shapes[0].where);
    char *js = NULL;
    CHECK_OK(rg2_check_format(&r, 1, &js, &err), &err);
    cJSON *j = js ? cJSON_Parse(js) : NULL;
    CHECK(j != NULL, "JSON parses");
    if (j) {
        cJSON *g2 = cJSON_GetObjectItem(j, "g2_curvature_jump");
        CHECK(cJSON_IsFalse(cJSON_GetObjectItem(j, "g2")) && cJSON_IsFalse(cJSON_GetObjectItem(j, "exact")) &&
                  g2 && fabs(cJSON_GetObjectItem(g2, "value")->valuedouble - r.g2.value) <= 1e-12 * r.g2.value,
              "JSON reports the failures");
        cJSON *shapes = cJSON_GetObjectItem(j, "shapes");
        CHECK(cJSON_GetArraySize(shapes) == 1 &&
                  !strcmp(cJSON_GetObjectItem(cJSON_GetArrayItem(shapes, 0), "label")->valuestring, "ring"),
              "JSON shape label");
        cJSON_Delete(j);
    }
    free(js);
    rg2_check_report_free(&r);

    /* a tag pointing outside the shape list is an exactness failure */
    s.tag[0] = 5;
    CHECK_OK(rg2_check(&s, 1, &sh, labels, 1, &o, &r, &err), &err);
    CHECK(r.untagged_bad == 1 && (rg2_check_failures(&r, RG2_REQUIRE_EXACT) & RG2_REQUIRE_EXACT), "unknown tag: %d",
          r.untagged_bad);
    rg2_check_report_free(&r);
    free(s.tag);
    s.tag = NULL;
    rg2_surface_free(&s);
}

/* The report's size and weights against the control points read directly: size is the
 * diagonal of the box of all affine control points (positive weights), wmin / wmax the extreme
 * homogeneous weights. One control weight made negative (-1e-2, an inner point: the patch's
 * denominator stays positive at every sample) fails the weights promise on its own. */
static void size_and_weights(void)
{
    rg2_mesh m;
    rg2_surface s;
    rg2_error err;
    CHECK_OK(rg2t_torus(3, 1, 8, 6, &m, &s, &err), &err);
    for (int round = 0; round < 2; round++) {
        double lo[3] = {INFINITY, INFINITY, INFINITY}, hi[3] = {-INFINITY, -INFINITY, -INFINITY};
        double wlo = INFINITY, whi = -INFINITY;
        for (int k = 0; k < s.nu * s.nv; k++)
            for (int a = 0; a < 4; a++)
                for (int b = 0; b < 4; b++) {
                    const double *h = s.patch[k].h[a][b];
                    wlo = fmin(wlo, h[3]);
                    whi = fmax(whi, h[3]);
                    for (int d = 0; d < 3 && h[3] > 0; d++) {
                        lo[d] = fmin(lo[d], h[d] / h[3]);
                        hi[d] = fmax(hi[d], h[d] / h[3]);
                    }
                }
        double diag = sqrt((hi[0] - lo[0]) * (hi[0] - lo[0]) + (hi[1] - lo[1]) * (hi[1] - lo[1]) +
                           (hi[2] - lo[2]) * (hi[2] - lo[2]));
        rg2_check_report r;
        CHECK_OK(rg2_check(&s, 1, NULL, NULL, 0, NULL, &r, &err), &err);
        unsigned f = rg2_check_failures(&r, RG2_REQUIRE_WEIGHTS);
        printf("torus 8 x 6%s: size %.17g (control box %.17g), weights [%.6g, %.6g] ([%.6g, %.6g]), at samples "
               "%.6g, weight failure %d\n",
               round ? " with a control weight -1e-2" : "", r.size, diag, r.wmin, r.wmax, wlo, whi, r.eval_wmin,
               f != 0);
        CHECK(rel(r.size, diag) <= 1e-15, "size %.17g vs control box diagonal %.17g", r.size, diag);
        CHECK(r.wmin == wlo && r.wmax == whi, "weights [%.17g, %.17g] vs control points [%.17g, %.17g]", r.wmin,
              r.wmax, wlo, whi);
        CHECK(r.eval_wmin > 0 && f == (round ? RG2_REQUIRE_WEIGHTS : 0u),
              "round %d: denominators at the samples >= %.3g, weight failure %#x", round, r.eval_wmin, f);
        rg2_check_report_free(&r);
        s.patch[13].h[1][2][3] = -1e-2;
    }
    rg2_surface_free(&s);
    rg2_mesh_free(&m);
}

/* The G1 cylinder + plane: G1 holds, G2 fails at its one seam by the jump 1/R -> 0. */
static void g1_join(void)
{
    rg2_surface s;
    rg2_error err;
    CHECK_OK(scene_cyl_plane(2.0, 1.5, 2.0, &s, &err), &err);
    rg2_check_report r;
    CHECK_OK(rg2_check(&s, 1, NULL, NULL, 0, NULL, &r, &err), &err);
    unsigned f = rg2_check_failures(&r, RG2_REQUIRE_G1 | RG2_REQUIRE_G2);
    /* normal curvature across the seam: 1/R on the cylinder, 0 on the plane; relative to
     * max(|k|, 1/size) = 1/R: jump exactly 1 */
    printf("cylinder+plane: G0 %.2e, G1 %.2e, G2 %.6f, k [%g, %g]\n", r.g0.value, r.g1.value, r.g2.value, r.kmin, r.kmax);
    CHECK(f == RG2_REQUIRE_G2, "G2 fails, G1 holds: %#x", f);
    CHECK(fabs(r.g2.value - 1.0) < 1e-12, "relative curvature jump %.17g", r.g2.value);
    CHECK(fabs(r.kmax - 0.5) < 1e-12 || fabs(r.kmin + 0.5) < 1e-12, "cylinder curvature 1/R in [%g, %g]", r.kmin,
          r.kmax);
    rg2_check_report_free(&r);
    CHECK(rg2_check(&s, 0, NULL, NULL, 0, NULL, &r, &err) == RG2_EINVAL && strstr(err.msg, "no surfaces"), "%s",
          err.msg);
    /* the other refused inputs, each by its message */
    CHECK(rg2_check(&s, 1, NULL, NULL, 0, NULL, NULL, &err) == RG2_EINVAL && !strcmp(err.msg, "check: no report"),
          "%s", err.msg);
    CHECK(rg2_check(&s, 1, NULL, NULL, 2, NULL, &r, &err) == RG2_EINVAL &&
              !strcmp(err.msg, "check: 2 shapes without a shape list"),
          "%s", err.msg);
    rg2_check_opts o;
    rg2_check_opts_default(&o);
    o.seam_samples = 10001;
    CHECK(rg2_check(&s, 1, NULL, NULL, 0, &o, &r, &err) == RG2_EINVAL &&
              !strcmp(err.msg, "check: samples 10001 per seam / 12 per patch outside 1..10000 / 1..1000"),
          "%s", err.msg);
    const double bad_tol[3] = {NAN, -1e-9, INFINITY};
    for (int k = 0; k < 3; k++) {
        char want[96];
        rg2_check_opts_default(&o);
        double *t = k == 0 ? &o.tol_g0 : k == 1 ? &o.tol_g2 : &o.tol_exact;
        *t = bad_tol[k];
        snprintf(want, sizeof want, "check: %s = %g, must be a finite number >= 0",
                 k == 0 ? "tol_g0" : k == 1 ? "tol_g2" : "tol_exact", bad_tol[k]);
        CHECK(rg2_check(&s, 1, NULL, NULL, 0, &o, &r, &err) == RG2_EINVAL && !strcmp(err.msg, want), "%s", err.msg);
    }
    rg2_check_opts_default(&o);
    o.patch_samples = 0;
    CHECK(rg2_check(&s, 1, NULL, NULL, 0, &o, &r, &err) == RG2_EINVAL && strstr(err.msg, "per seam / 0 per patch"),
          "%s", err.msg);
    rg2_surface bad = s;
    bad.nv = 0;
    CHECK(rg2_check(&bad, 1, NULL, NULL, 0, NULL, &r, &err) == RG2_EINVAL && !strcmp(err.msg, "check: surface 0 has no patches"),
          "%s", err.msg);
    bad = s; /* either count: nu = 0 would make nu - 1 = -1 rows of u seams */
    bad.nu = 0;
    CHECK(rg2_check(&bad, 1, NULL, NULL, 0, NULL, &r, &err) == RG2_EINVAL && !strcmp(err.msg, "check: surface 0 has no patches"),
          "nu = 0: %s", err.msg);
    bad = s;
    bad.bv = NULL;
    CHECK(rg2_check(&bad, 1, NULL, NULL, 0, NULL, &r, &err) == RG2_EINVAL &&
              !strcmp(err.msg, "check: surface 0 has no junction scalars"),
          "%s", err.msg);
    /* past RG2_MAX_CHECK_SAMPLES samples (the report's int counts): refused before any work. A
       closed 300 x 300 torus has 2 x 300 x 300 seams and 300 x 300 patches */
    rg2_surface big;
    CHECK_OK(rg2t_torus(3.0, 1.0, 300, 300, NULL, &big, &err), &err);
    rg2_check_opts_default(&o);
    o.seam_samples = 10000;
    char want[160];
    snprintf(want, sizeof want, "check: %.0f seam samples (10001 per seam) exceed the limit of %d: fewer samples per "
             "seam (seam_samples; rg2 check --samples)", 2.0 * 300 * 300 * 10001, RG2_MAX_CHECK_SAMPLES);
    CHECK(rg2_check(&big, 1, NULL, NULL, 0, &o, &r, &err) == RG2_ELIMIT && !strcmp(err.msg, want), "%s", err.msg);
    rg2_check_opts_default(&o);
    o.patch_samples = 1000;
    snprintf(want, sizeof want, "check: %.0f patch samples (1001 x 1001 per patch) exceed the limit of %d: fewer "
             "samples per patch (patch_samples)", 300.0 * 300 * 1001 * 1001, RG2_MAX_CHECK_SAMPLES);
    CHECK(rg2_check(&big, 1, NULL, NULL, 0, &o, &r, &err) == RG2_ELIMIT && !strcmp(err.msg, want), "%s", err.msg);
    /* two surfaces: the totals add up (5001 samples per seam: 900180000 per torus, under the limit) */
    rg2_surface two[2] = {big, big};
    rg2_check_opts_default(&o);
    o.seam_samples = 5000;
    snprintf(want, sizeof want, "check: %.0f seam samples", 2 * 2.0 * 300 * 300 * 5001);
    CHECK(rg2_check(two, 2, NULL, NULL, 0, &o, &r, &err) == RG2_ELIMIT && strstr(err.msg, want), "%s", err.msg);
    rg2_surface_free(&big);
    char *text = (char *)1;
    CHECK(rg2_check_format(NULL, 0, &text, &err) == RG2_EINVAL && !strcmp(err.msg, "check: nothing to format"), "%s",
          err.msg);
    rg2_surface_free(&s);
}

static char *read_text(const char *path)
{
    FILE *f = fopen(path, "rb");
    if (!f)
        return NULL;
    fseek(f, 0, SEEK_END);
    long n = ftell(f);
    fseek(f, 0, SEEK_SET);
    char *t = n >= 0 ? malloc((size_t)n + 1) : NULL;
    if (t && fread(t, 1, (size_t)n, f) != (size_t)n) {
        free(t);
        t = NULL;
    }
    if (t)
        t[n] = '\0';
    fclose(f);
    return t;
}

/* Every example design: per output surface, the check's patch, exact-per-shape and transition
 * counts equal the design file's own "expect" block, and every surface is G2, exact and has
 * positive weights. */
/* The shapes of a loaded design as one array for rg2_check (calloc'd, ns + 1 entries). */
static rg2_shape *design_shapes(const rg2_design *d)
{
    int ns = rg2_design_num_shapes(d);
    rg2_shape *shapes = calloc((size_t)ns + 1, sizeof *shapes);
    for (int k = 0; k < ns; k++)
        shapes[k] = *rg2_design_shape(d, k);
    return shapes;
}

static void check_example(const char *path)
{
    rg2_design *d = NULL;
    rg2_error err;
    CHECK_OK(rg2_design_load(path, &d, &err), &err);
    char *txt = read_text(path);
    cJSON *j = txt ? cJSON_Parse(txt) : NULL;
    cJSON *exp = cJSON_GetObjectItem(cJSON_GetObjectItem(j, "expect"), "surfaces");
    if (!d || !exp) {
        CHECK(d && exp, "%s: loads and has an expect block", path);
        goto out;
    }
    int ns = rg2_design_num_shapes(d), n = rg2_design_num_surfaces(d);
    rg2_shape *shapes = calloc((size_t)ns + 1, sizeof *shapes);
    const char **labels = calloc((size_t)ns + 1, sizeof *labels);
    for (int k = 0; k < ns; k++) {
        shapes[k] = *rg2_design_shape(d, k);
        labels[k] = rg2_design_shape_label(d, k);
    }
    CHECK(cJSON_GetArraySize(exp) == n, "%s: %d surfaces, expect lists %d", path, n, cJSON_GetArraySize(exp));
    double worst_res = 0, worst_g2 = 0;
    for (int s = 0; s < n && s < cJSON_GetArraySize(exp); s++) {
        cJSON *e = cJSON_GetArrayItem(exp, s);
        rg2_check_report r;
        CHECK_OK(rg2_check(rg2_design_surface(d, s), 1, shapes, labels, ns, NULL, &r, &err), &err);
        CHECK(r.patches == cJSON_GetObjectItem(e, "patches")->valueint &&
                  r.transitions == cJSON_GetObjectItem(e, "transition")->valueint,
              "%s surface %d: %d patches, %d transitions", path, s, r.patches, r.transitions);
        int listed = 0;
        cJSON *ex;
        cJSON_ArrayForEach(ex, cJSON_GetObjectItem(e, "exact"))
        {
            int found = 0;
            for (int k = 0; k < ns; k++)
                if (!strcmp(r.shapes[k].label, ex->string)) {
                    found = 1;
                    listed += r.shapes[k].patches;
                    CHECK(r.shapes[k].patches == ex->valueint, "%s surface %d: %s has %d exact patches, expected %d",
                          path, s, ex->string, r.shapes[k].patches, ex->valueint);
                }
            CHECK(found, "%s: shape %s in the report", path, ex->string);
        }
        CHECK(listed == r.exact_patches, "%s surface %d: %d exact patches, %d listed", path, s, r.exact_patches, listed);
        CHECK(r.folds == 0 && r.singular == 0, "%s surface %d: %d folds, %d singular samples", path, s, r.folds,
              r.singular);
        /* exactness is a promise only where something is exact (Fig. 11 keeps nothing) */
        CHECK(!rg2_check_failures(&r, RG2_REQUIRE_G2 | RG2_REQUIRE_WEIGHTS |
                                          (r.exact_patches ? RG2_REQUIRE_EXACT : 0)),
              "%s surface %d: residual %.3g, G2 %.3g at %s seam (%d,%d)|(%d,%d)", path, s, r.worst_residual,
              r.g2.value, r.g2.seam_dir ? "v" : "u", r.g2.pi, r.g2.pj, r.g2.qi, r.g2.qj);
        worst_res = fmax(worst_res, r.worst_residual);
        worst_g2 = fmax(worst_g2, r.g2.value);
        rg2_check_report_free(&r);
        char name[600];
        snprintf(name, sizeof name, "%s surface %d", path, s);
        mixed_same(rg2_design_surface(d, s), shapes, labels, ns, name);
    }
    printf("%s: %d surfaces match their expect block; residual %.2e, G2 %.2e\n", path, n, worst_res, worst_g2);
    free(shapes);
    free(labels);
out:
    cJSON_Delete(j);
    free(txt);
    rg2_design_free(d);
}

static void examples(void)
{
    char *names[64];
    int n = rg2t_example_names(names, 64);
    for (int k = 0; k < n; k++) {
        check_example(names[k]);
        free(names[k]);
    }
}

/* Pole designs at several sample counts: next to a pole the evaluator loses digits like 1/v
 * (normal) and 1/v^2 (curvature), which made the verdict depend on --samples. Every sample count
 * must pass G2, exact and weights; nothing away from a pole is left unmeasured; the samples
 * measured against their rounding bound are reported, and that bound is not vacuous (the worst
 * gap reaches a measurable fraction of it). */
static void pole_sample_counts(void)
{
    static const char *files[] = {"examples/fig9_polar_sphere.json", "examples/fig10_sphere_cylinder.json",
                                  "examples/fig11_cube_tube.json", "examples/fig12_paraboloid_hyperboloid.json",
                                  "examples/fig14_mobius.json", "examples/fig15_saddle_caps.json"};
    static const int counts[] = {16, 64, 256, 1000};
    double worst_ratio = 0;
    for (size_t f = 0; f < sizeof files / sizeof *files; f++) {
        rg2_design *d = NULL;
        rg2_error err;
        CHECK_OK(rg2_design_load(files[f], &d, &err), &err);
        if (!d)
            continue;
        int ns = rg2_design_num_shapes(d), n = rg2_design_num_surfaces(d), poles = 0;
        rg2_shape *shapes = design_shapes(d);
        for (size_t c = 0; c < sizeof counts / sizeof *counts; c++) {
            double g1 = 0, g2 = 0, r1 = 0, r2 = 0, l1 = 0, l2 = 0;
            int near = 0;
            for (int s = 0; s < n; s++) {
                rg2_check_opts o;
                rg2_check_opts_default(&o);
                o.seam_samples = counts[c];
                rg2_check_report r;
                CHECK_OK(rg2_check(rg2_design_surface(d, s), 1, shapes, NULL, ns, &o, &r, &err), &err);
                /* a surface with no exact patch (Fig. 11's tubes, a cap surface) fails the exact
                 * promise by definition: nothing on it is measured against a shape */
                unsigned fl = rg2_check_failures(&r, RG2_REQUIRE_G2 | RG2_REQUIRE_WEIGHTS |
                                                         (r.exact_patches ? RG2_REQUIRE_EXACT : 0));
                CHECK(r.exact_patches || rg2_check_failures(&r, RG2_REQUIRE_EXACT) == RG2_REQUIRE_EXACT,
                      "%s surface %d: no exact patch, yet the exact promise holds", files[f], s);
                CHECK(!fl, "%s surface %d, %d samples: failures %#x (G1 %.3g, G2 %.3g; near a pole %.3g / %.3g of "
                           "their limits; %d unmeasured)",
                      files[f], s, counts[c], fl, r.g1.value, r.g2.value, r.g1_pole.value, r.g2_pole.value,
                      r.unmeasured);
                CHECK(r.unmeasured == 0 && r.skipped == r.pole_samples + r.pole_unresolved,
                      "%s surface %d: %d unmeasured samples", files[f], s, r.unmeasured);
                CHECK(r.seam_samples == r.seams * (counts[c] + 1), "%s: %d samples on %d seams", files[f],
                      r.seam_samples, r.seams);
                poles += r.pole_samples;
                near += r.near_pole;
                g1 = fmax(g1, r.g1.value);
                g2 = fmax(g2, r.g2.value);
                r1 = fmax(r1, r.g1_pole.value);
                r2 = fmax(r2, r.g2_pole.value);
                l1 = fmax(l1, r.near_pole_tol1);
                l2 = fmax(l2, r.near_pole_tol2);
                rg2_check_report_free(&r);
            }
            if (counts[c] == 1000) {
                CHECK(near > 0, "%s: at 1000 samples some samples next to a pole need their rounding bound", files[f]);
                worst_ratio = fmax(worst_ratio, fmax(r1, r2));
            }
            printf("%s, %4d samples: G1 %.2e rad, G2 %.2e; %d next to a pole, limits <= %.1e rad / %.1e, gap / limit "
                   "<= %.3f / %.3f\n",
                   files[f], counts[c], g1, g2, near, l1, l2, r1, r2);
        }
        CHECK(poles > 0, "%s has pole samples", files[f]);
        free(shapes);
        rg2_design_free(d);
    }
    /* a bound 1000 times above every measured rounding gap would hide real defects */
    CHECK(worst_ratio >= 1e-3 && worst_ratio <= 1.0, "worst near-pole gap / rounding bound %.3g", worst_ratio);
    printf("near-pole samples: worst gap / rounding bound %.3f\n", worst_ratio);
}

/* t = s with u and v swapped: patch (i, j) of t is patch (j, i) of s transposed (h[r][s] ->
 * h[s][r]), the junction scalars, closedness and tags likewise. Bi-3 surfaces only. */
static void transpose_surface(const rg2_surface *s, rg2_surface *t)
{
    rg2_error err;
    CHECK(s->xp == NULL, "transpose_surface: bi-3 surfaces only");
    CHECK_OK(rg2_surface_copy(s, t, &err), &err);
    t->nu = s->nv, t->nv = s->nu, t->closed_u = s->closed_v, t->closed_v = s->closed_u;
    double *b = t->bu, *g = t->gu;
    t->bu = t->bv, t->gu = t->gv, t->bv = b, t->gv = g;
    for (int i = 0; i < t->nu; i++)
        for (int j = 0; j < t->nv; j++) {
            const rg2_patch *P = &s->patch[j * s->nv + i];
            for (int r = 0; r < 4; r++)
                for (int c = 0; c < 4; c++)
                    memcpy(t->patch[i * t->nv + j].h[r][c], P->h[c][r], sizeof P->h[c][r]);
            if (t->tag && s->tag)
                t->tag[i * t->nv + j] = s->tag[j * s->nv + i];
        }
}

/* The worst gap names its seam: the cylinder + plane's one seam joins patches (0,0) and (1,0)
 * in u (seam_dir 0); transposed, (0,0) and (0,1) in v (seam_dir 1). Either way the relative
 * curvature jump is 1 (1/R against the plane's 0) and the point lies on the seam line x = z = 0. */
static void seam_direction_reported(void)
{
    rg2_surface s, t;
    rg2_error err;
    CHECK_OK(scene_cyl_plane(2.0, 1.5, 2.0, &s, &err), &err);
    transpose_surface(&s, &t);
    for (int dir = 0; dir < 2; dir++) {
        rg2_check_report r;
        CHECK_OK(rg2_check(dir ? &t : &s, 1, NULL, NULL, 0, NULL, &r, &err), &err);
        const rg2_check_gap *g = &r.g2;
        printf("cylinder+plane%s: G2 %.6f at seam_dir %d (%d,%d)|(%d,%d) t=%.3g p=(%.3g, %.3g, %.3g)\n",
               dir ? " transposed" : "", g->value, g->seam_dir, g->pi, g->pj, g->qi, g->qj, g->t, g->p[0], g->p[1],
               g->p[2]);
        CHECK(fabs(g->value - 1.0) < 1e-12 && g->surf == 0 && g->seam_dir == dir && g->pi == 0 && g->pj == 0 &&
                  g->qi == 1 - dir && g->qj == dir && g->t >= 0 && g->t <= 1 && fabs(g->p[0]) < 1e-15 &&
                  fabs(g->p[2]) < 1e-15 && fabs(g->p[dir ? 0 : 1] - 2.0 * g->t) < 1e-14,
              "%s: G2 %.17g at surface %d seam_dir %d (%d,%d)|(%d,%d), t %.3g, p (%.3g, %.3g, %.3g)",
              dir ? "transposed" : "cylinder+plane", g->value, g->surf, g->seam_dir, g->pi, g->pj, g->qi, g->qj,
              g->t, g->p[0], g->p[1], g->p[2]);
        rg2_check_report_free(&r);
    }
    rg2_surface_free(&t);
    rg2_surface_free(&s);
}

/* Poles on u sides: the capped sphere of Fig. 9 with u and v swapped has its poles on the u = 0
 * and u = 1 sides of its patches. Its report must count the same seams, pole samples and samples
 * measured against their rounding bound next to a pole as the original's (the same seams, met
 * from the other direction), and pass G2 at 256 samples per seam: a sample next to a u-side
 * pole taken for one far from it fails there. */
static void poles_on_u_sides(void)
{
    rg2_design *d = NULL;
    rg2_error err;
    CHECK_OK(rg2_design_load("examples/fig9_polar_sphere.json", &d, &err), &err);
    if (!d)
        return;
    rg2_shape *shapes = design_shapes(d);
    int ns = rg2_design_num_shapes(d), near = 0;
    for (int s = 0; s < rg2_design_num_surfaces(d); s++) {
        rg2_surface tr;
        transpose_surface(rg2_design_surface(d, s), &tr);
        rg2_check_opts o;
        rg2_check_opts_default(&o);
        o.seam_samples = 256; /* 416 samples next to the poles; 1000 gave 1674, 4 times slower */
        rg2_check_report a, b;
        CHECK_OK(rg2_check(rg2_design_surface(d, s), 1, shapes, NULL, ns, &o, &a, &err), &err);
        CHECK_OK(rg2_check(&tr, 1, shapes, NULL, ns, &o, &b, &err), &err);
        unsigned fa = rg2_check_failures(&a, RG2_REQUIRE_G2 | RG2_REQUIRE_EXACT),
                 fb = rg2_check_failures(&b, RG2_REQUIRE_G2 | RG2_REQUIRE_EXACT);
        CHECK(!fa && !fb, "fig9 surface %d: failures %#x, transposed %#x (G1 %.3g, G2 %.3g; next to a pole %.3g / %.3g "
                          "of their limits)", s, fa, fb, b.g1.value, b.g2.value, b.g1_pole.value, b.g2_pole.value);
        CHECK(a.seams == b.seams && a.pole_samples == b.pole_samples && a.near_pole == b.near_pole &&
                  a.pole_unresolved == b.pole_unresolved && a.ill_conditioned == b.ill_conditioned,
              "fig9 surface %d: seams %d/%d, pole samples %d/%d, next to a pole %d/%d, unresolved %d/%d, "
              "ill-conditioned %d/%d (original / transposed)", s, a.seams, b.seams, a.pole_samples, b.pole_samples,
              a.near_pole, b.near_pole, a.pole_unresolved, b.pole_unresolved, a.ill_conditioned, b.ill_conditioned);
        near += b.near_pole;
        rg2_check_report_free(&a);
        rg2_check_report_free(&b);
        rg2_surface_free(&tr);
    }
    CHECK(near > 0, "the transposed fig9 surfaces have samples next to a u-side pole measured against their bound");
    printf("poles on u sides (fig9 transposed): %d samples next to a pole, reports as the original's\n", near);
    free(shapes);
    rg2_design_free(d);
}

/* The capped sphere of Fig. 9 (its last surface: the south pole on the v = 0 sides of patches
 * (i, 0)) copied into s; the design (the caller frees it), NULL if it did not load. */
static rg2_design *fig9_cap(rg2_surface *s)
{
    rg2_design *d = NULL;
    rg2_error err;
    CHECK_OK(rg2_design_load("examples/fig9_polar_sphere.json", &d, &err), &err);
    if (d)
        CHECK_OK(rg2_surface_copy(rg2_design_surface(d, rg2_design_num_surfaces(d) - 1), s, &err), &err);
    return d;
}

/* A defect next to a pole is not hidden by the near-pole limits: the control point next to the
 * pole of one fan patch of the Fig. 9 sphere moved by 1e-6 fails G1 and G2 at 16 and at 1000
 * samples, and at 1000 the samples measured against their rounding bound fail too (the pole is
 * still found). */
static void defect_near_pole(void)
{
    rg2_surface s;
    rg2_error err;
    rg2_design *d = fig9_cap(&s);
    if (!d)
        return;
    CHECK(!s.xp && s.nv > 2, "capped sphere: bi-3, %d rows", s.nv);
    /* patch (0, 0): its v = 0 side is the south pole; move control point (1, 1) */
    double *h = s.patch[0].h[1][1];
    CHECK(h[3] > 0, "weight");
    for (int k = 0; k < 3; k++)
        h[k] += 1e-6 * h[3];
    for (int n = 16; n <= 1000; n = n == 16 ? 1000 : 2000) {
        rg2_check_opts o;
        rg2_check_opts_default(&o);
        o.seam_samples = n;
        rg2_check_report r;
        CHECK_OK(rg2_check(&s, 1, NULL, NULL, 0, &o, &r, &err), &err);
        unsigned f = rg2_check_failures(&r, RG2_REQUIRE_G1 | RG2_REQUIRE_G2);
        printf("fig9 cap, control point next to the pole moved by 1e-6, %d samples: G0 %.2e, G1 %.2e rad, G2 %.2e, "
               "near the pole %.3g / %.3g of the limits, %d pole samples\n",
               n, r.g0.value, r.g1.value, r.g2.value, r.g1_pole.value, r.g2_pole.value, r.pole_samples);
        CHECK((f & RG2_REQUIRE_G1) && (f & RG2_REQUIRE_G2) && !(rg2_check_failures(&r, RG2_REQUIRE_G0)) &&
                  r.pole_samples > 0 && (n < 1000 || r.g1_pole.value > 1.0),
              "%d samples: a moved control point next to a pole fails G1 (failures %#x)", n, f);
        rg2_check_report_free(&r);
    }
    rg2_surface_free(&s);
    rg2_design_free(d);
}

/* Scale the bi-3 surface s: affine control points by `pos`, homogeneous weights by `w`. */
static void scale_surface(rg2_surface *s, double pos, double w)
{
    for (int k = 0; k < s->nu * s->nv; k++)
        for (int c = 0; c < 16; c++)
            for (int q = 0; q < 4; q++)
                s->patch[k].h[c / 4][c % 4][q] *= q < 3 ? pos * w : w;
}

/* Diagonal of the box of the affine control points (a, b), a = 0..3, of row b of a bi-3 patch. */
static double row_spread(const rg2_patch *P, int b)
{
    double lo[3] = {INFINITY, INFINITY, INFINITY}, hi[3] = {-INFINITY, -INFINITY, -INFINITY}, d2 = 0;
    for (int a = 0; a < 4; a++)
        for (int d = 0; d < 3; d++) {
            lo[d] = fmin(lo[d], P->h[a][b][d] / P->h[a][b][3]);
            hi[d] = fmax(hi[d], P->h[a][b][d] / P->h[a][b][3]);
        }
    for (int d = 0; d < 3; d++)
        d2 += (hi[d] - lo[d]) * (hi[d] - lo[d]);
    return sqrt(d2);
}

/* A pole is a side whose control points coincide to 1e-11 of the widest parallel control line
 * (rounding of a placed design leaves them apart by less): the Fig. 9 sphere scaled by 50, the
 * inner points of every south pole row moved apart along x to 3e-12 of that line (the corners
 * stay, so the seams still meet), reports the same pole samples as the original, no fold or
 * singular sample, and passes G2. */
static void pole_within_rounding(void)
{
    rg2_surface s;
    rg2_error err;
    rg2_design *d = fig9_cap(&s);
    if (!d)
        return;
    scale_surface(&s, 50, 1);
    rg2_check_report a, b;
    CHECK_OK(rg2_check(&s, 1, NULL, NULL, 0, NULL, &a, &err), &err);
    double ratio = 0, wmin = INFINITY;
    for (int i = 0; i < s.nu; i++) {
        rg2_patch *P = rg2_surface_patch(&s, i, 0);
        double w = fmax(fmax(row_spread(P, 1), row_spread(P, 2)), row_spread(P, 3)), dx = 1.5e-12 * w;
        CHECK(row_spread(P, 0) <= 1e-15 * w, "patch (%d,0): a south pole row (%.3g)", i, row_spread(P, 0) / w);
        P->h[1][0][0] += dx * P->h[1][0][3];
        P->h[2][0][0] -= dx * P->h[2][0][3];
        ratio = fmax(ratio, row_spread(P, 0) / w);
        wmin = fmin(wmin, w);
    }
    CHECK_OK(rg2_check(&s, 1, NULL, NULL, 0, NULL, &b, &err), &err);
    unsigned f = rg2_check_failures(&b, RG2_REQUIRE_G2);
    printf("fig9 cap x 50, south pole rows %.2g of their widest parallel lines (>= %.3g) apart: %d pole samples "
           "(%d before), %d folds, %d singular, %d unmeasured, failures %#x\n",
           ratio, wmin, b.pole_samples, a.pole_samples, b.folds, b.singular, b.unmeasured, f);
    CHECK(ratio > 2e-12 && ratio < 1e-11 && wmin > 2, "pole rows %.3g apart (widest lines >= %.3g)", ratio, wmin);
    CHECK(a.pole_samples > 0 && b.pole_samples == a.pole_samples && b.folds == 0 && b.singular == 0 &&
              b.unmeasured == 0 && f == 0 && !rg2_check_failures(&a, RG2_REQUIRE_G2),
          "pole within rounding: %d pole samples (%d), %d folds, %d singular, %d unmeasured, failures %#x",
          b.pole_samples, a.pole_samples, b.folds, b.singular, b.unmeasured, f);
    rg2_check_report_free(&a);
    rg2_check_report_free(&b);
    rg2_surface_free(&s);
    rg2_design_free(d);
}

/* The rounding bounds are relative: the Fig. 9 cap at 256 samples per seam (hundreds of samples
 * next to a pole measured against their bound) scaled by 2^30 in position and by 2^-20 in its
 * homogeneous weights (both exact: the same surface, its evaluations scaled exactly) reports the
 * same samples next to a pole, the same limits and gaps there and the same G1 / G2 gaps. */
static void bounds_scale_free(void)
{
    rg2_surface s;
    rg2_error err;
    rg2_design *d = fig9_cap(&s);
    if (!d)
        return;
    rg2_check_opts o;
    rg2_check_opts_default(&o);
    o.seam_samples = 256;
    rg2_check_report a, b;
    CHECK_OK(rg2_check(&s, 1, NULL, NULL, 0, &o, &a, &err), &err);
    for (int k = 0; k < 2; k++) {
        scale_surface(&s, k ? 1 : 0x1p30, k ? 0x1p-20 : 1);
        CHECK_OK(rg2_check(&s, 1, NULL, NULL, 0, &o, &b, &err), &err);
        const double x[8] = {a.near_pole_tol1, a.near_pole_tol2, a.g1_pole.value, a.g2_pole.value, a.g1.value,
                             a.g2.value, a.size * 0x1p30, a.g0.value};
        const double y[8] = {b.near_pole_tol1, b.near_pole_tol2, b.g1_pole.value, b.g2_pole.value, b.g1.value,
                             b.g2.value, b.size, b.g0.value};
        double worst = 0;
        for (int q = 0; q < 8; q++)
            worst = fmax(worst, q == 7 ? fabs(x[q] - y[q]) : rel(x[q], y[q]));
        printf("fig9 cap, 256 samples, scaled by 2^30%s: %d next to a pole (%d), limits %.3e / %.3e (%.3e / %.3e), "
               "worst relative difference %.2g\n", k ? " and weights by 2^-20" : "", b.near_pole, a.near_pole,
               b.near_pole_tol1, b.near_pole_tol2, a.near_pole_tol1, a.near_pole_tol2, worst);
        CHECK(a.near_pole > 100 && b.near_pole == a.near_pole && b.pole_samples == a.pole_samples &&
                  b.pole_unresolved == a.pole_unresolved && worst <= 1e-12,
              "scaled%s: %d next to a pole (%d), limits or gaps differ by %.3g", k ? ", weights too" : "",
              b.near_pole, a.near_pole, worst);
        rg2_check_report_free(&b);
    }
    rg2_check_report_free(&a);
    rg2_surface_free(&s);
    rg2_design_free(d);
}

/* Undefined normals away from a pole are no pole: a cylinder band of height 1e-95 (every normal
 * undefined, no collapsed side) must fail G1 and G2 with the samples counted as unmeasured, not
 * pass with nothing compared; so must a torus scaled to 1e100, whose metric E G - F^2 overflows. */
static void unmeasured_fails(void)
{
    for (int f = 0; f < 2; f++) {
        const char *file = f == 0 ? "tests/data/thin_band.json" : "examples/fig1_torus.json";
        rg2_design *d = NULL;
        rg2_error err;
        CHECK_OK(rg2_design_load(file, &d, &err), &err);
        if (!d)
            continue;
        rg2_surface s;
        CHECK_OK(rg2_surface_copy(rg2_design_surface(d, 0), &s, &err), &err);
        if (f == 1)
            for (int k = 0; k < s.nu * s.nv; k++)
                for (int a = 0; a < 4; a++)
                    for (int b = 0; b < 4; b++)
                        for (int c = 0; c < 3; c++)
                            s.patch[k].h[a][b][c] *= 1e100;
        rg2_check_report r;
        CHECK_OK(rg2_check(&s, 1, NULL, NULL, 0, NULL, &r, &err), &err);
        unsigned g1 = rg2_check_failures(&r, RG2_REQUIRE_G1), g2 = rg2_check_failures(&r, RG2_REQUIRE_G2);
        printf("%s%s: %d samples, %d at a pole, %d unmeasured; failures G1 %#x, G2 %#x\n", file,
               f ? " scaled by 1e100" : "", r.seam_samples, r.pole_samples, r.unmeasured, g1, g2);
        CHECK(r.unmeasured > 0 && g1 == RG2_REQUIRE_G1 && g2 == RG2_REQUIRE_G2 && !rg2_check_failures(&r, RG2_REQUIRE_G0),
              "%s: unmeasured %d, failures G1 %#x G2 %#x", file, r.unmeasured, g1, g2);
        CHECK(r.pole_samples == 0 && r.unmeasured == r.seam_samples,
              "%s: no pole (%d pole samples), every sample unmeasured (%d of %d)", file, r.pole_samples, r.unmeasured,
              r.seam_samples);
        char *text = NULL;
        CHECK_OK(rg2_check_format(&r, 0, &text, &err), &err);
        CHECK(text && strstr(text, "NOT MEASURED") && strstr(text, "G1 normal angle") && strstr(text, "FAIL"),
              "%s: the table says what was not measured: %s", file, text ? text : "(none)");
        same_on_threads(&s, 1, NULL, NULL, 0, NULL,
                        f ? "fig1_torus scaled by 1e100 (unmeasured)" : "thin band (unmeasured)");
        free(text);
        rg2_check_report_free(&r);
        rg2_surface_free(&s);
        rg2_design_free(d);
    }
}

/* rg2_check_report.unmeasured_at: where the first unmeasured sample is, in the order seams are
 * measured (surface, u seams then v seams, row by row, t along each), with its rounding bound
 * over the measurable limits (+inf for an undefined normal). Each case's expected place follows
 * from that order: a thin band (every sample unmeasured, u closed: the first u seam is
 * (7,0)|(0,0), t = 0), the band as the second surface after a torus (nothing unmeasured on the
 * torus: surface 1's), and a cylinder with a knot interval 1e-6 long (v knots 0, 1, 1 + 1e-6, 2:
 * 60 of 340 samples unmeasured, on v seams of the short patches, j = 1, at rounding bounds 13.6
 * times the measurable limit). The text names the place and the JSON carries it; the same on 1,
 * 2, 3 and 8 threads (the merge of the threads' parts keeps the first part's first). */
static rg2_design *design_checked(const char *js, const char *name, rg2t_parts *p, const rg2_check_opts *o,
                                  rg2_check_report *r);

static void unmeasured_where(void)
{
    static const char *band = "\"band\": {\"shape\": \"c\", \"u\": {\"arcs\": 8}, \"v\": {\"segments\": 20, \"from\": 0, "
                              "\"to\": 1e-95}}";
    static const struct {
        const char *name, *js;
        int surf, pi, pj, qi, qj, finite;
    } cases[] = {
        {"thin band", NULL, 0, 7, 0, 0, 0, 0},
        {"torus, then the thin band", NULL, 1, 7, 0, 0, 0, 0},
        {"cylinder with a knot interval of 1e-6",
         "{\"shapes\": {\"c\": {\"kind\": \"cylinder\"}}, \"meshes\": {\"m\": {\"shape\": \"c\", \"u\": {\"arcs\": 4}, "
         "\"v\": {\"knots\": [0, 1, 1.000001, 2]}}}}",
         0, 3, 1, 0, 1, 1},
    };
    for (size_t c = 0; c < sizeof cases / sizeof *cases; c++) {
        char js[600];
        if (cases[c].js)
            snprintf(js, sizeof js, "%s", cases[c].js);
        else
            snprintf(js, sizeof js,
                     "{\"shapes\": {\"c\": {\"kind\": \"cylinder\"}, \"t\": {\"kind\": \"torus\"}}, \"meshes\": {%s%s}, "
                     "\"output\": %s}",
                     c == 0 ? "" : "\"ring\": {\"shape\": \"t\", \"u\": {\"arcs\": 4}, \"v\": {\"arcs\": 4}}, ", band,
                     c == 0 ? "\"band\"" : "[\"ring\", \"band\"]");
        rg2t_parts p;
        rg2_check_opts o;
        rg2_check_opts_default(&o);
        rg2_check_report r;
        rg2_error err;
        rg2_design *d = design_checked(js, cases[c].name, &p, &o, &r);
        if (!d)
            continue;
        const rg2_check_gap *u = &r.unmeasured_at;
        printf("%s: %d of %d samples unmeasured, the first at surface %d %s seam (%d,%d)|(%d,%d) t=%g, bound / limit "
               "%.3g\n",
               cases[c].name, r.unmeasured, r.seam_samples, u->surf, u->seam_dir ? "v" : "u", u->pi, u->pj, u->qi,
               u->qj, u->t, u->value);
        if (cases[c].finite) /* the short patches' seams: a v seam (the u seams along them are measured) */
            CHECK(r.unmeasured > 0 && u->surf == 0 && (u->pj == 1 || u->qj == 1) && u->pj <= u->qj,
                  "%s: the first unmeasured sample at surface %d seam %d (%d,%d)|(%d,%d), want one of the short "
                  "patches (j = 1)",
                  cases[c].name, u->surf, u->seam_dir, u->pi, u->pj, u->qi, u->qj);
        else
            CHECK(r.unmeasured > 0 && u->surf == cases[c].surf && u->seam_dir == 0 && u->pi == cases[c].pi &&
                      u->pj == cases[c].pj && u->qi == cases[c].qi && u->qj == cases[c].qj && u->t == 0,
                  "%s: the first unmeasured sample at surface %d seam %d (%d,%d)|(%d,%d) t=%g, want surface %d u seam "
                  "(%d,%d)|(%d,%d) t=0",
                  cases[c].name, u->surf, u->seam_dir, u->pi, u->pj, u->qi, u->qj, u->t, cases[c].surf, cases[c].pi,
                  cases[c].pj, cases[c].qi, cases[c].qj);
        CHECK(cases[c].finite ? isfinite(u->value) && u->value > 1 : isinf(u->value) && u->value > 0,
              "%s: bound over limit %.3g (want %s)", cases[c].name, u->value,
              cases[c].finite ? "finite, > 1" : "+inf: an undefined normal");
        /* the point is the first side's, at the seam's end of its transversal parameter */
        rg2_eval e;
        if (u->surf >= 0 && u->surf < p.n && u->pi >= 0 && u->pi < p.s[u->surf].nu && u->pj >= 0 &&
            u->pj < p.s[u->surf].nv) {
            rg2_surface_eval(&p.s[u->surf], u->pi, u->pj, u->seam_dir == 0 ? 1.0 : u->t, u->seam_dir == 0 ? u->t : 1.0,
                             0, &e);
            CHECK(e.p[0] == u->p[0] && e.p[1] == u->p[1] && e.p[2] == u->p[2],
                  "%s: point (%.17g, %.17g, %.17g), the patch there (%.17g, %.17g, %.17g)", cases[c].name, u->p[0],
                  u->p[1], u->p[2], e.p[0], e.p[1], e.p[2]);
        }
        char *text = NULL, *json = NULL, where[160];
        CHECK_OK(rg2_check_format(&r, 0, &text, &err), &err);
        CHECK_OK(rg2_check_format(&r, 1, &json, &err), &err);
        snprintf(where, sizeof where, "    the first at surface %d %s seam (%d,%d)|(%d,%d) t=%.3g, point (", u->surf,
                 u->seam_dir ? "v" : "u", u->pi, u->pj, u->qi, u->qj, u->t);
        const char *line = text ? strstr(text, where) : NULL;
        CHECK(line && strstr(line, cases[c].finite ? "): rounding bound " : "): an undefined normal or metric\n"),
              "%s: the text names the first unmeasured sample ('%s'): %s", cases[c].name, where, text ? text : "");
        cJSON *root = json ? cJSON_Parse(json) : NULL, *ua = cJSON_GetObjectItem(root, "unmeasured_at");
        cJSON *pa = cJSON_GetObjectItem(ua, "patch_a"), *why = cJSON_GetObjectItem(ua, "reason");
        CHECK(ua && cJSON_GetObjectItem(ua, "surface") && cJSON_GetObjectItem(ua, "surface")->valuedouble == u->surf &&
                  cJSON_GetArraySize(pa) == 2 && cJSON_GetArrayItem(pa, 0)->valueint == u->pi &&
                  cJSON_GetArrayItem(pa, 1)->valueint == u->pj && cJSON_IsString(why) &&
                  !strcmp(why->valuestring, cases[c].finite ? "rounding bound" : "undefined normal or metric") &&
                  (cases[c].finite
                       ? cJSON_GetObjectItem(ua, "bound_over_limit")->valuedouble == u->value
                       : cJSON_IsNull(cJSON_GetObjectItem(ua, "bound_over_limit"))),
              "%s: the JSON's unmeasured_at: %s", cases[c].name, json ? json : "");
        cJSON_Delete(root);
        same_on_threads(p.s, p.n, p.shapes, p.labels, p.ns, &o, cases[c].name);
        free(text);
        free(json);
        rg2_check_report_free(&r);
        rg2t_design_parts_free(&p);
        rg2_design_free(d);
    }
    /* a report with every sample measured has no unmeasured_at in its JSON, and no 'the first' line */
    rg2t_parts p;
    rg2_check_report r;
    rg2_error err;
    rg2_design *d = design_checked("{\"shapes\": {\"t\": {\"kind\": \"torus\"}}, \"meshes\": {\"m\": {\"shape\": \"t\", "
                                   "\"u\": {\"arcs\": 4}, \"v\": {\"arcs\": 4}}}}",
                                   "torus", &p, NULL, &r);
    if (!d)
        return;
    char *text = NULL, *json = NULL;
    CHECK_OK(rg2_check_format(&r, 0, &text, &err), &err);
    CHECK_OK(rg2_check_format(&r, 1, &json, &err), &err);
    CHECK(r.unmeasured == 0 && text && !strstr(text, "the first") && json && !strstr(json, "unmeasured_at"),
          "torus: %d unmeasured, the text or JSON names a first one: %s%s", r.unmeasured, text ? text : "",
          json ? json : "");
    free(text);
    free(json);
    rg2_check_report_free(&r);
    rg2t_design_parts_free(&p);
    rg2_design_free(d);
}

/* rg2.h, rg2_check: a non-finite control value is measured, not refused; the gaps and the
 * residual come out NaN and every G0, G1, G2 and EXACT promise fails. */
/* rg2.h, rg2_check: a shape of an unknown kind is refused, naming it (it was measured: NaN
 * residuals and a failing exact promise, with RG2_OK). */
static void unknown_shape_kind(void)
{
    rg2_design *d = NULL;
    rg2_error err;
    CHECK_OK(rg2_design_load("examples/fig1_torus.json", &d, &err), &err);
    if (!d)
        return;
    static const int kinds[2] = {99, -1};
    for (int k = 0; k < 2; k++)
        for (int named = 0; named < 2; named++) {
            rg2_shape sh = *rg2_design_shape(d, 0);
            sh.kind = (rg2_shape_kind)kinds[k];
            const char *label[1] = {"ring"};
            rg2_check_report r;
            rg2_status st = rg2_check(rg2_design_surface(d, 0), 1, &sh, named ? label : NULL, 1, NULL, &r, &err);
            char want[80];
            snprintf(want, sizeof want, "check: shapes[0]%s has an unknown kind %d", named ? " ('ring')" : "",
                     kinds[k]);
            CHECK(st == RG2_EINVAL && !strcmp(err.msg, want) && r.shapes == NULL && r.patches == 0,
                  "a shape of kind %d: %s '%s', want '%s'", kinds[k], rg2_status_str(st), err.msg, want);
            if (!st)
                rg2_check_report_free(&r);
        }
    rg2_design_free(d);
    printf("a shape of an unknown kind (99, -1) is refused, naming it\n");
}

static void nonfinite_fails(void)
{
    rg2_design *d = NULL;
    rg2_error err;
    CHECK_OK(rg2_design_load("examples/fig1_torus.json", &d, &err), &err);
    if (!d)
        return;
    for (int c = 0; c < 2; c++) {
        rg2_surface s;
        CHECK_OK(rg2_surface_copy(rg2_design_surface(d, 0), &s, &err), &err);
        s.patch[s.nv + 1].h[1][2][c ? 3 : 0] = c ? INFINITY : -NAN; /* a coordinate, a weight */
        const rg2_shape *sh = rg2_design_shape(d, 0);
        const char *label[1] = {c ? "pipe-nan" : "nan"}; /* (a label is written as given) */
        rg2_check_report r;
        rg2_status st = rg2_check(&s, 1, sh, label, 1, NULL, &r, &err);
        unsigned want = RG2_REQUIRE_G0 | RG2_REQUIRE_G1 | RG2_REQUIRE_G2 | RG2_REQUIRE_EXACT;
        unsigned got = st ? 0 : rg2_check_failures(&r, want);
        char *text = NULL;
        if (!st)
            CHECK_OK(rg2_check_format(&r, 0, &text, &err), &err);
        CHECK(st == RG2_OK && got == want && text && strstr(text, "FAIL"),
              "check of a surface with a non-finite %s: status %s, failures %#x of %#x", c ? "weight" : "coordinate",
              rg2_status_str(st), got, want);
        /* a NaN reads "NaN" in the table, whatever its sign bit ("-nan" from printf before) */
        char named[32];
        snprintf(named, sizeof named, "  0 %s ", label[0]);
        int lower = 0; /* "nan" written: only the label's own */
        for (const char *p = text; p && (p = strstr(p, "nan")); p++)
            lower++;
        CHECK(!text || (strstr(text, " NaN ") && strstr(text, named) && lower == 1),
              "check of a surface with a non-finite %s: the table's NaN figures or the label '%s' read: %s",
              c ? "weight" : "coordinate", label[0], text ? text : "");
        free(text);
        if (!st)
            rg2_check_report_free(&r);
        rg2_surface_free(&s);
    }
    rg2_design_free(d);
}

/* A metric that overflows on one side of a seam only is no measurement either: two flat
 * patches side by side, extruded over y in [0, Y], one X wide and the other 4 X wide (|Su| = X
 * and 4 X, |Sv| = Y, Su . Sv = 0). At X = Y = 1e77 the narrow patch's E G - F^2 = X^2 Y^2 is
 * finite and the wide one's, 16 X^2 Y^2, overflows: every sample of the seam is unmeasured and
 * G1 and G2 fail, whichever side is the wide one (a seam was measured when one side's metric
 * still held). At 1e76 both hold: the plane is G2. */
static void metric_overflow_one_side(void)
{
    for (int wide = 0; wide < 2; wide++)
        for (int e = 0; e < 2; e++) {
            double X = e ? 1e77 : 1e76, Y = X;
            double w0 = wide ? 4 * X : X, w1 = wide ? X : 4 * X; /* widths of patches 0, 1 */
            double p0[4][3], p1[4][3];
            for (int r = 0; r < 4; r++) {
                p0[r][0] = w0 * r / 3.0;
                p1[r][0] = w0 + w1 * r / 3.0;
                p0[r][1] = p1[r][1] = 0;
                p0[r][2] = p1[r][2] = 1;
            }
            rg2_surface s;
            rg2_error err;
            CHECK_OK(scene_two_extruded(p0, p1, Y, &s, &err), &err);
            rg2_check_report r;
            CHECK_OK(rg2_check(&s, 1, NULL, NULL, 0, NULL, &r, &err), &err);
            int over = !isfinite(16 * X * X * Y * Y), narrow_ok = isfinite(X * X * Y * Y);
            unsigned f = rg2_check_failures(&r, RG2_REQUIRE_G0 | RG2_REQUIRE_G1 | RG2_REQUIRE_G2);
            printf("plane, patches %.0e and %.0e wide, %.0e long: E G - F^2 %s on the wide side; %d of %d samples "
                   "unmeasured, failures %#x\n", w0, w1, Y, over ? "overflows" : "finite", r.unmeasured,
                   r.seam_samples, f);
            CHECK(narrow_ok && r.seams == 1 && r.seam_samples == 17 && r.g0.value <= 1e-15,
                  "one seam of 17 samples, positions equal (G0 %.3g)", r.g0.value);
            if (over)
                CHECK(r.unmeasured == 17 && r.pole_samples == 0 && f == (RG2_REQUIRE_G1 | RG2_REQUIRE_G2),
                      "wide patch %d at %.0e: %d unmeasured, failures %#x", 1 - wide, X, r.unmeasured, f);
            else
                CHECK(r.unmeasured == 0 && f == 0 && r.g1.value <= 1e-15 && r.g2.value <= 1e-15,
                      "at %.0e: %d unmeasured, failures %#x, G1 %.3g, G2 %.3g", X, r.unmeasured, f, r.g1.value,
                      r.g2.value);
            rg2_check_report_free(&r);
            rg2_surface_free(&s);
        }
}

/* Looser limits measure the same samples: with tol_g1 = tol_g2 = 1 nothing becomes unmeasured,
 * every sample that was measured against its rounding bound is measured at the loose limits,
 * the worst gaps cover those of the default report (its near-pole gaps included), and every
 * promise still holds. (Limits above the near-pole ceilings 1e-4 rad / 1e-2 once turned every
 * sample into "not measured" and failed G1 and G2.) */
static void loose_limits(void)
{
    static const char *files[] = {"examples/torus_sphere.json", "examples/fig9_polar_sphere.json",
                                  "examples/fig14_mobius.json", "examples/fig15_saddle_caps.json"};
    for (size_t f = 0; f < sizeof files / sizeof *files; f++) {
        rg2_design *d = NULL;
        rg2_error err;
        CHECK_OK(rg2_design_load(files[f], &d, &err), &err);
        if (!d)
            continue;
        int ns = rg2_design_num_shapes(d), n = rg2_design_num_surfaces(d);
        rg2_shape *shapes = design_shapes(d);
        rg2_surface *all = calloc((size_t)n, sizeof *all); /* shallow copies, owned by d */
        for (int k = 0; k < n; k++)
            all[k] = *rg2_design_surface(d, k);
        rg2_check_opts o;
        rg2_check_opts_default(&o);
        rg2_check_report def, loose;
        CHECK_OK(rg2_check(all, n, shapes, NULL, ns, &o, &def, &err), &err);
        o.tol_g1 = 1.0;
        o.tol_g2 = 1.0;
        CHECK_OK(rg2_check(all, n, shapes, NULL, ns, &o, &loose, &err), &err);
        unsigned req = RG2_REQUIRE_G2 | RG2_REQUIRE_EXACT | RG2_REQUIRE_WEIGHTS;
        printf("%s, limits 1 rad / 1: %d unmeasured, %d next to a pole, G1 %.2e rad, G2 %.2e (default limits: "
               "%d next to a pole, G1 %.2e, G2 %.2e)\n",
               files[f], loose.unmeasured, loose.near_pole, loose.g1.value, loose.g2.value, def.near_pole,
               def.g1.value, def.g2.value);
        CHECK(!rg2_check_failures(&def, req) && !rg2_check_failures(&loose, req),
              "%s: failures %#x at the default limits, %#x at limits 1", files[f], rg2_check_failures(&def, req),
              rg2_check_failures(&loose, req));
        CHECK(loose.unmeasured == 0 && loose.near_pole == 0 && loose.pole_samples == def.pole_samples &&
                  loose.skipped == def.skipped && loose.seam_samples == def.seam_samples,
              "%s: limits 1 leave %d unmeasured, %d near a pole, %d skipped (default %d)", files[f], loose.unmeasured,
              loose.near_pole, loose.skipped, def.skipped);
        CHECK(loose.g1.value >= def.g1.value && loose.g2.value >= def.g2.value && loose.g0.value == def.g0.value,
              "%s: loose G1 %.3g G2 %.3g below the default report's %.3g %.3g", files[f], loose.g1.value,
              loose.g2.value, def.g1.value, def.g2.value);
        rg2_check_report_free(&def);
        rg2_check_report_free(&loose);
        free(all);
        free(shapes);
        rg2_design_free(d);
    }
}

/* The first fold of report r of s (default samples, 12 per patch side) lies between two
 * neighbouring samples (its parameters: their midpoint, a half step along u or v), whose normals,
 * evaluated here, point into opposite half-spaces. */
static void fold_between_samples(const rg2_surface *s, const rg2_check_report *r, const char *name)
{
    const double S = 12;
    double hu = 2 * S * r->fold_at.u, hv = 2 * S * r->fold_at.v, du = 0, dv = 0;
    int ou = fabs(hu - round(hu)) < 1e-9 && fmod(round(hu), 2) == 1;
    int ov = fabs(hv - round(hv)) < 1e-9 && fmod(round(hv), 2) == 1;
    int eu = fabs(hu - round(hu)) < 1e-9 && !ou, ev = fabs(hv - round(hv)) < 1e-9 && !ov;
    if (ou && ev)
        du = 0.5 / S;
    else if (eu && ov)
        dv = 0.5 / S;
    rg2_eval e0, e1;
    rg2_surface_eval(s, r->fold_at.pi, r->fold_at.pj, r->fold_at.u - du, r->fold_at.v - dv, 1, &e0);
    rg2_surface_eval(s, r->fold_at.pi, r->fold_at.pj, r->fold_at.u + du, r->fold_at.v + dv, 1, &e1);
    double dn = e0.n[0] * e1.n[0] + e0.n[1] * e1.n[1] + e0.n[2] * e1.n[2];
    printf("%s: first fold at patch (%d,%d) u=%.17g v=%.17g: between samples %s, n0 . n1 = %.3g\n", name,
           r->fold_at.pi, r->fold_at.pj, r->fold_at.u, r->fold_at.v, du > 0 ? "along u" : dv > 0 ? "along v" : "?",
           dn);
    CHECK((du > 0 || dv > 0) && dn < 0, "%s: the fold at u=%.17g v=%.17g lies between two samples with opposite "
          "normals (n0 . n1 = %.3g)", name, r->fold_at.u, r->fold_at.v, dn);
}

/* Seams alone cannot see a surface that runs back over itself: a cylinder mesh merged with
 * itself (tests/data/folded_merge.json, the second copy over the first) has G2 seams, but S_v
 * vanishes inside the middle transitions and the normal reverses there. The check must find the
 * fold, name where, and fail G1 and G2 (not G0). A bend by more than 90 degrees between two
 * samples is no fold: a torus tube of 3 arcs of 120 degrees sampled at the patch corners only
 * (normals 120 degrees apart) has none. */
static void folds_fail(void)
{
    rg2_design *d = NULL;
    rg2_error err;
    CHECK_OK(rg2_design_load("tests/data/folded_merge.json", &d, &err), &err);
    if (d) {
        rg2_check_report r;
        CHECK_OK(rg2_check(rg2_design_surface(d, 0), 1, NULL, NULL, 0, NULL, &r, &err), &err);
        unsigned g1 = rg2_check_failures(&r, RG2_REQUIRE_G1), g2 = rg2_check_failures(&r, RG2_REQUIRE_G2);
        printf("folded merge: G1 %.2e rad, G2 %.2e at the seams; %d folds, %d singular, first at patch (%d,%d) "
               "u=%.3g v=%.3g; failures G1 %#x, G2 %#x\n",
               r.g1.value, r.g2.value, r.folds, r.singular, r.fold_at.pi, r.fold_at.pj, r.fold_at.u, r.fold_at.v, g1,
               g2);
        CHECK(r.g1.value <= 1e-10 && r.g2.value <= 1e-8, "the seams themselves are G2 (%.3g, %.3g)", r.g1.value,
              r.g2.value);
        /* the transitions are v patches 3..5 of 9; the fold lies inside them */
        CHECK(r.folds > 0 && r.fold_at.pj >= 3 && r.fold_at.pj <= 5 && r.fold_at.u >= 0 && r.fold_at.u <= 1 &&
                  r.fold_at.v > 0 && r.fold_at.v < 1,
              "fold found in a transition: %d folds at patch (%d,%d) v=%.3g", r.folds, r.fold_at.pi, r.fold_at.pj,
              r.fold_at.v);
        CHECK(g1 == RG2_REQUIRE_G1 && g2 == RG2_REQUIRE_G2 && !rg2_check_failures(&r, RG2_REQUIRE_G0),
              "a fold fails G1 and G2, not G0 (failures %#x %#x)", g1, g2);
        fold_between_samples(rg2_design_surface(d, 0), &r, "folded merge");
        rg2_surface tr;
        transpose_surface(rg2_design_surface(d, 0), &tr);
        rg2_check_report rt;
        CHECK_OK(rg2_check(&tr, 1, NULL, NULL, 0, NULL, &rt, &err), &err);
        CHECK(rt.folds == r.folds && rt.fold_at.pi == r.fold_at.pj && rt.fold_at.pj == r.fold_at.pi,
              "transposed: %d folds (%d), first at patch (%d,%d)", rt.folds, r.folds, rt.fold_at.pi, rt.fold_at.pj);
        fold_between_samples(&tr, &rt, "folded merge transposed");
        rg2_check_report_free(&rt);
        rg2_surface_free(&tr);
        same_on_threads(rg2_design_surface(d, 0), 1, NULL, NULL, 0, NULL, "folded merge");
        char *text = NULL, *json = NULL;
        CHECK_OK(rg2_check_format(&r, 0, &text, &err), &err);
        CHECK_OK(rg2_check_format(&r, 1, &json, &err), &err);
        CHECK(text && strstr(text, "NOT REGULAR") && strstr(text, "folds back") && strstr(text, "patch (0,"),
              "the table names the fold: %s", text ? text : "(none)");
        /* the seam rows are within their limits yet FAIL: each says why */
        CHECK(text && strstr(text, "FAIL (limit 1e-10; not regular, below)") &&
                  strstr(text, "FAIL (limit 1e-08; G1 fails, so G2 cannot hold)"),
              "the G1 and G2 rows give the reason they fail: %s", text ? text : "(none)");
        cJSON *j = json ? cJSON_Parse(json) : NULL, *rg = cJSON_GetObjectItem(j, "regularity");
        CHECK(rg && cJSON_GetObjectItem(rg, "folds")->valueint == r.folds && cJSON_GetObjectItem(rg, "patch") &&
                  cJSON_IsFalse(cJSON_GetObjectItem(j, "g2")),
              "the JSON report names the fold");
        cJSON_Delete(j);
        free(text);
        free(json);
        rg2_check_report_free(&r);
        rg2_design_free(d);
    }
    rg2_shape t;
    rg2_shape_init(&t, RG2_SHAPE_TORUS);
    double au[8], av[3] = {2 * RG2_PI / 3, 2 * RG2_PI / 3, 2 * RG2_PI / 3};
    for (int k = 0; k < 8; k++)
        au[k] = RG2_PI / 4;
    rg2_partition pu = {RG2_PART_ANGLES, 1, 8, au, 0.0}, pv = {RG2_PART_ANGLES, 1, 3, av, 0.0};
    rg2_surface s;
    CHECK_OK(rg2_shape_surface(&t, &pu, &pv, &s, NULL, &err), &err);
    for (int S = 1; S <= 2; S++) {
        rg2_check_opts o;
        rg2_check_opts_default(&o);
        o.patch_samples = S;
        rg2_check_report r;
        CHECK_OK(rg2_check(&s, 1, &t, NULL, 1, &o, &r, &err), &err);
        printf("torus, 3 tube arcs of 120 degrees, %d samples per patch side: %d folds, %d singular; failures %#x "
               "(G2 %.2e)\n",
               S, r.folds, r.singular, rg2_check_failures(&r, RG2_REQUIRE_G2), r.g2.value);
        CHECK(r.folds == 0 && r.singular == 0 && !rg2_check_failures(&r, RG2_REQUIRE_G2),
              "a bend of 120 degrees between samples is no fold (%d folds)", r.folds);
        rg2_check_report_free(&r);
    }
    /* a NaN control value in an exact-tagged patch: its samples have no distance from the shape,
     * and the exact promise fails (the NaN gradient was skipped like an apex's, and exact passed) */
    rg2_design *dn = NULL;
    CHECK_OK(rg2_design_load("examples/torus_sphere.json", &dn, &err), &err);
    if (dn) {
        rg2_surface c;
        CHECK_OK(rg2_surface_copy(rg2_design_surface(dn, 0), &c, &err), &err);
        int k = 0;
        while (k < c.nu * c.nv - 1 && c.tag[k] < 0)
            k++;
        int ns = rg2_design_num_shapes(dn);
        const char *lab[8];
        rg2_shape sh[8];
        for (int q = 0; q < ns && q < 8; q++) {
            lab[q] = rg2_design_shape_label(dn, q);
            sh[q] = *rg2_design_shape(dn, q);
        }
        rg2_check_report r;
        CHECK_OK(rg2_check(&c, 1, sh, lab, ns, NULL, &r, &err), &err);
        CHECK(!rg2_check_failures(&r, RG2_REQUIRE_EXACT), "the design itself is exact");
        rg2_check_report_free(&r);
        c.patch[k].h[1][1][3] = NAN;
        CHECK_OK(rg2_check(&c, 1, sh, lab, ns, NULL, &r, &err), &err);
        CHECK(rg2_check_failures(&r, RG2_REQUIRE_EXACT) == RG2_REQUIRE_EXACT && isnan(r.shapes[c.tag[k]].residual),
              "a NaN weight in exact patch %d: exact failures %#x, residual %g", k,
              rg2_check_failures(&r, RG2_REQUIRE_EXACT), r.shapes[c.tag[k]].residual);
        rg2_check_report_free(&r);
        rg2_surface_free(&c);
        rg2_design_free(dn);
    }
    rg2_surface_free(&s);
}

/* Away from poles, an ill-conditioned patch is measured against its rounding bound too: a
 * torus flattened by 1e-6 in z (homogeneous z scaled, the exact image of the torus) turns its
 * normal by 90 degrees within 1e-6 of the rim, where the evaluations' normals round to ~1e-9 rad;
 * it passes G2 with those samples reported as ill-conditioned, and the bound is not vacuous (the
 * worst gap reaches a measurable fraction of it). A small out-of-plane defect of one control
 * point (1e-9 of the unflattened size) still fails G1. */
static void ill_conditioned_flat(void)
{
    rg2_mesh m;
    rg2_surface s;
    rg2_error err;
    CHECK_OK(rg2t_torus(3, 1, 8, 6, &m, &s, &err), &err);
    size_t np = (size_t)s.nu * s.nv;
    for (size_t k = 0; k < np; k++)
        for (int a = 0; a < 4; a++)
            for (int b = 0; b < 4; b++)
                s.patch[k].h[a][b][2] *= 1e-6;
    rg2_check_opts o;
    rg2_check_opts_default(&o);
    rg2_check_report r;
    CHECK_OK(rg2_check(&s, 1, NULL, NULL, 0, &o, &r, &err), &err);
    unsigned f = rg2_check_failures(&r, RG2_REQUIRE_G2);
    printf("torus flattened by 1e-6: G1 %.2e, G2 %.2e; %d ill-conditioned samples, limits up to %.2e rad / %.2e, "
           "worst gap / limit %.3g / %.3g; %d unmeasured\n",
           r.g1.value, r.g2.value, r.ill_conditioned, r.ill_tol1, r.ill_tol2, r.g1_ill.value, r.g2_ill.value,
           r.unmeasured);
    CHECK(!f && r.ill_conditioned > 0 && r.unmeasured == 0 && r.near_pole == 0, "flattened torus: failures %#x, %d "
          "ill-conditioned, %d unmeasured", f, r.ill_conditioned, r.unmeasured);
    CHECK(r.g1_ill.value > 1e-4 && r.ill_tol1 < 1e-5, "the bound is not vacuous: gap / limit %.3g, limit %.3g",
          r.g1_ill.value, r.ill_tol1);
    char *txt = NULL;
    CHECK_OK(rg2_check_format(&r, 0, &txt, &err), &err);
    CHECK(txt && strstr(txt, "ill-conditioned") && strstr(txt, "worst gap / limit") && !strstr(txt, "FAIL (limit") &&
              !strstr(txt, "NOT "),
          "text:\n%s", txt ? txt : "");
    free(txt);
    rg2_check_report_free(&r);
    same_on_threads(&s, 1, NULL, NULL, 0, &o, "torus flattened by 1e-6 (ill-conditioned)");
    double *h = rg2_surface_patch(&s, 3, 2)->h[2][1];
    h[2] += 1e-9 * h[3];
    CHECK_OK(rg2_check(&s, 1, NULL, NULL, 0, &o, &r, &err), &err);
    f = rg2_check_failures(&r, RG2_REQUIRE_G0 | RG2_REQUIRE_G1);
    printf("  one control point moved by 1e-9 out of the plane: G1 %.2e rad, ill-conditioned gap / limit %.3g; "
           "failures %#x\n", r.g1.value, r.g1_ill.value, f);
    CHECK(f == RG2_REQUIRE_G1, "a defect on the flattened torus fails G1 (and only G1 of G0, G1): %#x", f);
    rg2_check_report_free(&r);
    same_on_threads(&s, 1, NULL, NULL, 0, &o, "flattened torus with a defect");
    rg2_surface_free(&s);
    rg2_mesh_free(&m);
    /* flattened by 1e-10 the rim's rounding bounds pass 1e-4 rad: those samples are no
     * measurement (away from any pole), and G1, G2 fail on them, whatever the gaps measured */
    CHECK_OK(rg2t_torus(3, 1, 8, 6, &m, &s, &err), &err);
    for (size_t k = 0; k < np; k++)
        for (int a = 0; a < 4; a++)
            for (int b = 0; b < 4; b++)
                s.patch[k].h[a][b][2] *= 1e-10;
    CHECK_OK(rg2_check(&s, 1, NULL, NULL, 0, &o, &r, &err), &err);
    f = rg2_check_failures(&r, RG2_REQUIRE_G0 | RG2_REQUIRE_G1 | RG2_REQUIRE_G2);
    CHECK_OK(rg2_check_format(&r, 0, &txt, &err), &err);
    printf("torus flattened by 1e-10: %d of %d samples unmeasured, %d next to a pole unresolved; failures %#x\n",
           r.unmeasured, r.seam_samples, r.pole_unresolved, f);
    CHECK(r.unmeasured > 0 && r.pole_unresolved == 0 && r.skipped >= r.unmeasured && r.unmeasured_pole == 0 &&
              txt && !strstr(txt, "on patches with a pole side") &&
              f == (RG2_REQUIRE_G1 | RG2_REQUIRE_G2) && txt &&
              strstr(txt, "samples away from any pole could not be measured") && strstr(txt, "G1 and G2 FAIL"),
          "torus flattened by 1e-10: %d unmeasured, failures %#x, text:\n%s", r.unmeasured, f, txt ? txt : "");
    /* the first one's rounding bound over the measurable limits: the normal's (19.3 times 1e-4 rad;
     * the curvature's is 0.78 times 1e-2), above 1 as every unmeasured sample's is */
    printf("  the first unmeasured: bound over limit %.4g\n", r.unmeasured_at.value);
    CHECK(isfinite(r.unmeasured_at.value) && r.unmeasured_at.value > 1 && txt && strstr(txt, "): rounding bound 19.3 times"),
          "torus flattened by 1e-10: the first unmeasured sample's bound over the limit %.4g, want 19.3 (the normal's)",
          r.unmeasured_at.value);
    free(txt);
    rg2_check_report_free(&r);
    rg2_surface_free(&s);
    rg2_mesh_free(&m);
}

/* The same report on any thread count: every example (all its surfaces in one check, at the
 * default samples and at 64 per seam / 5 per patch), a G1 join of 2 patches and 1 seam (fewer
 * items than threads), and a torus with NaN control weights in some patches: the NaN is reported
 * (not hidden by the weights after it) and fails the weights requirement, on every thread count.
 * Negative thread counts are refused.
 * (The folded merge, the unmeasured designs and the ill-conditioned torus: in their tests.) */
static void threads_identical(void)
{
    char *names[64];
    int nd = rg2t_example_names(names, 64);
    for (int k = 0; k < nd; k++) {
        rg2_design *d = NULL;
        rg2_error err;
        CHECK_OK(rg2_design_load(names[k], &d, &err), &err);
        if (d) {
            int ns = rg2_design_num_shapes(d), n = rg2_design_num_surfaces(d);
            rg2_shape *shapes = design_shapes(d);
            const char **labels = calloc((size_t)ns + 1, sizeof *labels);
            rg2_surface *all = calloc((size_t)n, sizeof *all); /* shallow copies, owned by d */
            for (int q = 0; q < ns; q++)
                labels[q] = rg2_design_shape_label(d, q);
            for (int q = 0; q < n; q++)
                all[q] = *rg2_design_surface(d, q);
            same_on_threads(all, n, shapes, labels, ns, NULL, names[k]);
            rg2_check_opts o;
            rg2_check_opts_default(&o);
            o.seam_samples = 64;
            o.patch_samples = 5;
            char name[600];
            snprintf(name, sizeof name, "%s, 64 / 5 samples", names[k]);
            same_on_threads(all, n, shapes, labels, ns, &o, name);
            free(all);
            free(labels);
            free(shapes);
            rg2_design_free(d);
        }
        free(names[k]);
    }
    rg2_surface s;
    rg2_error err;
    CHECK_OK(scene_cyl_plane(2.0, 1.5, 2.0, &s, &err), &err);
    same_on_threads(&s, 1, NULL, NULL, 0, NULL, "cylinder+plane (2 patches, 1 seam)");
    rg2_check_opts o;
    rg2_check_opts_default(&o);
    o.threads = -1;
    rg2_check_report r;
    CHECK(rg2_check(&s, 1, NULL, NULL, 0, &o, &r, &err) == RG2_EINVAL && strstr(err.msg, "threads -1"),
          "threads -1 refused: %s", err.msg);
    rg2_surface_free(&s);

    rg2_mesh m;
    CHECK_OK(rg2t_torus(3, 1, 8, 6, &m, &s, &err), &err);
    rg2_shape t;
    rg2_shape_init(&t, RG2_SHAPE_TORUS);
    s.tag = calloc((size_t)s.nu * s.nv, sizeof *s.tag);
    same_on_threads(&s, 1, &t, NULL, 1, NULL, "torus 8 x 6");
    s.patch[7].h[1][2][3] = NAN; /* inside the first chunks; the weights after it must not hide it */
    s.patch[29].h[0][0][3] = NAN;
    s.patch[30].h[3][3][3] = NAN;
    same_on_threads(&s, 1, &t, NULL, 1, NULL, "torus 8 x 6 with NaN weights in patches 7, 29, 30");
    for (int th = 1; th <= 2; th++) {
        rg2_check_opts_default(&o);
        o.threads = th;
        CHECK_OK(rg2_check(&s, 1, &t, NULL, 1, &o, &r, &err), &err);
        CHECK(isnan(r.wmin) && isnan(r.wmax) && isnan(r.eval_wmin) &&
                  (rg2_check_failures(&r, RG2_REQUIRE_WEIGHTS) & RG2_REQUIRE_WEIGHTS),
              "%d thread(s): NaN weights in patch 7 reported (wmin %g, wmax %g, at samples %g) and failing",
              th, r.wmin, r.wmax, r.eval_wmin);
        rg2_check_report_free(&r);
    }
    s.patch[47].h[2][2][3] = NAN; /* the last patch too */
    same_on_threads(&s, 1, &t, NULL, 1, NULL, "torus 8 x 6 with a NaN weight in the last patch");
    free(s.tag);
    s.tag = NULL;
    rg2_surface_free(&s);
    rg2_mesh_free(&m);
}

/* The sample of patch (pi, pj) at (u, v) with the larger principal curvature in magnitude. */
static double larger_k(const rg2_surface *s, int pi, int pj, double u, double v, double p[3])
{
    rg2_eval e;
    rg2_surface_eval(s, pi, pj, u, v, 2, &e);
    memcpy(p, e.p, 3 * sizeof *p);
    if (e.flags & RG2_EVAL_CURVATURE_UNDEFINED)
        return NAN;
    return fabs(e.k2) > fabs(e.k1) ? e.k2 : e.k1;
}

/* a JSON number, or an array of three, that reads back to exactly x */
static int json_is(const cJSON *n, double x)
{
    return cJSON_IsNumber(n) && n->valuedouble == x;
}

static int json_point_is(const cJSON *a, const double x[3])
{
    return cJSON_GetArraySize(a) == 3 && json_is(cJSON_GetArrayItem(a, 0), x[0]) &&
           json_is(cJSON_GetArrayItem(a, 1), x[1]) && json_is(cJSON_GetArrayItem(a, 2), x[2]);
}

/* A ruled hyperboloid with c = 1e-9 bends by a / c^2 = 1e18 at its waist, too sharply for
 * doubles: its largest |k| comes out infinite. The text says so instead of "inf (radius 0)", and
 * names the place (the waist, v = 0: patch (0,1) at v = 1); the JSON's k is null. */
static void curvature_peak_unresolved(void)
{
    rg2t_parts p;
    rg2_check_report r;
    rg2_error err;
    rg2_design *d = design_checked("{\"shapes\": {\"h\": {\"kind\": \"hyperboloid1_ruled\", \"c\": 1e-9}}, "
                                   "\"meshes\": {\"m\": {\"shape\": \"h\"}}}",
                                   "thin hyperboloid", &p, NULL, &r);
    if (!d)
        return;
    char *text = NULL, *json = NULL;
    CHECK_OK(rg2_check_format(&r, 0, &text, &err), &err);
    CHECK_OK(rg2_check_format(&r, 1, &json, &err), &err);
    const char *line = text ? strstr(text, "  largest |k|") : NULL;
    printf("ruled hyperboloid, c = 1e-9: largest |k| %g at patch (%d,%d) u=%g v=%g\n", r.kpeak_k, r.kpeak.pi,
           r.kpeak.pj, r.kpeak.u, r.kpeak.v);
    static const char want[] = "  largest |k|        inf: a bend too sharp for double precision to resolve (its "
                               "radius rounds to 0) at surface 0 patch (";
    CHECK(isinf(r.kpeak_k) && r.kpeak.pj == 1 && r.kpeak.v == 1 && line && !strncmp(line, want, strlen(want)) &&
              !strstr(text, "radius 0)"),
          "thin hyperboloid: largest |k| %g at (%d,%d) v=%g; the line: %s", r.kpeak_k, r.kpeak.pi, r.kpeak.pj, r.kpeak.v,
          line ? line : "(none)");
    cJSON *j = json ? cJSON_Parse(json) : NULL;
    CHECK(cJSON_IsNull(cJSON_GetObjectItem(cJSON_GetObjectItem(j, "largest_curvature"), "k")),
          "thin hyperboloid: the JSON's largest_curvature.k is not null");
    cJSON_Delete(j);
    free(text);
    free(json);
    rg2_check_report_free(&r);
    rg2t_design_parts_free(&p);
    rg2_design_free(d);
}

/* Where the surface bends most (rg2_check_report.kpeak, the "largest |k|" line). A cylinder of
 * radius 1 scaled by 2 along x is an elliptic cylinder, a = 2, b = 1: it bends most at the ends
 * of the major axis, |k| = a / b^2 = 2, which its 4 arcs put on patch corners. A torus with one
 * control point moved: the report names the sample this test finds by its own scan of the same
 * 13 x 13 samples per patch in the same order (first strictly larger), on 1 to 4 threads; the
 * JSON carries the same k, and every number of its report, bit for bit. */
static void curvature_peak(void)
{
    rg2_shape c;
    rg2_shape_init(&c, RG2_SHAPE_CYLINDER);
    c.xform[0] = 2;
    double au[5], kv[4];
    rg2_partition pu, pv;
    rg2_surface s;
    rg2_error err;
    CHECK_OK(rg2_partition_equal(&pu, RG2_PART_ANGLES, 1, 0, 0, 4, au, 5, &err), &err);
    CHECK_OK(rg2_partition_equal(&pv, RG2_PART_KNOTS, 0, 0, 3, 3, kv, 4, &err), &err);
    CHECK_OK(rg2_shape_surface(&c, &pu, &pv, &s, NULL, &err), &err);
    rg2_check_report r;
    CHECK_OK(rg2_check(&s, 1, NULL, NULL, 0, NULL, &r, &err), &err);
    double k = r.kpeak_k, *p = r.kpeak.p;
    printf("elliptic cylinder: largest |k| %.17g at (%.3g, %.3g, %.3g), patch (%d,%d) u=%g v=%g\n", fabs(k), p[0],
           p[1], p[2], r.kpeak.pi, r.kpeak.pj, r.kpeak.u, r.kpeak.v);
    CHECK(r.kpeak.surf == 0 && rel(fabs(k), 2.0) <= 1e-13 && fabs(fabs(p[0]) - 2) <= 1e-13 && fabs(p[1]) <= 1e-13,
          "elliptic cylinder: largest |k| %.17g at (%g, %g, %g), expected 2 at x = +-2, y = 0", fabs(k), p[0], p[1],
          p[2]);
    CHECK(k == (fabs(r.kmin) > fabs(r.kmax) ? r.kmin : r.kmax), "elliptic cylinder: k %g is not kmin %g or kmax %g",
          k, r.kmin, r.kmax);
    /* the text's line gives |k| and its radius 1 / |k| = 0.5 */
    char *text = NULL;
    CHECK_OK(rg2_check_format(&r, 0, &text, &err), &err);
    const char *line = text ? strstr(text, "  largest |k|        ") : NULL;
    CHECK(line && !strncmp(line, "  largest |k|        2 (radius 0.5) at surface 0 patch (", 56),
          "elliptic cylinder: the largest |k| line: %.100s", line ? line : "(none)");
    free(text);
    rg2_check_report_free(&r);
    rg2_surface_free(&s);

    rg2_mesh m;
    CHECK_OK(rg2t_torus(3, 1, 8, 6, &m, &s, &err), &err);
    rg2_surface_free(&s);
    double *q = m.p + (2 * m.nv + 3) * 4, d[3] = {0.3, 0.2, 0.4};
    for (int t = 0; t < 3; t++)
        q[t] += d[t] * q[3];
    CHECK_OK(rg2_surface_build(&m, &s, &err), &err);
    rg2_check_opts o;
    rg2_check_opts_default(&o);
    int S = o.patch_samples, bi = -1, bj = -1, ba = 0, bb = 0;
    double best = 0, x[3];
    for (int i = 0; i < s.nu; i++)
        for (int j = 0; j < s.nv; j++)
            for (int a = 0; a <= S; a++)
                for (int b = 0; b <= S; b++) {
                    double kk = larger_k(&s, i, j, (double)a / S, (double)b / S, x);
                    if (fabs(kk) > fabs(best) || (bi < 0 && !isnan(kk))) {
                        best = kk;
                        bi = i, bj = j, ba = a, bb = b;
                    }
                }
    for (int th = 1; th <= 4; th++) {
        o.threads = th;
        CHECK_OK(rg2_check(&s, 1, NULL, NULL, 0, &o, &r, &err), &err);
        larger_k(&s, bi, bj, (double)ba / S, (double)bb / S, x);
        CHECK(r.kpeak.surf == 0 && r.kpeak.pi == bi && r.kpeak.pj == bj && r.kpeak.u == (double)ba / S &&
                  r.kpeak.v == (double)bb / S && r.kpeak_k == best && !memcmp(r.kpeak.p, x, sizeof x),
              "torus with a moved point, %d thread(s): largest |k| %.17g at patch (%d,%d) u=%g v=%g, expected %.17g "
              "at (%d,%d) u=%g v=%g", th, r.kpeak_k, r.kpeak.pi, r.kpeak.pj, r.kpeak.u, r.kpeak.v, best, bi, bj,
              (double)ba / S, (double)bb / S);
        char *json = NULL;
        CHECK_OK(rg2_check_format(&r, 1, &json, &err), &err);
        cJSON *j = json ? cJSON_Parse(json) : NULL, *kp = cJSON_GetObjectItem(j, "largest_curvature");
        cJSON *jk = cJSON_GetObjectItem(kp, "k");
        CHECK(cJSON_IsNumber(jk) && jk->valuedouble == best, "JSON largest_curvature.k %.17g, expected %.17g",
              cJSON_IsNumber(jk) ? jk->valuedouble : NAN, best);
        /* every number reads back to the report's own double (cJSON's 15 digits dropped the last
         * bit of some: the point copied into a design's "to" must be the sample's) */
        int bits = json_point_is(cJSON_GetObjectItem(kp, "point"), r.kpeak.p) &&
                   json_is(cJSON_GetObjectItem(kp, "u"), r.kpeak.u) && json_is(cJSON_GetObjectItem(kp, "v"), r.kpeak.v);
        cJSON *g2 = cJSON_GetObjectItem(j, "g2_curvature_jump");
        bits = bits && json_is(cJSON_GetObjectItem(g2, "value"), r.g2.value) &&
               json_is(cJSON_GetObjectItem(g2, "t"), r.g2.t) && json_point_is(cJSON_GetObjectItem(g2, "point"), r.g2.p);
        cJSON *w = cJSON_GetObjectItem(j, "weights");
        bits = bits && json_is(cJSON_GetArrayItem(w, 0), r.wmin) && json_is(cJSON_GetArrayItem(w, 1), r.wmax) &&
               json_is(cJSON_GetObjectItem(j, "min_weight_at_samples"), r.eval_wmin) &&
               json_is(cJSON_GetObjectItem(j, "size"), r.size);
        CHECK(bits, "%d thread(s): the JSON's largest_curvature u, v, point, G2 gap value, t, point, weights "
              "and size read back bit for bit", th);
        cJSON_Delete(j);
        free(json);
        rg2_check_report_free(&r);
    }
    printf("torus with a moved point: largest |k| %.6g (radius %.4g) at patch (%d,%d) u=%g v=%g on 1-4 threads, as "
           "scanned\n", fabs(best), 1 / fabs(best), bi, bj, (double)ba / S, (double)bb / S);
    rg2_surface_free(&s);
    rg2_mesh_free(&m);
}

/* rg2_surface_shape_residuals (rg2 check --on): every patch of a tilted torus lies on it, with the
 * worst residual rg2_check finds for the tagged patches (the same samples and, every patch tagged,
 * the same size); a control point moved off the torus takes exactly the 4 x 4 patches of its
 * support off it (a bi-3 patch (i, j) of a closed mesh reads the points i - 1..i + 2, j - 1..j + 2),
 * untagged as they are; no patch lies on a sphere through the torus; bad arguments are named. */
static void shape_residuals(void)
{
    rg2_shape sh, ball;
    rg2_shape_init(&sh, RG2_SHAPE_TORUS);
    sh.param[0] = 3;
    sh.param[1] = 1;
    rg2_xform_rotate(sh.xform, 1, 2, 3, 0.7);
    rg2_shape_init(&ball, RG2_SHAPE_SPHERE);
    ball.param[0] = 4;
    rg2_error err;
    rg2_surface s;
    torus_8x6(&sh, &s);
    double res[48];
    rg2_check_report r;
    CHECK_OK(rg2_surface_shape_residuals(&s, &sh, 12, res, &err), &err);
    CHECK_OK(rg2_check(&s, 1, &sh, NULL, 1, NULL, &r, &err), &err);
    double worst = 0;
    for (int k = 0; k < 48; k++)
        worst = fmax(worst, res[k]);
    CHECK(worst <= 1e-13 && worst == r.worst_residual, "torus on its torus: worst %.3g, rg2_check %.3g", worst,
          r.worst_residual);
    rg2_check_report_free(&r);
    CHECK_OK(rg2_surface_shape_residuals(&s, &ball, 3, res, &err), &err);
    double nearest = INFINITY;
    for (int k = 0; k < 48; k++)
        nearest = fmin(nearest, res[k]);
    CHECK(nearest > 1e-3, "torus patches on a sphere of radius 4: nearest %.3g", nearest);
    /* a control point moved outward by 0.05 of the size: the 16 patches of its support leave */
    double au[9], av[7];
    rg2_partition pu, pv;
    rg2_mesh m;
    rg2_surface t;
    CHECK_OK(rg2_partition_equal(&pu, RG2_PART_ANGLES, 1, 0, 0, 8, au, 9, &err), &err);
    CHECK_OK(rg2_partition_equal(&pv, RG2_PART_ANGLES, 1, 0, 0, 6, av, 7, &err), &err);
    CHECK_OK(rg2_shape_mesh(&sh, &pu, &pv, &m, &err), &err);
    double *q = rg2_mesh_at(&m, 0, 2);
    for (int k = 0; k < 3; k++)
        q[k] *= 1.05;
    CHECK_OK(rg2_surface_build(&m, &t, &err), &err);
    CHECK(t.tag == NULL, "a built surface is untagged");
    CHECK_OK(rg2_surface_shape_residuals(&t, &sh, 12, res, &err), &err);
    int off = 0, wrong = 0;
    double on_worst = 0, off_least = INFINITY;
    for (int i = 0; i < 8; i++)
        for (int j = 0; j < 6; j++) {
            int di = (0 - i + 8) % 8, dj = (2 - j + 6) % 6; /* control index minus patch index, cyclic */
            int near = (di <= 2 || di == 7) && (dj <= 2 || dj == 5);
            double x = res[i * 6 + j];
            off += x > 1e-11;
            wrong += near != (x > 1e-11);
            if (near)
                off_least = fmin(off_least, x);
            else
                on_worst = fmax(on_worst, x);
        }
    printf("shape residuals: torus %.2e on its torus (rg2_check the same); a control point moved: %d patches off "
           "(least %.2e), the others %.2e; on a sphere: nearest %.2e\n", worst, off, off_least, on_worst, nearest);
    CHECK(off == 16 && wrong == 0 && on_worst <= 1e-13, "moved point: %d patches off, %d misplaced, others %.3g", off,
          wrong, on_worst);
    /* samples = 1: the four corners of each patch, against |f| / |grad f| computed here */
    double res1[48], lo[3] = {INFINITY, INFINITY, INFINITY}, hi[3] = {-INFINITY, -INFINITY, -INFINITY};
    for (int k = 0; k < t.nu * t.nv * 16; k++) {
        const double *h = t.patch[k / 16].h[k % 16 / 4][k % 4];
        for (int c = 0; c < 3; c++)
            lo[c] = fmin(lo[c], h[c] / h[3]), hi[c] = fmax(hi[c], h[c] / h[3]);
    }
    double size = sqrt((hi[0] - lo[0]) * (hi[0] - lo[0]) + (hi[1] - lo[1]) * (hi[1] - lo[1]) +
                       (hi[2] - lo[2]) * (hi[2] - lo[2]));
    CHECK_OK(rg2_surface_shape_residuals(&t, &sh, 1, res1, &err), &err);
    double corner_err = 0;
    for (int k = 0; k < 48; k++) {
        double w = 0;
        for (int c = 0; c < 4; c++) {
            rg2_eval e;
            double g[3];
            rg2_surface_eval(&t, k / 6, k % 6, c / 2, c % 2, 0, &e);
            double f = rg2_shape_implicit(&sh, e.p, g);
            w = fmax(w, fabs(f) / sqrt(g[0] * g[0] + g[1] * g[1] + g[2] * g[2]) / size);
        }
        corner_err = fmax(corner_err, fabs(res1[k] - w) - 1e-12 * w); /* (over a rounding allowance) */
    }
    CHECK(corner_err <= 1e-18, "samples = 1: the corners' residuals off by %.3g", corner_err);
    /* errors */
    rg2_status st = rg2_surface_shape_residuals(&t, &sh, 0, res, &err);
    CHECK(st == RG2_EINVAL && strstr(err.msg, "samples 0 outside 1..1000"), "samples 0: %d %s", st, err.msg);
    st = rg2_surface_shape_residuals(&t, &sh, 1001, res, &err);
    CHECK(st == RG2_EINVAL && strstr(err.msg, "samples 1001 outside 1..1000"), "samples 1001: %d %s", st, err.msg);
    /* the least samples, 1: the patch corners, on the torus but for the moved point's 16 patches */
    CHECK_OK(rg2_surface_shape_residuals(&t, &sh, 1, res, &err), &err);
    int far = 0;
    for (int k = 0; k < 48; k++)
        far += !(res[k] <= 1e-11);
    CHECK(far > 0 && far <= 16, "samples 1: %d patches off the torus", far);
    rg2_surface none = {.nu = 0, .nv = 6, .patch = t.patch}; /* (no patches, though a patch array) */
    st = rg2_surface_shape_residuals(&none, &sh, 4, res, &err);
    CHECK(st == RG2_EINVAL && strstr(err.msg, "the surface has no patches"), "no patches: %d %s", st, err.msg);
    /* 1000 patches x 1001^2 samples pass RG2_MAX_CHECK_SAMPLES: refused before any patch is read
       (the view's patch array is the 48 of t) */
    rg2_surface wide = {.nu = 1000, .nv = 1, .patch = t.patch};
    char want[160];
    snprintf(want, sizeof want, "shape residuals: 1000 patches x 1001 x 1001 samples exceed the limit of %d",
             RG2_MAX_CHECK_SAMPLES);
    st = rg2_surface_shape_residuals(&wide, &sh, 1000, res, &err);
    CHECK(st == RG2_ELIMIT && !strcmp(err.msg, want), "over the limit: %d %s", st, err.msg);
    st = rg2_surface_shape_residuals(&t, NULL, 4, res, &err);
    CHECK(st == RG2_EINVAL && strstr(err.msg, "no shape"), "no shape: %d %s", st, err.msg);
    st = rg2_surface_shape_residuals(&t, &sh, 4, NULL, &err);
    CHECK(st == RG2_EINVAL && strstr(err.msg, "no residual array"), "no res: %d %s", st, err.msg);
    rg2_surface_free(&t);
    rg2_mesh_free(&m);
    rg2_surface_free(&s);
}

/* ------------------------------------------------ the formatted report, on reports made by hand */

/* The promises report r breaks, from their definitions in rg2.h and the usage (not from
 * rg2_check_failures): g0 the position gap over its limit; g1 that, or the normal angle over
 * its limit, a sample next to a pole or ill-conditioned over its own bound (gap / limit > 1),
 * a sample not measured, every sample on a pole, a fold or a singular sample; g2 that, or a
 * curvature jump over its limit or over its own bound; exact a residual over its limit, a tag
 * beyond the shapes, or no exact patch; weights a weight <= 0 at a control point or sample;
 * no-crossings not searched, or a crossing. */
static unsigned want_failures(const rg2_check_report *r)
{
    const rg2_check_opts *o = &r->opts;
    int g0 = !(r->g0.value <= o->tol_g0);
    int irregular = r->unmeasured > 0 || (r->seams > 0 && r->seam_samples == r->pole_samples) || r->folds > 0 ||
                    r->singular > 0;
    int g1 = g0 || irregular || !(r->g1.value <= o->tol_g1) || !(r->g1_pole.value <= 1) || !(r->g1_ill.value <= 1);
    int g2 = g1 || !(r->g2.value <= o->tol_g2) || !(r->g2_pole.value <= 1) || !(r->g2_ill.value <= 1);
    int exact = r->worst_residual <= o->tol_exact && r->untagged_bad == 0 && r->exact_patches > 0;
    int weights = r->wmin > 0 && r->eval_wmin > 0;
    int crossings = r->crossings.density == 0 || r->crossings.crossings > 0;
    return (g0 ? RG2_REQUIRE_G0 : 0u) | (g1 ? RG2_REQUIRE_G1 : 0u) | (g2 ? RG2_REQUIRE_G2 : 0u) |
           (exact ? 0u : RG2_REQUIRE_EXACT) | (weights ? 0u : RG2_REQUIRE_WEIGHTS) |
           (crossings ? RG2_REQUIRE_NO_CROSSINGS : 0u);
}

/* A value against limit lim: 0, below, at, one ulp over, or well over it. */
static double around(rg2t_rng *g, double lim)
{
    switch (rg2t_int(g, 0, 4)) {
    case 0:
        return 0;
    case 1:
        return lim * rg2t_uniform(g, 0.01, 0.99);
    case 2:
        return lim;
    case 3:
        return nextafter(lim, INFINITY);
    default:
        return lim * rg2t_uniform(g, 1.5, 1e3);
    }
}

static void random_gap(rg2t_rng *g, rg2_check_gap *gap, double lim)
{
    gap->value = around(g, lim);
    gap->surf = rg2t_int(g, 0, 3);
    gap->seam_dir = rg2t_int(g, 0, 1);
    gap->pi = rg2t_int(g, 0, 9), gap->pj = rg2t_int(g, 0, 9), gap->qi = rg2t_int(g, 0, 9), gap->qj = rg2t_int(g, 0, 9);
    gap->t = rg2t_uniform(g, 0, 1);
    for (int k = 0; k < 3; k++)
        gap->p[k] = rg2t_uniform(g, -10, 10);
}

static void random_sample(rg2t_rng *g, rg2_check_sample *s)
{
    s->surf = rg2t_int(g, 0, 3), s->pi = rg2t_int(g, 0, 9), s->pj = rg2t_int(g, 0, 9);
    s->u = rg2t_uniform(g, 0, 1), s->v = rg2t_uniform(g, 0, 1);
    for (int k = 0; k < 3; k++)
        s->p[k] = rg2t_uniform(g, -10, 10);
}

/* A report with every count either 0 or not and every value around its limit (shapes: room
 * for 12). */
static void random_report(rg2t_rng *g, rg2_check_report *r, rg2_check_shape *shapes)
{
    memset(r, 0, sizeof *r);
    rg2_check_opts_default(&r->opts);
    r->opts.seam_samples = rg2t_int(g, 1, 40);
    r->opts.tol_g0 = rg2t_uniform(g, 1e-13, 1e-6), r->opts.tol_g1 = rg2t_uniform(g, 1e-13, 1e-6);
    r->opts.tol_g2 = rg2t_uniform(g, 1e-13, 1e-6), r->opts.tol_exact = rg2t_uniform(g, 1e-13, 1e-6);
    r->surfaces = rg2t_int(g, 1, 4), r->patches = rg2t_int(g, 1, 60);
    r->exact_patches = rg2t_int(g, 0, 1) * rg2t_int(g, 1, r->patches), r->transitions = r->patches - r->exact_patches;
    r->untagged_bad = rg2t_int(g, 0, 2) == 0 ? rg2t_int(g, 1, 3) : 0;
    r->n_shapes = rg2t_int(g, 0, 12);
    r->shapes = shapes;
    for (int k = 0; k < r->n_shapes; k++) {
        shapes[k].shape = k;
        snprintf(shapes[k].label, sizeof shapes[k].label, "shape%d_%.*s", k, rg2t_int(g, 0, 40),
                 "abcdefghijklmnopqrstuvwxyzabcdefghijklmn");
        shapes[k].patches = rg2t_int(g, 0, 3);
        shapes[k].residual = around(g, r->opts.tol_exact);
        shapes[k].limit = 0; /* (no limit of its own: held to tol_exact) */
        snprintf(shapes[k].where, sizeof shapes[k].where, "patch (%d,%d) u=%.3g v=%.3g", rg2t_int(g, 0, 9),
                 rg2t_int(g, 0, 9), rg2t_uniform(g, 0, 1), rg2t_uniform(g, 0, 1));
    }
    r->worst_residual = around(g, r->opts.tol_exact);
    r->seams = rg2t_int(g, 0, 3) ? rg2t_int(g, 1, 100) : 0;
    r->seam_samples = r->seams * (r->opts.seam_samples + 1);
    r->pole_samples = rg2t_int(g, 0, 3) == 0 ? r->seam_samples : rg2t_int(g, 0, r->seam_samples / 2);
    r->unmeasured = rg2t_int(g, 0, 3) == 0 ? rg2t_int(g, 1, 5) : 0;
    r->pole_unresolved = rg2t_int(g, 0, 3) == 0 ? rg2t_int(g, 1, 5) : 0;
    r->pole_unresolved_dist = r->pole_unresolved ? rg2t_uniform(g, 1e-4, 0.25) : 0;
    r->skipped = r->pole_samples + r->pole_unresolved + r->unmeasured;
    random_gap(g, &r->g0, r->opts.tol_g0);
    random_gap(g, &r->g1, r->opts.tol_g1);
    random_gap(g, &r->g2, r->opts.tol_g2);
    r->near_pole = rg2t_int(g, 0, 1) ? rg2t_int(g, 1, 50) : 0;
    r->near_pole_tol1 = rg2t_uniform(g, 1e-12, 1e-4), r->near_pole_tol2 = rg2t_uniform(g, 1e-12, 1e-2);
    random_gap(g, &r->g1_pole, 1.0);
    random_gap(g, &r->g2_pole, 1.0);
    r->ill_conditioned = rg2t_int(g, 0, 1) ? rg2t_int(g, 1, 50) : 0;
    r->ill_tol1 = rg2t_uniform(g, 1e-12, 1e-4), r->ill_tol2 = rg2t_uniform(g, 1e-12, 1e-2);
    random_gap(g, &r->g1_ill, 1.0);
    random_gap(g, &r->g2_ill, 1.0);
    r->folds = rg2t_int(g, 0, 3) == 0 ? rg2t_int(g, 1, 9) : 0;
    r->singular = rg2t_int(g, 0, 3) == 0 ? rg2t_int(g, 1, 9) : 0;
    random_sample(g, &r->fold_at);
    r->wmin = rg2t_uniform(g, -1, 1), r->wmax = r->wmin + rg2t_uniform(g, 0, 2);
    r->eval_wmin = rg2t_int(g, 0, 3) ? fabs(r->wmin) + 0.1 : rg2t_uniform(g, -1, 0.1);
    r->kmin = rg2t_uniform(g, -5, 0), r->kmax = rg2t_uniform(g, 0, 5);
    r->Hmin = rg2t_uniform(g, -5, 0), r->Hmax = rg2t_uniform(g, 0, 5);
    r->Kmin = rg2t_uniform(g, -5, 0), r->Kmax = rg2t_uniform(g, 0, 5);
    random_sample(g, &r->kpeak);
    r->kpeak.surf = rg2t_int(g, 0, 3) ? r->kpeak.surf : -1;
    r->kpeak_k = rg2t_int(g, 0, 3) ? (rg2t_int(g, 0, 1) ? r->kmin : r->kmax) : 0;
    r->size = rg2t_uniform(g, 0.1, 100);
    rg2_crossing_report *c = &r->crossings;
    if (rg2t_int(g, 0, 1)) {
        c->density = rg2t_int(g, 1, 1000), c->triangles = rg2t_int(g, 2, 100000);
        c->pairs = rg2t_int(g, 0, 100000), c->candidates = rg2t_int(g, 0, 100);
        c->crossings = rg2t_int(g, 0, 1) ? rg2t_int(g, 1, 10) : 0;
        rg2_check_sample a, b;
        random_sample(g, &a), random_sample(g, &b);
        c->a = (rg2_crossing_sheet){.surf = a.surf, .pi = a.pi, .pj = a.pj, .u = a.u, .v = a.v};
        c->b = (rg2_crossing_sheet){.surf = b.surf, .pi = b.pi, .pj = b.pj, .u = b.u, .v = b.v};
        memcpy(c->p, a.p, sizeof c->p);
        c->angle = rg2t_uniform(g, 1e-3, 1.5), c->residual = rg2t_uniform(g, 0, 1e-9), c->size = r->size;
    }
}

/* A member of o as a number (NaN when missing or not a number). */
static double jnum(const cJSON *o, const char *name)
{
    const cJSON *x = cJSON_GetObjectItem(o, name);
    return cJSON_IsNumber(x) ? x->valuedouble : NAN;
}

/* The n numbers of array member `name` of o equal x[0..n) (exactly: they read back). */
static int jarr_is(const cJSON *o, const char *name, const double *x, int n)
{
    const cJSON *a = cJSON_GetObjectItem(o, name);
    int same = cJSON_IsArray(a) && cJSON_GetArraySize(a) == n;
    for (int k = 0; k < n && same; k++)
        same = cJSON_IsNumber(cJSON_GetArrayItem(a, k)) && cJSON_GetArrayItem(a, k)->valuedouble == x[k];
    return same;
}

/* A gap object of the JSON report holds g, its limit and verdict ok. */
static int jgap_is(const cJSON *o, const rg2_check_gap *g, double lim, int ok)
{
    const cJSON *seam = cJSON_GetObjectItem(o, "seam"), *okj = cJSON_GetObjectItem(o, "ok");
    double a[2] = {g->pi, g->pj}, b[2] = {g->qi, g->qj};
    return jnum(o, "value") == g->value && jnum(o, "limit") == lim && cJSON_IsBool(okj) && cJSON_IsTrue(okj) == ok &&
           jnum(o, "surface") == g->surf && cJSON_IsString(seam) && !strcmp(seam->valuestring, g->seam_dir ? "v" : "u") &&
           jarr_is(o, "patch_a", a, 2) && jarr_is(o, "patch_b", b, 2) && jnum(o, "t") == g->t && jarr_is(o, "point", g->p, 3);
}

/* Sample members surface, patch, u, v, point of o hold s. */
static int jsample_is(const cJSON *o, const rg2_check_sample *s)
{
    double ij[2] = {s->pi, s->pj};
    return jnum(o, "surface") == s->surf && jarr_is(o, "patch", ij, 2) && jnum(o, "u") == s->u &&
           jnum(o, "v") == s->v && jarr_is(o, "point", s->p, 3);
}

/* The line of text that begins with `start` (copied into line; 0 if none). */
static int text_line(const char *text, const char *start, char *line, size_t size)
{
    size_t n = strlen(start);
    for (const char *p = text; p && *p; p = strchr(p, '\n') ? strchr(p, '\n') + 1 : NULL)
        if (!strncmp(p, start, n)) {
            size_t l = strcspn(p, "\n");
            snprintf(line, size, "%.*s", (int)(l < size ? l : size - 1), p);
            return 1;
        }
    line[0] = '\0';
    return 0;
}

/* The JSON report of r read back field by field. */
static void json_matches(const rg2_check_report *r, const char *js, unsigned want, int trial)
{
    const rg2_check_opts *o = &r->opts;
    cJSON *j = cJSON_Parse(js);
    CHECK(j != NULL, "report %d: the JSON parses", trial);
    if (!j)
        return;
    CHECK(jnum(j, "surfaces") == r->surfaces && jnum(j, "patches") == r->patches &&
              jnum(j, "exact_patches") == r->exact_patches && jnum(j, "transitions") == r->transitions &&
              jnum(j, "unknown_tags") == r->untagged_bad && jnum(j, "worst_residual") == r->worst_residual &&
              jnum(j, "exact_limit") == o->tol_exact && jnum(j, "seams") == r->seams &&
              jnum(j, "seam_samples") == r->seam_samples && jnum(j, "skipped") == r->skipped &&
              jnum(j, "pole_samples") == r->pole_samples && jnum(j, "unmeasured") == r->unmeasured &&
              jnum(j, "size") == r->size && jnum(j, "min_weight_at_samples") == r->eval_wmin,
          "report %d: the JSON counts", trial);
    const cJSON *sh = cJSON_GetObjectItem(j, "shapes");
    CHECK(cJSON_GetArraySize(sh) == r->n_shapes, "report %d: %d JSON shapes of %d", trial, cJSON_GetArraySize(sh),
          r->n_shapes);
    for (int k = 0; k < r->n_shapes && k < cJSON_GetArraySize(sh); k++) {
        const cJSON *s = cJSON_GetArrayItem(sh, k), *ok = cJSON_GetObjectItem(s, "ok");
        const cJSON *label = cJSON_GetObjectItem(s, "label"), *where = cJSON_GetObjectItem(s, "where");
        CHECK(jnum(s, "index") == k && cJSON_IsString(label) && !strcmp(label->valuestring, r->shapes[k].label) &&
                  jnum(s, "patches") == r->shapes[k].patches && jnum(s, "residual") == r->shapes[k].residual &&
                  cJSON_IsBool(ok) && cJSON_IsTrue(ok) == (r->shapes[k].residual <= o->tol_exact) &&
                  cJSON_IsString(where) && !strcmp(where->valuestring, r->shapes[k].where),
              "report %d: JSON shape %d", trial, k);
    }
    const cJSON *rg = cJSON_GetObjectItem(j, "regularity");
    int irregular = r->folds || r->singular;
    CHECK(jnum(rg, "folds") == r->folds && jnum(rg, "singular") == r->singular &&
              (irregular ? jsample_is(rg, &r->fold_at) : !cJSON_GetObjectItem(rg, "point")),
          "report %d: JSON regularity (folds %d, singular %d)", trial, r->folds, r->singular);
    CHECK(jgap_is(cJSON_GetObjectItem(j, "g0_position"), &r->g0, o->tol_g0, !(want & RG2_REQUIRE_G0)) &&
              jgap_is(cJSON_GetObjectItem(j, "g1_normal_angle"), &r->g1, o->tol_g1, !(want & RG2_REQUIRE_G1)) &&
              jgap_is(cJSON_GetObjectItem(j, "g2_curvature_jump"), &r->g2, o->tol_g2, !(want & RG2_REQUIRE_G2)),
          "report %d: JSON G0/G1/G2 (failures %#x)", trial, want);
    const cJSON *np = cJSON_GetObjectItem(j, "near_pole"), *ic = cJSON_GetObjectItem(j, "ill_conditioned");
    CHECK(jnum(np, "samples") == r->near_pole && jnum(np, "unresolved") == r->pole_unresolved &&
              jnum(np, "unresolved_distance") == r->pole_unresolved_dist &&
              jnum(np, "g1_limit_max") == fmax(r->near_pole_tol1, o->tol_g1) &&
              jnum(np, "g2_limit_max") == fmax(r->near_pole_tol2, o->tol_g2) &&
              jgap_is(cJSON_GetObjectItem(np, "g1_gap_over_limit"), &r->g1_pole, 1, r->g1_pole.value <= 1) &&
              jgap_is(cJSON_GetObjectItem(np, "g2_gap_over_limit"), &r->g2_pole, 1, r->g2_pole.value <= 1) &&
              jnum(ic, "samples") == r->ill_conditioned && jnum(ic, "g1_limit_max") == fmax(r->ill_tol1, o->tol_g1) &&
              jnum(ic, "g2_limit_max") == fmax(r->ill_tol2, o->tol_g2) &&
              jgap_is(cJSON_GetObjectItem(ic, "g1_gap_over_limit"), &r->g1_ill, 1, r->g1_ill.value <= 1) &&
              jgap_is(cJSON_GetObjectItem(ic, "g2_gap_over_limit"), &r->g2_ill, 1, r->g2_ill.value <= 1),
          "report %d: JSON near_pole / ill_conditioned", trial);
    double w[2] = {r->wmin, r->wmax}, k[2] = {r->kmin, r->kmax}, h[2] = {r->Hmin, r->Hmax}, K[2] = {r->Kmin, r->Kmax};
    CHECK(jarr_is(j, "weights", w, 2) && jarr_is(j, "principal_curvature", k, 2) && jarr_is(j, "mean_curvature", h, 2) &&
              jarr_is(j, "gauss_curvature", K, 2),
          "report %d: JSON weights and curvature ranges", trial);
    const cJSON *kp = cJSON_GetObjectItem(j, "largest_curvature");
    CHECK(r->kpeak.surf >= 0 ? kp && jnum(kp, "k") == r->kpeak_k && jsample_is(kp, &r->kpeak) : !kp,
          "report %d: JSON largest_curvature (surface %d)", trial, r->kpeak.surf);
    const rg2_crossing_report *c = &r->crossings;
    const cJSON *x = cJSON_GetObjectItem(j, "crossings"), *xok = cJSON_GetObjectItem(x, "ok");
    int sheets = 1;
    for (int s = 0; s < 2 && c->crossings; s++) {
        const rg2_crossing_sheet *e = s ? &c->b : &c->a;
        const cJSON *js_ = cJSON_GetObjectItem(x, s ? "b" : "a");
        double ij[2] = {e->pi, e->pj}, uv[2] = {e->u, e->v};
        sheets = sheets && jnum(js_, "surface") == e->surf && jarr_is(js_, "patch", ij, 2) && jarr_is(js_, "uv", uv, 2);
    }
    CHECK(c->density > 0 ? x && jnum(x, "density") == c->density && jnum(x, "triangles") == c->triangles &&
                               jnum(x, "pairs") == c->pairs && jnum(x, "candidates") == c->candidates &&
                               jnum(x, "crossings") == c->crossings && cJSON_IsBool(xok) &&
                               cJSON_IsTrue(xok) == !(want & RG2_REQUIRE_NO_CROSSINGS) && sheets &&
                               (c->crossings ? jarr_is(x, "point", c->p, 3) && jnum(x, "angle") == c->angle &&
                                                   jnum(x, "residual") == c->residual
                                             : !cJSON_GetObjectItem(x, "a") && !cJSON_GetObjectItem(x, "point"))
                         : !x,
          "report %d: JSON crossings (density %d, %d crossings)", trial, c->density, c->crossings);
    CHECK(cJSON_IsBool(cJSON_GetObjectItem(j, "g2")) && cJSON_IsBool(cJSON_GetObjectItem(j, "exact")) &&
              cJSON_IsBool(cJSON_GetObjectItem(j, "positive_weights")) &&
              cJSON_IsTrue(cJSON_GetObjectItem(j, "g2")) == !(want & RG2_REQUIRE_G2) &&
              cJSON_IsTrue(cJSON_GetObjectItem(j, "exact")) == !(want & RG2_REQUIRE_EXACT) &&
              cJSON_IsTrue(cJSON_GetObjectItem(j, "positive_weights")) == !(want & RG2_REQUIRE_WEIGHTS),
          "report %d: JSON promises (failures %#x)", trial, want);
    cJSON_Delete(j);
}

/* The row of a gap in the text table names verdict `v` ("ok", "FAIL" or "-" without seams) and,
 * when the row has a verdict and a gap, where it is. */
static void text_gap_row(const char *text, const char *name, const rg2_check_gap *g, const char *v, int trial)
{
    char line[512], at[160], want_v[16];
    snprintf(at, sizeof at, "at surface %d %s seam (%d,%d)|(%d,%d)", g->surf, g->seam_dir ? "v" : "u", g->pi, g->pj,
             g->qi, g->qj);
    snprintf(want_v, sizeof want_v, " %-4s (limit", v);
    CHECK(text_line(text, name, line, sizeof line) && strstr(line, want_v) &&
              !strstr(line, at) == (!strcmp(v, "-") || !(g->value > 0)),
          "report %d: the row '%s' wants '%s'%s: %s", trial, name, v, g->value > 0 ? " and where" : "", line);
}

/* A block of samples against their own bound ("next to a pole", "ill-conditioned") is there
 * when n > 0 with the verdicts of g1 and g2 over their bound 1, and where the larger is. */
static void text_rounded(const char *text, const char *name, int n, const rg2_check_gap *g1, const rg2_check_gap *g2,
                         int trial)
{
    char head[512], want[160];
    int has = text_line(text, name, head, sizeof head);
    CHECK(has == (n > 0), "report %d: '%s' %s with %d samples", trial, name, has ? "shown" : "not shown", n);
    if (!has)
        return;
    const char *next = strstr(text, head) + strlen(head) + 1, *end = strchr(next, '\n');
    snprintf(want, sizeof want, "G1 %.2g %s, G2 %.2g %s", g1->value, g1->value <= 1 ? "ok" : "FAIL", g2->value,
             g2->value <= 1 ? "ok" : "FAIL");
    const rg2_check_gap *w = g2->value >= g1->value ? g2 : g1;
    char at[160];
    snprintf(at, sizeof at, "at surface %d %s seam (%d,%d)|(%d,%d)", w->surf, w->seam_dir ? "v" : "u", w->pi, w->pj,
             w->qi, w->qj);
    char *row = end ? strstr(next, want) : NULL, *where = end ? strstr(next, at) : NULL;
    CHECK(row && row < end && (g2->value > 0 ? where && where < end : !strstr(next, "  at surface") ||
                                                                            strstr(next, "  at surface") > end),
          "report %d: '%s' wants '%s'%s: %.*s", trial, name, want, g2->value > 0 ? " and where" : "",
          end ? (int)(end - next) : 0, next);
}

/* The text table of r: the verdicts and the lines present as the report's own values say. */
static void text_matches(const rg2_check_report *r, const char *text, unsigned want, int trial)
{
    const rg2_check_opts *o = &r->opts;
    char line[512], want_s[160];
    int has = r->seams > 0;
    snprintf(want_s, sizeof want_s, "seams %d, %d samples (%d per seam): %d at a pole", r->seams, r->seam_samples,
             o->seam_samples + 1, r->pole_samples);
    CHECK(strstr(text, want_s) != NULL, "report %d: wants '%s'", trial, want_s);
    text_gap_row(text, "  G0 position gap", &r->g0, !has ? "-" : want & RG2_REQUIRE_G0 ? "FAIL" : "ok", trial);
    text_gap_row(text, "  G1 normal angle", &r->g1, !has ? "-" : want & RG2_REQUIRE_G1 ? "FAIL" : "ok", trial);
    text_gap_row(text, "  G2 curvature jump", &r->g2, !has ? "-" : want & RG2_REQUIRE_G2 ? "FAIL" : "ok", trial);
    text_rounded(text, "  next to a pole", r->near_pole, &r->g1_pole, &r->g2_pole, trial);
    text_rounded(text, "  ill-conditioned", r->ill_conditioned, &r->g1_ill, &r->g2_ill, trial);
    snprintf(want_s, sizeof want_s, "%d samples up to %.3g from a pole", r->pole_unresolved, r->pole_unresolved_dist);
    int close = text_line(text, "  too close to a pole", line, sizeof line);
    CHECK(close == !!r->pole_unresolved && (!close || strstr(line, want_s)),
          "report %d: %d samples too close to a pole, up to %.3g: %s", trial, r->pole_unresolved,
          r->pole_unresolved_dist, close ? line : "(no line)");
    CHECK(!text_line(text, "  NOT MEASURED", line, sizeof line) ==
              !(r->unmeasured || (has && r->seam_samples == r->pole_samples)),
          "report %d: NOT MEASURED with %d unmeasured, %d of %d samples on a pole", trial, r->unmeasured,
          r->pole_samples, r->seam_samples);
    snprintf(want_s, sizeof want_s, "first at surface %d patch (%d,%d)", r->fold_at.surf, r->fold_at.pi, r->fold_at.pj);
    int irr = text_line(text, "  NOT REGULAR", line, sizeof line);
    CHECK(irr == (r->folds || r->singular) && (!irr || strstr(line, want_s)), "report %d: NOT REGULAR (%d, %d): %s",
          trial, r->folds, r->singular, line);
    CHECK(text_line(text, "  NO EXACT PATCH", line, sizeof line) == (r->exact_patches == 0),
          "report %d: NO EXACT PATCH with %d exact patches", trial, r->exact_patches);
    for (int k = 0; k < r->n_shapes; k++) {
        const rg2_check_shape *s = &r->shapes[k];
        char start[96], label[96], v[16];
        int idx = -1, patches = -1;
        double res = NAN;
        snprintf(start, sizeof start, "  %2d %s ", k, s->label);
        int row = text_line(text, start, line, sizeof line) &&
                  sscanf(line, "%d %95s %d %lf %15s", &idx, label, &patches, &res, v) == 5;
        CHECK(row && patches == s->patches && rel(res, s->residual) < 1e-2 &&
                  !strcmp(v, !s->patches ? "-" : s->residual <= o->tol_exact ? "ok" : "FAIL") && strstr(line, s->where),
              "report %d: shape row %d: %s", trial, k, line);
    }
    CHECK((strstr(text, "(NON-POSITIVE)") == NULL) == (r->wmin > 0), "report %d: weights from %g", trial, r->wmin);
    CHECK(text_line(text, "  largest |k|", line, sizeof line) == (r->kpeak.surf >= 0 && r->kpeak_k != 0),
          "report %d: largest |k| %g at surface %d", trial, r->kpeak_k, r->kpeak.surf);
    const rg2_crossing_report *c = &r->crossings;
    int xl = text_line(text, "crossings ", line, sizeof line);
    size_t len = strlen(line);
    const char *xv = c->crossings ? " FAIL" : " ok";
    CHECK(xl == (c->density > 0) && (!xl || (len > strlen(xv) && !strcmp(line + len - strlen(xv), xv))),
          "report %d: crossings (density %d, %d): %s", trial, c->density, c->crossings, line);
    snprintf(want_s, sizeof want_s, "  first at surface %d patch (%d,%d)", c->a.surf, c->a.pi, c->a.pj);
    CHECK(!text_line(text, want_s, line, sizeof line) == !(c->density > 0 && c->crossings),
          "report %d: the first crossing named (density %d, %d)", trial, c->density, c->crossings);
}

/* Reports made by hand, every count zero or not and every value 0, below, at, an ulp over or well
 * over its limit: rg2_check_failures keeps the promises' definitions for every set required; the
 * JSON reads back to the report's own numbers with the verdicts those define; the text table
 * shows the same verdicts and the lines and places the report's values call for. */
static void format_made_reports(void)
{
    rg2t_rng g;
    rg2t_seed(&g, 20261206);
    rg2_check_shape shapes[12];
    int bad = 0, failed = rg2t_failed;
    for (int trial = 0; trial < 600; trial++) {
        rg2_check_report r;
        random_report(&g, &r, shapes);
        unsigned want = want_failures(&r);
        for (unsigned req = 0; req < 64; req++)
            bad += rg2_check_failures(&r, req) != (want & req);
        CHECK(!bad, "report %d: failures %#x of %#x required, want %#x", trial, rg2_check_failures(&r, 63u), 63u, want);
        rg2_error err;
        char *text = NULL, *js = NULL;
        CHECK_OK(rg2_check_format(&r, 0, &text, &err), &err);
        CHECK_OK(rg2_check_format(&r, 1, &js, &err), &err);
        if (text)
            text_matches(&r, text, want, trial);
        if (js)
            json_matches(&r, js, want, trial);
        free(text);
        free(js);
        if (rg2t_failed > failed)
            break; /* (the first report that fails is enough to read) */
    }
    printf("check report: 600 reports made by hand read back from their JSON and text\n");
}

/* Design text js parsed (named name), its surfaces and shapes (*p) checked with o into *r; the
 * design, or NULL when it does not parse (then *p and *r are untouched). */
static rg2_design *design_checked(const char *js, const char *name, rg2t_parts *p, const rg2_check_opts *o,
                                  rg2_check_report *r)
{
    rg2_design *d = NULL;
    rg2_error err;
    CHECK_OK(rg2_design_parse(js, strlen(js), name, &d, &err), &err);
    if (!d)
        return NULL;
    CHECK(!rg2t_design_parts(d, p), "%s: parts", name);
    CHECK_OK(rg2_check(p->s, p->n, p->shapes, p->labels, p->ns, o, r, &err), &err);
    return d;
}

/* A small shape far from the origin: its exact patches cannot lie closer to it than their
 * coordinates round, about DBL_EPSILON x |x| / size relative to its size. A cylinder of radius
 * 1e-3 (patches 3e-5 tall) at (T, T, 0) measured 1.9e-11 at T = 100 and 1.6e-10 at T = 1000,
 * which failed the exact limit of 1e-11 although the design is valid (README, numeric range:
 * size down to 1e-12 of the largest coordinate). Each shape is held to the larger of tol_exact
 * and its coordinates' rounding (rg2_check_shape.limit); a real defect there still fails. */
static void far_from_origin(void)
{
    for (int t = 0; t < 3; t++) {
        static const double T[3] = {0, 100, 1000};
        char js[400];
        snprintf(js, sizeof js,
                 "{\"shapes\": {\"c\": {\"kind\": \"cylinder\", \"radius\": 0.001, \"translate\": [%g, %g, 0]}},"
                 " \"meshes\": {\"m\": {\"shape\": \"c\", \"u\": {\"arcs\": 3},"
                 " \"v\": {\"segments\": 5, \"from\": -0.0002, \"to\": -0.00017}}}}",
                 T[t], T[t]);
        rg2t_parts p;
        rg2_check_opts o;
        rg2_check_opts_default(&o);
        rg2_check_report r;
        rg2_error err;
        rg2_design *d = design_checked(js, "far", &p, &o, &r);
        if (!d)
            return;
        const rg2_check_shape *c = &r.shapes[0];
        printf("cylinder of radius 1e-3 at (%g, %g, 0): %d exact patches, residual %.2e, limit %.2e\n", T[t], T[t],
               c->patches, c->residual, c->limit);
        CHECK(c->patches == 15 && !rg2_check_failures(&r, RG2_REQUIRE_EXACT) && c->residual <= c->limit,
              "far %g: residual %.3g, limit %.3g, failures %#x", T[t], c->residual, c->limit,
              rg2_check_failures(&r, RG2_REQUIRE_EXACT));
        if (t == 0)
            CHECK(c->limit == o.tol_exact, "at the origin the limit is tol_exact: %.3g", c->limit);
        else /* the case is not vacuous: past tol_exact, within a limit not much above the residual */
            CHECK(c->residual > o.tol_exact && c->limit < 20 * c->residual, "far %g: residual %.3g, limit %.3g", T[t],
                  c->residual, c->limit);
        rg2_check_report_free(&r);
        /* one control point of patch (1, 2) moved by 1e-7 of the shape's size (2e-3), tag kept */
        rg2_patch *P = rg2_surface_patch(&p.s[0], 1, 2);
        P->h[1][1][0] += 2e-10 * P->h[1][1][3];
        CHECK_OK(rg2_check(p.s, p.n, p.shapes, p.labels, p.ns, &o, &r, &err), &err);
        printf("  a control point moved by 1e-7 of the size: residual %.2e, limit %.2e, exact %s\n",
               r.shapes[0].residual, r.shapes[0].limit,
               rg2_check_failures(&r, RG2_REQUIRE_EXACT) ? "fails" : "passes");
        CHECK(rg2_check_failures(&r, RG2_REQUIRE_EXACT) == RG2_REQUIRE_EXACT,
              "far %g: a moved point passes exact (residual %.3g, limit %.3g)", T[t], r.shapes[0].residual,
              r.shapes[0].limit);
        rg2_check_report_free(&r);
        rg2t_design_parts_free(&p);
        rg2_design_free(d);
    }
}

/* Polar spheres capped at the south, thin pole patches: their seam samples next to the pole
 * have rounding bounds past 1e-2 (the curvature's, growing like 1 / d^2 toward the pole) further
 * than 1e-3 from it. Where the bounds carried out by that law are back within the limits by 0.25
 * from the pole, the samples are the pole's floating-point limit: not compared, and the verdict
 * does not depend on --samples. 600 arcs, a cap at v knots 0.01, 0.02: the samples at v = 1/16
 * (bound 1.0e-2, reach 0.0625); 1200 arcs: v = 2/16 as well (reach 0.126, past 1/8). With a cap
 * 10 times smaller (knots 0.001, 0.002) the bounds stay past the limits over most of the pole
 * patches: not measured, on pole patches, up to 0.625 from the pole, G1 and G2 fail, in the
 * report, its text and its JSON (the flattened torus's unmeasured samples, on no pole patch,
 * are not: ill_conditioned_flat). */
static void thin_pole_patches(void)
{
    static const struct {
        int arcs, samples;
        const char *knots;
        int unresolved;    /* samples too close to the pole, -1: not measured instead */
        double dist;       /* the farthest of them from the pole */
    } cases[] = {
        {600, 16, "0.01, 0.02", 600, 0.0625},  {600, 32, "0.01, 0.02", 1200, 0.0625},
        {600, 8, "0.01, 0.02", 0, 0},          {600, 15, "0.01, 0.02", 0, 0},
        {1200, 16, "0.01, 0.02", 2400, 0.125}, {600, 16, "0.001, 0.002", -1, 0.625},
    };
    for (size_t c = 0; c < sizeof cases / sizeof cases[0]; c++) {
        char js[300];
        snprintf(js, sizeof js,
                 "{\"shapes\": {\"e\": {\"kind\": \"sphere\"}}, \"meshes\": {\"p\": {\"polar\": \"e\","
                 " \"u\": {\"arcs\": %d}, \"v\": {\"knots\": [%s, 0.5]}}, \"c\": {\"cap\": \"p\", \"ends\": \"south\"}}}",
                 cases[c].arcs, cases[c].knots);
        rg2t_parts p;
        rg2_check_opts o;
        rg2_check_opts_default(&o);
        o.seam_samples = cases[c].samples;
        rg2_check_report r;
        rg2_error err;
        rg2_design *d = design_checked(js, "thin", &p, &o, &r);
        if (!d)
            return;
        char *txt = NULL, *json = NULL;
        CHECK_OK(rg2_check_format(&r, 0, &txt, &err), &err);
        CHECK_OK(rg2_check_format(&r, 1, &json, &err), &err);
        printf("polar sphere of %d arcs, cap knots %s, %d samples: %d too close to the pole (up to %.4g), %d "
               "unmeasured (%d on pole patches, up to %.4g)\n",
               cases[c].arcs, cases[c].knots, cases[c].samples, r.pole_unresolved, r.pole_unresolved_dist,
               r.unmeasured, r.unmeasured_pole, r.unmeasured_pole_dist);
        cJSON *jr = json ? cJSON_Parse(json) : NULL;
        const cJSON *np = cJSON_GetObjectItem(jr, "near_pole");
        double ju = jnum(np, "unresolved"), jud = jnum(np, "unresolved_distance"),
               jn = jnum(jr, "unmeasured_near_pole"), jd = jnum(jr, "unmeasured_pole_distance");
        char want[160];
        unsigned f = rg2_check_failures(&r, RG2_REQUIRE_G1 | RG2_REQUIRE_G2);
        if (cases[c].unresolved >= 0) {
            snprintf(want, sizeof want, "  too close to a pole    %d samples up to %.3g from a pole (parametric)",
                     cases[c].unresolved, cases[c].dist);
            CHECK(r.unmeasured == 0 && r.unmeasured_pole == 0 && !f && r.pole_unresolved == cases[c].unresolved &&
                      r.pole_unresolved_dist == cases[c].dist && ju == r.pole_unresolved &&
                      jud == r.pole_unresolved_dist && jn == 0 && txt &&
                      (r.pole_unresolved ? strstr(txt, want) != NULL : !strstr(txt, "too close to a pole")) &&
                      !strstr(txt, "NOT MEASURED"),
                  "%d arcs, %d samples: failures %#x, %d too close to the pole up to %.4g (want %d, %.4g; JSON %g, "
                  "%g), %d unmeasured; text:\n%s",
                  cases[c].arcs, cases[c].samples, f, r.pole_unresolved, r.pole_unresolved_dist,
                  cases[c].unresolved, cases[c].dist, ju, jud, r.unmeasured, txt ? txt : "");
        } else {
            snprintf(want, sizeof want, "    %d of them on patches with a pole side, up to %.3g from the pole",
                     r.unmeasured, cases[c].dist);
            CHECK(r.unmeasured > 0 && r.unmeasured_pole == r.unmeasured && r.unmeasured_pole_dist == cases[c].dist &&
                      jn == r.unmeasured && jd == cases[c].dist && txt && strstr(txt, want) &&
                      strstr(txt, "NOT MEASURED") && f == (RG2_REQUIRE_G1 | RG2_REQUIRE_G2),
                  "tiny cap: failures %#x, %d unmeasured, %d on pole patches, up to %.4g (JSON %g, %g); text:\n%s", f,
                  r.unmeasured, r.unmeasured_pole, r.unmeasured_pole_dist, jn, jd, txt ? txt : "");
        }
        cJSON_Delete(jr);
        free(txt);
        free(json);
        if (c == 0 || c + 1 == sizeof cases / sizeof cases[0])
            same_on_threads(p.s, p.n, p.shapes, p.labels, p.ns, &o, "thin pole patches");
        rg2_check_report_free(&r);
        rg2t_design_parts_free(&p);
        rg2_design_free(d);
    }
}

/* Two cylinders of radius 1e-3, one at the origin and one at (1000, 1000, 0), in either order:
 * each shape's limit comes from its own patches' coordinates, so the one at the origin keeps
 * tol_exact exactly (the far one's coordinates would give it about 1.8e-9) while the far one's
 * limit is past tol_exact, and both pass. */
static void near_and_far_shapes(void)
{
    static const char cyl[] = "\"%s\": {\"kind\": \"cylinder\", \"radius\": 0.001, \"translate\": [%g, %g, 0]}";
    static const char mesh[] = "\"%s\": {\"shape\": \"%s\", \"u\": {\"arcs\": 3},"
                               " \"v\": {\"segments\": 5, \"from\": -0.0002, \"to\": -0.00017}}";
    for (int order = 0; order < 2; order++) {
        char c0[200], c1[200], m0[200], m1[200], js[900];
        const char *nm[2] = {order ? "f" : "n", order ? "n" : "f"};
        for (int k = 0; k < 2; k++) {
            double t = nm[k][0] == 'f' ? 1000 : 0;
            snprintf(k ? c1 : c0, sizeof c0, cyl, nm[k], t, t);
            char mn[2] = {(char)(nm[k][0] - 32), 0};
            snprintf(k ? m1 : m0, sizeof m0, mesh, mn, nm[k]);
        }
        snprintf(js, sizeof js, "{\"shapes\": {%s, %s}, \"meshes\": {%s, %s}, \"output\": [\"%c\", \"%c\"]}", c0,
                 c1, m0, m1, nm[0][0] - 32, nm[1][0] - 32);
        rg2t_parts p;
        rg2_check_opts o;
        rg2_check_opts_default(&o);
        rg2_check_report r;
        rg2_design *d = design_checked(js, "nearfar", &p, &o, &r);
        if (!d)
            return;
        CHECK(r.n_shapes == 2, "near and far: %d shapes", r.n_shapes);
        for (int k = 0; k < r.n_shapes && k < 2; k++) {
            const rg2_check_shape *c = &r.shapes[k];
            int far = !strcmp(c->label, "f");
            printf("near and far (order %d): shape %d '%s': %d patches, residual %.2e, limit %.2e\n", order, k,
                   c->label, c->patches, c->residual, c->limit);
            CHECK(c->patches == 15 && (far || !strcmp(c->label, "n")) && c->residual <= c->limit &&
                      (far ? c->limit > o.tol_exact && c->limit < 1e-7 : c->limit == o.tol_exact),
                  "near and far (order %d): shape '%s' residual %.3g, limit %.3g (tol_exact %g)", order, c->label,
                  c->residual, c->limit, o.tol_exact);
        }
        CHECK(!rg2_check_failures(&r, RG2_REQUIRE_EXACT), "near and far (order %d): exact fails", order);
        rg2_check_report_free(&r);
        rg2t_design_parts_free(&p);
        rg2_design_free(d);
    }
}

/* A shape's own limit (rg2_check_shape.limit above tol_exact) in a report made by hand: a
 * residual at the limit passes, one ulp over it fails, in rg2_check_failures, the JSON's "ok"
 * and "limit" and the text's verdict; the text gives the limit line only for a shape with
 * patches whose limit exceeds tol_exact. */
static void shape_limit_by_hand(void)
{
    for (int over = 0; over < 2; over++) {
        rg2_check_report r;
        rg2_check_shape sh[3];
        memset(&r, 0, sizeof r);
        memset(sh, 0, sizeof sh);
        rg2_check_opts_default(&r.opts);
        const double tol = r.opts.tol_exact, L = 4 * tol;
        r.surfaces = 1, r.patches = r.exact_patches = 3;
        r.n_shapes = 3, r.shapes = sh;
        snprintf(sh[0].label, sizeof sh[0].label, "own");
        sh[0].patches = 2, sh[0].limit = L, sh[0].residual = over ? nextafter(L, INFINITY) : L;
        snprintf(sh[1].label, sizeof sh[1].label, "plain");
        sh[1].patches = 1, sh[1].limit = tol, sh[1].residual = tol / 2;
        snprintf(sh[2].label, sizeof sh[2].label, "empty"); /* (no patches, a limit of its own) */
        sh[2].patches = 0, sh[2].limit = L, sh[2].residual = 0;
        for (int k = 0; k < 3; k++)
            sh[k].shape = k, snprintf(sh[k].where, sizeof sh[k].where, "patch (0,%d) u=0.5 v=0.5", k);
        r.worst_residual = sh[0].residual;
        unsigned f = rg2_check_failures(&r, RG2_REQUIRE_EXACT);
        char *txt = NULL, *json = NULL;
        rg2_error err;
        CHECK_OK(rg2_check_format(&r, 0, &txt, &err), &err);
        CHECK_OK(rg2_check_format(&r, 1, &json, &err), &err);
        cJSON *j = json ? cJSON_Parse(json) : NULL, *js = cJSON_GetObjectItem(j, "shapes");
        const cJSON *j0 = cJSON_GetArrayItem(js, 0), *j1 = cJSON_GetArrayItem(js, 1);
        const cJSON *ok0 = cJSON_GetObjectItem(j0, "ok"), *lim0 = cJSON_GetObjectItem(j0, "limit"),
                    *lim1 = cJSON_GetObjectItem(j1, "limit");
        char row[200], lim[120];
        snprintf(row, sizeof row, "%-24s %7d  %14.2e  %-7s  patch (0,0)", "own", 2, sh[0].residual,
                 over ? "FAIL" : "ok");
        snprintf(lim, sizeof lim, "\n       (limit %.2e, not %g: ", L, tol);
        const char *l1 = txt ? strstr(txt, lim) : NULL;
        CHECK(f == (over ? RG2_REQUIRE_EXACT : 0u) && txt && strstr(txt, row) && l1 && !strstr(l1 + strlen(lim), "\n       (limit ") &&
                  cJSON_IsBool(ok0) && cJSON_IsTrue(ok0) == !over && cJSON_IsNumber(lim0) && lim0->valuedouble == L &&
                  cJSON_IsNumber(lim1) && lim1->valuedouble == tol,
              "a shape's own limit by hand (residual %s the limit): failures %#x, json %s, text:\n%s",
              over ? "an ulp over" : "at", f, json ? json : "", txt ? txt : "");
        /* the worst residual past tol_exact but no shape past it (a report made some other way):
         * nothing vouches for it, exact fails; the plain shape exactly at tol_exact is not past */
        sh[0].residual = tol / 4, sh[1].residual = tol;
        r.worst_residual = 2 * tol;
        CHECK(rg2_check_failures(&r, RG2_REQUIRE_EXACT) == RG2_REQUIRE_EXACT,
              "worst residual past tol_exact with no shape past it passes exact");
        cJSON_Delete(j);
        free(txt);
        free(json);
    }
    printf("a shape's own limit, made by hand: at it passes, an ulp over fails\n");
}

/* A label longer than rg2_check_shape.label keeps its first bytes, cut between UTF-8
 * characters: 40 'ä's (80 bytes) kept 63, the last the lead byte of an 'ä', and the JSON report
 * (and its table) carried that half character. */
static void long_utf8_label(void)
{
    rg2_shape sh;
    rg2_shape_init(&sh, RG2_SHAPE_TORUS);
    rg2_surface s;
    torus_8x6(&sh, &s);
    char label[100] = "";
    for (int k = 0; k < 40; k++)
        strcat(label, "\xc3\xa4");
    const char *labels[1] = {label};
    rg2_check_opts o;
    rg2_check_opts_default(&o);
    o.seam_samples = 2;
    o.patch_samples = 2;
    rg2_check_report r;
    rg2_error err;
    CHECK_OK(rg2_check(&s, 1, &sh, labels, 1, &o, &r, &err), &err);
    if (r.n_shapes == 1) {
        const char *l = r.shapes[0].label;
        size_t n = strlen(l);
        CHECK(n == 62 && !strncmp(l, label, n), "an 80-byte label kept as %zu bytes (want the 62 of 31 whole "
              "'\xc3\xa4's), last byte 0x%02x", n, n ? (unsigned)(unsigned char)l[n - 1] : 0u);
    }
    rg2_check_report_free(&r);
    rg2_surface_free(&s);
}

int main(void)
{
    harness_agreement();
    long_utf8_label();
    shape_table_layout();
    no_exact_patch_reason();
    exact_and_broken(0);
    exact_and_broken(1);
    size_and_weights();
    g1_join();
    examples();
    pole_sample_counts();
    defect_near_pole();
    pole_within_rounding();
    bounds_scale_free();
    poles_on_u_sides();
    seam_direction_reported();
    unmeasured_fails();
    unmeasured_where();
    unknown_shape_kind();
    curvature_peak_unresolved();
    nonfinite_fails();
    metric_overflow_one_side();
    loose_limits();
    folds_fail();
    ill_conditioned_flat();
    threads_identical();
    curvature_peak();
    shape_residuals();
    far_from_origin();
    thin_pole_patches();
    near_and_far_shapes();
    shape_limit_by_hand();
    format_made_reports();
    return rg2t_done("test_check");
}
