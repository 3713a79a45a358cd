/* test_scaling.c -- work that must grow linearly with the input, measured by what it allocates
 * (never by time): the bytes the library asks for (rg2__fi_bytes, counted by the rg2_fi build of
 * the library that test_faults uses too, with no failure injected) and the items cJSON allocates.
 * Each case compares an input with one twice as long (or a per-item figure with a bound that an
 * allocation per item of the whole mesh would exceed many times). */
#define _POSIX_C_SOURCE 200809L
#include "harness.h"
#include "../cli/cli.h"

#include <math.h>

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

/* rg2_retessellate keeps the mesh's allocation when it holds the new mesh (rg2.h): into the block of
 * the same tessellation, which fits exactly, it asks for its temporaries only (a few KB), not a
 * block of the mesh's size; a finer mesh needs a new block. A new block is the mesh's arrays
 * (positions, normals, K, H, (u, v), patches, triangles), each on its own 64-byte cache line. */
static void retessellate_block(void)
{
    rg2_surface s;
    rg2_error err;
    CHECK_OK(rg2t_torus(13.0, 4.0, 8, 6, NULL, &s, &err), &err);
    rg2_tess t = {0};
    unsigned long long used[3];
    size_t cap[3];
    static const int dens[3] = {8, 8, 9};
    for (int k = 0; k < 3; k++) {
        unsigned long long before = rg2__fi_bytes;
        CHECK_OK(rg2_retessellate(&s, dens[k], 1, &t, &err), &err);
        used[k] = rg2__fi_bytes - before;
        cap[k] = t.capacity;
        size_t nv = (size_t)t.n_vertices, arrays = (2 * 3 + 2 + 2) * nv * sizeof(double) + nv * sizeof(int) +
                                                   3 * (size_t)t.n_triangles * sizeof(int);
        if (k != 1)
            CHECK(cap[k] >= arrays && cap[k] < arrays + 7 * 64, "retessellate at density %d: a block of %zu bytes for "
                  "arrays of %zu", dens[k], cap[k], arrays);
    }
    CHECK(used[0] >= cap[0] && cap[1] == cap[0] && used[1] < cap[0] / 16 && used[2] >= cap[2] && cap[2] > cap[0],
          "retessellate: %llu bytes for a mesh of %zu, %llu again into it (%zu), %llu for a finer one of %zu", used[0],
          cap[0], used[1], cap[1], used[2], cap[2]);
    printf("  rg2_retessellate into the block of the same mesh (%zu bytes): %llu bytes allocated\n", cap[0], used[1]);
    rg2_tess_free(&t);
    rg2_surface_free(&s);
}

/* rg2 render's note on output surfaces drawn on top of each other (cli/overlap.c): the first
 * pair of boxes, in the order a = 1, 2, ..., b < a, that overlap by half the smaller extent along
 * every axis. It compared every pair: 64 000 outputs, 2 billion pairs, 19.5 s of a 22.5 s render.
 * The pair must be the one every pair's loop finds (random boxes, some NaN, touching, flat), with
 * a 200th of the pairs compared on a 200 x 200 grid of boxes laid out apart. */
static int brute_overlap(const double (*box)[2][3], int n, int *pa, int *pb)
{
    for (int a = 0; a < n; a++)
        for (int b = 0; b < a; b++)
            if (!isnan(box[a][0][0]) && !isnan(box[b][0][0]) && rg2_cli_box_overlap(box[a], box[b])) {
                *pa = a, *pb = b;
                return 1;
            }
    return 0;
}

/* n random boxes (some NaN, touching, flat) into box. */
static void random_boxes(rg2t_rng *r, double (*box)[2][3], int n)
{
    double spread = rg2t_uniform(r, 0.5, 20);
    for (int s = 0; s < n; s++)
        for (int k = 0; k < 3; k++) {
            double c = rg2t_uniform(r, 0, spread), e = rg2t_int(r, 0, 9) == 0 ? 0 : rg2t_uniform(r, 0, 2);
            if (rg2t_int(r, 0, 3) == 0) /* (snapped: equal and touching ends) */
                c = floor(c), e = floor(e + 0.5);
            box[s][0][k] = c - e / 2, box[s][1][k] = c + e / 2;
        }
    for (int s = 0; s < n; s++)
        if (rg2t_int(r, 0, 15) == 0)
            box[s][0][0] = NAN;
}

static void render_overlaps(void)
{
    rg2t_rng r;
    rg2t_seed(&r, 20261207);
    int bad = 0, found = 0;
    enum { MAXN = 60 };
    double box[MAXN][2][3];
    for (int trial = 0; trial < 20000; trial++) {
        int n = rg2t_int(&r, 0, MAXN);
        random_boxes(&r, box, n);
        int a = -1, b = -1, ra = -1, rb = -1;
        int got = rg2_cli_first_overlap((const double(*)[2][3])box, n, &a, &b, NULL);
        int want = brute_overlap((const double(*)[2][3])box, n, &ra, &rb);
        bad += got != want || (want && (a != ra || b != rb));
        found += want;
    }
    CHECK(bad == 0, "%d of 20000 random box sets gave another first overlapping pair than every pair's loop", bad);
    /* a box the sweep cannot order (an infinite end, or its ends the wrong way round) sends the
     * set to every pair's loop: the same answer, 1 and the pair or 0 (cli.h) */
    int bad_all = 0, found_all = 0;
    for (int trial = 0; trial < 2000; trial++) {
        int n = rg2t_int(&r, 1, MAXN), s = rg2t_int(&r, 0, n - 1), k = rg2t_int(&r, 0, 2);
        random_boxes(&r, box, n);
        if (trial % 2)
            box[s][1][k] = INFINITY;
        else {
            double lo = box[s][0][k];
            box[s][0][k] = box[s][1][k] + 1.0, box[s][1][k] = lo;
        }
        int a = -1, b = -1, ra = -1, rb = -1;
        int got = rg2_cli_first_overlap((const double(*)[2][3])box, n, &a, &b, NULL);
        int want = brute_overlap((const double(*)[2][3])box, n, &ra, &rb);
        bad_all += got != want || (want && (a != ra || b != rb));
        found_all += want;
    }
    CHECK(bad_all == 0 && found_all > 0,
          "%d of 2000 box sets with a box the sweep cannot order gave another answer than every pair's loop "
          "(%d with an overlap)", bad_all, found_all);
    /* 40 000 unit boxes 4 apart on a 200 x 200 grid (none overlaps), then one more on top of box 12345 */
    enum { G = 200, N = G * G + 1 };
    double(*grid)[2][3] = malloc(sizeof *grid * N);
    if (!grid)
        return;
    for (int s = 0; s < N; s++)
        for (int k = 0; k < 3; k++) {
            double c = k == 0 ? 4.0 * (s % G) : k == 1 ? 4.0 * (s / G) : 0.0;
            if (s == N - 1)
                c = k == 0 ? 4.0 * (12345 % G) + 0.2 : k == 1 ? 4.0 * (12345 / G) : 0.1;
            grid[s][0][k] = c - 1, grid[s][1][k] = c + 1;
        }
    long cmp_none = 0, cmp_one = 0;
    int a = -1, b = -1;
    int none = rg2_cli_first_overlap((const double(*)[2][3])grid, N - 1, &a, &b, &cmp_none);
    int one = rg2_cli_first_overlap((const double(*)[2][3])grid, N, &a, &b, &cmp_one);
    /* (the pairs intersecting along the sweep's axis: a column of 200, n^1.5 / 2 on a square grid) */
    CHECK(!none && one && a == N - 1 && b == 12345 && cmp_none < 5000000 && cmp_one < 5000000,
          "grid of %d boxes: overlap %d (%ld pairs compared), with one on top %d: (%d, %d) (%ld pairs compared; "
          "every pair: %.3g)", N - 1, none, cmp_none, one, a, b, cmp_one, 0.5 * N * (N - 1.0));
    printf("  render overlap note: 20000 random box sets as every pair's loop (%d with an overlap); %d boxes apart: "
           "%ld pairs compared (every pair: %.3g)\n", found, N - 1, cmp_none, 0.5 * (N - 1.0) * (N - 2.0));
    free(grid);
}

/* The resident kilobytes of the process's [heap] mapping (the brk heap; /proc/self/smaps), or -1. */
static long heap_rss_kb(void)
{
    FILE *f = fopen("/proc/self/smaps", "r");
    if (!f)
        return -1;
    char line[512];
    int in_heap = 0;
    long kb = -1;
    while (fgets(line, sizeof line, f)) { /* (the mapping's line, then its fields: Size, ..., Rss) */
        if (strstr(line, "[heap]"))
            in_heap = 1;
        else if (in_heap && !strncmp(line, "Rss:", 4)) {
            kb = strtol(line + 4, NULL, 10);
            break;
        }
    }
    fclose(f);
    return kb;
}

/* The cJSON tree of a large design text, freed after parsing, stayed resident in the heap under
 * the built design (the meshes allocated while parsing sit above it): a 1000 x 1000 NURBS design
 * took 859 MB where the design is 554 MB. With the design alive (its meshes are in the heap too),
 * the heap must hold less than 8 times the text: 18 times before (40 MB for 2.2 MB of text), 3.9
 * times after. glibc on Linux only (malloc_trim, smaps). */
static void parse_memory(void)
{
#if defined(__GLIBC__) && defined(__linux__)
    enum { N = 300 };
    text t = {0};
    add(&t, "{\"shapes\": {}, \"meshes\": {\"F\": {\"nurbs\": {\"nu\": %d, \"nv\": %d, \"knots_u\": [", N, N);
    for (int k = -3; k <= N; k++)
        add(&t, "%s%d", k > -3 ? ", " : "", k);
    add(&t, "], \"knots_v\": [");
    for (int k = -3; k <= N; k++)
        add(&t, "%s%d", k > -3 ? ", " : "", k);
    add(&t, "], \"points\": [");
    for (int i = 0; i < N; i++)
        for (int j = 0; j < N; j++)
            add(&t, "%s[%.3f, %.3f, %.3f]", i + j ? ", " : "", 0.1 * i, 0.1 * j, 0.01 * ((i * 7 + j * 3) % 11));
    add(&t, "]}}}}");
    rg2_design *d = NULL;
    rg2_error err;
    rg2_status st = rg2_design_parse(t.s, t.n, "nurbs", &d, &err);
    long kb = heap_rss_kb();
    CHECK(st == RG2_OK, "nurbs: %s", err.msg);
    if (kb >= 0) {
        CHECK((double)kb * 1024 < 8.0 * (double)t.n,
              "a design of %zu bytes of text keeps %ld KB of heap resident (the freed cJSON tree)", t.n, kb);
        printf("  a NURBS design of %d x %d points, %zu bytes of text: %ld KB of heap resident while it lives\n", N,
               N, t.n, kb);
    } else
        printf("  (no [heap] in /proc/self/smaps, as under a sanitizer's allocator: not measured)\n");
    rg2_design_free(d);
    free(t.s);
#endif
}

int main(void)
{
    printf("allocations that grow linearly:\n");
    transform_chains();
    edit_lists();
    mesh_file();
    retessellate_block();
    render_overlaps();
    parse_memory();
    return rg2t_done("test_scaling");
}
