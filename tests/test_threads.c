/* test_threads.c -- calls from several threads at once (rg2.h, "Thread safety"). Every bundled
 * design is taken through the whole library once serially, and then by THREADS threads at once:
 * each thread parses and loads every design (which builds the surfaces and caps), a NURBS spec
 * and malformed texts, and takes half the designs (each design goes to two threads) and one
 * design shared read-only by all through grids of different sizes on 1 and 2 threads (the
 * worker pool and the grid's table cache), points, the tessellation, the export formats (a
 * third of them per design, each thread in a directory of its own), the control-mesh JSON,
 * pictures and the check report (with the crossing search). Every result must be the serial run's, bit for bit (a digest
 * of the bytes). Half the threads parse and write
 * under de_DE.UTF-8 (uselocale), the others under "C": cJSON reads the decimal point through
 * localeconv(), whose one result struct every caller rewrites, and rg2's parses and prints are
 * serialised so that none of them reads another thread's decimal point. Every file written is
 * removed again: a temporary file left behind fails the test. (Two threads writing one path:
 * test_export, temp_files.)
 *
 * Race detectors run it too (scripts/check_tsan.sh): ThreadSanitizer (clang, OpenMP through
 * libomp with its Archer tool) and, for the JSON parser whose library (libcjson) no compiler here
 * instruments, valgrind's helgrind on the argument "parse" (only the parsing stage). */
#define _GNU_SOURCE
#include "harness.h"

#include <glob.h>
#include <locale.h>
#include <pthread.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#define THREADS 4
#define MAX_DESIGNS 32

static const char *const formats[] = {"step", "igs", "bv", "bez", "obj", "stl", "ply", "glb", "json"};
#define N_FORMATS (int)(sizeof formats / sizeof *formats)

/* one design's results, each a digest (FNV-1a, 64 bits) of the bytes; 0 = not made */
enum { R_PARSE, R_LOAD, R_GRID1, R_GRID2, R_GRID3, R_POINTS, R_TESS, R_MESHJSON, R_RENDER, R_CHECK, R_CHECKTXT, R_EXPORT };
#define N_RESULTS (R_EXPORT + N_FORMATS)
static const char *const result_name[R_EXPORT] = {"parse", "load",  "grid 5x7 (1 thread)", "grid 9x4 (2 threads)",
                                                  "grid 9x8 (2 threads, all outputs)", "points", "tessellation",
                                                  "mesh JSON", "render", "check JSON", "check text"};

typedef struct {
    uint64_t r[N_RESULTS];
    char err[400]; /* the first failed call */
} results;

static glob_t designs;
static int n_designs;
static char *texts[MAX_DESIGNS];
static size_t lens[MAX_DESIGNS];
static char dir[] = "/tmp/rg2-threads-XXXXXX";
static locale_t de_locale; /* (locale_t)0 if de_DE.UTF-8 could not be made */

static uint64_t fnv(uint64_t h, const void *p, size_t n)
{
    const unsigned char *b = p;
    for (size_t i = 0; i < n; i++)
        h = (h ^ b[i]) * 1099511628211u;
    return h;
}
#define FNV0 14695981039346656037u

static uint64_t file_digest(const char *path)
{
    char *t;
    size_t n;
    rg2_error err;
    if (rg2_read_text(path, &t, &n, &err) != RG2_OK)
        return 0;
    uint64_t h = fnv(FNV0, t, n);
    free(t);
    return h;
}

static void fail(results *R, const char *what, const rg2_error *err)
{
    if (!R->err[0])
        snprintf(R->err, sizeof R->err, "%.120s: %.240s", what, err ? err->msg : "");
}

/* the digest of a surface grid of n x m points per patch on `threads` threads */
static uint64_t grid(const rg2_surface *s, int n, int m, int threads, int all, results *R)
{
    size_t pts = (size_t)s->nu * (size_t)s->nv * (size_t)n * (size_t)m;
    int arrays = all ? 8 : 2; /* pos, normal (all: du, dv, duu, duv, dvv, and K, H) */
    double *buf = calloc(pts * 3 * (size_t)arrays, sizeof *buf);
    if (!buf) {
        fail(R, "grid: out of memory", NULL);
        return 0;
    }
    rg2_grid_out o = {buf, buf + 3 * pts, NULL, NULL, NULL, NULL, NULL, NULL, NULL};
    if (all) {
        o.du = buf + 6 * pts;
        o.dv = buf + 9 * pts;
        o.duu = buf + 12 * pts;
        o.duv = buf + 15 * pts;
        o.dvv = buf + 18 * pts;
        o.K = buf + 21 * pts;
        o.H = buf + 22 * pts;
    }
    rg2_error err;
    uint64_t h = 0;
    if (rg2_surface_grid(s, n, m, threads, &o, &err) == RG2_OK)
        h = fnv(FNV0, buf, pts * 3 * (size_t)arrays * sizeof *buf);
    else
        fail(R, "rg2_surface_grid", &err);
    free(buf);
    return h;
}

/* Everything on design k's surfaces (the design d, read only), file names tagged by `tag`. */
static void use_design(const rg2_design *d, int k, const char *tag, results *R)
{
    rg2_error err;
    rg2t_parts P;
    if (rg2t_design_parts(d, &P)) {
        fail(R, "out of memory", NULL);
        return;
    }
    rg2_surface *s = P.s;
    int n = P.n;
    R->r[R_GRID1] = R->r[R_GRID2] = R->r[R_GRID3] = R->r[R_POINTS] = R->r[R_TESS] = FNV0;
    for (int q = 0; q < n; q++) {
        R->r[R_GRID1] = fnv(R->r[R_GRID1], (uint64_t[]){grid(&s[q], 5, 7, 1, 0, R)}, 8);
        R->r[R_GRID2] = fnv(R->r[R_GRID2], (uint64_t[]){grid(&s[q], 9, 4, 2, 0, R)}, 8);
        R->r[R_GRID3] = fnv(R->r[R_GRID3], (uint64_t[]){grid(&s[q], 9, 8, 2, 1, R)}, 8);
        for (int p = 0; p < s[q].nu * s[q].nv; p++) {
            double pn[6];
            rg2_eval e;
            rg2_patch_point_normal(&s[q].patch[p], 0.3, 0.7, pn, pn + 3);
            rg2_surface_eval(&s[q], p / s[q].nv, p % s[q].nv, 0.6, 0.2, 2, &e);
            R->r[R_POINTS] = fnv(R->r[R_POINTS], pn, sizeof pn);
            R->r[R_POINTS] = fnv(R->r[R_POINTS], e.p, sizeof e.p);
            R->r[R_POINTS] = fnv(R->r[R_POINTS], e.n, sizeof e.n);
        }
        rg2_tess t;
        if (rg2_tessellate(&s[q], 4, 1, &t, &err) == RG2_OK) {
            R->r[R_TESS] = fnv(R->r[R_TESS], t.pos, 3 * sizeof(double) * (size_t)t.n_vertices);
            R->r[R_TESS] = fnv(R->r[R_TESS], t.normal, 3 * sizeof(double) * (size_t)t.n_vertices);
            R->r[R_TESS] = fnv(R->r[R_TESS], t.H, sizeof(double) * (size_t)t.n_vertices);
            R->r[R_TESS] = fnv(R->r[R_TESS], t.tri, 3 * sizeof(int) * (size_t)t.n_triangles);
            rg2_tess_free(&t);
        } else
            fail(R, "rg2_tessellate", &err);
        rg2_locator *L; /* picking: nearest points and first hits (a refusal is a result too) */
        rg2_status lst = rg2_locator_build(&s[q], &L, &err);
        R->r[R_POINTS] = fnv(R->r[R_POINTS], &lst, sizeof lst);
        if (lst == RG2_OK) {
            double lo[3], hi[3];
            rg2_surface_box(&s[q], lo, hi);
            for (int a = 0; a < 3; a++) {
                double x[3], ray[3];
                for (int c = 0; c < 3; c++) {
                    x[c] = lo[c] + (hi[c] - lo[c]) * (a == c ? 1.3 : 0.35 + 0.1 * a);
                    ray[c] = 0.5 * (lo[c] + hi[c]) - x[c];
                }
                rg2_hit h[2];
                if (rg2_locator_closest(L, x, &h[0], &err) || rg2_locator_ray(L, x, ray, INFINITY, &h[1], &err))
                    fail(R, "rg2_locator", &err);
                for (int b = 0; b < 2; b++) {
                    R->r[R_POINTS] = fnv(R->r[R_POINTS], h[b].p, sizeof h[b].p);
                    R->r[R_POINTS] = fnv(R->r[R_POINTS], &h[b].dist, sizeof h[b].dist);
                }
            }
            rg2_locator_free(L);
        }
    }
    char path[256];
    rg2_export_opts eo;
    rg2_export_opts_default(&eo);
    eo.density = 3;
    for (int f = (3 - k % 3) % 3; f < N_FORMATS; f += 3) { /* a third of the formats per design */
        snprintf(path, sizeof path, "%s/%s/%d.%s", dir, tag, k, formats[f]);
        if (rg2_export_file(s, n, path, &eo, &err) == RG2_OK)
            R->r[R_EXPORT + f] = file_digest(path);
        else
            fail(R, path, &err);
        unlink(path);
    }
    snprintf(path, sizeof path, "%s/%s/%d-mesh.json", dir, tag, k);
    if (rg2_design_write_mesh(d, path, &err) == RG2_OK)
        R->r[R_MESHJSON] = file_digest(path);
    else
        fail(R, "rg2_design_write_mesh", &err);
    unlink(path);

    rg2_render_opts ro;
    rg2_render_opts_default(&ro);
    ro.width = 48;
    ro.height = 32;
    ro.mode = k % 2 ? RG2_RENDER_MEAN : RG2_RENDER_SHADED;
    ro.threads = 1 + k % 2;
    ro.boundaries = ro.mesh = 1;
    rg2_image img;
    if (rg2_render(s, n, P.meshes, &ro, &img, &err) == RG2_OK) {
        R->r[R_RENDER] = fnv(FNV0, img.rgb, (size_t)img.width * (size_t)img.height * 3);
        rg2_image_free(&img);
    } else
        fail(R, "rg2_render", &err);

    rg2_check_opts co;
    rg2_check_opts_default(&co);
    co.seam_samples = 4;
    co.patch_samples = 3;
    co.threads = 1 + k % 2;
    co.crossing_density = 2; /* the crossing search too, on the check's threads */
    rg2_check_report rep;
    if (rg2_check(s, n, P.shapes, P.labels, P.ns, &co, &rep, &err) == RG2_OK) {
        for (int json = 0; json <= 1; json++) {
            char *txt = NULL;
            if (rg2_check_format(&rep, json, &txt, &err) == RG2_OK)
                R->r[json ? R_CHECK : R_CHECKTXT] = fnv(FNV0, txt, strlen(txt));
            else
                fail(R, "rg2_check_format", &err);
            free(txt);
        }
        rg2_check_report_free(&rep);
    } else
        fail(R, "rg2_check", &err);
    rg2t_design_parts_free(&P);
}

/* The digest of what parsing design k gives (its grids stand for its surfaces), or 0. */
static uint64_t parse_one(int k, int load, results *R, rg2_design **keep)
{
    rg2_error err;
    rg2_design *d = NULL;
    rg2_status st = load ? rg2_design_load(designs.gl_pathv[k], &d, &err)
                         : rg2_design_parse(texts[k], lens[k], designs.gl_pathv[k], &d, &err);
    if (st != RG2_OK) {
        fail(R, designs.gl_pathv[k], &err);
        return 0;
    }
    uint64_t h = FNV0;
    for (int q = 0; q < rg2_design_num_surfaces(d); q++) {
        const rg2_surface *s = rg2_design_surface(d, q);
        h = fnv(h, &s->nu, sizeof s->nu);
        h = fnv(h, &s->nv, sizeof s->nv);
        h = fnv(h, (uint64_t[]){grid(s, 2, 2, 1, 0, R)}, 8);
    }
    if (keep)
        *keep = d;
    else
        rg2_design_free(d);
    return h;
}

/* A NURBS spec and two malformed texts: their results and error messages (the positions each
 * call's own). */
static uint64_t parse_small(results *R)
{
    static const char spec[] = "{\"nu\": 4, \"nv\": 4, \"points\": [[0,0,0],[1,0,0.2],[2,0,0.1],[3,0,0.4],"
                               "[0,1,0.1],[1,1,0.5],[2,1,0.3],[3,1,0.2],[0,2,0.3],[1,2,0.2],[2,2,0.9],[3,2,0.4],"
                               "[0,3,0.2],[1,3,0.4],[2,3,0.1],[3,3,0.6]],"
                               "\"weights\": [1,1.2,0.9,1, 1,0.8,1.3,1, 1,1,1,1.4, 1.1,1,0.9,1],"
                               "\"knots_u\": [0,0,0,0,1,1,1,1], \"knots_v\": [0,0,0,0,1,1,1,1]}";
    static const char bad1[] = "{\"format\": \"rg2 design 1\",\n \"shapes\": {\"a\": [1.5, 2.5,, 3]}}";
    static const char bad2[] = "{\"nu\": 4,\n\n   \"nv\": 4.5.1}";
    rg2_error err;
    rg2_mesh m;
    uint64_t h = FNV0;
    if (rg2_nurbs_parse(spec, strlen(spec), "spec", &m, &err) == RG2_OK) {
        h = fnv(h, m.p, 4 * sizeof *m.p * (size_t)m.nu * (size_t)m.nv);
        rg2_mesh_free(&m);
    } else
        fail(R, "rg2_nurbs_parse", &err);
    rg2_design *d = NULL;
    if (rg2_design_parse(bad1, strlen(bad1), "bad1", &d, &err) == RG2_OK)
        rg2_design_free(d);
    h = fnv(h, err.msg, strlen(err.msg));
    if (rg2_nurbs_parse(bad2, strlen(bad2), "bad2", &m, &err) == RG2_OK)
        rg2_mesh_free(&m);
    h = fnv(h, err.msg, strlen(err.msg));
    return h;
}

/* ---------------------------------------------------------------- the threads */

typedef struct {
    int id, parse_only;       /* id THREADS: the serial run, on every design */
    const rg2_design *shared; /* design 0, read by every thread */
    results R[MAX_DESIGNS];   /* per design */
    results shared_R, small;
} worker;

/* Whether worker id takes design k through the whole library (else it only parses it): each
 * design goes to one thread under "C" and one under de_DE. */
static int uses(int id, int k) { return id == THREADS || (k + id / 2) % 2 == 0; }

static void *run(void *arg)
{
    worker *w = arg;
    locale_t old = (locale_t)0;
    if (w->id % 2 && de_locale)
        old = uselocale(de_locale);
    char tag[32], stag[32];
    snprintf(tag, sizeof tag, "w%d", w->id);
    snprintf(stag, sizeof stag, "w%ds", w->id);
    for (int i = 0; i < n_designs; i++) {
        int k = (i + w->id * 3) % n_designs; /* the threads start on different designs */
        results *R = &w->R[k];
        rg2_design *d = NULL;
        int use = !w->parse_only && uses(w->id, k);
        R->r[R_PARSE] = parse_one(k, 0, R, use ? &d : NULL);
        R->r[R_LOAD] = parse_one(k, 1, R, NULL);
        if (d)
            use_design(d, k, tag, R);
        rg2_design_free(d);
        w->small.r[0] = parse_small(&w->small);
        if (!w->parse_only && i == w->id % THREADS)
            use_design(w->shared, 0, stag, &w->shared_R);
    }
    if (old)
        uselocale(old);
    return NULL;
}

/* the first n results of got against the serial run's */
static void compare(const results *got, const results *want, int n, const char *who, const char *design)
{
    CHECK(!got->err[0], "%s, %s: %s", who, design, got->err);
    for (int i = 0; i < n; i++) {
        char what[64];
        if (i < R_EXPORT)
            snprintf(what, sizeof what, "%s", result_name[i]);
        else
            snprintf(what, sizeof what, "export .%s", formats[i - R_EXPORT]);
        CHECK(got->r[i] == want->r[i], "%s, %s: %s differs from the serial run (%016llx, serial %016llx)", who,
              design, what, (unsigned long long)got->r[i], (unsigned long long)want->r[i]);
    }
}

extern int rg2__crossing_threads_from; /* src/internal.h */

int main(int argc, char **argv)
{
    rg2__crossing_threads_from = 0; /* the crossing search on the check's threads however small the design */
    int parse_only = argc > 1 && !strcmp(argv[1], "parse"); /* helgrind: only the parsing (scripts/check_tsan.sh) */
    CHECK(mkdtemp(dir) != NULL, "mkdtemp");
    setenv("SOURCE_DATE_EPOCH", "1700000000", 1); /* the STEP and IGES time stamps */
    if (!parse_only) {
        char cmd[256];
        snprintf(cmd, sizeof cmd, "localedef -i de_DE -f UTF-8 %s/de_DE.UTF-8 >/dev/null 2>&1", dir);
        if (system(cmd) >= 0) { /* exit 1 is a warning only */
            setenv("LOCPATH", dir, 1);
            /* (through setlocale: newlocale under LOCPATH leaves a block of glibc's unreachable) */
            if (setlocale(LC_ALL, "de_DE.UTF-8"))
                de_locale = duplocale(LC_GLOBAL_LOCALE);
            setlocale(LC_ALL, "C");
        }
        snprintf(cmd, sizeof cmd, "rm -rf %s/de_DE.UTF-8", dir);
        CHECK(system(cmd) == 0, "%s", cmd);
        CHECK(de_locale != (locale_t)0, "de_DE.UTF-8 could not be made (the Debian package 'locales')");
    }
    CHECK(glob("examples/*.json", 0, NULL, &designs) == 0 && designs.gl_pathc >= 10, "the bundled designs");
    n_designs = designs.gl_pathc < MAX_DESIGNS ? (int)designs.gl_pathc : MAX_DESIGNS;
    rg2_error err;
    for (int k = 0; k < n_designs; k++)
        CHECK_OK(rg2_read_text(designs.gl_pathv[k], &texts[k], &lens[k], &err), &err);

    /* the serial run (the main thread, "C" locale) */
    worker *serial = calloc(1, sizeof *serial), *w = calloc(THREADS, sizeof *w);
    rg2_design *shared = NULL;
    if (!serial || !w) {
        CHECK(0, "out of memory");
        return rg2t_done("test_threads");
    }
    CHECK_OK(rg2_design_parse(texts[0], lens[0], designs.gl_pathv[0], &shared, &err), &err);
    for (int i = 0; i <= THREADS; i++) { /* the file names are the same in each directory */
        char sub[64];
        snprintf(sub, sizeof sub, "%s/w%d", dir, i);
        mkdir(sub, 0700);
        snprintf(sub, sizeof sub, "%s/w%ds", dir, i);
        mkdir(sub, 0700);
    }
    serial->shared = shared;
    serial->parse_only = parse_only;
    serial->id = THREADS;
    run(serial);

    for (int i = 0; i < THREADS; i++) {
        w[i].id = i;
        w[i].shared = shared;
        w[i].parse_only = parse_only;
    }
    pthread_t t[THREADS];
    for (int i = 0; i < THREADS; i++)
        CHECK(pthread_create(&t[i], NULL, run, &w[i]) == 0, "pthread_create");
    for (int i = 0; i < THREADS; i++)
        pthread_join(t[i], NULL);
    for (int i = 0; i < THREADS; i++) {
        char who[48];
        snprintf(who, sizeof who, "thread %d (%s)", i, i % 2 && de_locale ? "de_DE" : "C");
        for (int k = 0; k < n_designs; k++)
            compare(&w[i].R[k], &serial->R[k], !parse_only && uses(i, k) ? N_RESULTS : R_GRID1, who,
                    designs.gl_pathv[k]);
        compare(&w[i].small, &serial->small, 1, who, "NURBS and malformed texts");
        if (!parse_only)
            compare(&w[i].shared_R, &serial->shared_R, N_RESULTS, who, "the shared design");
    }

    rg2_design_free(shared);
    for (int k = 0; k < n_designs; k++)
        free(texts[k]);
    free(serial);
    free(w);
    globfree(&designs);
    if (de_locale)
        freelocale(de_locale);
    /* every file was removed: a temporary file left behind keeps its directory */
    char cmd[128];
    snprintf(cmd, sizeof cmd, "rmdir %s/w[0-9]* %s", dir, dir);
    CHECK(system(cmd) == 0, "files left in %s", dir);
    return rg2t_done("test_threads");
}
