/* test_faults.c -- allocation failures: every operation below runs with its N-th allocation
 * made to fail, N = 0, 1, 2, ... (every N up to 200, then steps of about 5 %), until a run
 * meets no injected failure. Each failing run must return RG2_ENOMEM with a message and leave
 * nothing in the output directory (neither the file nor a temporary one); under ASan (make
 * test) LeakSanitizer reports anything it did not free. The run without a failure must give
 * the same result (the file's bytes, the surface's values) as a run without injection, and the
 * run N = 0 must have had its first allocation fail (else no failure was ever injected). First
 * the allocators themselves (allocators()): sizes, zeroing, overflow and 2 MiB alignment.
 *
 * Linked with rg2_fi, the library built with RG2_FAULT_INJECT (src/internal.h: the counting
 * allocators; only allocations in src/ are counted, not cJSON's, libpng's or libc's own).
 * The threads: render and check run with threads = 1, and the test runs with OMP_NUM_THREADS=1
 * (tests/CMakeLists.txt; main re-executes itself with it otherwise) for the tessellation and
 * the exports, so one thread allocates and the N-th allocation is the same one run after run;
 * SOURCE_DATE_EPOCH=0 fixes the time stamps of STEP and IGES. */
#define _POSIX_C_SOURCE 200809L
#include "harness.h"

#include <dirent.h>
#include <time.h>
#include <stdint.h>
#include <math.h>
#include <stdlib.h>
#include <sys/mman.h>
#include <string.h>
#include <unistd.h>
#ifdef __GLIBC__
#include <malloc.h>
#endif

extern long rg2__fi_countdown, rg2__fi_injected, rg2__fi_calls;
int rg2__grid_tables_cached(int n, int m);
void *rg2__calloc(size_t n, size_t size);
void *rg2__calloc_big(size_t n, size_t size);
void *rg2__alloc_big(size_t n, size_t size, size_t from, int zero);

/* A result as bytes, to compare a run with the reference run. */
typedef struct {
    unsigned char *b;
    size_t n, cap;
} blob;

static void put(blob *o, const void *p, size_t n)
{
    if (n == 0 || !p)
        return;
    if (o->n + n > o->cap) {
        size_t c = o->cap ? o->cap : 4096;
        while (c < o->n + n)
            c *= 2;
        unsigned char *b = realloc(o->b, c);
        if (!b) {
            fprintf(stderr, "test_faults: out of memory\n");
            exit(1);
        }
        o->b = b;
        o->cap = c;
    }
    memcpy(o->b + o->n, p, n);
    o->n += n;
}

static void put_surface(blob *o, const rg2_surface *s)
{
    size_t np = (size_t)s->nu * (size_t)s->nv;
    int head[4] = {s->nu, s->nv, s->closed_u, s->closed_v};
    put(o, head, sizeof head);
    put(o, s->patch, np * sizeof *s->patch);
    put(o, s->bu, (size_t)s->nu * sizeof(double));
    put(o, s->gu, (size_t)s->nu * sizeof(double));
    put(o, s->bv, (size_t)s->nv * sizeof(double));
    put(o, s->gv, (size_t)s->nv * sizeof(double));
    put(o, s->tag, s->tag ? np * sizeof(int) : 0);
    put(o, s->xp, s->xp ? np * sizeof *s->xp : 0);
}

/* The operations: each runs once, returns its status and on success appends its result to out
 * and frees everything it made. path is the output file of the writers (in an empty directory). */
typedef rg2_status (*op_fn)(const void *ctx, const char *path, blob *out, rg2_error *err);

static char dir[64];
static long cur_N; /* the N of the run (-1: the reference run), for the operations' messages */

/* Entries of dir other than . and .. (the output file and temporary files). */
static int dir_entries(char *first, size_t n)
{
    DIR *d = opendir(dir);
    int count = 0;
    if (!d)
        return -1;
    for (struct dirent *e; (e = readdir(d));) {
        if (!strcmp(e->d_name, ".") || !strcmp(e->d_name, ".."))
            continue;
        if (count++ == 0)
            snprintf(first, n, "%s", e->d_name);
    }
    closedir(d);
    return count;
}

static int read_file(const char *path, blob *out)
{
    FILE *f = fopen(path, "rb");
    if (!f)
        return -1;
    unsigned char buf[65536];
    for (size_t k; (k = fread(buf, 1, sizeof buf, f)) > 0;)
        put(out, buf, k);
    fclose(f);
    return 0;
}

/* ---- the operations ---- */

static rg2_status op_build(const void *ctx, const char *path, blob *out, rg2_error *err)
{
    (void)path;
    rg2_surface s;
    rg2_status st = rg2_surface_build(ctx, &s, err);
    if (st == RG2_OK) {
        put_surface(out, &s);
        rg2_surface_free(&s);
    }
    return st;
}

static void put_mesh(blob *o, const rg2_mesh *m)
{
    int head[4] = {m->nu, m->nv, m->su.closed, m->sv.closed};
    put(o, head, sizeof head);
    put(o, m->p, (size_t)m->nu * (size_t)m->nv * 4 * sizeof(double));
    for (int k = 0; k < 2; k++) {
        const rg2_scalars *s = k ? &m->sv : &m->su;
        put(o, s->w, (size_t)rg2_scalars_num_w(s) * sizeof(double));
        put(o, s->b, (size_t)s->n * sizeof(double));
        put(o, s->g, (size_t)s->n * sizeof(double));
    }
}

/* The mesh operations of the C API on a closed ring J: cut it in two, merge them closed again,
 * transpose, reverse, morph, roll; a failed step must leave its output empty (nothing to free). */
static rg2_status op_meshops(const void *ctx, const char *path, blob *out, rg2_error *err)
{
    (void)path;
    const rg2_mesh *J = ctx;
    rg2_mesh m[7];
    memset(m, 0, sizeof m);
    const int fa[2] = {0, -1}, la[2] = {8, 0}, fb[2] = {9, -1}, lb[2] = {14, 0};
    memset(m, 0xab, sizeof m); /* (each operation must set its output, emptied on failure) */
    int k = 0;
    rg2_status st = rg2_mesh_cut(J, fa, la, &m[0], err);
    if (!st && ++k)
        st = rg2_mesh_cut(J, fb, lb, &m[1], err);
    const rg2_mesh *two[2] = {&m[0], &m[1]};
    if (!st && ++k)
        st = rg2_mesh_merge(two, 2, 0, 1, RG2_SEAM_PRESERVE, &m[2], err);
    if (!st && ++k)
        st = rg2_mesh_transpose(&m[2], &m[3], err);
    if (!st && ++k)
        st = rg2_mesh_reverse(&m[3], 0, &m[4], err);
    if (!st && ++k)
        st = rg2_mesh_morph(&m[2], J, 0.5, &m[5], err);
    if (!st && ++k)
        st = rg2_mesh_roll(&m[2], 0, 3, &m[6], err);
    if (st)
        CHECK(m[k].p == NULL && m[k].su.w == NULL && m[k].sv.b == NULL && m[k].nu == 0,
              "mesh operation %d failed (%s) but left its output unemptied", k, rg2_status_str(st));
    for (int q = 0; q <= k; q++) {
        if (!st)
            put_mesh(out, &m[q]);
        rg2_mesh_free(&m[q]);
    }
    return st;
}

/* rg2_polar_mesh of the unit sphere and of a paraboloid. */
static rg2_status op_polar(const void *ctx, const char *path, blob *out, rg2_error *err)
{
    (void)ctx;
    (void)path;
    double au[6], v[4] = {0.2, 0.4, 0.6, 0.8};
    for (int a = 0; a < 6; a++)
        au[a] = 2.0 * M_PI / 6;
    rg2_partition pu = {RG2_PART_ANGLES, 1, 6, au, 0.0};
    rg2_shape sh;
    rg2_mesh m;
    rg2_status st = RG2_OK;
    for (int k = 0; k < 2 && !st; k++) {
        rg2_shape_init(&sh, k ? RG2_SHAPE_PARABOLOID : RG2_SHAPE_SPHERE);
        memset(&m, 0xab, sizeof m);
        st = rg2_polar_mesh(&sh, &pu, v, 4, &m, err);
        if (st)
            CHECK(m.p == NULL && m.su.w == NULL && m.nu == 0, "rg2_polar_mesh failed (%s) but left its output unemptied",
                  rg2_status_str(st));
        else
            put_mesh(out, &m);
        rg2_mesh_free(&m);
    }
    return st;
}

/* rg2_mesh_mobius_shape about the unit sphere (a boost: poles not antipodal) on a copy of ctx;
 * a failure leaves the copy as it was. */
static rg2_status op_mobius(const void *ctx, const char *path, blob *out, rg2_error *err)
{
    (void)path;
    const rg2_mesh *src = ctx;
    rg2_mesh m;
    rg2_status st = rg2_mesh_copy(src, &m, err);
    if (st)
        return st;
    rg2_shape sh;
    rg2_shape_init(&sh, RG2_SHAPE_SPHERE);
    static const double south[3] = {0, 0.6, -0.8}, north[3] = {0.6, 0, 0.8};
    st = rg2_mesh_mobius_shape(&m, &sh, NULL, south, north, err);
    if (st)
        CHECK(!memcmp(m.p, src->p, (size_t)m.nu * (size_t)m.nv * 4 * sizeof(double)),
              "rg2_mesh_mobius_shape failed (%s) but changed the mesh", rg2_status_str(st));
    else
        put_mesh(out, &m);
    rg2_mesh_free(&m);
    return st;
}

static rg2_status op_load(const void *ctx, const char *path, blob *out, rg2_error *err)
{
    (void)path;
    rg2_design *d = NULL;
    rg2_status st = rg2_design_load(ctx, &d, err);
    if (st == RG2_OK) {
        for (int k = 0; k < rg2_design_num_surfaces(d); k++)
            put_surface(out, rg2_design_surface(d, k));
        rg2_design_free(d);
    }
    return st;
}

static rg2_status op_tess(const void *ctx, const char *path, blob *out, rg2_error *err)
{
    (void)path;
    rg2_tess t;
    rg2_status st = rg2_tessellate(ctx, 6, 1, &t, err);
    if (st == RG2_OK) {
        size_t nv = (size_t)t.n_vertices;
        put(out, t.pos, 3 * nv * sizeof(double));
        put(out, t.normal, 3 * nv * sizeof(double));
        put(out, t.K, nv * sizeof(double));
        put(out, t.H, nv * sizeof(double));
        put(out, t.patch, nv * sizeof(int));
        put(out, t.uv, 2 * nv * sizeof(double));
        put(out, t.tri, 3 * (size_t)t.n_triangles * sizeof(int));
        rg2_tess_free(&t);
    }
    return st;
}

static rg2_status op_retess(const void *ctx, const char *path, blob *out, rg2_error *err)
{
    (void)path;
    rg2_tess t = {0};
    rg2_status st = rg2_retessellate(ctx, 2, 0, &t, err); /* (grown below: the second allocates) */
    if (st == RG2_OK)
        st = rg2_retessellate(ctx, 7, 1, &t, err);
    if (st == RG2_OK) {
        put(out, t.pos, 3 * (size_t)t.n_vertices * sizeof(double));
        put(out, t.K, (size_t)t.n_vertices * sizeof(double));
        put(out, t.tri, 3 * (size_t)t.n_triangles * sizeof(int));
    }
    rg2_tess_free(&t); /* (left empty on failure) */
    return st;
}

static rg2_status op_grid(const void *ctx, const char *path, blob *out, rg2_error *err)
{
    (void)path;
    const rg2_surface *s = ctx;
    size_t np = (size_t)s->nu * (size_t)s->nv * 5 * 4;
    double *a = calloc(np * 8, sizeof(double));
    rg2_grid_out go = {a, a + 3 * np, NULL, NULL, NULL, NULL, NULL, a + 6 * np, a + 7 * np};
    rg2_status st = a ? rg2_surface_grid(s, 5, 4, 1, &go, err) : RG2_ENOMEM;
    if (st == RG2_OK)
        put(out, a, np * 8 * sizeof(double));
    free(a);
    return st;
}

static rg2_status op_read_text(const void *ctx, const char *path, blob *out, rg2_error *err)
{
    (void)path;
    char *text = NULL;
    size_t len = 0;
    rg2_status st = rg2_read_text(ctx, &text, &len, err);
    if (st == RG2_OK) {
        put(out, text, len);
        free(text);
    }
    return st;
}

static rg2_status op_write_mesh(const void *ctx, const char *path, blob *out, rg2_error *err)
{
    rg2_status st = rg2_design_write_mesh(ctx, path, err);
    if (st == RG2_OK) {
        CHECK(read_file(path, out) == 0, "write_mesh: no file after success");
        unlink(path);
    }
    return st;
}

/* A design's surfaces written to a file. */
typedef struct {
    const rg2_surface *surfs;
    const rg2_mesh *meshes;
    int n;
    const char *ext;
    rg2_export_opts eo;
    rg2_render_opts ro;
} write_job;

static rg2_status op_export(const void *ctx, const char *path, blob *out, rg2_error *err)
{
    const write_job *j = ctx;
    if (strcmp(j->ext, ".obj+step+ply")) {
        rg2_status st = rg2_export_file(j->surfs, j->n, path, &j->eo, err);
        if (st == RG2_OK) {
            CHECK(read_file(path, out) == 0, "export %s: no file after success", j->ext);
            unlink(path);
        }
        return st;
    }
    /* rg2_export_files: three outputs as one, the mesh ones sharing a tessellation */
    char paths[3][160];
    const char *pp[3] = {paths[0], paths[1], paths[2]};
    const char *ext[3] = {".obj", ".step", ".ply"};
    for (int k = 0; k < 3; k++)
        snprintf(paths[k], sizeof paths[k], "%s%s", path, ext[k]);
    int failed = -2;
    rg2_status st = rg2_export_files(j->surfs, j->n, pp, 3, &j->eo, &failed, err);
    CHECK((st == RG2_OK) == (failed == -1), "export_files: N = %ld: status %s, *failed = %d", cur_N,
          rg2_status_str(st), failed);
    for (int k = 0; k < 3 && st == RG2_OK; k++) {
        CHECK(read_file(paths[k], out) == 0, "export_files: no %s after success", paths[k]);
        unlink(paths[k]);
    }
    return st;
}

/* rg2_export_memory: the format is the job's extension without its dot; nothing is written to
 * the directory (the sweep checks it stays empty), and a failure leaves data NULL. */
static rg2_status op_export_memory(const void *ctx, const char *path, blob *out, rg2_error *err)
{
    (void)path;
    const write_job *j = ctx;
    char *data = (char *)&cur_N;
    size_t size = 1;
    rg2_status st = rg2_export_memory(j->surfs, j->n, j->ext + 1, &j->eo, &data, &size, err);
    CHECK(st == RG2_OK ? data && data[size] == 0 : !data && size == 0,
          "export_memory %s: N = %ld: status %s with data %p, size %zu", j->ext, cur_N, rg2_status_str(st),
          (void *)data, size);
    if (st == RG2_OK) {
        put(out, data, size);
        free(data);
    }
    return st;
}

static rg2_status op_render(const void *ctx, const char *path, blob *out, rg2_error *err)
{
    const write_job *j = ctx;
    rg2_status st = rg2_render_png(j->surfs, j->n, j->meshes, &j->ro, path, err);
    if (st == RG2_OK) {
        CHECK(read_file(path, out) == 0, "render: no file after success");
        unlink(path);
    }
    return st;
}

/* rg2_check of n surfaces against n_shapes shapes (crossing_density 0: no crossing search); the
 * result: the report as JSON text. */
static rg2_status check_run(const rg2_surface *surfs, int n, const rg2_shape *shapes, int n_shapes,
                            int crossing_density, blob *out, rg2_error *err)
{
    rg2_check_opts o;
    rg2_check_opts_default(&o);
    o.threads = 1;
    o.seam_samples = 4;
    o.patch_samples = 3;
    o.crossing_density = crossing_density;
    rg2_check_report r;
    rg2_status st = rg2_check(surfs, n, shapes, NULL, n_shapes, &o, &r, err);
    if (st == RG2_OK) {
        long saved = rg2__fi_countdown;
        rg2__fi_countdown = -1; /* (the report's text is the result, not a step that may fail) */
        char *text = NULL;
        rg2_error e2;
        CHECK_OK(rg2_check_format(&r, 1, &text, &e2), &e2);
        rg2__fi_countdown = saved;
        if (text)
            put(out, text, strlen(text));
        free(text);
        rg2_check_report_free(&r);
    }
    return st;
}

static rg2_status op_check(const void *ctx, const char *path, blob *out, rg2_error *err)
{
    (void)path;
    const write_job *j = ctx;
    return check_run(j->surfs, j->n, NULL, 0, 0, out, err);
}

/* rg2_check of a design's first surface against the design's shapes (at most 8). */
static rg2_status op_check_shapes(const void *ctx, const char *path, blob *out, rg2_error *err)
{
    (void)path;
    const rg2_design *d = ctx;
    rg2_shape sh[8];
    int ns = rg2_design_num_shapes(d) < 8 ? rg2_design_num_shapes(d) : 8;
    for (int k = 0; k < ns; k++)
        sh[k] = *rg2_design_shape(d, k);
    return check_run(rg2_design_surface(d, 0), 1, sh, ns, 0, out, err);
}

/* Surfaces searched for crossings at a density. */
typedef struct {
    const rg2_surface *surfs;
    int n, density;
} crossing_job;

/* rg2_find_crossings; the result: the report's fields (one by one: no padding). A failed run
 * leaves the report all zero. */
static rg2_status op_crossings(const void *ctx, const char *path, blob *out, rg2_error *err)
{
    (void)path;
    const crossing_job *c = ctx;
    rg2_crossing_report r;
    memset(&r, 0xff, sizeof r);
    rg2_status st = rg2_find_crossings(c->surfs, c->n, c->density, 1, &r, err);
    if (st != RG2_OK) {
        CHECK(r.density == 0 && r.triangles == 0 && r.candidates == 0 && r.crossings == 0 && r.size == 0,
              "find_crossings: N = %ld -> %s, but the report is not cleared (%d triangles, %d crossings)", cur_N,
              rg2_status_str(st), r.triangles, r.crossings);
        return st;
    }
    int ints[14] = {r.density, r.triangles, r.candidates, r.crossings, r.a.surf, r.a.pi, r.a.pj,
                    r.b.surf, r.b.pi, r.b.pj, 0, 0, 0, 0};
    double dbl[10] = {r.a.u, r.a.v, r.b.u, r.b.v, r.p[0], r.p[1], r.p[2], r.residual, r.angle, r.size};
    put(out, ints, sizeof ints);
    put(out, dbl, sizeof dbl);
    return st;
}

/* rg2_check with the crossing search (crossing_density > 0); the result: the report's JSON. */
static rg2_status op_check_crossings(const void *ctx, const char *path, blob *out, rg2_error *err)
{
    (void)path;
    const crossing_job *c = ctx;
    return check_run(c->surfs, c->n, NULL, 0, c->density, out, err);
}

static rg2_status op_format(const void *ctx, const char *path, blob *out, rg2_error *err)
{
    (void)path;
    char *text = NULL;
    rg2_status st = rg2_check_format(ctx, 0, &text, err);
    if (st == RG2_OK) {
        put(out, text, strlen(text));
        free(text);
    }
    return st;
}

/* rg2_locator_build, then nearest points and first ray hits (the heaps of their searches grow
 * on the way); the result: the hits. A failed step leaves nothing to free. */
static rg2_status op_locate(const void *ctx, const char *path, blob *out, rg2_error *err)
{
    (void)path;
    rg2_locator *L = NULL;
    rg2_status st = rg2_locator_build(ctx, &L, err);
    for (int q = 0; q < 6 && st == RG2_OK; q++) {
        double x[3] = {4.0 - q, 0.5 * q - 1.0, 0.3 * q - 0.5}, d[3] = {-1.0, 0.1 * q, -0.05 * q};
        rg2_hit h[2];
        st = rg2_locator_closest(L, x, &h[0], err);
        if (st == RG2_OK)
            st = rg2_locator_ray(L, x, d, INFINITY, &h[1], err);
        for (int k = 0; k < 2 && st == RG2_OK; k++) { /* (field by field: no padding) */
            double f[10] = {h[k].u, h[k].v, h[k].p[0], h[k].p[1], h[k].p[2], h[k].n[0], h[k].n[1], h[k].n[2],
                            h[k].dist, h[k].bound};
            int ij[2] = {h[k].i, h[k].j};
            put(out, ij, sizeof ij);
            put(out, f, sizeof f);
        }
    }
    CHECK(st == RG2_OK || st == RG2_ENOMEM, "locate: N = %ld -> %s: %s", cur_N, rg2_status_str(st), err->msg);
    rg2_locator_free(L);
    return st;
}

/* ---- the sweep ---- */

static long total_points;

static void sweep(const char *name, op_fn run, const void *ctx, const char *ext)
{
    char path[128], first[256];
    snprintf(path, sizeof path, "%s/out%s", dir, ext ? ext : "");
    rg2_error err;
    blob ref = {0};
    struct timespec t0, t1;
    clock_gettime(CLOCK_MONOTONIC, &t0);
    long calls0 = rg2__fi_calls;
    rg2__fi_countdown = cur_N = -1;
    rg2_status st = run(ctx, path, &ref, &err);
    CHECK(st == RG2_OK, "%s: reference run -> %s: %s", name, rg2_status_str(st), err.msg);
    long calls = rg2__fi_calls - calls0;
    int tried = 0, recovered = 0, done = 0;
    long inj_first = -1; /* failures injected in the run N = 0 */
    for (long N = 0, next; N <= calls + 16 && !done; N = next) {
        next = N < 200 ? N + 1 : N + N / 20;
        if (N < calls && next > calls) /* (the last step lands on the reference run's count) */
            next = calls;
        blob got = {0};
        long inj0 = rg2__fi_injected;
        memset(&err, 0, sizeof err);
        rg2__fi_countdown = cur_N = N;
        st = run(ctx, path, &got, &err);
        rg2__fi_countdown = -1;
        if (N == 0)
            inj_first = rg2__fi_injected - inj0;
        if (rg2__fi_injected == inj0) { /* no allocation failed: the whole result */
            CHECK(st == RG2_OK, "%s: N = %ld, no failure injected -> %s: %s", name, N, rg2_status_str(st),
                  err.msg);
            CHECK(got.n == ref.n && (got.n == 0 || !memcmp(got.b, ref.b, got.n)),
                  "%s: N = %ld: the result differs from the reference run (%zu, %zu bytes)", name, N, got.n,
                  ref.n);
            done = 1;
        } else {
            tried++;
            if (st == RG2_OK) { /* a fallback (huge-page array, cache): the result must not differ */
                recovered++;
                if (getenv("RG2_FI_VERBOSE"))
                    printf("  %s: N = %ld recovered from\n", name, N);
                CHECK(got.n == ref.n && (got.n == 0 || !memcmp(got.b, ref.b, got.n)),
                      "%s: N = %ld: failure recovered from, but the result differs", name, N);
            } else {
                CHECK(st == RG2_ENOMEM, "%s: N = %ld -> %s (not ENOMEM): %s", name, N, rg2_status_str(st), err.msg);
                CHECK(err.msg[0] != 0, "%s: N = %ld: RG2_ENOMEM without a message", name, N);
            }
            int left = dir_entries(first, sizeof first);
            CHECK(left == 0, "%s: N = %ld: %d file(s) left in the output directory (%s)", name, N, left,
                  left > 0 ? first : "?");
            if (left > 0) { /* (clear it for the next run) */
                char p[600];
                DIR *d = opendir(dir);
                for (struct dirent *e; d && (e = readdir(d));)
                    if (strcmp(e->d_name, ".") && strcmp(e->d_name, "..")) {
                        snprintf(p, sizeof p, "%s/%s", dir, e->d_name);
                        unlink(p);
                    }
                if (d)
                    closedir(d);
            }
        }
        free(got.b);
    }
    CHECK(done, "%s: still failing after N = %ld (allocations of the reference run: %ld)", name, calls + 16,
          calls);
    CHECK(calls == 0 || inj_first == 1, "%s: N = 0 made %ld allocations fail, not the first of the reference run's %ld",
          name, inj_first, calls);
    clock_gettime(CLOCK_MONOTONIC, &t1);
    printf("  %-30s %5ld allocations, %4d failure points tried, %3d recovered from, %.2f s\n", name, calls, tried,
           recovered, (double)(t1.tv_sec - t0.tv_sec) + 1e-9 * (double)(t1.tv_nsec - t0.tv_nsec));
    total_points += tried;
    free(ref.b);
}

/* The allocators (src/internal.h): n * size bytes, zeroed unless asked not to; NULL when
 * n * size overflows, also where the product wrapped past SIZE_MAX would be a size they could
 * allocate (4 MiB here); on Linux, from the threshold up (2 MiB for rg2__calloc_big) on 2 MiB
 * boundaries (transparent huge pages), below it from the ordinary heap. */
static void allocators(void)
{
    const size_t mib2 = (size_t)2 << 20, wrap = SIZE_MAX / 2 + 1 + mib2; /* wrap * 2 = 4 MiB mod 2^N */
    void *w[4] = {rg2__calloc(wrap, 2), rg2__calloc_big(wrap, 2), rg2__alloc_big(wrap, 2, 4096, 0),
                  rg2__alloc_big(wrap, 2, 4096, 1)};
    CHECK(!w[0] && !w[1] && !w[2] && !w[3], "(SIZE_MAX / 2 + 1 + 2 MiB) x 2 bytes allocated: %p %p %p %p", w[0], w[1],
          w[2], w[3]);
    for (int k = 0; k < 4; k++)
        free(w[k]);
    static const size_t sizes[] = {1, 100, ((size_t)2 << 20) - 1, (size_t)2 << 20, ((size_t)2 << 20) + 1,
                                   ((size_t)6 << 20) + 5};
    int bad = 0, misaligned = 0, small = 0, small_aligned = 0;
    for (size_t k = 0; k < sizeof sizes / sizeof sizes[0]; k++)
        for (int zero = 0; zero < 2; zero++) {
            size_t n = sizes[k];
            unsigned char *p = zero ? rg2__calloc_big(n, 1) : rg2__alloc_big(n / 4 + 1, 4, mib2, 0);
            size_t got = zero ? n : 4 * (n / 4 + 1);
            if (!p) {
                bad++;
                continue;
            }
#ifdef __GLIBC__
            bad += malloc_usable_size(p) < got;
#endif
            for (size_t q = 0; zero && q < got; q++)
                bad += p[q] != 0;
            memset(p, 0xA5, got); /* (the whole array is the caller's: ASan checks the bytes) */
#if defined(__linux__) && defined(MADV_HUGEPAGE) /* (src/alloc.c aligns under the same condition) */
            if (got >= mib2)
                misaligned += (uintptr_t)p % mib2 != 0;
            else { /* (one may sit on a 2 MiB boundary by chance, not all of them) */
                small++;
                small_aligned += (uintptr_t)p % mib2 == 0;
            }
#endif
            free(p);
        }
    CHECK(bad == 0 && misaligned == 0 && (small == 0 || small_aligned < small),
          "allocators: %d arrays short, missing or not zeroed; %d of 2 MiB and more not on 2 MiB boundaries, %d of %d "
          "smaller ones on them",
          bad, misaligned, small_aligned, small);
}

int main(int argc, char **argv)
{
    (void)argc;
    const char *omp = getenv("OMP_NUM_THREADS");
    const char *sde = getenv("SOURCE_DATE_EPOCH");
    if (!omp || strcmp(omp, "1") || !sde || strcmp(sde, "0")) { /* one thread allocates (see the top) */
        setenv("OMP_NUM_THREADS", "1", 1);
        setenv("SOURCE_DATE_EPOCH", "0", 1); /* (STEP and IGES stamp the time) */
        execv("/proc/self/exe", argv);
        perror("test_faults: execv");
        return 1;
    }
    snprintf(dir, sizeof dir, "/tmp/rg2_faults_XXXXXX");
    if (!mkdtemp(dir)) {
        perror("test_faults: mkdtemp");
        return 1;
    }
    rg2_error err;
    allocators();

    /* surfaces built from meshes: a torus, and each mesh of the polar sphere */
    rg2_mesh torus;
    rg2_surface ts;
    CHECK_OK(rg2t_torus(3, 1, 6, 4, &torus, &ts, &err), &err);
    rg2_surface_free(&ts);
    sweep("surface_build torus", op_build, &torus, NULL);

    rg2_design *ds = NULL, *dp = NULL;
    CHECK_OK(rg2_design_load("examples/torus_sphere.json", &ds, &err), &err);
    CHECK_OK(rg2_design_load("examples/fig9_polar_sphere.json", &dp, &err), &err);
    if (!ds || !dp)
        return rg2t_done("test_faults");
    for (int k = 0; k < rg2_design_num_surfaces(dp); k++) {
        char name[64];
        snprintf(name, sizeof name, "surface_build polar %d", k);
        sweep(name, op_build, rg2_design_mesh(dp, k), NULL);
    }

    sweep("mesh operations torus_sphere", op_meshops, rg2_design_mesh(ds, 0), NULL);
    sweep("polar_mesh sphere, paraboloid", op_polar, NULL, NULL);
    sweep("mesh_mobius_shape polar 0", op_mobius, rg2_design_mesh(dp, 0), NULL);
    sweep("design_load torus_sphere", op_load, "examples/torus_sphere.json", NULL);
    sweep("design_load fig9_polar", op_load, "examples/fig9_polar_sphere.json", NULL);

    sweep("tessellate torus_sphere 0", op_tess, rg2_design_surface(ds, 0), NULL);
    sweep("tessellate polar 0", op_tess, rg2_design_surface(dp, 0), NULL);
    sweep("retessellate torus_sphere 0", op_retess, rg2_design_surface(ds, 0), NULL);
    sweep("locator torus_sphere 0", op_locate, rg2_design_surface(ds, 0), NULL);
    sweep("locator polar 0", op_locate, rg2_design_surface(dp, 0), NULL);
    sweep("read_text", op_read_text, "examples/torus_sphere.json", NULL);
    sweep("design_write_mesh torus_sphere", op_write_mesh, ds, ".json");
    sweep("design_write_mesh fig9_polar", op_write_mesh, dp, ".json");

    int n = rg2_design_num_surfaces(ds), m = rg2_design_num_surfaces(dp);
    rg2_surface *surfs = calloc((size_t)(n + m), sizeof *surfs);
    rg2_mesh *meshes = calloc((size_t)(n + m), sizeof *meshes);
    for (int k = 0; k < n + m; k++) { /* (views: the designs own the arrays) */
        surfs[k] = *rg2_design_surface(k < n ? ds : dp, k < n ? k : k - n);
        meshes[k] = *rg2_design_mesh(k < n ? ds : dp, k < n ? k : k - n);
    }
    write_job j = {surfs, meshes, n + m, NULL, {0}, {0}};
    rg2_export_opts_default(&j.eo);
    j.eo.density = 4;
    struct {
        const char *name, *ext;
        int layout, brep;
    } fmt[] = {{"export STEP face per patch", ".step", RG2_STEP_FACE_PER_PATCH, 0},
               {"export STEP face per mesh", ".step", RG2_STEP_FACE_PER_MESH, 0},
               {"export IGES", ".igs", RG2_STEP_FACE_PER_PATCH, 0},
               {"export IGES B-rep", ".igs", RG2_STEP_FACE_PER_PATCH, 1},
               {"export IGES B-rep per mesh", ".igs", RG2_STEP_FACE_PER_MESH, 1},
               {"export OBJ", ".obj", 0, 0},
               {"export STL", ".stl", 0, 0},
               {"export glb", ".glb", 0, 0},
               {"export PLY", ".ply", 0, 0},
               {"export BezierView", ".bv", 0, 0},
               {"export BEZ", ".bez", 0, 0},
               {"export JSON", ".json", 0, 0},
               {"export_files OBJ+STEP+PLY", ".obj+step+ply", 0, 0}};
    for (size_t f = 0; f < sizeof fmt / sizeof fmt[0]; f++) {
        j.ext = fmt[f].ext;
        j.eo.layout = (rg2_step_layout)fmt[f].layout;
        j.eo.iges_brep = fmt[f].brep;
        write_job one = j; /* (several outputs: of the polar sphere alone, for the run time) */
        if (f == sizeof fmt / sizeof fmt[0] - 1) {
            one.surfs = surfs + n;
            one.n = m;
        }
        sweep(fmt[f].name, op_export, &one, fmt[f].ext);
    }
    static const char *mem_ext[] = {".step", ".igs", ".glb"};
    for (size_t f = 0; f < sizeof mem_ext / sizeof *mem_ext; f++) {
        char name[40];
        snprintf(name, sizeof name, "export_memory %s", mem_ext[f] + 1);
        j.ext = mem_ext[f];
        j.eo.layout = RG2_STEP_FACE_PER_PATCH;
        j.eo.iges_brep = 1;
        sweep(name, op_export_memory, &j, NULL);
    }

    struct {
        const char *name;
        int apart_mesh_keep;
        rg2_render_mode mode;
    } pic[] = {{"render PNG", 0, RG2_RENDER_SHADED},
               {"render PNG apart, mesh, H", 1, RG2_RENDER_MEAN}}; /* (laid apart: render.c's own copies) */
    for (size_t f = 0; f < sizeof pic / sizeof pic[0]; f++) {
        rg2_render_opts_default(&j.ro);
        j.ro.width = 48;
        j.ro.height = 32;
        j.ro.threads = 1;
        j.ro.mode = pic[f].mode;
        j.ro.apart = j.ro.mesh = j.ro.boundaries = j.ro.keep_pixels = pic[f].apart_mesh_keep;
        sweep(pic[f].name, op_render, &j, ".png");
    }

    sweep("check", op_check, &j, NULL);
    sweep("check with shapes torus_sphere 0", op_check_shapes, ds, NULL);
    /* crossings: two cylinders that cross (confirmed crossings, two surfaces welded apart), the
     * polar sphere (poles, seams welded) and torus_sphere (none crossing) */
    rg2_design *dc = NULL;
    CHECK_OK(rg2_design_load("tests/data/crossing_cylinders.json", &dc, &err), &err);
    if (dc) {
        rg2_surface cyl[2] = {*rg2_design_surface(dc, 0), *rg2_design_surface(dc, 1)};
        crossing_job cj[3] = {{cyl, 2, 4}, {surfs + n, m, 3}, {surfs, n, 2}};
        rg2_crossing_report cr;
        CHECK_OK(rg2_find_crossings(cyl, 2, 4, 1, &cr, &err), &err);
        CHECK(cr.crossings > 0, "the cylinders cross (%d crossings): the sweep meets the confirmation", cr.crossings);
        sweep("find_crossings cylinders", op_crossings, &cj[0], NULL);
        sweep("find_crossings fig9_polar", op_crossings, &cj[1], NULL);
        sweep("find_crossings torus_sphere", op_crossings, &cj[2], NULL);
        sweep("check crossings cylinders", op_check_crossings, &cj[0], NULL);
        rg2_design_free(dc);
    }
    rg2_check_opts co;
    rg2_check_opts_default(&co);
    co.threads = 1;
    rg2_check_report r;
    CHECK_OK(rg2_check(surfs, n + m, NULL, NULL, 0, &co, &r, &err), &err);
    sweep("check_format", op_format, &r, NULL);
    rg2_check_report_free(&r);

    /* the grid keeps the tables of the first 8 grid sizes (grid.c): fill its slots with other
     * sizes first, so every call of the sweep makes (and may fail to make) tables of its own
     * (last: with the slots full, the renders and mesh exports above would make theirs per
     * patch, 500-800 allocations a run, each failure recovered from, at twice the run time) */
    for (int k = 0; k < 9; k++) {
        const rg2_surface *s = rg2_design_surface(ds, 0);
        size_t np = (size_t)s->nu * (size_t)s->nv * (size_t)(11 + k) * 3;
        double *pos = malloc(3 * np * sizeof(double));
        rg2_grid_out go = {.pos = pos};
        CHECK_OK(rg2_surface_grid(s, 11 + k, 3, 1, &go, &err), &err);
        free(pos);
    }
    CHECK(!rg2__grid_tables_cached(5, 4), "the 5 x 4 grid's tables are cached");
    for (int k = 0; k < 2; k++) {
        char name[64];
        snprintf(name, sizeof name, "surface_grid polar %d", k);
        sweep(name, op_grid, rg2_design_surface(dp, k), NULL);
    }
    printf("  %ld failure points in all\n", total_points);
    free(surfs);
    free(meshes);
    rg2_design_free(ds);
    rg2_design_free(dp);
    rg2_mesh_free(&torus);
    rmdir(dir);
    return rg2t_done("test_faults");
}
