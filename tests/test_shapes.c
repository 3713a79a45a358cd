/* test_shapes.c -- exact basic shapes: every named shape, closed and partial, over equal and
 * random partitions, scales 1e-3 .. 1e3 and far-from-origin placements, measured against its
 * implicit equation (residual, Gaussian and mean curvature), its own parameterization through
 * the arc map of MATH.md section 2, and G2 across every seam; the generic family
 * constructors, exact transforms, the weight report and every invalid-parameter error. */
#include "expect_err.h"
#include "harness.h"

#include <limits.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#define MAXSEG 16

static double dot3(const double *a, const double *b) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }

/* Worst measurements of one shape kind. */
typedef struct {
    double resid, K, H, repro, angle, curv, pos;
    double minw;
    long samples;
    int configs, skipped;
} stats;

static void stats_init(stats *s)
{
    memset(s, 0, sizeof *s);
    s->minw = INFINITY;
}

/* Limits of the knot range used for a polynomial direction of each shape in these tests
 * (away from poles, apexes and points at infinity, where the shape itself degenerates). */
static void safe_range(rg2_shape_kind kind, int dir, double r[2])
{
    r[0] = -2.0, r[1] = 2.0;
    switch (kind) {
    case RG2_SHAPE_SPHERE:
    case RG2_SHAPE_ELLIPSOID: r[0] = 0.05, r[1] = 0.95; break;
    case RG2_SHAPE_CONE: r[0] = 0.2, r[1] = 2.0; break;
    case RG2_SHAPE_HYPERBOLOID1: r[0] = 0.3, r[1] = 3.0; break;
    case RG2_SHAPE_HYPERBOLOID2: r[0] = 0.1, r[1] = 0.9; break;
    case RG2_SHAPE_PARABOLOID: r[0] = 0.1, r[1] = 2.0; break;
    default: break;
    }
    (void)dir;
}

/* A partition of m segments: closed or open circle arcs, or knots in [lo, hi]; equal or random. */
static void make_partition(rg2t_rng *r, rg2_partition_kind kind, int closed, int m, int random,
                           const double range[2], double *vals, rg2_partition *p)
{
    memset(p, 0, sizeof *p);
    p->kind = kind;
    p->values = vals;
    if (kind == RG2_PART_ANGLES) {
        p->closed = closed;
        p->n = m;
        p->start = rg2t_uniform(r, -M_PI, M_PI);
        double sweep = closed ? 2.0 * M_PI : rg2t_uniform(r, 0.2, fmin(1.9 * M_PI, 0.9 * M_PI * m));
        for (int tries = 0;; tries++) {
            double sum = 0.0, mx = 0.0;
            for (int k = 0; k < m; k++)
                sum += (vals[k] = random ? rg2t_uniform(r, 0.4, 1.6) : 1.0);
            for (int k = 0; k < m; k++) {
                vals[k] *= sweep / sum;
                mx = fmax(mx, vals[k]);
            }
            if (mx < 0.95 * M_PI || tries > 100)
                break;
        }
        if (closed) { /* make the sum 2 pi to rounding */
            double sum = 0.0;
            for (int k = 0; k + 1 < m; k++)
                sum += vals[k];
            vals[m - 1] = 2.0 * M_PI - sum;
        }
    } else {
        double lo = range[0], hi = range[1];
        if (random) { /* a random sub-range */
            double a = rg2t_uniform(r, lo, hi), b = rg2t_uniform(r, lo, hi);
            lo = fmin(a, b), hi = fmax(a, b);
            if (hi - lo < 0.2 * (range[1] - range[0]))
                lo = range[0], hi = range[1];
        }
        p->n = m + 1;
        double sum = 0.0, w[MAXSEG + 1];
        for (int k = 0; k < m; k++)
            sum += (w[k] = random ? rg2t_uniform(r, 0.3, 1.7) : 1.0);
        vals[0] = lo;
        double acc = 0.0;
        for (int k = 1; k < m; k++) {
            acc += w[k - 1];
            vals[k] = lo + (hi - lo) * acc / sum;
        }
        vals[m] = hi;
    }
}

/* The test's own arc / identity map (MATH.md section 2), independent of rg2_partition_map. */
static double own_map(const rg2_partition *p, int seg, double t)
{
    if (p->kind == RG2_PART_KNOTS)
        return p->values[seg] + t * (p->values[seg + 1] - p->values[seg]);
    double th = p->start;
    for (int k = 0; k < seg; k++)
        th += p->values[k];
    double beta = 0.5 * p->values[seg];
    return th + beta + 2.0 * atan(tan(0.5 * beta) * (2.0 * t - 1.0));
}

/* A random similarity placement: scale, rotation about a random axis, translation. */
static void random_placement(rg2t_rng *r, double scale, double offset, double M[16])
{
    double S[16], R[16], T[16];
    rg2_xform_scale(S, scale, scale, scale);
    rg2_xform_rotate(R, rg2t_uniform(r, -1, 1), rg2t_uniform(r, -1, 1), rg2t_uniform(r, -1, 1),
                     rg2t_uniform(r, -M_PI, M_PI));
    double d[3] = {rg2t_uniform(r, -1, 1), rg2t_uniform(r, -1, 1), rg2t_uniform(r, -1, 1)};
    double len = sqrt(dot3(d, d));
    rg2_xform_translate(T, offset * d[0] / len, offset * d[1] / len, offset * d[2] / len);
    rg2_xform_mul(R, S, M);
    rg2_xform_mul(T, M, M);
}

/* Gaussian and mean curvature of the level set f = 0 from the gradient and Hessian
 * (normal along the gradient): K = g^T adj(Hf) g / |g|^4, H = (g^T Hf g - |g|^2 tr Hf) / (2 |g|^3). */
static void implicit_curvatures(const double g[3], const double h[9], double *K, double *H)
{
    double adj[9] = {h[4] * h[8] - h[5] * h[7], h[2] * h[7] - h[1] * h[8], h[1] * h[5] - h[2] * h[4],
                     h[5] * h[6] - h[3] * h[8], h[0] * h[8] - h[2] * h[6], h[2] * h[3] - h[0] * h[5],
                     h[3] * h[7] - h[4] * h[6], h[1] * h[6] - h[0] * h[7], h[0] * h[4] - h[1] * h[3]};
    double gg = dot3(g, g), q = 0.0, qa = 0.0;
    for (int i = 0; i < 3; i++)
        for (int j = 0; j < 3; j++) {
            q += g[i] * h[3 * i + j] * g[j];
            qa += g[i] * adj[3 * i + j] * g[j];
        }
    *K = qa / (gg * gg);
    *H = (q - gg * (h[0] + h[4] + h[8])) / (2.0 * gg * sqrt(gg));
}

/* Sample every patch on an ns x ns grid and fold the measurements into st. */
static void measure_surface(const rg2_shape *sh, const rg2_surface *s, const rg2_partition *pu,
                            const rg2_partition *pv, double L, int ns, stats *st)
{
    for (int i = 0; i < s->nu; i++)
        for (int j = 0; j < s->nv; j++)
            for (int a = 0; a < ns; a++)
                for (int b = 0; b < ns; b++) {
                    double tu = (a + 0.5) / ns, tv = (b + 0.5) / ns;
                    if (a == 0) tu = 0.0;
                    if (b == ns - 1) tv = 1.0;
                    rg2_eval e;
                    rg2_patch_eval(rg2_surface_patch(s, i, j), tu, tv, 2, &e);
                    double g[3], h[9];
                    double f = rg2_shape_implicit2(sh, e.p, g, h);
                    double gn = sqrt(dot3(g, g));
                    st->samples++;
                    double res = fabs(f) / (gn * L);
                    if (!(res <= st->resid)) st->resid = res;
                    /* own parameterization through the arc map */
                    double hp[4];
                    rg2_shape_param(sh, own_map(pu, i, tu), own_map(pv, j, tv), hp);
                    double d[3];
                    for (int k = 0; k < 3; k++)
                        d[k] = hp[k] / hp[3] - e.p[k];
                    double rep = sqrt(dot3(d, d)) / L;
                    if (!(rep <= st->repro)) st->repro = rep;
                    if (e.flags & RG2_EVAL_CURVATURE_UNDEFINED) {
                        st->skipped++;
                        continue;
                    }
                    double Ki, Hi;
                    implicit_curvatures(g, h, &Ki, &Hi);
                    if (dot3(g, e.n) < 0.0)
                        Hi = -Hi;
                    double kap = fmax(fmax(fabs(e.k1), fabs(e.k2)), 1.0 / L);
                    double eK = fabs(e.K - Ki) / (kap * kap), eH = fabs(e.H - Hi) / kap;
                    if (!(eK <= st->K)) st->K = eK;
                    if (!(eH <= st->H)) st->H = eH;
                }
}

/* Build one configuration of a shape, measure it, and fold the figures into near[0] (centred
 * placements) or near[1] (far from the origin). Far placements put the shape at 10 times its
 * size from the origin: coordinates then carry only eps * |x| absolute precision, so the
 * curvature and seam figures are divided by rho = (size + offset) / size before folding. */
static void run_config(rg2t_rng *r, rg2_shape_kind kind, int cfg, stats st2[2])
{
    const rg2_shape_desc *d = rg2_shape_describe(kind);
    rg2_shape sh;
    rg2_shape_init(&sh, kind);
    /* shape parameter variants: cyclide ring / horn / spindle, torus radii */
    if (kind == RG2_SHAPE_CYCLIDE) {
        static const double mus[3] = {1.5, 0.6, 2.6}; /* ring c < mu < a, horn mu < c, spindle mu > a */
        sh.param[2] = mus[cfg % 3];
    } else if (kind == RG2_SHAPE_TORUS) {
        sh.param[1] = rg2t_uniform(r, 0.2, 2.5);
    } else if (kind == RG2_SHAPE_HYPAR || kind == RG2_SHAPE_PARABOLOID) {
        sh.param[0] = rg2t_uniform(r, 0.5, 2.0);
        sh.param[1] = rg2t_uniform(r, 0.5, 2.0);
    }
    static const double scales[3] = {1e-3, 1.0, 1e3};
    int far = cfg & 1;
    double scale = scales[cfg % 3];
    double vu[MAXSEG + 1], vv[MAXSEG + 1];
    rg2_partition pu, pv;
    rg2_partition *ps[2] = {&pu, &pv};
    double *vs[2] = {vu, vv};
    for (int dir = 0; dir < 2; dir++) {
        int closed = d->dir_kind[dir] == RG2_PART_ANGLES && !((cfg >> (1 + dir)) & 1);
        int m = rg2t_int(r, 3, 12);
        int random = (cfg >> 3) & 1 ? 1 : (cfg % 2 == 0);
        double range[2];
        safe_range(kind, dir, range);
        make_partition(r, d->dir_kind[dir], closed, m, random, range, vs[dir], ps[dir]);
    }
    /* the cyclide's horn form has its singular points at v = pi, cos u = mu / c, the spindle
     * form at u = pi, cos v = a / mu: open v partitions keep the samples away from them */
    if (kind == RG2_SHAPE_CYCLIDE && cfg % 3 != 0) {
        double lo = cfg % 3 == 1 ? -0.75 * M_PI : 0.35 * M_PI, span = cfg % 3 == 1 ? 1.5 * M_PI : 1.3 * M_PI;
        pv.closed = 0;
        pv.start = lo;
        double sum = 0.0;
        for (int k = 0; k < pv.n; k++)
            sum += vv[k];
        for (int k = 0; k < pv.n; k++)
            vv[k] *= span / sum;
        while (pv.n < 3 || span / pv.n >= 0.95 * M_PI) /* keep every arc below pi */
            pv.n = 3, vv[0] = vv[1] = vv[2] = span / 3;
    }
    rg2_surface s;
    rg2_weight_report rep;
    rg2_error err;
    /* size of the unplaced shape, for the far offset */
    rg2_status stt = rg2_shape_surface(&sh, &pu, &pv, &s, NULL, &err);
    CHECK(stt == RG2_OK, "%s config %d: %s", d->name, cfg, err.msg);
    if (stt)
        return;
    double size = rg2t_surface_scale(&s) * scale, offset = far ? 10.0 * size : 0.0;
    rg2_surface_free(&s);
    random_placement(r, scale, offset, sh.xform);
    stt = rg2_shape_surface(&sh, &pu, &pv, &s, &rep, &err);
    CHECK(stt == RG2_OK, "%s config %d: %s", d->name, cfg, err.msg);
    if (stt)
        return;
    CHECK(s.nu == rg2_partition_num_segments(&pu) && s.nv == rg2_partition_num_segments(&pv),
          "%s config %d: %d x %d patches for %d x %d segments", d->name, cfg, s.nu, s.nv,
          rg2_partition_num_segments(&pu), rg2_partition_num_segments(&pv));
    CHECK(rep.min_weight == rg2_surface_min_weight(&s), "%s: weight report %g vs %g", d->name,
          rep.min_weight, rg2_surface_min_weight(&s));
    CHECK(((rep.flags & RG2_SHAPE_WARN_WEIGHT) != 0) == (rep.min_weight <= 0.0),
          "%s: weight flag %u for min weight %g", d->name, rep.flags, rep.min_weight);
    stats *st = &st2[far], one;
    stats_init(&one);
    double L = size + offset, rho = L / size;
    int ns = 2;
    while ((long)ns * ns * s.nu * s.nv < 1400)
        ns++;
    measure_surface(&sh, &s, &pu, &pv, L, ns, &one);
    rg2t_seams g;
    rg2t_surface_seams(&s, 10, &g);
    st->resid = fmax(st->resid, one.resid);
    st->repro = fmax(st->repro, one.repro);
    st->K = fmax(st->K, one.K / rho);
    st->H = fmax(st->H, one.H / rho);
    st->angle = fmax(st->angle, g.angle / rho);
    st->curv = fmax(st->curv, g.curv / rho);
    st->pos = fmax(st->pos, g.pos);
    st->minw = fmin(st->minw, rep.min_weight);
    st->samples += one.samples;
    st->skipped += one.skipped;
    st->configs++;
    if (getenv("RG2T_VERBOSE"))
        printf("    %s cfg %d scale %g offset %g: %d x %d, K %.2e H %.2e angle %.2e curv %.2e\n", d->name,
               cfg, scale, offset, s.nu, s.nv, one.K, one.H, g.angle, g.curv);
    rg2_surface_free(&s);
}

static void named_shapes(void)
{
    rg2t_rng r;
    uint64_t seed = 3003;
    rg2t_seed(&r, seed);
    printf("named shapes, seed %llu: residual = |f| / (|grad f| L), L = size + offset; reproduction\n"
           "  = distance / L; K, H relative to max(|k1|, |k2|, 1/L); far rows: offset = 10 size,\n"
           "  curvature and seam figures divided by rho = L / size = 11\n",
           (unsigned long long)seed);
    printf("  %-19s %4s %7s %9s %9s %9s %9s %9s %9s %9s\n", "shape", "cfgs", "samples", "residual",
           "K rel", "H rel", "repro", "seam ang", "seam crv", "min w");
    for (int kind = 0; kind < RG2_SHAPE_COUNT; kind++) {
        stats st[2];
        stats_init(&st[0]);
        stats_init(&st[1]);
        for (int cfg = 0; cfg < 10; cfg++)
            run_config(&r, (rg2_shape_kind)kind, cfg, st);
        const char *name = rg2_shape_name((rg2_shape_kind)kind);
        for (int far = 0; far < 2; far++) {
            printf("  %-19s %4d %7ld %9.2e %9.2e %9.2e %9.2e %9.2e %9.2e %9.3g\n", far ? "  (far)" : name,
                   st[far].configs, st[far].samples, st[far].resid, st[far].K, st[far].H, st[far].repro,
                   st[far].angle, st[far].curv, st[far].minw);
            CHECK(st[far].resid <= 1e-13, "%s far %d: implicit residual %.3g", name, far, st[far].resid);
            CHECK(st[far].K <= 1e-9, "%s far %d: Gaussian curvature error %.3g", name, far, st[far].K);
            CHECK(st[far].H <= 1e-9, "%s far %d: mean curvature error %.3g", name, far, st[far].H);
            CHECK(st[far].repro <= 1e-13, "%s far %d: reproduction of the parameterization %.3g", name,
                  far, st[far].repro);
            CHECK(st[far].pos <= 1e-14, "%s far %d: seam position gap %.3g", name, far, st[far].pos);
            /* far rows: 1.6e-12 at most for a clang build, 7.5e-13 for GCC's (the cyclide) */
            CHECK(st[far].angle <= (far ? 5e-12 : 1e-12), "%s far %d: seam normal angle %.3g", name, far,
                  st[far].angle);
            CHECK(st[far].curv <= 1e-10, "%s far %d: seam curvature jump %.3g", name, far, st[far].curv);
        }
        CHECK(st[0].samples + st[1].samples >= 10000, "%s: %ld samples", name,
              st[0].samples + st[1].samples);
    }
}

/* Distance of patch points from a reference homogeneous map over the partitions' own maps. */
typedef void (*ref_fn)(const void *ctx, double u, double v, double h[4]);

static double reproduction(const rg2_surface *s, const rg2_partition *pu, const rg2_partition *pv,
                           ref_fn f, const void *ctx, int ns)
{
    double L = rg2t_surface_scale(s), worst = 0.0;
    for (int i = 0; i < s->nu; i++)
        for (int j = 0; j < s->nv; j++)
            for (int a = 0; a <= ns; a++)
                for (int b = 0; b <= ns; b++) {
                    double tu = (double)a / ns, tv = (double)b / ns, h[4], d[3];
                    rg2_eval e;
                    rg2_patch_eval(rg2_surface_patch(s, i, j), tu, tv, 0, &e);
                    f(ctx, own_map(pu, i, tu), own_map(pv, j, tv), h);
                    for (int k = 0; k < 3; k++)
                        d[k] = h[k] / h[3] - e.p[k];
                    double x = sqrt(dot3(d, d)) / L;
                    if (!(x <= worst)) worst = x;
                }
    return worst;
}

static void ref_family1(const void *ctx, double u, double v, double h[4])
{
    const double(*a)[9] = (const double(*)[9])ctx;
    double bs[9] = {1, cos(u), sin(u), cos(v), sin(v), cos(u) * cos(v), sin(u) * cos(v),
                    cos(u) * sin(v), sin(u) * sin(v)};
    for (int k = 0; k < 4; k++) {
        h[k] = 0.0;
        for (int q = 0; q < 9; q++)
            h[k] += a[k][q] * bs[q];
    }
}

static void ref_family2(const void *ctx, double u, double v, double h[4])
{
    const double(*c)[3][4] = (const double(*)[3][4])ctx;
    for (int k = 0; k < 4; k++) {
        h[k] = 0.0;
        for (int s = 0; s < 4; s++)
            h[k] += (c[k][0][s] + c[k][1][s] * cos(u) + c[k][2][s] * sin(u)) * pow(v, s);
    }
}

static void ref_family3(const void *ctx, double u, double v, double h[4])
{
    const double(*A)[4][4] = (const double(*)[4][4])ctx;
    for (int k = 0; k < 4; k++) {
        h[k] = 0.0;
        for (int r = 0; r < 4; r++)
            for (int s = 0; s < 4; s++)
                h[k] += A[k][r][s] * pow(u, r) * pow(v, s);
    }
}

/* Generic family constructors on random coefficients: reproduction and G2. */
static void families(void)
{
    rg2t_rng r;
    rg2t_seed(&r, 77);
    printf("generic families, seed 77\n");
    double worst[3] = {0, 0, 0}, wang = 0, wcurv = 0;
    rg2_error err;
    double range[2] = {-1.0, 1.0};
    for (int trial = 0; trial < 12; trial++) {
        int fam = trial % 3;
        double vu[MAXSEG + 1], vv[MAXSEG + 1];
        rg2_partition pu, pv;
        make_partition(&r, fam == 2 ? RG2_PART_KNOTS : RG2_PART_ANGLES, trial & 4 ? 0 : 1,
                       rg2t_int(&r, 3, 12), trial & 8 ? 1 : 0, range, vu, &pu);
        make_partition(&r, fam == 0 ? RG2_PART_ANGLES : RG2_PART_KNOTS, trial & 2 ? 0 : 1,
                       rg2t_int(&r, 3, 12), 1, range, vv, &pv);
        rg2_mesh m;
        rg2_status st;
        double a1[4][9], c2[4][3][4], A3[4][4][4];
        const void *ctx;
        ref_fn f;
        if (fam == 0) {
            for (int k = 0; k < 4; k++)
                for (int q = 0; q < 9; q++)
                    a1[k][q] = k == 3 ? (q ? rg2t_uniform(&r, -0.4, 0.4) : 4.0) : rg2t_uniform(&r, -2, 2);
            st = rg2_family1_mesh((const double(*)[9])a1, &pu, &pv, &m, &err);
            ctx = a1, f = ref_family1;
        } else if (fam == 1) {
            for (int k = 0; k < 4; k++)
                for (int q = 0; q < 3; q++)
                    for (int s = 0; s < 4; s++)
                        c2[k][q][s] = k == 3 ? (q || s ? rg2t_uniform(&r, -0.3, 0.3) : 4.0)
                                             : rg2t_uniform(&r, -2, 2);
            st = rg2_family2_mesh((const double(*)[3][4])c2, &pu, &pv, &m, &err);
            ctx = c2, f = ref_family2;
        } else {
            for (int k = 0; k < 4; k++)
                for (int q = 0; q < 4; q++)
                    for (int s = 0; s < 4; s++)
                        A3[k][q][s] = k == 3 ? (q || s ? rg2t_uniform(&r, -0.2, 0.2) : 4.0)
                                             : rg2t_uniform(&r, -2, 2);
            st = rg2_family3_mesh((const double(*)[4][4])A3, &pu, &pv, &m, &err);
            ctx = A3, f = ref_family3;
        }
        CHECK(st == RG2_OK, "family %d trial %d: %s", fam + 1, trial, err.msg);
        if (st)
            continue;
        rg2_surface s;
        CHECK_OK(rg2_surface_build(&m, &s, &err), &err);
        double rep = reproduction(&s, &pu, &pv, f, ctx, 6);
        if (rep > worst[fam]) worst[fam] = rep;
        rg2t_seams g;
        rg2t_surface_seams(&s, 8, &g);
        wang = fmax(wang, g.angle);
        wcurv = fmax(wcurv, g.curv);
        rg2_surface_free(&s);
        rg2_mesh_free(&m);
    }
    printf("  reproduction: family 1 %.2e, family 2 %.2e, family 3 %.2e; seams: angle %.2e, "
           "curvature %.2e\n",
           worst[0], worst[1], worst[2], wang, wcurv);
    for (int k = 0; k < 3; k++)
        CHECK(worst[k] <= 1e-13, "family %d reproduction %.3g", k + 1, worst[k]);
    CHECK(wang <= 1e-12 && wcurv <= 1e-10, "family seams: angle %.3g curvature %.3g", wang, wcurv);
}

/* Exact transforms: transforming the mesh then building equals building then transforming,
 * for a projective matrix; and a projectively placed shape satisfies its implicit equation. */
static void transforms(void)
{
    rg2t_rng r;
    rg2t_seed(&r, 5);
    rg2_error err;
    rg2_shape sh;
    rg2_shape_init(&sh, RG2_SHAPE_TORUS);
    double vu[8], vv[8];
    rg2_partition pu, pv;
    double range[2] = {0, 0};
    make_partition(&r, RG2_PART_ANGLES, 1, 7, 1, range, vu, &pu);
    make_partition(&r, RG2_PART_ANGLES, 0, 5, 1, range, vv, &pv);
    double M[16] = {0.9, 0.2, -0.1, 1.5, -0.3, 1.1, 0.25, -2.0, 0.1, -0.2, 0.8, 0.5,
                    0.03, -0.02, 0.04, 1.0};
    rg2_mesh m0, m1;
    rg2_surface s0, s1;
    CHECK_OK(rg2_shape_mesh(&sh, &pu, &pv, &m0, &err), &err);
    CHECK_OK(rg2_mesh_copy(&m0, &m1, &err), &err);
    rg2_mesh_transform(&m1, M);
    CHECK_OK(rg2_surface_build(&m0, &s0, &err), &err);
    CHECK_OK(rg2_surface_build(&m1, &s1, &err), &err);
    double worst = 0.0, L = rg2t_surface_scale(&s1);
    for (int i = 0; i < s0.nu; i++)
        for (int j = 0; j < s0.nv; j++)
            for (int a = 0; a <= 8; a++)
                for (int b = 0; b <= 8; b++) {
                    double H[6][4], q[4];
                    rg2_patch_eval_h(rg2_surface_patch(&s0, i, j), a / 8.0, b / 8.0, H);
                    for (int k = 0; k < 4; k++)
                        q[k] = M[4 * k] * H[0][0] + M[4 * k + 1] * H[0][1] + M[4 * k + 2] * H[0][2] +
                               M[4 * k + 3] * H[0][3];
                    rg2_eval e;
                    rg2_patch_eval(rg2_surface_patch(&s1, i, j), a / 8.0, b / 8.0, 0, &e);
                    double d[3] = {q[0] / q[3] - e.p[0], q[1] / q[3] - e.p[1], q[2] / q[3] - e.p[2]};
                    worst = fmax(worst, sqrt(dot3(d, d)) / L);
                }
    printf("transform then build vs build then transform (projective): %.2e\n", worst);
    CHECK(worst <= 1e-13, "transform commutes with the construction: %.3g", worst);
    /* the projectively placed torus against its implicit equation and parameterization */
    memcpy(sh.xform, M, sizeof M);
    stats st;
    stats_init(&st);
    measure_surface(&sh, &s1, &pu, &pv, L, 8, &st);
    printf("projectively placed torus: residual %.2e, K %.2e, H %.2e, reproduction %.2e\n", st.resid,
           st.K, st.H, st.repro);
    CHECK(st.resid <= 1e-13 && st.repro <= 1e-13, "projective torus residual %.3g repro %.3g",
          st.resid, st.repro);
    CHECK(st.K <= 1e-9 && st.H <= 1e-9, "projective torus curvatures %.3g %.3g", st.K, st.H);
    /* its Hessian itself (the curvatures see only its part on the tangent plane, where the part
     * antisymmetric in x, y, z cancels): symmetric, and the gradient's central differences, at
     * points on and off the projectively placed torus */
    double hw = 0.0;
    for (int k = 0; k < 60; k++) {
        double x[3] = {4.0 * sin(1.3 * k), 4.0 * cos(0.7 * k + 1.0), 1.5 * sin(0.3 * k + 2.0)}, g[3], h[9], hs = 1.0;
        rg2_shape_implicit2(&sh, x, g, h);
        for (int q = 0; q < 9; q++)
            hs = fmax(hs, fabs(h[q]));
        for (int j = 0; j < 3; j++) {
            double xp[3] = {x[0], x[1], x[2]}, xm[3] = {x[0], x[1], x[2]}, gp[3], gm[3];
            xp[j] += 1e-5, xm[j] -= 1e-5;
            rg2_shape_implicit(&sh, xp, gp);
            rg2_shape_implicit(&sh, xm, gm);
            for (int i = 0; i < 3; i++)
                hw = fmax(hw, fmax(fabs(h[3 * i + j] - (gp[i] - gm[i]) / 2e-5), fabs(h[3 * i + j] - h[3 * j + i])) / hs);
        }
    }
    printf("its Hessian against the gradient's central differences and its transpose: %.2e (relative)\n", hw);
    CHECK(hw <= 1e-6, "projective torus Hessian: %.3g off the differences of the gradient or not symmetric", hw);
    /* non-uniform scale: the unit sphere scaled by (2, 1.5, 0.5) is the ellipsoid (2, 1.5, 0.5) */
    rg2_shape sp, el;
    rg2_shape_init(&sp, RG2_SHAPE_SPHERE);
    rg2_shape_init(&el, RG2_SHAPE_ELLIPSOID);
    el.param[0] = 2.0, el.param[1] = 1.5, el.param[2] = 0.5;
    rg2_xform_scale(sp.xform, 2.0, 1.5, 0.5);
    double kv[4] = {0.1, 0.3, 0.7, 0.9};
    rg2_partition pk = {RG2_PART_KNOTS, 0, 4, kv, 0};
    rg2_surface se, ss;
    CHECK_OK(rg2_shape_surface(&sp, &pu, &pk, &ss, NULL, &err), &err);
    CHECK_OK(rg2_shape_surface(&el, &pu, &pk, &se, NULL, &err), &err);
    double de = 0.0;
    for (int k = 0; k < se.nu * se.nv; k++)
        for (int q = 0; q < 64; q++)
            de = fmax(de, fabs((&se.patch[k].h[0][0][0])[q] - (&ss.patch[k].h[0][0][0])[q]));
    CHECK(de <= 1e-15, "scaled sphere equals the ellipsoid: %.3g", de);
    rg2_surface_free(&se);
    rg2_surface_free(&ss);
    /* placement helpers: place() maps z to the axis and the origin to the centre */
    double P[16], c[3] = {1, -2, 3}, ax[3] = {0.3, -0.4, 0.5}, z[4] = {0, 0, 1, 0}, o[4] = {0, 0, 0, 1};
    rg2_xform_place(P, c, ax);
    double pz[4], po[4], la = sqrt(dot3(ax, ax));
    for (int k = 0; k < 4; k++) {
        pz[k] = P[4 * k] * z[0] + P[4 * k + 1] * z[1] + P[4 * k + 2] * z[2] + P[4 * k + 3] * z[3];
        po[k] = P[4 * k] * o[0] + P[4 * k + 1] * o[1] + P[4 * k + 2] * o[2] + P[4 * k + 3] * o[3];
    }
    double e1 = 0, e2 = 0;
    for (int k = 0; k < 3; k++) {
        e1 = fmax(e1, fabs(pz[k] - ax[k] / la));
        e2 = fmax(e2, fabs(po[k] - c[k]));
    }
    CHECK(e1 <= 1e-15 && e2 <= 1e-15, "xform_place: axis %.3g centre %.3g", e1, e2);
    double inv[16], I[16];
    CHECK_OK(rg2_xform_invert(M, inv, &err), &err);
    rg2_xform_mul(M, inv, I);
    double ei = 0;
    for (int k = 0; k < 16; k++)
        ei = fmax(ei, fabs(I[k] - (k % 5 == 0 ? 1.0 : 0.0)));
    CHECK(ei <= 1e-14, "xform_invert: M M^-1 - I = %.3g", ei);
    /* a scale of 1e-310 (subnormal): the inverse's 1e310 is past the double range; it came back as
     * inf with RG2_OK */
    double S[16], Si[16];
    rg2_xform_scale(S, 1e-310, 1.0, 1.0);
    memcpy(Si, I, sizeof Si);
    expect_err(rg2_xform_invert(S, Si, &err), RG2_EDOMAIN, &err, "inverse entry [0][0] overflows", "subnormal scale");
    CHECK(!memcmp(Si, I, sizeof Si), "xform_invert: the output written on failure");
    for (int k = 1; k < 3; k++) { /* the entry named is the one that overflows: [1][1] for y, [2][2] for z */
        double sc[3] = {1.0, 1.0, 1.0};
        char want[48];
        sc[k] = 1e-310;
        rg2_xform_scale(S, sc[0], sc[1], sc[2]);
        snprintf(want, sizeof want, "inverse entry [%d][%d] overflows", k, k);
        expect_err(rg2_xform_invert(S, Si, &err), RG2_EDOMAIN, &err, want, "subnormal scale of y or z");
    }
    rg2_surface_free(&s0);
    rg2_surface_free(&s1);
    rg2_mesh_free(&m0);
    rg2_mesh_free(&m1);
}

/* Partitions with explicit data arcs / knots; the library's parameter map. */
static void full_partitions(void)
{
    rg2_error err;
    rg2_shape sh;
    rg2_shape_init(&sh, RG2_SHAPE_TORUS);
    double arcs[4] = {0.4, 0.7, 0.5, 0.6};
    double full[8] = {0.4, 0.4, 0.4, 0.7, 0.5, 0.6, 0.6, 0.6};
    rg2_partition pa = {RG2_PART_ANGLES, 0, 4, arcs, 0.3};
    rg2_partition pf = {RG2_PART_ANGLES_FULL, 0, 8, full, 0.3};
    double va[3] = {0.0, 1.0, 2.5};
    rg2_partition pv = {RG2_PART_ANGLES, 0, 3, va, -1.0};
    va[0] = 0.9, va[1] = 1.0, va[2] = 1.1;
    rg2_surface s1, s2;
    CHECK_OK(rg2_shape_surface(&sh, &pa, &pv, &s1, NULL, &err), &err);
    CHECK_OK(rg2_shape_surface(&sh, &pf, &pv, &s2, NULL, &err), &err);
    double d = 0;
    for (int k = 0; k < s1.nu * s1.nv && s1.nu == s2.nu; k++)
        for (int q = 0; q < 64; q++)
            d = fmax(d, fabs((&s1.patch[k].h[0][0][0])[q] - (&s2.patch[k].h[0][0][0])[q]));
    CHECK(s1.nu == 4 && s2.nu == 4 && d == 0.0, "angles_full with copied data arcs equals angles: %.3g", d);
    rg2_surface_free(&s2);
    /* different data arcs: same shape, still exact, same parameter map */
    full[0] = 1.2, full[1] = 0.2, full[6] = 2.0, full[7] = 0.1;
    CHECK_OK(rg2_shape_surface(&sh, &pf, &pv, &s2, NULL, &err), &err);
    double worst = 0, L = rg2t_surface_scale(&s2);
    for (int i = 0; i < s2.nu; i++)
        for (int j = 0; j < s2.nv; j++)
            for (int a = 0; a <= 6; a++) {
                double t = a / 6.0, h[4];
                rg2_eval e;
                rg2_patch_eval(rg2_surface_patch(&s2, i, j), t, 1 - t, 0, &e);
                CHECK(fabs(rg2_partition_map(&pf, i, t) - own_map(&pa, i, t)) <= 1e-15,
                      "partition map of full angles");
                rg2_shape_param(&sh, rg2_partition_map(&pf, i, t), rg2_partition_map(&pv, j, 1 - t), h);
                for (int k = 0; k < 3; k++)
                    worst = fmax(worst, fabs(h[k] / h[3] - e.p[k]) / L);
            }
    CHECK(worst <= 1e-14, "torus with other data arcs reproduces the torus: %.3g", worst);
    rg2_surface_free(&s1);
    rg2_surface_free(&s2);
    /* knots with explicit data knots: sphere band */
    rg2_shape_init(&sh, RG2_SHAPE_SPHERE);
    double kn[7] = {-0.5, 0.0, 0.2, 0.45, 0.7, 1.0, 1.7};
    rg2_partition pk = {RG2_PART_KNOTS_FULL, 0, 7, kn, 0};
    double eq[6];
    rg2_partition pu;
    CHECK_OK(rg2_partition_equal(&pu, RG2_PART_ANGLES, 1, 0.0, 0.0, 5, eq, 6, &err), &err);
    CHECK(rg2_partition_num_segments(&pk) == 2, "knots_full segments %d", rg2_partition_num_segments(&pk));
    CHECK_OK(rg2_shape_surface(&sh, &pu, &pk, &s1, NULL, &err), &err);
    worst = 0;
    for (int i = 0; i < s1.nu; i++)
        for (int j = 0; j < s1.nv; j++)
            for (int a = 0; a <= 8; a++) {
                double t = a / 8.0, h[4];
                rg2_eval e;
                rg2_patch_eval(rg2_surface_patch(&s1, i, j), 0.5, t, 0, &e);
                rg2_shape_param(&sh, rg2_partition_map(&pu, i, 0.5), kn[j + 2] + t * (kn[j + 3] - kn[j + 2]), h);
                for (int k = 0; k < 3; k++)
                    worst = fmax(worst, fabs(h[k] / h[3] - e.p[k]));
            }
    CHECK(s1.nv == 2 && worst <= 1e-14, "sphere band over knots_full [0.2, 0.7]: %.3g", worst);
    rg2_surface_free(&s1);
}

/* Knot directions: rg2_partition_map is v_seg + t (v_seg+1 - v_seg), checked on a cylinder (z = v
 * exactly) through the independent patch evaluator; out-of-range segments give NaN. The
 * partition checks refuse what the layouts cannot mean, naming it. */
static void knot_maps_and_checks(void)
{
    rg2_error err;
    rg2_shape sh;
    rg2_shape_init(&sh, RG2_SHAPE_CYLINDER);
    sh.param[0] = 2.0;
    double kv[4] = {-1.0, 0.5, 1.7, 2.0}, eq[7];
    rg2_partition pu, pv = {RG2_PART_KNOTS, 0, 4, kv, 0.0};
    CHECK_OK(rg2_partition_equal(&pu, RG2_PART_ANGLES, 1, 0.0, 0.0, 6, eq, 7, &err), &err);
    rg2_surface s;
    CHECK_OK(rg2_shape_surface(&sh, &pu, &pv, &s, NULL, &err), &err);
    double wz = 0, wr = 0;
    for (int i = 0; i < s.nu; i++)
        for (int j = 0; j < s.nv; j++)
            for (int a = 0; a <= 8; a++) {
                double t = a / 8.0;
                rg2_eval e;
                rg2_patch_eval(rg2_surface_patch(&s, i, j), 1.0 - t, t, 0, &e);
                double z = rg2_partition_map(&pv, j, t);
                CHECK(z == kv[j] + t * (kv[j + 1] - kv[j]), "knot map seg %d t %g: %.17g", j, t, z);
                wz = fmax(wz, fabs(e.p[2] - z));
                wr = fmax(wr, fabs(hypot(e.p[0], e.p[1]) - 2.0));
            }
    CHECK(s.nv == 3 && wz <= 2e-15 && wr <= 4e-15, /* a few ulps of the coordinates, 2 */ "cylinder over knots: height vs the knot map %.3g, radius %.3g",
          wz, wr);
    CHECK(isnan(rg2_partition_map(&pv, 3, 0.5)) && isnan(rg2_partition_map(&pv, -1, 0.5)) &&
              isnan(rg2_partition_map(&pu, 6, 0.0)),
          "segments outside the partition map to NaN");
    rg2_surface_free(&s);

    rg2_partition bad = pv;
    bad.kind = (rg2_partition_kind)7;
    expect_err(rg2_partition_check(&bad, "u", &err), RG2_EINVAL, &err, "u partition has unknown kind 7", "unknown kind");
    CHECK(rg2_partition_num_segments(&bad) == 0, "unknown kind: %d segments", rg2_partition_num_segments(&bad));
    /* a negative count near INT_MIN: n - 4 / n - 5 overflowed to about 2^31 segments */
    for (int kind = RG2_PART_ANGLES; kind <= RG2_PART_KNOTS_FULL; kind++) {
        bad.kind = (rg2_partition_kind)kind;
        bad.n = INT_MIN + 2;
        int ns = rg2_partition_num_segments(&bad);
        CHECK(ns == 0 && isnan(rg2_partition_map(&bad, 1000, 0.5)), /* (the map read values[1002]) */
              "kind %d, %d values: %d segments", kind, bad.n, ns);
    }
    double five[5] = {0.5, 0.5, 0.5, 0.5, 0.5};
    rg2_partition pf = {RG2_PART_ANGLES_FULL, 1, 5, five, 0.0};
    expect_err(rg2_partition_check(&pf, "u", &err), RG2_EINVAL, &err,
               "u partition: a full (data-arc) angle list is open only", "closed full angles");
    pf.closed = 0;
    pf.n = 4;
    expect_err(rg2_partition_check(&pf, "v", &err), RG2_EINVAL, &err,
               "v partition: 4 arcs given with data arcs; need at least 5", "too few full angles");
    pf.n = 5;
    CHECK_OK(rg2_partition_check(&pf, "v", &err), &err);
    CHECK(rg2_partition_num_segments(&pf) == 1, "5 full arcs: %d segments", rg2_partition_num_segments(&pf));
    /* two arcs just below pi: they sum to 2 pi within the tolerance, but a closed circle needs 3 */
    double two[2] = {nextafter(M_PI, 0.0), nextafter(M_PI, 0.0)};
    rg2_partition p2 = {RG2_PART_ANGLES, 1, 2, two, 0.0};
    expect_err(rg2_partition_check(&p2, "u", &err), RG2_EINVAL, &err,
               "u partition: a closed circle needs at least 3 arcs", "closed circle of 2 arcs");
    rg2_partition pe;
    expect_err(rg2_partition_equal(&pe, RG2_PART_KNOTS_FULL, 0, 0, 1, 3, eq, 7, &err), RG2_EINVAL, &err,
               "kind must be angles or knots", "equal partition of a full kind");
    expect_err(rg2_partition_equal(&pe, RG2_PART_KNOTS, 0, 0, 1, 0, eq, 7, &err), RG2_EINVAL, &err,
               "0 segments, need at least 1", "equal partition of 0 segments");
    expect_err(rg2_partition_equal(&pe, RG2_PART_KNOTS, 0, 0, INFINITY, 3, eq, 7, &err), RG2_ENONFINITE, &err,
               "range is not finite", "equal partition of an infinite range");

    /* placement on the z axis and against it: +z is the identity rotation, -z the half turn
     * about x (z -> -z, y -> -y), a zero or NaN axis keeps the orientation (rg2.h) */
    double P[16], c[3] = {1, 2, 3};
    const double axes[4][3] = {{0, 0, 2}, {0, 0, -0.5}, {0, 0, 0}, {NAN, 0, 1}};
    const double want_z[4] = {1, -1, 1, 1}, want_y[4] = {1, -1, 1, 1};
    for (int k = 0; k < 4; k++) {
        rg2_xform_place(P, c, axes[k]);
        double e = 0;
        for (int r = 0; r < 3; r++) {
            e = fmax(e, fabs(P[4 * r + 3] - c[r]));
            for (int q = 0; q < 3; q++) {
                double w = r != q ? 0.0 : r == 0 ? 1.0 : r == 1 ? want_y[k] : want_z[k];
                e = fmax(e, fabs(P[4 * r + q] - w));
            }
        }
        e = fmax(e, fabs(P[12]) + fabs(P[13]) + fabs(P[14]) + fabs(P[15] - 1.0));
        CHECK(e <= 1e-15, "xform_place axis (%g, %g, %g): off by %.3g", axes[k][0], axes[k][1], axes[k][2], e);
    }
    double Rz[16], Rn[16];
    rg2_xform_rotate(Rz, 0, 0, 0, 1.0);
    rg2_xform_rotate(Rn, NAN, 1, 0, 1.0);
    double I[16];
    rg2_xform_identity(I);
    CHECK(!memcmp(Rz, I, sizeof I) && !memcmp(Rn, I, sizeof I), "xform_rotate about a zero or NaN axis: the identity");
    printf("knot maps: cylinder heights %.2e, radius %.2e; partition checks and z-axis placements\n", wz, wr);
}

/* The weight report flags H_rs,4 <= 0: a cyclide with c close to a over 3 x 3 arcs has
 * some negative Bezier weights (the conic's far middle points times a - c cu cv), though the
 * surface itself stays exact. */
static void weight_warning(void)
{
    rg2_error err;
    rg2_shape sh;
    rg2_shape_init(&sh, RG2_SHAPE_CYCLIDE);
    sh.param[0] = 1.0, sh.param[1] = 0.8, sh.param[2] = 0.97;
    double e3[4], e4[5];
    rg2_partition p3, p4;
    CHECK_OK(rg2_partition_equal(&p3, RG2_PART_ANGLES, 1, 0.0, 0.0, 3, e3, 4, &err), &err);
    CHECK_OK(rg2_partition_equal(&p4, RG2_PART_ANGLES, 1, 0.0, 0.0, 4, e4, 5, &err), &err);
    rg2_surface s;
    rg2_weight_report rep;
    CHECK_OK(rg2_shape_surface(&sh, &p3, &p3, &s, &rep, &err), &err);
    printf("cyclide a = 1, c = 0.8 over 3 x 3 arcs: min weight %.3g, %d patches with H_rs,4 <= 0 "
           "(patch %d,%d)\n",
           rep.min_weight, rep.n_nonpositive, rep.patch_i, rep.patch_j);
    CHECK((rep.flags & RG2_SHAPE_WARN_WEIGHT) && rep.n_nonpositive > 0 && rep.min_weight <= 0.0,
          "non-positive weight flagged: flags %u, min %g", rep.flags, rep.min_weight);
    CHECK(rg2_surface_min_weight(&s) == rep.min_weight, "report min weight");
    stats st;
    stats_init(&st);
    measure_surface(&sh, &s, &p3, &p3, rg2t_surface_scale(&s), 12, &st);
    CHECK(st.resid <= 1e-13 && st.repro <= 1e-13, "the flagged cyclide is still exact: %.3g %.3g",
          st.resid, st.repro);
    rg2_surface_free(&s);
    CHECK_OK(rg2_shape_surface(&sh, &p4, &p4, &s, &rep, &err), &err);
    CHECK(rep.flags == 0 && rep.min_weight > 0.0, "4 x 4 arcs: positive weights not flagged: %u %g",
          rep.flags, rep.min_weight);
    rg2_surface_free(&s);
}

/* Every invalid parameter gets its code and a message naming the item. */
static void errors(void)
{
    rg2_error err;
    rg2_shape sh;
    rg2_mesh m;
    double eq[9], kn[4] = {0.2, 0.4, 0.6, 0.8};
    rg2_partition pu, pv = {RG2_PART_KNOTS, 0, 4, kn, 0}, pc;
    CHECK(rg2_partition_equal(&pu, RG2_PART_ANGLES, 1, 0.0, 0.0, INT_MAX, eq, 9, &err) == RG2_EINVAL &&
              strstr(err.msg, "2147483648 values"),
          "INT_MAX segments: %s", err.msg);
    rg2_partition_equal(&pu, RG2_PART_ANGLES, 1, 0.0, 0.0, 6, eq, 9, &err);
    rg2_partition_equal(&pc, RG2_PART_ANGLES, 1, 0.0, 0.0, 5, eq + 6 - 6, 9, &err);
    double e6[6] = {M_PI / 3, M_PI / 3, M_PI / 3, M_PI / 3, M_PI / 3, M_PI / 3};
    pu.values = e6, pc.values = e6, pc.n = 6;

    rg2_shape_init(&sh, RG2_SHAPE_TORUS);
    sh.param[0] = 1.0, sh.param[1] = 1.5;
    expect_err(rg2_shape_mesh(&sh, &pu, &pc, &m, &err), RG2_EDOMAIN, &err, "r = 1.5 must be < R = 1",
               "torus r >= R");
    sh.param[1] = -1;
    expect_err(rg2_shape_mesh(&sh, &pu, &pc, &m, &err), RG2_EDOMAIN, &err, "r = -1", "torus r < 0");
    sh.param[1] = NAN;
    expect_err(rg2_shape_mesh(&sh, &pu, &pc, &m, &err), RG2_ENONFINITE, &err, "parameter r", "torus NaN");
    rg2_shape_init(&sh, RG2_SHAPE_TORUS);
    expect_err(rg2_shape_mesh(&sh, &pu, &pv, &m, &err), RG2_EINVAL, &err, "v is a circle direction",
               "knots for a circle direction");
    rg2_shape_init(&sh, RG2_SHAPE_CYCLIDE);
    sh.param[1] = 3.0;
    expect_err(rg2_shape_mesh(&sh, &pu, &pc, &m, &err), RG2_EDOMAIN, &err, "b^2 = a^2 - c^2 = -5",
               "cyclide b^2 <= 0");
    rg2_shape_init(&sh, RG2_SHAPE_CYCLIDE);
    sh.param[2] = 0;
    expect_err(rg2_shape_mesh(&sh, &pu, &pc, &m, &err), RG2_EDOMAIN, &err, "mu = 0", "cyclide mu");
    rg2_shape_init(&sh, RG2_SHAPE_SPHERE);
    sh.param[0] = 0;
    expect_err(rg2_shape_mesh(&sh, &pu, &pv, &m, &err), RG2_EDOMAIN, &err, "radius = 0", "sphere radius");
    rg2_shape_init(&sh, RG2_SHAPE_CONE);
    sh.param[0] = 0;
    expect_err(rg2_shape_mesh(&sh, &pu, &pv, &m, &err), RG2_EDOMAIN, &err, "k = 0", "cone slope");
    rg2_shape_init(&sh, RG2_SHAPE_ELLIPSOID);
    sh.param[2] = -2;
    expect_err(rg2_shape_mesh(&sh, &pu, &pv, &m, &err), RG2_EDOMAIN, &err, "c = -2", "ellipsoid axis");

    /* partitions */
    rg2_shape_init(&sh, RG2_SHAPE_CYLINDER);
    rg2_partition bad = pu;
    bad.n = 0;
    expect_err(rg2_shape_mesh(&sh, &bad, &pv, &m, &err), RG2_EINVAL, &err, "u partition is empty",
               "empty u partition");
    bad.n = -3;
    expect_err(rg2_shape_mesh(&sh, &bad, &pv, &m, &err), RG2_EINVAL, &err, "u partition is empty (n = -3",
               "negative u partition count");
    /* values NULL with a count: say so, not "empty (no knots given)" */
    bad = pv;
    bad.values = NULL;
    expect_err(rg2_shape_mesh(&sh, &pu, &bad, &m, &err), RG2_EINVAL, &err,
               "v partition: values is NULL (n = 4 knots)", "v partition without values");
    expect_err(rg2_partition_check(NULL, "u", &err), RG2_EINVAL, &err, "u partition is NULL", "NULL partition");
    double a5[5] = {1.0, 1.0, 1.0, 1.0, 1.0};
    bad = pu, bad.values = a5, bad.n = 5;
    expect_err(rg2_shape_mesh(&sh, &bad, &pv, &m, &err), RG2_EDOMAIN, &err, "must sum to 2 pi",
               "closed arcs not summing to 2 pi");
    double a3[3] = {2.0, M_PI, 2 * M_PI - 2.0 - M_PI};
    bad = pu, bad.values = a3, bad.n = 3;
    expect_err(rg2_shape_mesh(&sh, &bad, &pv, &m, &err), RG2_EDOMAIN, &err, "arc 1 has opening angle",
               "arc of pi");
    a3[1] = -0.5;
    expect_err(rg2_shape_mesh(&sh, &bad, &pv, &m, &err), RG2_EDOMAIN, &err, "(0, pi)", "negative arc");
    double a8[8] = {3, 3, 3, 3, 3, 3, 3, 3};
    bad = pu, bad.values = a8, bad.n = 8, bad.closed = 0;
    expect_err(rg2_shape_mesh(&sh, &bad, &pv, &m, &err), RG2_EDOMAIN, &err, "past 2 pi",
               "open arcs past 2 pi");
    double k4[4] = {0.0, 0.5, 0.5, 1.0};
    bad = pv, bad.values = k4;
    expect_err(rg2_shape_mesh(&sh, &pu, &bad, &m, &err), RG2_EDOMAIN, &err, "knot 2 (= 0.5) is not greater",
               "repeated knot");
    k4[2] = 0.3;
    expect_err(rg2_shape_mesh(&sh, &pu, &bad, &m, &err), RG2_EDOMAIN, &err, "knot 2", "decreasing knot");
    bad = pv, bad.closed = 1;
    expect_err(rg2_shape_mesh(&sh, &pu, &bad, &m, &err), RG2_EINVAL, &err, "open", "closed knots");
    bad = pv, bad.n = 1;
    expect_err(rg2_shape_mesh(&sh, &pu, &bad, &m, &err), RG2_EINVAL, &err, "at least 2", "one knot");
    double kinf[2] = {0.0, INFINITY};
    bad = pv, bad.values = kinf, bad.n = 2;
    expect_err(rg2_shape_mesh(&sh, &pu, &bad, &m, &err), RG2_ENONFINITE, &err, "value 1", "inf knot");
    /* knot intervals 1e-300 and 1 give K = inf (RG2_EWEIGHT from the scalars' check until the
     * scalars refused it, RG2_EDOMAIN naming the expanded layout's "knots[2..3]" and junction 2):
     * named by the partition's values */
    rg2_shape_init(&sh, RG2_SHAPE_CYLINDER);
    double kw[4] = {0.0, 1e-300, 1.0, 2.0};
    bad = pv, bad.values = kw, bad.n = 4;
    expect_err(rg2_shape_mesh(&sh, &pu, &bad, &m, &err), RG2_EDOMAIN, &err,
               "cylinder: v: knots: the knot intervals values[0..1] = [0, 1e-300] and values[1..2] = [1e-300, 1] "
               "give b = 1e+300, g = 0, K = inf: K is out of the double range",
               "knot intervals 1e-300 and 1");
    /* at the mirrored end of the values: named as mirrored (it named values[4..5], which the
     * caller never gave), as is a mirrored interval of zero length (it was "interval 5") */
    double kw2[4] = {-2.0, -1.0, 0.0, 1e-300};
    bad = pv, bad.values = kw2, bad.n = 4;
    expect_err(rg2_shape_mesh(&sh, &pu, &bad, &m, &err), RG2_EDOMAIN, &err,
               "the knot intervals the first mirrored after values[3] = [1e-300, 2e-300] and the second mirrored "
               "after values[3] = [2e-300, 1] give",
               "knot intervals 1 and 1e-300 at the end");
    /* the last interval the caller gave is named as given, next to the mirrored ones: 5e-324 after
     * 2 is a ratio b below the double range, at the junction of values[2..3] and values[3..4] */
    double kw4[5] = {-6.0, -4.0, -2.0, 0.0, 0x1p-1074};
    bad = pv, bad.values = kw4, bad.n = 5;
    expect_err(rg2_shape_mesh(&sh, &pu, &bad, &m, &err), RG2_EDOMAIN, &err,
               "the knot intervals values[2..3] = [-2, 0] and values[3..4] = [0, 5e-324] give b = 0, g = 0, K = 0: "
               "b is out of the double range",
               "knot intervals 2 and 5e-324 at the end");
    double kw3[3] = {0.0, 1e-300, 1.0};
    bad = pv, bad.values = kw3, bad.n = 3;
    expect_err(rg2_shape_mesh(&sh, &pu, &bad, &m, &err), RG2_EDOMAIN, &err,
               "interval the second mirrored after values[2] [2, 2] has zero or negative length",
               "mirrored end of zero length");

    /* shape-specific ranges */
    rg2_shape_init(&sh, RG2_SHAPE_HYPERBOLOID1);
    double kneg[3] = {-0.5, 0.5, 1.0};
    bad = pv, bad.values = kneg, bad.n = 3;
    expect_err(rg2_shape_mesh(&sh, &pu, &bad, &m, &err), RG2_EDOMAIN, &err, "v knot 0 = -0.5 must be > 0",
               "hyperboloid1 v <= 0");
    double kzero[3] = {0.0, 0.5, 1.0}; /* v = 0 itself: the weight's zero, not a knot next to it */
    bad.values = kzero;
    expect_err(rg2_shape_mesh(&sh, &pu, &bad, &m, &err), RG2_EDOMAIN, &err, "v knot 0 = 0 must be > 0",
               "hyperboloid1 v = 0");
    rg2_shape_init(&sh, RG2_SHAPE_HYPERBOLOID2);
    double kbig[3] = {0.0, 0.5, 1.0};
    bad = pv, bad.values = kbig, bad.n = 3;
    expect_err(rg2_shape_mesh(&sh, &pu, &bad, &m, &err), RG2_EDOMAIN, &err, "v knot 2 = 1 must satisfy |v| < 1",
               "hyperboloid2 |v| >= 1");
    /* sphere and ellipsoid bands: knots in (0, 1), the poles outside (the full knots of a
     * polar configuration reach them on purpose: the knots_full test above) */
    rg2_shape_init(&sh, RG2_SHAPE_SPHERE);
    expect_err(rg2_shape_mesh(&sh, &pu, &bad, &m, &err), RG2_EDOMAIN, &err, "sphere: v knot 0 = 0 must lie in (0, 1)",
               "sphere knot at the south pole");
    double kpast[3] = {0.2, 0.5, 1.5};
    bad.values = kpast;
    rg2_shape_init(&sh, RG2_SHAPE_ELLIPSOID);
    expect_err(rg2_shape_mesh(&sh, &pu, &bad, &m, &err), RG2_EDOMAIN, &err,
               "ellipsoid: v knot 2 = 1.5 must lie in (0, 1)", "ellipsoid knot past the north pole");
    double kin[3] = {0.01, 0.5, 0.99};
    bad.values = kin;
    CHECK_OK(rg2_shape_mesh(&sh, &pu, &bad, &m, &err), &err);
    rg2_mesh_free(&m);

    /* placement, names, families */
    rg2_shape_init(&sh, RG2_SHAPE_CYLINDER);
    sh.xform[10] = 0.0;
    expect_err(rg2_shape_mesh(&sh, &pu, &pv, &m, &err), RG2_EDOMAIN, &err, "singular", "singular xform");
    sh.xform[10] = NAN;
    expect_err(rg2_shape_mesh(&sh, &pu, &pv, &m, &err), RG2_ENONFINITE, &err, "[2][2]", "NaN xform");
    /* a projective placement must keep the weights positive: last row (1, 0, 0, 1) takes the
     * torus's weights through 0 (x from -4 to 4), (0, 0, 0, -1) flips them all */
    rg2_shape_init(&sh, RG2_SHAPE_TORUS);
    sh.xform[12] = 1.0;
    expect_err(rg2_shape_mesh(&sh, &pu, &pc, &m, &err), RG2_EWEIGHT, &err,
               "torus: the placement gives control point [2, 0] the weight W = -1.55064", "weights through 0");
    CHECK(m.p == NULL, "no mesh left after a refused placement");
    rg2_shape_init(&sh, RG2_SHAPE_TORUS);
    sh.xform[15] = -1.0;
    expect_err(rg2_shape_mesh(&sh, &pu, &pc, &m, &err), RG2_EWEIGHT, &err,
               "control point [0, 0] the weight W = -1", "weights flipped");
    /* a last row (0, 0, c, 1) alone, c = 0.01, 0.1, 1: on a cylinder from z = -250 to 0 the weight
     * 1 + c z passes through 0 (the test of x rows above does not see a z row) */
    double kz[2] = {-250.0, 0.0};
    rg2_partition pz = {RG2_PART_KNOTS, 0, 2, kz, 0.0};
    static const double crow[3] = {0.01, 0.1, 1.0};
    for (int k = 0; k < 3; k++) {
        rg2_shape_init(&sh, RG2_SHAPE_CYLINDER);
        sh.xform[14] = crow[k];
        expect_err(rg2_shape_mesh(&sh, &pu, &pz, &m, &err), RG2_EWEIGHT, &err, "the placement gives control point",
                   "a z row through 0");
    }
    rg2_shape_init(&sh, RG2_SHAPE_TORUS);
    sh.xform[15] = 1.0, sh.xform[12] = 0.1; /* |0.1 x| < 1: still positive */
    CHECK_OK(rg2_shape_mesh(&sh, &pu, &pc, &m, &err), &err);
    int wi = -1, wj = -1;
    CHECK_OK(rg2_mesh_check_weights(&m, &wi, &wj, &err), &err);
    rg2_mesh_at(&m, 2, 1)[3] = 0.0;
    expect_err(rg2_mesh_check_weights(&m, &wi, &wj, &err), RG2_EWEIGHT, &err,
               "control point [2, 1] has weight W = 0, must be > 0", "mesh weight check");
    CHECK(wi == 2 && wj == 1, "mesh weight check names [2, 1]: [%d, %d]", wi, wj);
    rg2_mesh_free(&m);
    /* the numeric range of design numbers, shared with rg2 shape */
    CHECK_OK(rg2_number_check(0.0, "x", &err), &err);
    CHECK_OK(rg2_number_check(-3.5e50, "x", &err), &err);
    expect_err(rg2_number_check(1e200, "--R", &err), RG2_EDOMAIN, &err,
               "--R: number 1e+200 is outside the supported range", "number too big");
    expect_err(rg2_number_check(-1e-200, "--scale", &err), RG2_EDOMAIN, &err,
               "--scale: number -1e-200 is outside", "number too small");
    expect_err(rg2_number_check(NAN, "y", &err), RG2_ENONFINITE, &err, "y: number is not finite", "NaN number");
    rg2_shape_kind kind;
    expect_err(rg2_shape_from_name("doughnut", &kind, &err), RG2_EINVAL, &err, "unknown shape 'doughnut'",
               "unknown name");
    CHECK(rg2_shape_from_name("cyclide", &kind, &err) == RG2_OK && kind == RG2_SHAPE_CYCLIDE, "name lookup");
    /* a NULL name is named as such (it went to the unknown-name message as "unknown shape '(null)'") */
    CHECK(rg2_shape_from_name(NULL, &kind, &err) == RG2_EINVAL && !strcmp(err.msg, "shape: no name (NULL name)"),
          "NULL name: %s", err.msg);
    CHECK(rg2_shape_from_name("torus", NULL, &err) == RG2_EINVAL && !strcmp(err.msg, "shape: NULL output kind"),
          "NULL kind: %s", err.msg);
    CHECK(rg2_shape_name((rg2_shape_kind)RG2_SHAPE_COUNT) == NULL && rg2_shape_describe((rg2_shape_kind)-1) == NULL,
          "unknown kinds have no name");
    double a1[4][9] = {{0}};
    expect_err(rg2_family1_mesh((const double(*)[9])a1, &pu, &pv, &m, &err), RG2_EINVAL, &err,
               "v is a circle direction", "family 1 with knots");
    double A[4][4][4] = {{{0}}};
    A[3][0][0] = 1, A[0][3][0] = 1;
    expect_err(rg2_product_mesh((const double(*)[4][4])A, &pu, &pv, &m, &err), RG2_EINVAL, &err,
               "coefficient [0][3][0]", "cubic coefficient on a circle direction");
    A[0][3][0] = NAN;
    expect_err(rg2_product_mesh((const double(*)[4][4])A, &pv, &pv, &m, &err), RG2_ENONFINITE, &err,
               "coefficient [0][3][0]", "NaN coefficient");
    rg2_partition pe;
    double buf[3];
    expect_err(rg2_partition_equal(&pe, RG2_PART_ANGLES, 1, 0, 0, 5, buf, 3, &err), RG2_EINVAL, &err,
               "5 segments need 6 values, room for 3 (cap)", "equal partition capacity");
    expect_err(rg2_partition_equal(&pe, RG2_PART_ANGLES, 1, 0, 0, 2, buf, 3, &err), RG2_EDOMAIN, &err,
               "(0, pi)", "2 closed arcs of pi");
}

/* Small shapes: every named shape with its size parameters at 1e-3 of the defaults (the cone's
 * slope kept) builds over its default partitions and lies on its implicit surface, along its own
 * parameterization, to rounding (a parameter in (0, 0.01] was refused by a mis-set positivity
 * bound and no test noticed). Each size parameter set negative in turn is refused, naming it. */
/* The text of a number in a message: the fewest significant digits that read back as the
 * number, but never fewer than its integer digits below 1e17 (90 reads "90", not "9e+01");
 * found here by trying %.*g from that many digits up. */
static void number_text(double x, char *buf, size_t cap)
{
    int p = 1;
    if (fabs(x) >= 1.0 && fabs(x) < 1e17) {
        char ip[32];
        p = snprintf(ip, sizeof ip, "%.0f", floor(fabs(x)));
    }
    for (; p <= 17; p++) {
        snprintf(buf, cap, "%.*g", p, x);
        if (strtod(buf, NULL) == x)
            return;
    }
}

/* A negative first parameter is named with its value as number_text writes it: integers below
 * 1e17 in all their digits (90, 2e16), 1e17, fractions and a subnormal in the fewest digits that
 * read back. */
static void parameter_number_text(const rg2_shape_desc *d, rg2_shape_kind kind, const rg2_partition p[2])
{
    static const double vals[] = {-90.0, -123456789.0, -2e16, -1e17, -0.1, -1.0 / 3.0, -3e-16, -5e-324};
    for (size_t k = 0; k < sizeof vals / sizeof vals[0]; k++) {
        rg2_shape sh;
        rg2_shape_init(&sh, kind);
        sh.param[0] = vals[k];
        char num[40], want[128];
        number_text(vals[k], num, sizeof num);
        snprintf(want, sizeof want, "%s: parameter %s = %s must be > 0", d->name, d->param_names[0], num);
        rg2_error err;
        rg2_mesh m;
        expect_err(rg2_shape_mesh(&sh, &p[0], &p[1], &m, &err), RG2_EDOMAIN, &err, want, "the value's digits");
    }
}

static void parameter_ranges(void)
{
    rg2_error err;
    double worst = 0.0, wrep = 0.0;
    for (int kind = 0; kind < RG2_SHAPE_COUNT; kind++) {
        const rg2_shape_desc *d = rg2_shape_describe((rg2_shape_kind)kind);
        rg2_shape sh;
        rg2_shape_init(&sh, (rg2_shape_kind)kind);
        if (kind != RG2_SHAPE_CONE)
            for (int k = 0; k < d->n_params; k++)
                sh.param[k] *= 1e-3;
        double vals[2][MAXSEG + 1];
        rg2_partition p[2];
        for (int dir = 0; dir < 2; dir++)
            CHECK_OK(rg2_partition_equal(&p[dir], d->dir_kind[dir], d->default_closed[dir], d->default_range[dir][0],
                                         d->default_range[dir][1], d->default_segments[dir], vals[dir], MAXSEG + 1,
                                         &err),
                     &err);
        rg2_surface s;
        rg2_status st = rg2_shape_surface(&sh, &p[0], &p[1], &s, NULL, &err);
        CHECK(st == RG2_OK, "%s with parameters 1e-3 of the defaults: %s", d->name, err.msg);
        if (st == RG2_OK) {
            stats one;
            stats_init(&one);
            measure_surface(&sh, &s, &p[0], &p[1], rg2t_surface_scale(&s), 4, &one);
            worst = fmax(worst, one.resid);
            wrep = fmax(wrep, one.repro);
            rg2_surface_free(&s);
        }
        /* a negative size parameter (not the cone's slope, which may be negative) */
        for (int k = 0; k < d->n_params && kind != RG2_SHAPE_CONE; k++) {
            rg2_shape_init(&sh, (rg2_shape_kind)kind);
            sh.param[k] = -sh.param[k];
            char want[96];
            snprintf(want, sizeof want, "%s: parameter %s = %g must be", d->name, d->param_names[k], sh.param[k]);
            rg2_mesh m;
            expect_err(rg2_shape_mesh(&sh, &p[0], &p[1], &m, &err), RG2_EDOMAIN, &err, want, d->name);
        }
        if (kind == RG2_SHAPE_SPHERE)
            parameter_number_text(d, (rg2_shape_kind)kind, p);
    }
    printf("shapes at 1e-3 of the default parameters: residual %.2e, reproduction %.2e\n", worst, wrep);
    CHECK(worst <= 1e-13 && wrep <= 1e-13, "small shapes: residual %.3g, reproduction %.3g", worst, wrep);
}

/* rg2_partition_equal over knots: n + 1 increasing knots from lo to hi in equal steps (each step
 * (hi - lo) / n to rounding), and a cylinder over them reaches every knot's height. */
static void equal_knots(void)
{
    rg2_error err;
    rg2_partition pk, pu;
    double kv[8], eq[7];
    CHECK_OK(rg2_partition_equal(&pk, RG2_PART_KNOTS, 0, -1.0, 2.5, 7, kv, 8, &err), &err);
    double wstep = 0.0;
    for (int k = 1; k <= 7; k++)
        wstep = fmax(wstep, fabs((kv[k] - kv[k - 1]) - 0.5));
    CHECK(pk.n == 8 && kv[0] == -1.0 && kv[7] == 2.5 && wstep <= 1e-15,
          "equal knots on [-1, 2.5]: %d values from %g to %g, steps off 0.5 by %.3g", pk.n, kv[0], kv[7], wstep);
    rg2_shape sh;
    rg2_shape_init(&sh, RG2_SHAPE_CYLINDER);
    CHECK_OK(rg2_partition_equal(&pu, RG2_PART_ANGLES, 1, 0.0, 0.0, 6, eq, 7, &err), &err);
    rg2_surface s;
    rg2_status st = rg2_shape_surface(&sh, &pu, &pk, &s, NULL, &err);
    CHECK(st == RG2_OK && s.nv == 7, "cylinder over 7 equal knot intervals: %s", err.msg);
    if (st == RG2_OK) {
        double wz = 0.0;
        for (int j = 0; j < s.nv; j++) {
            rg2_eval e0, e1;
            rg2_patch_eval(rg2_surface_patch(&s, 0, j), 0.5, 0.0, 0, &e0);
            rg2_patch_eval(rg2_surface_patch(&s, 0, j), 0.5, 1.0, 0, &e1);
            wz = fmax(wz, fmax(fabs(e0.p[2] - (-1.0 + 0.5 * j)), fabs(e1.p[2] - (-1.0 + 0.5 * (j + 1)))));
        }
        CHECK(wz <= 1e-14, "cylinder over equal knots: heights off the knots by %.3g", wz);
        rg2_surface_free(&s);
    }
}

/* An arc below the smallest supported one is refused naming its angle, and the smallest, in
 * radians and degrees: each degree figure is its radian figure times 180 / pi. */
static void small_arc_message(void)
{
    rg2_error err;
    double arcs[4] = {1e-3, M_PI / 2, M_PI / 2, M_PI - 1e-3};
    rg2_partition p = {RG2_PART_ANGLES, 1, 4, arcs, 0.0};
    rg2_status st = rg2_partition_check(&p, "u", &err);
    double a = 0, ad = 0, m = 0, md = 0;
    const char *at = strstr(err.msg, "opening angle "), *mt = strstr(err.msg, "smallest supported arc of ");
    int got = st == RG2_EDOMAIN && at && mt && sscanf(at, "opening angle %lf rad (%lf deg)", &a, &ad) == 2 &&
              sscanf(mt, "smallest supported arc of %lf rad (%lf deg)", &m, &md) == 2;
    CHECK(got && strstr(err.msg, "arc 0 ") && a == 1e-3 && m > a && fabs(ad - a * 180.0 / M_PI) <= 1e-5 * ad &&
              fabs(md - m * 180.0 / M_PI) <= 1e-5 * md,
          "arc below the smallest: %s %s", rg2_status_str(st), err.msg);
    /* with data arcs the produced arcs count from values[1]: values[2] is arc 1 */
    double full[5] = {0.4, 0.4, 1e-3, 0.5, 0.5};
    rg2_partition pf = {RG2_PART_ANGLES_FULL, 0, 5, full, 0.0};
    expect_err(rg2_partition_check(&pf, "v", &err), RG2_EDOMAIN, &err, "v partition: arc 1 has opening angle 0.001 rad",
               "data-arc layout: small arc named by its produced index");
}

/* rg2_angle_total_in_radians: 2 pi, pi, pi / 2, pi / 4, pi / 3, pi / 6, 3 pi / 2 and 2 pi / 3 degrees each to 1e-3 relative (just inside
 * is named, just outside not), nothing else (360, 90, 0, NaN, infinity, a negative turn). */
static void radian_totals(void)
{
    static const char *const names[8] = {"2 pi (a full circle in radians)", "pi (a half circle in radians)",
                                         "pi / 2 (a quarter circle in radians)", "pi / 4 (45 degrees in radians)",
                                         "pi / 3 (60 degrees in radians)", "pi / 6 (30 degrees in radians)",
                                         "3 pi / 2 (270 degrees in radians)", "2 pi / 3 (120 degrees in radians)"};
    static const double turns[8] = {2.0 * M_PI, M_PI, M_PI / 2, M_PI / 4, M_PI / 3, M_PI / 6, 1.5 * M_PI,
                                    2.0 * M_PI / 3};
    for (int k = 0; k < 8; k++) {
        double t = turns[k];
        for (int side = -1; side <= 1; side += 2) {
            const char *in = rg2_angle_total_in_radians(t * (1 + side * 0.999e-3));
            const char *out = rg2_angle_total_in_radians(t * (1 + side * 1.001e-3));
            CHECK(in && !strcmp(in, names[k]) && !out, "%s: %s inside 1e-3, %s outside", names[k],
                  in ? in : "NULL", out ? out : "NULL");
        }
    }
    const double other[] = {360.0, 180.0, 90.0, 0.0, -2.0 * M_PI, 4.0 * M_PI, NAN, INFINITY};
    for (size_t k = 0; k < sizeof other / sizeof other[0]; k++)
        CHECK(!rg2_angle_total_in_radians(other[k]), "%g degrees is not named", other[k]);
}

/* The smallest data-knot layout, 6 values (v_-1, v_0, v_1, v_2 and two data knots): one
 * produced interval [values[2], values[3]]; a cylinder over it spans exactly those heights. */
static void smallest_full_knots(void)
{
    rg2_error err;
    double kn[6] = {-1.0, 0.0, 1.0, 2.5, 3.0, 4.0}, eq[7];
    rg2_partition pk = {RG2_PART_KNOTS_FULL, 0, 6, kn, 0}, pu;
    CHECK_OK(rg2_partition_check(&pk, "v", &err), &err);
    CHECK(rg2_partition_num_segments(&pk) == 1, "6 full knots: %d segments", rg2_partition_num_segments(&pk));
    rg2_shape sh;
    rg2_shape_init(&sh, RG2_SHAPE_CYLINDER);
    CHECK_OK(rg2_partition_equal(&pu, RG2_PART_ANGLES, 1, 0.0, 0.0, 6, eq, 7, &err), &err);
    rg2_surface s;
    rg2_status st = rg2_shape_surface(&sh, &pu, &pk, &s, NULL, &err);
    CHECK(st == RG2_OK && s.nv == 1, "cylinder over 6 full knots: %s", err.msg);
    if (st == RG2_OK) {
        rg2_eval e0, e1;
        rg2_patch_eval(rg2_surface_patch(&s, 2, 0), 0.3, 0.0, 0, &e0);
        rg2_patch_eval(rg2_surface_patch(&s, 2, 0), 0.3, 1.0, 0, &e1);
        CHECK(fabs(e0.p[2] - 1.0) <= 2e-15 && fabs(e1.p[2] - 2.5) <= 2e-15, "heights %.17g, %.17g for knots 1, 2.5",
              e0.p[2], e1.p[2]);
        rg2_surface_free(&s);
    }
    pk.n = 5;
    expect_err(rg2_partition_check(&pk, "v", &err), RG2_EINVAL, &err, "5 knots given, need at least 6", "5 full knots");
}

/* An unknown shape name lists the known ones: every name once, joined by ", ", nothing after the last. */
static void unknown_name_list(void)
{
    rg2_error err;
    rg2_shape_kind kind;
    char want[512] = "(known: ";
    for (int k = 0; k < RG2_SHAPE_COUNT; k++) {
        strcat(want, rg2_shape_name((rg2_shape_kind)k));
        strcat(want, k + 1 == RG2_SHAPE_COUNT ? ")" : ", ");
    }
    expect_err(rg2_shape_from_name("doughnut", &kind, &err), RG2_EINVAL, &err, want, "the list of known shapes");
}

/* docs/shapes.md's text (NULL, and a failed check, when it cannot be read). */
static char *shapes_doc(void)
{
    rg2_error err;
    char *md = NULL;
    CHECK_OK(rg2_read_text("docs/shapes.md", &md, NULL, &err), &err);
    return md;
}

/* The text after "| `name` | " of the first table row of shape d from `from` on (NULL, and a
 * failed check naming the table, when there is none). */
static const char *shape_row(const char *from, const rg2_shape_desc *d, const char *table)
{
    char key[64];
    snprintf(key, sizeof key, "\n| `%s` | ", d->name);
    const char *row = from ? strstr(from, key) : NULL;
    CHECK(row != NULL, "docs/shapes.md has no %s row for %s", table, d->name);
    return row ? row + strlen(key) : NULL;
}

/* The defaults of rg2_shape_describe are the ones docs/shapes.md gives: the table row of each
 * shape lists "name = value" in the parameters' order (no geometric property sees a wrong
 * default: a shape of other size is exact too). */
static void documented_defaults(void)
{
    char *md = shapes_doc();
    if (!md)
        return;
    int rows = 0;
    for (int kind = 0; kind < RG2_SHAPE_COUNT; kind++) {
        const rg2_shape_desc *d = rg2_shape_describe((rg2_shape_kind)kind);
        const char *row = shape_row(md, d, "shape table");
        if (!row)
            continue;
        const char *end = strstr(row, " | "), *at = row;
        int k = 0, same = 1;
        for (; end && k < d->n_params; k++) { /* the k-th "= number" of the row's parameter cell */
            const char *eq = strstr(at, "= ");
            char *stop = NULL;
            double v = eq && eq < end ? strtod(eq + 2, &stop) : NAN;
            if (!eq || eq >= end || stop == eq + 2)
                break;
            same &= v == d->param_defaults[k];
            CHECK(v == d->param_defaults[k], "%s: docs/shapes.md gives %s = %g, rg2_shape_describe %g", d->name,
                  d->param_names[k], v, d->param_defaults[k]);
            at = stop;
        }
        CHECK(k == d->n_params, "%s: docs/shapes.md gives %d of its %d parameter defaults", d->name, k, d->n_params);
        rows += k == d->n_params && same;
    }
    printf("shape defaults: %d of %d table rows of docs/shapes.md agree with rg2_shape_describe\n", rows,
           (int)RG2_SHAPE_COUNT);
    free(md);
}

/* One cell of docs/shapes.md's "Default partitions" table against the description of direction
 * dir: "N arcs, full circle" (a closed angle partition of [0, 2 pi]) or "N knot intervals of
 * [A, B]". Returns whether they agree. */
static int partition_cell_agrees(const rg2_shape_desc *d, int dir, const char *cell)
{
    int n = 0, used = 0;
    double lo = NAN, hi = NAN;
    if (sscanf(cell, "%d arcs, full circle%n", &n, &used) == 1 && used > 0)
        return d->dir_kind[dir] == RG2_PART_ANGLES && d->default_closed[dir] && n == d->default_segments[dir] &&
               d->default_range[dir][0] == 0 && d->default_range[dir][1] == 2 * M_PI;
    if (sscanf(cell, "%d knot intervals of [%lf, %lf]", &n, &lo, &hi) == 3)
        return d->dir_kind[dir] == RG2_PART_KNOTS && !d->default_closed[dir] && n == d->default_segments[dir] &&
               lo == d->default_range[dir][0] && hi == d->default_range[dir][1];
    return 0;
}

/* The default partitions of rg2_shape_describe (used by rg2 shape and by design meshes without
 * u / v) are the ones docs/shapes.md gives in "Default partitions" (a wrong default count or
 * range builds an exact shape too: no geometric property sees it). */
static void documented_partitions(void)
{
    char *md = shapes_doc();
    if (!md)
        return;
    const char *table = strstr(md, "**Default partitions**");
    int rows = 0;
    for (int kind = 0; kind < RG2_SHAPE_COUNT; kind++) {
        const rg2_shape_desc *d = rg2_shape_describe((rg2_shape_kind)kind);
        const char *u = shape_row(table, d, "Default partitions"), *v = u ? strstr(u, " | ") : NULL;
        if (!u)
            continue;
        int same = v && partition_cell_agrees(d, 0, u) && partition_cell_agrees(d, 1, v + 3);
        CHECK(same, "%s: docs/shapes.md's default partition (%.60s) differs from rg2_shape_describe: u %d %s [%g, %g], "
                    "v %d %s [%g, %g]", d->name, u, d->default_segments[0], d->default_closed[0] ? "closed" : "open",
              d->default_range[0][0], d->default_range[0][1], d->default_segments[1],
              d->default_closed[1] ? "closed" : "open", d->default_range[1][0], d->default_range[1][1]);
        rows += same;
    }
    printf("default partitions: %d of %d rows of docs/shapes.md agree with rg2_shape_describe\n", rows,
           (int)RG2_SHAPE_COUNT);
    free(md);
}

/* docs/shapes.md, "Where a knot puts the ring": the radius and height of the ring at knot v, and
 * the knot back from the height, of every shape whose u is a circle about z, from the table's
 * formulas, against rg2_shape_param. */
static void ring_heights(void)
{
    static const rg2_shape_kind kinds[] = {RG2_SHAPE_CYLINDER, RG2_SHAPE_CONE, RG2_SHAPE_SPHERE,
                                           RG2_SHAPE_ELLIPSOID, RG2_SHAPE_PARABOLOID, RG2_SHAPE_HYPERBOLOID1,
                                           RG2_SHAPE_HYPERBOLOID2, RG2_SHAPE_HYPERBOLOID1_RULED};
    double worst = 0.0;
    for (size_t k = 0; k < sizeof kinds / sizeof kinds[0]; k++) {
        rg2_shape s;
        rg2_shape_init(&s, kinds[k]);
        for (int i = 0; i < 3; i++) /* parameters other than the defaults */
            s.param[i] = 0.7 + 0.45 * i;
        if (kinds[k] == RG2_SHAPE_CONE)
            s.param[0] = -1.3;
        const double *q = s.param;
        for (int t = 1; t <= 7; t++) {
            double v = t / 8.0, r = 0.0, z = 0.0, vz = 0.0, u = 0.3, h[4];
            if (kinds[k] == RG2_SHAPE_HYPERBOLOID1)
                v = 0.4 * t;
            if (kinds[k] == RG2_SHAPE_HYPERBOLOID1_RULED)
                v = 0.5 * t - 2.0;
            rg2_shape_param(&s, u, v, h);
            double x = h[0] / h[3], y = h[1] / h[3], zz = h[2] / h[3];
            switch (kinds[k]) {
            case RG2_SHAPE_CYLINDER: r = q[0], z = v, vz = zz; break;
            case RG2_SHAPE_CONE: r = fabs(v), z = q[0] * v, vz = zz / q[0]; break;
            case RG2_SHAPE_SPHERE:
            case RG2_SHAPE_ELLIPSOID: {
                double c = kinds[k] == RG2_SHAPE_SPHERE ? q[0] : q[2], phi = 2.0 * atan(2.0 * v - 1.0);
                r = kinds[k] == RG2_SHAPE_SPHERE ? q[0] * cos(phi) : 0.0;
                z = c * sin(phi);
                vz = (1.0 + tan(0.5 * asin(zz / c))) / 2.0;
                if (kinds[k] == RG2_SHAPE_ELLIPSOID) /* radii a, b in x, y */
                    worst = fmax(worst, fabs(hypot(x / q[0], y / q[1]) - cos(phi)));
                break;
            }
            case RG2_SHAPE_PARABOLOID:
                z = v * v, vz = sqrt(zz);
                worst = fmax(worst, fabs(hypot(x / q[0], y / q[1]) - v));
                break;
            case RG2_SHAPE_HYPERBOLOID1:
                r = q[0] * (1.0 + v * v) / (2.0 * v), z = q[1] * (1.0 - v * v) / (2.0 * v);
                vz = sqrt(1.0 + (zz / q[1]) * (zz / q[1])) - zz / q[1];
                break;
            case RG2_SHAPE_HYPERBOLOID2:
                r = 2.0 * q[0] * v / (1.0 - v * v), z = q[1] * (1.0 + v * v) / (1.0 - v * v);
                vz = sqrt((zz - q[1]) / (zz + q[1]));
                break;
            default: /* ruled: the ring turned by atan v */
                r = q[0] * sqrt(1.0 + v * v), z = q[1] * v, vz = zz / q[1];
                worst = fmax(worst, fabs(atan2(y, x) - (u + atan(v))));
                break;
            }
            if (r > 0.0)
                worst = fmax(worst, fabs(hypot(x, y) - r) / r);
            worst = fmax(worst, fabs(zz - z) / fmax(1.0, fabs(z)));
            worst = fmax(worst, fabs(vz - v) / fmax(1.0, fabs(v)));
        }
    }
    printf("ring heights (docs/shapes.md table): radius, height and knot from height within %.2e\n", worst);
    CHECK(worst <= 1e-14, "ring radius / height / knot formulas of docs/shapes.md: %.3g off", worst);
}

/* docs/shapes.md, cyclide notes: the tube circles at u = 0, 90, 180, 270 degrees (plane, centre,
 * radius, where v = 0 lies and which way v and u run), from the table, against rg2_shape_param
 * at 12 points of each circle. */
static void cyclide_circles(void)
{
    rg2_shape s;
    rg2_shape_init(&s, RG2_SHAPE_CYCLIDE);
    s.param[0] = 2.3, s.param[1] = 0.9, s.param[2] = 1.4; /* a, c, mu: a ring cyclide */
    double a = s.param[0], c = s.param[1], mu = s.param[2], b = sqrt(a * a - c * c);
    const double ctr[4][3] = {{a, 0, 0}, {mu * c / a, b, 0}, {-a, 0, 0}, {mu * c / a, -b, 0}};
    const double rad[4] = {mu - c, b * mu / a, mu + c, b * mu / a};
    const double run[4][3] = {{0, 1, 0}, {-1, 0, 0}, {0, -1, 0}, {1, 0, 0}}; /* the plane's normal, as u grows */
    double worst = 0.0;
    int ok_dirs = 1;
    for (int q = 0; q < 4; q++) {
        double u = q * M_PI / 2, h[4], h2[4];
        for (int t = 0; t < 12; t++) {
            rg2_shape_param(&s, u, t * M_PI / 6, h);
            double d[3], off = 0.0, dist = 0.0;
            for (int k = 0; k < 3; k++) {
                d[k] = h[k] / h[3] - ctr[q][k];
                off += d[k] * run[q][k];
                dist += d[k] * d[k];
            }
            worst = fmax(worst, fmax(fabs(off), fabs(sqrt(dist) - rad[q])));
        }
        /* v = 0 nearest the z axis, v growing towards -z, u growing along the tube's direction */
        double h0[4], p0[3], pv[3], pu[3];
        rg2_shape_param(&s, u, 0.0, h0);
        rg2_shape_param(&s, u, 1e-3, h);
        rg2_shape_param(&s, u + 1e-3, 0.0, h2);
        for (int k = 0; k < 3; k++) {
            p0[k] = h0[k] / h0[3];
            pv[k] = h[k] / h[3] - p0[k];
            pu[k] = h2[k] / h2[3] - p0[k];
        }
        /* v = 0 at the centre less the radius along e = (1, 0, 0), (0, 1, 0), (-1, 0, 0), (0, -1, 0) */
        const double e[4][2] = {{1, 0}, {0, 1}, {-1, 0}, {0, -1}};
        double gap = hypot(p0[0] - (ctr[q][0] - rad[q] * e[q][0]), p0[1] - (ctr[q][1] - rad[q] * e[q][1]));
        ok_dirs &= gap <= 1e-14 && fabs(p0[2]) <= 1e-14 && pv[2] < 0.0 &&
                   pu[0] * run[q][0] + pu[1] * run[q][1] + pu[2] * run[q][2] > 0.0;
    }
    printf("cyclide tube circles at u = 0, 90, 180, 270: on their planes and radii within %.2e\n", worst);
    CHECK(worst <= 1e-14 && ok_dirs, "cyclide circles of docs/shapes.md: %.3g off, directions %s", worst,
          ok_dirs ? "ok" : "wrong");
}

/* A circle partition that starts many turns round: its junction angles start + alpha_0 + ...
 * rounded onto the start (1e9 degrees by 3e-8 rad, 1e18 rad entirely), so the corners left the
 * arcs (torus residual 2.4e-10 at 1e9 degrees, 0.11 at 1e18 rad). The start is taken within one
 * turn: every start below builds the torus to rounding (closed and open u, and as v), its patches
 * starting where the start says. */
static void start_turns(void)
{
    static const double starts[] = {1e9 * M_PI / 180.0, -1e15 * M_PI / 180.0, 1e18, 1e100, -3e300};
    int worst_at = -1;
    double worst = 0, worst_rep = 0;
    for (size_t q = 0; q < sizeof starts / sizeof starts[0]; q++)
        for (int cfg = 0; cfg < 3; cfg++) {
            double vu[8] = {M_PI / 4, M_PI / 4, M_PI / 4, M_PI / 4, M_PI / 4, M_PI / 4, M_PI / 4, M_PI / 4};
            double vv[6];
            rg2_error err;
            rg2_partition pu = {RG2_PART_ANGLES, cfg != 1, cfg == 1 ? 3 : 8, vu, starts[q]}, pv;
            CHECK_OK(rg2_partition_equal(&pv, RG2_PART_ANGLES, 1, 0.0, 0.0, 5, vv, 6, &err), &err);
            if (cfg == 2) { /* the start on v */
                pv.start = starts[q];
                pu.start = 0.0;
            }
            rg2_shape sh;
            rg2_shape_init(&sh, RG2_SHAPE_TORUS);
            rg2_surface s;
            rg2_status st = rg2_shape_surface(&sh, &pu, &pv, &s, NULL, &err);
            CHECK(st == RG2_OK, "start %g: %s", starts[q], err.msg);
            if (st)
                continue;
            stats f;
            stats_init(&f);
            measure_surface(&sh, &s, &pu, &pv, 8.0, 5, &f);
            if (!(f.resid <= worst))
                worst = f.resid, worst_at = (int)q;
            CHECK(f.resid <= 1e-15, "start %g rad (%s): residual %.3g", starts[q],
                  cfg == 0 ? "closed u" : cfg == 1 ? "open u" : "closed v", f.resid);
            /* closed u: patch i begins at the angle start + i pi / 4 (the rotation by the start,
             * exact in cos and sin) */
            for (int i = 0; cfg == 0 && i < 8; i++) {
                rg2_eval e;
                rg2_patch_eval(rg2_surface_patch(&s, i, 0), 0.0, 0.0, 0, &e);
                double c = cos(starts[q]), sn = sin(starts[q]), ph = i * M_PI / 4, l = hypot(e.p[0], e.p[1]);
                double dx = e.p[0] / l - (c * cos(ph) - sn * sin(ph)), dy = e.p[1] / l - (sn * cos(ph) + c * sin(ph));
                if (!(hypot(dx, dy) <= worst_rep))
                    worst_rep = hypot(dx, dy);
                CHECK(hypot(dx, dy) <= 1e-14, "start %g rad: patch %d starts %.3g rad off start + %d pi / 4",
                      starts[q], i, hypot(dx, dy), i);
            }
            rg2_surface_free(&s);
        }
    printf("circle partitions started 1e9 degrees to 3e300 rad round: residual %.2g (start %d), "
           "patch starts %.2g rad off\n", worst, worst_at, worst_rep);
}

/* Hyperboloid knots next to the zero of the weight (2v; 1 - v^2): within 1e-12 the ring there lies
 * 1e12 times further out and rounds the rest away (undefined normals), and from about 1e-17 the
 * control weight rounded to 0, a point at infinity (NaN residuals and gaps in rg2_check, STEP
 * refused). Refused naming the knot; just outside, built with every patch weight positive. */
static void hyperboloid_weight_zero(void)
{
    static const struct { rg2_shape_kind kind; double k[2]; int refuse; } cs[] = {
        {RG2_SHAPE_HYPERBOLOID1, {1e-17, 1}, 1}, {RG2_SHAPE_HYPERBOLOID1, {1e-30, 1}, 1},
        {RG2_SHAPE_HYPERBOLOID1, {9.9e-13, 1}, 1}, {RG2_SHAPE_HYPERBOLOID1, {1.01e-12, 1}, 0},
        {RG2_SHAPE_HYPERBOLOID1, {1e-6, 1e-5}, 0}, {RG2_SHAPE_HYPERBOLOID2, {0.5, 1 - 1e-15}, 1},
        {RG2_SHAPE_HYPERBOLOID2, {-(1 - 1e-15), 0.5}, 1}, {RG2_SHAPE_HYPERBOLOID2, {0.5, 1 - 2e-12}, 0}};
    for (size_t q = 0; q < sizeof cs / sizeof cs[0]; q++) {
        rg2_shape sh;
        rg2_shape_init(&sh, cs[q].kind);
        double vu[6], vv[2] = {cs[q].k[0], cs[q].k[1]};
        rg2_error err;
        rg2_partition pu, pv = {RG2_PART_KNOTS, 0, 2, vv, 0.0};
        CHECK_OK(rg2_partition_equal(&pu, RG2_PART_ANGLES, 1, 0.0, 0.0, 5, vu, 6, &err), &err);
        rg2_surface s;
        rg2_weight_report rep;
        rg2_status st = rg2_shape_surface(&sh, &pu, &pv, &s, &rep, &err);
        if (cs[q].refuse) {
            CHECK(st == RG2_EDOMAIN && strstr(err.msg, "v knot") && strstr(err.msg, "1e-12"),
                  "%s knots %g, %g: %s %s", rg2_shape_name(cs[q].kind), vv[0], vv[1], rg2_status_str(st),
                  st ? err.msg : "accepted");
        } else {
            CHECK(st == RG2_OK && rep.n_nonpositive == 0 && rep.min_weight > 0, "%s knots %g, %g: %s %s (min weight %g)",
                  rg2_shape_name(cs[q].kind), vv[0], vv[1], rg2_status_str(st), st ? err.msg : "", st ? 0 : rep.min_weight);
        }
        if (!st) {
            rg2_check_report r;
            rg2_check_opts o;
            rg2_check_opts_default(&o);
            o.threads = 1;
            CHECK_OK(rg2_check(&s, 1, &sh, NULL, 1, &o, &r, &err), &err);
            CHECK(r.worst_residual <= 1e-15 && r.g0.value <= 1e-15 && r.unmeasured == 0 && r.singular == 0,
                  "%s knots %g, %g: residual %g, G0 %g, %d unmeasured, %d singular", rg2_shape_name(cs[q].kind), vv[0],
                  vv[1], r.worst_residual, r.g0.value, r.unmeasured, r.singular);
            rg2_check_report_free(&r);
            rg2_surface_free(&s);
        }
    }
}

/* A torus of a thin tube: rg2_check's residual |f| / |grad f| of the polynomial
 * (x^2 + y^2 + z^2 + R^2 - r^2)^2 - 4 R^2 (x^2 + y^2) divided a rounding of eps R^4 by a gradient
 * of 8 R^2 r, and read an exact tube of r = 1e-6 R as 3.9e-11 of its size off itself (FAIL at the
 * 1e-11 limit), r = 1e-9 R as 3.9e-8, r = 1e-12 R as 3.9e-5. The implicit function is the product
 * of its factors for tubes thinner than R / 100: the residual is the patches' own, down to
 * r = 1e-12 R, placed and scaled; the value, gradient and Hessian are the polynomial's. */
static void thin_tubes(void)
{
    static const double rs[] = {1e-3, 1e-6, 1e-9, 1e-12};
    static const double scale[] = {1.0, 1e-30, 1e40};
    double worst = 0;
    for (size_t q = 0; q < sizeof rs / sizeof rs[0]; q++)
        for (size_t c = 0; c < sizeof scale / sizeof scale[0]; c++) {
            rg2_shape sh;
            rg2_shape_init(&sh, RG2_SHAPE_TORUS);
            sh.param[0] = 1.0;
            sh.param[1] = rs[q];
            double S[16], Rm[16], T[16];
            rg2_xform_scale(S, scale[c], scale[c], scale[c]);
            rg2_xform_rotate(Rm, 1, 2, 3, 0.7);
            rg2_xform_translate(T, 0.25 * scale[c], -0.5 * scale[c], 0.125 * scale[c]);
            rg2_xform_mul(Rm, S, sh.xform);
            rg2_xform_mul(T, sh.xform, sh.xform);
            double vu[8], vv[6];
            rg2_error err;
            rg2_partition pu, pv;
            CHECK_OK(rg2_partition_equal(&pu, RG2_PART_ANGLES, 1, 0.0, 0.0, 7, vu, 8, &err), &err);
            CHECK_OK(rg2_partition_equal(&pv, RG2_PART_ANGLES, 1, 0.0, 0.0, 5, vv, 6, &err), &err);
            rg2_surface s;
            if (rg2_shape_surface(&sh, &pu, &pv, &s, NULL, &err)) {
                CHECK(0, "thin torus r = %g: %s", rs[q], err.msg);
                continue;
            }
            rg2_check_report r;
            rg2_check_opts o;
            rg2_check_opts_default(&o);
            o.threads = 1;
            o.seam_samples = 2;
            CHECK_OK(rg2_check(&s, 1, &sh, NULL, 1, &o, &r, &err), &err);
            worst = fmax(worst, r.worst_residual);
            CHECK(r.worst_residual <= 1e-15, "torus R = 1, r = %g, scale %g: residual %.3g of its size", rs[q], scale[c],
                  r.worst_residual);
            rg2_check_report_free(&r);
            rg2_surface_free(&s);
        }
    /* the factored value, gradient and Hessian are the polynomial's (a torus of r = R / 103,
     * points on and off it, placed) */
    rg2_shape sh;
    rg2_shape_init(&sh, RG2_SHAPE_TORUS);
    sh.param[1] = 0.029; /* R = 3: r < R / 100, the factored form */
    rg2_xform_rotate(sh.xform, 1, -1, 2, 0.3);
    double bad = 0;
    for (int k = 0; k < 200; k++) {
        double x[3] = {3.0 * sin(1.3 * k), 3.0 * cos(0.7 * k + 1), 0.1 * sin(0.3 * k + 2)}, g[3], h[9], y[3];
        double f = rg2_shape_implicit2(&sh, x, g, h);
        for (int i = 0; i < 3; i++) /* the unplaced point: R^T x */
            y[i] = sh.xform[i] * x[0] + sh.xform[4 + i] * x[1] + sh.xform[8 + i] * x[2];
        double t = y[0] * y[0] + y[1] * y[1] + y[2] * y[2] + 9.0 - 0.029 * 0.029, rho2 = y[0] * y[0] + y[1] * y[1];
        double f0 = t * t - 36.0 * rho2;
        double gl[3] = {4 * t * y[0] - 72 * y[0], 4 * t * y[1] - 72 * y[1], 4 * t * y[2]}, g0[3];
        for (int i = 0; i < 3; i++) /* the placed gradient: R gl */
            g0[i] = sh.xform[4 * i] * gl[0] + sh.xform[4 * i + 1] * gl[1] + sh.xform[4 * i + 2] * gl[2];
        double scl = t * t + 36.0 * rho2 + 1.0;
        bad = fmax(bad, fabs(f - f0) / scl);
        for (int i = 0; i < 3; i++)
            bad = fmax(bad, fabs(g[i] - g0[i]) / scl);
        double tr = h[0] + h[4] + h[8], tr0 = 12 * t + 8 * (y[0] * y[0] + y[1] * y[1] + y[2] * y[2]) - 144;
        /* (the Laplacian: sum of d2/dyi2 of t^2 - 36 rho^2 = 4 t * 3 + 8 |y|^2 - 72 * 2) */
        bad = fmax(bad, fabs(tr - tr0) / scl);
    }
    CHECK(bad <= 1e-13, "factored torus function off the polynomial by %.3g (relative)", bad);
    printf("thin torus tubes r = 1e-3 .. 1e-12 R at scales 1, 1e-30, 1e40: residual %.2g; factored f, grad, "
           "Laplacian = the polynomial's to %.2g\n", worst, bad);
}

/* The control meshes of two partitions are one mesh: the same points and scalars, bit for bit. */
static int meshes_same(const rg2_mesh *a, const rg2_mesh *b)
{
    const rg2_scalars *sa[2] = {&a->su, &a->sv}, *sb[2] = {&b->su, &b->sv};
    int same = a->nu == b->nu && a->nv == b->nv && !memcmp(a->p, b->p, sizeof(double) * 4 * (size_t)a->nu * (size_t)a->nv);
    for (int d = 0; d < 2 && same; d++)
        same = sa[d]->n == sb[d]->n && sa[d]->closed == sb[d]->closed &&
               !memcmp(sa[d]->w, sb[d]->w, sizeof(double) * (size_t)rg2_scalars_num_w(sa[d])) &&
               !memcmp(sa[d]->b, sb[d]->b, sizeof(double) * (size_t)sa[d]->n) &&
               !memcmp(sa[d]->g, sb[d]->g, sizeof(double) * (size_t)sa[d]->n);
    return same;
}

/* Open knot partitions get the data knots docs/shapes.md gives: the end intervals mirrored about
 * the end knots, copies of the interval when there is only one. A paraboloid over such knots has
 * the control mesh of the same knots given with those data knots (RG2_PART_KNOTS_FULL); dyadic
 * knots, so that both layouts are exact. */
static void knot_data_ends(void)
{
    static const double one[2] = {0.5, 1.25}, one_full[6] = {-1.0, -0.25, 0.5, 1.25, 2.0, 2.75};
    static const double four[4] = {0.25, 0.5, 1.0, 1.75}, four_full[8] = {-0.5, 0.0, 0.25, 0.5, 1.0, 1.75, 2.5, 3.0};
    const double *kn[2] = {one, four}, *full[2] = {one_full, four_full};
    const int n[2] = {2, 4};
    rg2_error err;
    rg2_shape sh;
    rg2_shape_init(&sh, RG2_SHAPE_PARABOLOID);
    double eq[7];
    rg2_partition pu;
    CHECK_OK(rg2_partition_equal(&pu, RG2_PART_ANGLES, 1, 0.0, 0.0, 6, eq, 7, &err), &err);
    for (int q = 0; q < 2; q++) {
        rg2_partition pk = {RG2_PART_KNOTS, 0, n[q], (double *)kn[q], 0}, pf = {RG2_PART_KNOTS_FULL, 0, n[q] + 4,
                                                                                (double *)full[q], 0};
        rg2_mesh a, b;
        CHECK_OK(rg2_shape_mesh(&sh, &pu, &pk, &a, &err), &err);
        CHECK_OK(rg2_shape_mesh(&sh, &pu, &pf, &b, &err), &err);
        CHECK(meshes_same(&a, &b), "paraboloid over %d knots from %g to %g: not the mesh of the data knots %s", n[q],
              kn[q][0], kn[q][n[q] - 1], q ? "mirrored about the ends" : "copying the one interval");
        rg2_mesh_free(&a);
        rg2_mesh_free(&b);
    }
    printf("open knot partitions: data knots copied (one interval) and mirrored (three), as the full layout\n");
}

/* Two neighbouring arcs must leave at least the smallest arc of the circle (docs/shapes.md). An
 * open end arc of 3.14 and its data-only copy leave 2 pi - 6.28 = 0.0032 rad: refused, naming
 * that in degrees and the distance of their common control point, about 4 / (2 pi - sum) radii.
 * With the data arcs given (RG2_PART_ANGLES_FULL) every given pair counts, produced and data
 * arcs alike, and an end's data arc is not paired with a copy of itself: a last data arc of 3.14
 * builds a torus whose patches lie on it. */
static void neighbour_arcs(void)
{
    rg2_error err;
    double open[3] = {3.14, 1.0, 1.0}, deg = 0.0, away = 0.0, left = 2.0 * M_PI - 2.0 * 3.14;
    rg2_partition p = {RG2_PART_ANGLES, 0, 3, open, 0.0};
    rg2_status st = rg2_partition_check(&p, "u", &err);
    const char *at = strstr(err.msg, "leave only ");
    int got = st == RG2_EDOMAIN && at &&
              sscanf(at, "leave only %lf deg of the circle: their common control point lies about %lf times", &deg,
                     &away) == 2;
    CHECK(got && strstr(err.msg, "arc 0 at the open start") && fabs(deg - left * 180.0 / M_PI) <= 5e-3 * deg &&
              fabs(away - 4.0 / left) <= 5e-3 * away, /* (3 digits) */
          "open end arc 3.14: want %.3g deg left and %.3g radii away: %s", left * 180.0 / M_PI, 4.0 / left, err.msg);
    double full[5] = {0.5, 0.5, 3.14, 3.14, 0.5};
    rg2_partition pf = {RG2_PART_ANGLES_FULL, 0, 5, full, 0.0};
    expect_err(rg2_partition_check(&pf, "v", &err), RG2_EDOMAIN, &err, "v partition: arcs 1 and 2 leave only",
               "a produced arc and a data arc of 3.14");
    double last[5] = {0.5, 0.5, 1.0, 0.5, 3.14}, eq[7];
    rg2_partition pl = {RG2_PART_ANGLES_FULL, 0, 5, last, 0.0}, pu;
    rg2_shape sh;
    rg2_shape_init(&sh, RG2_SHAPE_TORUS);
    CHECK_OK(rg2_partition_equal(&pu, RG2_PART_ANGLES, 1, 0.0, 0.0, 6, eq, 7, &err), &err);
    rg2_surface s;
    st = rg2_shape_surface(&sh, &pu, &pl, &s, NULL, &err);
    CHECK(st == RG2_OK, "torus with a last data arc of 3.14: %s", err.msg);
    if (st == RG2_OK) {
        stats one;
        stats_init(&one);
        measure_surface(&sh, &s, &pu, &pl, rg2t_surface_scale(&s), 6, &one);
        CHECK(one.resid <= 1e-13, "torus with a last data arc of 3.14: residual %.3g", one.resid);
        rg2_surface_free(&s);
    }
}

/* One placed shape measured on its implicit surface, against its parameterization and its
 * curvatures (the bounds of named_shapes); returns the residual. */
static double placed_off(const rg2_shape *sh, const rg2_partition *pu, const rg2_partition *pv, const char *what)
{
    rg2_error err;
    rg2_surface s;
    rg2_weight_report rep;
    rg2_status st = rg2_shape_surface(sh, pu, pv, &s, &rep, &err);
    CHECK(st == RG2_OK && rep.n_nonpositive == 0, "%s: %s %s", what, rg2_status_str(st), st ? err.msg : "");
    if (st)
        return INFINITY;
    stats one;
    stats_init(&one);
    measure_surface(sh, &s, pu, pv, rg2t_surface_scale(&s), 6, &one);
    rg2_surface_free(&s);
    CHECK(one.resid <= 1e-13 && one.repro <= 1e-13 && one.K <= 1e-9 && one.H <= 1e-9,
          "%s: residual %.3g, reproduction %.3g, K %.3g, H %.3g", what, one.resid, one.repro, one.K, one.H);
    return one.resid;
}

/* Placements at the edges of the weight and the affine tests, and slopes other than 1.
 * A hyperboloid1 over the knots 0.5, 1 has the data knots -0.5, 0 (mirrored), so its first v row
 * has the weight 2 (-0.5 + 0 + 0.5) / 3 = 0 exactly: points at infinity, carrying data only. A last
 * placement row (0, 0, -0.01, 1) gives that row the weight -0.01 z < 0 and keeps every positive
 * weight positive: accepted (only those must stay positive), on the placed hyperboloid.
 * A torus placed with the last row (0, 0.05, 0, 1): the inverse's last row begins with an exact 0,
 * and the placed implicit function must divide by that row all the same.
 * Cones of slopes -2.5, 0.4 and 3 (named_shapes keeps k = 1, where k^2 = k / k). */
static void placed_edges(void)
{
    rg2_error err;
    double eq[7], kv[2] = {0.5, 1.0}, worst = 0.0;
    rg2_partition pu, pv = {RG2_PART_KNOTS, 0, 2, kv, 0.0};
    CHECK_OK(rg2_partition_equal(&pu, RG2_PART_ANGLES, 1, 0.0, 0.0, 6, eq, 7, &err), &err);
    rg2_shape sh;
    rg2_shape_init(&sh, RG2_SHAPE_HYPERBOLOID1);
    rg2_mesh m;
    int zero = 0;
    CHECK_OK(rg2_shape_mesh(&sh, &pu, &pv, &m, &err), &err);
    for (int i = 0; i < m.nu; i++)
        zero += rg2_mesh_at(&m, i, 0)[3] == 0.0 && rg2_mesh_at(&m, i, 0)[2] > 0.0;
    CHECK(zero == m.nu && m.nu > 0, "hyperboloid1 over [0.5, 1]: %d of the %d points of v row 0 of weight 0, z > 0", zero,
          m.nu);
    rg2_mesh_free(&m);
    sh.xform[14] = -0.01;
    worst = fmax(worst, placed_off(&sh, &pu, &pv, "hyperboloid1, a weight-0 row placed to a negative weight"));
    rg2_shape_init(&sh, RG2_SHAPE_TORUS);
    sh.xform[13] = 0.05;
    double inv[16], vv[6];
    CHECK_OK(rg2_xform_invert(sh.xform, inv, &err), &err);
    CHECK(inv[12] == 0.0 && inv[13] != 0.0, "the inverse's last row: %g %g", inv[12], inv[13]);
    rg2_partition pt;
    CHECK_OK(rg2_partition_equal(&pt, RG2_PART_ANGLES, 1, 0.0, 0.0, 5, vv, 6, &err), &err);
    worst = fmax(worst, placed_off(&sh, &pu, &pt, "torus placed with the last row (0, 0.05, 0, 1)"));
    static const double slopes[3] = {-2.5, 0.4, 3.0};
    double kc[4] = {0.5, 0.8, 1.2, 1.5};
    rg2_partition pc = {RG2_PART_KNOTS, 0, 4, kc, 0.0};
    for (int k = 0; k < 3; k++) {
        rg2_shape_init(&sh, RG2_SHAPE_CONE);
        sh.param[0] = slopes[k];
        rg2_xform_rotate(sh.xform, 1, 2, 3, 0.7);
        char what[32];
        snprintf(what, sizeof what, "cone of slope %g", slopes[k]);
        worst = fmax(worst, placed_off(&sh, &pu, &pc, what));
    }
    printf("placed at the weight and affine edges, cones of slopes -2.5 .. 3: residual %.2e\n", worst);
}

int main(void)
{
    named_shapes();
    documented_defaults();
    documented_partitions();
    families();
    transforms();
    full_partitions();
    knot_maps_and_checks();
    weight_warning();
    parameter_ranges();
    equal_knots();
    small_arc_message();
    radian_totals();
    smallest_full_knots();
    unknown_name_list();
    ring_heights();
    cyclide_circles();
    start_turns();
    hyperboloid_weight_zero();
    thin_tubes();
    knot_data_ends();
    neighbour_arcs();
    placed_edges();
    errors();
    return rg2t_done("test_shapes");
}
