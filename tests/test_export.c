/* test_export.c -- the export writers read back by readers of our own: OBJ, binary STL and
 * PLY round-trips against the tessellation, .glb validated structurally (header, chunk
 * lengths, accessor and index bounds, min/max), .bv / .bez / .json patches exactly, STEP
 * numbers, complex-instance order and one pcurve per edge use, IGES record layout and B-rep
 * loops; the STEP and IGES B-reps read back entity by entity (knots, edge ends at their
 * vertices, pcurves on the faces using them, shell faces, closed or open shells); a big surface's STEP entities in file order and its four IGES forms read back
 * (directory pointers, every number); and the failure cases (unwritable path, non-positive
 * weight, empty input, unknown extension, more IGES records than its sequence numbers hold)
 * leave no file behind. */
#define _POSIX_C_SOURCE 200809L
#define _DEFAULT_SOURCE /* setgroups */
#include "../src/export_internal.h"
#include "export_fixtures.h"

#include <cjson/cJSON.h>
#include <errno.h>
#include <float.h>
#include <dirent.h>
#include <stdint.h>
#include <stdlib.h>
#include <grp.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <time.h>
#include <pthread.h>
#include <unistd.h>

static char g_dir[64];

/* name in the test directory, written into buf (a path that must outlive path_in's buffers) */
static char *path_at(char buf[256], const char *name)
{
    int n = snprintf(buf, 256, "%s/%s", g_dir, name);
    CHECK(n > 0 && n < 256, "test path '%s/%s' longer than its buffer", g_dir, name);
    return buf;
}

/* name in the test directory, in one of eight buffers used in turn: a ninth call overwrites the
 * first one's path */
static char *path_in(const char *name)
{
    static char buf[8][256];
    static int k;
    k = (k + 1) % 8;
    return path_at(buf[k], name);
}

static unsigned char *slurp(const char *path, size_t *len)
{
    FILE *f = fopen(path, "rb");
    if (!f)
        return NULL;
    fseek(f, 0, SEEK_END);
    long n = ftell(f);
    fseek(f, 0, SEEK_SET);
    unsigned char *b = malloc((size_t)n + 1);
    if (b && fread(b, 1, (size_t)n, f) != (size_t)n) {
        free(b);
        b = NULL;
    }
    fclose(f);
    if (b) {
        b[n] = 0;
        *len = (size_t)n;
    }
    return b;
}

static uint32_t rd_u32(const unsigned char *p) { return p[0] | p[1] << 8 | p[2] << 16 | (uint32_t)p[3] << 24; }
static float rd_f32(const unsigned char *p)
{
    uint32_t u = rd_u32(p);
    float f;
    memcpy(&f, &u, 4);
    return f;
}

static int count_files(void)
{
    DIR *d = opendir(g_dir);
    int n = 0;
    struct dirent *e;
    while (d && (e = readdir(d)))
        if (e->d_name[0] != '.')
            n++;
    if (d)
        closedir(d);
    return n;
}

static int exists(const char *p)
{
    struct stat st;
    return stat(p, &st) == 0;
}

static rg2_status export_one(const rg2_surface *s, const char *name, rg2_error *err)
{
    rg2_export_opts o;
    rg2_export_opts_default(&o);
    o.density = 6;
    o.name = "torus";
    return rg2_export_file(s, 1, path_in(name), &o, err);
}

/* ---------------------------------------------------------------- OBJ */
/* t: the tessellation at `density`; from 16 x 2048 lines up the OBJ is formatted in several
 * batches of blocks on the threads (src/meshio.c), which must give the same lines in order. */
static void obj_roundtrip(const rg2_surface *s, const rg2_tess *t, int density)
{
    rg2_error err;
    rg2_export_opts o;
    rg2_export_opts_default(&o);
    o.density = density;
    o.name = "torus";
    CHECK_OK(rg2_export_file(s, 1, path_in("t.obj"), &o, &err), &err);
    FILE *f = fopen(path_in("t.obj"), "r");
    CHECK(f != NULL, "t.obj not written");
    if (!f)
        return;
    char line[512];
    int nv = 0, nn = 0, nf = 0, bad = 0;
    while (fgets(line, sizeof line, f)) {
        double x, y, z;
        int a[3], b[3];
        if (sscanf(line, "v %lf %lf %lf", &x, &y, &z) == 3) {
            if (nv >= t->n_vertices || x != t->pos[3 * nv] || y != t->pos[3 * nv + 1] || z != t->pos[3 * nv + 2])
                bad++;
            nv++;
        } else if (sscanf(line, "vn %lf %lf %lf", &x, &y, &z) == 3) {
            if (nn >= t->n_vertices || x != t->normal[3 * nn] || y != t->normal[3 * nn + 1] || z != t->normal[3 * nn + 2])
                bad++;
            nn++;
        } else if (sscanf(line, "f %d//%d %d//%d %d//%d", &a[0], &b[0], &a[1], &b[1], &a[2], &b[2]) == 6) {
            for (int k = 0; k < 3; k++)
                if (nf >= t->n_triangles || a[k] != b[k] || a[k] - 1 != t->tri[3 * nf + k])
                    bad++;
            nf++;
        }
    }
    fclose(f);
    CHECK(nv == t->n_vertices && nn == nv && nf == t->n_triangles && bad == 0,
          "OBJ at density %d: %d vertices, %d normals, %d faces read (expected %d, %d), %d mismatches", density, nv,
          nn, nf, t->n_vertices, t->n_triangles, bad);
}

/* ---------------------------------------------------------------- STL */
static void stl_roundtrip(const rg2_surface *s, const rg2_tess *t)
{
    rg2_error err;
    CHECK_OK(export_one(s, "t.stl", &err), &err);
    size_t len = 0;
    unsigned char *b = slurp(path_in("t.stl"), &len);
    CHECK(b && len >= 84, "STL: not read");
    if (!b)
        return;
    uint32_t n = rd_u32(b + 80);
    CHECK(n == (uint32_t)t->n_triangles && len == 84 + 50 * (size_t)n, "STL: %u triangles, %zu bytes", n, len);
    int bad = 0, flipped = 0;
    for (uint32_t q = 0; q < n && len == 84 + 50 * (size_t)n; q++) {
        const unsigned char *r = b + 84 + 50 * q;
        for (int v = 0; v < 3; v++)
            for (int k = 0; k < 3; k++)
                if (rd_f32(r + 12 + 12 * v + 4 * k) != (float)t->pos[3 * t->tri[3 * q + v] + k])
                    bad++;
        double dot = 0;
        for (int k = 0; k < 3; k++)
            dot += rd_f32(r + 4 * k) * t->normal[3 * t->tri[3 * q] + k];
        if (!(dot > 0))
            flipped++;
    }
    CHECK(bad == 0 && flipped == 0, "STL: %d coordinate mismatches, %d facet normals against the surface", bad, flipped);
    free(b);
}

/* The STL of s at `density` against t, its tessellation at that density: each facet's normal is
 * the unit normal of its triangle's vertices a, b, d, (b - a) x (d - a) over its length, and a
 * facet of zero area (that cross product exactly 0) gets the unit mean of its three vertices'
 * exact normals. Counts the zero-area facets into *zero; returns the largest deviation of a
 * written normal from its expected one (a component, or its length from 1). */
static double stl_normals_off(const rg2_surface *s, const rg2_tess *t, int density, const char *file, int *zero)
{
    rg2_error err;
    rg2_export_opts o;
    rg2_export_opts_default(&o);
    o.density = density;
    CHECK_OK(rg2_export_file(s, 1, path_in(file), &o, &err), &err);
    size_t len = 0;
    unsigned char *b = slurp(path_in(file), &len);
    if (!b || len != 84 + 50 * (size_t)t->n_triangles || rd_u32(b + 80) != (uint32_t)t->n_triangles) {
        CHECK(0, "%s: %zu bytes for %d triangles", file, len, t->n_triangles);
        free(b);
        return INFINITY;
    }
    double worst = 0.0;
    *zero = 0;
    for (int q = 0; q < t->n_triangles; q++) {
        const int *c = t->tri + 3 * q;
        const double *p0 = t->pos + 3 * c[0], *p1 = t->pos + 3 * c[1], *p2 = t->pos + 3 * c[2];
        double e1[3], e2[3], n[3], l2 = 0.0, got2 = 0.0;
        for (int k = 0; k < 3; k++)
            e1[k] = p1[k] - p0[k], e2[k] = p2[k] - p0[k];
        for (int k = 0; k < 3; k++)
            n[k] = e1[(k + 1) % 3] * e2[(k + 2) % 3] - e1[(k + 2) % 3] * e2[(k + 1) % 3];
        if (n[0] == 0.0 && n[1] == 0.0 && n[2] == 0.0) {
            ++*zero;
            for (int k = 0; k < 3; k++)
                n[k] = t->normal[3 * c[0] + k] + t->normal[3 * c[1] + k] + t->normal[3 * c[2] + k];
        }
        for (int k = 0; k < 3; k++)
            l2 += n[k] * n[k];
        for (int k = 0; k < 3; k++) {
            double got = rd_f32(b + 84 + 50 * (size_t)q + 4 * k);
            worst = fmax(worst, fabs(got - n[k] / sqrt(l2)));
            got2 += got * got;
        }
        worst = fmax(worst, fabs(sqrt(got2) - 1.0));
    }
    free(b);
    remove(path_in(file));
    return worst;
}

/* STL facet normals, read back: the torus's triangles, and a folded sheet all of whose facets
 * have zero area at density 1. Its patches run x = u and z = 2 x^2 along u, and leave y = 0 and
 * come back to it along v (y control values 0, 0.5, 0.5, 0), so every grid row lies on one curve
 * in y = 0, while the vertex normals there, +-Su x Sv, point in the x, z plane, opposite at v = 0
 * and v = 1 of a patch. */
static void stl_facet_normals(const rg2_surface *torus, const rg2_tess *t)
{
    int zero_t = 0, zero_f = 0;
    double off_t = stl_normals_off(torus, t, 6, "normals.stl", &zero_t);
    rg2_surface fold;
    rg2_tess tf;
    rg2_error err;
    CHECK_OK(fx_random(7, 7, 5, &fold, &err), &err);
    for (int i = 0; i < fold.nu; i++)
        for (int j = 0; j < fold.nv; j++)
            for (int r = 0; r < 4; r++)
                for (int q = 0; q < 4; q++) {
                    double *h = rg2_surface_patch(&fold, i, j)->h[r][q], x = (3.0 * i + r) / (3.0 * fold.nu);
                    h[0] = x, h[1] = q == 1 || q == 2 ? 0.5 : 0.0, h[2] = 2.0 * x * x, h[3] = 1.0;
                }
    CHECK_OK(rg2_tessellate(&fold, 1, 0, &tf, &err), &err);
    double off_f = stl_normals_off(&fold, &tf, 1, "fold.stl", &zero_f);
    CHECK(zero_t == 0 && off_t <= 1e-6, "torus STL: facet normals %.3g off their triangles' (%d of zero area)", off_t,
          zero_t);
    CHECK(fold.nu * fold.nv == 8 && zero_f == tf.n_triangles && zero_f == 16 && off_f <= 1e-6,
          "folded sheet STL (%d patches): %d of %d facets of zero area, normals %.3g off the mean vertex normals",
          fold.nu * fold.nv, zero_f, tf.n_triangles, off_f);
    rg2_tess_free(&tf);
    rg2_surface_free(&fold);
}

/* ---------------------------------------------------------------- PLY */
static void ply_roundtrip(const rg2_surface *s, const rg2_tess *t)
{
    rg2_error err;
    CHECK_OK(export_one(s, "t.ply", &err), &err);
    size_t len = 0;
    unsigned char *b = slurp(path_in("t.ply"), &len);
    CHECK(b != NULL, "PLY: not read");
    if (!b)
        return;
    char *end = strstr((char *)b, "end_header\n");
    int nv = -1, nf = -1;
    char *p = strstr((char *)b, "element vertex ");
    if (p)
        nv = atoi(p + 15);
    p = strstr((char *)b, "element face ");
    if (p)
        nf = atoi(p + 13);
    CHECK(end && nv == t->n_vertices && nf == t->n_triangles, "PLY header: %d vertices, %d faces", nv, nf);
    CHECK(strstr((char *)b, "property float gaussian_curvature") && strstr((char *)b, "property float mean_curvature"),
          "PLY: curvature properties missing");
    if (!end || nv != t->n_vertices || nf != t->n_triangles) {
        free(b);
        return;
    }
    const unsigned char *d = (unsigned char *)end + 11;
    size_t expect = (size_t)(d - b) + 32 * (size_t)nv + 13 * (size_t)nf;
    CHECK(len == expect, "PLY: %zu bytes, expected %zu", len, expect);
    int bad = 0;
    rg2_tess tc;
    rg2_tessellate(s, 6, 1, &tc, &err);
    for (int v = 0; v < nv && len == expect; v++, d += 32) {
        for (int k = 0; k < 3; k++) {
            bad += rd_f32(d + 4 * k) != (float)t->pos[3 * v + k];
            bad += rd_f32(d + 12 + 4 * k) != (float)t->normal[3 * v + k];
        }
        bad += rd_f32(d + 24) != (float)tc.K[v];
        bad += rd_f32(d + 28) != (float)tc.H[v];
    }
    for (int q = 0; q < nf && len == expect; q++, d += 13) {
        bad += d[0] != 3;
        for (int k = 0; k < 3; k++)
            bad += (int)rd_u32(d + 1 + 4 * k) != t->tri[3 * q + k];
    }
    CHECK(bad == 0, "PLY: %d mismatches", bad);
    rg2_tess_free(&tc);
    free(b);
}

/* ---------------------------------------------------------------- glb */
static double num(const cJSON *o, const char *k)
{
    const cJSON *v = cJSON_GetObjectItemCaseSensitive(o, k);
    return cJSON_IsNumber(v) ? v->valuedouble : -1;
}

static void glb_validate(const rg2_surface *s, const rg2_tess *t)
{
    rg2_error err;
    CHECK_OK(export_one(s, "t.glb", &err), &err);
    size_t len = 0;
    unsigned char *b = slurp(path_in("t.glb"), &len);
    CHECK(b && len >= 28, "glb: not read");
    if (!b || len < 28) {
        free(b);
        return;
    }
    CHECK(!memcmp(b, "glTF", 4) && rd_u32(b + 4) == 2 && rd_u32(b + 8) == len, "glb header: version %u length %u of %zu",
          rd_u32(b + 4), rd_u32(b + 8), len);
    uint32_t jl = rd_u32(b + 12);
    CHECK(!memcmp(b + 16, "JSON", 4) && jl % 4 == 0 && 20 + (size_t)jl + 8 <= len, "glb JSON chunk: length %u", jl);
    if (20 + (size_t)jl + 8 > len) {
        free(b);
        return;
    }
    const unsigned char *bin = b + 20 + jl + 8;
    uint32_t bl = rd_u32(b + 20 + jl);
    CHECK(!memcmp(b + 20 + jl + 4, "BIN\0", 4) && bl % 4 == 0 && 20 + (size_t)jl + 8 + bl == len,
          "glb BIN chunk: length %u", bl);
    cJSON *j = cJSON_ParseWithLength((const char *)b + 20, jl);
    CHECK(j != NULL, "glb: JSON chunk does not parse");
    const cJSON *asset = cJSON_GetObjectItemCaseSensitive(j, "asset");
    const cJSON *ver = cJSON_GetObjectItemCaseSensitive(asset, "version");
    CHECK(cJSON_IsString(ver) && !strcmp(ver->valuestring, "2.0"), "glb: asset.version");
    const cJSON *buffers = cJSON_GetObjectItemCaseSensitive(j, "buffers");
    CHECK(num(cJSON_GetArrayItem(buffers, 0), "byteLength") == bl, "glb: buffer byteLength != BIN chunk");
    const cJSON *views = cJSON_GetObjectItemCaseSensitive(j, "bufferViews");
    const cJSON *acc = cJSON_GetObjectItemCaseSensitive(j, "accessors");
    const cJSON *prim = cJSON_GetArrayItem(cJSON_GetObjectItemCaseSensitive(
                                               cJSON_GetArrayItem(cJSON_GetObjectItemCaseSensitive(j, "meshes"), 0),
                                               "primitives"),
                                           0);
    int bad = 0;
    const cJSON *v;
    cJSON_ArrayForEach(v, views) bad += num(v, "byteOffset") + num(v, "byteLength") > bl || num(v, "byteOffset") < 0;
    const cJSON *a;
    cJSON_ArrayForEach(a, acc)
    {
        const cJSON *view = cJSON_GetArrayItem(views, (int)num(a, "bufferView"));
        const cJSON *type = cJSON_GetObjectItemCaseSensitive(a, "type");
        int comps = cJSON_IsString(type) && !strcmp(type->valuestring, "VEC3") ? 3 : 1;
        bad += !view || num(a, "count") * comps * 4 > num(view, "byteLength");
    }
    /* the scene graph a viewer walks: scene 0 lists node 0, which shows mesh 0 (named as the
     * export), whose primitive lists triangles (mode 4, TRIANGLES: the indices are 3 per face) */
    const cJSON *scene = cJSON_GetArrayItem(cJSON_GetObjectItemCaseSensitive(j, "scenes"), 0);
    const cJSON *snodes = cJSON_GetObjectItemCaseSensitive(scene, "nodes");
    const cJSON *node = cJSON_GetArrayItem(cJSON_GetObjectItemCaseSensitive(j, "nodes"), 0);
    const cJSON *mesh = cJSON_GetArrayItem(cJSON_GetObjectItemCaseSensitive(j, "meshes"), 0);
    const cJSON *nname = cJSON_GetObjectItemCaseSensitive(node, "name");
    const cJSON *mname = cJSON_GetObjectItemCaseSensitive(mesh, "name");
    const cJSON *node0 = cJSON_GetArrayItem(snodes, 0);
    CHECK(num(j, "scene") == 0 && cJSON_GetArraySize(snodes) == 1 && cJSON_IsNumber(node0) && node0->valuedouble == 0 &&
              num(node, "mesh") == 0 && cJSON_IsString(nname) && !strcmp(nname->valuestring, "torus") &&
              cJSON_IsString(mname) && !strcmp(mname->valuestring, "torus"),
          "glb: scene 0 -> node 0 -> mesh 0 'torus' not linked");
    CHECK(num(prim, "mode") == 4, "glb: primitive mode %g, expected 4 (TRIANGLES)", num(prim, "mode"));
    const cJSON *attr = cJSON_GetObjectItemCaseSensitive(prim, "attributes");
    const cJSON *pa = cJSON_GetArrayItem(acc, (int)num(attr, "POSITION"));
    const cJSON *ia = cJSON_GetArrayItem(acc, (int)num(prim, "indices"));
    CHECK(pa && ia && num(pa, "count") == t->n_vertices && num(ia, "count") == 3 * t->n_triangles,
          "glb: accessor counts");
    if (pa && ia && !bad && num(pa, "count") == t->n_vertices) {
        const unsigned char *pos = bin + (size_t)num(cJSON_GetArrayItem(views, (int)num(pa, "bufferView")), "byteOffset");
        const unsigned char *idx = bin + (size_t)num(cJSON_GetArrayItem(views, (int)num(ia, "bufferView")), "byteOffset");
        const cJSON *mn = cJSON_GetObjectItemCaseSensitive(pa, "min"), *mx = cJSON_GetObjectItemCaseSensitive(pa, "max");
        double lo[3] = {INFINITY, INFINITY, INFINITY}, hi[3] = {-INFINITY, -INFINITY, -INFINITY};
        for (int q = 0; q < t->n_vertices; q++)
            for (int k = 0; k < 3; k++) {
                float x = rd_f32(pos + 12 * q + 4 * k);
                bad += x != (float)t->pos[3 * q + k];
                lo[k] = fmin(lo[k], x);
                hi[k] = fmax(hi[k], x);
            }
        for (int k = 0; k < 3; k++)
            bad += cJSON_GetArrayItem(mn, k)->valuedouble != lo[k] || cJSON_GetArrayItem(mx, k)->valuedouble != hi[k];
        for (int q = 0; q < 3 * t->n_triangles; q++)
            bad += rd_u32(idx + 4 * q) >= (uint32_t)t->n_vertices || (int)rd_u32(idx + 4 * q) != t->tri[q];
    }
    CHECK(bad == 0, "glb: %d structural or data errors (views, accessors, min/max, index bounds)", bad);
    cJSON_Delete(j);
    free(b);
}

/* ---------------------------------------------------------------- patch formats */
/* Worst distance (relative to the size) between rg2's patches and the patches read back from
 * .bez (elevated to the file's degrees), and of the .bez patches from the exact torus. */
static double g_bez_dev, g_bez_torus;

/* .bv, .bez and .json read back: .bv and .json hold each patch with its own degrees, exactly;
 * .bez holds every patch elevated to the highest degrees (the header's), exactly the
 * elevation of rg2's patch, and evaluating to the same surface. torus_R > 0: s is that torus
 * (minor radius torus_r), and the .bez patches are checked against it. */
static void patches_roundtrip(const rg2_surface *s, double torus_R, double torus_r)
{
    rg2_error err;
    CHECK_OK(export_one(s, "t.bv", &err), &err);
    CHECK_OK(export_one(s, "t.bez", &err), &err);
    CHECK_OK(export_one(s, "t.json", &err), &err);
    int np = s->nu * s->nv, bad = 0, n = 0;
    FILE *f = fopen(path_in("t.bv"), "r");
    char line[512];
    while (f && fgets(line, sizeof line, f)) {
        if (!strncmp(line, "Group", 5))
            continue;
        int du, dv;
        rg2_xpatch X;
        rg2_surface_patch_get(s, (n < np ? n : 0) / s->nv, (n < np ? n : 0) % s->nv, &X);
        bad += strcmp(line, "8\n") != 0;
        bad += !fgets(line, sizeof line, f) || sscanf(line, "%d %d", &du, &dv) != 2 || du != X.du || dv != X.dv;
        for (int r = 0; r <= X.du; r++)
            for (int t = 0; t <= X.dv; t++) {
                double h[4];
                bad += !fgets(line, sizeof line, f) || sscanf(line, "%lf %lf %lf %lf", &h[0], &h[1], &h[2], &h[3]) != 4;
                bad += n >= np || memcmp(h, X.h[r][t], sizeof h) != 0;
            }
        n++;
    }
    if (f)
        fclose(f);
    CHECK(n == np && bad == 0, "BezierView: %d patches read (expected %d), %d mismatches", n, np, bad);
    int Du, Dv;
    rg2_surface_degree(s, &Du, &Dv);
    char header[16];
    snprintf(header, sizeof header, "BEZ%d%d4\n", Du, Dv);
    f = fopen(path_in("t.bez"), "r");
    bad = 0;
    n = 0;
    bad += !f || !fgets(line, sizeof line, f) || strcmp(line, header);
    double scale = rg2t_surface_scale(s), dev = 0.0, off = 0.0;
    for (; f && n < np; n++) {
        rg2_xpatch X, E, R;
        memset(&R, 0, sizeof R);
        R.du = Du;
        R.dv = Dv;
        rg2_surface_patch_get(s, n / s->nv, n % s->nv, &X);
        CHECK_OK(rg2_xpatch_elevate(&X, Du, Dv, &E, &err), &err);
        for (int t = 0; t <= Dv; t++)
            for (int r = 0; r <= Du; r++) {
                double *h = R.h[r][t];
                bad += fscanf(f, "%lf %lf %lf %lf", &h[0], &h[1], &h[2], &h[3]) != 4 ||
                       memcmp(h, E.h[r][t], sizeof(double[4])) != 0;
            }
        for (int a = 0; a <= 4; a++)
            for (int b = 0; b <= 4; b++) {
                rg2_eval e, q;
                rg2_surface_eval(s, n / s->nv, n % s->nv, a / 4.0, b / 4.0, 0, &e);
                rg2_xpatch_eval(&R, a / 4.0, b / 4.0, 0, &q);
                double d = hypot(hypot(e.p[0] - q.p[0], e.p[1] - q.p[1]), e.p[2] - q.p[2]) / scale;
                dev = d > dev ? d : dev;
                if (torus_R > 0) {
                    double t = fx_torus_dist(torus_R, torus_r, q.p) / scale;
                    off = t > off ? t : off;
                }
            }
    }
    if (f)
        fclose(f);
    CHECK(bad == 0, "%.6s: %d mismatches", header, bad);
    CHECK(dev <= 1e-14, "%.6s: patches evaluate %.3g (relative) from rg2's", header, dev);
    CHECK(off <= 1e-13, "%.6s: patches %.3g (relative) off the exact torus", header, off);
    g_bez_dev = dev > g_bez_dev ? dev : g_bez_dev;
    g_bez_torus = off > g_bez_torus ? off : g_bez_torus;
    size_t len;
    unsigned char *b = slurp(path_in("t.json"), &len);
    cJSON *j = b ? cJSON_Parse((char *)b) : NULL;
    const cJSON *sf = cJSON_GetArrayItem(cJSON_GetObjectItemCaseSensitive(j, "surfaces"), 0);
    const cJSON *pa = cJSON_GetObjectItemCaseSensitive(sf, "patches");
    const cJSON *jdu = cJSON_GetObjectItemCaseSensitive(sf, "du"), *jdv = cJSON_GetObjectItemCaseSensitive(sf, "dv");
    bad = cJSON_GetArraySize(pa) != np || cJSON_GetArraySize(jdu) != np || cJSON_GetArraySize(jdv) != np ||
          num(sf, "nu") != s->nu || num(sf, "nv") != s->nv;
    for (int p = 0; p < np && !bad; p++) {
        rg2_xpatch X;
        rg2_surface_patch_get(s, p / s->nv, p % s->nv, &X);
        const cJSON *jp = cJSON_GetArrayItem(pa, p);
        bad += cJSON_GetArrayItem(jdu, p)->valueint != X.du || cJSON_GetArrayItem(jdv, p)->valueint != X.dv ||
               cJSON_GetArraySize(jp) != 4 * (X.du + 1) * (X.dv + 1);
        for (int k = 0; k < 4 * (X.du + 1) * (X.dv + 1) && !bad; k++)
            bad += cJSON_GetArrayItem(jp, k)->valuedouble != X.h[k / (4 * (X.dv + 1))][k / 4 % (X.dv + 1)][k % 4];
    }
    CHECK(j && bad == 0, "JSON: %d mismatches", bad);
    cJSON_Delete(j);
    free(b);
}

/* ---------------------------------------------------------------- STEP and IGES text */
static int is_sorted_complex(const char *ent)
{
    /* "( A() B(...) C(...) )": the top-level partial type names must be in ascending order */
    char prev[96] = "", name[96];
    int depth = 0;
    for (const char *p = ent + 1; *p; p++) {
        if (*p == '\'') {
            p = strchr(p + 1, '\'');
            if (!p)
                return 0;
            continue;
        }
        if (*p == '(')
            depth++;
        else if (*p == ')')
            depth--;
        else if (depth == 0 && (*p >= 'A' && *p <= 'Z')) {
            size_t n = strspn(p, "ABCDEFGHIJKLMNOPQRSTUVWXYZ_0123456789");
            if (n >= sizeof name)
                return 0;
            memcpy(name, p, n);
            name[n] = 0;
            if (strcmp(prev, name) >= 0)
                return 0;
            strcpy(prev, name);
            p += n - 1;
        }
    }
    return 1;
}

/* Records of an IGES file: the number of malformed ones (length, section letter, order,
 * sequence numbers (1, 2, ... in each section, right-justified in columns 74-80 with blanks before
 * them), terminate section; -1 if unreadable) and the entity count per type
 * (types[0..999]) from the directory entries. */
static int iges_scan(const char *path, int types[1000])
{
    memset(types, 0, 1000 * sizeof(int));
    FILE *f = fopen(path, "r");
    if (!f)
        return -1;
    char line[256];
    int count[5] = {0}, badline = 0, order = 0;
    const char *letters = "SGDPT";
    while (fgets(line, sizeof line, f)) {
        size_t n = strlen(line);
        if (n != 81 || line[80] != '\n') {
            badline++;
            continue;
        }
        const char *l = strchr(letters, line[72]);
        if (!l) {
            badline++;
            continue;
        }
        int sec = (int)(l - letters);
        if (sec < order)
            badline++;
        order = sec;
        count[sec]++;
        char seq[16]; /* the sequence number right-justified in blanks, as in every section */
        snprintf(seq, sizeof seq, "%7d", count[sec]);
        if (memcmp(line + 73, seq, 7))
            badline++;
        if (sec == 2 && count[2] % 2 == 1) {
            int type = atoi(line);
            if (type > 0 && type < 1000)
                types[type]++;
        }
    }
    fclose(f);
    return badline + (count[4] != 1);
}

/* A surface's STEP, whose vertices, surfaces and edges (face per patch) or the one surface's
 * points, pole list and weights (face per mesh) are formatted on the threads in several batches
 * of blocks (src/step.c, emit_all, put_all_rows), must come out as writing them one after the
 * other does: every entity once, numbered 1, 2, 3, ... in the order of the file, and every
 * reference to an entity written before it. */
static void step_in_order(const rg2_surface *s, int mesh)
{
    rg2_error err;
    rg2_export_opts o;
    rg2_export_opts_default(&o);
    o.layout = mesh ? RG2_STEP_FACE_PER_MESH : RG2_STEP_FACE_PER_PATCH;
    const char *name = mesh ? "bigm.step" : "big.step";
    CHECK_OK(rg2_export_file(s, 1, path_in(name), &o, &err), &err);
    size_t len;
    char *b = (char *)slurp(path_in(name), &len);
    CHECK(b != NULL, "big STEP not read");
    if (!b)
        return;
    int expect = 1, out_of_order = 0, forward = 0, faces = 0, id = 0;
    /* Line by line with memchr and digits read by hand: AddressSanitizer's strstr, strchr and
     * sscanf take the length of the whole remaining 10 MB text at every call (minutes). */
    const char *p = b, *stop = b + len;
    while (p < stop) {
        const char *nl = memchr(p, '\n', (size_t)(stop - p));
        const char *eol = nl ? nl : stop;
        const char *q = p;
        if (*q == '#') { /* an entity starts: "#id=..." */
            int n = 0;
            for (q++; q < eol && *q >= '0' && *q <= '9'; q++)
                n = 10 * n + (*q - '0');
            if (q < eol && *q == '=') {
                id = n;
                out_of_order += id != expect;
                expect = id + 1;
                faces += eol - q > 14 && !memcmp(q + 1, "ADVANCED_FACE", 13);
                q++;
            } else {
                q = p;
            }
        }
        for (; q < eol; q++) /* references on this line of entity id */
            if (*q == '#') {
                int ref = 0;
                for (q++; q < eol && *q >= '0' && *q <= '9'; q++)
                    ref = 10 * ref + (*q - '0');
                forward += ref >= id;
            }
        p = eol + 1;
    }
    int want = mesh ? 1 : s->nu * s->nv;
    CHECK(out_of_order == 0 && forward == 0 && faces == want,
          "big STEP %s: %d entities out of order, %d references forward, %d faces (expected %d)", name, out_of_order,
          forward, faces, want);
    printf("STEP %s of %d x %d patches (written on the threads): %d entities, %d out of order, %d references "
           "forward\n",
           name, s->nu, s->nv, expect - 1, out_of_order, forward);
    free(b);
}

/* The surface of 47 x 47 patches, some of higher degree, in both layouts. */
static void step_big_in_order(void)
{
    rg2_surface s;
    rg2_error err;
    CHECK_OK(fx_random(20261204, 50, 50, &s, &err), &err);
    CHECK_OK(rg2t_elevate_some(&s, 5, 3, 7, 1, &err), &err);
    for (int mesh = 0; mesh < 2; mesh++) /* face per patch, face per mesh (a net of 33 512 points) */
        step_in_order(&s, mesh);
    rg2_surface_free(&s);
}

/* The numbers of an IGES record's parameter columns 1-64 appended to v[*n..cap) (tokens never
 * span records); copies each token before strtod (AddressSanitizer's interceptors would measure
 * the whole remaining text at every call). */
static void iges_record_nums(const char *rec, double *v, int *n, int cap)
{
    char tok[72];
    int t = 0;
    for (int c = 0; c < 64; c++) {
        char ch = rec[c];
        if (ch == ',' || ch == ';') {
            tok[t] = 0;
            if (t && *n < cap)
                v[(*n)++] = strtod(tok, NULL);
            t = 0;
        } else if (ch != ' ') {
            tok[t++] = ch;
        }
    }
}

static int iges_int(const char *p, int w) /* the integer in w columns */
{
    char b[16];
    memcpy(b, p, (size_t)w);
    b[w] = 0;
    return atoi(b);
}

/* The knot vector of n poles of degree d as piecewise Bezier spans ((n - 1) / d of them, an
 * exact number): 0 d + 1 times, then 1, 2, ... d times each, the last d + 1 times. The knots
 * k[0 .. n + d] that differ from it (all n + d + 1 if the spans do not fit). */
static int knots_differ(const double *k, int n, int d)
{
    int spans = (n - 1) / d, bad = 0;
    if (d < 1 || spans * d != n - 1)
        return n + d + 1;
    for (int a = 0; a < n + d + 1; a++)
        bad += k[a] != (a <= d ? 0 : a >= n ? spans : (a - 1) / d);
    return bad;
}

/* The parameter data of every entity of an IGES file as numbers, in one pass (the delimiters
 * dropped; tokens never span records): those of DE pointer de are v[at[de] .. at[de] + n[de]),
 * n[de] 0 for none. 0, or -1 (malformed or out of memory). */
typedef struct {
    double *v;
    int *at, *n, nde;
} iges_nums;

static void iges_nums_free(iges_nums *P)
{
    free(P->v);
    free(P->at);
    free(P->n);
}

static int iges_nums_read(const char *text, size_t len, iges_nums *P)
{
    int nrec = (int)(len / 81), count = 0, cap = 32 * nrec + 1;
    P->nde = nrec + 2;
    P->v = malloc(sizeof(double) * (size_t)cap);
    P->at = calloc((size_t)P->nde, sizeof(int));
    P->n = calloc((size_t)P->nde, sizeof(int));
    if (!P->v || !P->at || !P->n || len % 81)
        return -1;
    for (int k = 0; k < nrec; k++) {
        const char *rec = text + (size_t)k * 81;
        int de = iges_int(rec + 65, 7);
        if (rec[72] != 'P')
            continue;
        if (de < 1 || de >= P->nde || (P->n[de] && P->at[de] + P->n[de] != count))
            return -1;
        if (!P->n[de])
            P->at[de] = count;
        iges_record_nums(rec, P->v, &count, cap);
        P->n[de] = count - P->at[de];
    }
    return 0;
}

/* The DE pointer of the entity whose first directory record is l, if it is of the type (else 0). */
static int iges_dir_of(const char *l, const iges_nums *P, int type)
{
    int de = iges_int(l + 73, 7);
    return l[72] == 'D' && de % 2 == 1 && de < P->nde && iges_int(l, 8) == type ? de : 0;
}

/* p and q (3 coordinates each) the same point but for rounding */
static int near3(const double *p, const double *q)
{
    double d = 0, m = 1;
    for (int c = 0; c < 3; c++) {
        d = fmax(d, fabs(p[c] - q[c]));
        m = fmax(m, fabs(p[c]));
    }
    return d <= 1e-9 * m;
}

/* The point of entity 128 s (its numbers, n of them) at the corner (u, v) of its parameter
 * range (NULL if (u, v) is no corner): that corner's pole. */
static const double *corner_128(const double *s, int n, double u, double v)
{
    int NU = (int)s[1] + 1, NV = (int)s[2] + 1, du = (int)s[3], dv = (int)s[4];
    int w0 = 10 + (NU + du + 1) + (NV + dv + 1);
    if (n != w0 + 4 * NU * NV + 4 || s[0] != 128)
        return NULL;
    const double *r = s + n - 4; /* U0, U1, V0, V1 */
    int a = u == r[0] ? 0 : u == r[1] ? NU - 1 : -1, b = v == r[2] ? 0 : v == r[3] ? NV - 1 : -1;
    return a < 0 || b < 0 ? NULL : s + w0 + NU * NV + 3 * (b * NU + a);
}

/* Every loop (508) of an IGES B-rep file closes: with its orientation flags, each edge use
 * ends at the vertex where the next one starts (edges and vertices from the 504 list). And
 * (*astray counts the faults) every face (510) holds one loop, flagged as its outer one; the
 * shell (514) lists every face once, is of form 1 (closed)
 * exactly when every edge is used twice by the loops (else form 2, open), and every edge runs
 * between its vertices where it is drawn: its model curve (126) from its start vertex's point
 * (502) to its end vertex's (first and last pole), and in each loop its pcurve (110), mapped by
 * the face's surface (128: a corner of the parameter range to that corner's pole), from the
 * use's first vertex to its last; and every pcurve (110) is used by a loop (an unused one is read
 * as a curve of its own, outside the shell). Returns the number of loops checked, -1 for a
 * malformed file, and counts the broken ones. */
static int iges_loops_close(const char *path, int *broken, int *astray)
{
    size_t len;
    char *text = (char *)slurp(path, &len);
    iges_nums P = {0};
    int loops = 0, n504 = 0, n502 = 0, n510 = 0, form = 0, *surf_of = NULL, *type_of = NULL, *euse = NULL,
        *pc_used = NULL;
    const double *el = NULL, *vl = NULL, *sh = NULL;
    *broken = *astray = 0;
    if (!text || iges_nums_read(text, len, &P) || !(surf_of = calloc((size_t)P.nde, sizeof(int))) ||
        !(type_of = calloc((size_t)P.nde, sizeof(int))) || !(pc_used = calloc((size_t)P.nde, sizeof(int)))) {
        loops = -1;
        goto done;
    }
    for (size_t o = 0; o + 81 <= len; o += 81) { /* the directory: 504, 502, and each loop's face */
        const char *l = text + o;
        int type = iges_int(l, 8), de = iges_int(l + 73, 7);
        if (l[72] != 'D' || de % 2 == 0 || de >= P.nde)
            continue;
        const double *v = P.v + P.at[de];
        type_of[de] = type;
        n510 += type == 510;
        if (type == 514) {
            sh = P.n[de] > 2 && P.n[de] == 2 + 2 * (int)v[1] ? v : NULL;
            form = o + 162 <= len ? iges_int(l + 81 + 32, 8) : 0; /* the second record's 5th field */
        }
        if (type == 504)
            n504++, el = v;
        if (type == 502)
            n502++, vl = v;
        if (type == 510 && P.n[de] == 5 && v[4] > 0 && v[4] < P.nde)
            surf_of[(int)v[4]] = (int)v[1];
        /* 510: surface, N loops, outer-loop flag, the N loops: one loop, the outer one */
        if (type == 510)
            *astray += P.n[de] < 4 || P.n[de] != 4 + (int)v[2] || v[2] != 1 || v[3] != 1;
    }
    int ne = el ? (int)el[1] : 0, nv = vl ? (int)vl[1] : 0;
    if (n504 != 1 || n502 != 1 || ne < 1 || nv < 1 || !(euse = calloc((size_t)ne + 1, sizeof(int)))) {
        loops = -1;
        goto done;
    }
    *astray += !sh || (int)sh[1] != n510;
    for (int k = 0; sh && k < (int)sh[1]; k++) { /* each face once: its 510 marked by a negative type */
        int f = (int)sh[2 + 2 * k];
        *astray += f < 1 || f >= P.nde || type_of[f] != 510;
        if (f > 0 && f < P.nde)
            type_of[f] = -type_of[f];
    }
    for (int e = 0; e < ne; e++) { /* curve DE, list, start, list, end */
        const double *u = el + 2 + 5 * e;
        int c = (int)u[0], sv = (int)u[2], tv = (int)u[4];
        const double *cv = c > 0 && c < P.nde ? P.v + P.at[c] : NULL;
        int np = cv ? (int)cv[1] + 1 : 0, deg = cv ? (int)cv[2] : 0, p0 = 7 + (np + deg + 1) + np;
        if (!cv || P.n[c] != p0 + 3 * np + 2 || cv[0] != 126 || knots_differ(cv + 7, np, deg) || sv < 1 || sv > nv || tv < 1 || tv > nv ||
            !near3(cv + p0, vl + 2 + 3 * (sv - 1)) || !near3(cv + p0 + 3 * (np - 1), vl + 2 + 3 * (tv - 1)))
            (*astray)++;
    }
    for (size_t o = 0; o + 81 <= len; o += 81) {
        int de = iges_dir_of(text + o, &P, 508);
        if (!de)
            continue;
        const double *lp = P.v + P.at[de];
        int n = P.n[de], k = n > 1 ? (int)lp[1] : 0, sf = surf_of[de];
        if (k < 1 || k > 8 || n != 2 + 7 * k || sf < 1 || sf >= P.nde) {
            loops = -1;
            break;
        }
        int from[8], to[8];
        for (int q = 0; q < k; q++) {
            const double *u = lp + 2 + 7 * q; /* type, list, index, OF, K, ISOP, pcurve */
            int e = (int)u[2], pc = (int)u[6];
            if (e < 1 || e > ne || pc < 1 || pc >= P.nde) {
                loops = -1;
                break;
            }
            int sv = (int)el[2 + 5 * (e - 1) + 2], tv = (int)el[2 + 5 * (e - 1) + 4];
            euse[e]++;
            pc_used[pc] = 1;
            from[q] = u[3] != 0 ? sv : tv;
            to[q] = u[3] != 0 ? tv : sv;
            const double *line = P.v + P.at[pc], *s = P.v + P.at[sf]; /* 110: x1 y1 z1 x2 y2 z2 */
            const double *a = P.n[pc] == 7 && line[0] == 110 ? corner_128(s, P.n[sf], line[1], line[2]) : NULL;
            const double *b = a ? corner_128(s, P.n[sf], line[4], line[5]) : NULL;
            *astray += !b || from[q] < 1 || from[q] > nv || to[q] < 1 || to[q] > nv ||
                       !near3(a, vl + 2 + 3 * (from[q] - 1)) || !near3(b, vl + 2 + 3 * (to[q] - 1));
        }
        if (loops < 0)
            break;
        int ok = 1;
        for (int q = 0; q < k; q++)
            ok &= to[q] == from[(q + 1) % k];
        *broken += !ok;
        loops++;
    }
    int twice = 1;
    for (int e = 1; e <= ne && euse; e++)
        twice &= euse[e] == 2;
    *astray += form != (twice ? 1 : 2);
    for (int de = 1; de < P.nde; de += 2)
        *astray += type_of[de] == 110 && !pc_used[de];
done:
    free(text);
    free(surf_of);
    free(pc_used);
    free(type_of);
    free(euse);
    iges_nums_free(&P);
    return loops;
}

/* The factor of an IGES entity's weights whose smallest is lo and largest hi (docs/export.md,
 * "IGES"): 1, or, when lo is below 1e-6, the power of two that puts hi in [0.5, 1). */
static double weights_factor(double lo, double hi)
{
    int e;
    frexp(hi, &e);
    return lo < 1e-6 ? ldexp(1.0, -e) : 1.0;
}

/* Mismatches between the numbers v[0..n-1] of an entity 128 and the NU x NV net h (a along u)
 * of degrees (du, dv): its type, upper indices, degrees and count, its knots (piecewise Bezier,
 * knots_differ), then its weights and points (u fastest), and its parameter range (the knots'). */
static double g_min_w128 = INFINITY; /* the smallest weight cmp_128 has read */

static int cmp_128(const double *v, int n, const double (*h)[4], int NU, int NV, int du, int dv)
{
    int w0 = 10 + (NU + du + 1) + (NV + dv + 1), nn = NU * NV, bad = 0; /* after ints and knots */
    if (n != w0 + 4 * nn + 4 || v[0] != 128 || v[1] != NU - 1 || v[2] != NV - 1 || v[3] != du || v[4] != dv)
        return 1;
    bad += knots_differ(v + 10, NU, du) + knots_differ(v + 10 + NU + du + 1, NV, dv);
    bad += v[n - 4] != 0 || v[n - 3] != (NU - 1) / du || v[n - 2] != 0 || v[n - 1] != (NV - 1) / dv;
    /* the weights as they are; or, when the smallest is below 1e-6 (which OpenCASCADE's IGES
     * reader takes for 0), times the power of two that puts the largest in [0.5, 1) */
    double lo = INFINITY, hi = 0;
    for (int k = 0; k < nn; k++) {
        lo = fmin(lo, h[k][3]);
        hi = fmax(hi, h[k][3]);
    }
    double f = weights_factor(lo, hi);
    for (int b = 0; b < NV; b++)
        for (int a = 0; a < NU; a++) {
            const double *p = h[a * NV + b];
            int k = b * NU + a;
            bad += v[w0 + k] != p[3] * f;
            g_min_w128 = fmin(g_min_w128, v[w0 + k]);
            for (int c = 0; c < 3; c++)
                bad += v[w0 + nn + 3 * k + c] != p[c] / p[3];
        }
    return bad;
}

/* The directory and parameter sections of an IGES file agree: entity q's parameter records
 * (its DE record's start and count) carry its DE pointer 2 q + 1, start where entity q - 1's
 * end, and the last ends the section. Returns the disagreements (-1 unreadable) and the
 * entity count. With s, the numbers of every entity are read back (*mismatch counts those
 * that differ): check 1, the plain face-per-patch layout (entity q is patch q's 128); check 2,
 * the plain face-per-mesh layout (entity 0 is the merged net's); check 3, the B-rep face-per-patch
 * layout (entity 5 is the vertex list, the corners of rg2__topo_build's vertices). Linear in the
 * file. */
static int iges_sections_agree(const char *path, int *entities, const rg2_surface *s, int check, int *mismatch)
{
    size_t len;
    char *b = (char *)slurp(path, &len);
    *entities = 0;
    *mismatch = 0;
    int NU = 0, NV = 0, du = 0, dv = 0;
    double(*net)[4] = check == 2 ? rg2__merged_net(s, &NU, &NV, &du, &dv) : NULL;
    rg2__topo t = {0};
    rg2_error err;
    if (check == 3 && rg2__topo_build(s, &t, &err))
        return -1;
    int cap = 64 + 8 * (check == 2 ? NU * NV : check == 3 ? t.n_vertices : 36);
    double *v = malloc(sizeof(double) * (size_t)cap);
    int nrec = 0, d0 = -1, p0 = -1, nd = 0, np = 0, bad = -1;
    if (!b || len % 81 || !v || (check == 2 && !net))
        goto done;
    nrec = (int)(len / 81);
    for (int r = 0; r < nrec; r++) {
        char sec = b[(size_t)r * 81 + 72];
        if (sec == 'D' && !nd++)
            d0 = r;
        if (sec == 'P' && !np++)
            p0 = r;
    }
    if (d0 < 0 || p0 < 0 || nd % 2)
        goto done;
    bad = 0;
    *entities = nd / 2;
    int next = 1;
    for (int q = 0; q < nd / 2; q++) {
        const char *d = b + (size_t)(d0 + 2 * q) * 81;
        int start = iges_int(d + 8, 8), count = iges_int(d + 81 + 24, 8);
        if (start != next || count < 1 || start + count - 1 > np) {
            bad++;
            break;
        }
        next = start + count;
        int n = 0;
        for (int l = start; l < next; l++) {
            const char *rec = b + (size_t)(p0 + l - 1) * 81;
            bad += iges_int(rec + 65, 7) != 2 * q + 1;
            if (check)
                iges_record_nums(rec, v, &n, cap);
        }
        if (check == 3 && q == 5) { /* 502, count, then the points */
            *mismatch += n != 2 + 3 * t.n_vertices || v[0] != 502 || v[1] != t.n_vertices;
            for (int k = 0; k < t.n_vertices && n == 2 + 3 * t.n_vertices; k++) {
                double h[4];
                rg2__corner_affine(&t, s, t.vcorner[k] / (s->nv + 1), t.vcorner[k] % (s->nv + 1), h);
                for (int c = 0; c < 3; c++)
                    *mismatch += v[2 + 3 * k + c] != h[c];
            }
        } else if (check == 2) {
            *mismatch += q > 0 ? 1 : cmp_128(v, n, (const double(*)[4])net, NU, NV, du, dv);
        } else if (check == 1) {
            rg2_xpatch X;
            double h[36][4];
            if (q >= s->nu * s->nv) {
                (*mismatch)++;
                continue;
            }
            rg2_surface_patch_get(s, q / s->nv, q % s->nv, &X);
            rg2__xpatch_net(&X, h);
            *mismatch += cmp_128(v, n, (const double(*)[4])h, X.du + 1, X.dv + 1, X.du, X.dv);
        }
    }
    bad += next != np + 1;
done:
    free(b);
    free(v);
    free(net);
    rg2__topo_free(&t);
    return bad;
}

/* IGES of the same surface, whose entities are formatted on the threads in several rounds of
 * blocks (src/iges.c, emit_items; the vertex list and a whole-mesh net through pw_reals): the
 * records well formed and numbered, the directory pointing at each entity's parameter records,
 * and every patch's weights and points read back exactly. */
static void iges_big(void)
{
    rg2_surface s;
    rg2_error err;
    CHECK_OK(fx_random(20261204, 50, 50, &s, &err), &err);
    CHECK_OK(rg2t_elevate_some(&s, 5, 3, 7, 1, &err), &err);
    /* plain and B-rep, face per patch and per mesh */
    const char *name[4] = {"big.igs", "bigb.igs", "bigm.igs", "bigbm.igs"};
    int np = s.nu * s.nv;
    for (int k = 0; k < 4; k++) {
        rg2_export_opts o;
        rg2_export_opts_default(&o);
        o.iges_brep = k & 1;
        o.layout = k & 2 ? RG2_STEP_FACE_PER_MESH : RG2_STEP_FACE_PER_PATCH;
        CHECK_OK(rg2_export_file(&s, 1, path_in(name[k]), &o, &err), &err);
        int types[1000], badline = iges_scan(path_in(name[k]), types);
        int n, mismatch, bad = iges_sections_agree(path_in(name[k]), &n, &s, (int[]){1, 3, 2, 0}[k], &mismatch);
        int faces = k & 1 ? types[510] : types[128], want = k & 2 ? 1 : np;
        CHECK(badline == 0 && bad == 0 && mismatch == 0 && faces == want,
              "big IGES %s: %d malformed records, %d directory/parameter disagreements, %d numbers not read "
              "back, %d faces (expected %d)",
              name[k], badline, bad, mismatch, faces, want);
        printf("IGES %s of %d x %d patches (written on the threads): %d entities, %d malformed records, %d "
               "disagreements, %d numbers not read back\n",
               name[k], s.nu, s.nv, n, badline, bad, mismatch);
    }
    rg2_surface_free(&s);
}

/* A surface whose 4-tuples are all multiplied by 1e-10 (rg2_surface_transform: the same torus,
 * weights about 1e-10): OpenCASCADE's IGES reader took its entities' weights, all below its 1e-9,
 * for non-positive ones and made every one 1 (the faces 1.5e-3 of the size off, no message;
 * tests/occt/test_import.cpp). The
 * IGES writer multiplies such an entity's weights by a power of two (exactly the same surface):
 * the plain layouts read back with every weight at least 0.25 (the torus's own weights span
 * 0.5 .. 1 of each other), the points as written before. */
static void iges_small_weights(void)
{
    rg2_surface s;
    rg2_error err;
    CHECK_OK(fx_torus(13.0, 4.0, 6, 4, &s, &err), &err);
    double M[16] = {1e-10, 0, 0, 0, 0, 1e-10, 0, 0, 0, 0, 1e-10, 0, 0, 0, 0, 1e-10};
    rg2_surface_transform(&s, M);
    double wmin = rg2_surface_min_weight(&s);
    for (int per_mesh = 0; per_mesh < 2; per_mesh++) {
        rg2_export_opts o;
        rg2_export_opts_default(&o);
        o.layout = per_mesh ? RG2_STEP_FACE_PER_MESH : RG2_STEP_FACE_PER_PATCH;
        CHECK_OK(rg2_export_file(&s, 1, path_in("smallw.igs"), &o, &err), &err);
        g_min_w128 = INFINITY;
        int n, mismatch, bad = iges_sections_agree(path_in("smallw.igs"), &n, &s, per_mesh ? 2 : 1, &mismatch);
        CHECK(bad == 0 && mismatch == 0 && g_min_w128 >= 0.25,
              "IGES %s of a torus with weights from %.3g: %d disagreements, %d numbers not as rg2's (weights times "
              "a power of two), smallest weight written %.3g",
              per_mesh ? "per mesh" : "per patch", wmin, bad, mismatch, g_min_w128);
        printf("IGES %s of a torus with weights from %.3g: smallest weight written %.3g, %d numbers not as rg2's\n",
               per_mesh ? "per mesh" : "per patch", wmin, g_min_w128, mismatch);
    }
    remove(path_in("smallw.igs"));
    rg2_surface_free(&s);
}

/* The model curves (126) of an IGES B-rep file against s, read back: each must be the row of
 * control points along a side of one of s's patches, in either direction, with its knots
 * piecewise Bezier (knots_differ), its poles the row's points h / w and its weights the row's,
 * or, when the row's smallest weight is below 1e-6, the row's times the power of two that puts
 * its largest in [0.5, 1) (docs/export.md, "IGES"). Returns the curves that are none (-1 if the
 * file does not read) and counts them (*curves). */
static int iges_126_rows(const char *path, const rg2_surface *s, int *curves)
{
    size_t len;
    char *text = (char *)slurp(path, &len);
    iges_nums P = {0};
    int bad = 0;
    *curves = 0;
    if (!text || iges_nums_read(text, len, &P)) {
        bad = -1;
        goto done;
    }
    for (size_t o = 0; o + 81 <= len; o += 81) {
        int de = iges_dir_of(text + o, &P, 126);
        if (!de)
            continue;
        /* 126, K, M, 4 flags, K + M + 2 knots, K + 1 weights, the K + 1 poles, V0, V1 */
        const double *cv = P.v + P.at[de];
        int np = P.n[de] > 3 ? (int)cv[1] + 1 : 0, deg = np ? (int)cv[2] : 0, w0 = 7 + np + deg + 1;
        (*curves)++;
        if (np < 2 || np > RG2_MAX_DEGREE + 1 || P.n[de] != w0 + 4 * np + 2 || cv[0] != 126 ||
            knots_differ(cv + 7, np, deg)) {
            bad++;
            continue;
        }
        int found = 0;
        for (int p = 0; p < s->nu * s->nv && !found; p++) {
            rg2_xpatch X;
            rg2_surface_patch_get(s, p / s->nv, p % s->nv, &X);
            for (int side = 0; side < 4 && !found; side++) { /* v = 0, u = 1, v = 1, u = 0 */
                int n = (side & 1 ? X.dv : X.du) + 1;
                const double *row[RG2_MAX_DEGREE + 1];
                double lo = INFINITY, hi = 0;
                for (int a = 0; a < n; a++) {
                    row[a] = side == 0 ? X.h[a][0] : side == 1 ? X.h[X.du][a] : side == 2 ? X.h[a][X.dv] : X.h[0][a];
                    lo = fmin(lo, row[a][3]);
                    hi = fmax(hi, row[a][3]);
                }
                double f = weights_factor(lo, hi);
                for (int dir = 0; dir < 2 && n == np && !found; dir++) {
                    int same = 1;
                    for (int a = 0; a < n; a++) {
                        const double *h = row[dir ? n - 1 - a : a];
                        same &= cv[w0 + a] == h[3] * f;
                        for (int c = 0; c < 3; c++)
                            same &= cv[w0 + np + 3 * a + c] == h[c] / h[3];
                    }
                    found = same;
                }
            }
        }
        bad += !found;
    }
done:
    free(text);
    iges_nums_free(&P);
    return bad;
}

/* The same rule where one control point alone has a small weight: the torus with the 4-tuple of
 * patch (0, 0)'s control point [0][1] on its u = 0 side, and of the same point [3][1] of patch
 * (nu - 1, 0) across that seam, times 2^-24 (the same point, a weight of about 5e-8 among
 * weights of about 1). The surfaces (128) that hold it, the patch's (plain, face per patch) and
 * the merged net's (face per mesh), and the model curve (126) of the seam (B-rep), written with
 * every weight times the factor, and every other entity with its own weights. */
static void iges_one_small_weight(void)
{
    rg2_surface s;
    rg2_error err;
    CHECK_OK(fx_torus(13.0, 4.0, 6, 4, &s, &err), &err);
    int q = (s.nu - 1) * s.nv;
    for (int c = 0; c < 4; c++) {
        s.patch[0].h[0][1][c] = ldexp(s.patch[0].h[0][1][c], -24);
        s.patch[q].h[3][1][c] = ldexp(s.patch[q].h[3][1][c], -24);
    }
    static const char *const form[3] = {"plain, face per patch", "plain, face per mesh", "B-rep, face per patch"};
    for (int k = 0; k < 3; k++) {
        rg2_export_opts o;
        rg2_export_opts_default(&o);
        o.layout = k == 1 ? RG2_STEP_FACE_PER_MESH : RG2_STEP_FACE_PER_PATCH;
        o.iges_brep = k == 2;
        CHECK_OK(rg2_export_file(&s, 1, path_in("onew.igs"), &o, &err), &err);
        int n = 0, mismatch = 0, curves = 0, want = k == 2 ? 2 * s.nu * s.nv : 0;
        int bad = k < 2 ? iges_sections_agree(path_in("onew.igs"), &n, &s, k + 1, &mismatch)
                        : iges_126_rows(path_in("onew.igs"), &s, &curves);
        CHECK(bad == 0 && mismatch == 0 && curves == want,
              "IGES %s of a torus with one weight of %.3g: %d disagreements, %d numbers of its surfaces and %d of "
              "%d model curves not as rg2's (weights times a power of two where one is below 1e-6)",
              form[k], s.patch[0].h[0][1][3], k < 2 ? bad : 0, mismatch, k < 2 ? 0 : bad, curves);
    }
    remove(path_in("onew.igs"));
    rg2_surface_free(&s);
}

/* ---------------------------------------------------------------- STEP B-rep read back */
/* A STEP file's DATA section as entities by id: ent[id] is the text after "#id=" up to its ';'
 * (made the end of the string), NULL where no entity has that id. */
typedef struct {
    char *text;
    char **ent;
    int n; /* ids 0 .. n-1 */
} step_ents;

static void step_unload(step_ents *f)
{
    free(f->text);
    free(f->ent);
}

static int step_load(const char *path, step_ents *f)
{
    size_t len;
    memset(f, 0, sizeof *f);
    f->text = (char *)slurp(path, &len);
    char *p = f->text ? strstr(f->text, "DATA;\n") : NULL;
    if (!p)
        return -1;
    f->n = (int)len; /* ids < bytes */
    f->ent = calloc(len, sizeof(char *));
    for (p += 6; f->ent && *p == '#';) {
        char *e = strstr(p, ";\n"), *eq = strchr(p, '=');
        int id = atoi(p + 1);
        if (!e || !eq || eq > e || id <= 0 || id >= f->n || f->ent[id])
            return -1;
        *e = 0;
        f->ent[id] = eq + 1;
        p = e + 2;
    }
    return f->ent && !strncmp(p, "ENDSEC;", 7) ? 0 : -1;
}

/* Entity id if it is of the type (its text starts with type, e.g. "VERTEX_POINT("), else NULL. */
static const char *step_ent(const step_ents *f, int id, const char *type)
{
    const char *e = id > 0 && id < f->n ? f->ent[id] : NULL;
    return e && !strncmp(e, type, strlen(type)) ? e : NULL;
}

/* The references #id in s (up to end, or its end if NULL), in order (at most cap). */
static int step_refs(const char *s, const char *end, int *ref, int cap)
{
    int n = 0;
    for (const char *p = s; p && *p && (!end || p < end); p++)
        if (*p == '#' && n < cap)
            ref[n++] = atoi(p + 1);
    return n;
}

static int step_point(const step_ents *f, int id, double p[3])
{
    const char *e = step_ent(f, id, "CARTESIAN_POINT(");
    return e && sscanf(e, "CARTESIAN_POINT('',(%lf,%lf,%lf))", &p[0], &p[1], &p[2]) == 3 ? 0 : -1;
}

/* The numbers of the list "(a,b,...)" at *p (-1 if none), *p moved past it. */
static int step_nums(const char **p, double *v, int cap)
{
    const char *q = *p;
    int n = 0;
    while (*q == '\n' || *q == ' ')
        q++;
    if (*q != '(')
        return -1;
    for (q++; *q != ')'; q++) {
        char *end;
        double x = strtod(q, &end);
        if (end == q || n >= cap)
            return -1;
        v[n++] = x;
        q = end;
        while (*q == '\n' || *q == ' ')
            q++;
        if (*q != ',' && *q != ')')
            return -1;
        if (*q == ')')
            break;
    }
    *p = q + 1;
    return n;
}

/* A clamped piecewise knot vector: the multiplicities m[0..nm) and knot values k[0..nk) of n
 * poles of degree deg: as many of each, deg + 1 at the ends and 1 .. deg inside, increasing
 * values, multiplicities summing to n + deg + 1. Returns the faults. */
static int knots_bad(const double *m, int nm, const double *k, int nk, int n, int deg)
{
    double sum = 0;
    int bad = nm != nk || nm < 2 || m[0] != deg + 1 || m[nm - 1] != deg + 1;
    for (int a = 0; a < nm; a++) {
        sum += m[a];
        bad += a > 0 && a < nm - 1 && (m[a] < 1 || m[a] > deg);
        bad += a > 0 && a < nk && !(k[a] > k[a - 1]);
    }
    return bad + (sum != n + deg + 1);
}

/* The knot vectors of the B-spline curve or surface e (number of poles counted in its pole
 * lists, weights one per pole): the faults, 0 if e is neither. */
static int step_spline_bad(const char *e)
{
    double m[2][64], k[2][64], wt[64];
    int nm[2], nk[2], deg[2], n[2];
    const char *c = strstr(e, "B_SPLINE_CURVE("), *s = strstr(e, "B_SPLINE_SURFACE(");
    const char *kn = strstr(e, c ? "B_SPLINE_CURVE_WITH_KNOTS(" : "B_SPLINE_SURFACE_WITH_KNOTS(");
    int refs[4096], dirs = s ? 2 : 1;
    if (!c && !s)
        return 0;
    if (!kn || (c && sscanf(c, "B_SPLINE_CURVE(%d,", &deg[0]) != 1) ||
        (s && sscanf(s, "B_SPLINE_SURFACE(%d,%d,", &deg[0], &deg[1]) != 2))
        return 1;
    int np = step_refs(c ? c : s, kn, refs, 4096), rows = 0;
    for (const char *p = s; s && p < kn && (p = strstr(p, "(#")) && p < kn; p++)
        rows++;
    n[0] = s ? rows : np;
    n[1] = rows ? np / rows : 0;
    const char *p = kn + strlen(c ? "B_SPLINE_CURVE_WITH_KNOTS" : "B_SPLINE_SURFACE_WITH_KNOTS") + 1;
    for (int d = 0; d < dirs; d++, p++)
        nm[d] = step_nums(&p, m[d], 64);
    for (int d = 0; d < dirs; d++, p++)
        nk[d] = step_nums(&p, k[d], 64);
    int bad = s && rows * n[1] != np;
    for (int d = 0; d < dirs; d++)
        bad += nm[d] < 0 || nk[d] < 0 || knots_bad(m[d], nm[d], k[d], nk[d], n[d], deg[d]);
    /* the weights: one list of n (curve), or rows lists of n[1] (surface) */
    const char *w = strstr(e, c ? "RATIONAL_B_SPLINE_CURVE(" : "RATIONAL_B_SPLINE_SURFACE((");
    if (!w)
        return bad + 1;
    p = strchr(w, '(') + (s ? 2 : 1); /* the list (of rows) */
    for (int r = 0; r < (s ? n[0] : 1); r++, p++)
        bad += step_nums(&p, wt, 64) != (s ? n[1] : n[0]);
    return bad;
}

/* The poles of the B-spline curve a SURFACE_CURVE or SEAM_CURVE sc refers to, first and last
 * (a, b), and its pcurves pc[0 .. *npc). 0, or -1 if not so. */
static int step_edge_curve(const step_ents *f, int sc, double a[3], double b[3], int pc[2], int *npc)
{
    const char *e = step_ent(f, sc, "SURFACE_CURVE(");
    e = e ? e : step_ent(f, sc, "SEAM_CURVE(");
    int ref[3], pt[64];
    int n = e ? step_refs(e, NULL, ref, 3) : 0;
    const char *c = n >= 2 ? step_ent(f, ref[0], "( BOUNDED_CURVE() B_SPLINE_CURVE(") : NULL;
    int np = c ? step_refs(c, strstr(c, "B_SPLINE_CURVE_WITH_KNOTS("), pt, 64) : 0;
    *npc = n - 1;
    for (int k = 1; k < n; k++)
        pc[k - 1] = ref[k];
    return np >= 2 && !step_point(f, pt[0], a) && !step_point(f, pt[np - 1], b) ? 0 : -1;
}

static int step_vertex(const step_ents *f, int id, double p[3])
{
    const char *e = step_ent(f, id, "VERTEX_POINT(");
    int ref;
    return e && step_refs(e, NULL, &ref, 1) == 1 ? step_point(f, ref, p) : -1;
}

/* What step_brep read from a STEP file. */
typedef struct {
    int faces, edges, uses;   /* ADVANCED_FACEs, EDGE_CURVEs, ORIENTED_EDGEs in loops */
    int closed_shells, open_shells;
    int bad_knots;    /* curves and surfaces whose knots do not fit their poles and degrees */
    int bad_ends;     /* edge ends: a vertex not at its curve's end, or not a corner of s */
    int bad_pcurves;  /* edges with other pcurves than one on each face using them */
    int open_loops;   /* loops whose oriented edges do not follow each other */
    int twice;        /* edges used by exactly two oriented edges */
    int seams;        /* SEAM_CURVEs (both pcurves on one surface) */
    int bad_seams;    /* a SEAM_CURVE whose pcurves lie on two surfaces or one, or a SURFACE_CURVE whose
                         two lie on one (ISO 10303-42: a seam curve is one whose two associated
                         geometries are on the same surface) */
} step_brep_read;

/* |p - q| (Euclidean), p a STEP point, q homogeneous. */
static double dist_h(const double p[3], const double q[4])
{
    return sqrt(pow(p[0] - q[0] / q[3], 2) + pow(p[1] - q[1] / q[3], 2) + pow(p[2] - q[2] / q[3], 2));
}

/* The faces' loops, edges, vertices and pcurves of a STEP file of surface s read back: each
 * loop's oriented edges run end to start; each edge's vertices are its curve's end points and
 * corners of s's patches (their corner control points); each edge carries one PCURVE on each
 * face's surface that uses it (a seam's two on one surface). -1 if the file does not parse. */
static int step_brep(const char *path, const rg2_surface *s, step_brep_read *r)
{
    step_ents f;
    memset(r, 0, sizeof *r);
    if (step_load(path, &f)) {
        step_unload(&f);
        return -1;
    }
    int *uses = calloc((size_t)f.n, sizeof(int)), *esurf = calloc(2 * (size_t)f.n, sizeof(int)), ok = uses && esurf;
    double tol = 1e-9 * rg2t_surface_scale(s);
    for (int id = 1; ok && id < f.n; id++) {
        const char *e = f.ent[id];
        if (!e)
            continue;
        r->bad_knots += step_spline_bad(e) != 0;
        r->closed_shells += !strncmp(e, "CLOSED_SHELL(", 13);
        r->open_shells += !strncmp(e, "OPEN_SHELL(", 11);
        if (strncmp(e, "ADVANCED_FACE(", 14))
            continue;
        /* the face: its bound, loop, oriented edges */
        int ref[2], lp, oe[8], from[8], to[8];
        const char *b = step_refs(e, NULL, ref, 2) == 2 ? step_ent(&f, ref[0], "FACE_OUTER_BOUND(") : NULL;
        const char *l = b && step_refs(b, NULL, &lp, 1) == 1 ? step_ent(&f, lp, "EDGE_LOOP(") : NULL;
        int n = l ? step_refs(l, NULL, oe, 8) : 0;
        r->faces++;
        for (int k = 0; k < n; k++) {
            const char *o = step_ent(&f, oe[k], "ORIENTED_EDGE('',*,*,#");
            int ed = o ? atoi(o + 22) : 0, v[3];
            const char *ec = step_ent(&f, ed, "EDGE_CURVE(");
            if (!ec || step_refs(ec, NULL, v, 3) != 3) {
                n = 0; /* (an open loop) */
                break;
            }
            int fwd = strstr(o, ",.T.)") != NULL;
            from[k] = fwd ? v[0] : v[1];
            to[k] = fwd ? v[1] : v[0];
            if (uses[ed] < 2)
                esurf[2 * ed + uses[ed]] = ref[1];
            uses[ed]++;
            r->uses++;
        }
        int open = n == 0;
        for (int k = 0; k < n; k++)
            open |= to[k] != from[(k + 1) % n];
        r->open_loops += open;
    }
    for (int id = 1; ok && id < f.n; id++) {
        const char *e = step_ent(&f, id, "EDGE_CURVE(");
        int v[3], pc[2], npc;
        double p0[3], p1[3], a[3], b[3];
        if (!e)
            continue;
        r->edges++;
        r->twice += uses[id] == 2;
        if (step_refs(e, NULL, v, 3) != 3 || step_vertex(&f, v[0], p0) || step_vertex(&f, v[1], p1) ||
            step_edge_curve(&f, v[2], a, b, pc, &npc)) {
            r->bad_ends++;
            continue;
        }
        double corner[2] = {INFINITY, INFINITY}; /* each vertex's distance from the nearest patch corner */
        for (int i = 0; i < s->nu; i++)
            for (int j = 0; j < s->nv; j++) {
                rg2_xpatch X;
                rg2_surface_patch_get(s, i, j, &X);
                for (int c = 0; c < 4; c++) {
                    const double *h = X.h[c & 1 ? X.du : 0][c & 2 ? X.dv : 0];
                    corner[0] = fmin(corner[0], dist_h(p0, h));
                    corner[1] = fmin(corner[1], dist_h(p1, h));
                }
            }
        double ends = fmax(fmax(fabs(p0[0] - a[0]), fabs(p0[1] - a[1])), fabs(p0[2] - a[2]));
        ends = fmax(ends, fmax(fmax(fabs(p1[0] - b[0]), fabs(p1[1] - b[1])), fabs(p1[2] - b[2])));
        r->bad_ends += !(ends <= tol && corner[0] <= tol && corner[1] <= tol);
        /* one pcurve per use, on the surfaces of the faces using the edge (as a multiset) */
        int nuse = uses[id] < 2 ? uses[id] : 2, surf[2] = {0, 0}, badp = npc != uses[id];
        for (int k = 0; k < npc && k < 2 && !badp; k++) {
            const char *q = step_ent(&f, pc[k], "PCURVE(");
            surf[k] = q ? atoi(strchr(q, '#') + 1) : -1;
        }
        if (!badp && nuse == 2)
            badp = !((surf[0] == esurf[2 * id] && surf[1] == esurf[2 * id + 1]) ||
                     (surf[0] == esurf[2 * id + 1] && surf[1] == esurf[2 * id]));
        else if (!badp && nuse == 1)
            badp = surf[0] != esurf[2 * id];
        r->bad_pcurves += badp;
        int seam = step_ent(&f, v[2], "SEAM_CURVE(") != NULL;
        r->seams += seam;
        r->bad_seams += seam != (npc == 2 && surf[0] > 0 && surf[0] == surf[1]);
    }
    free(uses);
    free(esurf);
    step_unload(&f);
    return ok ? 0 : -1;
}

/* The STEP B-rep of s in a layout read back (step_brep): faces as many as patches (one per
 * mesh), knots fitting every curve and surface, each edge between the corners at its curve's
 * ends, one pcurve per face using it, the loops closed; and a CLOSED_SHELL exactly when s is
 * closed (want_closed: a torus; a surface with a boundary is open), which is when every edge
 * bounds two faces. The IGES B-rep likewise (iges_loops_close). */
static void brep_case(const rg2_surface *s, int per_mesh, int want_closed, const char *what)
{
    rg2_error err;
    rg2_export_opts o;
    rg2_export_opts_default(&o);
    o.layout = per_mesh ? RG2_STEP_FACE_PER_MESH : RG2_STEP_FACE_PER_PATCH;
    CHECK_OK(rg2_export_file(s, 1, path_in("brep.step"), &o, &err), &err);
    step_brep_read r;
    int st = step_brep(path_in("brep.step"), s, &r), want_faces = per_mesh ? 1 : s->nu * s->nv;
    CHECK(st == 0 && r.faces == want_faces && r.edges > 0 && !r.bad_knots && !r.bad_ends && !r.bad_pcurves &&
              !r.open_loops,
          "STEP %s %s: read %d, %d faces (want %d), %d edges: knots wrong in %d curves/surfaces, %d edges not "
          "between their vertices, %d with wrong pcurves, %d open loops",
          what, per_mesh ? "per mesh" : "per patch", st, r.faces, want_faces, r.edges, r.bad_knots, r.bad_ends,
          r.bad_pcurves, r.open_loops);
    CHECK(r.closed_shells == want_closed && r.open_shells == !want_closed && (r.twice == r.edges) == want_closed,
          "STEP %s %s: %d closed and %d open shells, %d of %d edges bound two faces (closed: %d)", what,
          per_mesh ? "per mesh" : "per patch", r.closed_shells, r.open_shells, r.twice, r.edges, want_closed);
    /* a SEAM_CURVE where both pcurves lie on one surface (per mesh: a closed direction's seam;
     * per patch no edge, every surface here having two patches or more a direction), else a
     * SURFACE_CURVE */
    int want_seams = per_mesh ? s->closed_u + s->closed_v : 0;
    CHECK(r.seams == want_seams && r.bad_seams == 0,
          "STEP %s %s: %d SEAM_CURVEs (want %d), %d edges whose curve is not a SEAM_CURVE exactly when both its "
          "pcurves lie on one surface",
          what, per_mesh ? "per mesh" : "per patch", r.seams, want_seams, r.bad_seams);
    o.iges_brep = 1;
    CHECK_OK(rg2_export_file(s, 1, path_in("brep.igs"), &o, &err), &err);
    int broken, astray, loops = iges_loops_close(path_in("brep.igs"), &broken, &astray);
    CHECK(loops == want_faces && broken == 0 && astray == 0,
          "IGES B-rep %s %s: %d loops (want %d), %d not closing, %d faults of the shell's faces, edge curves or "
          "pcurves",
          what, per_mesh ? "per mesh" : "per patch", loops, want_faces, broken, astray);
}

/* Patches of degree below 3, which rg2_xpatch allows (1 <= du, dv): a surface of 3 x 2 patches
 * of degree (2, 1), cut from one C0 net of random points and weights (neighbours share their
 * boundary rows), read back as B-reps in STEP and IGES, face per patch (brep_case): the knots of
 * every surface and edge curve fit its poles and degrees (one Bezier span: multiplicities du + 1
 * and dv + 1, summing to the poles plus the degree plus 1). */
static void low_degrees(void)
{
    rg2_surface s;
    rg2_error err;
    CHECK_OK(fx_random(11, 6, 5, &s, &err), &err); /* 3 x 2 patches, open */
    enum { DU = 2, DV = 1 };
    double net[DU * 3 + 1][DV * 2 + 1][4];
    rg2t_rng r;
    rg2t_seed(&r, 11);
    for (int a = 0; a <= DU * 3; a++)
        for (int b = 0; b <= DV * 2; b++) {
            double W = rg2t_uniform(&r, 0.6, 1.5);
            net[a][b][0] = W * (5.0 * a + rg2t_uniform(&r, -1, 1));
            net[a][b][1] = W * (10.0 * b + rg2t_uniform(&r, -1, 1));
            net[a][b][2] = W * rg2t_uniform(&r, -3, 3);
            net[a][b][3] = W;
        }
    CHECK(s.nu == 3 && s.nv == 2 && !s.xp && (s.xp = calloc(6, sizeof(rg2_xpatch))), "low degrees: 3 x 2 patches");
    for (int k = 0; s.xp && k < 6; k++) {
        int i = k / s.nv, j = k % s.nv;
        s.xp[k].du = DU;
        s.xp[k].dv = DV;
        for (int a = 0; a <= DU; a++)
            for (int b = 0; b <= DV; b++)
                memcpy(s.xp[k].h[a][b], net[DU * i + a][DV * j + b], sizeof(double[4]));
        for (int a = 0; a < 4; a++)
            for (int b = 0; b < 4; b++)
                for (int c = 0; c < 4; c++)
                    s.patch[k].h[a][b][c] = NAN;
    }
    if (s.xp)
        brep_case(&s, 0, 0, "degrees (2, 1)");
    rg2_surface_free(&s);
}

/* The STEP and IGES B-reps read back for a closed torus, an open random surface with patches of degrees (5, 3)
 * (the merged net's degrees differ in u and v), a surface with a pole, in both layouts. */
static void breps_read_back(const rg2_surface *torus)
{
    rg2_surface open, pole;
    rg2_error err;
    CHECK_OK(fx_random(7, 5, 4, &open, &err), &err);
    CHECK_OK(rg2t_elevate_some(&open, 5, 3, 3, 1, &err), &err);
    CHECK_OK(fx_pole(6, 5, &pole, &err), &err);
    for (int per_mesh = 0; per_mesh < 2; per_mesh++) {
        brep_case(torus, per_mesh, 1, "torus");
        brep_case(&open, per_mesh, 0, "open (5, 3)");
        brep_case(&pole, per_mesh, 0, "pole");
    }
    low_degrees();
    rg2_surface_free(&open);
    rg2_surface_free(&pole);
}

static void step_text(const rg2_surface *s)
{
    rg2_error err;
    CHECK_OK(export_one(s, "t.step", &err), &err);
    size_t len;
    char *b = (char *)slurp(path_in("t.step"), &len);
    CHECK(b && !strncmp(b, "ISO-10303-21;", 13) && strstr(b, "END-ISO-10303-21;"), "STEP: envelope");
    if (!b)
        return;
    int complex = 0, unsorted = 0, badnum = 0, faces = 0;
    int ecurves = 0, scurves = 0, pcurves = 0, oedges = 0, edge_sc = 0;
    char *is_sc = calloc(len, 1); /* by entity id: a SURFACE_CURVE or SEAM_CURVE */
    char *data = strstr(b, "DATA;");
    for (char *p = data; p && *p;) {
        char *e = strstr(p, ";\n");
        if (!e)
            break;
        *e = 0;
        char *eq = strchr(p, '=');
        if (eq && eq[1] == '(') {
            complex++;
            unsorted += !is_sorted_complex(eq + 1);
        }
        if (eq && !strncmp(eq + 1, "ADVANCED_FACE", 13))
            faces++;
        if (eq) {
            ecurves += !strncmp(eq + 1, "EDGE_CURVE(", 11);
            int sc = !strncmp(eq + 1, "SURFACE_CURVE(", 14) || !strncmp(eq + 1, "SEAM_CURVE(", 11), id = 0;
            scurves += sc;
            if (is_sc && sscanf(p, "#%d=", &id) == 1 && id > 0 && (size_t)id < len) /* ids < bytes */
                is_sc[id] = (char)sc;
            pcurves += !strncmp(eq + 1, "PCURVE(", 7);
            oedges += !strncmp(eq + 1, "ORIENTED_EDGE(", 14);
            if (!strncmp(eq + 1, "EDGE_CURVE(", 11)) { /* its curve: the 4th argument */
                int cid = 0;
                char *c = eq;
                for (int k = 0; k < 3 && c; k++)
                    c = strchr(c + 1, ',');
                if (is_sc && c && sscanf(c + 1, "#%d", &cid) == 1 && cid > 0 && (size_t)cid < len)
                    edge_sc += is_sc[cid]; /* (written before the edge) */
            }
        }
        /* numbers outside strings: a real needs '.', and exponents are upper case */
        for (char *q = eq ? eq : p; *q; q++) {
            if (*q == '\'') {
                q = strchr(q + 1, '\'');
                if (!q)
                    break;
                continue;
            }
            if (*q == '#') {
                q += strspn(q + 1, "0123456789");
                continue;
            }
            if ((*q >= '0' && *q <= '9') && !(q[-1] >= 'A' && q[-1] <= 'Z') && q[-1] != '_') {
                size_t n = strspn(q, "0123456789.eE+-");
                int has_e = memchr(q, 'e', n) || memchr(q, 'E', n), has_dot = memchr(q, '.', n) != NULL;
                if (memchr(q, 'e', n) || (has_e && !has_dot))
                    badnum++;
                q += n - 1;
            }
        }
        p = e + 2;
    }
    CHECK(complex >= 2 * s->nu * s->nv && unsorted == 0, "STEP: %d complex instances, %d not in alphabetical order",
          complex, unsorted);
    CHECK(badnum == 0, "STEP: %d malformed reals", badnum);
    CHECK(faces == s->nu * s->nv, "STEP: %d ADVANCED_FACEs, expected %d", faces, s->nu * s->nv);
    /* every edge a SURFACE_CURVE with one PCURVE per face it bounds: one per use in a loop */
    CHECK(ecurves > 0 && edge_sc == ecurves && scurves == ecurves && pcurves == oedges,
          "STEP: %d edges, %d on surface curves (%d written), %d pcurves for %d edge uses", ecurves, edge_sc,
          scurves, pcurves, oedges);
    free(is_sc);
    free(b);

    CHECK_OK(export_one(s, "t.igs", &err), &err);
    int types[1000], badline = iges_scan(path_in("t.igs"), types);
    CHECK(badline == 0, "IGES: %d malformed records", badline);
    CHECK(types[128] == s->nu * s->nv, "IGES: %d entities 128, expected %d", types[128], s->nu * s->nv);

    /* the B-rep form: one shell; a face, loop and surface per patch; one vertex list and one
     * edge list; a model curve (126) per edge, as many as the STEP file's edges; the four pcurve
     * lines (110) shared by all loops (OpenCASCADE reads it back in tests/occt) */
    rg2_export_opts o;
    rg2_export_opts_default(&o);
    o.iges_brep = 1;
    CHECK_OK(rg2_export_file(s, 1, path_in("b.igs"), &o, &err), &err);
    badline = iges_scan(path_in("b.igs"), types);
    int np = s->nu * s->nv;
    CHECK(badline == 0 && types[514] == 1 && types[510] == np && types[508] == np && types[128] == np &&
              types[502] == 1 && types[504] == 1 && types[110] == 4 && types[126] == ecurves,
          "IGES B-rep: %d malformed records; entities 514 %d, 510 %d, 508 %d, 128 %d, 502 %d, 504 %d, 110 %d, "
          "126 %d (STEP edges %d)",
          badline, types[514], types[510], types[508], types[128], types[502], types[504], types[110], types[126],
          ecurves);
    int broken, astray, loops = iges_loops_close(path_in("b.igs"), &broken, &astray);
    CHECK(loops == np && broken == 0 && astray == 0,
          "IGES B-rep: %d loops read (expected %d), %d do not close with their edge orientations, %d faults of "
          "the shell's faces, edge curves or pcurves",
          loops, np, broken, astray);
    /* face per mesh: one face on the merged net, its seams used twice by its loop */
    o.layout = RG2_STEP_FACE_PER_MESH;
    CHECK_OK(rg2_export_file(s, 1, path_in("bm.igs"), &o, &err), &err);
    badline = iges_scan(path_in("bm.igs"), types);
    int edges = (s->closed_u ? 1 : 2) + (s->closed_v ? 1 : 2); /* (this surface has no pole) */
    CHECK(badline == 0 && types[514] == 1 && types[510] == 1 && types[508] == 1 && types[128] == 1 &&
              types[502] == 1 && types[504] == 1 && types[110] == 4 && types[126] == edges,
          "IGES B-rep per mesh: %d malformed records; entities 514 %d, 510 %d, 508 %d, 128 %d, 502 %d, 504 %d, "
          "110 %d, 126 %d (expected %d)",
          badline, types[514], types[510], types[508], types[128], types[502], types[504], types[110], types[126],
          edges);
    loops = iges_loops_close(path_in("bm.igs"), &broken, &astray);
    CHECK(loops == 1 && broken == 0 && astray == 0, "IGES B-rep per mesh: %d loops, %d do not close, %d astray",
          loops, broken, astray);
}

/* ---------------------------------------------------------------- degrees in STEP and IGES */
static int g_deg_checked;

/* Degree of patch (i, j) (any kind) in u (dir 0) or v (dir 1). */
static int pdeg(const rg2_surface *s, int i, int j, int dir)
{
    rg2_xpatch X;
    rg2_surface_patch_get(s, i, j, &X);
    return dir ? X.dv : X.du;
}

/* Counts of "B_SPLINE_SURFACE(a,b," and "B_SPLINE_CURVE(a," in STEP text. */
static void step_degree_counts(const char *text, int surf[8][8], int curve[8])
{
    memset(surf, 0, sizeof(int[8][8]));
    memset(curve, 0, sizeof(int[8]));
    for (const char *p = text; (p = strstr(p, "B_SPLINE_")); p++) {
        int a, b;
        if (sscanf(p, "B_SPLINE_SURFACE(%d,%d,", &a, &b) == 2 && a >= 0 && a < 8 && b >= 0 && b < 8)
            surf[a][b]++;
        else if (sscanf(p, "B_SPLINE_CURVE(%d,", &a) == 1 && a >= 0 && a < 8)
            curve[a]++;
    }
}

/* Multiplicities "(d+1,d,...,d,d+1)" of n spans of degree d. */
static void mults_text(char *buf, size_t cap, int n, int d)
{
    size_t len = 0;
    len += (size_t)snprintf(buf + len, cap - len, "(");
    for (int k = 0; k <= n; k++)
        len += (size_t)snprintf(buf + len, cap - len, "%s%d", k ? "," : "", k == 0 || k == n ? d + 1 : d);
    snprintf(buf + len, cap - len, ")");
}

/*
 * Every STEP face / IGES entity 128 carries the degrees of its patch (face per patch), or
 * the surface's highest degrees with interior knots of that multiplicity (face per mesh);
 * every STEP edge curve has the lowest degree of the patch sides along it (s: no pole).
 */
static void export_degrees(const rg2_surface *s)
{
    rg2_error err;
    rg2_export_opts o;
    rg2_export_opts_default(&o);
    o.name = "degrees";
    int nu = s->nu, nv = s->nv, Du, Dv;
    rg2_surface_degree(s, &Du, &Dv);
    int want_s[8][8] = {{0}}, want_c[8] = {0}, got_s[8][8], got_c[8];
    for (int i = 0; i < nu; i++)
        for (int j = 0; j < nv; j++) {
            want_s[pdeg(s, i, j, 0)][pdeg(s, i, j, 1)]++;
            /* the u = 0 side (a v-curve) and the v = 0 side (a u-curve) of each patch, shared with
             * the previous patch where there is one; the far boundaries of open directions */
            int dl = pdeg(s, i, j, 1), db = pdeg(s, i, j, 0);
            if (i > 0 || s->closed_u) {
                int o2 = pdeg(s, (i + nu - 1) % nu, j, 1);
                dl = o2 < dl ? o2 : dl;
            }
            if (j > 0 || s->closed_v) {
                int o2 = pdeg(s, i, (j + nv - 1) % nv, 0);
                db = o2 < db ? o2 : db;
            }
            want_c[dl]++;
            want_c[db]++;
            if (i == nu - 1 && !s->closed_u)
                want_c[pdeg(s, i, j, 1)]++;
            if (j == nv - 1 && !s->closed_v)
                want_c[pdeg(s, i, j, 0)]++;
        }
    size_t len;
    o.layout = RG2_STEP_FACE_PER_PATCH;
    CHECK_OK(rg2_export_file(s, 1, path_in("d.step"), &o, &err), &err);
    char *b = (char *)slurp(path_in("d.step"), &len);
    CHECK(b != NULL, "d.step not read");
    if (!b)
        return;
    step_degree_counts(b, got_s, got_c);
    free(b);
    CHECK(!memcmp(got_s, want_s, sizeof got_s), "STEP per patch: face degrees differ from the patches'");
    CHECK(!memcmp(got_c, want_c, sizeof got_c),
          "STEP per patch: edge curve degrees 3/4/5: %d/%d/%d, expected %d/%d/%d", got_c[3], got_c[4], got_c[5],
          want_c[3], want_c[4], want_c[5]);
    o.layout = RG2_STEP_FACE_PER_MESH;
    CHECK_OK(rg2_export_file(s, 1, path_in("d.step"), &o, &err), &err);
    b = (char *)slurp(path_in("d.step"), &len);
    CHECK(b != NULL, "d.step (per mesh) not read");
    if (!b)
        return;
    step_degree_counts(b, got_s, got_c);
    char knots[256], mu[100], mv[100];
    mults_text(mu, sizeof mu, nu, Du);
    mults_text(mv, sizeof mv, nv, Dv);
    snprintf(knots, sizeof knots, "B_SPLINE_SURFACE_WITH_KNOTS(%s,%s,", mu, mv);
    int others = 0;
    for (int a = 0; a < 8; a++)
        for (int c = 0; c < 8; c++)
            others += (a != Du || c != Dv) ? got_s[a][c] : 0;
    CHECK(got_s[Du][Dv] == 1 && others == 0 && strstr(b, knots),
          "STEP per mesh: %d surfaces of degree (%d, %d), %d others, knots %s %s", got_s[Du][Dv], Du, Dv, others,
          knots, strstr(b, knots) ? "found" : "missing");
    free(b);
    /* IGES: the first parameter record of each entity starts "128,K1,K2,M1,M2," */
    for (int layout = 0; layout < 2; layout++) {
        o.layout = layout ? RG2_STEP_FACE_PER_MESH : RG2_STEP_FACE_PER_PATCH;
        CHECK_OK(rg2_export_file(s, 1, path_in("d.igs"), &o, &err), &err);
        FILE *f = fopen(path_in("d.igs"), "r");
        char line[256];
        int n = 0, bad = 0, prev_de = -1;
        while (f && fgets(line, sizeof line, f)) {
            if (strlen(line) < 73 || line[72] != 'P')
                continue;
            int de = atoi(line + 64);
            if (de == prev_de)
                continue;
            prev_de = de;
            int K1, K2, M1, M2;
            if (sscanf(line, "128,%d,%d,%d,%d,", &K1, &K2, &M1, &M2) != 4) {
                bad++;
                continue;
            }
            if (layout == 0)
                bad += n >= nu * nv || M1 != pdeg(s, n / nv, n % nv, 0) || M2 != pdeg(s, n / nv, n % nv, 1) ||
                       K1 != M1 || K2 != M2;
            else
                bad += M1 != Du || M2 != Dv || K1 != Du * nu || K2 != Dv * nv;
            n++;
        }
        if (f)
            fclose(f);
        CHECK(n == (layout ? 1 : nu * nv) && bad == 0, "IGES %s: %d entities, %d with wrong degrees",
              layout ? "per mesh" : "per patch", n, bad);
    }
    g_deg_checked++;
}

/* ---------------------------------------------------------------- failures */
static void failures(const rg2_surface *s)
{
    rg2_error err;
    int before = count_files();
    rg2_status st = export_one(s, "no/such/dir/x.step", &err);
    CHECK(st == RG2_EIO && strstr(err.msg, "x.step"), "unwritable path: %s: %s", rg2_status_str(st), err.msg);
    st = rg2_export_file(s, 1, g_dir, NULL, &err); /* a directory, no extension */
    CHECK(st == RG2_EINVAL, "directory as path: %s", rg2_status_str(st));
    st = export_one(s, "x.xyz", &err);
    CHECK(st == RG2_EINVAL && strstr(err.msg, ".xyz"), "unknown extension: %s", err.msg);
    rg2_export_opts lo;
    rg2_export_opts_default(&lo);
    lo.layout = (rg2_step_layout)7; /* was written as face per patch */
    st = rg2_export_file(s, 1, path_in("layout.step"), &lo, &err);
    CHECK(st == RG2_EINVAL && !strcmp(err.msg, "export: layout 7, must be RG2_STEP_FACE_PER_PATCH (0) or RG2_STEP_FACE_PER_MESH (1)"),
          "layout 7: %s: %s", rg2_status_str(st), err.msg);
    /* the same verdicts without writing: every known extension, any case; the unknown ones */
    static const char *known[] = {"a.step", "a.STP", "d/a.igs", "a.IGES", "a.bv", "a.bez", "a.obj",
                                  "a.Stl", "a.ply", "a.glb", "a.json", ".a.step", "d/..step", ".d/a.stl"};
    for (size_t k = 0; k < sizeof known / sizeof *known; k++)
        CHECK(rg2_export_format_check(known[k], &err) == RG2_OK, "%s refused: %s", known[k], err.msg);
    static const char *unknown[] = {"a.xyz", "a", "d.step/a", "a.", "", "a.step.tmp", ".step", "d/.IGS", "./.glb"};
    for (size_t k = 0; k < sizeof unknown / sizeof *unknown; k++) {
        st = rg2_export_format_check(unknown[k], &err);
        CHECK(st == RG2_EINVAL && err.msg[0], "'%s' accepted (%s)", unknown[k], rg2_status_str(st));
    }
    CHECK(rg2_export_format_check(NULL, &err) == RG2_EINVAL, "NULL path accepted");
    st = rg2_export_file(s, 0, path_in("empty.step"), NULL, &err);
    CHECK(st == RG2_EINVAL && !strcmp(err.msg, "export: no surfaces to write (n_surfs = 0: an empty design)"),
          "empty input: %s", err.msg);
    st = rg2_export_file(NULL, 1, path_in("empty.step"), NULL, &err); /* (both said "empty design" to C callers) */
    CHECK(st == RG2_EINVAL && !strcmp(err.msg, "export: no surfaces to write (surfs is NULL)"), "NULL surfs: %s",
          err.msg);
    st = rg2_export_file(s, -1, path_in("empty.step"), NULL, &err);
    CHECK(st == RG2_EINVAL && !strcmp(err.msg, "export: no surfaces to write (n_surfs < 0)"), "n_surfs -1: %s",
          err.msg);
    rg2_surface none;
    memset(&none, 0, sizeof none);
    st = rg2_export_file(&none, 1, path_in("none.igs"), NULL, &err);
    CHECK(st == RG2_EINVAL && strstr(err.msg, "no patches"), "surface without patches: %s", err.msg);
    rg2_surface bad;
    CHECK_OK(rg2_surface_copy(s, &bad, &err), &err);
    double *h = rg2_surface_patch(&bad, 2, 1)->h[1][2];
    for (int k = 0; k < 4; k++)
        h[k] *= -0.5; /* same point, negative weight */
    /* more records than IGES's 7-digit sequence numbers hold (the limit lowered by the test
     * hook: a real case needs some 440,000 patches, 250,000 in the B-rep form) */
    rg2__iges_max_records = 50;
    st = export_one(s, "many.igs", &err);
    rg2__iges_max_records = 9999999;
    CHECK(st == RG2_ELIMIT && strstr(err.msg, "sequence numbers"), "IGES past its record limit: %s: %s",
          rg2_status_str(st), err.msg);
    rg2_export_opts o;
    rg2_export_opts_default(&o);
    o.iges_brep = 1;
    st = rg2_export_file(&bad, 1, path_in("neg_brep.igs"), &o, &err);
    CHECK(st == RG2_EWEIGHT && strstr(err.msg, "patch (2, 1)"), "IGES B-rep negative weight: %s", err.msg);
    /* the refusal says what to do, not only what importers would make of it (it named the point
     * and stopped at "importers drop the face or ignore the weights") */
    const char *remedy = "(importers drop the face or ignore the weights): use more arcs or knots there (coarse ones "
                         "can give an exact shape patch weights <= 0, docs/shapes.md \"Homogeneous weights\"; a "
                         "merge's note on a weight <= 0 says which knots to move)";
    CHECK(st == RG2_EWEIGHT && strstr(err.msg, remedy), "IGES B-rep negative weight names the remedy: %s", err.msg);
    const char *names[] = {"neg.step", "neg.igs"};
    for (int k = 0; k < 2; k++) {
        st = export_one(&bad, names[k], &err);
        CHECK(st == RG2_EWEIGHT && strstr(err.msg, "patch (2, 1)"), "%s: %s: %s", names[k], rg2_status_str(st), err.msg);
        CHECK(st == RG2_EWEIGHT && strstr(err.msg, k ? "IGES needs every weight > 0 " : "STEP needs every weight > 0 ") &&
                  strstr(err.msg, remedy),
              "%s names the remedy: %s", names[k], err.msg);
    }
    /* err is nullable (rg2.h): the same verdicts without a report (the message was prefixed
     * with the file name through *err, a NULL dereference) */
    st = rg2_export_file(&bad, 1, path_in("neg_noerr.step"), NULL, NULL);
    CHECK(st == RG2_EWEIGHT, "negative weight, err NULL: %s", rg2_status_str(st));
    const char *neg_paths[] = {path_in("neg_noerr.igs")};
    st = rg2_export_files(&bad, 1, neg_paths, 1, NULL, NULL, NULL);
    CHECK(st == RG2_EWEIGHT, "rg2_export_files, negative weight, err NULL: %s", rg2_status_str(st));
    h[3] = 0.0;
    st = export_one(&bad, "zero.step", &err);
    CHECK(st == RG2_EWEIGHT && strstr(err.msg, "patch (2, 1)"), "zero weight: %s", err.msg);
    /* a NaN in a later patch than the zero weight: every format refuses it (the patch formats
     * wrote "nan" when the weight was found first, and the .json did not parse) */
    char where[48];
    snprintf(where, sizeof where, "patch (%d, %d)", bad.nu - 1, bad.nv - 1);
    rg2_surface_patch(&bad, bad.nu - 1, bad.nv - 1)->h[1][1][0] = NAN;
    const char *later[] = {"nan.json", "nan.bv", "nan.bez", "nan.step", "nan.obj"};
    for (int k = 0; k < 5; k++) {
        st = export_one(&bad, later[k], &err);
        CHECK(st == RG2_ENONFINITE && (k == 4 || strstr(err.msg, where)), "%s, NaN after a zero weight: %s '%s'",
              later[k], rg2_status_str(st), err.msg);
    }
    h[0] = NAN;
    st = export_one(&bad, "nan.obj", &err);
    CHECK(st == RG2_ENONFINITE, "NaN: %s", err.msg);
    st = rg2_export_file(&bad, 1, path_in("nan_noerr.obj"), NULL, NULL);
    CHECK(st == RG2_ENONFINITE, "NaN, err NULL: %s", rg2_status_str(st));
    rg2_surface_free(&bad);
    CHECK(count_files() == before, "failed exports left %d files", count_files() - before);
    char negtmp[40];
    snprintf(negtmp, sizeof negtmp, "neg.step.%ld.tmp", (long)getpid());
    CHECK(!exists(path_in(negtmp)) && !exists(path_in("neg.step")), "neg.step or its temporary file left behind");
}

/* rg2_export_files of surfs[0..n) at density to the four mesh formats, STEP and IGES in one call:
 * every file holds the bytes rg2_export_file writes (STEP/IGES: but the stamp), and the mesh
 * files come from one tessellation, made with the curvatures that PLY writes (the positions,
 * normals and triangles that OBJ, STL and glTF write are the same bits with or without them);
 * IGES, named after the last mesh file, is written after the tessellation is freed. */
static void several_same_bytes(const rg2_surface *surfs, int n, int density)
{
    rg2_error err;
    rg2_export_opts o;
    rg2_export_opts_default(&o);
    o.density = density;
    int failed = 7;
    static const char *names[] = {"m1.obj", "m1.step", "m1.stl", "m1.ply", "m1.glb", "m1.igs"};
    enum { n_ok = sizeof names / sizeof *names };
    char buf[n_ok][256], one[256];
    const char *paths[n_ok];
    for (int k = 0; k < n_ok; k++)
        paths[k] = path_at(buf[k], names[k]);
    unsigned long calls = rg2__tess_all_calls();
    CHECK_OK(rg2_export_files(surfs, n, paths, n_ok, &o, &failed, &err), &err);
    calls = rg2__tess_all_calls() - calls;
    CHECK(failed == -1, "success gave failed = %d", failed);
    CHECK(calls == 1, "%d surface(s) at density %d: %lu tessellations for the four mesh files, want one", n, density,
          calls);
    for (int k = 0; k < n_ok; k++) { /* the same bytes as one file at a time (STEP/IGES: but the stamp) */
        char name[16];
        snprintf(name, sizeof name, "m2%s", strrchr(names[k], '.')); /* a name of the same length */
        CHECK_OK(rg2_export_file(surfs, n, path_at(one, name), &o, &err), &err);
        size_t la, lb;
        unsigned char *a = slurp(paths[k], &la), *b = slurp(one, &lb);
        CHECK(a && b && la == lb, "%s: %zu bytes, one at a time %zu", paths[k], la, lb);
        if (!strstr(paths[k], ".step") && !strstr(paths[k], ".igs"))
            CHECK(a && b && la == lb && !memcmp(a, b, la), "%d surface(s) at density %d: %s differs from the file written alone",
                  n, density, paths[k]);
        free(a);
        free(b);
        remove(one);
    }
    for (int k = 0; k < n_ok; k++)
        remove(paths[k]);
}

/* Into memory (rg2_export_memory): for every format, the bytes rg2_export_file writes to
 * "<name>.<format>" (with SOURCE_DATE_EPOCH, the STEP and IGES stamps too), and a 0 after them;
 * the name with a '/' (the headers give it as '_'); failures leave *data NULL: an unknown or
 * dotted format, NULL arguments, a weight <= 0 for STEP. */
static void into_memory(const rg2_surface *s, const rg2_surface *x)
{
    static const char *fmts[] = {"step", "stp", "igs", "IGES", "bv", "bez", "obj", "stl", "ply", "glb", "json"};
    const char *old = getenv("SOURCE_DATE_EPOCH");
    char *keep = old ? strdup(old) : NULL;
    setenv("SOURCE_DATE_EPOCH", "1700000000", 1);
    rg2_error err;
    rg2_export_opts o;
    rg2_export_opts_default(&o);
    int same = 0;
    size_t total = 0;
    for (int v = 0; v < 3; v++) {
        const rg2_surface *surf = v == 2 ? x : s;
        o.name = v == 1 ? "parts/flange 7" : "rg2";
        o.iges_brep = v == 1;
        o.layout = v == 1 ? RG2_STEP_FACE_PER_MESH : RG2_STEP_FACE_PER_PATCH;
        for (size_t k = 0; k < sizeof fmts / sizeof *fmts; k++) {
            char name[64], buf[256];
            snprintf(name, sizeof name, "%s.%s", v == 1 ? "parts_flange 7" : "rg2", fmts[k]);
            CHECK_OK(rg2_export_file(surf, 1, path_at(buf, name), &o, &err), &err);
            size_t lf = 0, lm = 12345;
            unsigned char *f = slurp(buf, &lf);
            char *m = (char *)&lm;
            rg2_status st = rg2_export_memory(surf, 1, fmts[k], &o, &m, &lm, &err);
            CHECK_OK(st, &err);
            int ok = !st && f && m && lm == lf && !memcmp(f, m, lf) && m[lm] == 0;
            CHECK(ok, "%s in memory: %zu bytes, the file %zu, %s", name, lm, lf,
                  !st && f && m && lm == lf ? "different bytes" : "a different size");
            same += ok;
            total += lm;
            free(f);
            if (!st)
                free(m);
            remove(buf);
        }
    }
    /* failures: *data NULL and *size 0, with the error named */
    static const char *bad[] = {"xyz", ".step", "", "step/x", "toolongformat"};
    for (size_t k = 0; k < sizeof bad / sizeof *bad; k++) {
        size_t n = 7;
        char *m = (char *)&n;
        rg2_status st = rg2_export_memory(s, 1, bad[k], NULL, &m, &n, &err);
        CHECK(st == RG2_EINVAL && !m && n == 0 && strstr(err.msg, "unknown format"),
              "format '%s': %s, data %p, size %zu: %s", bad[k], rg2_status_str(st), (void *)m, n, err.msg);
    }
    size_t n = 0;
    char *m = NULL;
    CHECK(rg2_export_memory(s, 1, NULL, NULL, &m, &n, &err) == RG2_EINVAL && !m &&
              strstr(err.msg, "rg2_export_memory: format is NULL (use step "),
          "format NULL: %s", err.msg);
    CHECK(rg2_export_memory(s, 1, "step", NULL, NULL, &n, &err) == RG2_EINVAL, "data NULL accepted");
    CHECK(rg2_export_memory(s, 1, "step", NULL, &m, NULL, &err) == RG2_EINVAL && !m, "size NULL accepted");
    CHECK(rg2_export_memory(s, 0, "step", NULL, &m, &n, &err) == RG2_EINVAL && !m, "no surfaces accepted");
    rg2_surface w;
    CHECK_OK(rg2_surface_copy(s, &w, &err), &err);
    w.patch[1].h[2][1][3] = -0.5;
    rg2_status st = rg2_export_memory(&w, 1, "step", NULL, &m, &n, &err);
    CHECK(st == RG2_EWEIGHT && !m && n == 0 && strstr(err.msg, "rg2.step"),
          "a negative weight in STEP into memory: %s, %s", rg2_status_str(st), err.msg);
    rg2_surface_free(&w);
    if (keep) {
        setenv("SOURCE_DATE_EPOCH", keep, 1);
        free(keep);
    } else
        unsetenv("SOURCE_DATE_EPOCH");
    printf("into memory: %d of %d outputs (11 formats; the torus, named with a '/', and of higher degree) the bytes "
           "of their files (%zu bytes in all); 9 refusals with nothing allocated\n",
           same, 3 * (int)(sizeof fmts / sizeof *fmts), total);
}

/* The STEP and IGES time stamps: with SOURCE_DATE_EPOCH (reproducible-builds.org) the time it
 * gives, in UTC, as gmtime and strftime spell it here: FILE_NAME's second string, the IGES global
 * section's date of the file's creation and of its last change (parameters 18 and 25, read from
 * columns 1-72 of its lines joined). */
static void time_stamps(const rg2_surface *s)
{
    static const long long when[] = {0, 1700000000, 951868799}; /* 1970, 2023, 2000-02-29 23:59:59 */
    const char *old = getenv("SOURCE_DATE_EPOCH");
    char *keep = old ? strdup(old) : NULL;
    int right = 0, asked = 0;
    for (size_t k = 0; k < sizeof when / sizeof *when; k++) {
        char sde[32], step_want[40], iges_want[40], got[2][40] = {"", ""};
        snprintf(sde, sizeof sde, "%lld", when[k]);
        setenv("SOURCE_DATE_EPOCH", sde, 1);
        time_t t = (time_t)when[k];
        struct tm tmv;
        CHECK(gmtime_r(&t, &tmv) && strftime(step_want, sizeof step_want, "'%Y-%m-%dT%H:%M:%S'", &tmv) &&
                  strftime(iges_want, sizeof iges_want, "15H%Y%m%d.%H%M%S", &tmv),
              "gmtime of %lld", when[k]);
        rg2_error err;
        char *m = NULL;
        size_t n = 0;
        CHECK_OK(rg2_export_memory(s, 1, "step", NULL, &m, &n, &err), &err);
        const char *fn = m ? strstr(m, "FILE_NAME(") : NULL, *q = fn ? strstr(fn, "','") : NULL;
        if (q)
            snprintf(got[0], sizeof got[0], "%.21s", q + 2);
        free(m);
        CHECK_OK(rg2_export_memory(s, 1, "igs", NULL, &m, &n, &err), &err);
        char g[2048] = "";
        size_t gl = 0;
        for (const char *l = m; l && *l && gl + 72 < sizeof g;) { /* the G lines' columns 1-72 */
            const char *e = strchr(l, '\n');
            if (!e)
                break;
            if (e - l >= 73 && l[72] == 'G') {
                memcpy(g + gl, l, 72);
                gl += 72;
                g[gl] = 0;
            }
            l = e + 1;
        }
        free(m);
        int stamps = 0; /* parameters 18 and 25 */
        for (const char *h = g; (h = strstr(h, iges_want)); h++)
            stamps++;
        right += !strcmp(got[0], step_want) && stamps == 2;
        asked++;
        CHECK(!strcmp(got[0], step_want) && stamps == 2,
              "SOURCE_DATE_EPOCH=%s: STEP stamp %s (want %s), IGES global section holds %s %d times (want 2)", sde,
              got[0], step_want, iges_want, stamps);
    }
    if (keep) {
        setenv("SOURCE_DATE_EPOCH", keep, 1);
        free(keep);
    } else
        unsetenv("SOURCE_DATE_EPOCH");
    printf("time stamps: %d of %d SOURCE_DATE_EPOCH values written as given in STEP and IGES\n", right, asked);
}

/* Several files as one (rg2_export_files): on success every path holds what rg2_export_file
 * writes (the torus; a surface with poles, whose collapsed sides the tessellation merges, next
 * to it; at two densities); when any output fails (a negative weight for STEP, an unwritable
 * directory, an unknown extension), no path is touched: files that were there keep their bytes,
 * none is added and no .tmp is left. */
static void several_files(const rg2_surface *s)
{
    rg2_error err;
    int failed = 7;
    rg2_surface two[2];
    two[0] = *s; /* (a shallow copy: read only) */
    CHECK_OK(fx_pole(6, 7, &two[1], &err), &err);
    several_same_bytes(s, 1, 16);
    several_same_bytes(two, 2, 16);
    several_same_bytes(two, 2, 3);
    rg2_surface_free(&two[1]);
    /* an old file, then a failing set: it keeps its bytes */
    char oldp[256], nb[3][2][256];
    FILE *f = fopen(path_at(oldp, "old.obj"), "w");
    CHECK(f && fputs("old\n", f) >= 0 && fclose(f) == 0, "cannot write old.obj");
    rg2_surface bad;
    CHECK_OK(rg2_surface_copy(s, &bad, &err), &err);
    double *h = rg2_surface_patch(&bad, 1, 0)->h[2][1];
    for (int k = 0; k < 4; k++)
        h[k] *= -0.5; /* the same point, a negative weight: fine for meshes, refused by STEP */
    int before = count_files();
    const char *sets[3][3] = {{oldp, path_at(nb[0][0], "new.stl"), path_at(nb[0][1], "new.step")},
                              {oldp, path_at(nb[1][0], "new.glb"), "/nonexistent-rg2-dir/x.igs"},
                              {oldp, path_at(nb[2][0], "new.ply"), path_at(nb[2][1], "new.xyz")}};
    const rg2_status want[3] = {RG2_EWEIGHT, RG2_EIO, RG2_EINVAL};
    for (int k = 0; k < 3; k++) {
        rg2_status st = rg2_export_files(k == 1 ? s : &bad, 1, sets[k], 3, NULL, &failed, &err);
        size_t n;
        unsigned char *old = slurp(oldp, &n);
        CHECK(st == want[k] && failed == 2 && strstr(err.msg, strrchr(sets[k][2], '/') + 1), "set %d: %s (failed %d) '%s'",
              k, rg2_status_str(st), failed, err.msg);
        CHECK(old && n == 4 && !memcmp(old, "old\n", 4), "set %d: a failed set changed old.obj (%zu bytes)", k, n);
        CHECK(count_files() == before, "set %d: %d files before, %d after", k, before, count_files());
        free(old);
    }
    CHECK(rg2_export_files(s, 1, sets[0], 0, NULL, &failed, &err) == RG2_EINVAL, "no paths: %s", err.msg);
    rg2_surface_free(&bad);
    remove(oldp);
}

/* STL, PLY and glTF store floats: a torus of size 4e45 (inside the supported 1e60) was written
 * as infinities with status ok (glTF min/max null), one of size 1e-50 as zeros; both are refused
 * naming the format, and leave no file; OBJ (17 digits) and STEP take them. Sizes 1e-30 and 1e30
 * are written, every float finite. */
static void float_range(void)
{
    rg2_error err;
    const double scale[] = {1e45, 1e-50, 1e30, 1e-30};
    const char *fmt[] = {"stl", "ply", "glb", "obj"}, *name[] = {"STL", "PLY", "glTF", "OBJ"};
    for (int q = 0; q < 4; q++) {
        rg2_surface s;
        CHECK_OK(fx_torus(3.0 * scale[q], 1.0 * scale[q], 4, 4, &s, &err), &err);
        for (int f = 0; f < 4; f++) {
            char file[32];
            snprintf(file, sizeof file, "fr%d.%s", q, fmt[f]);
            rg2_status st = rg2_export_file(&s, 1, path_in(file), NULL, &err);
            if (q < 2 && f < 3)
                CHECK(st == RG2_EDOMAIN && strstr(err.msg, name[f]) && strstr(err.msg, "float") && !exists(path_in(file)),
                      "%s at size %g: %s '%s'", file, scale[q], rg2_status_str(st), err.msg);
            else
                CHECK(st == RG2_OK && exists(path_in(file)), "%s at size %g: %s '%s'", file, scale[q],
                      rg2_status_str(st), err.msg);
            if (st == RG2_OK && f == 0) { /* binary STL: 80 + 4 bytes, then 50 per triangle */
                size_t len;
                unsigned char *b = slurp(path_in(file), &len);
                int bad = 0;
                for (size_t o = 84; b && o + 50 <= len; o += 50)
                    for (int c = 0; c < 12; c++)
                        bad += !isfinite(rd_f32(b + o + 4 * c)); /* (little-endian, as every host reads it) */
                CHECK(b && !bad, "%s: %d non-finite floats", file, bad);
                free(b);
            }
            remove(path_in(file));
        }
        rg2_surface_free(&s);
    }
}

/* The float formats' upper limit itself (docs/export.md: "up to 3.40282e+38"): a plane whose
 * control points span x in [0, FLT_MAX] exactly (the last column's corner FLT_MAX, reached at u = 1
 * exactly) is written, its STL's largest x is FLT_MAX; the same plane stretched by 2^-40 more is
 * refused. */
static void float_max(void)
{
    rg2_error err;
    for (int q = 0; q < 2; q++) {
        rg2_surface s;
        CHECK_OK(fx_random(7, 4, 4, &s, &err), &err);
        int N = 3 * s.nu;
        for (int i = 0; i < s.nu; i++)
            for (int j = 0; j < s.nv; j++)
                for (int r = 0; r < 4; r++)
                    for (int t = 0; t < 4; t++) {
                        double *h = rg2_surface_patch(&s, i, j)->h[r][t];
                        h[0] = (double)FLT_MAX * (3 * i + r) / N * (q ? 1 + 0x1p-40 : 1);
                        h[1] = (3.0 * j + t) / (3 * s.nv);
                        h[2] = 0;
                        h[3] = 1;
                    }
        rg2_status st = rg2_export_file(&s, 1, path_in("fmax.stl"), NULL, &err);
        if (q == 0) {
            size_t len;
            unsigned char *b = st == RG2_OK ? slurp(path_in("fmax.stl"), &len) : NULL;
            float mx = 0;
            for (size_t o = 84; b && o + 50 <= len; o += 50)
                for (int c = 1; c < 4; c++)
                    mx = fmaxf(mx, rd_f32(b + o + 12 * c));
            CHECK(st == RG2_OK && mx == FLT_MAX, "a plane up to x = FLT_MAX as STL: %s '%s', largest x %.9g",
                  rg2_status_str(st), err.msg, (double)mx);
            free(b);
        } else
            CHECK(st == RG2_EDOMAIN && strstr(err.msg, "float") && !exists(path_in("fmax.stl")),
                  "a plane up to x = FLT_MAX (1 + 2^-40) as STL: %s '%s'", rg2_status_str(st), err.msg);
        remove(path_in("fmax.stl"));
        rg2_surface_free(&s);
    }
}

/* The mesh formats' vertex limit over all surfaces together (rg2__tess_all): two tori of 6 x 4
 * patches at density 300 need 2 (6 * 300 + 1)(4 * 300 + 1) vertices, each alone fewer than
 * RG2_MAX_POINTS, both more: refused before anything is tessellated, with that count and the
 * largest density that fits, 288 (2 (6 * 288 + 1)(4 * 288 + 1) = 3987074, at 289 4014790). */
static void vertex_limit(const rg2_surface *s)
{
    rg2_surface two[2] = {*s, *s};
    rg2_export_opts o;
    rg2_export_opts_default(&o);
    o.density = 300;
    double each = (6.0 * o.density + 1) * (4.0 * o.density + 1);
    char want[160];
    snprintf(want, sizeof want,
             "export: 2 surfaces at density %d need %.0f vertices, more than the limit %d; density 288 or less fits",
             o.density, 2 * each, RG2_MAX_POINTS);
    rg2_error err;
    rg2_status st = rg2_export_file(two, 2, path_in("limit.obj"), &o, &err);
    CHECK(s->nu == 6 && s->nv == 4 && each < RG2_MAX_POINTS && 2 * each > RG2_MAX_POINTS && st == RG2_ELIMIT &&
              !strcmp(err.msg, want) && !exists(path_in("limit.obj")),
          "2 surfaces of %d x %d patches at density %d: %s '%s' (want '%s')", s->nu, s->nv, o.density,
          rg2_status_str(st), err.msg, want);
}

/* The failures again where the offending point is in a higher-degree patch, beyond the bi-3
 * index range: the weight and finiteness checks read every patch at its own degrees. */
static void xfailures(const rg2_surface *x)
{
    rg2_error err;
    int before = count_files(), k = -1;
    rg2_surface bad;
    CHECK_OK(rg2_surface_copy(x, &bad, &err), &err);
    for (int q = 0; bad.xp && q < bad.nu * bad.nv; q++)
        if (bad.xp[q].du > 3)
            k = q;
    CHECK(k >= 0, "no patch of u-degree > 3 in the elevated torus");
    if (k < 0) {
        rg2_surface_free(&bad);
        return;
    }
    rg2_xpatch *X = &bad.xp[k];
    char where[64];
    snprintf(where, sizeof where, "patch (%d, %d) control point [%d][%d]", k / bad.nv, k % bad.nv, X->du, X->dv - 1);
    double *h = X->h[X->du][X->dv - 1];
    for (int c = 0; c < 4; c++)
        h[c] *= -0.5; /* same point, negative weight */
    const char *names[] = {"xneg.step", "xneg.igs"};
    for (int q = 0; q < 2; q++) {
        rg2_status st = export_one(&bad, names[q], &err);
        CHECK(st == RG2_EWEIGHT && strstr(err.msg, where), "%s: %s: %s (expected %s)", names[q], rg2_status_str(st),
              err.msg, where);
    }
    h[3] = 0.0;
    rg2_status st = export_one(&bad, "xzero.step", &err);
    CHECK(st == RG2_EWEIGHT && strstr(err.msg, where), "zero weight in a degree-%d patch: %s", X->du, err.msg);
    h[1] = NAN;
    st = export_one(&bad, "xnan.bv", &err);
    CHECK(st == RG2_ENONFINITE && strstr(err.msg, where), "NaN in a degree-%d patch: %s", X->du, err.msg);
    rg2_surface_free(&bad);
    CHECK(count_files() == before, "failed exports left %d files", count_files() - before);
}

/* A torus with some patches replaced by their exact degree elevations to (4, 3), (5, 3),
 * (4, 4) and (3, 5): the same surface through the higher-degree code paths. */
static rg2_status elevated_torus(rg2_surface *s, rg2_error *err)
{
    static const int deg[4][2] = {{4, 3}, {5, 3}, {4, 4}, {3, 5}}, stride[4] = {3, 5, 7, 4};
    rg2_status st = fx_torus(13.0, 4.0, 6, 4, s, err);
    for (int k = 0; k < 4 && !st; k++)
        st = rg2t_elevate_some(s, deg[k][0], deg[k][1], stride[k], k, err);
    return st;
}

/* ---------------------------------------------------------------- a full disk */
/* Every writer through a full disk: files of this process fail past 100 bytes (EFBIG), so the
 * writes fail when they are flushed. The error names the file and the reason, neither the
 * output nor its temporary file is left behind. */
static void full_disk(const rg2_surface *s)
{
    static const char *names[] = {"full.step", "full.igs", "full.bv", "full.bez", "full.obj", "full.stl",
                                  "full.ply", "full.glb", "full.json"};
    int before = count_files();
    for (size_t k = 0; k < sizeof names / sizeof names[0]; k++) {
        char *out = path_in(names[k]);
        rg2_error err;
        CHECK(rg2t_file_limit(100) == 0, "file size limit");
        rg2_status st = export_one(s, names[k], &err);
        rg2t_file_limit(-1);
        CHECK(st == RG2_EIO && strstr(err.msg, out) && strstr(err.msg, "write failed") &&
                  strstr(err.msg, strerror(EFBIG)),
              "%s on a full disk: %s '%s'", names[k], rg2_status_str(st), err.msg);
        struct stat sb;
        CHECK(lstat(out, &sb) != 0, "%s on a full disk: the output left behind", names[k]);
    }
    CHECK(count_files() == before, "full disk: %d files before, %d after", before, count_files());
}

/* ---------------------------------------------------------------- temporary files */
/* The temporary file is created new next to the output, never through a symbolic link: a
 * link planted at its name ("<path>.<pid>.tmp", the first name tried) is left alone and its
 * target keeps its bytes (the old "<path>.tmp", opened with fopen, wrote through it). Two
 * threads writing one path each get a file of their own: the path ends with one writer's whole
 * file, never a mix, and both succeed. A path given twice to rg2_export_files is refused. */
typedef struct {
    const rg2_surface *s;
    const char *path;
    rg2_status st;
} same_path_job;

static void *same_path_writer(void *arg)
{
    same_path_job *j = arg;
    rg2_export_opts o;
    rg2_export_opts_default(&o);
    o.density = 24; /* ~0.9 MB of OBJ: long enough for the two writes to overlap */
    j->st = rg2_export_file(j->s, 1, j->path, &o, NULL);
    return NULL;
}

/* ".<pid>.tmp", the suffix of a first temporary name. */
static const char *suffix_of_pid(void)
{
    static char suffix[48];
    snprintf(suffix, sizeof suffix, ".%ld.tmp", (long)getpid());
    return suffix;
}

/* The file-name limit the next temp_name_max call reports, and the directory it was asked for. */
static long g_name_max;
static char g_name_dir[600];

static long temp_name_max(const char *dir)
{
    snprintf(g_name_dir, sizeof g_name_dir, "%s", dir);
    return g_name_max;
}

/* Temporary names cut to the limit of the output's directory (pathconf's _PC_NAME_MAX: eCryptfs
 * takes 143 bytes), through the test hook, since no file system here has a limit below 255: a
 * 140-byte name is cut to 143 bytes with the hash of the whole name and written (a name whose
 * temporary name is 143 bytes exactly is not cut, one a byte longer is); the limit is
 * asked of the path's own directory ("." and "/" for names without one); no answer (-1) means
 * 255, and a limit too small for the suffix and hash leaves the name whole; a larger one (vfat
 * and exfat answer 1530) counts as 255; a name of continuation bytes only is cut whole. */
static void temp_names_limit(const rg2_surface *s)
{
    rg2_error err;
    long (*saved)(const char *) = rg2__dir_name_max;
    rg2__dir_name_max = temp_name_max;
    char base[256], lng[600], tname[700], whole[700];
    memset(base, 'y', 136);
    strcpy(base + 136, ".obj"); /* 140 bytes */
    snprintf(lng, sizeof lng, "%s/%s", g_dir, base);
    snprintf(whole, sizeof whole, "%s.%ld.tmp", lng, (long)getpid());
    const long limits[3] = {143, -1, 10};
    for (int q = 0; q < 3; q++) {
        g_name_max = limits[q];
        g_name_dir[0] = '\0';
        CHECK(rg2_temp_name(lng, tname, sizeof tname) == 0, "rg2_temp_name of a 140-byte name, limit %ld", limits[q]);
        const char *tb = tname + strlen(g_dir) + 1, *suffix = whole + strlen(lng);
        size_t n = strlen(tb), kept = 143 - 9 - strlen(suffix); /* base, ".%08x", suffix */
        if (q == 0)
            CHECK(n == 143 && !strncmp(tb, base, kept) && tb[kept] == '.' &&
                      strspn(tb + kept + 1, "0123456789abcdef") == 8 && !strcmp(tb + kept + 9, suffix),
                  "limit 143: temporary name '%s' (%zu bytes)", tb, n);
        else
            CHECK(!strcmp(tname, whole), "limit %ld: temporary name '%s', want the whole name", limits[q], tname);
        CHECK(!strcmp(g_name_dir, g_dir), "limit %ld: asked of '%s', not of the directory '%s'", limits[q], g_name_dir, g_dir);
    }
    /* a name whose temporary name fits the limit exactly (143 bytes with the suffix) is not cut,
     * nor one of a byte more, cut to the limit (a cut at "fits or more" hashed the first) */
    g_name_max = 143;
    for (int over = 0; over < 2; over++) {
        char fit[256], fitp[600];
        size_t nb = 143 - strlen(suffix_of_pid()) + (size_t)over;
        memset(fit, 'f', nb - 4);
        strcpy(fit + nb - 4, ".obj");
        snprintf(fitp, sizeof fitp, "%s/%s", g_dir, fit);
        snprintf(whole, sizeof whole, "%s%s", fitp, suffix_of_pid());
        CHECK(rg2_temp_name(fitp, tname, sizeof tname) == 0 && strlen(strrchr(tname, '/') + 1) <= 143 &&
                  (over ? strcmp(tname, whole) != 0 : !strcmp(tname, whole)),
              "limit 143, a %zu-byte name: temporary name '%s' (%zu bytes), %s", nb, tname,
              strlen(strrchr(tname, '/') + 1), over ? "want it cut to 143" : "want the whole name, 143 bytes");
    }
    /* a limit with room for the hash and the suffix and nothing more: a 12-byte name (within the
     * limit) is cut whole and the temporary name is the hash and the suffix, the limit's length
     * (it was left whole, too long for the directory); a byte less leaves no room, and the name
     * whole */
    char twelve[600];
    snprintf(twelve, sizeof twelve, "%s/twelve_b.obj", g_dir);
    for (int less = 0; less < 2; less++) {
        size_t room = strlen(suffix_of_pid()) + 9 - (size_t)less;
        g_name_max = (long)room;
        CHECK(rg2_temp_name(twelve, tname, sizeof tname) == 0, "limit %zu: rg2_temp_name failed", room);
        const char *tb = strrchr(tname, '/') + 1;
        snprintf(whole, sizeof whole, "%s%s", twelve, suffix_of_pid());
        if (less)
            CHECK(!strcmp(tname, whole), "limit %zu (no room for the hash): temporary name '%s', want the whole name",
                  room, tname);
        else
            CHECK(strlen(tb) == room && tb[0] == '.' && strspn(tb + 1, "0123456789abcdef") == 8 &&
                      !strcmp(tb + 9, suffix_of_pid()) && !strncmp(tname, twelve, strlen(g_dir) + 1),
                  "limit %zu (room for the hash and the suffix only): temporary name '%s', want "
                  "'<dir>/.<8 hex digits>%s'", room, tname, suffix_of_pid());
    }
    /* a last component of UTF-8 continuation bytes only (not UTF-8, but Linux takes any bytes)
     * has no character boundary before the cut: all of it goes, and the temporary name is the
     * hash and the suffix in the output's own directory */
    g_name_max = 143;
    memset(base, 0x80, 136);
    strcpy(base + 136, ".obj");
    snprintf(lng, sizeof lng, "%s/%s", g_dir, base);
    size_t nd = strlen(g_dir);
    char suffix[48];
    snprintf(suffix, sizeof suffix, ".%ld.tmp", (long)getpid());
    CHECK(rg2_temp_name(lng, tname, sizeof tname) == 0 && !strncmp(tname, g_dir, nd) && tname[nd] == '/' &&
              tname[nd + 1] == '.' && strspn(tname + nd + 2, "0123456789abcdef") == 8 && !strcmp(tname + nd + 10, suffix),
          "limit 143, a name of 136 continuation bytes: temporary name '%s', want '%s/.<8 hex digits>%s'", tname, g_dir,
          suffix);
    g_name_max = 143;
    rg2_export_opts o;
    rg2_export_opts_default(&o);
    o.density = 2;
    CHECK_OK(rg2_export_file(s, 1, lng, &o, &err), &err);
    struct stat sb;
    CHECK(stat(lng, &sb) == 0 && sb.st_size > 100, "limit 143: a 140-byte file name was not written");
    remove(lng);
    /* vfat and exfat answer 255 UTF-16 units x 6 bytes = 1530 but take 255 ASCII bytes: a
     * 250-byte name there (here: the hook on a 255-byte file system) is cut at 255 and written */
    g_name_max = 1530;
    char lng2[600], base2[256];
    memset(base2, 'z', 246);
    strcpy(base2 + 246, ".obj"); /* 250 bytes */
    snprintf(lng2, sizeof lng2, "%s/%s", g_dir, base2);
    CHECK(rg2_temp_name(lng2, tname, sizeof tname) == 0 && strlen(strrchr(tname, '/') + 1) <= 255,
          "limit 1530 (vfat): temporary name of %zu bytes", strlen(strrchr(tname, '/') + 1));
    rg2_status st1530 = rg2_export_file(s, 1, lng2, &o, &err);
    CHECK(st1530 == RG2_OK, "limit 1530 (vfat): a 250-byte file name was not written: %s", err.msg);
    remove(lng2);
    const char *bare[2][2] = {{"rg2-rel.obj", "."}, {"/rg2-abs.obj", "/"}};
    for (int q = 0; q < 2; q++)
        CHECK(rg2_temp_name(bare[q][0], tname, sizeof tname) == 0 && !strcmp(g_name_dir, bare[q][1]),
              "%s: the limit asked of '%s', want '%s'", bare[q][0], g_name_dir, bare[q][1]);
    rg2__dir_name_max = saved;
}

/* A regular file replaced keeps its permission bits (mode & 0777, as sed -i keeps them; not the
 * setuid, setgid or sticky bit, which a 04755 file loses): the
 * renamed temporary file used to have 0666 & ~umask, so a 0600 or 0444 file became 0644. A new
 * file, and one written over a symbolic link, has 0666 & ~umask; the link's target keeps its own. */
/* A file written over by a user who may not give the new file its owner (not root): the new file
 * is the writer's, keeps the old file's group where the writer belongs to it (fchown to the group
 * alone), and else gets the writer's group with group bits that grant no more than the others'
 * bits do. Run as user 65534 in a forked child; only when the test runs as root. */
static int stranger_case(const rg2_surface *s, mode_t mode, int in_group, mode_t want_mode, gid_t want_gid)
{
    char *p = path_in("stranger/mode.obj");
    FILE *f = fopen(p, "w");
    CHECK(f && fclose(f) == 0 && chown(p, 0, 0) == 0 && chmod(p, mode) == 0, "write %s", p);
    pid_t pid = fork();
    CHECK(pid >= 0, "fork");
    if (pid == 0) {
        gid_t groups[2] = {65534, 0};
        rg2_error err;
        if (setgroups(in_group ? 2 : 1, groups) != 0 || setgid(65534) != 0 || setuid(65534) != 0)
            _exit(2); /* a container without CAP_SETUID / CAP_SETGID */
        _exit(export_one(s, "stranger/mode.obj", &err) == RG2_OK ? 0 : 1);
    }
    int status = 0;
    if (waitpid(pid, &status, 0) == pid && WIFEXITED(status) && WEXITSTATUS(status) == 2) {
        remove(p);
        return 0;
    }
    CHECK(WIFEXITED(status) && WEXITSTATUS(status) == 0,
          "user 65534 writing over a %04o file of root:root failed", (unsigned)mode);
    struct stat sb;
    CHECK(stat(p, &sb) == 0 && sb.st_size > 1000 && sb.st_uid == 65534 && sb.st_gid == want_gid &&
              (sb.st_mode & 07777) == want_mode,
          "user 65534%s wrote over a %04o file of root:root: %u:%u, mode %04o (expected 65534:%u, %04o)",
          in_group ? " in group 0" : "", (unsigned)mode, (unsigned)sb.st_uid, (unsigned)sb.st_gid,
          (unsigned)(sb.st_mode & 07777), (unsigned)want_gid, (unsigned)want_mode);
    remove(p);
    return 1;
}

static void kept_modes_stranger(const rg2_surface *s)
{
    if (geteuid() != 0) {
        printf("  (not root: a file written over by another user is not tested)\n");
        return;
    }
    char *dir = path_in("stranger");
    /* the test directory (mkdtemp: 0700) searchable by the writer while it runs */
    CHECK(chmod(g_dir, 0711) == 0 && mkdir(dir, 0777) == 0 && chmod(dir, 0777) == 0, "mkdir %s", dir);
    if (stranger_case(s, 0664, 0, 0644, 65534)) { /* root's group bits would grant group 65534 more */
        stranger_case(s, 0640, 0, 0600, 65534);   /* the others have nothing: neither has the group */
        stranger_case(s, 0606, 0, 0606, 65534);
        stranger_case(s, 0664, 1, 0664, 0);       /* a member of group 0 keeps it, and the bits */
        stranger_case(s, 0640, 1, 0640, 0);
    } else
        printf("  (cannot become user 65534 here: a file written over by another user is not tested)\n");
    CHECK(rmdir(path_in("stranger")) == 0 && chmod(g_dir, 0700) == 0, "rmdir stranger");
}

static void kept_modes(const rg2_surface *s)
{
    rg2_error err;
    mode_t saved = umask(022);
    static const mode_t modes[] = {0600, 0444, 0640, 0755, 04755, 01644};
    struct stat sb;
    for (size_t k = 0; k < sizeof modes / sizeof *modes; k++) {
        char *p = path_in("mode.obj");
        FILE *f = fopen(p, "w");
        CHECK(f && fputs("x\n", f) >= 0 && fclose(f) == 0 && chmod(p, modes[k]) == 0, "write %s", p);
        CHECK_OK(export_one(s, "mode.obj", &err), &err);
        CHECK(stat(p, &sb) == 0 && sb.st_size > 1000 && (sb.st_mode & 07777) == (modes[k] & 0777),
              "a %04o file written over: mode %04o", (unsigned)modes[k], (unsigned)(sb.st_mode & 07777));
        remove(p);
    }
    /* several outputs of one call, each keeping its own */
    const char *two[2] = {path_in("mode2.obj"), path_in("mode2.stl")};
    for (int k = 0; k < 2; k++) {
        FILE *f = fopen(two[k], "w");
        CHECK(f && fclose(f) == 0 && chmod(two[k], k ? 0604 : 0600) == 0, "write %s", two[k]);
    }
    CHECK_OK(rg2_export_files(s, 1, two, 2, NULL, NULL, &err), &err);
    for (int k = 0; k < 2; k++) {
        CHECK(stat(two[k], &sb) == 0 && (sb.st_mode & 07777) == (k ? 0604u : 0600u),
              "rg2_export_files: %s has mode %04o", two[k], (unsigned)(sb.st_mode & 07777));
        remove(two[k]);
    }
    /* new files: 0666 & ~umask */
    static const mode_t masks[] = {022, 077, 0};
    for (size_t k = 0; k < sizeof masks / sizeof *masks; k++) {
        umask(masks[k]);
        char *p = path_in("mode_new.obj");
        CHECK_OK(export_one(s, "mode_new.obj", &err), &err);
        CHECK(stat(p, &sb) == 0 && (sb.st_mode & 07777) == (0666 & ~masks[k]),
              "a new file under umask %03o: mode %04o", (unsigned)masks[k], (unsigned)(sb.st_mode & 07777));
        remove(p);
    }
    umask(022);
    /* its owner and group too, where the writer may give them (root, as CI runs): a 0660 file of
     * nobody:nogroup stayed 0660 but became root:root, its group bits granting root's group */
    if (geteuid() == 0) {
        char *p = path_in("mode_owner.obj");
        FILE *f = fopen(p, "w");
        CHECK(f && fclose(f) == 0 && chown(p, 65534, 65534) == 0 && chmod(p, 0660) == 0, "chown %s", p);
        CHECK_OK(export_one(s, "mode_owner.obj", &err), &err);
        CHECK(stat(p, &sb) == 0 && sb.st_uid == 65534 && sb.st_gid == 65534 && (sb.st_mode & 07777) == 0660,
              "a 0660 file of 65534:65534 written over: %u:%u, mode %04o", (unsigned)sb.st_uid, (unsigned)sb.st_gid,
              (unsigned)(sb.st_mode & 07777));
        remove(p);
    } else
        printf("  (not root: a file's owner and group kept is not tested)\n");
    kept_modes_stranger(s);
    /* a symbolic link at the path becomes a new file; its 0600 target is left as it was */
    char *target = path_in("mode_target.txt"), *link = path_in("mode_link.obj");
    FILE *f = fopen(target, "w");
    CHECK(f && fclose(f) == 0 && chmod(target, 0600) == 0 && symlink(target, link) == 0, "link %s", link);
    CHECK_OK(export_one(s, "mode_link.obj", &err), &err);
    CHECK(lstat(link, &sb) == 0 && S_ISREG(sb.st_mode) && (sb.st_mode & 07777) == 0644,
          "written over a link: mode %04o", (unsigned)(sb.st_mode & 07777));
    CHECK(stat(target, &sb) == 0 && sb.st_size == 0 && (sb.st_mode & 07777) == 0600, "the link's target changed");
    remove(link);
    remove(target);
    umask(saved);
    printf("  files written over keep their modes (0600, 0444, 0640, 0755; two outputs of one call); new "
           "files 0666 & ~umask\n");
}

static void temp_files(const rg2_surface *s)
{
    rg2_error err;
    int before = count_files();
    kept_modes(s);
    /* a planted symbolic link at the temporary file's name */
    char *out = path_in("planted.obj"), *victim = path_in("victim.txt"), link[300];
    FILE *v = fopen(victim, "w");
    CHECK(v && fputs("victim\n", v) >= 0 && fclose(v) == 0, "write %s", victim);
    snprintf(link, sizeof link, "%s.%ld.tmp", out, (long)getpid());
    CHECK(symlink(victim, link) == 0, "symlink %s", link);
    char next[300], want[300], tiny[8];
    snprintf(want, sizeof want, "%s.%ld.1.tmp", out, (long)getpid());
    CHECK(rg2_temp_name(out, next, sizeof next) == 0 && !strcmp(next, want), "rg2_temp_name: '%s', want '%s'", next,
          want);
    CHECK(rg2_temp_name(out, tiny, sizeof tiny) == -1 && rg2_temp_name(NULL, next, sizeof next) == -1,
          "rg2_temp_name: a small buffer or no path is -1");
    CHECK_OK(export_one(s, "planted.obj", &err), &err);
    size_t len;
    unsigned char *vb = slurp(victim, &len);
    struct stat sb;
    CHECK(vb && len == 7 && !memcmp(vb, "victim\n", 7), "the link's target was written (%zu bytes)", len);
    free(vb);
    CHECK(lstat(out, &sb) == 0 && S_ISREG(sb.st_mode) && sb.st_size > 1000, "%s is not the written file", out);
    CHECK(lstat(link, &sb) == 0 && S_ISLNK(sb.st_mode), "the planted link was removed or replaced");
    remove(link);
    remove(victim);
    remove(out);
    /* two threads, two different surfaces, one path; each result must be one writer's whole file */
    rg2_surface other;
    CHECK_OK(fx_torus(7.0, 2.0, 6, 4, &other, &err), &err);
    char *ref[2] = {path_in("ref0.obj"), path_in("ref1.obj")}, *shared = path_in("shared.obj");
    unsigned char *rb[2];
    size_t rl[2];
    for (int k = 0; k < 2; k++) {
        same_path_job j = {k ? &other : s, ref[k], RG2_EINVAL};
        same_path_writer(&j);
        CHECK_OK(j.st, &err);
        rb[k] = slurp(ref[k], &rl[k]);
    }
    int mixed = 0, failed = 0, wins[2] = {0, 0};
    for (int round = 0; round < 8; round++) {
        same_path_job j[2] = {{s, shared, RG2_EINVAL}, {&other, shared, RG2_EINVAL}};
        pthread_t th[2];
        for (int k = 0; k < 2; k++)
            pthread_create(&th[k], NULL, same_path_writer, &j[k]);
        for (int k = 0; k < 2; k++)
            pthread_join(th[k], NULL);
        failed += j[0].st != RG2_OK || j[1].st != RG2_OK;
        size_t sl;
        unsigned char *sbuf = slurp(shared, &sl);
        int which = -1;
        for (int k = 0; k < 2; k++)
            if (sbuf && rb[k] && sl == rl[k] && !memcmp(sbuf, rb[k], sl))
                which = k;
        if (which < 0)
            mixed++;
        else
            wins[which]++;
        free(sbuf);
    }
    CHECK(!failed && !mixed, "one path from two threads: %d rounds failed, %d left a mixed file", failed, mixed);
    printf("  one path written by two threads at once, 8 rounds: each time one writer's whole file (%d / %d); "
           "a link planted at the temporary name left alone\n", wins[0], wins[1]);
    for (int k = 0; k < 2; k++) {
        free(rb[k]);
        remove(ref[k]);
    }
    remove(shared);
    rg2_surface_free(&other);
    /* file names up to the 255-byte limit: the temporary name is cut to fit, at a character
     * boundary (it was "File name too long" within 12 bytes of the limit), and carries a hash of
     * the whole name (".%08x" before the suffix). utf8 1 and 2 shift the two-byte characters by
     * one byte, so one of them has a character at the cut whatever the pid's length. */
    char first[700] = "";
    for (int utf8 = 0; utf8 < 3; utf8++) {
        char base[256] = "", lng[600], tname[700], suffix[48];
        if (utf8 == 2)
            strcat(base, "a");
        if (utf8)
            for (int c = 0; c < 125; c++)
                strcat(base, "\xc3\xa9"); /* U+00E9, two bytes */
        else
            memset(base, 'x', 251);
        strcat(base, ".obj"); /* 255, 254 and 255 bytes */
        snprintf(lng, sizeof lng, "%s/%s", g_dir, base);
        snprintf(suffix, sizeof suffix, ".%ld.tmp", (long)getpid());
        CHECK(rg2_temp_name(lng, tname, sizeof tname) == 0, "rg2_temp_name of a %zu-byte name", strlen(base));
        const char *tb = tname + strlen(g_dir) + 1;
        size_t kept = strlen(tb) - strlen(suffix) - 9;
        CHECK(strlen(tb) <= 255 && strlen(tb) >= strlen(suffix) + 9 && !strncmp(tb, base, kept) &&
                  tb[kept] == '.' && strspn(tb + kept + 1, "0123456789abcdef") == 8 &&
                  !strcmp(tb + kept + 9, suffix) && (!utf8 || (kept - (utf8 == 2)) % 2 == 0),
              "temporary name of a %zu-byte name: '%s' (%zu bytes)", strlen(base), tb, strlen(tb));
        if (utf8 == 0) {
            snprintf(first, sizeof first, "%s", tname);
            /* a name that differs only past the cut gets another temporary name (the rg2 command
             * predicts each output's to remove it on a signal; they were the same) */
            char alt[600], oname[700];
            snprintf(alt, sizeof alt, "%s/%.251s.stl", g_dir, base);
            CHECK(rg2_temp_name(alt, oname, sizeof oname) == 0 && strcmp(oname, first) != 0,
                  "x...x.obj and x...x.stl: the same temporary name '%s'", oname);
        }
        rg2_export_opts o;
        rg2_export_opts_default(&o);
        o.density = 2;
        CHECK_OK(rg2_export_file(s, 1, lng, &o, &err), &err);
        struct stat lsb;
        CHECK(stat(lng, &lsb) == 0 && lsb.st_size > 100, "a %zu-byte file name was not written", strlen(base));
        remove(lng);
    }
    temp_names_limit(s);
    /* the same path twice in one call */
    const char *twice[3] = {path_in("a.obj"), path_in("b.stl"), path_in("a.obj")};
    int bad = -2;
    CHECK(rg2_export_files(s, 1, twice, 3, NULL, &bad, &err) == RG2_EINVAL && bad == 2 &&
              strstr(err.msg, "given twice (outputs 0 and 2)"),
          "a path given twice: %d '%s'", bad, err.msg);
    CHECK(count_files() == before, "temporary files: %d files before, %d after", before, count_files());
}

/* ---------------------------------------------------------------- poles on a u side */
/* Faces, edges, vertices and closed shells of a STEP file (closed: NULL or the CLOSED_SHELL count). */
static void step_counts(const char *path, int *faces, int *edges, int *verts, int *closed)
{
    size_t len;
    char *b = (char *)slurp(path, &len);
    *faces = *edges = *verts = 0;
    if (closed)
        *closed = 0;
    for (char *p = b; p && (p = strchr(p, '=')); p++) {
        *faces += !strncmp(p + 1, "ADVANCED_FACE(", 14);
        *edges += !strncmp(p + 1, "EDGE_CURVE(", 11);
        *verts += !strncmp(p + 1, "VERTEX_POINT(", 13);
        if (closed)
            *closed += !strncmp(p + 1, "CLOSED_SHELL(", 13);
    }
    free(b);
}

/* Entities of one type in a STEP file ("=LINE(" and the like). */
static int step_count_of(const char *path, const char *type)
{
    size_t len, tl = strlen(type);
    char *b = (char *)slurp(path, &len);
    int n = 0;
    for (char *p = b; p && (p = strstr(p, type)); p += tl)
        n++;
    free(b);
    return n;
}

/* The pcurve lines of several surfaces in one STEP file (docs/export.md, "Pcurves"): face per
 * patch, every face of every surface on [0, 1]^2 uses the same four lines, written once (they
 * were written again for each surface: 12 for three); per mesh, one set of four per surface
 * (each its own rectangle [0, nu] x [0, nv]). */
static void step_lines_shared(const rg2_surface *s)
{
    rg2_surface three[3] = {*s, *s, *s};
    rg2_export_opts o;
    rg2_export_opts_default(&o);
    rg2_error err;
    for (int layout = 0; layout < 2; layout++) {
        o.layout = layout ? RG2_STEP_FACE_PER_MESH : RG2_STEP_FACE_PER_PATCH;
        CHECK_OK(rg2_export_file(three, 3, path_in("three.step"), &o, &err), &err);
        int lines = step_count_of(path_in("three.step"), "=LINE(");
        int reps = step_count_of(path_in("three.step"), "=DEFINITIONAL_REPRESENTATION(");
        int want = layout ? 12 : 4;
        CHECK(lines == want && reps == want,
              "three surfaces in one STEP file, %s: %d lines, %d representations of them, want %d",
              layout ? "per mesh" : "per patch", lines, reps, want);
    }
    remove(path_in("three.step"));
}

/* The pole surface and its transpose (built from the transposed mesh): the same patches with u
 * and v exchanged, and B-reps of the same topology in STEP and IGES (both layouts): the
 * collapsed side is a v = 0 side in one and a u = 0 side in the other. */
static void transposed_pole(void)
{
    rg2_surface a, b;
    rg2_error err;
    CHECK_OK(fx_pole(6, 7, &a, &err), &err);
    CHECK_OK(fx_pole_t(7, 6, &b, &err), &err);
    double d = 0;
    for (int i = 0; i < a.nu && a.nu == b.nv && a.nv == b.nu; i++)
        for (int j = 0; j < a.nv; j++)
            for (int r = 0; r < 4; r++)
                for (int t = 0; t < 4; t++)
                    for (int k = 0; k < 4; k++)
                        d = fmax(d, fabs(rg2_surface_patch(&a, i, j)->h[r][t][k] - rg2_surface_patch(&b, j, i)->h[t][r][k]));
    CHECK(a.nu == b.nv && a.nv == b.nu && b.closed_v && !b.closed_u && d <= 1e-13,
          "transposed pole: %d x %d vs %d x %d patches, %.3g apart", a.nu, a.nv, b.nu, b.nv, d);
    rg2_export_opts o;
    rg2_export_opts_default(&o);
    for (int layout = 0; layout < 2; layout++) {
        o.layout = layout ? RG2_STEP_FACE_PER_MESH : RG2_STEP_FACE_PER_PATCH;
        o.iges_brep = 0;
        CHECK_OK(rg2_export_file(&a, 1, path_in("pa.step"), &o, &err), &err);
        CHECK_OK(rg2_export_file(&b, 1, path_in("pb.step"), &o, &err), &err);
        int f[2], e[2], v[2];
        step_counts(path_in("pa.step"), &f[0], &e[0], &v[0], NULL);
        step_counts(path_in("pb.step"), &f[1], &e[1], &v[1], NULL);
        /* per patch: nu * nv faces; edges: u lines (nu + 1) * nv... less the collapsed ones */
        int want_f = layout ? 1 : a.nu * a.nv;
        CHECK(f[0] == want_f && f[1] == want_f && e[0] == e[1] && v[0] == v[1] && e[0] > 0,
              "STEP %s: faces %d / %d (want %d), edges %d / %d, vertices %d / %d", layout ? "per mesh" : "per patch",
              f[0], f[1], want_f, e[0], e[1], v[0], v[1]);
        o.iges_brep = 1;
        CHECK_OK(rg2_export_file(&a, 1, path_in("pa.igs"), &o, &err), &err);
        CHECK_OK(rg2_export_file(&b, 1, path_in("pb.igs"), &o, &err), &err);
        int ta[1000], tb[1000];
        int bad = iges_scan(path_in("pa.igs"), ta) + iges_scan(path_in("pb.igs"), tb), broken = 0, astray = 0;
        int loops = iges_loops_close(path_in("pb.igs"), &broken, &astray);
        CHECK(bad == 0 && ta[126] == e[0] && tb[126] == e[1] && ta[510] == tb[510] && loops == want_f && broken == 0 &&
                  astray == 0,
              "IGES B-rep %s: %d malformed records, model curves %d / %d (STEP edges %d), faces %d / %d, %d loops "
              "(%d not closing, %d astray)",
              layout ? "per mesh" : "per patch", bad, ta[126], tb[126], e[0], ta[510], tb[510], loops, broken, astray);
    }
    rg2_surface_free(&a);
    rg2_surface_free(&b);
}

/* Edges and vertices of a B-rep on an nu x nv patch grid, counted from the grid alone: corner
 * lines lu = nu (closed u: line nu is line 0) or nu + 1, likewise lv; the collapsed side `pole`
 * (0 v = 0, 1 u = 1, 2 v = 1, 3 u = 0; -1 none) is no edge and its corners are one vertex. The
 * face-per-mesh layout is the same count with nu = nv = 1. */
static void grid_brep(int nu, int nv, int cu, int cv, int pole, int *edges, int *verts)
{
    int lu = cu ? nu : nu + 1, lv = cv ? nv : nv + 1;
    *edges = lu * nv + lv * nu - (pole < 0 ? 0 : (pole & 1) ? nv : nu);
    *verts = lu * lv - (pole < 0 ? 0 : ((pole & 1) ? lv : lu) - 1);
}

/* One surface's STEP (both layouts) against grid_brep: faces, edges (`extra` more), vertices,
 * and a closed shell exactly when `closed`. */
static void pole_brep_counts(const rg2_surface *s, int pole, int closed, int extra, const char *what)
{
    rg2_export_opts o;
    rg2_export_opts_default(&o);
    rg2_error err;
    for (int layout = 0; layout < 2; layout++) {
        o.layout = layout ? RG2_STEP_FACE_PER_MESH : RG2_STEP_FACE_PER_PATCH;
        int f = -1, e = -1, v = -1, sh = -1, we, wv, wf = layout ? 1 : s->nu * s->nv;
        grid_brep(layout ? 1 : s->nu, layout ? 1 : s->nv, s->closed_u, s->closed_v, pole, &we, &wv);
        CHECK_OK(rg2_export_file(s, 1, path_in("brep.step"), &o, &err), &err);
        step_counts(path_in("brep.step"), &f, &e, &v, &sh);
        we += extra;
        CHECK(f == wf && e == we && v == wv && sh == closed,
              "%s (%d x %d patches, closed %d/%d, pole side %d) %s: faces %d, edges %d, vertices %d, closed shell %d; "
              "want %d, %d, %d, %d",
              what, s->nu, s->nv, s->closed_u, s->closed_v, pole, layout ? "per mesh" : "per patch", f, e, v, sh, wf,
              we, wv, closed);
    }
}

/* The pole's topology on every side: the profile's start or end, along v or (transposed) along
 * u, with more arcs than profile patches and fewer, closed around and opened (the closed flag
 * cleared: the same patches, the seam two free sides), counted and read back (brep_case, both
 * layouts); only the torus is a closed shell. A pole side within 1e-11 of the size (docs/export.md) is still a pole, one 10 times
 * that is an edge. */
static void pole_topology(void)
{
    rg2_error err;
    static const int size[2][2] = {{8, 5}, {3, 9}}; /* arcs, profile points */
    for (int z = 0; z < 2; z++)
        for (int t = 0; t < 2; t++)
            for (int end = 0; end < 2; end++)
                for (int open = 0; open < 2; open++) {
                    rg2_surface s;
                    CHECK_OK(fx_revolved(size[z][0], size[z][1], t, end, &s, &err), &err);
                    if (open)
                        *(t ? &s.closed_v : &s.closed_u) = 0;
                    char what[64];
                    snprintf(what, sizeof what, "pole (%d arcs, %d points, %s, %s%s)", size[z][0], size[z][1],
                             t ? "u the profile" : "v the profile", end ? "at its end" : "at its start",
                             open ? ", opened" : "");
                    pole_brep_counts(&s, t ? (end ? 1 : 3) : (end ? 2 : 0), 0, 0, what);
                    /* the counts do not see which corners were merged: merging the corners on
                     * the wrong grid line (the pole side's neighbour) gives as many vertices;
                     * read back, every edge must run between corners at its curve's ends */
                    for (int per_mesh = 0; per_mesh < 2; per_mesh++)
                        brep_case(&s, per_mesh, 0, what);
                    rg2_surface_free(&s);
                }
    rg2_surface s;
    CHECK_OK(fx_torus(13.0, 4.0, 5, 3, &s, &err), &err);
    pole_brep_counts(&s, -1, 1, 0, "torus");
    rg2_surface_free(&s);
    /* the pole side's control point [1][0] of patch (0, 0) moved off the pole by 0.3e-11 and
     * 3e-11 of the control points' box diagonal */
    for (int k = 0; k < 2; k++) {
        CHECK_OK(fx_pole(8, 5, &s, &err), &err);
        double lo[3], hi[3];
        rg2_surface_box(&s, lo, hi);
        double diag = sqrt((hi[0] - lo[0]) * (hi[0] - lo[0]) + (hi[1] - lo[1]) * (hi[1] - lo[1]) +
                           (hi[2] - lo[2]) * (hi[2] - lo[2]));
        double *h = rg2_surface_patch(&s, 0, 0)->h[1][0];
        h[0] += (k ? 3e-11 : 0.3e-11) * diag * h[3];
        /* 3e-11: that side an edge of its own, per patch and per mesh */
        pole_brep_counts(&s, 0, 0, k, k ? "pole moved by 3e-11 of its size" : "pole moved by 0.3e-11 of its size");
        rg2_surface_free(&s);
    }
    remove(path_in("brep.step"));
}

/* ---------------------------------------------------------------- poles written as one point */

/* The poles of s, found here and not by the writers' rule: the point h / w of the first control
 * point of every patch side whose points h / w lie within 1e-13 of the size of each other, one
 * per place (within 1e-12 of the size). How many, at most cap. */
static int pole_places(const rg2_surface *s, double size, double (*at)[3], int cap)
{
    int n = 0;
    for (int i = 0; i < s->nu; i++)
        for (int j = 0; j < s->nv; j++) {
            rg2_xpatch X;
            rg2_surface_patch_get(s, i, j, &X);
            for (int side = 0; side < 4; side++) {
                int m = (side & 1) ? X.dv : X.du;
                double p0[3] = {0, 0, 0}, spread = 0;
                for (int a = 0; a <= m; a++) {
                    const double *h = side == 0 ? X.h[a][0] : side == 1 ? X.h[X.du][a] : side == 2 ? X.h[a][X.dv] : X.h[0][a];
                    for (int d = 0; d < 3; d++) {
                        if (!a)
                            p0[d] = h[d] / h[3];
                        spread = fmax(spread, fabs(h[d] / h[3] - p0[d]));
                    }
                }
                int k = 0;
                while (k < n && !(fabs(at[k][0] - p0[0]) + fabs(at[k][1] - p0[1]) + fabs(at[k][2] - p0[2]) <= 1e-12 * size))
                    k++;
                if (spread <= 1e-13 * size && k == n && n < cap)
                    memcpy(at[n++], p0, sizeof p0);
            }
        }
    return n;
}

/* The 3D points a STEP or IGES file (text, len bytes) writes (CARTESIAN_POINTs; the poles of
 * the 128s and 126s and the 502 vertices), into *pts (malloc'd): how many, -1 unreadable. */
static int file_points(const char *text, size_t len, int iges, double (**pts)[3])
{
    int n = 0, cap = 1024;
    double(*p)[3] = malloc(sizeof(double[3]) * (size_t)cap);
    *pts = NULL;
    if (!p)
        return -1;
    if (!iges) {
        for (const char *q = strstr(text, "CARTESIAN_POINT('',("); q; q = strstr(q + 1, "CARTESIAN_POINT('',(")) {
            double x[3];
            if (sscanf(q, "CARTESIAN_POINT('',(%lf,%lf,%lf))", &x[0], &x[1], &x[2]) != 3)
                continue; /* a 2D point of a pcurve */
            if (n == cap && !(p = realloc(p, sizeof(double[3]) * (size_t)(cap *= 2))))
                return -1;
            memcpy(p[n++], x, sizeof x);
        }
        *pts = p;
        return n;
    }
    iges_nums P;
    if (iges_nums_read(text, len, &P)) {
        iges_nums_free(&P);
        free(p);
        return -1;
    }
    for (int de = 1; de < P.nde; de += 2) {
        const double *v = P.v + P.at[de];
        int at = -1, m = 0;
        if (!P.n[de])
            continue;
        if (v[0] == 128) { /* 10 integers, the two knot vectors, the weights, the poles */
            m = ((int)v[1] + 1) * ((int)v[2] + 1);
            at = 10 + ((int)v[1] + (int)v[3] + 2) + ((int)v[2] + (int)v[4] + 2) + m;
        } else if (v[0] == 126) { /* 7 integers, the knots, the weights, the poles */
            m = (int)v[1] + 1;
            at = 7 + ((int)v[1] + (int)v[2] + 2) + m;
        } else if (v[0] == 502) {
            m = (int)v[1];
            at = 2;
        }
        for (int k = 0; k < m && at + 3 * k + 3 <= P.n[de]; k++) {
            if (n == cap && !(p = realloc(p, sizeof(double[3]) * (size_t)(cap *= 2))))
                return -1;
            memcpy(p[n++], v + at + 3 * k, sizeof(double[3]));
        }
    }
    iges_nums_free(&P);
    *pts = p;
    return n;
}

/* Every collapsed row written as one point: surface s in the six forms (STEP and IGES B-rep face
 * per patch and per mesh, plain IGES per patch and per mesh), and in each, for each pole of s
 * (pole_places), the file's points within 1e-12 of the size of it (the collapsed rows of every
 * patch around it, the edge curves' ends and the vertex there) one double triple bit for bit, the
 * same in the six files and within 16 roundings of the surface's largest coordinate (times ratio,
 * the pole's weights' largest over their smallest) of the pole's h / w.
 * (The points h / w of a collapsed row are one only to rounding: the file's fan of patches
 * met at up to four points 1e-16 apart.) */
static int poles_one_point(const rg2_surface *s, const char *what, double ratio)
{
    static const char *const form[6] = {"STEP per patch", "STEP per mesh", "IGES per patch",
                                         "IGES per mesh", "IGES B-rep per patch", "IGES B-rep per mesh"};
    double size = rg2t_surface_scale(s), at[8][3], ref[8][3], big = 0, lo[3], hi[3];
    int np = pole_places(s, size, at, 8);
    memcpy(ref, at, sizeof ref);
    rg2_surface_box(s, lo, hi);
    for (int d = 0; d < 3; d++)
        big = fmax(big, fmax(fabs(lo[d]), fabs(hi[d])));
    for (int f = 0; f < 6 && np > 0; f++) {
        rg2_export_opts o;
        rg2_export_opts_default(&o);
        o.layout = f & 1 ? RG2_STEP_FACE_PER_MESH : RG2_STEP_FACE_PER_PATCH;
        o.iges_brep = f >= 4;
        rg2_error err;
        char *text = NULL;
        size_t len = 0;
        double(*pts)[3] = NULL;
        CHECK_OK(rg2_export_memory(s, 1, f < 2 ? "step" : "igs", &o, &text, &len, &err), &err);
        int n = text ? file_points(text, len, f >= 2, &pts) : -1;
        CHECK(n > 0, "%s %s: the file's points not read (%d)", what, form[f], n);
        for (int k = 0; k < np && n > 0; k++) {
            int near = 0, differ = 0;
            double worst = 0;
            for (int q = 0; q < n; q++) {
                double dd = 0;
                for (int d = 0; d < 3; d++)
                    dd = fmax(dd, fabs(pts[q][d] - at[k][d]));
                if (!(dd <= 1e-12 * size))
                    continue;
                if (!near++ && f == 0)
                    memcpy(ref[k], pts[q], sizeof ref[k]);
                differ += memcmp(pts[q], ref[k], sizeof ref[k]) != 0;
                worst = fmax(worst, dd);
            }
            CHECK(near >= 3 && differ == 0 && worst <= 16 * ratio * DBL_EPSILON * big,
                  "%s %s: pole %d at (%.17g, %.17g, %.17g): %d points written there, %d of them not the one point "
                  "(%.17g, %.17g, %.17g) of the first file, up to %.3g from the pole's h / w",
                  what, form[f], k, at[k][0], at[k][1], at[k][2], near, differ, ref[k][0], ref[k][1], ref[k][2], worst);
        }
        free(pts);
        free(text);
    }
    return np;
}

/* fx_pole(8, 5) scaled by scale (a power of 2: exact) with one point of its pole side moved off
 * by 0.3e-11 of its size: still a pole of the topology, but its points are written as they are,
 * h / w, once each in STEP and IGES. At scale 2^-30 the move is below 16 roundings of 0.01: a
 * floor under the largest coordinate the pole tolerance is relative to would snap the point. */
static void moved_pole_kept(double scale)
{
    rg2_error err;
    rg2_surface s;
    double M[16];
    CHECK_OK(fx_pole(8, 5, &s, &err), &err);
    rg2_xform_scale(M, scale, scale, scale);
    rg2_surface_transform(&s, M);
    double *h = rg2_surface_patch(&s, 0, 0)->h[1][0];
    h[0] += 0.3e-11 * rg2t_surface_scale(&s) * h[3];
    double want[3] = {h[0] / h[3], h[1] / h[3], h[2] / h[3]};
    for (int f = 0; f < 2; f++) {
        char *text = NULL;
        size_t len = 0;
        double(*pts)[3] = NULL;
        CHECK_OK(rg2_export_memory(&s, 1, f ? "igs" : "step", NULL, &text, &len, &err), &err);
        int n = text ? file_points(text, len, f, &pts) : -1, found = 0;
        for (int q = 0; q < n; q++)
            found += !memcmp(pts[q], want, sizeof want);
        CHECK(found == 1, "pole moved by 0.3e-11 of its size, scale %g, %s: its moved point h / w written %d times, want 1",
              scale, f ? "IGES" : "STEP", found);
        free(pts);
        free(text);
    }
    rg2_surface_free(&s);
}

/* A clamped 4 x 4 NURBS (one patch) whose row v = 0 is one point, (0.1, 0.2, 0.3), with weights
 * alternating 1 and r: a pole, but the construction's sums (weights 1 and r, the clamped end's
 * de Boor points extrapolated) leave its row's points h / w apart by about 0.7 r roundings (21 at
 * r = 32, 150 at r = 200), more than 16: the writers' tolerance grows with the weights' ratio, so
 * it is still written as one point (poles_one_point with the row's weights' ratio). That is the
 * surface rg2_surface_build makes of rg2_nurbs_mesh's mesh; a design's output makes the row the
 * point itself (rg2__surface_set_poles), written as one point all the same. */
static void nurbs_pole_written(double r)
{
    char spec[2048], json[2200];
    int n = snprintf(spec, sizeof spec, "{\"nu\": 4, \"nv\": 4, \"knots_u\": [0, 0, 0, 0, 1, 1, 1, 1], "
                     "\"knots_v\": [0, 0, 0, 0, 1, 1, 1, 1], \"points\": [");
    for (int k = 0; k < 16; k++) {
        double rho = (k % 4) / 3.0, th = 1.2 * M_PI * (k / 4) / 3.0;
        n += snprintf(spec + n, sizeof spec - (size_t)n, "%s[%.17g, %.17g, %.17g]", k ? ", " : "", rho * cos(th) + 0.1,
                      rho * sin(th) + 0.2, 0.4 * rho * rho + 0.3);
    }
    n += snprintf(spec + n, sizeof spec - (size_t)n, "], \"weights\": [");
    for (int k = 0; k < 16; k++)
        n += snprintf(spec + n, sizeof spec - (size_t)n, "%s%.17g", k ? ", " : "", (k / 4 + k % 4) % 2 ? r : 1.0);
    snprintf(spec + n, sizeof spec - (size_t)n, "]}");
    snprintf(json, sizeof json, "{\"shapes\": {}, \"meshes\": {\"N\": {\"nurbs\": %s}}}", spec);
    rg2_error err;
    rg2_mesh m;
    rg2_surface built = {0};
    rg2_design *d = NULL;
    CHECK_OK(rg2_nurbs_parse(spec, strlen(spec), "nurbs_pole", &m, &err), &err);
    CHECK_OK(rg2_surface_build(&m, &built, &err), &err);
    CHECK_OK(rg2_design_parse(json, strlen(json), "nurbs_pole", &d, &err), &err);
    for (int k = 0; k < 2; k++) {
        const rg2_surface *s = k ? (d ? rg2_design_surface(d, 0) : NULL) : built.patch ? &built : NULL;
        if (!s)
            continue;
        double wlo = INFINITY, whi = 0, spread = 0, p0[3];
        rg2_xpatch X;
        rg2_surface_patch_get(s, 0, 0, &X);
        for (int a = 0; a <= X.du; a++) {
            const double *h = X.h[a][0];
            wlo = fmin(wlo, fabs(h[3])), whi = fmax(whi, fabs(h[3]));
            for (int c = 0; c < 3; c++) {
                if (!a)
                    p0[c] = h[c] / h[3];
                spread = fmax(spread, fabs(h[c] / h[3] - p0[c]));
            }
        }
        char what[96];
        snprintf(what, sizeof what, "NURBS pole, weights 1 and %g (%s)", r, k ? "the design's" : "rg2_surface_build's");
        if (!k)
            CHECK(spread > 16 * DBL_EPSILON * 1.3, "%s: its row's points h / w %.3g apart, want more than 16 roundings",
                  what, spread);
        else
            CHECK(spread <= 2 * DBL_EPSILON * 1.3, "%s: its row's points h / w %.3g apart, want one point", what,
                  spread);
        CHECK(poles_one_point(s, what, whi / wlo) == 1, "%s: its pole not found", what);
    }
    rg2_design_free(d);
    rg2_surface_free(&built);
    rg2_mesh_free(&m);
}

/* The capped spheres of Fig. 9 and Fig. 14 (their collapsed rows one point only to rounding,
 * the weights along them differing) and the pole surface along v and along u, its pole at the
 * profile's start and at its end (there also with each patch's 4-tuples scaled by a factor of its
 * own); a pole side with one point moved off (moved_pole_kept, at scale 1 and 2^-30): a short
 * side is not a pole's one point; and a NURBS pole whose weights differ 32 and 200 times. */
static void poles_written(void)
{
    static const char *const files[] = {"examples/fig9_polar_sphere.json", "examples/fig14_mobius.json"};
    rg2_error err;
    int poles = 0; /* Fig. 9: its capped sphere's two; Fig. 14: three capped spheres' */
    for (int k = 0; k < 2; k++) {
        rg2_design *d = NULL;
        CHECK_OK(rg2_design_load(files[k], &d, &err), &err);
        for (int q = 0; d && q < rg2_design_num_surfaces(d); q++) {
            char what[96];
            snprintf(what, sizeof what, "%s surface %d", files[k], q);
            poles += poles_one_point(rg2_design_surface(d, q), what, 1.0);
        }
        rg2_design_free(d);
    }
    CHECK(poles == 8, "the capped spheres of Fig. 9 and Fig. 14: %d poles found, want 8", poles);
    rg2_surface s;
    CHECK_OK(fx_pole(6, 7, &s, &err), &err);
    CHECK(poles_one_point(&s, "pole surface (v = 0 side)", 1.0) == 1, "pole surface: its pole not found");
    rg2_surface_free(&s);
    CHECK_OK(fx_pole_t(7, 6, &s, &err), &err);
    CHECK(poles_one_point(&s, "transposed pole surface (u = 0 side)", 1.0) == 1, "transposed pole surface: its pole not found");
    rg2_surface_free(&s);
    for (int t = 0; t < 3; t++) { /* the pole at the profile's end (the topology's last edges),
                                    * moved off the axis (its rows' h / w then differ by roundings);
                                    * t = 2: along v, every patch's 4-tuples times a factor of its
                                    * own (the same surface; the pole's corners then differ too) */
        static const char *const name[3] = {"pole surface (v = 1 side)", "transposed pole surface (u = 1 side)",
                                            "pole surface (v = 1 side), patches scaled"};
        double M[16];
        CHECK_OK(fx_revolved(7, 7, t == 1, 1, &s, &err), &err);
        rg2_xform_translate(M, 0.1, 0.2, 0.3);
        rg2_surface_transform(&s, M);
        for (int i = 0; i < s.nu && t == 2; i++)
            for (int j = 0; j < s.nv; j++)
                for (int r = 0; r < 16; r++)
                    for (int d = 0; d < 4; d++)
                        rg2_surface_patch(&s, i, j)->h[r / 4][r % 4][d] *= 7.0 / (3 + i + 2 * j);
        CHECK(poles_one_point(&s, name[t], 1.0) == 1, "%s: its pole not found", name[t]);
        rg2_surface_free(&s);
    }
    moved_pole_kept(1.0);
    moved_pole_kept(0x1p-30);
    nurbs_pole_written(32);
    nurbs_pole_written(200);
}

/* ---------------------------------------------------------------- UTF-8 */
/* rg2__utf8_len (the names of glTF and JSON, design files) against the code point: every lead
 * byte with every second byte, the rest 0x80 or 0xBF, is one character of k bytes exactly when its
 * bits decode to a code point that needs k bytes (no overlong form), is at most U+10FFFF and no
 * surrogate (RFC 3629); cut one byte short it is none. */
static void utf8_table(void)
{
    int bad = 0, first = -1;
    for (int b0 = 0; b0 < 256; b0++)
        for (int b1 = 0; b1 < 256; b1++)
            for (int tail = 0x80; tail <= 0xBF; tail += 0x3F) {
                unsigned char p[4] = {(unsigned char)b0, (unsigned char)b1, (unsigned char)tail, (unsigned char)tail};
                int k = b0 < 0x80 ? 1 : (b0 & 0xE0) == 0xC0 ? 2 : (b0 & 0xF0) == 0xE0 ? 3 : (b0 & 0xF8) == 0xF0 ? 4 : 0;
                long cp = k == 1 ? b0 : k ? (b0 & (0x7F >> k)) : 0;
                for (int i = 1; i < k; i++)
                    cp = cp << 6 | (p[i] & 0x3F);
                static const long least[5] = {0, 0, 0x80, 0x800, 0x10000};
                int conts = 1;
                for (int i = 1; i < k; i++)
                    conts &= (p[i] & 0xC0) == 0x80;
                int ok = k && conts && cp >= least[k] && cp <= 0x10FFFF && !(cp >= 0xD800 && cp <= 0xDFFF);
                size_t got = rg2__utf8_len(p, 4), cut = k > 1 ? rg2__utf8_len(p, (size_t)k - 1) : 0;
                if (got != (size_t)(ok ? k : 0) || cut != 0) {
                    bad++;
                    if (first < 0)
                        first = b0 << 8 | b1;
                }
            }
    CHECK(bad == 0, "rg2__utf8_len: %d of 131072 sequences wrong, the first %02X %02X", bad, first >> 8, first & 0xFF);
}

/* ---------------------------------------------------------------- names, defaults, exponents */
/* Names in STEP strings (apostrophes doubled, backslashes doubled, other bytes outside printable
 * ASCII replaced) and IGES Hollerith strings (the raw count of characters); options left at 0 /
 * NULL and no options at all give the documented defaults (name "rg2", density 16: the same
 * bytes); a number of one significant digit past 1e16 is written with its decimal point. */
static void names_and_defaults(const rg2_surface *s)
{
    rg2_error err;
    rg2_export_opts o;
    rg2_export_opts_default(&o);
    o.name = "part 'A' \\ B \xc3\xa9"; /* part 'A' \ B e-acute (2 bytes of UTF-8) */
    CHECK_OK(rg2_export_file(s, 1, path_in("it's a \\ test.step"), &o, &err), &err);
    size_t len;
    char *b = (char *)slurp(path_in("it's a \\ test.step"), &len);
    CHECK(b && strstr(b, "FILE_NAME('it''s a \\\\ test.step',"), "STEP: file name string");
    CHECK(b && strstr(b, "=PRODUCT('part ''A'' \\\\ B __','part ''A'' \\\\ B __',") &&
              strstr(b, "=MANIFOLD_SURFACE_SHAPE_REPRESENTATION('part ''A'' \\\\ B __',"),
          "STEP: product name string");
    int odd = 0; /* every record's apostrophes pair up */
    for (char *p = b; b && p && *p;) {
        char *e = strchr(p, '\n');
        int q = 0;
        for (char *c = p; c < (e ? e : p + strlen(p)); c++)
            q += *c == '\'';
        odd += q % 2;
        p = e ? e + 1 : NULL;
    }
    CHECK(b && odd == 0, "STEP: %d lines with an unpaired apostrophe", odd);
    free(b);
    CHECK_OK(rg2_export_file(s, 1, path_in("named.igs"), &o, &err), &err);
    b = (char *)slurp(path_in("named.igs"), &len);
    CHECK(b && strstr(b, ",15Hpart 'A' \\ B __,") && strstr(b, ",9Hnamed.igs,"), "IGES: Hollerith name and file name");
    free(b);

    /* control characters in the name: a newline would end the OBJ and PLY header comments */
    rg2_export_opts_default(&o);
    o.name = "two\nlines\tand\x7f";
    o.density = 2;
    CHECK_OK(rg2_export_file(s, 1, path_in("ctl.obj"), &o, &err), &err);
    CHECK_OK(rg2_export_file(s, 1, path_in("ctl.ply"), &o, &err), &err);
    CHECK_OK(rg2_export_file(s, 1, path_in("ctl.step"), &o, &err), &err);
    b = (char *)slurp(path_in("ctl.obj"), &len);
    CHECK(b && strstr(b, ": two_lines_and_, ") && !strncmp(strchr(b, '\n') + 1, "o surface_0\n", 12),
          "OBJ: name on the comment line, then the object: %.80s", b ? b : "");
    free(b);
    b = (char *)slurp(path_in("ctl.ply"), &len);
    int bad_header = !b, lines = 0;
    static const char *const kw[] = {"ply\n", "format ", "comment ", "element ", "property ", "end_header\n"};
    for (char *p = b; p && !bad_header;) { /* every header line starts with a PLY keyword */
        int ok = 0;
        for (size_t k = 0; k < sizeof kw / sizeof kw[0]; k++)
            ok |= !strncmp(p, kw[k], strlen(kw[k]));
        bad_header = !ok;
        lines++;
        if (!strncmp(p, "end_header\n", 11))
            break;
        p = strchr(p, '\n');
        p = p ? p + 1 : NULL;
    }
    CHECK(!bad_header && b && strstr(b, "two_lines_and_"), "PLY header: line %d is not a PLY keyword", lines);
    free(b);
    b = (char *)slurp(path_in("ctl.step"), &len);
    CHECK(b && strstr(b, "=PRODUCT('two_lines_and_','two_lines_and_',"), "STEP: control characters as '_'");
    free(b);
    /* IGES's Hollerith strings likewise: the global section's product ids (fields 3 and 12), and
     * its file name (field 4), which comes from the path as it is: a DEL in it written as '_' */
    CHECK_OK(rg2_export_file(s, 1, path_in("ctl\x7f.igs"), &o, &err), &err);
    b = (char *)slurp(path_in("ctl\x7f.igs"), &len);
    int ids = 0, fname = 0; /* each a whole token: after a delimiter, or first on its record */
    for (char *p = b; p && (p = strstr(p, "14Htwo_lines_and_,")); p++)
        ids += p > b && (p[-1] == ',' || p[-1] == '\n');
    for (char *p = b; p && (p = strstr(p, "8Hctl_.igs,")); p++)
        fname += p > b && (p[-1] == ',' || p[-1] == '\n');
    CHECK(ids == 2 && fname == 1,
          "IGES: %d product ids 14Htwo_lines_and_ (want 2: newline, tab and DEL as '_'), %d file names 8Hctl_.igs (want 1)",
          ids, fname);
    free(b);

    /* a name that is not UTF-8 (Latin-1 e-acute, then the same letter in UTF-8): glTF and JSON
     * are UTF-8 text, so the stray byte is written as '?' */
    rg2_export_opts_default(&o);
    o.name = "caf\xe9 \xc3\xa9";
    o.density = 2;
    CHECK_OK(rg2_export_file(s, 1, path_in("latin.json"), &o, &err), &err);
    CHECK_OK(rg2_export_file(s, 1, path_in("latin.glb"), &o, &err), &err);
    static const char *const latin[] = {"latin.json", "latin.glb"};
    for (int k = 0; k < 2; k++) {
        unsigned char *u = slurp(path_in(latin[k]), &len);
        int good = 0, bad = 0; /* (a byte search: the glb's binary chunk may hold NULs) */
        for (size_t i = 0; u && i + 9 <= len; i++) {
            good |= !memcmp(u + i, "\"caf? \xc3\xa9\"", 9);
            bad |= !memcmp(u + i, "caf\xe9", 4);
        }
        CHECK(u && good && !bad,
              "%s: the name as UTF-8 with '?' for the Latin-1 byte", latin[k]);
        free(u);
    }

    /* defaults: name NULL and density 0 are "rg2" and 16, as are no options */
    rg2_export_opts z;
    memset(&z, 0, sizeof z);
    rg2_export_opts_default(&o);
    CHECK(o.density == 16 && !strcmp(o.name, "rg2") && o.layout == RG2_STEP_FACE_PER_PATCH && !o.ap242 &&
              !o.iges_brep,
          "rg2_export_opts_default");
    CHECK_OK(rg2_export_file(s, 1, path_in("def.obj"), &o, &err), &err);
    CHECK_OK(rg2_export_file(s, 1, path_in("zero.obj"), &z, &err), &err);
    CHECK_OK(rg2_export_file(s, 1, path_in("null.obj"), NULL, &err), &err);
    size_t l1, l2, l3;
    unsigned char *a = slurp(path_in("def.obj"), &l1), *c = slurp(path_in("zero.obj"), &l2),
                  *d = slurp(path_in("null.obj"), &l3);
    int nv = 0;
    for (size_t k = 0; a && k + 1 < l1; k++)
        nv += (k == 0 || a[k - 1] == '\n') && a[k] == 'v' && a[k + 1] == ' ';
    int want = s->nu * 16 * s->nv * 16; /* closed in both directions: (16 nu) x (16 nv) vertices */
    CHECK(a && c && d && l1 == l2 && l1 == l3 && !memcmp(a, c, l1) && !memcmp(a, d, l1) && nv == want &&
              strstr((char *)a, "rg2"),
          "OBJ with name NULL / density 0 / no options: %zu, %zu, %zu bytes, %d vertices (density 16: %d)", l1, l2,
          l3, nv, want);
    free(a);
    free(c);
    free(d);
    CHECK_OK(rg2_export_file(s, 1, path_in("zero.step"), &z, &err), &err);
    b = (char *)slurp(path_in("zero.step"), &len);
    CHECK(b && strstr(b, "=PRODUCT('rg2','rg2',"), "STEP with name NULL: product 'rg2'");
    free(b);

    /* a torus of size 1e20 with quarter arcs: vertices such as (4e20, 0, 0), whose %.17G form
     * "4E+20" needs its decimal point ("4.E+20"); step_text checks every real of the files */
    const char *json = "{\"shapes\": {\"t\": {\"kind\": \"torus\", \"R\": 3e20, \"r\": 1e20}},"
                       " \"meshes\": {\"T\": {\"shape\": \"t\", \"u\": {\"arcs\": 4}, \"v\": {\"arcs\": 4}}}}";
    rg2_design *dz = NULL;
    CHECK_OK(rg2_design_parse(json, strlen(json), "big", &dz, &err), &err);
    if (!dz)
        return;
    rg2_surface big = *rg2_design_surface(dz, 0); /* (a view: the design owns it) */
    CHECK_OK(export_one(&big, "big.step", &err), &err);
    b = (char *)slurp(path_in("big.step"), &len);
    CHECK(b && strstr(b, "(4.E+20,0.,0.)"), "STEP: the vertex (4e20, 0, 0) written as (4.E+20,0.,0.)");
    free(b);
    CHECK_OK(export_one(&big, "big.igs", &err), &err);
    b = (char *)slurp(path_in("big.igs"), &len);
    CHECK(b && strstr(b, ",4.E+20,"), "IGES: 4e20 written as 4.E+20");
    free(b);
    step_text(&big);
    rg2_design_free(dz);
}

/* A host program that uses cJSON itself with its own allocator (cJSON_InitHooks: one cJSON for
 * the whole process): what cJSON_Print returns goes back through cJSON_free. The .json and .glb
 * writers passed it to free(), which aborted ("double free or corruption") with these hooks. */
static unsigned g_hook_blocks;
static void *hook_malloc(size_t n)
{
    unsigned char *p = malloc(n + 16);
    if (!p)
        return NULL;
    g_hook_blocks++;
    return p + 16;
}
static void hook_free(void *p)
{
    if (p) {
        g_hook_blocks--;
        free((unsigned char *)p - 16);
    }
}

static void cjson_hooks(const rg2_surface *s)
{
    cJSON_Hooks h = {hook_malloc, hook_free};
    cJSON_InitHooks(&h);
    const char *names[] = {"hooks.json", "hooks.glb"};
    for (int k = 0; k < 2; k++) {
        rg2_error err;
        rg2_status st = export_one(s, names[k], &err);
        CHECK(st == RG2_OK, "%s with the host's cJSON hooks: %s", names[k], err.msg);
    }
    cJSON_InitHooks(NULL);
    CHECK(g_hook_blocks == 0, "%u blocks of the host's cJSON allocator not given back", g_hook_blocks);
}

/* The JSON patch dump is written as it is formatted (it was a cJSON tree of the whole dump, then
 * its printed text: 3 times the file at the peak). Two design surfaces, the first of more patches
 * than one formatting block (256), with tags, a name cJSON has to escape, and patches of degree
 * (5, 3) in the second: read back, everything equals the surfaces, exactly. */
static void json_dump_stream(void)
{
    const char *json =
        "{\"shapes\": {\"t\": {\"kind\": \"torus\", \"R\": 3, \"r\": 1}, \"b\": {\"kind\": \"paraboloid\"},"
        " \"c\": {\"kind\": \"cylinder\"}},"
        " \"meshes\": {\"T\": {\"shape\": \"t\", \"u\": {\"arcs\": 24}, \"v\": {\"arcs\": 12}},"
        " \"E\": {\"edit\": \"T\", \"points\": [{\"at\": [3, 4], \"move\": [0, 0, 0.3]}]},"
        " \"B\": {\"polar\": \"b\", \"u\": {\"arcs\": 8}, \"v\": {\"knots\": [0.3, 0.6, 0.9, 1.2]}},"
        " \"C\": {\"shape\": \"c\", \"u\": {\"arcs\": 8}, \"v\": {\"segments\": 3, \"from\": 3, \"to\": 4.8}},"
        " \"BC\": {\"merge\": [\"B\", \"C\"], \"along\": \"v\"},"
        " \"cap\": {\"cap\": \"BC\", \"ends\": \"north\", \"quadratic\": \"general\"}},"
        " \"output\": [\"E\", \"cap\"]}";
    rg2_design *d = NULL;
    rg2_error err;
    CHECK_OK(rg2_design_parse(json, strlen(json), "dump", &d, &err), &err);
    if (!d)
        return;
    rg2_surface surfs[2] = {*rg2_design_surface(d, 0), *rg2_design_surface(d, 1)};
    rg2_export_opts o;
    rg2_export_opts_default(&o);
    o.name = "a \"quoted\" \\ name";
    CHECK_OK(rg2_export_file(surfs, 2, path_in("two.json"), &o, &err), &err);
    size_t len;
    unsigned char *b = slurp(path_in("two.json"), &len);
    cJSON *j = b ? cJSON_Parse((char *)b) : NULL;
    const cJSON *arr = cJSON_GetObjectItemCaseSensitive(j, "surfaces"), *nm = cJSON_GetObjectItemCaseSensitive(j, "name");
    int bad = cJSON_GetArraySize(arr) != 2 || !cJSON_IsString(nm) || strcmp(nm->valuestring, o.name) ||
              num(j, "version") != 2, high = 0;
    for (int k = 0; k < 2 && !bad; k++) {
        const rg2_surface *s = &surfs[k];
        int np = s->nu * s->nv;
        const cJSON *sf = cJSON_GetArrayItem(arr, k), *pa = cJSON_GetObjectItemCaseSensitive(sf, "patches");
        const cJSON *tg = cJSON_GetObjectItemCaseSensitive(sf, "tag"), *jdu = cJSON_GetObjectItemCaseSensitive(sf, "du"),
                    *jdv = cJSON_GetObjectItemCaseSensitive(sf, "dv"), *bu = cJSON_GetObjectItemCaseSensitive(sf, "bu");
        bad += num(sf, "nu") != s->nu || num(sf, "nv") != s->nv || cJSON_GetArraySize(pa) != np ||
               cJSON_GetArraySize(tg) != np || cJSON_GetArraySize(jdu) != np || cJSON_GetArraySize(jdv) != np ||
               cJSON_GetArraySize(bu) != s->nu || cJSON_IsTrue(cJSON_GetObjectItemCaseSensitive(sf, "closed_u")) != s->closed_u;
        for (int i = 0; i < s->nu && !bad; i++)
            bad += cJSON_GetArrayItem(bu, i)->valuedouble != s->bu[i];
        const cJSON *jp = pa ? pa->child : NULL, *t = tg ? tg->child : NULL, *a = jdu ? jdu->child : NULL,
                    *c = jdv ? jdv->child : NULL;
        for (int p = 0; p < np && !bad; p++, jp = jp->next, t = t->next, a = a->next, c = c->next) {
            rg2_xpatch X;
            rg2_surface_patch_get(s, p / s->nv, p % s->nv, &X);
            high += X.du > 3;
            bad += t->valueint != s->tag[p] || a->valueint != X.du || c->valueint != X.dv ||
                   cJSON_GetArraySize(jp) != 4 * (X.du + 1) * (X.dv + 1);
            int q = 0;
            for (const cJSON *x = jp->child; x && !bad; x = x->next, q++)
                bad += x->valuedouble != X.h[q / (4 * (X.dv + 1))][q / 4 % (X.dv + 1)][q % 4];
        }
    }
    CHECK(j && bad == 0 && surfs[0].nu * surfs[0].nv > 256 && high > 0,
          "JSON dump of 2 surfaces (%d and %d patches, %d of a higher degree): %d mismatches", surfs[0].nu * surfs[0].nv,
          surfs[1].nu * surfs[1].nv, high, bad);
    CHECK(len > 0 && b[len - 1] == '\n' && !strncmp((char *)b, "{\n\t\"surfaces\":\t[{\n\t\t\t\"nu\":\t24,\n", 30),
          "JSON dump layout: starts '%.30s'", b ? (char *)b : "");
    cJSON_Delete(j);
    free(b);
    rg2_design_free(d);
}

int main(void)
{
    snprintf(g_dir, sizeof g_dir, "/tmp/rg2_export_XXXXXX");
    if (!mkdtemp(g_dir)) {
        perror("mkdtemp");
        return 1;
    }
    rg2_surface s;
    rg2_error err;
    rg2_tess t;
    CHECK_OK(fx_torus(13.0, 4.0, 6, 4, &s, &err), &err);
    CHECK_OK(rg2_tessellate(&s, 6, 0, &t, &err), &err);
    obj_roundtrip(&s, &t, 6);
    {
        rg2_tess big; /* 55 296 vertices, 110 592 faces: several batches of blocks */
        CHECK_OK(rg2_tessellate(&s, 48, 0, &big, &err), &err);
        obj_roundtrip(&s, &big, 48);
        rg2_tess_free(&big);
    }
    stl_roundtrip(&s, &t);
    stl_facet_normals(&s, &t);
    ply_roundtrip(&s, &t);
    glb_validate(&s, &t);
    patches_roundtrip(&s, 13.0, 4.0);
    step_text(&s);
    breps_read_back(&s);
    step_big_in_order();
    iges_big();
    iges_small_weights();
    iges_one_small_weight();
    utf8_table();
    names_and_defaults(&s);
    transposed_pole();
    pole_topology();
    poles_written();
    step_lines_shared(&s);
    full_disk(&s);
    temp_files(&s);
    failures(&s);
    cjson_hooks(&s);
    several_files(&s);
    float_range();
    float_max();
    vertex_limit(&s);
    export_degrees(&s);
    json_dump_stream();
    rg2_surface x;
    CHECK_OK(elevated_torus(&x, &err), &err);
    patches_roundtrip(&x, 13.0, 4.0);
    step_text(&x);
    export_degrees(&x);
    xfailures(&x);
    into_memory(&s, &x);
    time_stamps(&s);
    int Du, Dv;
    rg2_surface_degree(&x, &Du, &Dv);
    printf("higher-degree patches (torus 6 x 4, degrees up to (%d, %d)): .bez elevated patches %.2e from rg2's, "
           "%.2e from the exact torus (relative); degrees checked in STEP/IGES for %d surfaces\n",
           Du, Dv, g_bez_dev, g_bez_torus, g_deg_checked);
    rg2_surface_free(&x);
    rg2_tess_free(&t);
    rg2_surface_free(&s);
    /* clean up */
    DIR *d = opendir(g_dir);
    struct dirent *e;
    while (d && (e = readdir(d)))
        if (e->d_name[0] != '.')
            remove(path_in(e->d_name));
    if (d)
        closedir(d);
    rmdir(g_dir);
    return rg2t_done("test_export");
}
