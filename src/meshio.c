/* meshio.c -- triangle mesh files from tessellations: OBJ (positions and normals, 17
 * digits), binary STL, binary PLY (normals, Gaussian and mean curvature per vertex) and
 * glTF 2.0 binary (.glb). Several surfaces are written as separate objects / primitives. */
#include "export_internal.h"

#include <cjson/cJSON.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

/* ---------------------------------------------------------------- little-endian output */

/* Binary output through a buffer: one fwrite per 16 KB instead of one per value (stdio locks the
 * stream at every call; the STL of 983 040 triangles took 0.30 s, docs/export.md). */
typedef struct {
    FILE *f;
    size_t n;
    unsigned char b[16384];
} le_out;

static void le_flush(le_out *w)
{
    if (w->n)
        fwrite(w->b, 1, w->n, w->f);
    w->n = 0;
}

static void le_bytes(le_out *w, const void *p, size_t len)
{
    if (len > sizeof w->b - w->n)
        le_flush(w);
    if (len >= sizeof w->b) {
        fwrite(p, 1, len, w->f);
        return;
    }
    memcpy(w->b + w->n, p, len);
    w->n += len;
}

static void le_u32(le_out *w, uint32_t x)
{
    unsigned char b[4] = {(unsigned char)x, (unsigned char)(x >> 8), (unsigned char)(x >> 16),
                          (unsigned char)(x >> 24)};
    le_bytes(w, b, 4);
}

static void le_u16(le_out *w, unsigned x)
{
    unsigned char b[2] = {(unsigned char)x, (unsigned char)(x >> 8)};
    le_bytes(w, b, 2);
}

static void le_u8(le_out *w, unsigned x)
{
    unsigned char b = (unsigned char)x;
    le_bytes(w, &b, 1);
}

static void le_f32(le_out *w, double x)
{
    /* beyond FLT_MAX + half an ulp (0x1.ffffffp127) the conversion rounds to +-inf: that inf
     * without the conversion's FE_OVERFLOW (curvatures of a surface near the float formats'
     * smallest size, 1e-31, pass 3.4e38) */
    float v = isgreaterequal(fabs(x), 0x1.ffffffp127) ? (float)copysign(HUGE_VAL, x) : (float)x;
    uint32_t u;
    memcpy(&u, &v, 4);
    le_u32(w, u);
}

static void le_i32(le_out *w, int x) { le_u32(w, (uint32_t)x); }

static size_t total_triangles(const rg2_tess *t, int n)
{
    size_t s = 0;
    for (int k = 0; k < n; k++)
        s += (size_t)t[k].n_triangles;
    return s;
}

static size_t total_vertices(const rg2_tess *t, int n)
{
    size_t s = 0;
    for (int k = 0; k < n; k++)
        s += (size_t)t[k].n_vertices;
    return s;
}

/* ---------------------------------------------------------------- OBJ */

/* OBJ's lines are formatted on the threads (rg2__write_blocks; printf's 17 digits are nearly all
 * of the time: the bundled design at density 64, 3 million numbers, took 0.7 s on one thread). */
#define OBJ_LINES 2048 /* per block */

enum { OBJ_V, OBJ_VN, OBJ_F };

typedef struct {
    const rg2_tess *t;
    int kind;
    size_t base; /* OBJ number of the surface's first vertex */
} obj_part;

static int obj_block(FILE *m, void *arg, int b, int k0, int k1)
{
    (void)b;
    const obj_part *o = arg;
    const rg2_tess *t = o->t;
    for (int i = k0; i < k1; i++) {
        if (o->kind != OBJ_F) {
            const double *x = (o->kind == OBJ_V ? t->pos : t->normal) + 3 * (size_t)i;
            fprintf(m, "%s %.17g %.17g %.17g\n", o->kind == OBJ_V ? "v" : "vn", x[0], x[1], x[2]);
        } else {
            const int *c = t->tri + 3 * (size_t)i;
            size_t a = o->base + (size_t)c[0], bb = o->base + (size_t)c[1], d = o->base + (size_t)c[2];
            fprintf(m, "f %zu//%zu %zu//%zu %zu//%zu\n", a, a, bb, bb, d, d);
        }
    }
    return 0;
}

rg2_status rg2__write_obj(const rg2_tess *t, int n, const rg2_export_opts *o, rg2__out *out,
                          rg2_error *err)
{
    FILE *f = out->f;
    fprintf(f, "# rg2 %s: %s, %zu vertices, %zu triangles (exact points and normals)\n", rg2_version(),
            o->name, total_vertices(t, n), total_triangles(t, n));
    size_t base = 1;
    for (int k = 0; k < n; k++) {
        fprintf(f, "o surface_%d\n", k);
        for (int kind = OBJ_V; kind <= OBJ_F; kind++) {
            obj_part part = {&t[k], kind, base};
            if (rg2__write_blocks(f, kind == OBJ_F ? t[k].n_triangles : t[k].n_vertices, OBJ_LINES, obj_block,
                                  NULL, &part))
                return rg2__fail(err, RG2_ENOMEM, "%s: out of memory for the OBJ text", out->path);
        }
        base += (size_t)t[k].n_vertices;
    }
    return RG2_OK;
}

/* ---------------------------------------------------------------- STL */

rg2_status rg2__write_stl(const rg2_tess *t, int n, const rg2_export_opts *o, rg2__out *out,
                          rg2_error *err)
{
    size_t nt = total_triangles(t, n);
    if (nt > UINT32_MAX)
        return rg2__fail(err, RG2_ELIMIT, "%s: %zu triangles exceed binary STL's 32-bit count", out->path,
                         nt);
    le_out w = {.f = out->f}, *f = &w;
    char header[80];
    memset(header, ' ', sizeof header);
    char text[80];
    int len = snprintf(text, sizeof text, "rg2 %s binary STL: %s", rg2_version(), o->name);
    memcpy(header, text, (size_t)(len < 80 ? len : 79));
    le_bytes(f, header, 80);
    le_u32(f, (uint32_t)nt);
    for (int k = 0; k < n; k++)
        for (int q = 0; q < t[k].n_triangles; q++) {
            const int *c = t[k].tri + 3 * q;
            const double *a = t[k].pos + 3 * c[0], *b = t[k].pos + 3 * c[1], *d = t[k].pos + 3 * c[2];
            double e1[3] = {b[0] - a[0], b[1] - a[1], b[2] - a[2]};
            double e2[3] = {d[0] - a[0], d[1] - a[1], d[2] - a[2]};
            double nn[3] = {e1[1] * e2[2] - e1[2] * e2[1], e1[2] * e2[0] - e1[0] * e2[2],
                            e1[0] * e2[1] - e1[1] * e2[0]};
            double l = sqrt(nn[0] * nn[0] + nn[1] * nn[1] + nn[2] * nn[2]);
            if (!(l > 0.0)) { /* degenerate facet: the mean of the exact vertex normals */
                for (int m = 0; m < 3; m++)
                    nn[m] = t[k].normal[3 * c[0] + m] + t[k].normal[3 * c[1] + m] + t[k].normal[3 * c[2] + m];
                l = sqrt(nn[0] * nn[0] + nn[1] * nn[1] + nn[2] * nn[2]);
            }
            for (int m = 0; m < 3; m++)
                le_f32(f, l > 0.0 ? nn[m] / l : 0.0);
            for (int v = 0; v < 3; v++)
                for (int m = 0; m < 3; m++)
                    le_f32(f, t[k].pos[3 * c[v] + m]);
            le_u16(f, 0);
        }
    le_flush(f);
    return RG2_OK;
}

/* ---------------------------------------------------------------- PLY */

rg2_status rg2__write_ply(const rg2_tess *t, int n, const rg2_export_opts *o, rg2__out *out,
                          rg2_error *err)
{
    size_t nv = total_vertices(t, n), nt = total_triangles(t, n);
    if (nv > INT32_MAX)
        return rg2__fail(err, RG2_ELIMIT, "%s: %zu vertices exceed PLY's int indices", out->path, nv);
    fprintf(out->f, "ply\nformat binary_little_endian 1.0\ncomment rg2 %s: %s\n"
               "comment exact points, unit normals, Gaussian and mean curvature of the surface\n"
               "element vertex %zu\nproperty float x\nproperty float y\nproperty float z\n"
               "property float nx\nproperty float ny\nproperty float nz\n"
               "property float gaussian_curvature\nproperty float mean_curvature\n"
               "element face %zu\nproperty list uchar int vertex_indices\nend_header\n",
            rg2_version(), o->name, nv, nt);
    le_out w = {.f = out->f}, *f = &w;
    for (int k = 0; k < n; k++)
        for (int v = 0; v < t[k].n_vertices; v++) {
            for (int m = 0; m < 3; m++)
                le_f32(f, t[k].pos[3 * v + m]);
            for (int m = 0; m < 3; m++)
                le_f32(f, t[k].normal[3 * v + m]);
            le_f32(f, t[k].K ? t[k].K[v] : 0.0);
            le_f32(f, t[k].H ? t[k].H[v] : 0.0);
        }
    size_t base = 0;
    for (int k = 0; k < n; k++) {
        for (int q = 0; q < t[k].n_triangles; q++) {
            le_u8(f, 3);
            for (int m = 0; m < 3; m++)
                le_i32(f, (int)(base + (size_t)t[k].tri[3 * q + m]));
        }
        base += (size_t)t[k].n_vertices;
    }
    le_flush(f);
    return RG2_OK;
}

/* ---------------------------------------------------------------- glTF 2.0 binary */

static cJSON *vec3_array(const double v[3])
{
    return cJSON_CreateDoubleArray(v, 3);
}

/* Accessor object; min/max for POSITION (required by glTF), NULL otherwise. */
static int add_accessor(cJSON *accessors, int view, int ctype, size_t count, const char *type,
                        const double *mn, const double *mx)
{
    cJSON *a = cJSON_CreateObject();
    if (!a || !cJSON_AddItemToArray(accessors, a))
        return 0;
    int ok = cJSON_AddNumberToObject(a, "bufferView", view) && cJSON_AddNumberToObject(a, "componentType", ctype) &&
             cJSON_AddNumberToObject(a, "count", (double)count) && cJSON_AddStringToObject(a, "type", type);
    if (ok && mn) {
        cJSON *jmn = vec3_array(mn), *jmx = vec3_array(mx);
        ok = jmn && jmx && cJSON_AddItemToObject(a, "min", jmn) && cJSON_AddItemToObject(a, "max", jmx);
    }
    return ok;
}

static int add_view(cJSON *views, size_t offset, size_t length, int target)
{
    cJSON *v = cJSON_CreateObject();
    if (!v || !cJSON_AddItemToArray(views, v))
        return 0;
    return cJSON_AddNumberToObject(v, "buffer", 0) && cJSON_AddNumberToObject(v, "byteOffset", (double)offset) &&
           cJSON_AddNumberToObject(v, "byteLength", (double)length) &&
           cJSON_AddNumberToObject(v, "target", target);
}

/*
 * Layout: one mesh with one triangle primitive per surface. The binary chunk holds, per
 * surface, float32 positions, float32 normals, uint32 indices (all 4-byte aligned); each has
 * its bufferView and accessor (POSITION with min/max as required by the specification).
 */
rg2_status rg2__write_glb(const rg2_tess *t, int n, const rg2_export_opts *o, rg2__out *out,
                          rg2_error *err)
{
    cJSON *root = cJSON_CreateObject();
    cJSON *asset = root ? cJSON_AddObjectToObject(root, "asset") : NULL;
    cJSON *scenes = root ? cJSON_AddArrayToObject(root, "scenes") : NULL;
    cJSON *nodes = root ? cJSON_AddArrayToObject(root, "nodes") : NULL;
    cJSON *meshes = root ? cJSON_AddArrayToObject(root, "meshes") : NULL;
    cJSON *accessors = root ? cJSON_AddArrayToObject(root, "accessors") : NULL;
    cJSON *views = root ? cJSON_AddArrayToObject(root, "bufferViews") : NULL;
    cJSON *buffers = root ? cJSON_AddArrayToObject(root, "buffers") : NULL;
    int ok = root && asset && scenes && nodes && meshes && accessors && views && buffers &&
             cJSON_AddStringToObject(asset, "version", "2.0") &&
             cJSON_AddStringToObject(asset, "generator", "rg2") && cJSON_AddNumberToObject(root, "scene", 0);
    cJSON *scene = ok ? cJSON_CreateObject() : NULL;
    cJSON *node = ok ? cJSON_CreateObject() : NULL;
    cJSON *mesh = ok ? cJSON_CreateObject() : NULL;
    ok = ok && scene && cJSON_AddItemToArray(scenes, scene);
    ok = ok && node && cJSON_AddItemToArray(nodes, node);
    ok = ok && mesh && cJSON_AddItemToArray(meshes, mesh);
    int zero = 0;
    cJSON *snodes = ok ? cJSON_CreateIntArray(&zero, 1) : NULL;
    ok = ok && snodes && cJSON_AddItemToObject(scene, "nodes", snodes);
    ok = ok && cJSON_AddNumberToObject(node, "mesh", 0) && cJSON_AddStringToObject(node, "name", o->name) &&
         cJSON_AddStringToObject(mesh, "name", o->name);
    cJSON *prims = ok ? cJSON_AddArrayToObject(mesh, "primitives") : NULL;
    ok = ok && prims;
    size_t offset = 0;
    for (int k = 0; ok && k < n; k++) {
        size_t nv = (size_t)t[k].n_vertices, nt = (size_t)t[k].n_triangles;
        double mn[3] = {INFINITY, INFINITY, INFINITY}, mx[3] = {-INFINITY, -INFINITY, -INFINITY};
        for (size_t v = 0; v < nv; v++)
            for (int m = 0; m < 3; m++) {
                double x = (float)t[k].pos[3 * v + m];
                mn[m] = x < mn[m] ? x : mn[m];
                mx[m] = x > mx[m] ? x : mx[m];
            }
        int base = 3 * k;
        ok = add_view(views, offset, 12 * nv, 34962) && add_view(views, offset + 12 * nv, 12 * nv, 34962) &&
             add_view(views, offset + 24 * nv, 12 * nt, 34963) &&
             add_accessor(accessors, base, 5126, nv, "VEC3", mn, mx) &&
             add_accessor(accessors, base + 1, 5126, nv, "VEC3", NULL, NULL) &&
             add_accessor(accessors, base + 2, 5125, 3 * nt, "SCALAR", NULL, NULL);
        offset += 24 * nv + 12 * nt;
        cJSON *prim = ok ? cJSON_CreateObject() : NULL;
        ok = ok && prim && cJSON_AddItemToArray(prims, prim);
        cJSON *attr = ok ? cJSON_AddObjectToObject(prim, "attributes") : NULL;
        ok = ok && attr && cJSON_AddNumberToObject(attr, "POSITION", base) &&
             cJSON_AddNumberToObject(attr, "NORMAL", base + 1) && cJSON_AddNumberToObject(prim, "indices", base + 2) &&
             cJSON_AddNumberToObject(prim, "mode", 4);
    }
    cJSON *buf = ok ? cJSON_CreateObject() : NULL;
    ok = ok && buf && cJSON_AddItemToArray(buffers, buf) && cJSON_AddNumberToObject(buf, "byteLength", (double)offset);
    char *json = ok ? rg2__json_print(root, 0) : NULL;
    cJSON_Delete(root);
    if (!json)
        return rg2__fail(err, RG2_ENOMEM, "%s: out of memory building the glTF JSON", out->path);
    size_t jlen = strlen(json), jpad = (4 - jlen % 4) % 4;
    size_t total = 12 + 8 + jlen + jpad + 8 + offset;
    if (total > UINT32_MAX) {
        cJSON_free(json);
        return rg2__fail(err, RG2_ELIMIT, "%s: %zu bytes exceed the 4 GiB glb limit", out->path, total);
    }
    le_out w = {.f = out->f}, *f = &w;
    le_bytes(f, "glTF", 4);
    le_u32(f, 2);
    le_u32(f, (uint32_t)total);
    le_u32(f, (uint32_t)(jlen + jpad));
    le_bytes(f, "JSON", 4);
    le_bytes(f, json, jlen);
    for (size_t q = 0; q < jpad; q++)
        le_u8(f, ' ');
    cJSON_free(json); /* cJSON's allocator: the host may have set its own (cJSON_InitHooks) */
    le_u32(f, (uint32_t)offset);
    le_bytes(f, "BIN\0", 4);
    for (int k = 0; k < n; k++) {
        for (int v = 0; v < 3 * t[k].n_vertices; v++)
            le_f32(f, t[k].pos[v]);
        for (int v = 0; v < 3 * t[k].n_vertices; v++)
            le_f32(f, t[k].normal[v]);
        for (int q = 0; q < 3 * t[k].n_triangles; q++)
            le_u32(f, (uint32_t)t[k].tri[q]);
    }
    le_flush(f);
    return RG2_OK;
}
