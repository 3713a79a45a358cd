/* test_fptraps.c -- the public entry points on valid input with the floating-point traps of a CAD
 * host's debug build enabled, feenableexcept(FE_INVALID | FE_DIVBYZERO | FE_OVERFLOW): surface
 * builds (every bundled design, a torus, a capped sphere, a NURBS), grid evaluation on every
 * kernel (AVX-512 with hardware division and with Newton steps, portable; plain and streaming
 * stores; widths that leave padding lanes), per-point evaluation, tessellation, every export
 * format, the check and its reports, rendering in every mode, with 1 and 2 threads. A trap is
 * SIGFPE: the handler names the stage and the address, and the test fails.
 * Threads: the traps are enabled before the first rg2 call, so the grid's worker pool and the
 * OpenMP threads, created later by threads that trap, inherit them (Linux gives a new thread its
 * creator's floating-point environment); they are also enabled inside an OpenMP parallel region,
 * and the workers of both are checked to trap. Skipped (exit 77) where feenableexcept does not
 * exist (a glibc extension) or does not take effect. */
#define _GNU_SOURCE /* feenableexcept, fegetexcept; mkdtemp */
#include "../src/internal.h"
#include "harness.h"

#include <fenv.h>
#include <glob.h>
#include <math.h>
#include <signal.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>
#ifdef _OPENMP
#include <omp.h>
#endif

#if defined(__GLIBC__) && defined(FE_INVALID) && defined(FE_DIVBYZERO) && defined(FE_OVERFLOW)
#define HAVE_TRAPS 1
#define TRAPS (FE_INVALID | FE_DIVBYZERO | FE_OVERFLOW)

static char stage[256] = "start";
#define STAGE(...) snprintf(stage, sizeof stage, __VA_ARGS__)

static void on_fpe(int sig, siginfo_t *si, void *ctx)
{
    (void)sig;
    (void)ctx;
    const char *what = si->si_code == FPE_FLTDIV   ? "FE_DIVBYZERO"
                       : si->si_code == FPE_FLTOVF ? "FE_OVERFLOW"
                       : si->si_code == FPE_FLTINV ? "FE_INVALID"
                                                   : "a floating-point trap";
    char buf[512];
    int n = snprintf(buf, sizeof buf, "FAIL test_fptraps: SIGFPE (%s) at %p during %s\n", what, si->si_addr, stage);
    if (n > 0)
        (void)!write(2, buf, (size_t)n < sizeof buf ? (size_t)n : sizeof buf - 1);
    _exit(1);
}

/* Whether the calling thread traps the three exceptions. */
static int trapping(void)
{
    return (fegetexcept() & TRAPS) == TRAPS;
}

/* A chunk of the grid's worker pool: clears *arg if the thread running it does not trap. */
static void pool_chunk(void *arg, uint32_t c)
{
    (void)c;
    if (!trapping())
        *(volatile int *)arg = 0;
}

static size_t stream_default;
static char dir[64]; /* the temporary directory of the written files */
static volatile double sink; /* evaluation results, kept */

/* Grids of s: every kernel, positions / with normals / everything, 1 and 2 threads, on widths
 * of one vector, less than one (padding lanes past the last point), several vectors with a
 * partial last one, and (big) two blocks of columns (64 + 13) with a partial last vector. */
static void grids(const rg2_surface *s, const char *name, int big)
{
    static const int sizes[][2] = {{2, 2}, {5, 7}, {8, 8}, {9, 13}, {17, 37}, {21, 77}};
    const int nsizes = big ? 6 : 5;
    rg2_error err;
    for (int z = 0; z < nsizes; z++) {
        int n = sizes[z][0], m = sizes[z][1];
        size_t np = (size_t)s->nu * (size_t)s->nv * (size_t)n * (size_t)m;
        double *buf = malloc(sizeof(double) * np * 23);
        if (!buf) {
            CHECK(0, "%s: out of memory for %zu points", name, np);
            return;
        }
        for (int kern = 0; kern < 4; kern++) {
            rg2__grid_portable = kern == 3;
            rg2__grid_hwdiv = kern == 0 ? 1 : kern == 1 ? 0 : -1;
            rg2__grid_stream_bytes = kern == 2 ? 0 : stream_default; /* kern 2: streaming stores */
            for (int order = 0; order < 3; order++)
                for (int th = 1; th <= 2; th++) {
                    STAGE("%s: grid %d x %d, kernel %d, order %d, %d threads", name, n, m, kern, order, th);
                    rg2_grid_out o = {0};
                    o.pos = buf;
                    if (order >= 1)
                        o.normal = buf + 3 * np;
                    if (order >= 2) {
                        o.du = buf + 6 * np, o.dv = buf + 9 * np, o.duu = buf + 12 * np;
                        o.duv = buf + 15 * np, o.dvv = buf + 18 * np, o.K = buf + 21 * np, o.H = buf + 22 * np;
                    }
                    CHECK_OK(rg2_surface_grid(s, n, m, th, &o, &err), &err);
                    if (th == 1 && !(s->xp && s->xp[0].du > 0)) {
                        STAGE("%s: rg2_patch_grid %d x %d, kernel %d, order %d", name, n, m, kern, order);
                        CHECK_OK(rg2_patch_grid(&s->patch[0], n, m, &o, &err), &err);
                    }
                }
        }
        free(buf);
    }
    rg2__grid_portable = 0;
    rg2__grid_hwdiv = -1;
    rg2__grid_stream_bytes = stream_default;
}

/* Per-point evaluation of every patch (at most 200) on a 5 x 5 grid with the corners. */
static void points(const rg2_surface *s, const char *name)
{
    STAGE("%s: per-point evaluation", name);
    int np = s->nu * s->nv;
    for (int k = 0; k < np && k < 200; k++) {
        int i = k / s->nv, j = k % s->nv;
        int bi3 = !(s->xp && s->xp[k].du > 0);
        for (int a = 0; a <= 4; a++)
            for (int b = 0; b <= 4; b++) {
                double u = a / 4.0, v = b / 4.0, h[6][4], p[3], nn[3];
                rg2_eval e;
                for (int order = 0; order <= 2; order++) {
                    rg2_surface_eval(s, i, j, u, v, order, &e);
                    sink += e.p[0];
                }
                sink += rg2_eval_normal_curvature(&e, 1.0, 0.5);
                rg2_surface_eval_h(s, i, j, u, v, h);
                if (bi3) {
                    rg2_patch_point(&s->patch[k], u, v, p);
                    sink += rg2_patch_point_normal(&s->patch[k], u, v, p, nn);
                }
            }
    }
}

/* Picking: nearest points and first ray hits from points around and inside the control box,
 * along the axes (the slab tests' parallel case) and obliquely, and a ray with tmax = 0. */
static void locate(const rg2_surface *s, const char *name)
{
    STAGE("%s: picking", name);
    rg2_locator *L;
    rg2_error err;
    if (rg2_locator_build(s, &L, &err)) /* (a surface with weights <= 0 is refused: fine here) */
        return;
    double lo[3], hi[3];
    rg2_surface_box(s, lo, hi);
    for (int q = 0; q < 12; q++) {
        double x[3], d[3] = {0, 0, 0};
        for (int k = 0; k < 3; k++)
            x[k] = lo[k] + (hi[k] - lo[k]) * (-0.3 + 0.15 * ((q + 2 * k) % 11));
        if (q < 6)
            d[q % 3] = q < 3 ? 1 : -1;
        else
            for (int k = 0; k < 3; k++)
                d[k] = 0.5 * (lo[k] + hi[k]) - x[k] + 0.1 * (hi[k] - lo[k]) * (k - 1);
        if (d[0] == 0 && d[1] == 0 && d[2] == 0)
            d[0] = 1;
        rg2_hit h;
        if (!rg2_locator_closest(L, x, &h, &err))
            sink += h.dist;
        if (!rg2_locator_ray(L, x, d, q == 11 ? 0.0 : INFINITY, &h, &err))
            sink += h.bound;
    }
    rg2_locator_free(L);
}

static void tessellate(const rg2_surface *s, const char *name)
{
    rg2_error err;
    rg2_tess t = {0};
    static const int dens[] = {1, 5, 16};
    for (int d = 0; d < 3; d++)
        for (int curv = 0; curv < 2; curv++) {
            STAGE("%s: tessellate density %d, curvature %d", name, dens[d], curv);
            CHECK_OK(rg2_retessellate(s, dens[d], curv, &t, &err), &err);
        }
    rg2_tess_free(&t);
}

/* Every format (floats 0: not STL, PLY and glTF, which refuse surfaces beyond 3.4e38). */
static void export_all(const rg2_surface *s, int n, const char *name, int floats)
{
    static const char *const ext[] = {"step", "igs", "bv", "bez", "obj", "json", "stl", "ply", "glb"};
    const int NEXT = floats ? 9 : 6;
    char path[9][128];
    const char *paths[9];
    for (int k = 0; k < NEXT; k++) {
        snprintf(path[k], sizeof path[k], "%s/out.%s", dir, ext[k]);
        paths[k] = path[k];
    }
    rg2_error err;
    for (int v = 0; v < 2; v++) {
        rg2_export_opts o;
        rg2_export_opts_default(&o);
        if (v) {
            o.layout = RG2_STEP_FACE_PER_MESH;
            o.ap242 = 1;
            o.iges_brep = 1;
            o.density = 5;
        }
        STAGE("%s: export, options %d", name, v);
        int failed = -1;
        CHECK_OK(rg2_export_files(s, n, paths, NEXT, &o, &failed, &err), &err);
    }
    for (int k = 0; k < NEXT; k++)
        unlink(path[k]);
}

static void check_and_render(const rg2_surface *s, int n, const rg2_shape *shapes, const char *const *labels,
                             int ns, const rg2_mesh *meshes, const char *name)
{
    rg2_error err;
    for (int th = 1; th <= 2; th++) {
        rg2_check_opts co;
        rg2_check_opts_default(&co);
        co.threads = th;
        rg2_check_report r;
        STAGE("%s: check, %d threads", name, th);
        CHECK_OK(rg2_check(s, n, shapes, labels, ns, &co, &r, &err), &err);
        (void)rg2_check_failures(&r, RG2_REQUIRE_G2 | RG2_REQUIRE_EXACT | RG2_REQUIRE_WEIGHTS);
        for (int json = 0; json < 2; json++) {
            char *text = NULL;
            STAGE("%s: check report, json %d", name, json);
            CHECK_OK(rg2_check_format(&r, json, &text, &err), &err);
            free(text);
        }
        rg2_check_report_free(&r);
        for (int mode = RG2_RENDER_SHADED; mode <= RG2_RENDER_ZEBRA; mode++) {
            rg2_render_opts ro;
            rg2_render_opts_default(&ro);
            ro.width = 64, ro.height = 48, ro.threads = th, ro.mode = (rg2_render_mode)mode;
            ro.boundaries = mode == RG2_RENDER_SHADED;
            ro.mesh = meshes && mode == RG2_RENDER_MEAN;
            ro.apart = n > 1 && mode == RG2_RENDER_ZEBRA;
            rg2_image img;
            STAGE("%s: render mode %d, %d threads", name, mode, th);
            CHECK_OK(rg2_render(s, n, ro.mesh ? meshes : NULL, &ro, &img, &err), &err);
            rg2_image_free(&img);
        }
    }
}

/* Everything on surfaces s[0..n-1] (shapes nullable; big: a larger grid too; floats: see
 * export_all). */
static void run_all(const rg2_surface *s, int n, const rg2_shape *shapes, const char *const *labels, int ns,
                    const rg2_mesh *meshes, const char *name, int big, int floats)
{
    for (int k = 0; k < n; k++) {
        char nm[160];
        snprintf(nm, sizeof nm, "%s, surface %d", name, k);
        STAGE("%s: box and weights", nm);
        double lo[3], hi[3];
        rg2_weight_report wr;
        rg2_surface_box(&s[k], lo, hi);
        (void)rg2_surface_min_weight(&s[k]);
        rg2_surface_weight_report(&s[k], &wr);
        grids(&s[k], nm, big);
        points(&s[k], nm);
        locate(&s[k], nm);
    }
    for (int th = 1; th <= 2; th++) {
#ifdef _OPENMP
        omp_set_num_threads(th);
#endif
        for (int k = 0; k < n; k++)
            tessellate(&s[k], name);
        export_all(s, n, name, floats);
    }
    check_and_render(s, n, shapes, labels, ns, meshes, name);
}

static void designs(void)
{
    glob_t g;
    CHECK(glob("examples/*.json", 0, NULL, &g) == 0 && g.gl_pathc >= 10, "the bundled designs");
    for (size_t f = 0; f < g.gl_pathc; f++) {
        const char *path = g.gl_pathv[f];
        rg2_error err;
        rg2_design *d = NULL;
        for (int th = 1; th <= 2; th++) { /* (building more than 256 patches runs OpenMP threads) */
#ifdef _OPENMP
            omp_set_num_threads(th);
#endif
            STAGE("%s: load and build, %d threads", path, th);
            rg2_design_free(d);
            d = NULL;
            CHECK_OK(rg2_design_load(path, &d, &err), &err);
        }
        if (!d)
            continue;
        rg2t_parts P;
        if (rg2t_design_parts(d, &P)) {
            CHECK(0, "out of memory");
            break;
        }
        run_all(P.s, P.n, P.shapes, P.labels, P.ns, P.meshes, path, 0, 1);
        char mp[128];
        snprintf(mp, sizeof mp, "%s/mesh.json", dir);
        STAGE("%s: write the mesh", path);
        CHECK_OK(rg2_design_write_mesh(d, mp, &err), &err);
        unlink(mp);
        rg2t_design_parts_free(&P);
        rg2_design_free(d);
    }
    globfree(&g);
}

static void torus_cap_nurbs(void)
{
    rg2_error err;
    rg2_mesh m;
    rg2_surface s;
    STAGE("torus: build");
    CHECK_OK(rg2t_torus(3, 1, 8, 6, &m, &s, &err), &err);
    run_all(&s, 1, NULL, NULL, 0, &m, "torus 8 x 6", 1, 1);
    STAGE("torus: rebuild");
    CHECK_OK(rg2_surface_rebuild(&m, &s, &err), &err);
    rg2_surface_free(&s);
    /* near the ends of the numeric range (docs/robustness.md): coordinates 1.4e45 (the float
     * formats refuse them) and a size of 6e-30 (curvatures 4e59: beyond the float formats') */
    for (int e = 0; e < 2; e++) {
        double M[16], f = ldexp(1.0, e ? -100 : 150);
        char nm[64];
        snprintf(nm, sizeof nm, "torus scaled by 2^%d", e ? -100 : 150);
        rg2_mesh c;
        rg2_xform_scale(M, f, f, f);
        STAGE("%s: build", nm);
        CHECK_OK(rg2_mesh_copy(&m, &c, &err), &err);
        rg2_mesh_transform(&c, M);
        CHECK_OK(rg2_surface_build(&c, &s, &err), &err);
        run_all(&s, 1, NULL, NULL, 0, &c, nm, 0, e);
        rg2_surface_free(&s);
        rg2_mesh_free(&c);
    }
    rg2_mesh_free(&m);

    STAGE("capped sphere: build");
    CHECK_OK(rg2t_capped_sphere(&m, &s, &err), &err);
    run_all(&s, 1, NULL, NULL, 0, NULL, "capped sphere", 0, 1);
    rg2_surface_free(&s);
    /* the general quadratic caps (degree (4, 3) patches) on the same body */
    rg2_cap_opts co;
    rg2_cap_opts_default(&co);
    co.quadratic = RG2_CAP_GENERAL;
    rg2_cap_info info;
    STAGE("general caps: build");
    CHECK_OK(rg2_cap_build(&m, &co, &s, &info, &err), &err);
    run_all(&s, 1, NULL, NULL, 0, NULL, "general caps", 0, 1);
    rg2_surface_free(&s);
    rg2_mesh_free(&m);

    /* a rational NURBS with clamped ends and uneven knots */
    const char *spec = "{\"nu\": 5, \"nv\": 6, \"points\": ["
                       "[0,0,0],[1,0,0.2],[2,0,0.1],[3,0,0.4],[4,0,0],[5,0,0.3],"
                       "[0,1,0.1],[1,1,0.5],[2,1,0.3],[3,1,0.2],[4,1,0.6],[5,1,0.1],"
                       "[0,2,0.3],[1,2,0.2],[2,2,0.9],[3,2,0.4],[4,2,0.1],[5,2,0.2],"
                       "[0,3,0.2],[1,3,0.4],[2,3,0.1],[3,3,0.6],[4,3,0.3],[5,3,0.5],"
                       "[0,4,0],[1,4,0.1],[2,4,0.3],[3,4,0.2],[4,4,0.4],[5,4,0]],"
                       "\"weights\": [1,1.2,0.9,1,1.1,1, 1,0.8,1.3,1,1,1.2, 1,1,1,1.4,0.9,1,"
                       " 1.1,1,0.9,1,1.2,1, 1,1,1.1,1,1,1],"
                       "\"knots_u\": [0,0,0,0,0.4,1,1,1,1], \"knots_v\": [0,0,0,0,0.3,0.5,1,1,1,1]}";
    STAGE("NURBS: parse and build");
    CHECK_OK(rg2_nurbs_parse(spec, strlen(spec), "spec", &m, &err), &err);
    CHECK_OK(rg2_surface_build(&m, &s, &err), &err);
    run_all(&s, 1, NULL, NULL, 0, &m, "NURBS 5 x 6", 0, 1);
    rg2_surface_free(&s);
    rg2_mesh_free(&m);
}
#endif

int main(void)
{
#ifndef HAVE_TRAPS
    printf("test_fptraps: skipped (feenableexcept is a glibc extension)\n");
    return 77;
#else
    if (feenableexcept(TRAPS) == -1 || !trapping()) {
        printf("test_fptraps: skipped (the floating-point traps cannot be enabled here)\n");
        return 77;
    }
    struct sigaction sa;
    memset(&sa, 0, sizeof sa);
    sa.sa_sigaction = on_fpe;
    sa.sa_flags = SA_SIGINFO;
    sigaction(SIGFPE, &sa, NULL);
    stream_default = rg2__grid_stream_bytes;

    /* every worker traps: OpenMP's (enabled in the region too) and the grid pool's */
    int omp_ok = 1, pool_ok = 1;
#ifdef _OPENMP
#pragma omp parallel num_threads(2)
    {
        feenableexcept(TRAPS);
    }
#pragma omp parallel num_threads(2) reduction(&& : omp_ok)
    omp_ok = trapping();
#endif
    rg2__pool_run(2, 64, pool_chunk, &pool_ok);
    CHECK(omp_ok && pool_ok, "worker threads trap: OpenMP %d, pool %d", omp_ok, pool_ok);

    snprintf(dir, sizeof dir, "/tmp/rg2_fptraps_XXXXXX");
    if (!mkdtemp(dir)) {
        CHECK(0, "temporary directory");
        return rg2t_done("test_fptraps");
    }
    torus_cap_nurbs();
    designs();
    rmdir(dir);

    /* (the traps off again: the harness and libc print with them as they please) */
    fedisableexcept(TRAPS);
    return rg2t_done("test_fptraps");
#endif
}
