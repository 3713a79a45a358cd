/* test_design.c -- design files: every example builds, its exact patches lie on their shapes,
 * its seams are G2 and its exact/transition counts are the intended ones; edits are local;
 * morphs reproduce their ends; bad designs fail with clear messages. */
#define _POSIX_C_SOURCE 200809L /* mkdtemp */
#include "harness.h"
#include "../src/design_internal.h" /* the sources' stored windows, the name index */

#include <cjson/cJSON.h>
#include <errno.h>
#include <unistd.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

static char *read_text(const char *path)
{
    FILE *f = fopen(path, "rb");
    if (!f)
        return NULL;
    fseek(f, 0, SEEK_END);
    long n = ftell(f);
    fseek(f, 0, SEEK_SET);
    char *s = malloc((size_t)n + 1);
    if (s && fread(s, 1, (size_t)n, f) != (size_t)n) {
        free(s);
        s = NULL;
    }
    if (s)
        s[n] = 0;
    fclose(f);
    return s;
}

/* Largest |F| / (|grad F| * scale) over samples of the patches tagged with a shape. */
static double exact_residual(const rg2_design *d, const rg2_surface *s, int samples, int *n_exact)
{
    double scale = rg2t_surface_scale(s), worst = 0.0;
    *n_exact = 0;
    for (int k = 0; k < s->nu * s->nv; k++) {
        if (s->tag[k] < 0)
            continue;
        (*n_exact)++;
        const rg2_shape *sh = rg2_design_shape(d, s->tag[k]);
        for (int a = 0; a <= samples; a++)
            for (int b = 0; b <= samples; b++) {
                rg2_eval e;
                rg2_surface_eval(s, k / s->nv, k % s->nv, (double)a / samples, (double)b / samples, 0, &e);
                double g[3], F = rg2_shape_implicit(sh, e.p, g);
                double gn = sqrt(g[0] * g[0] + g[1] * g[1] + g[2] * g[2]);
                double r = gn > 0 ? fabs(F) / (gn * scale) : (F == 0 ? 0 : INFINITY);
                if (!(r <= worst))
                    worst = r;
            }
    }
    return worst;
}

/* Smallest sine of the angle between Su and Sv over samples of the transition patches: near 0
 * means a fold or a collapsed transition (G2 holds regardless, so this is the quality guard). */
static double transition_min_sine(const rg2_surface *s, int samples)
{
    double worst = 1.0;
    for (int k = 0; k < s->nu * s->nv; k++) {
        if (s->tag[k] >= 0)
            continue;
        for (int a = 0; a <= samples; a++)
            for (int b = 0; b <= samples; b++) {
                rg2_eval e;
                rg2_surface_eval(s, k / s->nv, k % s->nv, (double)a / samples, (double)b / samples, 1, &e);
                if (e.flags & RG2_EVAL_NORMAL_UNDEFINED)
                    continue; /* a collapsed edge (pole of a cap) is not a fold */
                double c[3] = {e.su[1] * e.sv[2] - e.su[2] * e.sv[1], e.su[2] * e.sv[0] - e.su[0] * e.sv[2],
                               e.su[0] * e.sv[1] - e.su[1] * e.sv[0]};
                double nu = sqrt(e.su[0] * e.su[0] + e.su[1] * e.su[1] + e.su[2] * e.su[2]);
                double nv = sqrt(e.sv[0] * e.sv[0] + e.sv[1] * e.sv[1] + e.sv[2] * e.sv[2]);
                double sn = sqrt(c[0] * c[0] + c[1] * c[1] + c[2] * c[2]) / (nu * nv);
                if (!(sn >= worst))
                    worst = sn;
            }
    }
    return worst;
}

static int label_index(const rg2_design *d, const char *label)
{
    for (int k = 0; k < rg2_design_num_shapes(d); k++)
        if (!strcmp(rg2_design_shape_label(d, k), label))
            return k;
    return -1;
}

/* Compare the surface's patch counts with the example's "expect" entry. */
static void check_expect(const char *file, const rg2_design *d, int o, const cJSON *ex)
{
    const rg2_surface *s = rg2_design_surface(d, o);
    int np = s->nu * s->nv, ns = rg2_design_num_shapes(d);
    int *cnt = calloc((size_t)ns + 1, sizeof(int));
    for (int k = 0; k < np; k++)
        cnt[s->tag[k] < 0 ? ns : s->tag[k]]++;
    const cJSON *x = cJSON_GetObjectItem(ex, "patches");
    CHECK(cJSON_IsNumber(x) && x->valueint == np, "%s surface %d: %d patches, expected %d", file, o, np,
          x ? x->valueint : -1);
    x = cJSON_GetObjectItem(ex, "transition");
    CHECK(cJSON_IsNumber(x) && x->valueint == cnt[ns], "%s surface %d: %d transition patches, expected %d",
          file, o, cnt[ns], x ? x->valueint : -1);
    const cJSON *exact = cJSON_GetObjectItem(ex, "exact");
    int listed = 0;
    for (const cJSON *it = exact ? exact->child : NULL; it; it = it->next) {
        int k = label_index(d, it->string);
        CHECK(k >= 0, "%s: expect names unknown shape '%s'", file, it->string);
        if (k >= 0) {
            CHECK(cnt[k] == it->valueint, "%s surface %d: %d patches exact on %s, expected %d", file, o,
                  cnt[k], it->string, it->valueint);
            listed += cnt[k];
        }
    }
    CHECK(listed + cnt[ns] == np, "%s surface %d: patches on shapes not listed in expect", file, o);
    free(cnt);
}

static void examples(void)
{
    char *names[64];
    int n = rg2t_example_names(names, 64); /* sorted, for a stable report */
    CHECK(n >= 6, "only %d examples", n);
    for (int e = 0; e < n; e++) {
        const char *file = names[e];
        rg2_design *d = NULL;
        rg2_error err;
        CHECK_OK(rg2_design_load(file, &d, &err), &err);
        char *text = read_text(file);
        cJSON *root = text ? cJSON_Parse(text) : NULL;
        const cJSON *surfs = cJSON_GetObjectItem(cJSON_GetObjectItem(root, "expect"), "surfaces");
        CHECK(cJSON_IsArray(surfs), "%s has no expect.surfaces", file);
        if (d && cJSON_IsArray(surfs)) {
            CHECK(cJSON_GetArraySize(surfs) == rg2_design_num_surfaces(d), "%s: %d surfaces, expect lists %d",
                  file, rg2_design_num_surfaces(d), cJSON_GetArraySize(surfs));
            for (int o = 0; o < rg2_design_num_surfaces(d); o++) {
                const rg2_surface *s = rg2_design_surface(d, o);
                int n_exact;
                double res = exact_residual(d, s, 8, &n_exact);
                rg2t_seams g;
                rg2t_surface_seams(s, 8, &g);
                double sine = transition_min_sine(s, 8);
                printf("  %-34s surface %d: %4d patches, %4d exact (residual %.1e), %3d transition "
                       "(min sin(Su, Sv) %.2f); seams: normal angle %.1e rad, curvature jump %.1e rel, "
                       "min weight %.3g\n",
                       file, o, s->nu * s->nv, n_exact, res, s->nu * s->nv - n_exact, sine, g.angle,
                       g.curv, rg2_surface_min_weight(s));
                CHECK(sine > 0.2, "%s surface %d: a transition patch nearly folds (sin %.3g)", file, o, sine);
                CHECK(res <= 1e-13, "%s surface %d: exact patches off their shape by %.3g", file, o, res);
                CHECK(g.angle <= 1e-11, "%s surface %d: normal angle %.3g at seams", file, o, g.angle);
                CHECK(g.curv <= 1e-9, "%s surface %d: curvature jump %.3g at %s", file, o, g.curv, g.where);
                CHECK(g.pos <= 1e-13, "%s surface %d: position gap %.3g", file, o, g.pos);
                CHECK(rg2_surface_min_weight(s) > 0, "%s surface %d: non-positive weight", file, o);
                if (o < cJSON_GetArraySize(surfs))
                    check_expect(file, d, o, cJSON_GetArrayItem(surfs, o));
            }
        }
        cJSON_Delete(root);
        free(text);
        rg2_design_free(d);
        free(names[e]);
    }
}

/* ------------------------------------------------------------------------------------- */

static rg2_design *parse(const char *json, rg2_error *err)
{
    rg2_design *d = NULL;
    rg2_status st = rg2_design_parse(json, strlen(json), "test", &d, err);
    CHECK(st == RG2_OK, "parse -> %s: %s", rg2_status_str(st), err->msg);
    return d;
}

/* parse() of the design `base` (a printf format with one %s) with `edit` in its place. */
static rg2_design *parse_edit(const char *base, const char *edit, rg2_error *err)
{
    char json[2048];
    snprintf(json, sizeof json, base, edit);
    return parse(json, err);
}

/* parse() of the design `base` (a printf format with two %s) with a and b in their places. */
static rg2_design *parse_edit2(const char *base, const char *a, const char *b, rg2_error *err)
{
    char json[2048];
    snprintf(json, sizeof json, base, a, b);
    return parse(json, err);
}

/* Patches of b that differ from a (bitwise); *outside counts those outside the support. */
static int changed_patches(const rg2_surface *a, const rg2_surface *b, const int *in_u, const int *in_v,
                           int *outside)
{
    int changed = 0;
    *outside = 0;
    for (int k = 0; k < a->nu; k++)
        for (int l = 0; l < a->nv; l++) {
            int diff = memcmp(rg2_surface_patch(a, k, l), rg2_surface_patch(b, k, l), sizeof(rg2_patch)) != 0;
            changed += diff;
            if (diff && !(in_u[k] && in_v[l]))
                (*outside)++;
        }
    return changed;
}

/* Support of control point / junction i in a direction of n points: the segments k whose
 * stencil uses it (closed: k = i-2..i+1 mod n; open: k = i-3..i); of leg i (leg = 1), one
 * segment more (closed: i-2..i+2; open: i-3..i+1, leg -1 the data-only first leg). */
static void support(int *in, int nseg, int n, int closed, int i, int leg)
{
    memset(in, 0, sizeof(int) * (size_t)nseg);
    for (int d = 0; d < 4 + leg; d++) {
        int k = closed ? ((i - 2 + d) % n + n) % n : i - 3 + d;
        if (k >= 0 && k < nseg)
            in[k] = 1;
    }
}

static void edits_are_local(void)
{
    enum { ALL = -99 }; /* a scalar edit: every segment of the other direction */
    /* closed x open torus piece: u closed (10 points), v open (8 arcs -> 11 points) */
    const char *base = "{\"shapes\": {\"t\": {\"kind\": \"torus\", \"R\": 3, \"r\": 1}},"
                       " \"meshes\": {\"m\": {\"shape\": \"t\", \"u\": {\"arcs\": 10},"
                       " \"v\": {\"arcs\": 8, \"from\": 0, \"to\": 270}}%s}}";
    struct {
        const char *edit;
        int i, j; /* point or (leg/junction, ALL) / (ALL, leg/junction) */
        int leg;  /* a leg weight w (its support is one segment wider) */
    } cases[] = {
        {", \"e\": {\"edit\": \"m\", \"points\": [{\"at\": [4, 5], \"move\": [0.1, -0.2, 0.3]}]}", 4, 5, 0},
        {", \"e\": {\"edit\": \"m\", \"points\": [{\"at\": [0, 0], \"to\": [2, 2, 2]}]}", 0, 0, 0},
        {", \"e\": {\"edit\": \"m\", \"points\": [{\"at\": [9, 10], \"W\": 0.7}]}", 9, 10, 0},
        {", \"e\": {\"edit\": \"m\", \"scalars\": [{\"dir\": \"u\", \"junction\": 3, \"b\": 1.3, \"g\": 0.2}]}", 3, ALL, 0},
        {", \"e\": {\"edit\": \"m\", \"scalars\": [{\"dir\": \"v\", \"junction\": 6, \"g\": -0.1}]}", ALL, 6, 0},
        {", \"e\": {\"edit\": \"m\", \"scalars\": [{\"dir\": \"u\", \"leg\": 0, \"w\": 0.8}]}", 0, ALL, 1},
        {", \"e\": {\"edit\": \"m\", \"scalars\": [{\"dir\": \"v\", \"leg\": 5, \"w\": 0.8}]}", ALL, 5, 1},
        {", \"e\": {\"edit\": \"m\", \"scalars\": [{\"dir\": \"v\", \"leg\": -1, \"w\": 0.8}]}", ALL, -1, 1},
        {", \"e\": {\"edit\": \"m\", \"scalars\": [{\"dir\": \"v\", \"leg\": 10, \"w\": 0.8}]}", ALL, 10, 1},
    };
    rg2_error err;
    rg2_design *d0 = parse_edit(base, "", &err);
    if (!d0)
        return;
    const rg2_surface *s0 = rg2_design_surface(d0, 0);
    const rg2_mesh *m0 = rg2_design_mesh(d0, 0);
    int in_u[64], in_v[64];
    for (size_t c = 0; c < sizeof cases / sizeof cases[0]; c++) {
        rg2_design *d1 = parse_edit(base, cases[c].edit, &err);
        if (!d1)
            continue;
        const rg2_surface *s1 = rg2_design_surface(d1, 0);
        if (cases[c].i != ALL)
            support(in_u, s0->nu, m0->nu, 1, cases[c].i, cases[c].leg);
        else
            for (int k = 0; k < s0->nu; k++) in_u[k] = 1;
        if (cases[c].j != ALL)
            support(in_v, s0->nv, m0->nv, 0, cases[c].j, cases[c].leg);
        else
            for (int k = 0; k < s0->nv; k++) in_v[k] = 1;
        int outside, ch = changed_patches(s0, s1, in_u, in_v, &outside);
        int n_in = 0;
        for (int k = 0; k < s0->nu; k++)
            for (int l = 0; l < s0->nv; l++)
                n_in += in_u[k] && in_v[l];
        printf("  edit %zu: %d patches changed (support %d), %d outside the support\n", c, ch, n_in, outside);
        CHECK(outside == 0, "edit %zu changed %d patches outside the support", c, outside);
        CHECK(ch > 0 && ch == n_in, "edit %zu changed %d patches, its support has %d", c, ch, n_in);
        /* changed patches are tagged transition, the others keep their tags */
        int tag_ok = 1;
        for (int k = 0; k < s0->nu * s0->nv; k++) {
            int diff = memcmp(&s0->patch[k], &s1->patch[k], sizeof(rg2_patch)) != 0;
            if (diff ? s1->tag[k] != -1 : s1->tag[k] != s0->tag[k])
                tag_ok = 0;
        }
        CHECK(tag_ok, "edit %zu: tags do not follow the changed patches", c);
        if (c < 3) {
            int ps = rg2_design_point_shape(d1, 0, cases[c].i, cases[c].j);
            int other = rg2_design_point_shape(d1, 0, (cases[c].i + 5) % m0->nu, (cases[c].j + 5) % m0->nv);
            CHECK(ps == -1 && other == 0, "edit %zu: point provenance %d (edited), %d (untouched)", c, ps, other);
        }
        rg2t_seams g;
        rg2t_surface_seams(s1, 6, &g);
        CHECK(g.angle <= 1e-11 && g.curv <= 1e-9, "edit %zu: seams %.3g rad, %.3g", c, g.angle, g.curv);
        rg2_design_free(d1);
    }
    rg2_design_free(d0);
}

/* Edits measured against the control mesh: a move along x alone moves the point's Euclidean
 * position by exactly that vector (and nothing else), a small positive weight is accepted and keeps
 * the position, and junction 0 (the first valid index) can be edited and changes the surface. */
static void edits_measured(void)
{
    const char *base = "{\"shapes\": {\"t\": {\"kind\": \"torus\", \"R\": 3, \"r\": 1}},"
                       " \"meshes\": {\"m\": {\"shape\": \"t\", \"u\": {\"arcs\": 10},"
                       " \"v\": {\"arcs\": 8, \"from\": 0, \"to\": 270}}%s}}";
    rg2_error err;
    rg2_design *d0 = parse_edit(base, "", &err);
    if (!d0)
        return;
    const rg2_mesh *m0 = rg2_design_mesh(d0, 0);
    const struct {
        const char *edit;
        double dx, W; /* expected x shift of point [4, 5], its expected weight (0: unchanged) */
    } cases[] = {
        {", \"e\": {\"edit\": \"m\", \"points\": [{\"at\": [4, 5], \"move\": [0.25, 0, 0]}]}", 0.25, 0.0},
        {", \"e\": {\"edit\": \"m\", \"points\": [{\"at\": [4, 5], \"W\": 0.004}]}", 0.0, 0.004},
    };
    for (size_t c = 0; c < sizeof cases / sizeof cases[0]; c++) {
        rg2_design *d1 = parse_edit(base, cases[c].edit, &err);
        if (!d1)
            continue;
        const rg2_mesh *m1 = rg2_design_mesh(d1, 0);
        double worst_other = 0.0, dpos = 0.0;
        for (int i = 0; i < m0->nu; i++)
            for (int j = 0; j < m0->nv; j++) {
                const double *a = rg2_mesh_at(m0, i, j), *b = rg2_mesh_at(m1, i, j);
                if (i == 4 && j == 5) {
                    double want[3] = {a[0] / a[3] + cases[c].dx, a[1] / a[3], a[2] / a[3]};
                    for (int k = 0; k < 3; k++)
                        dpos = fmax(dpos, fabs(b[k] / b[3] - want[k]));
                    double wW = cases[c].W > 0 ? cases[c].W : a[3];
                    CHECK(fabs(b[3] - wW) <= 1e-15 * wW, "edit %zu: W = %.17g, want %.17g", c, b[3], wW);
                } else {
                    for (int k = 0; k < 4; k++)
                        worst_other = fmax(worst_other, fabs(b[k] - a[k]));
                }
            }
        printf("  measured edit %zu: point off by %.3g, others moved %.3g\n", c, dpos, worst_other);
        CHECK(dpos <= 1e-14, "edit %zu: the edited point is %.3g from its intended position", c, dpos);
        CHECK(worst_other == 0.0, "edit %zu: other points moved by %.3g", c, worst_other);
        rg2_design_free(d1);
    }
    /* junction 0 is a valid index: the edit is accepted and changes the surface */
    rg2_design *d1 = parse_edit(
        base, ", \"e\": {\"edit\": \"m\", \"scalars\": [{\"dir\": \"u\", \"junction\": 0, \"g\": 0.1}]}", &err);
    if (d1) {
        const rg2_surface *s0 = rg2_design_surface(d0, 0), *s1 = rg2_design_surface(d1, 0);
        const rg2_mesh *m1 = rg2_design_mesh(d1, 0);
        CHECK(fabs(m1->su.g[0] - 0.1) <= 1e-15, "junction 0: g = %.17g, want 0.1", m1->su.g[0]);
        int diff = 0;
        for (int k = 0; k < s0->nu * s0->nv; k++)
            diff += memcmp(&s0->patch[k], &s1->patch[k], sizeof(rg2_patch)) != 0;
        CHECK(diff > 0, "junction 0 edit changed no patch");
        rg2_design_free(d1);
    }
    rg2_design_free(d0);
}

static int same_mesh(const rg2_mesh *a, const rg2_mesh *b);

/* Operations that must keep every patch exact (unequal arcs in both directions, so a patch matched
 * to the wrong segment of its source is not): cuts (ranges, wrap, open_at), transpose,
 * reverse (the same patches traversed backwards), transform, and cutting a closed torus in two and merging it back (the seam data agree, so
 * the result is the torus again, every patch exact). */
static void ops_keep_exactness(void)
{
    const char *json =
        "{\"shapes\": {\"t\": {\"kind\": \"torus\", \"R\": 3, \"r\": 1}},"
        " \"meshes\": {\"T\": {\"shape\": \"t\", \"u\": {\"arcs\": [20, 25, 30, 35, 40, 30, 25, 35, 30, 25, 35, 30]},"
        "                       \"v\": {\"arcs\": [50, 65, 70, 45, 80, 50]}},"
        "  \"wrap\": {\"cut\": \"T\", \"u\": [9, 15], \"v\": [1, 5]},"
        "  \"open\": {\"cut\": \"T\", \"u\": {\"open_at\": 3}},"
        "  \"turned\": {\"transpose\": \"wrap\"},"
        "  \"moved\": {\"transform\": \"turned\", \"scale\": 0.5, \"rotate\": {\"axis\": [1, 2, 3], \"degrees\": 33},"
        "             \"translate\": [1, -2, 0.5]},"
        "  \"A\": {\"cut\": \"T\", \"u\": [0, 5]}, \"B\": {\"cut\": \"T\", \"u\": [6, 11]},"
        "  \"again\": {\"merge\": [\"A\", \"B\"], \"along\": \"u\", \"closed\": true},"
        "  \"back\": {\"reverse\": \"wrap\", \"dir\": \"v\"}, \"backT\": {\"reverse\": \"T\", \"dir\": \"u\"},"
        "  \"both\": {\"reverse\": \"backT\", \"dir\": \"v\"}},"
        " \"output\": [\"wrap\", \"open\", \"turned\", \"moved\", \"again\", \"T\", \"back\", \"backT\", \"both\"]}";
    rg2_error err;
    rg2_design *d = parse(json, &err);
    if (!d)
        return;
    const int want[9][2] = {{4, 2}, {9, 6}, {2, 4}, {2, 4}, {12, 6}, {12, 6}, {4, 2}, {12, 6}, {12, 6}};
    for (int o = 0; o < rg2_design_num_surfaces(d); o++) {
        const rg2_surface *s = rg2_design_surface(d, o);
        int n_exact;
        double res = exact_residual(d, s, 6, &n_exact);
        CHECK(s->nu == want[o][0] && s->nv == want[o][1], "ops surface %d: %d x %d patches, expected %d x %d", o,
              s->nu, s->nv, want[o][0], want[o][1]);
        CHECK(n_exact == s->nu * s->nv, "ops surface %d (%s): %d of %d patches exact", o,
              rg2_design_mesh_name(d, o), n_exact, s->nu * s->nv);
        CHECK(res <= 1e-13, "ops surface %d: residual %.3g", o, res);
        printf("  %-7s %2d x %d patches, all exact (residual %.1e)%s\n", rg2_design_mesh_name(d, o), s->nu, s->nv,
               res, o == 3 ? ", on the transformed torus" : "");
    }
    CHECK(same_mesh(rg2_design_mesh(d, 4), rg2_design_mesh(d, 5)), "cut in two and merged back differs from T");
    /* leg i of backT is leg n - 2 - i of T: its patch is T's patch run backwards */
    const rg2_surface *T = rg2_design_surface(d, 5), *R = rg2_design_surface(d, 7);
    double dev = 0;
    for (int i = 0; i < T->nu; i++)
        for (int j = 0; j < T->nv; j++)
            for (int a = 0; a <= 4; a++) {
                rg2_eval e1, e2;
                rg2_patch_eval(rg2_surface_patch(T, i, j), a / 4.0, 0.3, 0, &e1);
                rg2_patch_eval(rg2_surface_patch(R, (2 * T->nu - 2 - i) % T->nu, j), 1.0 - a / 4.0, 0.3, 0, &e2);
                for (int q = 0; q < 3; q++)
                    dev = fmax(dev, fabs(e1.p[q] - e2.p[q]));
            }
    CHECK(dev <= 1e-14 * rg2t_surface_scale(T), "reversed torus differs from the torus run backwards by %.3g", dev);
    printf("  reverse: the reversed torus is the torus run backwards to %.1e\n", dev);
    const rg2_surface *mv = rg2_design_surface(d, 3);
    CHECK(mv->tag[0] >= 1 && strstr(rg2_design_shape_label(d, mv->tag[0]), "t@meshes.moved"),
          "transformed patches tagged %d", mv->tag[0]);
    rg2_design_free(d);
}

/* Random operation chains (fixed seed): cuts of two random tori-like shapes, random edits,
 * reversals, transposes, transforms and merges. Whatever the chain, every tagged patch must lie on its
 * shape and every seam must be G2; the count of exact patches is reported. */
static void random_arcs(rg2t_rng *r, int n, char *out, size_t cap)
{
    double a[16], sum = 0, acc = 0;
    for (int k = 0; k < n; k++)
        sum += a[k] = rg2t_uniform(r, 0.6, 1.4);
    for (int k = 0; k < n - 1; k++)
        acc += a[k] = 360.0 * a[k] / sum;
    a[n - 1] = 360.0 - acc; /* closes the circle exactly */
    size_t len = 0;
    for (int k = 0; k < n && len < cap; k++)
        len += (size_t)snprintf(out + len, cap - len, "%s%.17g%s", k ? ", " : "[", a[k], k == n - 1 ? "]" : "");
}

static void random_designs(void)
{
    rg2t_rng r;
    uint64_t seed = 4242;
    rg2t_seed(&r, seed);
    double worst_res = 0, worst_ang = 0, worst_curv = 0;
    int n_designs = 0, n_patches = 0, n_exact = 0;
    for (int trial = 0; trial < 40; trial++) {
        int nu = rg2t_int(&r, 8, 12), nv = rg2t_int(&r, 5, 7);
        char au[400], av[400], bu[400], json[4096];
        random_arcs(&r, nu, au, sizeof au);
        random_arcs(&r, nv, av, sizeof av);
        random_arcs(&r, nu, bu, sizeof bu);
        int c0 = rg2t_int(&r, 0, nu - 1), len0 = rg2t_int(&r, 4, nu);
        int c1 = rg2t_int(&r, 0, nu - 1), len1 = rg2t_int(&r, 4, nu);
        int ei = rg2t_int(&r, 0, len0 - 1), ej = rg2t_int(&r, 0, nv - 1);
        double mv = rg2t_int(&r, 0, 1) ? rg2t_uniform(&r, -0.3, 0.3) : 0.0;
        int closed = rg2t_int(&r, 0, 1), transpose = rg2t_int(&r, 0, 1);
        int rev = rg2t_int(&r, 0, 1);
        snprintf(json, sizeof json,
                 "{\"shapes\": {\"t\": {\"kind\": \"torus\", \"R\": %.6f, \"r\": %.6f},"
                 "  \"c\": {\"kind\": \"cyclide\", \"a\": %.6f, \"c\": %.6f, \"mu\": %.6f,"
                 "        \"rotate\": {\"axis\": [0, 0, 1], \"degrees\": %.3f}}},"
                 " \"meshes\": {\"T\": {\"shape\": \"t\", \"u\": {\"arcs\": %s}, \"v\": {\"arcs\": %s}},"
                 "  \"C\": {\"shape\": \"c\", \"u\": {\"arcs\": %s}, \"v\": {\"arcs\": %s, \"from\": 180}},"
                 "  \"A\": {\"cut\": \"T\", \"u\": [%d, %d]}, \"B\": {\"cut\": \"C\", \"u\": [%d, %d]},"
                 "  \"E\": {\"edit\": \"A\", \"points\": [{\"at\": [%d, %d], \"move\": [%.3f, 0, %.3f]}]},"
                 "  \"BR\": {\"reverse\": \"B\", \"dir\": \"u\"},"
                 "  \"M\": {\"merge\": [\"E\", \"%s\"], \"along\": \"u\", \"closed\": %s},"
                 "  \"P\": {\"transpose\": \"M\"},"
                 "  \"X\": {\"transform\": \"%s\", \"rotate\": {\"axis\": [1, 1, 0], \"degrees\": %.3f},"
                 "         \"translate\": [%.3f, 0, 1]}}}",
                 rg2t_uniform(&r, 2.5, 4), rg2t_uniform(&r, 0.5, 1), 3.0, rg2t_uniform(&r, 0.2, 0.8),
                 rg2t_uniform(&r, 0.9, 1.2), rg2t_uniform(&r, 0, 360), au, av, bu, av, c0, c0 + len0 - 1, c1,
                 c1 + len1 - 1, ei, ej, mv, mv, rev ? "BR" : "B", closed ? "true" : "false", transpose ? "P" : "M",
                 rg2t_uniform(&r, 0, 90), rg2t_uniform(&r, -2, 2));
        rg2_design *d = NULL;
        rg2_error err;
        rg2_status st = rg2_design_parse(json, strlen(json), "random", &d, &err);
        CHECK(st == RG2_OK, "random design %d: %s", trial, err.msg);
        if (st)
            continue;
        const rg2_surface *s = rg2_design_surface(d, 0);
        int ne;
        double res = exact_residual(d, s, 4, &ne);
        rg2t_seams g;
        rg2t_surface_seams(s, 4, &g);
        CHECK(res <= 1e-13, "random design %d: tagged patches off their shapes by %.3g", trial, res);
        CHECK(g.angle <= 1e-11 && g.curv <= 1e-9, "random design %d: seams %.3g rad, %.3g", trial, g.angle, g.curv);
        worst_res = fmax(worst_res, res);
        worst_ang = fmax(worst_ang, g.angle);
        worst_curv = fmax(worst_curv, g.curv);
        n_designs++;
        n_patches += s->nu * s->nv;
        n_exact += ne;
        rg2_design_free(d);
    }
    printf("  seed %llu: %d random designs, %d patches, %d tagged exact (residual %.1e), seams %.1e rad / %.1e\n",
           (unsigned long long)seed, n_designs, n_patches, n_exact, worst_res, worst_ang, worst_curv);
    CHECK(n_exact > n_patches / 4, "random designs: only %d of %d patches exact", n_exact, n_patches);
}

/* ------------------------------------------------------------------------------------- */

static int same_mesh(const rg2_mesh *a, const rg2_mesh *b)
{
    if (a->nu != b->nu || a->nv != b->nv)
        return 0;
    if (memcmp(a->p, b->p, sizeof(double) * 4 * (size_t)a->nu * (size_t)a->nv))
        return 0;
    const rg2_scalars *sa[2] = {&a->su, &a->sv}, *sb[2] = {&b->su, &b->sv};
    for (int k = 0; k < 2; k++)
        if (sa[k]->closed != sb[k]->closed ||
            memcmp(sa[k]->w, sb[k]->w, sizeof(double) * (size_t)rg2_scalars_num_w(sa[k])) ||
            memcmp(sa[k]->b, sb[k]->b, sizeof(double) * (size_t)sa[k]->n) ||
            memcmp(sa[k]->g, sb[k]->g, sizeof(double) * (size_t)sa[k]->n))
            return 0;
    return 1;
}

static int same_surface(const rg2_surface *a, const rg2_surface *b)
{
    return a->nu == b->nu && a->nv == b->nv &&
           !memcmp(a->patch, b->patch, sizeof(rg2_patch) * (size_t)a->nu * (size_t)a->nv) &&
           !memcmp(a->tag, b->tag, sizeof(int) * (size_t)a->nu * (size_t)a->nv);
}

/* Edits that give a point its own values: "to" its own design point d = p / W (printed with 17
 * digits, which read back exactly) and "W" its own weight, on every point of a sphere band whose
 * weights are not all 1. W * (p / W) is not always p, so an edit that recomputed p moved points
 * by an ulp and took their patches off the sphere; the surface must come out bit for bit with
 * every tag. */
static void edits_to_own_values(void)
{
    const char *base = "{\"shapes\": {\"s\": {\"kind\": \"sphere\", \"radius\": 1.3}},"
                       " \"meshes\": {\"S\": {\"shape\": \"s\", \"u\": {\"arcs\": 8},"
                       " \"v\": {\"knots\": [0.2, 0.35, 0.5, 0.65, 0.8]}}";
    rg2_error err;
    char *json = malloc(65536);
    int n = json ? snprintf(json, 65536, "%s}}", base) : 0;
    rg2_design *d0 = json ? parse(json, &err) : NULL;
    if (!d0) {
        free(json);
        return;
    }
    const rg2_mesh *m = rg2_design_mesh(d0, 0);
    int not_back = 0;
    for (int kind = 0; kind < 2; kind++) {
        n = snprintf(json, 65536, "%s, \"E\": {\"edit\": \"S\", \"points\": [", base);
        for (int i = 0; i < m->nu; i++)
            for (int j = 0; j < m->nv; j++) {
                const double *p = rg2_mesh_at(m, i, j);
                double x[3] = {p[0] / p[3], p[1] / p[3], p[2] / p[3]};
                for (int k = 0; kind == 0 && k < 3; k++)
                    not_back += p[3] * x[k] != p[k];
                if (kind == 0)
                    n += snprintf(json + n, 65536 - (size_t)n, "%s{\"at\": [%d, %d], \"to\": [%.17g, %.17g, %.17g]}",
                                  i + j ? ", " : "", i, j, x[0], x[1], x[2]);
                else
                    n += snprintf(json + n, 65536 - (size_t)n, "%s{\"at\": [%d, %d], \"W\": %.17g}", i + j ? ", " : "",
                                  i, j, p[3]);
            }
        snprintf(json + n, 65536 - (size_t)n, "]}}, \"output\": \"E\"}");
        rg2_design *d1 = parse(json, &err);
        if (!d1)
            continue;
        const rg2_surface *s0 = rg2_design_surface(d0, 0), *s1 = rg2_design_surface(d1, 0);
        int exact = 0;
        for (int k = 0; k < s0->nu * s0->nv; k++)
            exact += s0->tag[k] >= 0;
        CHECK(same_surface(s0, s1) && exact == s0->nu * s0->nv,
              "every point %s its own %s: the surface changed (%d of %d patches exact before)",
              kind ? "given" : "moved to", kind ? "W" : "d", exact, s0->nu * s0->nv);
        rg2_design_free(d1);
    }
    printf("  edits to own values: %d coordinates where W * (p / W) != p\n", not_back);
    CHECK(not_back > 0, "no coordinate where W * (p / W) != p: the test does not test");
    rg2_design_free(d0);
    free(json);
}

static void morph_ends(void)
{
    const char *json =
        "{\"shapes\": {\"t\": {\"kind\": \"torus\", \"R\": 3, \"r\": 1},"
        "  \"c\": {\"kind\": \"cyclide\", \"a\": 2, \"c\": 0.7, \"mu\": 1.2}},"
        " \"meshes\": {\"A\": {\"shape\": \"t\", \"u\": {\"arcs\": [40, 50, 60, 70, 60, 80]}, \"v\": {\"arcs\": 5}},"
        "  \"B0\": {\"shape\": \"c\", \"u\": {\"arcs\": 6}, \"v\": {\"arcs\": [72, 60, 84, 72, 72]}},"
        "  \"B\": {\"edit\": \"B0\", \"points\": [{\"at\": [2, 2], \"move\": [0, 0, 0.5]}]},"
        "  \"M0\": {\"morph\": [\"A\", \"B\"], \"t\": 0}, \"M1\": {\"morph\": [\"A\", \"B\"], \"t\": 1},"
        "  \"Mh\": {\"morph\": [\"A\", \"B\"], \"t\": 0.5}},"
        " \"output\": [\"A\", \"B\", \"M0\", \"M1\", \"Mh\"]}";
    rg2_error err;
    rg2_design *d = parse(json, &err);
    if (!d)
        return;
    CHECK(same_mesh(rg2_design_mesh(d, 0), rg2_design_mesh(d, 2)), "morph t = 0 differs from A");
    CHECK(same_mesh(rg2_design_mesh(d, 1), rg2_design_mesh(d, 3)), "morph t = 1 differs from B");
    CHECK(same_surface(rg2_design_surface(d, 0), rg2_design_surface(d, 2)), "morph t = 0 surface differs");
    CHECK(same_surface(rg2_design_surface(d, 1), rg2_design_surface(d, 3)), "morph t = 1 surface differs");
    CHECK(!same_mesh(rg2_design_mesh(d, 0), rg2_design_mesh(d, 4)), "morph t = 0.5 equals A");
    const rg2_surface *h = rg2_design_surface(d, 4);
    int exact = 0;
    for (int k = 0; k < h->nu * h->nv; k++)
        exact += h->tag[k] >= 0;
    CHECK(exact == 0, "morph t = 0.5 of different shapes has %d exact patches", exact);
    rg2t_seams g;
    rg2t_surface_seams(h, 6, &g);
    CHECK(g.angle <= 1e-11 && g.curv <= 1e-9, "morph t = 0.5 seams %.3g rad, %.3g", g.angle, g.curv);
    int ex0 = 0;
    const rg2_surface *s0 = rg2_design_surface(d, 0);
    for (int k = 0; k < s0->nu * s0->nv; k++)
        ex0 += s0->tag[k] >= 0;
    CHECK(ex0 == s0->nu * s0->nv, "morph t = 0 keeps %d of %d exact patches", ex0, s0->nu * s0->nv);
    printf("  morph: t = 0 and t = 1 reproduce both meshes and surfaces bit for bit\n");
    rg2_design_free(d);
}

/* ------------------------------------------------------------------------------------- */

/* Largest |k1|, |k2| (times the surface size) and |H| over samples of the transition patches. */
static void transition_curvature(const rg2_surface *s, int samples, double *kmax, double *hmax)
{
    double size = rg2t_surface_scale(s);
    *kmax = *hmax = 0.0;
    for (int k = 0; k < s->nu * s->nv; k++) {
        if (s->tag[k] >= 0)
            continue;
        for (int a = 0; a <= samples; a++)
            for (int b = 0; b <= samples; b++) {
                rg2_eval e;
                rg2_surface_eval(s, k / s->nv, k % s->nv, (double)a / samples, (double)b / samples, 2, &e);
                double km = fmax(fabs(e.k1), fabs(e.k2)) * size;
                if (km > *kmax)
                    *kmax = km;
                if (fabs(e.H) * size > *hmax)
                    *hmax = fabs(e.H) * size;
            }
    }
}

/* The seam rule: "preserve" keeps every patch of both parts exact; "plain" loses the end
 * patches next to each seam whose data-only weights differ. Both are G2, and their transitions
 * are equally fair. Measured on the examples with merges. */
static void seam_rules(void)
{
    const char *files[] = {"examples/torus_sphere.json", "examples/fig6_torus_hyperboloid.json",
                           "examples/fig7_torus_cyclide.json"};
    for (int f = 0; f < 3; f++) {
        char *text = read_text(files[f]);
        cJSON *root = text ? cJSON_Parse(text) : NULL;
        CHECK(root != NULL, "%s missing or unreadable", files[f]);
        int counts[2] = {0, 0};
        double kmax[2] = {0, 0};
        for (int rule = 0; root && rule < 2; rule++) {
            for (cJSON *m = cJSON_GetObjectItem(root, "meshes")->child; m; m = m->next)
                if (cJSON_GetObjectItem(m, "merge")) {
                    cJSON_DeleteItemFromObject(m, "seam");
                    cJSON_AddStringToObject(m, "seam", rule ? "plain" : "preserve");
                }
            char *t = cJSON_PrintUnformatted(root);
            rg2_design *d = NULL;
            rg2_error err;
            CHECK_OK(rg2_design_parse(t, strlen(t), files[f], &d, &err), &err);
            if (d) {
                const rg2_surface *s = rg2_design_surface(d, 0);
                double res = exact_residual(d, s, 8, &counts[rule]), hmax;
                rg2t_seams g;
                rg2t_surface_seams(s, 8, &g);
                transition_curvature(s, 16, &kmax[rule], &hmax);
                printf("  %-36s seam %-8s: %3d exact patches (residual %.1e), seams %.1e rad / %.1e; "
                       "transitions: max |k| size %.2f, max |H| size %.2f\n",
                       files[f], rule ? "plain" : "preserve", counts[rule], res, g.angle, g.curv, kmax[rule], hmax);
                CHECK(res <= 1e-13 && g.angle <= 1e-11 && g.curv <= 1e-9, "%s seam rule %d: %.3g %.3g %.3g",
                      files[f], rule, res, g.angle, g.curv);
                rg2_design_free(d);
            }
            cJSON_free(t);
        }
        CHECK(counts[0] >= counts[1] && (f || counts[0] > counts[1]), "%s: preserve keeps %d exact patches, plain %d",
              files[f], counts[0], counts[1]);
        cJSON_Delete(root);
        free(text);
    }
}

/* ------------------------------------------------------------------------------------- */

#define TORUS_SHAPES "\"shapes\": {\"t\": {\"kind\": \"torus\", \"R\": 3, \"r\": 1}, \"s\": {\"kind\": \"sphere\"}}"
#define TORUS_MESH "\"T\": {\"shape\": \"t\", \"u\": {\"arcs\": 8}, \"v\": {\"arcs\": 6}}"

/* Scalar provenance across a merge (written by rg2_design_write_mesh as w_shape, junction_shape):
 * two cuts of one torus merged along u keep, in v (the direction they share), every leg weight
 * and junction tagged with the torus (shape 0), as the unmerged torus has them. */
static void merge_keeps_scalar_provenance(void)
{
    rg2_error err;
    rg2_design *d = parse("{" TORUS_SHAPES ", \"meshes\": {" TORUS_MESH ", \"A\": {\"cut\": \"T\", \"u\": [0, 4]},"
                          " \"B\": {\"cut\": \"T\", \"u\": [4, 8]}, \"M\": {\"merge\": [\"A\", \"B\"], \"along\": \"u\"}},"
                          " \"output\": [\"T\", \"M\"]}", &err);
    if (!d)
        return;
    CHECK(d->n_out == 2, "outputs: %d", d->n_out);
    if (d->n_out == 2) {
        const rg2__dmesh *T = &d->mesh[d->out[0]], *M = &d->mesh[d->out[1]];
        int nw = rg2_scalars_num_w(&M->m.sv), bad = 0, tagged = 0;
        for (int i = 0; i < nw; i++) {
            bad += M->leg[1][i] != T->leg[1][i];
            tagged += T->leg[1][i] == 0;
        }
        for (int i = 0; i < M->m.sv.n; i++) {
            bad += M->jun[1][i] != T->jun[1][i];
            tagged += T->jun[1][i] == 0;
        }
        CHECK(nw == rg2_scalars_num_w(&T->m.sv) && tagged == nw + T->m.sv.n,
              "the torus's v scalars are not all tagged with it (%d of %d)", tagged, nw + T->m.sv.n);
        CHECK(bad == 0, "merge: %d v leg/junction provenance tags differ from the torus's", bad);
    }
    rg2_design_free(d);
}

/* In-memory text: the same size limit as files (and no wrap-around of len + 1). */
static void parse_sizes(void)
{
    rg2_design *d = (rg2_design *)1;
    rg2_error err;
    const char *txt = "{}";
    CHECK(rg2_design_parse(txt, (size_t)-1, "huge", &d, &err) == RG2_ELIMIT && !d && strstr(err.msg, "huge: "),
          "SIZE_MAX bytes: %s", err.msg);
    CHECK(rg2_design_parse(txt, (size_t)RG2_TEXT_MAX_BYTES + 1, "big", &d, &err) == RG2_ELIMIT && !d,
          "past the text limit: %s", err.msg);
    CHECK(rg2_design_parse(txt, 2, "x", NULL, &err) == RG2_EINVAL, "NULL out: %s", err.msg);
    /* rg2_design_load wrote through a NULL out (and read a NULL path) */
    CHECK(rg2_design_load("x.json", NULL, &err) == RG2_EINVAL && !strcmp(err.msg, "design: NULL output pointer"),
          "load, NULL out: %s", err.msg);
    d = (rg2_design *)1;
    CHECK(rg2_design_load(NULL, &d, &err) == RG2_EINVAL && !d &&
              !strcmp(err.msg, "design: no file name (NULL path)"),
          "load, NULL path: %s", err.msg);
}


/* Design files read through rg2_design_load / rg2_read_text: past the first 64 KiB buffer (the
 * growth path), exactly at the documented 64 MiB limit (read whole and built) and one byte past
 * it (refused, naming the file). The padding is trailing JSON whitespace, so each file must build
 * the same surface as its text parsed from memory. */
static int write_padded(const char *path, const char *text, size_t size)
{
    FILE *f = fopen(path, "wb");
    if (!f)
        return 0;
    size_t n = strlen(text), left = size - n;
    int ok = fwrite(text, 1, n, f) == n;
    static char pad[1 << 16];
    memset(pad, ' ', sizeof pad);
    while (ok && left > 0) {
        size_t k = left < sizeof pad ? left : sizeof pad;
        ok = fwrite(pad, 1, k, f) == k;
        left -= k;
    }
    return fclose(f) == 0 && ok;
}

/* The control mesh JSON (rg2_design_write_mesh) read back: every output mesh's design points
 * d = p_{1..3} / p_4 and weights W = p_4 against the mesh's homogeneous points, and its scalars
 * w, b, g, bit for bit (a torus with two weights edited, W = 2.5 and 0.5, and its transpose;
 * cJSON's own printing, 15 digits when they read back within an ulp, lost (with r = 1) the
 * last bit of 12 of the 384 d and W values and of 16 scalars: a point set with "to" from its
 * printed position was no longer the torus's). */
static int scalars_read_back(const cJSON *js, const rg2_scalars *s)
{
    const double *v[3] = {s->w, s->b, s->g};
    const char *key[3] = {"w", "b", "g"};
    int differ = 0;
    for (int k = 0; k < 3; k++) {
        const cJSON *a = cJSON_GetObjectItemCaseSensitive(js, key[k]);
        int n = k ? s->n : rg2_scalars_num_w(s);
        differ += cJSON_GetArraySize(a) != n;
        for (int i = 0; i < n && i < cJSON_GetArraySize(a); i++)
            differ += cJSON_GetArrayItem(a, i)->valuedouble != v[k][i];
    }
    return differ;
}

/* The numbers of a JSON text not written in the fewest of 15, 16 or 17 significant digits that
 * read back to the same double (docs/design-format.md, "The mesh file"): each number is read
 * with strtod and printed again here. *tight counts those 15 digits hold whose 16 digits print
 * otherwise (where starting at 16 digits would show). Strings are skipped. */
static int not_fewest_digits(const char *text, int *numbers, int *tight)
{
    int off = 0;
    *numbers = *tight = 0;
    for (const char *c = text; *c;) {
        if (*c == '"') {
            for (c++; *c && *c != '"'; c++)
                c += c[0] == '\\' && c[1];
            c += *c == '"';
        } else if (*c == '-' || (*c >= '0' && *c <= '9')) {
            char *end, want[40] = "";
            double x = strtod(c, &end);
            for (int digits = 15; digits <= 17; digits++) {
                snprintf(want, sizeof want, "%.*g", digits, x);
                if (strtod(want, NULL) == x)
                    break;
            }
            char alt[40];
            snprintf(alt, sizeof alt, "%.16g", x);
            *tight += strlen(want) < strlen(alt) && strtod(alt, NULL) == x;
            off += (size_t)(end - c) != strlen(want) || strncmp(c, want, strlen(want)) != 0;
            (*numbers)++;
            c = end > c ? end : c + 1;
        } else
            c++;
    }
    return off;
}

/* Non-finite numbers as JSON's null (cJSON's convention: JSON has no infinity or NaN), never as
 * the "inf" a digits loop would print and read back; finite ones in their fewest digits */
static void json_numbers(void)
{
    const double x[5] = {INFINITY, -INFINITY, NAN, 0.1, 1.0 / 3.0};
    cJSON *a = rg2__json_doubles(x, 5);
    char *text = a ? rg2__json_print(a, 0) : NULL;
    CHECK(text && !strcmp(text, "[null,null,null,0.1,0.3333333333333333]"), "inf, -inf, nan, 0.1, 1/3 as '%s'",
          text ? text : "(none)");
    free(text);
    cJSON_Delete(a);
}

/* Every form of a JSON number is taken (0, -0, 0.0e0, 1E+0, 10.25, 0e-5), and text like 01, 1.
 * and -.5 inside a string is not a number: the design parses, and its torus has the radii given.
 * (The malformed forms outside strings: bad_inputs.) */
static void json_number_forms(void)
{
    rg2_error err;
    rg2_design *d = parse("{\"description\": \"r = 01, R = 3., -.5 and \\\"0.\\\" in a string\", \"shapes\": "
                          "{\"t\": {\"kind\": \"torus\", \"R\": 30.0e-1, \"r\": 1E+0, \"translate\": [-0, 0.0e0, 0e-5]}},"
                          " \"meshes\": {\"T\": {\"shape\": \"t\", \"u\": {\"arcs\": [90, 90, 90, 90]},"
                          " \"v\": {\"arcs\": [10.25, 169.75, 90, 90]}}}}",
                          &err);
    if (!d)
        return;
    const rg2_surface *s = rg2_design_num_surfaces(d) == 1 ? rg2_design_surface(d, 0) : NULL;
    CHECK(s && s->nu == 4 && s->nv == 4, "JSON number forms: %d x %d patches, want 4 x 4", s ? s->nu : -1,
          s ? s->nv : -1);
    if (s) { /* the patch corner at u = 0, v = 0: (R + r, 0, 0) */
        rg2_eval e;
        rg2_patch_eval(rg2_surface_patch(s, 0, 0), 0, 0, 0, &e);
        CHECK(fabs(e.p[0] - 4) < 1e-15 && fabs(e.p[1]) < 1e-15 && fabs(e.p[2]) < 1e-15,
              "JSON number forms: corner (%.17g, %.17g, %.17g), want (4, 0, 0)", e.p[0], e.p[1], e.p[2]);
    }
    rg2_design_free(d);
}

/* A rotation of 1.5708, 3.1416 or 6.2832 "degrees" (radians typed for degrees, most likely) is
 * built as given, with a note naming the key, the value and the degrees meant; 90, 1.6 and 0
 * give none. The rotation is the one written: the torus's axis turns by 1.5708 degrees. */
static void rotate_radians_note(void)
{
    static const struct {
        double deg;
        const char *note; /* NULL: no note */
    } cases[] = {{1.5708, "shapes.t.rotate.degrees: 1.5708 is pi / 2 (a quarter circle in radians); angles in a "
                          "design file are in degrees, so this turns by 1.5708 degrees (for the turn of 1.5708 "
                          "radians write 90)"},
                 {-3.1416, "shapes.t.rotate.degrees: -3.1416 is pi (a half circle in radians)"},
                 {6.2832, "shapes.t.rotate.degrees: 6.2832 is 2 pi (a full circle in radians)"},
                 {0.7854, "shapes.t.rotate.degrees: 0.7854 is pi / 4 (45 degrees in radians); angles in a design "
                          "file are in degrees, so this turns by 0.7854 degrees (for the turn of 0.7854 radians "
                          "write 45)"},
                 {-1.0472, "shapes.t.rotate.degrees: -1.0472 is pi / 3 (60 degrees in radians)"},
                 {0.5236, "shapes.t.rotate.degrees: 0.5236 is pi / 6 (30 degrees in radians)"},
                 {4.71239, "shapes.t.rotate.degrees: 4.71239 is 3 pi / 2 (270 degrees in radians)"},
                 {2.0944, "shapes.t.rotate.degrees: 2.0944 is 2 pi / 3 (120 degrees in radians)"},
                 {45, NULL},
                 {0.8, NULL},
                 {90, NULL},
                 {1.6, NULL},
                 {0, NULL}};
    for (size_t k = 0; k < sizeof cases / sizeof *cases; k++) {
        char js[400];
        snprintf(js, sizeof js,
                 "{\"shapes\": {\"t\": {\"kind\": \"torus\", \"rotate\": {\"axis\": [1, 0, 0], \"degrees\": %.17g}}},"
                 " \"meshes\": {\"T\": {\"shape\": \"t\", \"u\": {\"arcs\": 4}, \"v\": {\"arcs\": 4}}}}",
                 cases[k].deg);
        rg2_error err;
        rg2_design *d = parse(js, &err);
        if (!d)
            continue;
        const char *note = rg2_design_note(d, 0), *at = note ? strstr(note, "shapes.t.") : NULL;
        if (cases[k].note)
            CHECK(rg2_design_num_notes(d) == 1 && at && !strncmp(at, cases[k].note, strlen(cases[k].note)),
                  "rotate %.17g degrees: %d notes, first '%s', want '%s'", cases[k].deg, rg2_design_num_notes(d),
                  note ? note : "(none)", cases[k].note);
        else
            CHECK(rg2_design_num_notes(d) == 0, "rotate %.17g degrees: a note '%s'", cases[k].deg, note);
        /* the torus's axis (0, 0, 1) turned about x by the degrees given: the point of the tube's top
         * circle over (R, 0) (u = 0, v = 90 degrees: (R, 0, r)) goes to (R, -r sin a, r cos a) */
        const rg2_surface *s = rg2_design_num_surfaces(d) == 1 ? rg2_design_surface(d, 0) : NULL;
        if (s) {
            rg2_eval e;
            rg2_patch_eval(rg2_surface_patch(s, 0, 1), 0, 0, 0, &e);
            double a = cases[k].deg * M_PI / 180, want[3] = {3, -sin(a), cos(a)};
            double dev = fabs(e.p[0] - want[0]) + fabs(e.p[1] - want[1]) + fabs(e.p[2] - want[2]);
            CHECK(dev < 1e-14, "rotate %.17g degrees: (%.17g, %.17g, %.17g), want (%.17g, %.17g, %.17g)",
                  cases[k].deg, e.p[0], e.p[1], e.p[2], want[0], want[1], want[2]);
        }
        rg2_design_free(d);
    }
    printf("rotate by radians typed for degrees: a note for 1.5708, -3.1416 and 6.2832, none for 90, 1.6 and 0\n");
}

/* A transformed shape's label is "<label>@<path>"; a chain of transforms appends each path while
 * the label stays within 255 bytes, and past that keeps its first part and the last path,
 * "c@...@meshes.m<k>": labels stay short and a chain's labels grow linearly in total (whole
 * labels of every part made a chain of T links O(T^2) bytes; test_scaling measures it). */
static void transform_chain_labels(void)
{
    enum { N = 60 };
    char *js = malloc(200 + 64 * N);
    if (!js)
        return;
    size_t n = (size_t)sprintf(js, "{\"shapes\": {\"c\": {\"kind\": \"cylinder\"}}, \"meshes\": {\"m0\": {\"shape\": "
                                   "\"c\", \"u\": {\"arcs\": 8}}");
    for (int k = 1; k <= N; k++)
        n += (size_t)sprintf(js + n, ", \"m%d\": {\"transform\": \"m%d\", \"translate\": [0, 0, 0.001]}", k, k - 1);
    sprintf(js + n, "}, \"output\": \"m%d\"}", N);
    rg2_error err;
    rg2_design *d = parse(js, &err);
    free(js);
    if (!d)
        return;
    size_t longest = 0;
    int elided = 0, chained = 0;
    for (int k = 0; k < rg2_design_num_shapes(d); k++) {
        const char *l = rg2_design_shape_label(d, k);
        longest = strlen(l) > longest ? strlen(l) : longest;
        elided += !strncmp(l, "c@...@meshes.m", 14);
        chained += !strncmp(l, "c@meshes.m1@meshes.m2@", 22);
    }
    const char *last = rg2_design_shape_label(d, rg2_design_num_shapes(d) - 1);
    char tail[32];
    snprintf(tail, sizeof tail, "@meshes.m%d", N);
    size_t lt = strlen(tail), ll = last ? strlen(last) : 0;
    printf("a chain of %d transforms: %d shape labels, the longest %zu bytes, %d of them elided, the last '%s'\n", N,
           rg2_design_num_shapes(d), longest, elided, last ? last : "");
    CHECK(rg2_design_num_shapes(d) == N + 1 && longest <= 255 + 16 && elided > 0 && chained > 0 && ll > lt &&
              !strcmp(last + ll - lt, tail) && !strncmp(last, "c@", 2),
          "a chain of %d transforms: %d shapes, longest label %zu bytes, %d elided, %d chained, last '%s'", N,
          rg2_design_num_shapes(d), longest, elided, chained, last ? last : "");
    rg2_design_free(d);
}

/* A transform of a mesh that uses many sources and shapes: 40 cylinder pieces, each its own
 * shape (c0 .. c39, the same cylinder) and source, merged along v and moved. Between them the
 * design has 15 shapes and 15 meshes it does not output, so the pieces' sources and shapes are
 * 16 apart: the transform's index maps (source -> its copy, shape -> its copy; 16 slots at first,
 * doubled at half full, a key's first slot its hash's low bits) hold 40 keys that collide at
 * every size. Every point of the moved mesh must come from the copy of its own shape
 * ("c<k>@meshes.T"), as in the merged mesh. */
static void transform_many_sources(void)
{
    enum { N = 40, GAP = 15 };
    char *js = malloc(400 + 200 * N * (GAP + 1));
    if (!js)
        return;
    size_t n = (size_t)sprintf(js, "{\"shapes\": {");
    for (int k = 0; k < N; k++) {
        n += (size_t)sprintf(js + n, "%s\"c%d\": {\"kind\": \"cylinder\"}", k ? ", " : "", k);
        for (int g = 0; g < GAP; g++)
            n += (size_t)sprintf(js + n, ", \"z%d_%d\": {\"kind\": \"sphere\"}", k, g);
    }
    n += (size_t)sprintf(js + n, "}, \"meshes\": {");
    for (int k = 0; k < N; k++) {
        n += (size_t)sprintf(js + n, "\"p%d\": {\"shape\": \"c%d\", \"u\": {\"arcs\": 4}, \"v\": {\"segments\": 3, "
                                     "\"from\": %d, \"to\": %d}}, ", k, k, k, k + 1);
        for (int g = 0; g < GAP; g++)
            n += (size_t)sprintf(js + n, "\"q%d_%d\": {\"shape\": \"c%d\", \"u\": {\"arcs\": 4}, \"v\": {\"segments\": 1, "
                                         "\"from\": 0, \"to\": 1}}, ", k, g, k);
    }
    n += (size_t)sprintf(js + n, "\"all\": {\"merge\": [");
    for (int k = 0; k < N; k++)
        n += (size_t)sprintf(js + n, "%s\"p%d\"", k ? ", " : "", k);
    sprintf(js + n, "], \"along\": \"v\"}, \"T\": {\"transform\": \"all\", \"translate\": [1, 2, 3]}}, "
                    "\"output\": [\"all\", \"T\"]}");
    rg2_error err;
    rg2_design *d = parse(js, &err);
    free(js);
    if (!d)
        return;
    const rg2_mesh *ma = rg2_design_mesh(d, 0), *mt = rg2_design_mesh(d, 1);
    int points = 0, same = 0, wrong = 0, seen[N] = {0};
    for (int i = 0; ma && mt && i < ma->nu && i < mt->nu; i++)
        for (int j = 0; j < ma->nv && j < mt->nv; j++) {
            int a = rg2_design_point_shape(d, 0, i, j), t = rg2_design_point_shape(d, 1, i, j);
            points++;
            if (a < 0 && t < 0)
                continue;
            const char *la = a >= 0 ? rg2_design_shape_label(d, a) : "", *lt = t >= 0 ? rg2_design_shape_label(d, t) : "";
            char want[64];
            snprintf(want, sizeof want, "%s@meshes.T", la);
            int k = a >= 0 && la[0] == 'c' ? atoi(la + 1) : -1;
            if (a >= 0 && t >= 0 && !strcmp(lt, want) && k >= 0 && k < N) {
                same++;
                seen[k] = 1;
            } else if (wrong++ < 3)
                printf("  point (%d, %d): merged from '%s', moved from '%s'\n", i, j, la, lt);
        }
    int shapes_seen = 0;
    for (int k = 0; k < N; k++)
        shapes_seen += seen[k];
    printf("a transform of %d merged pieces of %d shapes: %d of %d points from the copy of their own shape, %d not; "
           "%d shapes\n", N, N, same, points, wrong, rg2_design_num_shapes(d));
    CHECK(ma && mt && ma->nu == mt->nu && ma->nv == mt->nv && !wrong && shapes_seen == N &&
              rg2_design_num_shapes(d) == (GAP + 2) * N,
          "a transform of %d pieces: %d points from another shape's copy, %d of %d shapes seen, %d shapes", N, wrong,
          shapes_seen, N, rg2_design_num_shapes(d));
    rg2_design_free(d);
}

static void check_written_mesh(const char *path)
{
    rg2_error err;
    /* r = 0.987654321098765: 15 digits read back, 16 print as ...651 */
    rg2_design *d = parse("{\"shapes\": {\"t\": {\"kind\": \"torus\", \"R\": 3, \"r\": 0.987654321098765}, "
                          "\"s\": {\"kind\": \"sphere\"}}, \"meshes\": {" TORUS_MESH ", \"E\": {\"edit\": \"T\", \"points\":"
                          " [{\"at\": [1, 2], \"W\": 2.5}, {\"at\": [5, 0], \"W\": 0.5}]},"
                          " \"F\": {\"transpose\": \"E\"}}, \"output\": [\"E\", \"F\"]}",
                          &err);
    if (!d)
        return;
    CHECK_OK(rg2_design_write_mesh(d, path, &err), &err);
    char *text = read_text(path);
    cJSON *root = text ? cJSON_Parse(text) : NULL;
    int numbers = 0, tight = 0, long_form = text ? not_fewest_digits(text, &numbers, &tight) : -1;
    CHECK(long_form == 0 && numbers > 500 && tight > 0,
          "%s: %d of %d numbers not in the fewest of 15, 16, 17 digits that read back (%d where 15 differ from 16)",
          path, long_form, numbers, tight);
    /* formatted, one key per line as docs/design-format.md shows it, not a single line */
    CHECK(text && !strncmp(text, "{\n", 2), "%s is not formatted JSON: '%.20s'", path, text ? text : "");
    free(text);
    const cJSON *meshes = cJSON_GetObjectItemCaseSensitive(root, "meshes");
    CHECK(cJSON_GetArraySize(meshes) == rg2_design_num_surfaces(d), "%s: %d meshes written", path,
          cJSON_GetArraySize(meshes));
    /* each shape's placement: its 16 entries, as the design has them */
    const cJSON *shapes = cJSON_GetObjectItemCaseSensitive(root, "shapes");
    int xf_off = cJSON_GetArraySize(shapes) != rg2_design_num_shapes(d);
    for (int k = 0; k < cJSON_GetArraySize(shapes) && k < rg2_design_num_shapes(d); k++) {
        const cJSON *mx = cJSON_GetObjectItemCaseSensitive(cJSON_GetArrayItem(shapes, k), "matrix");
        const rg2_shape *sh = rg2_design_shape(d, k);
        xf_off += cJSON_GetArraySize(mx) != 16 || !sh;
        for (int e = 0; sh && e < 16 && e < cJSON_GetArraySize(mx); e++)
            xf_off += cJSON_GetArrayItem(mx, e)->valuedouble != sh->xform[e];
    }
    CHECK(!xf_off, "%s: %d shapes written, %d placement matrices or entries not the design's", path,
          cJSON_GetArraySize(shapes), xf_off);
    double dev = 0.0;
    int points = 0, w_not_1 = 0, off = 0, scalars_off = 0;
    for (int o = 0; o < rg2_design_num_surfaces(d) && o < cJSON_GetArraySize(meshes); o++) {
        const rg2_mesh *m = rg2_design_mesh(d, o);
        const cJSON *jm = cJSON_GetArrayItem(meshes, o), *D = cJSON_GetObjectItemCaseSensitive(jm, "d"),
                    *W = cJSON_GetObjectItemCaseSensitive(jm, "W");
        CHECK(cJSON_GetArraySize(D) == m->nu && cJSON_GetArraySize(W) == m->nu, "mesh %d: %d rows written", o,
              cJSON_GetArraySize(D));
        for (int i = 0; i < m->nu && i < cJSON_GetArraySize(D) && i < cJSON_GetArraySize(W); i++)
            for (int j = 0; j < m->nv; j++) {
                const double *p = rg2_mesh_at(m, i, j);
                const cJSON *x = cJSON_GetArrayItem(cJSON_GetArrayItem(D, i), j);
                const cJSON *w = cJSON_GetArrayItem(cJSON_GetArrayItem(W, i), j);
                if (cJSON_GetArraySize(x) != 3 || !cJSON_IsNumber(w)) {
                    dev = INFINITY;
                    continue;
                }
                for (int k = 0; k < 4; k++) {
                    double got = k < 3 ? cJSON_GetArrayItem(x, k)->valuedouble : w->valuedouble;
                    double want = k < 3 ? p[k] / p[3] : p[3];
                    dev = fmax(dev, fabs(got - want));
                    off += got != want;
                }
                w_not_1 += p[3] != 1.0;
                points++;
            }
        scalars_off += scalars_read_back(cJSON_GetObjectItemCaseSensitive(jm, "u"), &m->su) +
                       scalars_read_back(cJSON_GetObjectItemCaseSensitive(jm, "v"), &m->sv);
    }
    CHECK(off == 0 && scalars_off == 0 && w_not_1 > 0,
          "%s: %d points read back, %d values off (by up to %.3g), %d scalars off (%d with W != 1)", path, points,
          off, dev, scalars_off, w_not_1);
    cJSON_Delete(root);
    remove(path);
    rg2_design_free(d);
}

static void text_files(void)
{
    const char *text = "{\"shapes\": {\"comment\": \"a comment among the shapes\","
                       " \"t\": {\"kind\": \"torus\", \"R\": 3, \"r\": 1}},"
                       " \"meshes\": {\"T\": {\"shape\": \"t\", \"u\": {\"arcs\": 8}, \"v\": {\"arcs\": 6}}}}";
    rg2_error err;
    rg2_design *ref = parse(text, &err);
    if (!ref)
        return;
    /* the "comment" key of "shapes" is no shape */
    CHECK(rg2_design_num_shapes(ref) == 1 && !strcmp(rg2_design_shape_label(ref, 0), "t"),
          "shapes with a comment: %d shapes, first '%s'", rg2_design_num_shapes(ref), rg2_design_shape_label(ref, 0));
    char dir[] = "/tmp/rg2-design-XXXXXX";
    if (!mkdtemp(dir)) {
        CHECK(0, "mkdtemp failed");
        rg2_design_free(ref);
        return;
    }
    char path[96];
    snprintf(path, sizeof path, "%s/d.json", dir);
    const size_t sizes[3] = {100000, RG2_TEXT_MAX_BYTES, (size_t)RG2_TEXT_MAX_BYTES + 1};
    for (int k = 0; k < 3; k++) {
        CHECK(write_padded(path, text, sizes[k]), "cannot write %zu bytes to %s", sizes[k], path);
        rg2_design *d = (rg2_design *)1;
        rg2_status st = rg2_design_load(path, &d, &err);
        if (k < 2) {
            CHECK(st == RG2_OK, "a design file of %zu bytes: %s", sizes[k], err.msg);
            if (st == RG2_OK) {
                CHECK(same_surface(rg2_design_surface(d, 0), rg2_design_surface(ref, 0)),
                      "a design file of %zu bytes builds another surface than its text", sizes[k]);
                rg2_design_free(d);
            }
            char *buf = NULL;
            size_t len = 0;
            CHECK_OK(rg2_read_text(path, &buf, &len, &err), &err);
            CHECK(buf && len == sizes[k] && buf[len] == 0 && !strncmp(buf, text, strlen(text)),
                  "rg2_read_text of %zu bytes: length %zu", sizes[k], len);
            free(buf);
        } else {
            char want[64];
            snprintf(want, sizeof want, "larger than %u bytes", RG2_TEXT_MAX_BYTES);
            CHECK(st == RG2_ELIMIT && d == NULL && strstr(err.msg, path) && strstr(err.msg, want),
                  "a design file of %zu bytes: %s '%s'", sizes[k], rg2_status_str(st), err.msg);
        }
        remove(path);
    }
    /* the control mesh JSON read back, then onto a full disk (files fail past 100 bytes) */
    {
        snprintf(path, sizeof path, "%s/m.json", dir);
        check_written_mesh(path);
        json_numbers();
        json_number_forms();
        rotate_radians_note();
        transform_chain_labels();
        transform_many_sources();
        CHECK(rg2t_file_limit(100) == 0, "file size limit");
        rg2_status st = rg2_design_write_mesh(ref, path, &err);
        rg2t_file_limit(-1);
        CHECK(st == RG2_EIO && strstr(err.msg, path) && strstr(err.msg, "write failed") &&
                  strstr(err.msg, strerror(EFBIG)) && access(path, F_OK) != 0,
              "control mesh on a full disk: %s '%s'", rg2_status_str(st), err.msg);
    }
    /* an empty or NULL file name: said so, not fopen's ": cannot open: No such file" */
    {
        char *buf = (char *)1;
        rg2_design *d = (rg2_design *)1;
        CHECK(rg2_design_load("", &d, &err) == RG2_EIO && d == NULL &&
                  !strcmp(err.msg, "'': cannot open: the file name is empty"),
              "empty design file name: '%s'", err.msg);
        CHECK(rg2_read_text(NULL, &buf, NULL, &err) == RG2_EINVAL && buf == NULL &&
                  !strcmp(err.msg, "read_text: no file name"),
              "NULL path: '%s'", err.msg);
        CHECK(rg2_read_text(path, NULL, NULL, &err) == RG2_EINVAL && !strcmp(err.msg, "read_text: no output"),
              "NULL output: '%s'", err.msg);
    }
    CHECK(rmdir(dir) == 0, "a file left in %s", dir);
    printf("  design files of 100000 and %u bytes (the limit) build the same surface as their text; %u + 1 refused\n",
           RG2_TEXT_MAX_BYTES, RG2_TEXT_MAX_BYTES);
    /* accessors out of range, and texts without a name or without text */
    CHECK(rg2_design_point_shape(ref, 0, 0, 0) == 0 && rg2_design_point_shape(ref, 1, 0, 0) == -1 &&
              rg2_design_point_shape(ref, 0, 8, 0) == -1 && rg2_design_point_shape(ref, 0, 0, -1) == -1 &&
              rg2_design_point_shape(NULL, 0, 0, 0) == -1,
          "point provenance out of range is -1");
    CHECK(!rg2_design_surface(ref, 1) && !rg2_design_mesh(ref, -1) && !rg2_design_mesh_name(ref, 1) &&
              !rg2_design_shape(ref, 1) && !rg2_design_shape_label(ref, -1) && rg2_design_num_surfaces(NULL) == 0 &&
              rg2_design_num_shapes(NULL) == 0,
          "accessors out of range give NULL / 0");
    rg2_design_free(ref);
    rg2_design *d = (rg2_design *)1;
    CHECK(rg2_design_parse(NULL, 3, "nothing", &d, &err) == RG2_EINVAL && !d && !strcmp(err.msg, "nothing: no text"),
          "NULL text: %s", err.msg);
    CHECK(rg2_design_parse("[]", 2, NULL, &d, &err) == RG2_EPARSE && !d && !strncmp(err.msg, "design: ", 8),
          "no name: messages say 'design': %s", err.msg);
}

/* A bi-cubic NURBS wall (non-uniform u knots, one weight 1.5, a bulge) as a design mesh
 * ("nurbs" operation), merged closed along u with half a cylinder whose heights are the wall's
 * v knots: a D-shaped duct. The wall's v scalars agree with the cylinder's, the seams are G2, the
 * cylinder patches stay exact, and the wall's own patches in the duct are the NURBS itself: the
 * same points as the NURBS built alone (rg2_nurbs_mesh, checked against Cox-de Boor by
 * test_nurbs). */
#define WALL_SPEC \
    "{\"nu\": 6, \"nv\": 7, \"points\": [[-0.666667, -1, -0.5], [-0.666667, -1, 0.0], [-0.666667, -1, 0.5], [" \
    "-0.666667, -1, 1.0], [-0.666667, -1, 1.5], [-0.666667, -1, 2.0], [-0.666667, -1, 2.5], [-0.426667, -1, -" \
    "0.5], [-0.426667, -1, 0.0], [-0.426667, -1.15, 0.5], [-0.426667, -1.15, 1.0], [-0.426667, -1.15, 1.5], [" \
    "-0.426667, -1, 2.0], [-0.426667, -1, 2.5], [-0.151111, -1, -0.5], [-0.151111, -1, 0.0], [-0.151111, -1.1" \
    "5, 0.5], [-0.151111, -1.15, 1.0], [-0.151111, -1.15, 1.5], [-0.151111, -1, 2.0], [-0.151111, -1, 2.5], [" \
    "0.115556, -1, -0.5], [0.115556, -1, 0.0], [0.115556, -1.15, 0.5], [0.115556, -1.15, 1.0], [0.115556, -1." \
    "15, 1.5], [0.115556, -1, 2.0], [0.115556, -1, 2.5], [0.408889, -1, -0.5], [0.408889, -1, 0.0], [0.408889" \
    ", -1.15, 0.5], [0.408889, -1.15, 1.0], [0.408889, -1.15, 1.5], [0.408889, -1, 2.0], [0.408889, -1, 2.5]," \
    " [0.666667, -1, -0.5], [0.666667, -1, 0.0], [0.666667, -1, 0.5], [0.666667, -1, 1.0], [0.666667, -1, 1.5" \
    "], [0.666667, -1, 2.0], [0.666667, -1, 2.5]], \"weights\": [1, 1, 1, 1, 1, 1, 1, 1, 1, 1, 1, 1, 1, 1, 1," \
    " 1, 1, 1.5, 1, 1, 1, 1, 1, 1, 1, 1, 1, 1, 1, 1, 1, 1, 1, 1, 1, 1, 1, 1, 1, 1, 1, 1], \"knots_u\": [0, 1," \
    " 2, 3, 3.7, 5.1, 6, 7, 8, 9], \"knots_v\": [-1.5, -1, -0.5, 0, 0.5, 1, 1.5, 2, 2.5, 3, 3.5]}"

static void nurbs_pieces(void)
{
    const char *json = "{\"shapes\": {\"pipe\": {\"kind\": \"cylinder\", \"radius\": 1}},"
                       " \"meshes\": {\"half\": {\"shape\": \"pipe\", \"u\": {\"arcs\": 4, \"from\": 0, \"to\": 180},"
                       "                        \"v\": {\"segments\": 4, \"from\": 0, \"to\": 2}},"
                       "  \"wall\": {\"nurbs\": " WALL_SPEC "},"
                       "  \"duct\": {\"merge\": [\"half\", \"wall\"], \"along\": \"u\", \"closed\": true}},"
                       " \"output\": [\"wall\", \"duct\"]}";
    rg2_error err;
    rg2_design *d = parse(json, &err);
    cJSON *j = cJSON_Parse(WALL_SPEC);
    if (!d || !j) {
        CHECK(j != NULL, "wall spec parses");
        cJSON_Delete(j);
        rg2_design_free(d);
        return;
    }
    /* the NURBS built alone */
    int nu = cJSON_GetObjectItem(j, "nu")->valueint, nv = cJSON_GetObjectItem(j, "nv")->valueint, k = 0;
    double P[6 * 7 * 3], W[6 * 7], U[10], V[11];
    const cJSON *it;
    cJSON_ArrayForEach(it, cJSON_GetObjectItem(j, "points"))
    {
        for (int q = 0; q < 3; q++)
            P[3 * k + q] = cJSON_GetArrayItem(it, q)->valuedouble;
        k++;
    }
    k = 0;
    cJSON_ArrayForEach(it, cJSON_GetObjectItem(j, "weights")) W[k++] = it->valuedouble;
    k = 0;
    cJSON_ArrayForEach(it, cJSON_GetObjectItem(j, "knots_u")) U[k++] = it->valuedouble;
    k = 0;
    cJSON_ArrayForEach(it, cJSON_GetObjectItem(j, "knots_v")) V[k++] = it->valuedouble;
    rg2_nurbs nb = {nu, nv, P, W, U, V};
    rg2_mesh m;
    rg2_surface alone;
    CHECK_OK(rg2_nurbs_mesh(&nb, &m, &err), &err);
    CHECK_OK(rg2_surface_build(&m, &alone, &err), &err);
    const rg2_surface *wall = rg2_design_surface(d, 0), *duct = rg2_design_surface(d, 1);
    CHECK(wall->nu == nu - 3 && wall->nv == nv - 3 && duct->nu == 13 && duct->nv == 4,
          "wall %d x %d patches, duct %d x %d", wall->nu, wall->nv, duct->nu, duct->nv);
    /* duct patches: 0 and 5..7, 11, 12 straddle the seams; 1..4 the half cylinder, 8..10 the wall */
    double dev_wall = 0, dev_duct = 0, scale = rg2t_surface_scale(&alone);
    for (int a = 0; a < alone.nu && a < wall->nu; a++)
        for (int b = 0; b < alone.nv && b < wall->nv && b < duct->nv; b++)
            for (int q = 0; q <= 16; q++) {
                rg2_eval e0, e1, e2;
                double s = (q % 4) / 3.0, t = (q / 4) / 4.0;
                rg2_surface_eval(&alone, a, b, s, t, 0, &e0);
                rg2_surface_eval(wall, a, b, s, t, 0, &e1);
                rg2_surface_eval(duct, 8 + a, b, s, t, 0, &e2);
                for (int c = 0; c < 3; c++) {
                    dev_wall = fmax(dev_wall, fabs(e1.p[c] - e0.p[c]));
                    dev_duct = fmax(dev_duct, fabs(e2.p[c] - e0.p[c]));
                }
            }
    int exact = 0, wall_tagged = 0;
    for (int a = 0; a < duct->nu; a++)
        for (int b = 0; b < duct->nv; b++) {
            int tag = duct->tag[a * duct->nv + b];
            exact += tag >= 0 && a >= 1 && a <= 4;
            wall_tagged += tag >= 0 && !(a >= 1 && a <= 4);
        }
    rg2t_seams sm;
    rg2t_surface_seams(duct, 9, &sm);
    int ns = rg2_design_num_shapes(d), n_exact;
    double res = exact_residual(d, duct, 6, &n_exact);
    printf("  NURBS wall + half cylinder: wall = NURBS alone to %.1e, in the duct to %.1e (of size %.2f); %d exact "
           "cylinder patches (residual %.1e); seams %.1e rad, %.1e\n",
           dev_wall, dev_duct, scale, exact, res, sm.angle, sm.curv);
    CHECK(dev_wall <= 1e-15 * scale && dev_duct <= 1e-14 * scale, "the wall's patches are the NURBS (%.3g, %.3g)",
          dev_wall, dev_duct);
    CHECK(exact == 16 && wall_tagged == 0 && n_exact == 16 && ns == 1 && res <= 1e-13,
          "16 exact cylinder patches (%d, %d tagged elsewhere, residual %.3g)", exact, wall_tagged, res);
    CHECK(sm.pos <= 1e-14 && sm.angle <= 1e-12 && sm.curv <= 1e-10 && sm.skipped == 0,
          "duct seams G2: %.3g %.3g %.3g (%d skipped)", sm.pos, sm.angle, sm.curv, sm.skipped);
    rg2_surface_free(&alone);
    rg2_mesh_free(&m);
    cJSON_Delete(j);
    rg2_design_free(d);
}

/* A pole edit keeps each point's weight: a NURBS whose south row is one point with weights 1,
 * 1.5, 2, 2.5, 3 (collapsed projectively). Copying point 0 over the row made every weight 1, so a
 * zero move changed the surface (by up to 0.25); now the zero move builds the same patches bit
 * for bit, and a move of (0, 0, 0.5) keeps the weights and moves the whole row. */
static void pole_edit_weights(void)
{
    static const char *fmt = "{\"shapes\": {}, \"meshes\": {\"a\": {\"nurbs\": {\"nu\": 5, \"nv\": 5, \"points\": ["
                             "[0, 0, 0], [0.0, 1.0, 0.0], [0.0, 2.0, 0.0], [0.0, 3.0, 0.0], [0.0, 4.0, 0.0], "
                             "[0, 0, 0], [1.0, 1.0, 0.3], [1.0, 2.0, 0.6], [1.0, 3.0, 0.9], [1.0, 4.0, 1.2], "
                             "[0, 0, 0], [2.0, 1.0, 0.6], [2.0, 2.0, 1.2], [2.0, 3.0, 1.8], [2.0, 4.0, 2.4], "
                             "[0, 0, 0], [3.0, 1.0, 0.9], [3.0, 2.0, 1.8], [3.0, 3.0, 2.7], [3.0, 4.0, 3.6], "
                             "[0, 0, 0], [4.0, 1.0, 1.2], [4.0, 2.0, 2.4], [4.0, 3.0, 3.6], [4.0, 4.0, 4.8]], "
                             "\"weights\": [1.0, 1.0, 1.0, 1.0, 1.0, 1.5, 1.0, 1.0, 1.0, 1.0, 2.0, 1.0, 1.0, 1.0, 1.0, 2.5, 1.0, 1.0, 1.0, 1.0, 3.0, 1.0, 1.0, 1.0, 1.0], "
                             "\"knots_u\": [0, 1, 2, 3, 4, 5, 6, 7, 8], \"knots_v\": [0, 1, 2, 3, 4, 5, 6, 7, 8]}}, "
                             "\"b\": {\"edit\": \"a\", \"points\": [{\"pole\": \"south\", \"move\": [0, 0, %s]}]}}, "
                             "\"output\": [\"%s\"]}";
    char json[3][4096];
    const char *dz[3] = {"0", "0", "0.5"}, *out[3] = {"a", "b", "b"};
    rg2_design *d[3] = {NULL, NULL, NULL};
    rg2_error err;
    for (int k = 0; k < 3; k++) {
        snprintf(json[k], sizeof json[k], fmt, dz[k], out[k]);
        CHECK_OK(rg2_design_parse(json[k], strlen(json[k]), "pole-weights", &d[k], &err), &err);
    }
    if (!d[0] || !d[1] || !d[2])
        return;
    const rg2_surface *s0 = rg2_design_surface(d[0], 0), *s1 = rg2_design_surface(d[1], 0);
    size_t diff = 0;
    for (int p = 0; p < s0->nu * s0->nv && s0->nu == s1->nu && s0->nv == s1->nv; p++)
        diff += memcmp(&s0->patch[p], &s1->patch[p], sizeof s0->patch[p]) != 0;
    CHECK(s0->nu == s1->nu && s0->nv == s1->nv && diff == 0, "a zero pole move changed %zu of %d patches", diff,
          s0->nu * s0->nv);
    const rg2_mesh *m = rg2_design_mesh(d[2], 0);
    int bad = 0;
    for (int i = 0; i < m->nu; i++) {
        const double *p = rg2_mesh_at(m, i, 0);
        bad += p[3] != 1.0 + 0.5 * i || p[0] != 0.0 || p[1] != 0.0 || fabs(p[2] / p[3] - 0.5) > 1e-15;
    }
    CHECK(m->nu == 5 && bad == 0, "a pole moved by (0, 0, 0.5): %d of the row's points lost their weight or position",
          bad);
    for (int k = 0; k < 3; k++)
        rg2_design_free(d[k]);
}

/* Levenshtein distance by the full (la + 1) x (lb + 1) table: the test's own, for the rule of
 * rg2_closest_name (words up to 15 letters). */
static int edit_distance_table(const char *a, const char *b)
{
    int la = (int)strlen(a), lb = (int)strlen(b), D[16][16];
    for (int i = 0; i <= la; i++)
        for (int j = 0; j <= lb; j++)
            if (!i || !j)
                D[i][j] = i + j;
            else {
                int sub = D[i - 1][j - 1] + (a[i - 1] != b[j - 1]);
                int del = D[i - 1][j] + 1, ins = D[i][j - 1] + 1;
                D[i][j] = sub < del ? (sub < ins ? sub : ins) : (del < ins ? del : ins);
            }
    return D[la][lb];
}

/* rg2_closest_name: the parser's "did you mean" rule, shared with the command line */
static void closest_names(void)
{
    const char *const ops[] = {"shape", "cut", "merge", "transpose", "reverse", "edit"};
    CHECK(rg2_closest_name("merg", ops, 6) == ops[2], "merg -> %s", rg2_closest_name("merg", ops, 6));
    CHECK(rg2_closest_name("trnaspose", ops, 6) == ops[3], "trnaspose");
    CHECK(rg2_closest_name("xyz", ops, 6) == NULL, "xyz is close to nothing");
    CHECK(rg2_closest_name("cut", ops, 0) == NULL, "no names");
    /* the documented rule (rg2.h): the first name at the least edit distance if within
     * min(3, strlen(word) / 2 + 1) edits, else NULL; the distances computed here, the words chosen
     * to sit at the limit ("mrg": 2 of 2, "trnsps": 3 of 3, "dt": 2 of 2) and one past it */
    const char *const words[] = {"x", "ct", "dt", "mrg", "mrgee", "trnsps", "trnsp", "shp", "rvrs", "edt",
                                 "tansposer", "abcdef", "verse", "shapes", "reverse", "ab"};
    int at_limit = 0, past_limit = 0;
    for (size_t w = 0; w < sizeof words / sizeof words[0]; w++) {
        int best = -1, bd = 1 << 30, len = (int)strlen(words[w]);
        for (int k = 0; k < 6; k++) {
            int dd = edit_distance_table(words[w], ops[k]);
            if (dd < bd) {
                bd = dd;
                best = k;
            }
        }
        int lim = len / 2 + 1 < 3 ? len / 2 + 1 : 3;
        const char *want = bd <= lim ? ops[best] : NULL, *got = rg2_closest_name(words[w], ops, 6);
        at_limit += bd == lim;
        past_limit += bd == lim + 1;
        CHECK(got == want, "closest to '%s' (%d edits from '%s', limit %d): got %s, want %s", words[w], bd,
              ops[best], lim, got ? got : "NULL", want ? want : "NULL");
    }
    CHECK(at_limit >= 3 && past_limit >= 2, "%d words at the limit, %d one past it", at_limit, past_limit);
    /* random words and names of up to 15 letters over "abc": the same rule */
    rg2t_rng g;
    rg2t_seed(&g, 1162);
    int wrong = 0, found = 0;
    for (int t = 0; t < 3000; t++) {
        char w[16], nm[4][16];
        const char *names[4] = {nm[0], nm[1], nm[2], nm[3]};
        char *all[5] = {w, nm[0], nm[1], nm[2], nm[3]};
        for (int q = 0; q < 5; q++) {
            int len = rg2t_int(&g, 0, 15);
            for (int c = 0; c < len; c++)
                all[q][c] = (char)('a' + rg2t_int(&g, 0, 2));
            all[q][len] = 0;
        }
        int best = -1, bd = 1 << 30, len = (int)strlen(w);
        for (int k = 0; k < 4; k++) {
            int dd = edit_distance_table(w, names[k]);
            if (dd < bd)
                bd = dd, best = k;
        }
        int lim = len / 2 + 1 < 3 ? len / 2 + 1 : 3;
        const char *want = bd <= lim ? names[best] : NULL, *got = rg2_closest_name(w, names, 4);
        wrong += got != want;
        found += want != NULL;
    }
    CHECK(wrong == 0 && found > 300, "random words: %d of 3000 answered against the rule (%d with a name)", wrong, found);
    /* names of any length (a word or name past 63 bytes was never close to anything, not even to
     * itself), at the cost of its length: 200 000 letters */
    enum { LONG = 200000 };
    char *a = malloc(LONG + 1), *b = malloc(LONG + 1);
    if (!a || !b) {
        free(a);
        free(b);
        return;
    }
    for (int c = 0; c < LONG; c++)
        a[c] = b[c] = (char)('a' + c % 26);
    a[LONG] = b[LONG] = 0;
    const char *longs[2] = {"mesh", b};
    CHECK(rg2_closest_name(a, longs, 2) == b, "a 200000-letter word and the same name: %s", rg2_closest_name(a, longs, 2) ? "another" : "NULL");
    a[64] = 'X', a[100000] = 'Y';
    CHECK(rg2_closest_name(a, longs, 2) == b, "a 200000-letter word 2 edits from a name: not found");
    a[64] = 0;
    b[66] = 0; /* a 64-byte word, a 66-byte name that continues it */
    CHECK(rg2_closest_name(a, longs, 2) == b, "a 64-byte word 2 edits from a 66-byte name: not found");
    b[70] = 0, b[66] = 'x';
    CHECK(rg2_closest_name(a, longs, 2) == NULL, "a 64-byte word 6 edits from a 70-byte name: found");
    free(a);
    free(b);
}

static void bad_inputs(void)
{
    struct {
        const char *json;
        rg2_status code;
        const char *substr;
    } cases[] = {
        {"{\"shapes\": {}, \n  \"meshes\": {,}}", RG2_EPARSE, "test:2:15: malformed JSON near '}}'"},
        /* number literals that cJSON reads through strtod but JSON has not */
        {"{\"shapes\": {\"t\": {\"kind\": \"torus\", \"R\": 3, \"r\": 01}}, \"meshes\": {}}", RG2_EPARSE,
         "test:1:49: malformed JSON: number 01 has a leading zero"},
        {"{" TORUS_SHAPES ", \"meshes\": {\"T\": {\"shape\": \"t\", \"u\": {\"arcs\": [90, 90, 90, 90.]}}}}",
         RG2_EPARSE, "malformed JSON: number 90. has no digit on one side of its '.'"},
        {"{" TORUS_SHAPES ", \"meshes\": {\"T\": {\"shape\": \"t\", \"u\": {\"arcs\": 4}, \"v\": {\"from\": -.5}}}}",
         RG2_EPARSE, "malformed JSON: number -.5 has no digit on one side of its '.'"},
        {"{" TORUS_SHAPES ", \"meshes\": {\"T\": {\"shape\": \"t\", \"u\": {\"arcs\": 4}, \"v\": {\"from\": -00.5e1}}}}",
         RG2_EPARSE, "malformed JSON: number -00.5e1 has a leading zero"},
        {"{" TORUS_SHAPES ", \"meshes\": {\"T\": {\"shape\": \"t\", \"u\": {\"arcs\": 2.e0}}}}", RG2_EPARSE,
         "malformed JSON: number 2.e0 has no digit on one side of its '.'"},
        {"{\"shapes\": {\"t\": {\"kind\": \"torus\"}}", RG2_EPARSE, "malformed JSON"},
        {"{" TORUS_SHAPES ", \"meshes\": {" TORUS_MESH "}} x", RG2_EPARSE, "test:1:"},
        {"{" TORUS_SHAPES ", \"meshs\": {}}", RG2_EPARSE, "did you mean 'meshes'"},
        {"{\"shapes\": {\"t\": {\"kind\": \"tours\"}}, \"meshes\": {}}", RG2_EPARSE, "did you mean 'torus'"},
        {"{\"shapes\": {\"t\": {\"kind\": \"torus\", \"radius\": 2}}, \"meshes\": {}}", RG2_EPARSE,
         "unknown key 'radius'"},
        {"{\"shapes\": {\"t\": {\"kind\": \"torus\", \"R\": \"3\"}}, \"meshes\": {}}", RG2_EPARSE,
         "shapes.t.R: expected a number, found a string"},
        {"{\"shapes\": {\"t\": {\"kind\": \"torus\", \"R\": 1e999}}, \"meshes\": {}}", RG2_ENONFINITE,
         "shapes.t.R: number is not finite"},
        {"{\"shapes\": {\"t\": {\"R\": 3}}, \"meshes\": {}}", RG2_EPARSE, "shapes.t: missing key 'kind'"},
        {"{" TORUS_SHAPES "}", RG2_EPARSE, "missing key 'meshes'"},
        {"{" TORUS_SHAPES ", \"meshes\": {\"T\": {\"shape\": \"tt\"}}}", RG2_EPARSE, "did you mean 't'"},
        {"{" TORUS_SHAPES ", \"meshes\": {\"T\": {\"shape\": \"t\", \"u\": {\"arcs\": [90, 90, 200]}}}}", RG2_EDOMAIN,
         "meshes.T.u"},
        /* an arc or segment count past the 100,000 of the size limits is RG2_ELIMIT (README "Size
         * limits"), as a list of more than 100,000 values is; a count below 1 stays RG2_EDOMAIN */
        {"{" TORUS_SHAPES ", \"meshes\": {\"T\": {\"shape\": \"t\", \"u\": {\"arcs\": 100001}}}}", RG2_ELIMIT,
         "meshes.T.u.arcs: 100001 arcs; need 1 to 100000"},
        {"{\"shapes\": {\"c\": {\"kind\": \"cylinder\"}}, \"meshes\": {\"C\": {\"shape\": \"c\", \"v\": {\"segments\": 100001,"
         " \"from\": 0, \"to\": 1}}}}", RG2_ELIMIT, "meshes.C.v.segments: 100001 segments; need 1 to 100000"},
        {"{" TORUS_SHAPES ", \"meshes\": {\"T\": {\"shape\": \"t\", \"u\": {\"arcs\": 0}}}}", RG2_EDOMAIN,
         "meshes.T.u.arcs: 0 arcs; need 1 to 100000"},
        {"{" TORUS_SHAPES ", \"meshes\": {\"T\": {\"shape\": \"s\", \"v\": {\"arcs\": 4}}}}", RG2_EPARSE,
         "meshes.T.v: 'arcs' is for circle directions; v of a sphere is a polynomial (knot) direction"},
        {"{" TORUS_SHAPES ", \"meshes\": {\"N\": {\"nurbs\": {\"nu\": 4, \"nv\": 4, \"points\": [[0, 0, 0]],"
         " \"knots_u\": [0, 1, 2, 3, 4, 5, 6, 7], \"knots_v\": [0, 1, 2, 3, 4, 5, 6, 7]}}}}", RG2_EPARSE,
         "meshes.N.nurbs.points: expected nu * nv = 16 points"},
        {"{" TORUS_SHAPES ", \"meshes\": {\"N\": {\"nurbs\": {\"nu\": 3, \"nv\": 4}}}}", RG2_EINVAL,
         "meshes.N.nurbs.nu: 3 control points; a bi-cubic NURBS needs 4"},
        {"{" TORUS_SHAPES ", \"meshes\": {" TORUS_MESH ", \"C\": {\"cut\": \"T\", \"u\": [2, 40]}}}",
         RG2_EINVAL, "meshes.C.u: range [2, 40] is outside the 8 control points of mesh 'T' in u"},
        {"{" TORUS_SHAPES ", \"meshes\": {" TORUS_MESH ", \"C\": {\"cut\": \"T\", \"u\": [2, 4]}}}",
         RG2_EINVAL, "needs at least 4"},
        {"{" TORUS_SHAPES ", \"meshes\": {" TORUS_MESH ", \"C\": {\"cut\": \"X\", \"u\": [2, 4]}}}",
         RG2_EPARSE, "no mesh named 'X'"},
        {"{" TORUS_SHAPES ", \"meshes\": {" TORUS_MESH ", \"A\": {\"cut\": \"T\", \"u\": [0, 4]},"
         " \"S0\": {\"shape\": \"s\", \"u\": {\"arcs\": 5}}, \"S\": {\"transpose\": \"S0\"},"
         " \"M\": {\"merge\": [\"A\", \"S\"], \"along\": \"u\"}}}",
         RG2_EINCOMPATIBLE, "meshes.M.merge[1]: meshes 'A' and 'S' do not agree in v"},
        {"{" TORUS_SHAPES ", \"meshes\": {" TORUS_MESH ", \"A\": {\"cut\": \"T\", \"u\": [0, 4]},"
         " \"B\": {\"cut\": \"T\", \"u\": [4, 8]}, \"M\": {\"merge\": [\"A\", \"T\"], \"along\": \"u\"}}}",
         RG2_EINCOMPATIBLE, "meshes.M.merge[1]: mesh 'T' is closed in u"},
        {"{" TORUS_SHAPES ", \"meshes\": {" TORUS_MESH ", \"A\": {\"cut\": \"T\", \"u\": [0, 4]},"
         " \"M\": {\"merge\": [\"A\", \"A\"], \"along\": \"w\"}}}", RG2_EPARSE, "expected \"u\" or \"v\""},
        {"{" TORUS_SHAPES ", \"meshes\": {\"P\": {\"polar\": \"s\", \"u\": {\"arcs\": 8}, \"v\": {\"knots\": [0.2, 0.5, 0.8]}},"
         " \"C\": {\"shape\": \"s\", \"u\": {\"arcs\": 8}}, \"M\": {\"merge\": [\"P\", \"C\"], \"along\": \"v\"}}}",
         RG2_EINCOMPATIBLE, "meshes.M.merge[0]: mesh 'P' has a polar point at its last end (row v = 4"},
        /* a cut too short for an open direction names its exact count (singular and plural) */
        {"{" TORUS_SHAPES ", \"meshes\": {" TORUS_MESH ", \"A\": {\"cut\": \"T\", \"u\": [2, 2]}}}",
         RG2_EINVAL, "range [2, 2] keeps 1 control point; an open direction needs at least 4"},
        {"{" TORUS_SHAPES ", \"meshes\": {" TORUS_MESH ", \"A\": {\"cut\": \"T\", \"u\": [2, 4]}}}",
         RG2_EINVAL, "range [2, 4] keeps 3 control points; an open direction needs at least 4"},
        {"{" TORUS_SHAPES ", \"meshes\": {" TORUS_MESH ", \"E\": {\"edit\": \"T\", \"points\": [{\"at\": [8, 0], \"move\": [0, 0, 1]}]}}}",
         RG2_EINVAL, "meshes.E.points[0].at: control point [8, 0] is outside the 8 x 6"},
        {"{" TORUS_SHAPES ", \"meshes\": {" TORUS_MESH ", \"E\": {\"edit\": \"T\", \"points\": [{\"at\": [1, 1], \"W\": 0}]}}}",
         RG2_EWEIGHT, "meshes.E.points[0].W: weight W = 0, must be > 0"},
        {"{" TORUS_SHAPES ", \"meshes\": {" TORUS_MESH ", \"E\": {\"edit\": \"T\", \"points\": [{\"at\": [1, 1], \"move\": [0, 1e999, 0]}]}}}",
         RG2_ENONFINITE, "meshes.E.points[0].move[1]"},
        {"{" TORUS_SHAPES ", \"meshes\": {" TORUS_MESH ", \"E\": {\"edit\": \"T\", \"scalars\": [{\"dir\": \"u\", \"leg\": 2, \"w\": -1}]}}}",
         RG2_EWEIGHT, "meshes.E.scalars[0].w: leg weight w = -1, must be > 0"},
        {"{" TORUS_SHAPES ", \"meshes\": {" TORUS_MESH ", \"E\": {\"edit\": \"T\", \"scalars\": [{\"dir\": \"v\", \"junction\": 1, \"b\": 0}]}}}",
         RG2_EWEIGHT, "junction scalar b = 0"},
        {"{" TORUS_SHAPES ", \"meshes\": {" TORUS_MESH ", \"E\": {\"edit\": \"T\", \"scalars\": [{\"dir\": \"v\", \"junction\": 1, \"g\": -50}]}}}",
         RG2_EWEIGHT, "meshes.E.scalars[0]: v junction 1 has K"},
        {"{" TORUS_SHAPES ", \"meshes\": {" TORUS_MESH ", \"E\": {\"edit\": \"T\", \"scalars\": [{\"dir\": \"v\", \"junction\": 9, \"g\": 0}]}}}",
         RG2_EINVAL, "meshes.E.scalars[0].junction: v junction 9 is outside 0..5"},
        {"{" TORUS_SHAPES ", \"meshes\": {" TORUS_MESH ", \"E\": {\"edit\": \"T\", \"points\": [{\"at\": [1, 1], \"mvoe\": [0, 0, 1]}]}}}",
         RG2_EPARSE, "did you mean 'move'"},
        {"{" TORUS_SHAPES ", \"meshes\": {" TORUS_MESH ", \"S\": {\"shape\": \"s\"}, \"M\": {\"morph\": [\"T\", \"S\"], \"t\": 0.5}}}",
         RG2_EINCOMPATIBLE, "meshes.M.morph: meshes 'T' (8 control points, closed) and 'S'"},
        {"{" TORUS_SHAPES ", \"meshes\": {" TORUS_MESH ", \"M\": {\"morph\": [\"T\", \"T\"], \"t\": 1.5}}}",
         RG2_EDOMAIN, "meshes.M.t: t = 1.5"},
        {"{" TORUS_SHAPES ", \"meshes\": {" TORUS_MESH ", \"X\": {\"transform\": \"T\", \"rotate\": {\"axis\": [0, 0, 0], \"degrees\": 3}}}}",
         RG2_EDOMAIN, "meshes.X.rotate.axis: the rotation axis is the zero vector"},
        {"{" TORUS_SHAPES ", \"meshes\": {" TORUS_MESH ", \"X\": {\"transform\": \"T\", \"cut\": \"T\"}}}",
         RG2_EPARSE, "exactly one operation"},
        {"{" TORUS_SHAPES ", \"meshes\": {" TORUS_MESH "}, \"output\": \"Y\"}", RG2_EPARSE, "output: no mesh named 'Y'"},
        {"[1, 2]", RG2_EPARSE, "expected an object"},
        {"{" TORUS_SHAPES ", \"meshes\": {\"comment\": \"only a comment\"}}", RG2_EPARSE, "meshes: no meshes"},
        {"{" TORUS_SHAPES ", \"meshes\": {\"T\": {\"shape\": \"t\", \"u\": {\"arcs\": []}}}}", RG2_EPARSE,
         "meshes.T.u.arcs: expected at least one number"},
        {"{" TORUS_SHAPES ", \"meshes\": {\"T\": {\"shape\": \"t\", \"u\": {\"arcs\": [30, 30], \"to\": 90}}}}",
         RG2_EPARSE, "'to' goes with a number of arcs"},
        {"{" TORUS_SHAPES ", \"meshes\": {" TORUS_MESH ", \"R\": {\"reverse\": \"T\"}}}", RG2_EPARSE,
         "meshes.R: missing key 'dir'"},
        /* merges whose directions differ in kind or in one junction scalar name the first difference */
        {"{" TORUS_SHAPES ", \"meshes\": {" TORUS_MESH ", \"A\": {\"cut\": \"T\", \"u\": [0, 4]},"
         " \"B\": {\"cut\": \"T\", \"u\": [4, 8], \"v\": [0, 5]}, \"M\": {\"merge\": [\"A\", \"B\"], \"along\": \"u\"}}}",
         RG2_EINCOMPATIBLE, "meshes.M.merge[1]: meshes 'A' and 'B' do not agree in v (the direction that must match "
                            "when merging along u): closed vs open"},
        {"{\"shapes\": {\"c\": {\"kind\": \"cylinder\"}}, \"meshes\": {"
         "\"A\": {\"shape\": \"c\", \"u\": {\"arcs\": [60, 60, 60], \"from\": 0}, \"v\": {\"knots\": [0, 1, 2, 3, 4, 5]}},"
         " \"B\": {\"shape\": \"c\", \"u\": {\"arcs\": [60, 60, 60], \"from\": 180}, \"v\": {\"knots\": [0, 1, 2, 4, 5, 6]}},"
         " \"M\": {\"merge\": [\"A\", \"B\"], \"along\": \"u\"}}}",
         RG2_EINCOMPATIBLE, "do not agree in v (the direction that must match when merging along u): junction scalar "
                            "b[3] = 1 vs 2"},
        {"{\"shapes\": {\"c\": {\"kind\": \"cylinder\"}}, \"meshes\": {"
         "\"A\": {\"shape\": \"c\", \"u\": {\"arcs\": [60, 60, 60], \"from\": 0}, \"v\": {\"knots\": [0, 1, 2, 3, 4, 5]}},"
         " \"B0\": {\"shape\": \"c\", \"u\": {\"arcs\": [60, 60, 60], \"from\": 180}, \"v\": {\"knots\": [0, 1, 2, 3, 4, 5]}},"
         " \"B\": {\"edit\": \"B0\", \"scalars\": [{\"dir\": \"v\", \"junction\": 2, \"g\": 0.5}]},"
         " \"M\": {\"merge\": [\"A\", \"B\"], \"along\": \"u\"}}}",
         RG2_EINCOMPATIBLE, "do not agree in v (the direction that must match when merging along u): junction scalar "
                            "g[2] = 0 vs 0.5"},
        /* one zero factor of a scale vector is refused as all three are */
        {"{\"shapes\": {\"t\": {\"kind\": \"torus\", \"scale\": [0, 1, 1]}}, \"meshes\": {\"T\": {\"shape\": \"t\"}}}",
         RG2_EDOMAIN, "test: shapes.t.scale: scale factors must be non-zero"},
        {"{\"shapes\": {\"t\": {\"kind\": \"torus\", \"scale\": [1, 0, 1]}}, \"meshes\": {\"T\": {\"shape\": \"t\"}}}",
         RG2_EDOMAIN, "test: shapes.t.scale: scale factors must be non-zero"},
        {"{" TORUS_SHAPES ", \"meshes\": {" TORUS_MESH ", \"X\": {\"transform\": \"T\", \"scale\": [1, 1, 0]}}}",
         RG2_EDOMAIN, "test: meshes.X.scale: scale factors must be non-zero"},
        /* a transform's singular matrix is refused as a shape's is (it was taken, its flattened torus
         * tagged as exact on "t@meshes.X") */
        {"{" TORUS_SHAPES ", \"meshes\": {" TORUS_MESH ", \"X\": {\"transform\": \"T\", \"matrix\": [1, 0, 0, 0,"
         " 0, 1, 0, 0, 0, 0, 0, 0, 0, 0, 0, 1]}}}", RG2_EDOMAIN, "test: meshes.X.matrix: placement matrix is singular"},
        {"{\"shapes\": {\"t\": {\"kind\": \"torus\", \"matrix\": [1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 0, 0, 0, 0, 0, 1]}},"
         " \"meshes\": {\"T\": {\"shape\": \"t\"}}}", RG2_EDOMAIN, "test: shapes.t.matrix: placement matrix is singular"},
        /* exactly the 1,000,000 patches of the limit pass it (the design's range is what is refused
         * then), with "output" or without */
        {"{\"shapes\": {\"c\": {\"kind\": \"cylinder\", \"scale\": 1e61}}, \"meshes\": {\"C\": {\"shape\": \"c\","
         " \"u\": {\"arcs\": 1000}, \"v\": {\"segments\": 1000}}}, \"output\": \"C\"}", RG2_EDOMAIN,
         "test: meshes.C: coordinates up to"},
        {"{\"shapes\": {\"c\": {\"kind\": \"cylinder\", \"scale\": 1e61}}, \"meshes\": {\"C\": {\"shape\": \"c\","
         " \"u\": {\"arcs\": 1000}, \"v\": {\"segments\": 1000}}}}", RG2_EDOMAIN, "test: meshes.C: coordinates up to"},
        /* a count is an integer: 2.5 arcs is refused, not rounded */
        {"{" TORUS_SHAPES ", \"meshes\": {\"T\": {\"shape\": \"t\", \"u\": {\"arcs\": 2.5}}}}", RG2_EPARSE,
         "test: meshes.T.u.arcs: expected an integer, found 2.5"},
        /* poles 1e-9 apart on a sphere of radius 2 (5e-10 apart on the unit sphere, where
         * rg2_mobius_poles_matrix counts them as one point) are named as given, in world
         * coordinates, like coincident ones (were named by their unit-sphere image, (1, 0, 0)) */
        {"{\"shapes\": {\"s\": {\"kind\": \"sphere\", \"radius\": 2, \"translate\": [0, 0, 1]}}, \"meshes\": {"
         "\"P\": {\"polar\": \"s\", \"v\": {\"knots\": [0.2, 0.5]}}, \"M\": {\"mobius\": \"P\", \"sphere\": \"s\", "
         "\"poles\": {\"south\": [2, 0, 1], \"north\": [2, 1e-9, 1]}}}}",
         RG2_EDOMAIN, "test: meshes.M.poles: the south and north poles coincide at (2, 0, 1) on the reference sphere 's': "
                      "give two different points of it"},
        /* a polar configuration's v: missing, or not an object */
        {"{" TORUS_SHAPES ", \"meshes\": {\"P\": {\"polar\": \"s\", \"u\": {\"arcs\": 8}}}}", RG2_EPARSE,
         "test: meshes.P: missing key 'v'"},
        {"{" TORUS_SHAPES ", \"meshes\": {\"P\": {\"polar\": \"s\", \"u\": {\"arcs\": 8}, \"v\": [0.2, 0.8]}}}", RG2_EPARSE,
         "test: meshes.P.v: expected an object, found an array"},
    };
    for (size_t c = 0; c < sizeof cases / sizeof cases[0]; c++) {
        rg2_design *d = (rg2_design *)1;
        rg2_error err;
        memset(&err, 0, sizeof err);
        rg2_status st = rg2_design_parse(cases[c].json, strlen(cases[c].json), "test", &d, &err);
        CHECK(st == cases[c].code && d == NULL && strstr(err.msg, cases[c].substr),
              "bad case %zu: got %s '%s', expected %s with '%s'", c, rg2_status_str(st), err.msg,
              rg2_status_str(cases[c].code), cases[c].substr);
        if (st == RG2_OK)
            rg2_design_free(d);
    }
    printf("  %zu bad designs rejected with their messages, e.g. '%s'\n", sizeof cases / sizeof cases[0],
           "test:2:15: malformed JSON near '}}'");
    /* a polar configuration's v knows one key: an unknown one is named with exactly that list
     * (the whole message: a count past the list read beyond it) */
    {
        const char *json = "{" TORUS_SHAPES ", \"meshes\": {\"P\": {\"polar\": \"s\", \"u\": {\"arcs\": 8}, "
                           "\"v\": {\"knots\": [0.2, 0.8], \"arcs\": 4}}}}";
        rg2_design *dp = NULL;
        rg2_error e;
        rg2_status st = rg2_design_parse(json, strlen(json), "test", &dp, &e);
        CHECK(st == RG2_EPARSE && !dp && !strcmp(e.msg, "test: meshes.P.v: unknown key 'arcs'; known keys: knots"),
              "polar v with an unknown key: %s '%s'", rg2_status_str(st), e.msg);
        if (dp)
            rg2_design_free(dp);
    }
    rg2_design *d;
    rg2_error err;
    CHECK(rg2_design_load("tests/data/no-such-file.json", &d, &err) == RG2_EIO && d == NULL &&
              strstr(err.msg, "no-such-file.json"),
          "missing file: %s", err.msg);
}

/* A cap's seam positions v_c lie in [0, 1) (docs/design-format.md, docs/poles.md: v_c = 0 is
 * allowed): both ends of that range, 0 taken and 1 refused, and a negative one refused by name. */
/* A capped output's caps can be built again from the API: rg2_design_cap's options and
 * rg2_design_mesh's body give rg2_design_surface's patches bit for bit (Fig. 9's sphere, both
 * ends; Fig. 15's general quadratic caps of degree 4 or 5); its uncapped output reports 0. */
static void design_caps_again(void)
{
    const char *files[] = {"examples/fig9_polar_sphere.json", "examples/fig15_saddle_caps.json"};
    for (int f = 0; f < 2; f++) {
        rg2_design *d = NULL;
        rg2_error err;
        CHECK_OK(rg2_design_load(files[f], &d, &err), &err);
        int capped = 0, same = 0;
        for (int k = 0; k < rg2_design_num_surfaces(d); k++) {
            rg2_cap_opts o;
            if (!rg2_design_cap(d, k, &o))
                continue;
            capped++;
            const rg2_surface *a = rg2_design_surface(d, k);
            rg2_surface b;
            CHECK_OK(rg2_cap_build(rg2_design_mesh(d, k), &o, &b, NULL, &err), &err);
            int eq = a->nu == b.nu && a->nv == b.nv && !a->xp == !b.xp;
            size_t np = (size_t)a->nu * (size_t)a->nv;
            eq = eq && !memcmp(a->patch, b.patch, np * sizeof *a->patch);
            eq = eq && (!a->xp || !memcmp(a->xp, b.xp, np * sizeof *a->xp));
            same += eq;
            rg2_surface_free(&b);
        }
        int want = f ? 3 : 1;
        CHECK(capped == want && same == want && !rg2_design_cap(d, -1, NULL) &&
                  !rg2_design_cap(d, rg2_design_num_surfaces(d), NULL) && !rg2_design_cap(NULL, 0, NULL),
              "%s: %d capped outputs (want %d), %d built again bit for bit", files[f], capped, want, same);
        if (f == 0)
            CHECK(!rg2_design_cap(d, 0, NULL), "%s: output 0 (the band) is not capped", files[f]);
        rg2_design_free(d);
    }
}

static void cap_seam_positions(void)
{
    const char *fmt = "{\"shapes\": {\"c\": {\"kind\": \"cylinder\"}}, \"meshes\": {\"A\": {\"shape\": \"c\"},"
                      " \"C\": {\"cap\": \"A\", \"length\": [1, 1], \"vc\": [%s, %s]}}}";
    const char *vc[][2] = {{"0", "0"}, {"0", "0.5"}, {"-0.25", "0"}, {"0.5", "1"}};
    const char *want[] = {NULL, NULL, "test: meshes.C.vc[0]: south seam position v_c = -0.25, must lie in [0, 1)",
                          "test: meshes.C.vc[1]: north seam position v_c = 1, must lie in [0, 1)"};
    for (int c = 0; c < 4; c++) {
        char json[300];
        snprintf(json, sizeof json, fmt, vc[c][0], vc[c][1]);
        rg2_design *d = NULL;
        rg2_error err;
        memset(&err, 0, sizeof err);
        rg2_status st = rg2_design_parse(json, strlen(json), "test", &d, &err);
        if (!want[c])
            CHECK(st == RG2_OK && rg2_design_num_surfaces(d) == 1, "cap with v_c = [%s, %s]: %s '%s'", vc[c][0],
                  vc[c][1], rg2_status_str(st), err.msg);
        else
            CHECK(st == RG2_EDOMAIN && d == NULL && strstr(err.msg, want[c]), "cap with v_c = [%s, %s]: %s '%s'",
                  vc[c][0], vc[c][1], rg2_status_str(st), err.msg);
        rg2_design_free(d);
    }
}

/* An unknown key's message names it and lists every key its object takes, in order, and ends
 * there (docs/design-format.md "Errors": "...; known keys: merge, along, closed, seam"). */
static void unknown_key_lists(void)
{
    struct {
        const char *json, *msg;
    } cases[] = {
        {"{" TORUS_SHAPES ", \"meshes\": {\"T\": {\"shape\": \"t\", \"zzzzzz\": 8}}}",
         "test: meshes.T: unknown key 'zzzzzz'; known keys: shape, u, v"},
        {"{" TORUS_SHAPES ", \"meshes\": {" TORUS_MESH ", \"E\": {\"edit\": \"T\", \"scalars\": [{\"dir\": \"u\","
         " \"leg\": 2, \"w\": 2, \"zzzzzz\": 1}]}}}",
         "test: meshes.E.scalars[0]: unknown key 'zzzzzz'; known keys: dir, leg, junction, w, b, g"},
        /* a torus's v is an angle: 'radius' is only an unknown key; a sphere's v knots place its rings */
        {"{\"shapes\": {\"t\": {\"kind\": \"torus\", \"radius\": 2}}, \"meshes\": {\"T\": {\"shape\": \"t\"}}}",
         "test: shapes.t: unknown key 'radius'; known keys: kind, matrix, translate, rotate, scale, R, r"},
        {"{\"shapes\": {\"s\": {\"kind\": \"sphere\", \"height\": 2}}, \"meshes\": {\"T\": {\"shape\": \"s\"}}}",
         "test: shapes.s: unknown key 'height'; known keys: kind, matrix, translate, rotate, scale, radius: a sphere's "
         "extent is not a parameter but comes from its mesh's v partition, whose knots place the rings (knots in (0, 1), "
         "0 the south pole, 1 the north pole; in the mesh: \"v\": {\"from\": A, \"to\": B}; docs/shapes.md, \"Where a "
         "knot puts the ring\")"},
    };
    for (size_t c = 0; c < sizeof cases / sizeof cases[0]; c++) {
        rg2_design *d = (rg2_design *)1;
        rg2_error err;
        memset(&err, 0, sizeof err);
        rg2_status st = rg2_design_parse(cases[c].json, strlen(cases[c].json), "test", &d, &err);
        CHECK(st == RG2_EPARSE && d == NULL && !strcmp(err.msg, cases[c].msg), "unknown key %zu: got %s '%s', want '%s'",
              c, rg2_status_str(st), err.msg, cases[c].msg);
        if (st == RG2_OK)
            rg2_design_free(d);
    }
}

/* A transform's placement: scale, then rotate (by its degrees about its axis, of any length, by
 * the right-hand rule), then translate. Every control point of the transformed mesh against the
 * source's point mapped here. */
static void transform_placement(void)
{
    rg2_error err;
    rg2_design *d = parse("{" TORUS_SHAPES ", \"meshes\": {" TORUS_MESH ", \"X\": {\"transform\": \"T\", \"scale\": 2,"
                          " \"rotate\": {\"axis\": [0, 0, 3], \"degrees\": 30}, \"translate\": [1, -2, 0.5]}},"
                          " \"output\": [\"T\", \"X\"]}",
                          &err);
    if (!d)
        return;
    const rg2_mesh *a = rg2_design_mesh(d, 0), *b = rg2_design_mesh(d, 1);
    const double c = sqrt(3.0) / 2.0, s = 0.5; /* cos 30, sin 30 */
    double dev = 0.0;
    CHECK(a->nu == b->nu && a->nv == b->nv, "transform: %d x %d points from %d x %d", b->nu, b->nv, a->nu, a->nv);
    for (int i = 0; i < a->nu && a->nu == b->nu && a->nv == b->nv; i++)
        for (int j = 0; j < a->nv; j++) {
            const double *p = rg2_mesh_at(a, i, j), *q = rg2_mesh_at(b, i, j);
            double x = 2 * p[0] / p[3], y = 2 * p[1] / p[3], z = 2 * p[2] / p[3];
            double want[3] = {c * x - s * y + 1.0, s * x + c * y - 2.0, z + 0.5};
            for (int k = 0; k < 3; k++)
                dev = fmax(dev, fabs(q[k] / q[3] - want[k]));
        }
    CHECK(dev <= 1e-13, "transform (scale 2, 30 degrees about z, translate): points off by %.3g", dev);
    printf("  transform: scale, 30 degrees about z, translate: every point to %.1e\n", dev);
    rg2_design_free(d);
}

/* A transform copies each source the mesh uses, transformed, to keep its patches exact: only the
 * window of points the mesh refers to (it copied the whole source: a chain of transforms of a 6 x 6
 * cut of a 1000 x 1000 torus mesh took 32 MB a step, 1.3 GB for 40 steps). The cut wraps past the
 * end of the closed u direction, and a merge of two cuts of one source spans both. */
static void transform_windows(void)
{
    char json[4096];
    int n = snprintf(json, sizeof json,
                     "{\"shapes\": {\"t\": {\"kind\": \"torus\", \"R\": 3, \"r\": 1}},"
                     " \"meshes\": {\"big\": {\"shape\": \"t\", \"u\": {\"arcs\": 200}, \"v\": {\"arcs\": 100}},"
                     "  \"m0\": {\"cut\": \"big\", \"u\": [197, 202], \"v\": [10, 15]},"
                     "  \"a\": {\"cut\": \"big\", \"u\": [20, 26], \"v\": [40, 46]},"
                     "  \"b\": {\"cut\": \"big\", \"u\": [60, 66], \"v\": [40, 46]},"
                     "  \"ab\": {\"merge\": [\"a\", \"b\"], \"along\": \"u\"},"
                     "  \"ab1\": {\"transform\": \"ab\", \"rotate\": {\"axis\": [0, 0, 1], \"degrees\": 30}}");
    for (int k = 1; k <= 6; k++)
        n += snprintf(json + n, sizeof json - (size_t)n,
                      ", \"m%d\": {\"transform\": \"m%d\", \"translate\": [0.5, %d, 0], \"rotate\": {\"axis\": [1, 2, 3], "
                      "\"degrees\": %d}}",
                      k, k - 1, k, 10 * k);
    snprintf(json + n, sizeof json - (size_t)n, "}, \"output\": [\"m6\", \"ab1\", \"m0\", \"ab\"]}");
    rg2_error err;
    rg2_design *d = parse(json, &err);
    if (!d)
        return;
    /* the transformed meshes keep exact what their originals have exact: all of the cut, the merge
     * but for the 3 x 4 transitions of its seam */
    for (int o = 0; o < 2; o++) {
        const rg2_surface *s = rg2_design_surface(d, o), *t = rg2_design_surface(d, o + 2);
        int n_exact, n_orig;
        double res = exact_residual(d, s, 4, &n_exact);
        exact_residual(d, t, 4, &n_orig);
        int same = s->nu == t->nu && s->nv == t->nv;
        for (int k = 0; same && k < s->nu * s->nv; k++)
            same = (s->tag[k] < 0) == (t->tag[k] < 0);
        CHECK(same && n_exact == (o ? 32 : 9) && res <= 1e-13,
              "transformed %s: %d of %d patches exact (the original %d%s), residual %.3g", rg2_design_mesh_name(d, o),
              n_exact, s->nu * s->nv, n_orig, same ? "" : ", elsewhere", res);
    }
    /* source 0 is the torus mesh (all 200 x 100 points); ab1's copy stores the u range 20..66 of a
     * and b (47 x 7), m1..m6 each the 6 x 6 cut */
    CHECK(d->n_src == 8, "%d sources, expected 8", d->n_src);
    size_t stored = 0;
    for (int k = 1; k < d->n_src; k++)
        stored += (size_t)d->src[k].wu * (size_t)d->src[k].wv;
    CHECK(d->src[0].wu == 200 && d->src[0].wv == 100, "the torus source stores %d x %d points", d->src[0].wu,
          d->src[0].wv);
    CHECK(stored == 6 * 36 + 47 * 7, "the transformed sources store %zu points, expected %d", stored, 6 * 36 + 47 * 7);
    CHECK(d->src[1].i0 == 20 && d->src[1].wu == 47 && d->src[1].j0 == 40 && d->src[1].wv == 7,
          "the merge's window is %d x %d from (%d, %d)", d->src[1].wu, d->src[1].wv, d->src[1].i0, d->src[1].j0);
    CHECK(d->src[2].i0 == 197 && d->src[2].wu == 6 && d->src[2].j0 == 10 && d->src[2].wv == 6,
          "the wrapping cut's window is %d x %d from (%d, %d)", d->src[2].wu, d->src[2].wv, d->src[2].i0,
          d->src[2].j0);
    printf("  a chain of 6 transforms of a wrapping 6 x 6 cut of a 200 x 100 torus mesh and a transformed merge "
           "keep their patches exact; the copies store %zu points (the torus 20000)\n", stored);
    rg2_design_free(d);
}

/* Mesh names and shape labels are looked up by a hash index (a linear search made a design of
 * 64 000 meshes take 43 s to read): every name of a long chain resolves to its own mesh. */
static void many_names(void)
{
    enum { N = 3000 };
    size_t cap = 200 + (size_t)N * 80;
    char *json = malloc(cap);
    if (!json)
        return;
    size_t n = (size_t)snprintf(json, cap, "{\"shapes\": {\"t\": {\"kind\": \"torus\"}");
    for (int k = 0; k < N; k++)
        n += (size_t)snprintf(json + n, cap - n, ", \"s%d\": {\"kind\": \"sphere\"}", k);
    n += (size_t)snprintf(json + n, cap - n, "}, \"meshes\": {\"m0\": {\"shape\": \"t\"}");
    for (int k = 1; k < N; k++)
        n += (size_t)snprintf(json + n, cap - n, ", \"m%d\": {\"transpose\": \"m%d\"}", k, k - 1);
    snprintf(json + n, cap - n, "}, \"output\": [\"m%d\", \"m0\"]}", N - 1);
    rg2_error err;
    rg2_design *d = parse(json, &err);
    free(json);
    if (!d)
        return;
    int bad = 0;
    char name[32];
    for (int k = 0; k < N; k++) {
        snprintf(name, sizeof name, "m%d", k);
        bad += rg2__design_find_mesh(d, name) != k;
        snprintf(name, sizeof name, "s%d", k);
        bad += rg2__design_find_shape(d, name) != k + 1;
    }
    CHECK(bad == 0 && d->n_mesh == N && d->mesh_index.n == N && d->shape_index.n == N + 1 &&
              rg2__design_find_mesh(d, "m") < 0 && rg2__design_find_shape(d, "s") < 0,
          "%d names resolve wrongly (%d meshes, %zu indexed; %zu shapes indexed)", bad, d->n_mesh, d->mesh_index.n,
          d->shape_index.n);
    CHECK(d->mesh_points == (size_t)N * 48, "the meshes hold %zu points, expected %d", d->mesh_points, N * 48);
    const rg2_mesh *m = rg2_design_mesh(d, 0);
    CHECK(m->nu == 6 && m->nv == 8, "m%d (an odd number of transposes of 8 x 6) is %d x %d", N - 1, m->nu, m->nv);
    rg2_design_free(d);
}

/* A message longer than rg2_error.msg keeps its head and its tail (the reason), cut between
 * UTF-8 characters: a design path of 830 bytes (two-byte 'é's among them) that does not exist
 * lost "No such file or directory" before. */
static void long_messages(void)
{
    char path[900];
    size_t n = (size_t)snprintf(path, sizeof path, "/nonexistent-rg2-dir/");
    while (n < 826)
        n += (size_t)snprintf(path + n, sizeof path - n, n % 7 ? "d" : "\xc3\xa9");
    snprintf(path + n, sizeof path - n, ".json");
    rg2_design *d = NULL;
    rg2_error err;
    CHECK(rg2_design_load(path, &d, &err) == RG2_EIO && d == NULL, "missing design: %s", err.msg);
    size_t len = strlen(err.msg), tail = strlen(strerror(ENOENT));
    int utf8 = 1; /* every lead byte followed by its continuation bytes */
    for (size_t k = 0; k < len; k++) {
        unsigned char c = (unsigned char)err.msg[k];
        if (c >= 0xC0)
            utf8 &= k + 1 < len && ((unsigned char)err.msg[k + 1] & 0xC0) == 0x80;
        else if (c >= 0x80)
            utf8 &= k > 0 && (unsigned char)err.msg[k - 1] >= 0x80;
    }
    CHECK(len < sizeof err.msg && len > 400 && !strncmp(err.msg, path, 100) && strstr(err.msg, " [...] ") &&
              len > tail && !strcmp(err.msg + len - tail, strerror(ENOENT)) && utf8,
          "a %zu-byte path's message (%zu bytes, valid UTF-8 %d): %s", strlen(path), len, utf8, err.msg);
    printf("  a %zu-byte path: message of %zu bytes ending in \"%s\"\n", strlen(path), len, strerror(ENOENT));
    /* a prefix added to a message near the buffer's size keeps its end as well (the prefix was
     * made by shifting the message right, which cut the end) */
    memset(err.msg, 'x', 500);
    snprintf(err.msg + 500, sizeof err.msg - 500, " REASON");
    CHECK(rg2__prefix(&err, RG2_EINVAL, "mesh u") == RG2_EINVAL && err.code == RG2_EINVAL &&
              !strncmp(err.msg, "mesh u: xxx", 11) && strlen(err.msg) < sizeof err.msg &&
              !strcmp(err.msg + strlen(err.msg) - 7, " REASON"),
          "a prefixed 507-byte message: %s", err.msg);
}

/* Valid UTF-8: every lead byte followed by as many continuation bytes as it announces. */
static int utf8_valid(const char *s)
{
    const unsigned char *p = (const unsigned char *)s;
    while (*p) {
        int n = *p < 0x80 ? 0 : (*p & 0xE0) == 0xC0 ? 1 : (*p & 0xF0) == 0xE0 ? 2 : (*p & 0xF8) == 0xF0 ? 3 : -1;
        if (n < 0)
            return 0;
        for (p++; n > 0; n--, p++)
            if ((*p & 0xC0) != 0x80)
                return 0;
    }
    return 1;
}

/* Long UTF-8 names in a design's messages and labels (rg2.h: rg2_error.msg is UTF-8, a longer
 * message keeps its head and its end). The parser formatted its part of a message into 400 bytes
 * and its JSON paths into 300: a 600-byte label quoted in "no shape labelled ..." lost the end of
 * the message and, cut inside an 'ä', left half a character in it; a 600-byte mesh name cut the
 * path "meshes.<name>" inside one (for an odd number of ASCII bytes before the 'ä's). A transform's
 * copy of a shape is labelled "<label>@meshes.<name>", cut to 256 bytes: half a character again. */
static void long_utf8_names(void)
{
    for (int odd = 0; odd < 2; odd++) {
        char name[700];
        size_t o = 0;
        if (odd)
            name[o++] = 'a';
        for (int k = 0; k < 300; k++)
            o += (size_t)snprintf(name + o, sizeof name - o, "\xc3\xa4"); /* 'ä' */
        static char json[4096];
        rg2_design *d = NULL;
        rg2_error err;
        /* a shape label quoted whole: the message's end, "in \"shapes\"", is kept (4 edits from the
         * label: no suggestion) */
        snprintf(json, sizeof json,
                 "{\"shapes\": {\"%s\": {\"kind\": \"torus\"}}, \"meshes\": {\"m\": {\"shape\": \"wxyz%s\"}}}",
                 name, name);
        rg2_status st = rg2_design_parse(json, strlen(json), "t.json", &d, &err);
        size_t len = strlen(err.msg), tail = strlen("in \"shapes\"");
        CHECK(st == RG2_EPARSE && d == NULL && utf8_valid(err.msg) && len > tail &&
                  !strcmp(err.msg + len - tail, "in \"shapes\""),
              "unknown %zu-byte shape label (odd %d): %s, valid UTF-8 %d, message ends '%s'", strlen(name) + 4, odd,
              rg2_status_str(st), utf8_valid(err.msg), len > 40 ? err.msg + len - 40 : err.msg);
        /* one edit from the label: the suggestion names it, cut short between characters */
        snprintf(json, sizeof json,
                 "{\"shapes\": {\"%s\": {\"kind\": \"torus\"}}, \"meshes\": {\"m\": {\"shape\": \"%sx\"}}}",
                 name, name);
        st = rg2_design_parse(json, strlen(json), "t.json", &d, &err);
        len = strlen(err.msg);
        CHECK(st == RG2_EPARSE && d == NULL && utf8_valid(err.msg) && strstr(err.msg, "(did you mean '") && len > 6 &&
                  !strcmp(err.msg + len - 6, "...'?)"),
              "an unknown label one edit from a %zu-byte one (odd %d): %s, valid UTF-8 %d, message ends '%s'",
              strlen(name), odd, rg2_status_str(st), utf8_valid(err.msg), len > 40 ? err.msg + len - 40 : err.msg);
        /* a long mesh name in the path of a message */
        snprintf(json, sizeof json,
                 "{\"shapes\": {\"t\": {\"kind\": \"torus\"}}, \"meshes\": {\"%s\": {\"shape\": \"t\", "
                 "\"u\": {\"arcs\": 4, \"bogus\": 1}}}}",
                 name);
        st = rg2_design_parse(json, strlen(json), "t.json", &d, &err);
        CHECK(st == RG2_EPARSE && d == NULL && utf8_valid(err.msg) && strstr(err.msg, "bogus"),
              "unknown key under a long mesh name (odd %d): %s, valid UTF-8 %d: %s", odd, rg2_status_str(st),
              utf8_valid(err.msg), err.msg);
        /* a transformed copy's shape label, whole */
        snprintf(json, sizeof json,
                 "{\"shapes\": {\"%s\": {\"kind\": \"torus\"}}, \"meshes\": {\"m\": {\"shape\": \"%s\"}, "
                 "\"T%s\": {\"transform\": \"m\", \"translate\": [1, 0, 0]}}}",
                 name, name, name);
        st = rg2_design_parse(json, strlen(json), "t.json", &d, &err);
        CHECK(st == RG2_OK && rg2_design_num_shapes(d) == 2, "transform of a long-labelled shape: %s: %s",
              rg2_status_str(st), err.msg);
        if (st == RG2_OK && rg2_design_num_shapes(d) == 2) {
            /* (the label's path part is the operation's path, cut to 300 bytes as every path) */
            const char *l = rg2_design_shape_label(d, 1);
            char want[1500];
            snprintf(want, sizeof want, "%s@meshes.T", name);
            CHECK(!strncmp(l, want, strlen(want)) && strlen(l) > 800 && utf8_valid(l),
                  "the transformed copy's label (%zu bytes, starting with the %zu of '<label>@meshes.T'; valid UTF-8 %d)",
                  strlen(l), strlen(want), utf8_valid(l));
        }
        rg2_design_free(d);
    }
}

/* A NULL design (or path) as the header's conventions take it: rg2_design_write_mesh(NULL, ...)
 * dereferenced it (a segfault) and a NULL path went to strlen, where rg2_design_load refuses a
 * NULL path with RG2_EINVAL and the accessors give 0 / NULL / -1 for a NULL design. */
/* rg2_mesh_check_range measures design points p_{1..3} / p_4 (rg2.h): a 4 x 4 mesh of points within
 * 3 of the origin, one of them given as (x, 0, 0, 0.01) with x / w = +-1e61 (past the supported 1e60,
 * while x w is +-1e57) or 1e59 (inside): refused naming the coordinate x / w, or taken. */
static void mesh_check_range_weights(void)
{
    const double xs[3] = {1e59, -1e59, 1e57}, w = 0.01;
    for (int t = 0; t < 3; t++) {
        rg2_mesh m;
        rg2_error err;
        CHECK_OK(rg2_mesh_init(&m, 4, 4, 0, 0, &err), &err);
        for (int i = 0; i < 4; i++)
            for (int j = 0; j < 4; j++) {
                double *p = rg2_mesh_at(&m, i, j);
                p[0] = i, p[1] = j, p[2] = 0.0, p[3] = 1.0;
            }
        double *q = rg2_mesh_at(&m, 2, 1);
        q[0] = xs[t], q[1] = q[2] = 0.0, q[3] = w;
        double affine = xs[t] / w;
        char want[96];
        snprintf(want, sizeof want, "weighted: coordinates up to %g, size ", fabs(affine));
        rg2_status st = rg2_mesh_check_range(&m, "weighted", &err);
        if (fabs(affine) > 1e60)
            CHECK(st == RG2_EDOMAIN && !strncmp(err.msg, want, strlen(want)), "x / w = %g: %s %s", affine,
                  rg2_status_str(st), err.msg);
        else
            CHECK(st == RG2_OK, "x / w = %g refused: %s", affine, err.msg);
        rg2_mesh_free(&m);
    }
    /* a mesh whose every weight is 0 (rg2_mesh_init's) has no design points: said so (it was
     * "coordinates up to inf, size inf") */
    rg2_mesh z;
    rg2_error err;
    CHECK_OK(rg2_mesh_init(&z, 4, 5, 0, 0, &err), &err);
    rg2_status st = rg2_mesh_check_range(&z, "zero", &err);
    CHECK(st == RG2_EDOMAIN && strstr(err.msg, "zero: none of the 4 x 5 control points has a weight") &&
              !strstr(err.msg, "up to inf"),
          "an all-zero mesh: %s: %s", rg2_status_str(st), err.msg);
    rg2_mesh_free(&z);
}

static void null_designs(void)
{
    rg2_error err;
    CHECK(rg2_design_write_mesh(NULL, "unused.json", &err) == RG2_EINVAL &&
              !strcmp(err.msg, "design: no design to write (NULL design)"),
          "write_mesh(NULL design): %s", err.msg);
    CHECK(rg2_design_write_mesh(NULL, NULL, NULL) == RG2_EINVAL, "write_mesh(NULL, NULL, NULL)");
    CHECK(rg2_design_num_surfaces(NULL) == 0 && rg2_design_num_shapes(NULL) == 0 && !rg2_design_surface(NULL, 0) &&
              !rg2_design_mesh(NULL, 0) && !rg2_design_mesh_name(NULL, 0) && !rg2_design_shape(NULL, 0) &&
              !rg2_design_shape_label(NULL, 0) && rg2_design_point_shape(NULL, 0, 0, 0) == -1,
          "the accessors of a NULL design");
    rg2_design_free(NULL);
    rg2_design *d = parse("{" TORUS_SHAPES ", \"meshes\": {" TORUS_MESH "}, \"output\": [\"T\"]}", &err);
    if (!d)
        return;
    CHECK(rg2_design_write_mesh(d, NULL, &err) == RG2_EINVAL && !strcmp(err.msg, "test: no output path (NULL path)"),
          "write_mesh(NULL path): %s", err.msg);
    CHECK(rg2_design_write_mesh(d, "", &err) == RG2_EINVAL && !strcmp(err.msg, "test: no output path (empty path)"),
          "write_mesh(empty path): %s", err.msg);
    rg2_design_free(d);
}

/* A merge whose closed rows meet turned about their axis or running opposite ways round builds (it
 * is G2) but twists or pinches the tube: the design says so in a note naming the merge entry, both
 * meshes and the angle; aligned circles give none. Two cylinders stacked along v; the upper one's
 * circle starts at `from` degrees, or runs backwards. */
static void twisted_merges(void)
{
    static const char base[] =
        "{\"shapes\": {\"c\": {\"kind\": \"cylinder\"}}, \"meshes\": {"
        "\"A\": {\"shape\": \"c\", \"u\": {\"arcs\": 8}, \"v\": {\"segments\": 3, \"from\": 0, \"to\": 1}},"
        "\"B0\": {\"shape\": \"c\", \"u\": {\"arcs\": 8, \"from\": %s}, \"v\": {\"segments\": 3, \"from\": 2, "
        "\"to\": 3}},"
        "\"B\": %s, \"M\": {\"merge\": [\"A\", \"B\"], \"along\": \"v\"}}}";
    static const struct {
        const char *from, *b, *note;
    } cases[] = {
        {"0", "{\"cut\": \"B0\", \"v\": [0, 5]}", NULL},
        {"0.5", "{\"cut\": \"B0\", \"v\": [0, 5]}", NULL},
        {"45", "{\"cut\": \"B0\", \"v\": [0, 5]}",
         "test: meshes.M.merge[1]: the closed u rows of 'A' and 'B' meet turned by 45 degrees about their axis ('B' "
         "starts 45 degrees further along u)"},
        {"-22.5", "{\"cut\": \"B0\", \"v\": [0, 5]}",
         "test: meshes.M.merge[1]: the closed u rows of 'A' and 'B' meet turned by 22.5 degrees about their axis ('B' "
         "starts 22.5 degrees back along u)"},
        {"0", "{\"reverse\": \"B0\", \"dir\": \"u\"}",
         "test: meshes.M.merge[1]: the closed u rows of 'A' and 'B' run opposite ways round at their seam"},
    };
    for (size_t k = 0; k < sizeof cases / sizeof cases[0]; k++) {
        rg2_error err;
        rg2_design *d = parse_edit2(base, cases[k].from, cases[k].b, &err);
        if (!d)
            continue;
        const char *note = rg2_design_note(d, 0);
        if (cases[k].note)
            CHECK(rg2_design_num_notes(d) == 1 && note && !strncmp(note, cases[k].note, strlen(cases[k].note)),
                  "from %s, %s: %d notes, first '%s'", cases[k].from, cases[k].b, rg2_design_num_notes(d),
                  note ? note : "(none)");
        else
            CHECK(rg2_design_num_notes(d) == 0 && !note, "from %s: aligned circles give no note, got '%s'",
                  cases[k].from, note ? note : "(none)");
        CHECK(!rg2_design_note(d, -1) && !rg2_design_note(d, rg2_design_num_notes(d)), "note index out of range");
        rg2_design_free(d);
    }
    CHECK(rg2_design_num_notes(NULL) == 0 && !rg2_design_note(NULL, 0), "the notes of a NULL design");
}

/* The largest step back of the centres c[j] of mesh m's lines along v: over every step
 * s = c[j+1] - c[j] that runs against both the step before it (a) and the one after it (b),
 * the larger of -s.a / |a|^2 and -s.b / |b|^2, in units of the step it runs against; computed
 * here from the merged mesh, not from its parts as the library's note is. */
static double most_back(const rg2_mesh *m)
{
    double c[64][3] = {{0}};
    int nl = m->nv < 64 ? m->nv : 64;
    for (int j = 0; j < nl; j++)
        for (int i = 0; i < m->nu; i++) {
            const double *p = rg2_mesh_at(m, i, j);
            for (int k = 0; k < 3; k++)
                c[j][k] += p[k] / p[3] / m->nu;
        }
    double most = 0.0;
    for (int j = 1; j + 2 < nl; j++) {
        double a[3], s[3], b[3];
        for (int k = 0; k < 3; k++)
            a[k] = c[j][k] - c[j - 1][k], s[k] = c[j + 1][k] - c[j][k], b[k] = c[j + 2][k] - c[j + 1][k];
        double aa = a[0] * a[0] + a[1] * a[1] + a[2] * a[2], bb = b[0] * b[0] + b[1] * b[1] + b[2] * b[2];
        double ba = -(s[0] * a[0] + s[1] * a[1] + s[2] * a[2]) / aa, bs = -(s[0] * b[0] + s[1] * b[1] + s[2] * b[2]) / bb;
        if (ba > 0.0 && bs > 0.0) /* a step against both its neighbours: the one back */
            most = fmax(most, fmax(ba, bs));
    }
    return most;
}

/* The nesting message counts brackets only: a text with trailing junk '[' after 1200 blanks (at
 * depth 0) is malformed JSON at that bracket, not nested past cJSON's depth; a string of 1200
 * '[' is text. */
static void nesting_counts_brackets(void)
{
    char js[3000];
    int n = snprintf(js, sizeof js, "{\"description\": \"");
    for (int k = 0; k < 1200; k++)
        js[n++] = '[';
    n += snprintf(js + n, sizeof js - (size_t)n, "\", " TORUS_SHAPES ", \"meshes\": {" TORUS_MESH "}}");
    for (int k = 0; k < 1200; k++)
        js[n++] = ' ';
    js[n++] = '[';
    js[n] = 0;
    rg2_design *d = NULL;
    rg2_error err;
    rg2_status st = rg2_design_parse(js, strlen(js), "test", &d, &err);
    char want[80];
    snprintf(want, sizeof want, "test:1:%d: malformed JSON near '['", n);
    CHECK(st == RG2_EPARSE && !d && strstr(err.msg, want), "junk '[' after 1200 blanks: %s '%s' (want '%s')",
          rg2_status_str(st), err.msg, want);
    rg2_design_free(d);
}

/* Design text with `lit` as the y of a torus's translate, written compactly ([0,lit,0]: the
 * number before it ends at the comma) after a description `desc` (JSON string contents); the
 * status, the message in err, and lit's column (line 1) in *col. */
static rg2_status tiny_case(const char *desc, const char *lit, rg2_error *err, int *col)
{
    char js[600];
    snprintf(js, sizeof js,
             "{\"description\":\"%s\",\"shapes\":{\"t\":{\"kind\":\"torus\",\"R\":3,\"r\":1,\"translate\":[0,%s,0]}},"
             "\"meshes\":{\"T\":{\"shape\":\"t\"}}}",
             desc, lit);
    *col = (int)(strstr(js, "[0,") - js) + 4;
    rg2_design *d = NULL;
    rg2_status st = rg2_design_parse(js, strlen(js), "test", &d, err);
    rg2_design_free(d);
    return st;
}

/* A number literal with a non-zero digit but an order below 1e-323 is refused by name, line and
 * column (cJSON would read 0 or a subnormal); zero with any exponent is 0, and 1e-323 up to
 * 1e-100 reach the numeric range check instead. The order counts leading zeros, a fraction and
 * an exponent with a sign or leading zeros; a literal over 40 characters is shown cut to 40 and
 * "...". Strings are skipped, escapes included. */
static void tiny_literals(void)
{
    enum { OK, TINY, RANGE };
    static const struct {
        const char *lit;
        int want;
    } cases[] = {
        {"1e-400", TINY},      {"-1e-400", TINY},     {"1E-400", TINY},         {"9e-324", TINY},
        {"1e-324", TINY},      {"4.9e-324", TINY},    {"0.0001e-320", TINY},    {"0.01e-322", TINY},
        {"100e-326", TINY},    {"1e-00400", TINY},    {"1e-99999999999", TINY}, {"0.5e-323", TINY},
        {"0e-400", OK},        {"0.0e-400", OK},      {"-0.000e-999", OK},      {"0", OK},
        {"1e-5", OK},          {"2.5E+1", OK},        {"1e-323", RANGE},        {"1e-320", RANGE},
        {"11e-324", RANGE},    {"0.11e-322", RANGE},  {"1000e-326", RANGE},     {"0.001e-320", RANGE},
        {"1e-200", RANGE},
    };
    for (size_t c = 0; c < sizeof cases / sizeof cases[0]; c++) {
        rg2_error err;
        int col;
        rg2_status st = tiny_case("a", cases[c].lit, &err, &col);
        char want[160];
        snprintf(want, sizeof want, "test:1:%d: number %s is too small for a double (below 1e-323)", col,
                 cases[c].lit);
        int ok = cases[c].want == OK     ? st == RG2_OK
                 : cases[c].want == TINY ? st == RG2_EDOMAIN && strstr(err.msg, want) != NULL
                                         : st == RG2_EDOMAIN && !strstr(err.msg, "too small for a double") &&
                                               strstr(err.msg, "is outside the supported range");
        CHECK(ok, "literal %s (want %s): %s '%s'", cases[c].lit,
              cases[c].want == OK ? "accepted" : cases[c].want == TINY ? "too small" : "out of range",
              rg2_status_str(st), st ? err.msg : "");
    }
    /* 40 characters shown whole, 41 cut to 40 and "..." */
    for (int z = 32; z <= 33; z++) {
        char lit[64], shown[64], want[200];
        snprintf(lit, sizeof lit, "0.%0*d1e-300", z, 0);
        snprintf(shown, sizeof shown, "%.40s%s", lit, strlen(lit) > 40 ? "..." : "");
        rg2_error err;
        int col;
        rg2_status st = tiny_case("a", lit, &err, &col);
        snprintf(want, sizeof want, "test:1:%d: number %s is too small", col, shown);
        CHECK(st == RG2_EDOMAIN && strstr(err.msg, want), "literal of %zu characters: want '%s', got '%s'",
              strlen(lit), want, err.msg);
    }
    /* an escaped quote keeps the string open (its digits are text); an escaped backslash ends
     * with the string's quote, and the number after it is read */
    rg2_error err;
    int col;
    rg2_status st = tiny_case("x\\\"0,1e-400", "1", &err, &col);
    CHECK(st == RG2_OK, "1e-400 inside a string with an escaped quote: %s '%s'", rg2_status_str(st),
          st ? err.msg : "");
    st = tiny_case("x\\\\", "1e-400", &err, &col);
    char want[120];
    snprintf(want, sizeof want, "test:1:%d: number 1e-400 is too small", col);
    CHECK(st == RG2_EDOMAIN && strstr(err.msg, want), "1e-400 after a string ending in an escaped backslash: %s",
          err.msg);
    printf("tiny literals: %zu literals, two lengths and two strings\n", sizeof cases / sizeof cases[0]);
}

/* A merge next to a control weight <= 0 (a hyperboloid's data-only end rows mirrored past v = 0)
 * gets one note naming the part, the control point and its weight, which the merged mesh holds
 * there and which leaves the built surface with weights <= 0; the twist and overlap notes, which
 * measure the design points p / w (on the far side there), are not given for that seam. With the
 * knots moved away from 0 the weights stay positive and no such note comes. */
static void weight_notes(void)
{
    static const char base[] =
        "{\"shapes\": {\"c\": {\"kind\": \"cylinder\", \"radius\": 1.0089, \"translate\": [0, 0, 3]},"
        "\"h\": {\"kind\": \"hyperboloid1\"}}, \"meshes\": {"
        "\"C\": {\"shape\": \"c\", \"u\": {\"arcs\": 6}, \"v\": {\"segments\": 2, \"from\": 0, \"to\": 1}},"
        "\"H\": {\"shape\": \"h\", \"u\": {\"arcs\": 6}, \"v\": {\"knots\": [%s, %s, 0.9]}},"
        "\"M\": {\"merge\": [\"C\", \"H\"], \"along\": \"v\"}}, \"output\": \"M\"}";
    rg2_error err;
    rg2_design *d = parse_edit2(base, "0.1", "0.5", &err); /* (data-only knots -0.3, -0.7) */
    CHECK(d != NULL, "the design with knots 0.1, 0.5, 0.9 parses: %s", err.msg);
    if (d) {
        const char *note = rg2_design_note(d, 0), *at = note ? strstr(note, "'H' has weight ") : NULL;
        double w = 1.0;
        int idx = -1, line = -1;
        int got = at && sscanf(at, "'H' has weight %lf <= 0 at control point %d of its u line %d", &w, &idx, &line) == 3;
        const rg2_mesh *M = rg2_design_mesh(d, 0);
        /* H's 2 knot intervals give 5 control points along v, the last 5 of the merge's */
        int j = M ? M->nv - 5 + line : -1;
        CHECK(rg2_design_num_notes(d) == 1 && got && strstr(note, "test: meshes.M.merge[1]: ") &&
                  strstr(note, "next to its seam with 'C'"),
              "one weight note, got %d: '%s'", rg2_design_num_notes(d), note ? note : "(none)");
        CHECK(got && M && idx >= 0 && idx < M->nu && j >= 0 && j < M->nv && w <= 0 && rg2_mesh_at(M, idx, j)[3] == w,
              "the note's weight %g at (%d, %d) is the merged mesh's (%g)", w, idx, j,
              got && M && idx >= 0 && idx < M->nu && j >= 0 && j < M->nv ? rg2_mesh_at(M, idx, j)[3] : NAN);
        CHECK(rg2_surface_min_weight(rg2_design_surface(d, 0)) <= 0, "the built surface has weights <= 0 (%g)",
              rg2_surface_min_weight(rg2_design_surface(d, 0)));
        rg2_design_free(d);
    }
    d = parse_edit2(base, "0.7", "0.8", &err); /* (data-only knots 0.6, 0.5) */
    CHECK(d != NULL, "the design with knots 0.7, 0.8, 0.9 parses: %s", err.msg);
    if (d) {
        for (int k = 0; k < rg2_design_num_notes(d); k++)
            CHECK(!strstr(rg2_design_note(d, k), "<= 0 at control point"), "no weight note, got '%s'",
                  rg2_design_note(d, k));
        CHECK(rg2_surface_min_weight(rg2_design_surface(d, 0)) > 0, "weights > 0 (%g)",
              rg2_surface_min_weight(rg2_design_surface(d, 0)));
        rg2_design_free(d);
    }
}

/* The weight note's part, line and threshold: a hyperboloid2 merged before a cylinder (knots 0,
 * 0.3, 0.7: its data-only end knots 1.1 and 1.4 lie past |v| = 1) has weights <= 0 on its last
 * v line only, next to the seam, and the note names that part ('H', merge[1]), that line (4 of
 * its 5) and the merged mesh's weight there; a hyperboloid1 whose first control line lies at v =
 * 0.002 (knots 0.3, 0.594, 0.9: weights 0.0035 to 0.004 there, positive) gets no weight note. */
/* An output surface with a patch weight <= 0 (a cyclide close to a horn over 3 x 3 arcs,
 * docs/shapes.md "Homogeneous weights") builds, but STEP and IGES refuse it: the design carries
 * a note naming the mesh, the count, the smallest weight and its patch, which are the built
 * surface's (rg2_surface_weight_report; the weight to the note's 6 digits); the same over 4 x 4
 * arcs gets none (over 4 x 3, -9.5e-17 at patch (2, 1): a weight that vanishes), and a mesh made
 * from the coarse one (a transform) carries it under its own name. */
static void surface_weight_notes(void)
{
    static const char base[] = "{\"shapes\": {\"c\": {\"kind\": \"cyclide\", \"a\": 1, \"c\": 0.8, \"mu\": 0.97}},"
                               " \"meshes\": {\"C\": {\"shape\": \"c\", \"u\": {\"arcs\": %s}, \"v\": {\"arcs\": %s}},"
                               " \"T\": {\"transform\": \"C\", \"translate\": [1, 2, 3]}}, \"output\": [\"C\", \"T\"]}";
    rg2_error err;
    rg2_design *d = parse_edit2(base, "3", "3", &err);
    CHECK(d != NULL, "the 3 x 3 arc cyclide parses: %s", err.msg);
    for (int o = 0; d && o < 2; o++) {
        const rg2_surface *s = rg2_design_surface(d, o);
        rg2_weight_report rep;
        rg2_surface_weight_report(s, &rep);
        char head[64];
        snprintf(head, sizeof head, "test: meshes.%s: ", o ? "T" : "C");
        const char *note = NULL;
        for (int k = 0; k < rg2_design_num_notes(d); k++)
            if (!strncmp(rg2_design_note(d, k), head, strlen(head)) && strstr(rg2_design_note(d, k), "weight <= 0"))
                note = rg2_design_note(d, k);
        int n = -1, tot = -1, i = -1, j = -1;
        double w = 1.0;
        int got = note && sscanf(note + strlen(head),
                                 "%d of its %d patches %*s a homogeneous weight <= 0 (the smallest %lf, at patch (%d, %d))",
                                 &n, &tot, &w, &i, &j) == 5;
        CHECK(got && strstr(note, "STEP and IGES export refuse it") && strstr(note, "use more arcs or knots"),
              "%s: a weight note naming the refusal and the remedy, got '%s'", head, note ? note : "(none)");
        CHECK(got && n == rep.n_nonpositive && n >= 1 && tot == s->nu * s->nv && i == rep.patch_i && j == rep.patch_j &&
                  fabs(w - rep.min_weight) <= 1e-5 * fabs(rep.min_weight) && w <= 0,
              "%s: the note's %d of %d, %g at (%d, %d) are the surface's %d of %d, %g at (%d, %d)", head, n, tot, w, i, j,
              rep.n_nonpositive, s->nu * s->nv, rep.min_weight, rep.patch_i, rep.patch_j);
    }
    rg2_design_free(d);
    d = parse_edit2(base, "4", "4", &err);
    CHECK(d != NULL, "the 4 x 4 arc cyclide parses: %s", err.msg);
    for (int k = 0; d && k < rg2_design_num_notes(d); k++)
        CHECK(!strstr(rg2_design_note(d, k), "homogeneous weight <= 0"), "4 x 4 arcs: no weight note, got '%s'",
              rg2_design_note(d, k));
    CHECK(d && rg2_surface_min_weight(rg2_design_surface(d, 0)) > 0, "4 x 4 arcs: weights > 0 (%g)",
          d ? rg2_surface_min_weight(rg2_design_surface(d, 0)) : NAN);
    rg2_design_free(d);
}

static void weight_notes_ends(void)
{
    static const char first[] =
        "{\"shapes\": {\"c\": {\"kind\": \"cylinder\", \"radius\": 1.0089, \"translate\": [0, 0, -3]},"
        "\"h\": {\"kind\": \"hyperboloid2\"}}, \"meshes\": {"
        "\"H\": {\"shape\": \"h\", \"u\": {\"arcs\": 6}, \"v\": {\"knots\": [0, 0.3, 0.7]}},"
        "\"C\": {\"shape\": \"c\", \"u\": {\"arcs\": 6}, \"v\": {\"segments\": 2, \"from\": 0, \"to\": 1}},"
        "\"M\": {\"merge\": [\"H\", \"C\"], \"along\": \"v\"}}, \"output\": \"M\"}";
    rg2_error err;
    rg2_design *d = parse(first, &err);
    if (d) {
        const rg2_mesh *M = rg2_design_mesh(d, 0);
        const char *note = NULL;
        for (int k = 0; k < rg2_design_num_notes(d); k++)
            if (strstr(rg2_design_note(d, k), "<= 0 at control point"))
                note = rg2_design_note(d, k);
        const char *at = note ? strstr(note, "'H' has weight ") : NULL;
        double w = 1.0;
        int idx = -1, line = -1;
        int got = at && sscanf(at, "'H' has weight %lf <= 0 at control point %d of its u line %d", &w, &idx, &line) == 3;
        /* H's lines are the merge's first 5; line 3 (v about 0.7) is positive, line 4 is not */
        int lines_ok = M && M->nv > 5 && rg2_mesh_at(M, 0, 3)[3] > 0 && !(rg2_mesh_at(M, 0, 4)[3] > 0);
        CHECK(lines_ok && got && strstr(note, "test: meshes.M.merge[1]: ") && strstr(note, "next to its seam with 'C'") &&
                  idx == 0 && line == 4 && w <= 0 && fabs(rg2_mesh_at(M, idx, line)[3] - w) <= 1e-4 * fabs(w),
              "hyperboloid2 before a cylinder: lines 3, 4 weights %g, %g; note '%s'", M ? rg2_mesh_at(M, 0, 3)[3] : NAN,
              M ? rg2_mesh_at(M, 0, 4)[3] : NAN, note ? note : "(none)");
        rg2_design_free(d);
    }
    static const char small[] =
        "{\"shapes\": {\"c\": {\"kind\": \"cylinder\", \"radius\": 1.0089, \"translate\": [0, 0, 3]},"
        "\"h\": {\"kind\": \"hyperboloid1\"}}, \"meshes\": {"
        "\"C\": {\"shape\": \"c\", \"u\": {\"arcs\": 6}, \"v\": {\"segments\": 2, \"from\": 0, \"to\": 1}},"
        "\"H\": {\"shape\": \"h\", \"u\": {\"arcs\": 6}, \"v\": {\"knots\": [0.3, 0.594, 0.9]}},"
        "\"M\": {\"merge\": [\"C\", \"H\"], \"along\": \"v\"}}, \"output\": \"M\"}";
    d = parse(small, &err);
    if (d) {
        const rg2_mesh *M = rg2_design_mesh(d, 0);
        double lo = INFINITY, hi = -INFINITY;
        for (int i = 0; M && i < M->nu; i++) {
            double w = rg2_mesh_at(M, i, M->nv - 5)[3];
            lo = fmin(lo, w), hi = fmax(hi, w);
        }
        CHECK(lo > 0 && hi < 0.01, "hyperboloid1's first line at v = 0.002: weights %g to %g", lo, hi);
        for (int k = 0; k < rg2_design_num_notes(d); k++)
            CHECK(!strstr(rg2_design_note(d, k), "<= 0 at control point"), "weights %g to %g: a weight note '%s'", lo,
                  hi, rg2_design_note(d, k));
        rg2_design_free(d);
    }
}

/* A merge whose parts overlap (the next part starts before the last ends) gets a note naming how
 * far its control lines run back; parts with a gap between them, and every example, get none. */
static void overlapping_merges(void)
{
    static const char base[] =
        "{\"shapes\": {\"c\": {\"kind\": \"cylinder\"}}, \"meshes\": {"
        "\"A\": {\"shape\": \"c\", \"u\": {\"arcs\": 8}, \"v\": {\"segments\": 3, \"from\": 0, \"to\": 1}},"
        "\"B\": {\"shape\": \"c\", \"u\": {\"arcs\": 8}, \"v\": {\"segments\": 3, \"from\": %s, \"to\": %s}},"
        "\"M\": {\"merge\": [\"A\", \"B\"], \"along\": \"v\"}}, \"output\": \"M\"}";
    static const struct {
        const char *from, *to;
        int note; /* expected */
    } cases[] = {{"0.5", "1.5", 1}, {"1.0", "2.0", 1}, {"1.6", "2.6", 1}, {"1.45", "1.95", 1}, {"2.0", "3.0", 0},
                 {"3.0", "4.0", 0}}; /* (B from 1.45 to 1.95: its lines half as far apart as A's) */
    for (size_t k = 0; k < sizeof cases / sizeof cases[0]; k++) {
        rg2_error err;
        rg2_design *d = parse_edit2(base, cases[k].from, cases[k].to, &err);
        if (!d)
            continue;
        double back = most_back(rg2_design_mesh(d, 0));
        const char *note = rg2_design_note(d, 0), *at = note ? strstr(note, " lies ") : NULL;
        if (cases[k].note) {
            char want[64];
            snprintf(want, sizeof want, " lies %.2g line spacings", back);
            CHECK(rg2_design_num_notes(d) == 1 && at && !strncmp(at, want, strlen(want)) &&
                      strstr(note, "test: meshes.M.merge[1]: the control lines of 'A' and 'B' run back at their seam"),
                  "B from %s: want one note with '%s' (measured here), got %d: '%s'", cases[k].from, want,
                  rg2_design_num_notes(d), note ? note : "(none)");
        } else
            CHECK(rg2_design_num_notes(d) == 0 && back <= 0.05, "B from %s: a gap gives no note (back %.3g), got '%s'",
                  cases[k].from, back, note ? note : "(none)");
        rg2_design_free(d);
    }
    char *names[64];
    int n = rg2t_example_names(names, 64);
    for (int e = 0; e < n; e++) {
        rg2_design *d = NULL;
        rg2_error err;
        CHECK_OK(rg2_design_load(names[e], &d, &err), &err);
        CHECK(rg2_design_num_notes(d) == 0, "%s: no note expected, got '%s'", names[e],
              rg2_design_note(d, 0) ? rg2_design_note(d, 0) : "");
        rg2_design_free(d);
        free(names[e]);
    }
}

/* rg2_mesh_merge_overlap, the C caller's figure for a design file's merge note: for the parts of
 * overlapping_merges' cases (built by the design, output with the merge), back[1] is the merged
 * mesh's own largest step back (most_back, measured here) where the parts overlap, and at most
 * RG2_MERGE_OVERLAP where they leave a gap; the closing seam of a closed call is the seam of the
 * parts given the other way round; and the calls that cannot be measured are refused, named. */
static void merge_overlap_api(void)
{
    static const char base[] =
        "{\"shapes\": {\"c\": {\"kind\": \"cylinder\"}}, \"meshes\": {"
        "\"A\": {\"shape\": \"c\", \"u\": {\"arcs\": 8}, \"v\": {\"segments\": 3, \"from\": 0, \"to\": 1}},"
        "\"B\": {\"shape\": \"c\", \"u\": {\"arcs\": %s}, \"v\": {\"segments\": 3, \"from\": %s, \"to\": 2.6}},"
        "\"M\": {\"merge\": [\"A\", \"B\"], \"along\": \"v\"}}, \"output\": [\"A\", \"B\", \"M\"]}";
    static const struct {
        const char *from;
        int overlap; /* expected */
    } cases[] = {{"0.5", 1}, {"1.0", 1}, {"1.45", 1}, {"1.6", 1}, {"2.0", 0}, {"2.3", 0}};
    for (size_t k = 0; k < sizeof cases / sizeof cases[0]; k++) {
        rg2_error err;
        rg2_design *d = parse_edit2(base, "8", cases[k].from, &err);
        CHECK(d != NULL, "B from %s: %s", cases[k].from, err.msg);
        if (!d)
            continue;
        const rg2_mesh *ab[2] = {rg2_design_mesh(d, 0), rg2_design_mesh(d, 1)}, *ba[2] = {ab[1], ab[0]};
        double back[2] = {-1, -1}, closed[2], rev[2];
        CHECK_OK(rg2_mesh_merge_overlap(ab, 2, 1, 0, back, &err), &err);
        double most = most_back(rg2_design_mesh(d, 2));
        if (cases[k].overlap)
            CHECK(back[0] == 0.0 && back[1] > RG2_MERGE_OVERLAP && fabs(back[1] - most) <= 1e-12 * most &&
                      rg2_design_num_notes(d) == 1,
                  "B from %s: back %.17g, the merged mesh's step back %.17g, %d notes", cases[k].from, back[1], most,
                  rg2_design_num_notes(d));
        else
            CHECK(back[0] == 0.0 && back[1] <= RG2_MERGE_OVERLAP && most <= RG2_MERGE_OVERLAP &&
                      rg2_design_num_notes(d) == 0,
                  "B from %s: a gap, back %.3g (merged mesh %.3g), %d notes", cases[k].from, back[1], most,
                  rg2_design_num_notes(d));
        printf("  merge overlap, B from %s: back %.4g, merged mesh's step back %.4g\n", cases[k].from, back[1], most);
        CHECK_OK(rg2_mesh_merge_overlap(ab, 2, 1, 1, closed, &err), &err);
        CHECK_OK(rg2_mesh_merge_overlap(ba, 2, 1, 0, rev, &err), &err);
        CHECK(closed[1] == back[1] && closed[0] == rev[1], "B from %s: closed: %.17g, %.17g; B then A: %.17g",
              cases[k].from, closed[0], closed[1], rev[1]);
        rg2_design_free(d);
    }
    /* refused, named (B of 6 arcs: no merge in the design, which would refuse it) */
    static const char unmerged[] =
        "{\"shapes\": {\"c\": {\"kind\": \"cylinder\"}}, \"meshes\": {"
        "\"A\": {\"shape\": \"c\", \"u\": {\"arcs\": 8}, \"v\": {\"segments\": 3, \"from\": 0, \"to\": 1}},"
        "\"B\": {\"shape\": \"c\", \"u\": {\"arcs\": %s}, \"v\": {\"segments\": 3, \"from\": %s, \"to\": 2.6}}}, "
        "\"output\": [\"A\", \"B\"]}";
    rg2_error err;
    rg2_design *d = parse_edit2(unmerged, "6", "2.0", &err);
    CHECK(d != NULL, "B of 6 arcs: %s", err.msg);
    if (!d)
        return;
    const rg2_mesh *ab[2] = {rg2_design_mesh(d, 0), rg2_design_mesh(d, 1)}, *an[2] = {ab[0], NULL};
    double back[2];
    rg2_status st = rg2_mesh_merge_overlap(ab, 2, 1, 0, back, &err);
    CHECK(st == RG2_EINCOMPATIBLE && strstr(err.msg, "rg2_mesh_merge_overlap: in[0] and in[1] do not agree in u: 8 vs 6"),
          "counts that differ: %s (%s)", rg2_status_str(st), err.msg);
    st = rg2_mesh_merge_overlap(an, 2, 1, 0, back, &err);
    CHECK(st == RG2_EINVAL && strstr(err.msg, "in[1] is NULL"), "a NULL mesh: %s (%s)", rg2_status_str(st), err.msg);
    st = rg2_mesh_merge_overlap(ab, 2, 2, 0, back, &err);
    CHECK(st == RG2_EINVAL && strstr(err.msg, "dir = 2"), "dir 2: %s (%s)", rg2_status_str(st), err.msg);
    st = rg2_mesh_merge_overlap(ab, 2, 1, 0, NULL, &err);
    CHECK(st == RG2_EINVAL && strstr(err.msg, "back is NULL"), "no back: %s (%s)", rg2_status_str(st), err.msg);
    st = rg2_mesh_merge_overlap(ab, 0, 1, 0, back, &err);
    CHECK(st == RG2_EINVAL && strstr(err.msg, "no meshes"), "n = 0: %s (%s)", rg2_status_str(st), err.msg);
    rg2_design_free(d);
}

/* A list of rotations is applied in order: 90 degrees about x, then 90 about z, maps (x, y, z) to
 * (x, -z, y), then to (z, x, y) (worked out here); the placed cylinder's control points are the
 * unplaced ones mapped so. */
static void rotation_lists(void)
{
    static const char base[] =
        "{\"shapes\": {\"c\": {\"kind\": \"cylinder\"%s}}, \"meshes\": {\"M\": {\"shape\": \"c\", \"u\": "
        "{\"arcs\": 8}, \"v\": {\"segments\": 3, \"from\": 0, \"to\": 1}}}, \"output\": \"M\"}";
    rg2_error err;
    rg2_design *d0 = parse_edit(base, "", &err),
               *d1 = parse_edit(base, ", \"rotate\": [{\"axis\": [1, 0, 0], \"degrees\": 90}, "
                                      "{\"axis\": [0, 0, 1], \"degrees\": 90}]", &err);
    const rg2_mesh *m0 = rg2_design_mesh(d0, 0), *m1 = rg2_design_mesh(d1, 0);
    CHECK(m0 && m1 && m0->nu == m1->nu && m0->nv == m1->nv, "the two cylinders' meshes");
    double worst = 0.0;
    for (int i = 0; m0 && m1 && i < m0->nu; i++)
        for (int j = 0; j < m0->nv; j++) {
            const double *p = rg2_mesh_at(m0, i, j), *q = rg2_mesh_at(m1, i, j);
            double want[4] = {p[2], p[0], p[1], p[3]};
            for (int k = 0; k < 4; k++)
                worst = fmax(worst, fabs(q[k] - want[k]));
        }
    CHECK(worst < 1e-15, "rotate [x 90, z 90]: control points %.3g from (z, x, y)", worst);
    printf("  a list of two rotations, applied in order: control points %.1e from the map worked out by hand\n",
           worst);
    rg2_design_free(d0);
    rg2_design_free(d1);
}

/* roll turns a closed direction by whole steps: every patch of the rolled torus (unequal arcs, so
 * that each junction's scalars differ) is the patch k columns (or rows) on, bit for bit, with its tag; and rolling the twisted part of a merge back by
 * one 45-degree arc removes the twist note (rolling it on doubles the twist). */
static void rolled_meshes(void)
{
    static const char torus[] =
        "{\"shapes\": {\"t\": {\"kind\": \"torus\"}}, \"meshes\": {\"T\": {\"shape\": \"t\", \"u\": "
        "{\"arcs\": [30, 40, 50, 60, 40, 50, 45, 45]}, \"v\": {\"arcs\": [50, 70, 60, 60, 50, 70]}}, "
        "\"R\": {\"roll\": \"T\", \"dir\": \"%s\", \"by\": %s}}, \"output\": [\"T\", \"R\"]}";
    static const struct {
        const char *dir, *by;
        int du, dv; /* the rolled patch (i, j) is the original (i + du, j + dv) */
    } cases[] = {{"u", "3", 3, 0}, {"u", "-1", 7, 0}, {"v", "5", 0, 5}, {"v", "13", 0, 1}, {"u", "0", 0, 0}};
    for (size_t k = 0; k < sizeof cases / sizeof cases[0]; k++) {
        rg2_error err;
        rg2_design *d = parse_edit2(torus, cases[k].dir, cases[k].by, &err);
        const rg2_surface *a = rg2_design_surface(d, 0), *b = rg2_design_surface(d, 1);
        int same = a && b && a->nu == b->nu && a->nv == b->nv, differ = 0;
        for (int i = 0; same && i < a->nu; i++)
            for (int j = 0; j < a->nv; j++) {
                int si = (i + cases[k].du) % a->nu, sj = (j + cases[k].dv) % a->nv;
                same &= !memcmp(rg2_surface_patch(b, i, j), rg2_surface_patch(a, si, sj), sizeof(rg2_patch)) &&
                        b->tag[i * b->nv + j] == a->tag[si * a->nv + sj];
                differ |= memcmp(rg2_surface_patch(b, i, j), rg2_surface_patch(a, i, j), sizeof(rg2_patch)) != 0;
            }
        CHECK(same && differ == (cases[k].du || cases[k].dv), "roll %s by %s: the patches of the torus %s on",
              cases[k].dir, cases[k].by, cases[k].du || cases[k].dv ? "moved" : "not moved");
        rg2_design_free(d);
    }
    static const char twist[] =
        "{\"shapes\": {\"c\": {\"kind\": \"cylinder\"}}, \"meshes\": {"
        "\"A\": {\"shape\": \"c\", \"u\": {\"arcs\": 8}, \"v\": {\"segments\": 3, \"from\": 0, \"to\": 1}},"
        "\"B0\": {\"shape\": \"c\", \"u\": {\"arcs\": 8, \"from\": 45}, \"v\": {\"segments\": 3, \"from\": 2, "
        "\"to\": 3}}, \"B\": {\"roll\": \"B0\", \"dir\": \"u\", \"by\": %s}, \"M\": {\"merge\": [\"A\", \"B\"], "
        "\"along\": \"v\"}}, \"output\": \"M\"%s}";
    rg2_error err;
    rg2_design *d = parse_edit2(twist, "0", "", &err); /* the note says which roll undoes the twist */
    const char *said = rg2_design_note(d, 0);
    CHECK(said && strstr(said, "or roll it back: {\"roll\": \"B\", \"dir\": \"u\", \"by\": -1}"),
          "the 45-degree twist's note names the roll, got '%s'", said ? said : "(none)");
    rg2_design_free(d);
    d = parse_edit2(twist, "-1", "", &err);
    CHECK(d && rg2_design_num_notes(d) == 0, "rolled back by one arc: no twist note, got '%s'",
          rg2_design_note(d, 0) ? rg2_design_note(d, 0) : "");
    rg2_design_free(d);
    d = parse_edit2(twist, "1", "", &err);
    const char *note = rg2_design_note(d, 0);
    CHECK(note && strstr(note, "meet turned by 90 degrees"), "rolled on by one arc: a 90-degree note, got '%s'",
          note ? note : "(none)");
    rg2_design_free(d);
}

/* "normal": a point moved along the control net's normal. On a cylinder's net the normal at any
 * point, its open ends' one-sided differences included, is radial and outward (the net is
 * symmetric about the point's radial plane, its v differences run along the axis, and Su x Sv
 * points out): each listed point moves by 0.2 radially, to 1e-15, every other point stays bit
 * for bit; the normals come from the net before the entry, so the list's order does not matter
 * (bit for bit); rg2_mesh_net_normal gives the same move (bit for bit); a collapsed row has no
 * normal (RG2_EDOMAIN, naming the point), and an index outside the mesh is named. */
static void normal_edits(void)
{
    const char *base = "{\"shapes\": {\"c\": {\"kind\": \"cylinder\", \"radius\": 1.5}},"
                       " \"meshes\": {\"A\": {\"shape\": \"c\", \"u\": {\"arcs\": 6},"
                       " \"v\": {\"segments\": 4, \"from\": 0, \"to\": 2}}%s}, \"output\": \"%s\"}";
    rg2_error err;
    rg2_design *d0 = parse_edit2(base, "", "A", &err);
    rg2_design *d1 = parse_edit2(base, ", \"E\": {\"edit\": \"A\", \"points\": [{\"at\": [[2, 3], [3, 3], [0, 0], [5, 6]],"
                                 " \"normal\": 0.2}]}", "E", &err);
    rg2_design *d2 = parse_edit2(base, ", \"E\": {\"edit\": \"A\", \"points\": [{\"at\": [[5, 6], [0, 0], [3, 3], [2, 3]],"
                                 " \"normal\": 0.2}]}", "E", &err);
    if (!d0 || !d1 || !d2) {
        rg2_design_free(d0);
        rg2_design_free(d1);
        rg2_design_free(d2);
        return;
    }
    const rg2_mesh *m0 = rg2_design_mesh(d0, 0), *m1 = rg2_design_mesh(d1, 0), *m2 = rg2_design_mesh(d2, 0);
    double worst = 0;
    int moved = 0, other = 0, same_api = 1;
    for (int i = 0; i < m0->nu; i++)
        for (int j = 0; j < m0->nv; j++) {
            const double *p = rg2_mesh_at(m0, i, j), *q = rg2_mesh_at(m1, i, j);
            int listed = (i == 2 && j == 3) || (i == 3 && j == 3) || (i == 0 && j == 0) || (i == 5 && j == 6);
            if (!listed) {
                other += memcmp(p, q, 4 * sizeof *p) != 0;
                continue;
            }
            double r = hypot(p[0] / p[3], p[1] / p[3]), e[3];
            for (int k = 0; k < 3; k++) {
                double want = p[k] / p[3] + (k < 2 ? 0.2 * (p[k] / p[3]) / r : 0.0);
                worst = fmax(worst, fabs(q[k] / q[3] - want));
            }
            moved++;
            double n[3];
            CHECK_OK(rg2_mesh_net_normal(m0, i, j, n, &err), &err);
            for (int k = 0; k < 3; k++)
                e[k] = p[3] * (p[k] / p[3] + 0.2 * n[k]);
            same_api &= e[0] == q[0] && e[1] == q[1] && e[2] == q[2] && p[3] == q[3];
        }
    printf("  normal edits: 4 cylinder points moved 0.2 along the net's normal, off radial by %.2g\n", worst);
    CHECK(moved == 4 && worst <= 1e-15 && other == 0, "normal edit: %d moved, off radial by %g, %d others changed",
          moved, worst, other);
    CHECK(m1->nu * m1->nv == m2->nu * m2->nv &&
              !memcmp(m1->p, m2->p, (size_t)m1->nu * (size_t)m1->nv * 4 * sizeof *m1->p),
          "normal edit: the list's order changed the mesh");
    CHECK(same_api, "normal edit: rg2_mesh_net_normal gives another move");
    rg2_design_free(d0);
    rg2_design_free(d1);
    rg2_design_free(d2);

    rg2_design *dp = NULL;
    CHECK_OK(rg2_design_load("examples/fig9_polar_sphere.json", &dp, &err), &err);
    if (dp) {
        const rg2_mesh *mp = rg2_design_mesh(dp, 0);
        double n[3];
        rg2_status st = rg2_mesh_net_normal(mp, 3, mp->nv - 1, n, &err);
        CHECK(st == RG2_EDOMAIN && strstr(err.msg, "rg2_mesh_net_normal: the control net has no normal at [3, 7]"),
              "net normal at a pole: %s: %s", rg2_status_str(st), err.msg);
        st = rg2_mesh_net_normal(mp, 3, mp->nv, n, &err);
        CHECK(st == RG2_EINVAL && strstr(err.msg, "[3, 8] is outside the 8 x 8 points"), "net normal outside: %s",
              err.msg);
        CHECK_OK(rg2_mesh_net_normal(mp, 3, mp->nv - 2, n, &err), &err);
        rg2_design_free(dp);
    }
}

/* docs/design-format.md, `cut`: which patches a cut keeps. Open direction: patch i covers knot
 * interval i and uses points i..i+3, so [a, b] covers knots k_a..k_{b-2}; a polar mesh counts
 * from its first listed knot; closed direction: patch i covers arc i and uses points
 * i-1..i+2, so [a, b] keeps arcs a+1..b-2. Measured at the kept surface's first and last
 * patch ends against the shapes' own formulas. */
static void cut_ranges(void)
{
    rg2_error err;
    rg2_design *d = parse("{\"shapes\": {\"c\": {\"kind\": \"cylinder\"}, \"s\": {\"kind\": \"sphere\"},"
                          " \"t\": {\"kind\": \"torus\"}},"
                          " \"meshes\": {\"C\": {\"shape\": \"c\", \"v\": {\"knots\": [0, 0.3, 0.7, 1.2, 2.0, 2.5]}},"
                          " \"Ck\": {\"cut\": \"C\", \"v\": [1, 6]},"
                          " \"P\": {\"polar\": \"s\", \"v\": {\"knots\": [0.1, 0.2, 0.3, 0.4, 0.5, 0.6, 0.7]}},"
                          " \"Pk\": {\"cut\": \"P\", \"v\": [0, 6]},"
                          " \"T\": {\"shape\": \"t\", \"u\": {\"arcs\": 12}},"
                          " \"Tk\": {\"cut\": \"T\", \"u\": [0, 8]}},"
                          " \"output\": [\"Ck\", \"Pk\", \"Tk\"]}",
                          &err);
    if (!d)
        return;
    const rg2_surface *c = rg2_design_surface(d, 0), *p = rg2_design_surface(d, 1), *t = rg2_design_surface(d, 2);
    rg2_eval a, b;
    /* cylinder: knots k_1 = 0.3 to k_4 = 2.0, 3 patches */
    rg2_surface_eval(c, 0, 0, 0.0, 0.0, 0, &a);
    rg2_surface_eval(c, 0, c->nv - 1, 0.0, 1.0, 0, &b);
    CHECK(c->nv == 3 && fabs(a.p[2] - 0.3) <= 1e-15 && fabs(b.p[2] - 2.0) <= 1e-15,
          "cut v [1, 6] of knots 0, 0.3, ..., 2.5: %d patches from z %.17g to %.17g (want 3, 0.3 to 2.0)", c->nv,
          a.p[2], b.p[2]);
    /* polar sphere: from the first listed knot 0.1 to knots[4] = 0.5 (the equator, z = 0) */
    double v0 = 0.1, z0 = (2 * v0 - 1) / (2 * v0 * v0 - 2 * v0 + 1);
    rg2_surface_eval(p, 0, 0, 0.0, 0.0, 0, &a);
    rg2_surface_eval(p, 0, p->nv - 1, 0.0, 1.0, 0, &b);
    CHECK(p->nv == 4 && fabs(a.p[2] - z0) <= 1e-15 && fabs(b.p[2]) <= 1e-15,
          "cut v [0, 6] of the polar knots 0.1..0.7: %d patches from z %.17g to %.17g (want 4, %.17g to 0)", p->nv,
          a.p[2], b.p[2], z0);
    /* torus of 12 arcs: [0, 8] keeps arcs 1..6, 30 to 210 degrees */
    rg2_surface_eval(t, 0, 0, 0.0, 0.0, 0, &a);
    rg2_surface_eval(t, t->nu - 1, 0, 1.0, 0.0, 0, &b);
    double a0 = atan2(a.p[1], a.p[0]) * 180 / M_PI, a1 = atan2(b.p[1], b.p[0]) * 180 / M_PI;
    CHECK(t->nu == 6 && fabs(a0 - 30) <= 1e-12 && fabs(a1 + 150) <= 1e-12,
          "cut u [0, 8] of a 12-arc torus: %d patches from %.15g to %.15g degrees (want 6, 30 to 210 = -150)", t->nu,
          a0, a1);
    rg2_design_free(d);
}

/* A mobius without "sphere" maps about the unit sphere at the origin: on the polar mesh of a
 * placed sphere (radius 2 at (0, 0, 1)) that turns the sphere into another one (none of its
 * patches on it, the nearest 6.2e-2 of the size off it: rg2 check --on), so the design notes the "sphere" meant; none when "sphere" is given or the
 * mesh's sphere is the unit sphere at the origin. */
static void mobius_reference_notes(void)
{
    static const char base[] =
        "{\"shapes\": {\"s\": {\"kind\": \"sphere\", %s}}, \"meshes\": {\"P\": {\"polar\": \"s\","
        " \"u\": {\"arcs\": 8}, \"v\": {\"knots\": [0.2, 0.4, 0.6, 0.8]}}, \"M\": {\"mobius\": \"P\", %s\"b\": 0.5}}}";
    static const struct {
        const char *shape, *ref;
        int notes;
    } cases[] = {{"\"radius\": 2, \"translate\": [0, 0, 1]", "", 1},
                 {"\"radius\": 2, \"translate\": [0, 0, 1]", "\"sphere\": \"s\", ", 0},
                 {"\"radius\": 1", "", 0}};
    for (size_t c = 0; c < sizeof cases / sizeof cases[0]; c++) {
        char json[1024];
        snprintf(json, sizeof json, base, cases[c].shape, cases[c].ref);
        rg2_error err;
        rg2_design *d = parse(json, &err);
        if (!d)
            continue;
        int n = rg2_design_num_notes(d);
        const char *note = n > 0 ? rg2_design_note(d, 0) : "";
        CHECK(n == cases[c].notes && (n == 0 || (strstr(note, "meshes.M: no \"sphere\" given") &&
                                                     strstr(note, "give \"sphere\": \"s\""))),
              "mobius case %zu: %d notes (want %d): %s", c, n, cases[c].notes, note);
        /* what the note warns of, as rg2 check --on measures it: with a note no patch is on the
         * sphere (the nearest 6.2e-2 of the size off it), without one every patch is (1e-11) */
        const rg2_surface *s = rg2_design_surface(d, 0);
        double res[64], lo = INFINITY, hi = 0.0;
        if (s && s->nu * s->nv <= 64 && rg2_surface_shape_residuals(s, rg2_design_shape(d, 0), 8, res, &err) == RG2_OK)
            for (int k = 0; k < s->nu * s->nv; k++)
                lo = fmin(lo, res[k]), hi = fmax(hi, res[k]);
        CHECK(cases[c].notes ? lo > 1e-2 : hi <= 1e-11,
              "mobius case %zu: residuals on the sphere %.3g..%.3g (want %s)", c, lo, hi,
              cases[c].notes ? "all > 1e-2" : "all <= 1e-11");
        rg2_design_free(d);
    }
}

/* Moebius poles given on a placed sphere (radius 2, centre c = (0, 0, 1)) at the two ends of a
 * diameter along x, along y and along z: each pair is accepted (two different points, however
 * they differ), and the map, a rotation for antipodal poles, puts the polar mesh's collapsed
 * rows (on the reference's axis) on the axis from c through the poles given, at the same
 * distances from c for all three (1e-12 of the radius; z is the identity). Poles that differ in
 * one coordinate only were refused as coinciding when the distance test dropped or cancelled
 * that coordinate. */
static void mobius_axis_poles(void)
{
    static const char base[] =
        "{\"shapes\": {\"s\": {\"kind\": \"sphere\", \"radius\": 2, \"translate\": [0, 0, 1]}}, \"meshes\": {"
        "\"P\": {\"polar\": \"s\", \"u\": {\"arcs\": 8}, \"v\": {\"knots\": [0.2, 0.4, 0.6, 0.8]}}, \"M\": "
        "{\"mobius\": \"P\", \"sphere\": \"s\", \"poles\": {\"south\": [%g, %g, %g], \"north\": [%g, %g, %g]}}}, "
        "\"output\": \"M\"}";
    const double c[3] = {0, 0, 1};
    double along[3][2] = {{0}}, off = 0.0;
    int parsed = 0;
    for (int a = 0; a < 3; a++) {
        double S[3] = {0, 0, 1}, N[3] = {0, 0, 1};
        S[a] -= 2.0, N[a] += 2.0;
        char json[1024];
        snprintf(json, sizeof json, base, S[0], S[1], S[2], N[0], N[1], N[2]);
        rg2_error err;
        rg2_design *d = parse(json, &err);
        if (!d)
            continue;
        parsed++;
        const rg2_mesh *m = rg2_design_mesh(d, 0);
        for (int i = 0; i < m->nu; i++)
            for (int e = 0; e < 2; e++) {
                const double *p = rg2_mesh_at(m, i, e ? m->nv - 1 : 0);
                for (int k = 0; k < 3; k++) {
                    double x = p[k] / p[3] - c[k];
                    if (k == a)
                        along[a][e] = x;
                    else
                        off = fmax(off, fabs(x) / 2.0);
                }
            }
        rg2_design_free(d);
    }
    double spread = 0.0;
    for (int a = 0; a < 3; a++)
        for (int e = 0; e < 2; e++)
            spread = fmax(spread, fabs(along[a][e] - along[2][e]) / 2.0);
    CHECK(parsed == 3 && off <= 1e-12 && spread <= 1e-12 && along[2][0] < 0 && along[2][1] > 0,
          "Moebius poles along x, y, z: %d of 3 accepted, collapsed rows %.3g off the axis, distances %.3g apart "
          "(south %g, north %g)", parsed, off, spread, along[2][0], along[2][1]);
}

/* A circle direction started many turns round ("from": 1e20 degrees) is the one started at the
 * same angle within a turn, bit for bit: its junction angles rounded onto the start in radians,
 * and the torus's patches left it (residual 0.11 at 1e20 degrees, every u corner on one point;
 * 2.4e-10 at 1e9). Closed and open rings, positive and negative starts. */
static void start_many_turns(void)
{
    static const double from[] = {1e9, 1e12, 1e20, -1e15, 1e100};
    for (size_t q = 0; q < sizeof from / sizeof from[0]; q++)
        for (int open = 0; open < 2; open++) {
            char a[160], b[160];
            double red = fmod(from[q], 360.0);
            if (open) /* (a span of 90 degrees from a start of 1e12 is exact; past 2^53 the span rounds) */
                snprintf(a, sizeof a, "\"arcs\": 3, \"from\": %.17g, \"to\": %.17g", from[q] < 1e15 ? from[q] : red,
                         (from[q] < 1e15 ? from[q] : red) + 90);
            else
                snprintf(a, sizeof a, "\"arcs\": 8, \"from\": %.17g", from[q]);
            if (open)
                snprintf(b, sizeof b, "\"arcs\": 3, \"from\": %.17g, \"to\": %.17g", red, red + 90);
            else
                snprintf(b, sizeof b, "\"arcs\": 8, \"from\": %.17g", red);
            const char *base = "{\"shapes\": {\"t\": {\"kind\": \"torus\"}}, \"meshes\": {\"T\": {\"shape\": \"t\", \"u\": "
                               "{%s}, \"v\": {\"arcs\": 6}}}}";
            rg2_error err;
            rg2_design *da = parse_edit(base, a, &err), *db = parse_edit(base, b, &err);
            if (!da || !db) {
                rg2_design_free(da);
                rg2_design_free(db);
                continue;
            }
            const rg2_mesh *ma = rg2_design_mesh(da, 0), *mb = rg2_design_mesh(db, 0);
            int same = ma->nu == mb->nu && ma->nv == mb->nv &&
                       !memcmp(ma->p, mb->p, sizeof(double) * 4 * (size_t)ma->nu * (size_t)ma->nv);
            CHECK(same, "\"from\": %g (%s) is not the mesh of \"from\": %.17g", from[q], open ? "open" : "closed", red);
            rg2_check_report r;
            rg2_check_opts o;
            rg2_check_opts_default(&o);
            o.threads = 1;
            CHECK_OK(rg2_check(rg2_design_surface(da, 0), 1, rg2_design_shape(da, 0), NULL, 1, &o, &r, &err), &err);
            CHECK(r.worst_residual <= 1e-15 && r.g1.value <= 1e-13 && r.unmeasured == 0,
                  "\"from\": %g (%s): residual %.3g, G1 %.3g, %d samples unmeasured", from[q], open ? "open" : "closed",
                  r.worst_residual, r.g1.value, r.unmeasured);
            if (q == 2 && !open)
                printf("  torus u from 1e20 degrees: residual %.2g, G1 %.2g rad, the mesh of %.17g degrees: %s\n",
                       r.worst_residual, r.g1.value, red, same ? "bit for bit" : "NO");
            rg2_check_report_free(&r);
            rg2_design_free(da);
            rg2_design_free(db);
        }
}

/* One open arc near 180 degrees meets its data-only copy at the open end: the two leave less than
 * the smallest arc of the circle, their common control point lay 1150 radii away (179.9 degrees)
 * or 4.5e15 (180 - 3e-14: residual 0.08, the patches off the torus). Refused naming the arc, up to
 * 179.856 degrees accepted and exact. */
static void open_end_arc_near_180(void)
{
    const char *base = "{\"shapes\": {\"t\": {\"kind\": \"torus\"}}, \"meshes\": {\"T\": {\"shape\": \"t\", \"u\": "
                       "{%s, \"closed\": false}, \"v\": {\"arcs\": 6}}}}";
    static const char *const bad[] = {"\"arcs\": [179.9]", "\"arcs\": [179.99999999999997]",
                                       "\"arcs\": [179.9999999999, 179.9999999999]"};
    static const char *const names[] = {"meshes.T.u: arc 0 at the open start and its data-only copy beyond it leave only 0.2 deg",
                                        "meshes.T.u: arc 0 at the open start and its data-only copy beyond it leave only",
                                        "meshes.T.u: arc 0 at the open start"};
    for (int k = 0; k < 3; k++) {
        char json[512];
        snprintf(json, sizeof json, base, bad[k]);
        rg2_design *d = NULL;
        rg2_error err;
        rg2_status st = rg2_design_parse(json, strlen(json), "arc", &d, &err);
        CHECK(st == RG2_EDOMAIN && !d && strstr(err.msg, names[k]), "u %s: %s %s", bad[k], rg2_status_str(st),
              st ? err.msg : "accepted");
        rg2_design_free(d);
    }
    rg2_error err;
    rg2_design *d = parse_edit(base, "\"arcs\": [179.856]", &err);
    if (d) {
        rg2_check_report r;
        rg2_check_opts o;
        rg2_check_opts_default(&o);
        o.threads = 1;
        CHECK_OK(rg2_check(rg2_design_surface(d, 0), 1, rg2_design_shape(d, 0), NULL, 1, &o, &r, &err), &err);
        CHECK(r.worst_residual <= 1e-13, "open arc of 179.856 degrees: residual %.3g", r.worst_residual);
        rg2_check_report_free(&r);
        rg2_design_free(d);
    }
}

/* Caps on thin tubes: the cap fit's unknowns lambda1, lambda2 had columns of size L and L^2 (the
 * automatic cap length L = 2 rho / sigma: 8e-7 on a cylinder of radius 1e-7 over intervals of
 * 0.25), and from radius 1e-7 the fit was "rank-deficient ... is the ring degenerate?". Now
 * solved per unit of the cap's t: the tube of radius 1e-7 and 1e-6 capped at both ends passes
 * every promise of rg2_check. */
static void thin_tube_caps(void)
{
    static const double radius[] = {1e-6, 1e-7};
    for (int k = 0; k < 2; k++) {
        char json[512];
        snprintf(json, sizeof json,
                 "{\"shapes\": {\"c\": {\"kind\": \"cylinder\", \"radius\": %g}}, \"meshes\": {\"m\": {\"shape\": \"c\", "
                 "\"u\": {\"arcs\": 8}, \"v\": {\"segments\": 4}}, \"capped\": {\"cap\": \"m\", \"ends\": \"both\"}}}",
                 radius[k]);
        rg2_design *d = NULL;
        rg2_error err;
        rg2_status st = rg2_design_parse(json, strlen(json), "tube", &d, &err);
        CHECK(st == RG2_OK, "tube of radius %g capped: %s", radius[k], st ? err.msg : "");
        if (st)
            continue;
        rg2_check_report r;
        rg2_check_opts o;
        rg2_check_opts_default(&o);
        o.threads = 1;
        CHECK_OK(rg2_check(rg2_design_surface(d, 0), 1, rg2_design_shape(d, 0), NULL, 1, &o, &r, &err), &err);
        CHECK(r.g0.value <= o.tol_g0 && r.g1.value <= o.tol_g1 && r.g2.value <= o.tol_g2 && r.unmeasured == 0 &&
                  r.worst_residual <= 1e-15 && r.wmin > 0,
              "tube of radius %g capped: G0 %.3g, G1 %.3g, G2 %.3g, %d unmeasured, residual %.3g, weights from %g",
              radius[k], r.g0.value, r.g1.value, r.g2.value, r.unmeasured, r.worst_residual, r.wmin);
        printf("  cylinder of radius %g capped at both ends: G1 %.2g rad, G2 %.2g\n", radius[k], r.g1.value, r.g2.value);
        rg2_check_report_free(&r);
        rg2_design_free(d);
    }
    /* a given cap length the fit cannot use (1e100 on a unit cylinder) is named, not taken for a
     * degenerate ring ("is the ring degenerate?") */
    const char *big = "{\"shapes\": {\"c\": {\"kind\": \"cylinder\"}}, \"meshes\": {\"m\": {\"shape\": \"c\", \"u\": "
                      "{\"arcs\": 8}, \"v\": {\"segments\": 4}}, \"capped\": {\"cap\": \"m\", \"ends\": \"both\", "
                      "\"length\": [1e100, 1e100]}}}";
    rg2_design *d = NULL;
    rg2_error err;
    rg2_status st = rg2_design_parse(big, strlen(big), "tube", &d, &err);
    CHECK(st == RG2_EDOMAIN && !d && strstr(err.msg, "at the given cap length 1e+100") && !strstr(err.msg, "degenerate?"),
          "cap length 1e100: %s %s", rg2_status_str(st), st ? err.msg : "accepted");
    rg2_design_free(d);
}

/* An integer past the supported 1e9 was named as no integer at all ("meshes.R.by: expected an
 * integer, found 2147483647"); it is named as out of range, a fraction still as no integer. */
static void big_integers(void)
{
    static const char *const json[] = {
        "{\"shapes\": {\"t\": {\"kind\": \"torus\"}}, \"meshes\": {\"T\": {\"shape\": \"t\"}, \"R\": {\"roll\": \"T\", "
        "\"dir\": \"u\", \"by\": 2147483647}}}",
        "{\"shapes\": {\"t\": {\"kind\": \"torus\"}}, \"meshes\": {\"T\": {\"shape\": \"t\", \"u\": {\"arcs\": 2e9}}}}",
        "{\"shapes\": {\"t\": {\"kind\": \"torus\"}}, \"meshes\": {\"T\": {\"shape\": \"t\"}, \"R\": {\"roll\": \"T\", "
        "\"dir\": \"u\", \"by\": -1e12}}}"};
    static const char *const want[] = {"test: meshes.R.by: the integer 2147483647 is outside the supported range",
                                       "test: meshes.T.u.arcs: the integer 2000000000 is outside the supported range",
                                       "test: meshes.R.by: the integer -1000000000000 is outside the supported range"};
    for (int k = 0; k < 3; k++) {
        rg2_design *d = NULL;
        rg2_error err;
        rg2_status st = rg2_design_parse(json[k], strlen(json[k]), "test", &d, &err);
        CHECK(st == RG2_EDOMAIN && !d && strstr(err.msg, want[k]), "%s: %s %s", want[k], rg2_status_str(st),
              st ? err.msg : "accepted");
        rg2_design_free(d);
    }
}

/* A cap length given for an end the cap leaves open ("ends": "north" with "length": [2, 0]) has
 * no effect: the north cap is automatic. The design says so in a note naming the entry; a length
 * for a capped end, or 0 for the open one, gives none. Either way the surface is the one of the
 * same cap with that length dropped (bit for bit). */
static void cap_length_notes(void)
{
    static const char base[] =
        "{\"shapes\": {\"c\": {\"kind\": \"cylinder\"}}, \"meshes\": {\"A\": {\"shape\": \"c\"}, "
        "\"C\": {\"cap\": \"A\", \"ends\": \"%s\"%s}}}";
    static const struct {
        const char *ends, *length, *same_as, *note; /* note NULL: none */
    } cases[] = {
        {"north", ", \"length\": [2, 0]", "",
         "meshes.C.length[0]: 2 is the length of a south cap, but this cap closes only the north end (\"ends\": "
         "\"north\"), so it has no effect: the list is [south, north]; the north cap's length 0 is automatic (for "
         "a north cap of length 2 write [0, 2])"},
        {"south", ", \"length\": [1.5, 3]", ", \"length\": [1.5, 0]",
         "meshes.C.length[1]: 3 is the length of a north cap, but this cap closes only the south end (\"ends\": "
         "\"south\"), so it has no effect: the list is [south, north]"},
        {"south", ", \"length\": [0, 3]", "",
         "meshes.C.length[1]: 3 is the length of a north cap, but this cap closes only the south end (\"ends\": "
         "\"south\"), so it has no effect: the list is [south, north]; the south cap's length 0 is automatic (for "
         "a south cap of length 3 write [3, 0])"},
        {"north", ", \"length\": [0, 2]", ", \"length\": [0, 2]", NULL},
        {"both", ", \"length\": [2, 1]", ", \"length\": [2, 1]", NULL},
        /* small lengths are lengths: the note for 0.001, and no hint, the north length 0.002 being given */
        {"north", ", \"length\": [0.001, 0.002]", ", \"length\": [0, 0.002]",
         "meshes.C.length[0]: 0.001 is the length of a south cap, but this cap closes only the north end (\"ends\": "
         "\"north\"), so it has no effect: the list is [south, north]"}};
    for (size_t k = 0; k < sizeof cases / sizeof cases[0]; k++) {
        char json[600], json2[600];
        snprintf(json, sizeof json, base, cases[k].ends, cases[k].length);
        snprintf(json2, sizeof json2, base, cases[k].ends, cases[k].same_as);
        rg2_error err;
        rg2_design *d = parse(json, &err), *d2 = parse(json2, &err);
        if (d) {
            int n = rg2_design_num_notes(d);
            const char *note = n ? rg2_design_note(d, 0) : "";
            const char *at = strstr(note, "meshes.C.");
            if (cases[k].note)
                CHECK(n == 1 && at && !strcmp(at, cases[k].note), "cap ends %s%s: %d notes, first '%s', want '%s'",
                      cases[k].ends, cases[k].length, n, note, cases[k].note);
            else
                CHECK(n == 0, "cap ends %s%s: a note '%s'", cases[k].ends, cases[k].length, note);
        }
        if (d && d2) {
            const rg2_surface *a = rg2_design_surface(d, 0), *b = rg2_design_surface(d2, 0);
            int same = a && b && a->nu == b->nu && a->nv == b->nv;
            for (int i = 0; same && i < a->nu; i++)
                for (int j = 0; same && j < a->nv; j++)
                    same = !memcmp(rg2_surface_patch(a, i, j), rg2_surface_patch(b, i, j), sizeof(rg2_patch));
            CHECK(same, "cap ends %s%s: not the surface of %s", cases[k].ends, cases[k].length, json2);
        }
        rg2_design_free(d);
        rg2_design_free(d2);
    }
}

/* An operation uses a capped mesh uncapped (a cap belongs to an output surface): an output made
 * from a capped mesh, through any chain of operations, and not capped itself has open ends. The
 * design says so in a note naming the output, the capped mesh and the cap to add; an output that
 * is capped again, or the capped mesh itself, gets none. */
static void uncapped_output_notes(void)
{
    static const char base[] =
        "{\"shapes\": {\"c\": {\"kind\": \"cylinder\"}}, \"meshes\": {\"A\": {\"shape\": \"c\"}, "
        "\"K\": {\"cap\": \"A\", \"ends\": \"south\"}, \"T\": {\"transform\": \"K\", \"translate\": [3, 0, 0]}, "
        "\"R\": {\"reverse\": \"T\", \"dir\": \"u\"}, \"RK\": {\"cap\": \"R\"}, "
        "\"M\": {\"morph\": [\"A\", \"T\"], \"t\": 0.5}}, \"output\": %s}";
    static const struct {
        const char *output, *note; /* note NULL: none */
    } cases[] = {
        {"\"T\"", "meshes.T: the output 'T' is made from 'K', which is capped, and has no caps: a cap belongs to an "
                  "output surface, so an operation uses a capped mesh uncapped; to close the ends of 'T', cap it "
                  "as 'K' is capped ({\"cap\": \"T\", \"ends\": \"south\"}, the same options)"},
        {"[\"K\", \"R\"]", "meshes.R: the output 'R' is made from 'K', which is capped"},
        {"\"M\"", "meshes.M: the output 'M' is made from 'K', which is capped"},
        {"\"RK\"", NULL},
        {"\"K\"", NULL},
        {"\"A\"", NULL}};
    for (size_t k = 0; k < sizeof cases / sizeof cases[0]; k++) {
        char json[900];
        snprintf(json, sizeof json, base, cases[k].output);
        rg2_error err;
        rg2_design *d = parse(json, &err);
        if (!d)
            continue;
        int n = rg2_design_num_notes(d);
        const char *note = n ? rg2_design_note(d, 0) : "";
        const char *at = strstr(note, "meshes.");
        if (cases[k].note)
            CHECK(n == 1 && at && !strncmp(at, cases[k].note, strlen(cases[k].note)),
                  "output %s: %d notes, first '%s', want '%s'", cases[k].output, n, note, cases[k].note);
        else
            CHECK(n == 0, "output %s: a note '%s'", cases[k].output, note);
        rg2_design_free(d);
    }
    /* a shape or polar mesh has no mesh input, though its shape's label be a capped mesh's name */
    static const char same_names[] =
        "{\"shapes\": {\"c\": {\"kind\": \"cylinder\"}, \"s\": {\"kind\": \"sphere\"}}, \"meshes\": {"
        "\"A\": {\"shape\": \"c\"}, \"c\": {\"cap\": \"A\"}, \"s\": {\"cap\": \"A\", \"ends\": \"south\"}, "
        "\"B\": {\"shape\": \"c\"}, \"P\": {\"polar\": \"s\", \"u\": {\"arcs\": 8}, \"v\": {\"knots\": [0.15, 0.3,"
        " 0.42, 0.58, 0.7, 0.85]}}}, \"output\": [\"c\", \"s\", \"B\", \"P\"]}";
    rg2_error err;
    rg2_design *d = parse(same_names, &err);
    if (d) {
        CHECK(rg2_design_num_notes(d) == 0, "shapes named like capped meshes: a note '%s'", rg2_design_note(d, 0));
        rg2_design_free(d);
    }
}

/* A merge left open whose ends run on into each other, as the torus + sphere of Fig. 8 without
 * "closed": true (a ring with a gap of 3 patches' width), gets a note that names the parts and
 * says to close it; merges whose ends do not meet (two cylinders stacked, a torus arc of 270
 * degrees in 15 degree arcs, 6 spacings from closing) and closed ones get none. */
static char *replace_once(const char *s, const char *old, const char *new_text)
{
    const char *at = strstr(s, old);
    if (!at)
        return NULL;
    size_t a = (size_t)(at - s), n = strlen(new_text), rest = strlen(at + strlen(old));
    char *r = malloc(a + n + rest + 1);
    if (!r)
        return NULL;
    memcpy(r, s, a);
    memcpy(r + a, new_text, n);
    memcpy(r + a + n, at + strlen(old), rest + 1);
    return r;
}

static void open_ring_notes(void)
{
    char *ts = read_text("examples/torus_sphere.json");
    CHECK(ts != NULL, "read examples/torus_sphere.json");
    if (!ts)
        return;
    char *at = strstr(ts, ", \"closed\": true");
    CHECK(at != NULL, "torus_sphere.json merges with \"closed\": true");
    if (!at) {
        free(ts);
        return;
    }
    memmove(at, at + strlen(", \"closed\": true"), strlen(at + strlen(", \"closed\": true")) + 1);
    static const char stack[] =
        "{\"shapes\": {\"a\": {\"kind\": \"cylinder\"}, \"b\": {\"kind\": \"cylinder\", \"translate\": [0, 0, 2]}},"
        " \"meshes\": {\"A\": {\"shape\": \"a\"}, \"B\": {\"shape\": \"b\"}, \"M\": {\"merge\": [\"A\", \"B\"],"
        " \"along\": \"v\"}}}";
    static const char arc[] =
        "{\"shapes\": {\"t\": {\"kind\": \"torus\"}}, \"meshes\": {\"A\": {\"shape\": \"t\", \"u\": {\"arcs\": 8,"
        " \"from\": 0, \"to\": 120}}, \"B\": {\"shape\": \"t\", \"u\": {\"arcs\": 6, \"from\": 180, \"to\": 270}},"
        " \"M\": {\"merge\": [\"A\", \"B\"], \"along\": \"u\"}}}";
    /* a torus's v arcs 0..120 and 180..300: the parts' end control lines are one line to rounding
     * (their centres 1e-15 line spacings apart, with 8 or 4 u arcs) */
    static const char vring8[] =
        "{\"shapes\": {\"t\": {\"kind\": \"torus\"}}, \"meshes\": {\"A\": {\"shape\": \"t\", \"u\": {\"arcs\": 8},"
        " \"v\": {\"arcs\": 4, \"from\": 0, \"to\": 120}}, \"B\": {\"shape\": \"t\", \"u\": {\"arcs\": 8}, \"v\":"
        " {\"arcs\": 4, \"from\": 180, \"to\": 300}}, \"M\": {\"merge\": [\"A\", \"B\"], \"along\": \"v\"}}}";
    static const char vring4[] =
        "{\"shapes\": {\"t\": {\"kind\": \"torus\"}}, \"meshes\": {\"A\": {\"shape\": \"t\", \"u\": {\"arcs\": 4},"
        " \"v\": {\"arcs\": 4, \"from\": 0, \"to\": 120}}, \"B\": {\"shape\": \"t\", \"u\": {\"arcs\": 4}, \"v\":"
        " {\"arcs\": 4, \"from\": 180, \"to\": 300}}, \"M\": {\"merge\": [\"A\", \"B\"], \"along\": \"v\"}}}";
    /* the same along v (the parts transposed), and at 1/1000 of the size (line spacings of 0.0016) */
    static const char joined[] = "\"joined\": {\"merge\": [\"tube\", \"ball_band\"], \"along\": \"u\"}";
    char *tv = replace_once(ts, joined,
                            "\"tube_t\": {\"transpose\": \"tube\"}, \"joined\": {\"merge\": [\"tube_t\", "
                            "\"ball_mesh\"], \"along\": \"v\"}");
    char *tsm = replace_once(ts, joined,
                             "\"tube_s\": {\"transform\": \"tube\", \"scale\": 0.001}, \"band_s\": {\"transform\":"
                             " \"ball_band\", \"scale\": 0.001}, \"joined\": {\"merge\": [\"tube_s\", \"band_s\"], "
                             "\"along\": \"u\"}");
    CHECK(tv && tsm, "torus_sphere.json merges [\"tube\", \"ball_band\"] along u");
    const struct {
        const char *json, *note; /* note NULL: none */
    } cases[] = {{tv ? tv : ts, "meshes.joined: the merge is open along v, but its ends run on into each other as a "
                                "seam does: the first u line of 'tube_t' lies 1.7 line spacings on from the last of "
                                "'ball_mesh'"},
                 {tsm ? tsm : ts, "meshes.joined: the merge is open along u, but its ends run on into each other as "
                                  "a seam does: the first v line of 'tube_s' lies 1.7 line spacings on from the last "
                                  "of 'band_s'"},
                 {ts, "meshes.joined: the merge is open along u, but its ends run on into each other as a seam "
                      "does: the first v line of 'tube' lies 1.7 line spacings on from the last of 'ball_band', so "
                      "the surface is a ring with a gap there; if a closed ring is meant, add \"closed\": true"},
                 {vring8, "meshes.M: the merge is open along v, but its ends run on into each other as a seam does: "
                          "the first u line of 'A' lies on the last of 'B', so the surface is a ring with a gap there"},
                 {vring4, "meshes.M: the merge is open along v, but its ends run on into each other as a seam does: "
                          "the first u line of 'A' lies on the last of 'B', so"},
                 {stack, NULL},
                 {arc, NULL}};
    for (size_t k = 0; k < sizeof cases / sizeof cases[0]; k++) {
        rg2_error err;
        rg2_design *d = parse(cases[k].json, &err);
        if (!d)
            continue;
        int n = rg2_design_num_notes(d);
        const char *note = n ? rg2_design_note(d, 0) : "";
        const char *where = strstr(note, "meshes.");
        if (cases[k].note)
            CHECK(n == 1 && where && !strncmp(where, cases[k].note, strlen(cases[k].note)),
                  "open merge %zu: %d notes, first '%s', want '%s'", k, n, note, cases[k].note);
        else
            CHECK(n == 0, "open merge %zu: a note '%s'", k, note);
        rg2_design_free(d);
    }
    free(tv);
    free(tsm);
    free(ts);
}

/* Without "output" only the last mesh is built: a design of two parts that forgets to list both
 * builds the last alone. A mesh that is no output and that no operation uses gets a note naming
 * it; the inputs of the last mesh, a design with "output", and one part alone get none. */
static void unused_mesh_notes(void)
{
    static const struct {
        const char *meshes, *output, *note; /* note NULL: none */
    } cases[] = {
        {"\"ring\": {\"shape\": \"t\"}, \"ball\": {\"shape\": \"s\"}", "",
         "meshes: 'ring' is not an output and no operation uses it, so it is built into nothing: without \"output\" "
         "only the last mesh, 'ball', is built; to build more, list them: \"output\": [...]"},
        {"\"ring\": {\"shape\": \"t\"}, \"r2\": {\"shape\": \"t\"}, \"ball\": {\"shape\": \"s\"}", "",
         "meshes: 'ring', 'r2' are not outputs and no operation uses them, so they are built into nothing"},
        {"\"ring\": {\"shape\": \"t\"}, \"ball\": {\"shape\": \"s\"}", ", \"output\": [\"ring\", \"ball\"]", NULL},
        {"\"ring\": {\"shape\": \"t\"}, \"ball\": {\"shape\": \"s\"}", ", \"output\": \"ball\"", NULL},
        {"\"ring\": {\"shape\": \"t\"}, \"moved\": {\"transform\": \"ring\", \"translate\": [0, 0, 1]}", "", NULL},
        /* a shape's label is no use of the mesh of that name */
        {"\"t\": {\"shape\": \"t\"}, \"ball\": {\"shape\": \"s\"}", "",
         "meshes: 't' is not an output and no operation uses it, so it is built into nothing"}};
    for (size_t k = 0; k < sizeof cases / sizeof cases[0]; k++) {
        char json[900];
        snprintf(json, sizeof json,
                 "{\"shapes\": {\"t\": {\"kind\": \"torus\"}, \"s\": {\"kind\": \"sphere\", \"translate\": [6, 0, 0]}},"
                 " \"meshes\": {%s}%s}", cases[k].meshes, cases[k].output);
        rg2_error err;
        rg2_design *d = parse(json, &err);
        if (!d)
            continue;
        int n = rg2_design_num_notes(d);
        const char *note = n ? rg2_design_note(d, 0) : "";
        const char *at = strstr(note, "meshes");
        if (cases[k].note)
            CHECK(n == 1 && at && !strncmp(at, cases[k].note, strlen(cases[k].note)),
                  "unused case %zu: %d notes, first '%s', want '%s'", k, n, note, cases[k].note);
        else
            CHECK(n == 0, "unused case %zu: a note '%s'", k, note);
        rg2_design_free(d);
    }
}

int main(void)
{
    parse_sizes();
    long_messages();
    long_utf8_names();
    printf("design files:\n");
    text_files();
    printf("examples (exact-patch residual |F| / (|grad F| size), G2 seam gaps):\n");
    examples();
    printf("edit locality:\n");
    edits_are_local();
    edits_to_own_values();
    normal_edits();
    edits_measured();
    merge_keeps_scalar_provenance();
    printf("operations that keep exactness:\n");
    ops_keep_exactness();
    printf("random operation chains:\n");
    random_designs();
    printf("morph:\n");
    morph_ends();
    printf("merge seam rules:\n");
    seam_rules();
    printf("NURBS meshes:\n");
    nurbs_pieces();
    pole_edit_weights();
    closest_names();
    printf("transforms and long operation lists:\n");
    transform_placement();
    transform_windows();
    many_names();
    printf("bad input:\n");
    bad_inputs();
    mesh_check_range_weights();
    null_designs();
    unknown_key_lists();
    cap_seam_positions();
    design_caps_again();
    twisted_merges();
    overlapping_merges();
    weight_notes();
    surface_weight_notes();
    weight_notes_ends();
    tiny_literals();
    nesting_counts_brackets();
    merge_overlap_api();
    rotation_lists();
    rolled_meshes();
    cut_ranges();
    mobius_reference_notes();
    mobius_axis_poles();
    start_many_turns();
    open_end_arc_near_180();
    thin_tube_caps();
    cap_length_notes();
    uncapped_output_notes();
    open_ring_notes();
    unused_mesh_notes();
    big_integers();
    return rg2t_done("test_design");
}
