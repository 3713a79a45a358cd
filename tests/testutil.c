/* testutil.c -- shared test helpers: counting checks, random numbers, seam measurements. */
#define _POSIX_C_SOURCE 200809L /* setrlimit, sigaction */
#include "harness.h"

#include <dirent.h>
#include <math.h>
#include <signal.h>
#include <stdlib.h>
#include <string.h>
#include <sys/resource.h>

int rg2t_passed = 0, rg2t_failed = 0;

int rg2t_done(const char *name)
{
    printf("%s: %d passed, %d failed\n", name, rg2t_passed, rg2t_failed);
    return rg2t_failed ? 1 : 0;
}

int rg2t_file_limit(long long bytes)
{
    static struct rlimit saved;
    static int have;
    if (bytes < 0)
        return have ? setrlimit(RLIMIT_FSIZE, &saved) : 0;
    if (!have && getrlimit(RLIMIT_FSIZE, &saved) != 0)
        return -1;
    have = 1;
    signal(SIGXFSZ, SIG_IGN); /* the write returns EFBIG instead of killing the process */
    struct rlimit l = saved;
    l.rlim_cur = (rlim_t)bytes;
    return setrlimit(RLIMIT_FSIZE, &l);
}

void rg2t_seed(rg2t_rng *r, uint64_t seed) { r->s = seed; }

static uint64_t next(rg2t_rng *r)
{
    uint64_t z = (r->s += 0x9E3779B97F4A7C15ull);
    z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
    z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
    return z ^ (z >> 31);
}

double rg2t_uniform(rg2t_rng *r, double lo, double hi)
{
    return lo + (hi - lo) * ((double)(next(r) >> 11) * (1.0 / 9007199254740992.0));
}

int rg2t_int(rg2t_rng *r, int lo, int hi) { return lo + (int)(next(r) % (uint64_t)(hi - lo + 1)); }

double rg2t_surface_scale(const rg2_surface *s)
{
    double lo[3] = {INFINITY, INFINITY, INFINITY}, hi[3] = {-INFINITY, -INFINITY, -INFINITY};
    for (int i = 0; i < s->nu; i++)
        for (int j = 0; j < s->nv; j++) {
            rg2_xpatch P;
            rg2_surface_patch_get(s, i, j, &P);
            for (int r = 0; r <= P.du; r++)
            for (int t = 0; t <= P.dv; t++) {
                const double *h = P.h[r][t];
                for (int d = 0; d < 3; d++) {
                    double x = h[d] / h[3];
                    if (x < lo[d]) lo[d] = x;
                    if (x > hi[d]) hi[d] = x;
                }
            }
        }
    return sqrt((hi[0] - lo[0]) * (hi[0] - lo[0]) + (hi[1] - lo[1]) * (hi[1] - lo[1]) +
                (hi[2] - lo[2]) * (hi[2] - lo[2]));
}

static double dot(const double *a, const double *b) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }
static double norm(const double *a) { return sqrt(dot(a, a)); }

/* Normal curvature of evaluation e in the 3D tangent direction t (projected on the plane). */
static double kn_dir(const rg2_eval *e, const double t[3])
{
    double E = dot(e->su, e->su), F = dot(e->su, e->sv), G = dot(e->sv, e->sv);
    double r1 = dot(t, e->su), r2 = dot(t, e->sv);
    double det = E * G - F * F;
    double a = (G * r1 - F * r2) / det, c = (E * r2 - F * r1) / det;
    return rg2_eval_normal_curvature(e, a, c);
}

/* Measure one seam point: L at its transversal parameter end, R at its start. dir = 0: the
 * seam is u = const (transversal derivative in u), dir = 1: v = const. */
static void measure(const rg2_eval *L, const rg2_eval *R, int dir, double b, double g, double scale,
                    rg2t_seams *o, const char *where)
{
    o->samples++;
    double d[3];
    for (int k = 0; k < 3; k++)
        d[k] = L->p[k] - R->p[k];
    double pos = norm(d) / scale;
    if (pos > o->pos) o->pos = pos;
    /* parametric relations on the 3D point */
    const double *lt = dir == 0 ? L->su : L->sv, *rt = dir == 0 ? R->su : R->sv;
    const double *ltt = dir == 0 ? L->suu : L->svv, *rtt = dir == 0 ? R->suu : R->svv;
    double e1[3], e2[3];
    for (int k = 0; k < 3; k++) {
        e1[k] = rt[k] - b * lt[k];
        e2[k] = rtt[k] - b * b * ltt[k] - g * lt[k];
    }
    double nl = norm(lt);
    if (nl > 1e-12 * scale) { /* not at a collapsed edge (pole): there lt is rounding noise */
        double p1 = norm(e1) / nl;
        double p2 = norm(e2) / (b * b * norm(ltt) + fabs(g) * nl + nl);
        if (p1 > o->param1) o->param1 = p1;
        if (p2 > o->param2) o->param2 = p2;
    }
    if ((L->flags | R->flags) & RG2_EVAL_NORMAL_UNDEFINED) {
        o->skipped++;
        return;
    }
    double c[3] = {L->n[1] * R->n[2] - L->n[2] * R->n[1], L->n[2] * R->n[0] - L->n[0] * R->n[2],
                   L->n[0] * R->n[1] - L->n[1] * R->n[0]};
    double ang = atan2(norm(c), dot(L->n, R->n));
    if (ang > o->angle) o->angle = ang;
    /* tangent frame: t1 along the seam, t2 = n x t1 */
    const double *along = dir == 0 ? L->sv : L->su;
    double la = norm(along);
    if (la == 0) {
        o->skipped++;
        return;
    }
    double t1[3] = {along[0] / la, along[1] / la, along[2] / la};
    double t2[3] = {L->n[1] * t1[2] - L->n[2] * t1[1], L->n[2] * t1[0] - L->n[0] * t1[2],
                    L->n[0] * t1[1] - L->n[1] * t1[0]};
    double kscale = fmax(fmax(fabs(L->k1), fabs(L->k2)), 1.0 / scale);
    for (int q = 0; q < 6; q++) {
        double ph = M_PI * q / 6.0, t[3];
        for (int k = 0; k < 3; k++)
            t[k] = cos(ph) * t1[k] + sin(ph) * t2[k];
        double jump = fabs(kn_dir(L, t) - kn_dir(R, t)) / kscale;
        if (jump > o->curv) {
            o->curv = jump;
            snprintf(o->where, sizeof o->where, "%s", where);
        }
    }
}

void rg2t_surface_seams(const rg2_surface *s, int samples, rg2t_seams *o)
{
    memset(o, 0, sizeof *o);
    double scale = rg2t_surface_scale(s);
    char where[128];
    /* u seams: patch (i-1, j) u=1 | patch (i, j) u=0 with bu[i], gu[i] */
    for (int i = s->closed_u ? 0 : 1; i < s->nu; i++) {
        int im = (i + s->nu - 1) % s->nu;
        for (int j = 0; j < s->nv; j++) {
            o->seams++;
            snprintf(where, sizeof where, "u seam between patches (%d,%d) and (%d,%d)", im, j, i, j);
            for (int k = 0; k <= samples; k++) {
                double t = (double)k / samples;
                rg2_eval L, R;
                rg2_surface_eval(s, im, j, 1.0, t, 2, &L);
                rg2_surface_eval(s, i, j, 0.0, t, 2, &R);
                measure(&L, &R, 0, s->bu[i], s->gu[i], scale, o, where);
            }
        }
    }
    for (int j = s->closed_v ? 0 : 1; j < s->nv; j++) {
        int jm = (j + s->nv - 1) % s->nv;
        for (int i = 0; i < s->nu; i++) {
            o->seams++;
            snprintf(where, sizeof where, "v seam between patches (%d,%d) and (%d,%d)", i, jm, i, j);
            for (int k = 0; k <= samples; k++) {
                double t = (double)k / samples;
                rg2_eval L, R;
                rg2_surface_eval(s, i, jm, t, 1.0, 2, &L);
                rg2_surface_eval(s, i, j, t, 0.0, 2, &R);
                measure(&L, &R, 1, s->bv[j], s->gv[j], scale, o, where);
            }
        }
    }
}

rg2_status rg2t_torus(double R, double r, int nu, int nv, rg2_mesh *mesh, rg2_surface *out, rg2_error *err)
{
    rg2_mesh m = {0};
    memset(out, 0, sizeof *out);
    double *a = calloc((size_t)(nu + nv) * 3, sizeof(double));
    if (!a)
        return RG2_ENOMEM;
    double *au = a, *av = a + nu, *csu = a + nu + nv, *csv = csu + 2 * nu;
    for (int i = 0; i < nu; i++)
        au[i] = 2 * M_PI / nu;
    for (int j = 0; j < nv; j++)
        av[j] = 2 * M_PI / nv;
    rg2_status st = rg2_mesh_init(&m, nu, nv, 1, 1, err);
    if (!st)
        st = rg2_circle_coeffs(au, nu, 1, 0.0, csu, err);
    if (!st)
        st = rg2_circle_coeffs(av, nv, 1, 0.0, csv, err);
    if (!st) {
        rg2_scalars_free(&m.su);
        rg2_scalars_free(&m.sv);
        st = rg2_scalars_from_angles(&m.su, au, nu, 1, err);
    }
    if (!st)
        st = rg2_scalars_from_angles(&m.sv, av, nv, 1, err);
    if (!st) {
        for (int i = 0; i < nu; i++)
            for (int j = 0; j < nv; j++) {
                double *p = rg2_mesh_at(&m, i, j);
                p[0] = (R + r * csv[2 * j]) * csu[2 * i];
                p[1] = (R + r * csv[2 * j]) * csu[2 * i + 1];
                p[2] = r * csv[2 * j + 1];
                p[3] = 1.0;
            }
        st = rg2_surface_build(&m, out, err);
    }
    free(a);
    if (mesh && !st)
        *mesh = m;
    else
        rg2_mesh_free(&m);
    return st;
}

rg2_status rg2t_elevate_some(rg2_surface *s, int du, int dv, int stride, int phase, rg2_error *err)
{
    size_t np = (size_t)s->nu * (size_t)s->nv;
    if (!s->xp) {
        s->xp = calloc(np, sizeof(rg2_xpatch));
        if (!s->xp)
            return RG2_ENOMEM;
    }
    for (size_t k = 0; k < np; k++) {
        if ((int)(k % (size_t)stride) != phase || s->xp[k].du > 0)
            continue;
        rg2_xpatch x;
        rg2_xpatch_from_patch(&s->patch[k], &x);
        rg2_status st = rg2_xpatch_elevate(&x, du, dv, &s->xp[k], err);
        if (st)
            return st;
        for (int r = 0; r < 4; r++)
            for (int t = 0; t < 4; t++)
                for (int c = 0; c < 4; c++)
                    s->patch[k].h[r][t][c] = NAN;
    }
    return RG2_OK;
}

rg2_status rg2t_capped_sphere(rg2_mesh *mesh, rg2_surface *out, rg2_error *err)
{
    double a[6], v[4] = {0.2, 0.4, 0.6, 0.8};
    for (int k = 0; k < 6; k++)
        a[k] = RG2_PI / 3;
    memset(out, 0, sizeof *out);
    rg2_status st = rg2_polar_sphere_mesh(a, 6, 0.0, v, 4, NULL, mesh, err);
    if (!st && (st = rg2_cap_build(mesh, NULL, out, NULL, err)))
        rg2_mesh_free(mesh);
    return st;
}

int rg2t_design_parts(const rg2_design *d, rg2t_parts *p)
{
    p->n = rg2_design_num_surfaces(d);
    p->ns = rg2_design_num_shapes(d);
    p->s = calloc((size_t)p->n + 1, sizeof *p->s);
    p->meshes = calloc((size_t)p->n + 1, sizeof *p->meshes);
    p->shapes = calloc((size_t)p->ns + 1, sizeof *p->shapes);
    p->labels = calloc((size_t)p->ns + 1, sizeof *p->labels);
    if (!p->s || !p->meshes || !p->shapes || !p->labels) {
        rg2t_design_parts_free(p);
        return -1;
    }
    for (int k = 0; k < p->n; k++) {
        p->s[k] = *rg2_design_surface(d, k);
        p->meshes[k] = *rg2_design_mesh(d, k);
    }
    for (int q = 0; q < p->ns; q++) {
        p->shapes[q] = *rg2_design_shape(d, q);
        p->labels[q] = rg2_design_shape_label(d, q);
    }
    return 0;
}

void rg2t_design_parts_free(rg2t_parts *p)
{
    free(p->s);
    free(p->meshes);
    free(p->shapes);
    free(p->labels);
    p->s = NULL;
    p->meshes = NULL;
    p->shapes = NULL;
    p->labels = NULL;
}

static int cmp_str(const void *a, const void *b) { return strcmp(*(char *const *)a, *(char *const *)b); }

int rg2t_example_names(char **names, int max)
{
    DIR *dir = opendir("examples");
    CHECK(dir != NULL, "examples/ directory (tests run in the source tree)");
    if (!dir)
        return 0;
    int n = 0;
    struct dirent *de;
    while ((de = readdir(dir)) && n < max) {
        size_t len = strlen(de->d_name);
        if (len > 5 && !strcmp(de->d_name + len - 5, ".json")) {
            names[n] = malloc(len + 10);
            snprintf(names[n], len + 10, "examples/%s", de->d_name);
            n++;
        }
    }
    closedir(dir);
    qsort(names, (size_t)n, sizeof *names, cmp_str);
    CHECK(n >= 1, "%d example designs", n);
    return n;
}
