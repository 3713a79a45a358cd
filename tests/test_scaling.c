/* test_scaling.c -- work that must grow linearly with the input, measured by what it allocates
 * (never by time): the bytes the library asks for (rg2__fi_bytes, counted by the rg2_fi build of
 * the library that test_faults uses too, with no failure injected) and the items cJSON allocates.
 * Each case compares an input with one twice as long (or a per-item figure with a bound that an
 * allocation per item of the whole mesh would exceed many times). */
#define _POSIX_C_SOURCE 200809L
#include "harness.h"

#include <cjson/cJSON.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

extern unsigned long long rg2__fi_bytes;

/* A growing text. */
typedef struct {
    char *s;
    size_t n, cap;
} text;

static void add(text *t, const char *fmt, ...) __attribute__((format(printf, 2, 3)));
static void add(text *t, const char *fmt, ...)
{
    for (;;) {
        va_list ap;
        va_start(ap, fmt);
        int n = vsnprintf(t->s ? t->s + t->n : NULL, t->s ? t->cap - t->n : 0, fmt, ap);
        va_end(ap);
        if (t->s && t->n + (size_t)n < t->cap) {
            t->n += (size_t)n;
            return;
        }
        size_t cap = 2 * t->cap + (size_t)n + 4096;
        char *s = realloc(t->s, cap);
        if (!s) {
            fprintf(stderr, "test_scaling: out of memory\n");
            exit(1);
        }
        t->s = s;
        t->cap = cap;
    }
}

/* The bytes rg2_design_parse allocates for the text (-1 if it fails). */
static long long parse_bytes(const text *t, const char *what)
{
    rg2_design *d = NULL;
    rg2_error err;
    unsigned long long before = rg2__fi_bytes;
    rg2_status st = rg2_design_parse(t->s, t->n, what, &d, &err);
    unsigned long long used = rg2__fi_bytes - before;
    CHECK(st == RG2_OK, "%s: %s", what, err.msg);
    rg2_design_free(d);
    return st ? -1 : (long long)used;
}

/* A chain of n transforms of a cylinder's 8 x 6 mesh. Each link made tables for every source and
 * shape of the design so far (n of each): the chain allocated about 22 n^2 bytes, 4 times as
 * much for twice the links, against 2.1 times now. */
static text transform_chain(int n)
{
    text t = {0};
    add(&t, "{\"shapes\": {\"c\": {\"kind\": \"cylinder\"}}, \"meshes\": {\"m0\": {\"shape\": \"c\", \"u\": {\"arcs\": 8}}");
    for (int k = 1; k <= n; k++)
        add(&t, ", \"m%d\": {\"transform\": \"m%d\", \"translate\": [0, 0, 0.001]}", k, k - 1);
    add(&t, "}, \"output\": \"m%d\"}", n);
    return t;
}

static void transform_chains(void)
{
    enum { N = 800 };
    text a = transform_chain(N), b = transform_chain(2 * N);
    long long ba = parse_bytes(&a, "chain"), bb = parse_bytes(&b, "chain2");
    double ratio = (double)bb / (double)ba;
    CHECK(ba > 0 && bb > 0 && ratio < 2.3,
          "a chain of %d transforms allocated %lld bytes, one of %d %lld: %.2f times as much (linear: about 2)", N,
          ba, 2 * N, bb, ratio);
    printf("  transform chains of %d and %d links: %lld and %lld bytes allocated (%.2fx)\n", N, 2 * N, ba, bb, ratio);
    free(a.s);
    free(b.s);
}

/* One edit of n entries, each one point of a 100 x 103 cylinder mesh (kind: "move", "normal" or
 * "list": a one-point "at" list), the points apart. Each entry allocated a table of the whole mesh
 * (a list: the points it named; 'normal': a copy of the net): 41 KB or 330 KB an entry. */
static text edit_entries(int n, const char *kind)
{
    text t = {0};
    add(&t, "{\"shapes\": {\"c\": {\"kind\": \"cylinder\"}}, \"meshes\": {\"m0\": {\"shape\": \"c\", \"u\": {\"arcs\": 100}, "
            "\"v\": {\"segments\": 100, \"from\": 0, \"to\": 4}}, \"e\": {\"edit\": \"m0\", \"points\": [");
    for (int k = 0; k < n; k++) {
        int i = (7 * k) % 100, j = (k / 100) * 3 + 1 + (k % 3);
        if (!strcmp(kind, "normal"))
            add(&t, "%s{\"at\": [%d, %d], \"normal\": 0.001}", k ? ", " : "", i, j);
        else if (!strcmp(kind, "list"))
            add(&t, "%s{\"at\": [[%d, %d]], \"move\": [0, 0, 0.001]}", k ? ", " : "", i, j);
        else
            add(&t, "%s{\"at\": [%d, %d], \"move\": [0, 0, 0.001]}", k ? ", " : "", i, j);
    }
    add(&t, "]}}, \"output\": \"e\"}");
    return t;
}

static void edit_lists(void)
{
    static const char *const kinds[] = {"move", "normal", "list"};
    for (int q = 0; q < 3; q++) {
        text a = edit_entries(1, kinds[q]), b = edit_entries(400, kinds[q]);
        long long ba = parse_bytes(&a, kinds[q]), bb = parse_bytes(&b, kinds[q]);
        double per = (double)(bb - ba) / 399.0;
        CHECK(ba > 0 && bb > 0 && per < 200.0,
              "an edit of 400 '%s' entries allocated %lld bytes, of 1 entry %lld: %.0f bytes more an entry (the mesh "
              "has 10 300 points)", kinds[q], bb, ba, per);
        printf("  an edit of 1 and of 400 '%s' entries: %lld and %lld bytes allocated (%.0f an entry)\n", kinds[q], ba,
               bb, per);
        free(a.s);
        free(b.s);
    }
}

/* cJSON allocations, counted through its hooks. */
static long cjson_allocs;
static void *count_malloc(size_t n)
{
    cjson_allocs++;
    return malloc(n);
}

/* rg2 mesh's file (rg2_design_write_mesh) of a 300 x 303 cylinder mesh: it built a cJSON item for
 * every number and array of the file (about 6 a control point) and the whole text in memory before
 * writing it; now it writes as it goes, and cJSON allocates nothing. */
static void mesh_file(void)
{
    const char *json = "{\"shapes\": {\"c\": {\"kind\": \"cylinder\"}}, \"meshes\": {\"m0\": {\"shape\": \"c\", \"u\": "
                       "{\"arcs\": 300}, \"v\": {\"segments\": 300, \"from\": 0, \"to\": 4}}}}";
    rg2_design *d = NULL;
    rg2_error err;
    rg2_status st = rg2_design_parse(json, strlen(json), "big", &d, &err);
    CHECK(st == RG2_OK, "big: %s", err.msg);
    if (st)
        return;
    char path[64];
    snprintf(path, sizeof path, "/tmp/rg2_test_scaling_%d.json", (int)getpid());
    cJSON_Hooks hooks = {count_malloc, free};
    cJSON_InitHooks(&hooks);
    cjson_allocs = 0;
    unsigned long long before = rg2__fi_bytes;
    st = rg2_design_write_mesh(d, path, &err);
    unsigned long long used = rg2__fi_bytes - before;
    long allocs = cjson_allocs;
    cJSON_InitHooks(NULL);
    CHECK(st == RG2_OK, "write_mesh: %s", err.msg);
    CHECK(allocs < 100 && used < 100000,
          "writing the mesh file of 90 900 control points: %ld cJSON allocations, %llu bytes by rg2", allocs, used);
    printf("  the mesh file of 90 900 control points: %ld cJSON allocations, %llu bytes allocated by rg2\n", allocs,
           used);
    /* the file is the JSON it was: it reads back, with every point */
    FILE *f = fopen(path, "rb");
    char *buf = NULL;
    long len = 0;
    if (f && fseek(f, 0, SEEK_END) == 0 && (len = ftell(f)) > 0 && fseek(f, 0, SEEK_SET) == 0 &&
        (buf = malloc((size_t)len + 1)) && fread(buf, 1, (size_t)len, f) == (size_t)len) {
        buf[len] = 0;
        cJSON *root = cJSON_Parse(buf);
        cJSON *m = root ? cJSON_GetArrayItem(cJSON_GetObjectItem(root, "meshes"), 0) : NULL;
        cJSON *dd = m ? cJSON_GetObjectItem(m, "d") : NULL;
        CHECK(dd && cJSON_GetArraySize(dd) == 300 && cJSON_GetArraySize(dd->child) == 303,
              "the mesh file does not read back as 300 rows of 303 points");
        cJSON_Delete(root);
    } else
        CHECK(0, "cannot read %s back", path);
    free(buf);
    if (f)
        fclose(f);
    unlink(path);
    rg2_design_free(d);
}

int main(void)
{
    printf("allocations that grow linearly:\n");
    transform_chains();
    edit_lists();
    mesh_file();
    return rg2t_done("test_scaling");
}
