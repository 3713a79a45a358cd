/* rg2 shapes / rg2 shape -- list the exact basic shapes; build one (or a bi-cubic NURBS) into
 * rational bi-cubic patches and print a summary or a JSON dump of the mesh and patches. */
#include "cli.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#define MAXV (RG2_CLI_MAX_ARCS + 1) /* values of a list: n arcs, or n + 1 knots */

/* A direction's default partition as docs/shapes.md ("Default partitions") words it. */
static void print_default_partition(const rg2_shape_desc *d, int dir)
{
    if (d->dir_kind[dir] == RG2_PART_ANGLES && d->default_closed[dir])
        printf("%d arcs, full circle", d->default_segments[dir]);
    else if (d->dir_kind[dir] == RG2_PART_ANGLES)
        printf("%d arcs over [%g, %g] deg", d->default_segments[dir], d->default_range[dir][0] * 180 / M_PI,
               d->default_range[dir][1] * 180 / M_PI);
    else
        printf("%d knot intervals of [%g, %g]", d->default_segments[dir], d->default_range[dir][0],
               d->default_range[dir][1]);
}

static void print_shape_list_text(void)
{
    printf("exact basic shapes (build one with: rg2 shape NAME --PARAM value ...; see rg2 shape --help):\n\n");
    for (int k = 0; k < RG2_SHAPE_COUNT; k++) {
        const rg2_shape_desc *d = rg2_shape_describe((rg2_shape_kind)k);
        printf("%-19s", d->name);
        for (int p = 0; p < d->n_params; p++)
            printf(" %s=%g", d->param_names[p], d->param_defaults[p]);
        printf("\n  u: %s, v: %s\n", d->dir_kind[0] == RG2_PART_ANGLES ? "circle (angles)" : "polynomial (knots)",
               d->dir_kind[1] == RG2_PART_ANGLES ? "circle (angles)" : "polynomial (knots)");
        printf("  default u: ");
        print_default_partition(d, 0);
        printf("; v: ");
        print_default_partition(d, 1);
        printf("\n  h(u, v) = %s\n  implicit: %s\n", d->param_text, d->implicit_text);
    }
    printf("nurbs               bi-cubic NURBS from a JSON file (rg2 shape nurbs --file F.json)\n");
}

/* A JSON number, or null for NaN / infinity (JSON has neither). */
static void json_num(double x)
{
    if (isfinite(x))
        printf("%.17g", x);
    else
        printf("null");
}

static void json_doubles(const double *x, int n)
{
    printf("[");
    for (int k = 0; k < n; k++) {
        printf("%s", k ? ", " : "");
        json_num(x[k]);
    }
    printf("]");
}

static void print_shape_list_json(void)
{
    printf("{\"shapes\": [");
    for (int k = 0; k < RG2_SHAPE_COUNT; k++) {
        const rg2_shape_desc *d = rg2_shape_describe((rg2_shape_kind)k);
        printf("%s\n  {\"name\": \"%s\", \"params\": {", k ? "," : "", d->name);
        for (int p = 0; p < d->n_params; p++)
            printf("%s\"%s\": %.17g", p ? ", " : "", d->param_names[p], d->param_defaults[p]);
        printf("}, \"u\": \"%s\", \"v\": \"%s\", ", d->dir_kind[0] == RG2_PART_ANGLES ? "angles" : "knots",
               d->dir_kind[1] == RG2_PART_ANGLES ? "angles" : "knots");
        printf("\"default_range\": [");
        json_doubles(d->default_range[0], 2);
        printf(", ");
        json_doubles(d->default_range[1], 2);
        printf("], \"default_segments\": [%d, %d], \"default_closed\": [%s, %s]", d->default_segments[0],
               d->default_segments[1], d->default_closed[0] ? "true" : "false", d->default_closed[1] ? "true" : "false");
        printf(", \"param\": \"%s\", \"implicit\": \"%s\"}", d->param_text, d->implicit_text);
    }
    printf("\n]}\n");
}

int rg2_cmd_shapes(int argc, char **argv)
{
    int json = 0;
    for (int i = 1; i < argc; i++) {
        if (!strcmp(argv[i], "--json")) {
            json = 1;
        } else if (!strcmp(argv[i], "--help") || !strcmp(argv[i], "-h")) {
            printf("usage: rg2 shapes [--json]\n\nLists the exact basic shapes with their parameters "
                   "(and defaults), direction kinds,\nhomogeneous parameterization and implicit "
                   "equation. Build one with 'rg2 shape NAME'.\n");
            return 0;
        } else if (argv[i][0] != '-') { /* a shape name: 'rg2 shape NAME' builds it */
            fprintf(stderr, "rg2 shapes: unexpected argument '%s' (rg2 shapes lists every shape; to build one: "
                            "rg2 shape %s)\n", argv[i], argv[i]);
            return RG2_EXIT_USAGE;
        } else {
            fprintf(stderr, "rg2 shapes: unknown option '%s'\n", argv[i]);
            return RG2_EXIT_USAGE;
        }
    }
    if (json)
        print_shape_list_json();
    else
        print_shape_list_text();
    return 0;
}

/* An unknown option of `rg2 shape` (d: the shape's kind, or NULL): the message names the closest
 * of the options the shape takes (its parameters, the partitions of u and v, the placement), or,
 * for another shape's parameter or nothing close, the parameters this shape takes. */
static int shape_unknown_option(const rg2_shape_desc *d, const char *a)
{
    static const char *const dir_opts[] = {"arcs", "segments", "angles", "knots", "start",
                                           "sweep", "range", "open", "closed"};
    static const char *const place[] = {"--scale", "--axis", "--center", "--centre", "--xform",
                                        "--samples", "--json", "--help"};
    enum { N_PAR = 4 /* rg2_shape_desc.param_names */, N_DIR = 9, N_PLACE = 8 };
    char buf[N_PAR + 2 * N_DIR][24];
    const char *names[N_PAR + 2 * N_DIR + N_PLACE];
    int n = 0;
    for (int k = 0; d && k < d->n_params && k < N_PAR; k++, n++)
        snprintf(buf[n], sizeof buf[n], "--%s", d->param_names[k]), names[n] = buf[n];
    for (int uv = 0; uv < 2; uv++)
        for (int k = 0; k < N_DIR; k++, n++)
            snprintf(buf[n], sizeof buf[n], "--%c-%s", "uv"[uv], dir_opts[k]), names[n] = buf[n];
    for (int k = 0; k < N_PLACE; k++)
        names[n++] = place[k];
    int other_param = 0; /* another shape's parameter (--radius to a torus): say what this one takes */
    for (int k = 0; d && k < RG2_SHAPE_COUNT; k++) {
        const rg2_shape_desc *o = rg2_shape_describe((rg2_shape_kind)k);
        for (int q = 0; o && q < o->n_params; q++)
            other_param |= !strcmp(a + 2, o->param_names[q]);
    }
    int extent = d && d->dir_kind[1] == RG2_PART_KNOTS && d->dir_kind[0] == RG2_PART_ANGLES &&
                 (!strcmp(a, "--height") || !strcmp(a, "--length") || !strcmp(a, "--h") ||
                  (!strcmp(a, "--radius") && other_param));
    if (extent) { /* a size along the axis: the v knots place the rings (docs/shapes.md) */
        fprintf(stderr, "rg2 shape: unknown option '%s'; %s takes", a, d->name);
        for (int k = 0; k < d->n_params; k++)
            fprintf(stderr, " --%s", d->param_names[k]);
        fprintf(stderr, ": its extent is not a parameter but its v knots, which place the rings (--v-range A,B "
                        "or --v-knots; docs/shapes.md, \"Where a knot puts the ring\")\n");
        return RG2_EXIT_USAGE;
    }
    if (d && (other_param || !rg2_closest_name(a, names, n))) { /* (or nothing close) */
        fprintf(stderr, "rg2 shape: unknown option '%s'; %s takes", a, d->name);
        for (int k = 0; k < d->n_params; k++)
            fprintf(stderr, " --%s", d->param_names[k]);
        fprintf(stderr, " (see rg2 shape --help)\n");
        return RG2_EXIT_USAGE;
    }
    return rg2_cli_unknown_option_of("shape", a, names, n);
}

/* Usage to stdout for --help, to stderr as the usage error of a bare `rg2 shape`. */
static void help_shape(FILE *f)
{
    fprintf(f,
        "usage: rg2 shape NAME [--PARAM value ...] [direction options] [placement] [--json]\n"
        "       rg2 shape nurbs (--file F.json | --spec JSON) [--json]\n\n"
        "Builds the control mesh of an exact shape (rg2 shapes lists them) and its rational\n"
        "bi-cubic patches; prints a summary (partitions, placement given, patch counts, weights,\n"
        "implicit residual) or, with --json, the partitions, control mesh and every patch's\n"
        "homogeneous control points.\n\n"
        "Direction options (D = u or v). Circle directions, angles in degrees; every arc lies in\n"
        "[0.286479, 180) (0.005 rad up to pi, excluded), so a full circle has 3 to 1256 arcs:\n"
        "  --D-arcs N          N equal arcs: the full circle (closed), or --D-sweep DEG (open)\n"
        "  --D-angles A,B,...  opening angles; closed if they sum to 360 (to 12 digits)\n"
        "  --D-start DEG       angle where the first arc starts (default 0)\n"
        "  --D-sweep DEG       open partial circle of this total angle (> 0)\n"
        "  --D-open / --D-closed  force open or closed\n"
        "Polynomial directions:\n"
        "  --D-knots K0,K1,... increasing knots bounding the segments\n"
        "  --D-range A,B --D-segments N   N equal segments of [A, B], A < B\n"
        "Placement (applied in this order: scale, axis rotation, centre, then --xform):\n"
        "  --scale S | SX,SY,SZ   --axis X,Y,Z (the shape's z axis)   --center X,Y,Z\n"
        "  --xform M00,M01,...,M33 (16 numbers, row-major, applied to homogeneous 4-tuples)\n"
        "Other: --samples N (residual over (N + 1) x (N + 1) points per patch, 1..1000, default 8),\n"
        "  --json\n\n"
        "NURBS JSON: {\"nu\": 4, \"nv\": 5, \"points\": [[x,y,z], ...] (nu*nv, u-major),\n"
        "  \"weights\": [...] (optional), \"knots_u\": [nu+4 values], \"knots_v\": [nv+4 values]}\n\n"
        "examples:\n"
        "  rg2 shape torus --R 3 --r 1 --u-arcs 8 --v-arcs 6\n"
        "  rg2 shape torus --u-arcs 3 --u-sweep 90 --v-angles 60,120,90,90   (a quarter torus)\n"
        "  rg2 shape sphere --radius 2 --v-knots 0.25,0.4,0.6,0.75 --json\n"
        "  rg2 shape cone --k 2 --v-range 0.5,2 --v-segments 4 --center 1,0,0 --axis 1,0,0\n");
}

typedef struct {
    double vals[MAXV];
    int n_vals;      /* -1: none given */
    int arcs;        /* --D-arcs N, 0: none */
    int segments;    /* --D-segments N, 0: none */
    int has_range, has_sweep, has_start;
    double range[2], sweep, start;
    int open, closed, angles, knots; /* angles, knots: --D-angles, --D-knots given (o->vals holds the last) */
} dir_opts;

/* An angle total (the --D-angles' sum or --D-sweep) of 2 pi, pi or pi / 2 degrees, as a design
 * file's: a circle typed in radians (--u-angles 1.5708,1.5708,1.5708,1.5708 built an open sliver
 * of 6.28 degrees with no word); refused unless --D-open or --D-closed is given. */
static int radians(const char *shape, const char *D, const dir_opts *o, double deg)
{
    const char *turn = o->open || o->closed ? NULL : rg2_angle_total_in_radians(deg);
    if (turn)
        fprintf(stderr, "rg2 shape: %s: %s%s%s %.6g degrees, which is %s; angles are in degrees (a full circle "
                        "is 360): convert them (times 180 / pi), or add --%s-open if an open ring of %.6g degrees "
                        "is meant\n", shape, o->angles ? "the --" : "--", D, o->angles ? "-angles sum to" : "-sweep",
                deg, turn, D, deg);
    return turn != NULL;
}

/* Turn the options of one direction into a partition (values stored in o->vals). */
static int make_partition(const char *shape, const rg2_shape_desc *d, int dir, dir_opts *o,
                          rg2_partition *p)
{
    const char *D = dir ? "v" : "u";
    memset(p, 0, sizeof *p);
    rg2_error err = {0};
    if (d->dir_kind[dir] == RG2_PART_ANGLES) {
        if (o->knots || o->has_range || o->segments) {
            fprintf(stderr, "rg2 shape: %s: %s is a circle direction: use --%s-arcs, --%s-angles, "
                            "--%s-sweep, --%s-start\n", shape, D, D, D, D, D);
            return RG2_EXIT_USAGE;
        }
        /* options that contradict each other, or one of which the other would silently drop */
        const char *clash = o->open && o->closed ? "--%s-open and --%s-closed contradict each other"
                            : o->closed && o->has_sweep ? "--%s-sweep gives an open partial circle; --%s-closed contradicts it"
                            : o->angles && o->arcs ? "give --%s-angles (the arcs' angles) or --%s-arcs (a count), not both"
                            : o->angles && o->has_sweep ? "--%s-angles goes without --%s-sweep: the angles add up to the sweep"
                                                        : NULL;
        if (clash) {
            fprintf(stderr, "rg2 shape: %s: ", shape);
            fprintf(stderr, clash, D, D);
            fprintf(stderr, "\n");
            return RG2_EXIT_USAGE;
        }
        double start = o->has_start ? o->start * M_PI / 180.0 : 0.0;
        if (o->n_vals >= 0) {
            double sum = 0.0;
            for (int k = 0; k < o->n_vals; k++)
                sum += o->vals[k];
            for (int k = 0; k < o->n_vals; k++)
                o->vals[k] *= M_PI / 180.0;
            p->kind = RG2_PART_ANGLES;
            p->n = o->n_vals;
            p->values = o->vals;
            p->start = start;
            if (radians(shape, D, o, sum))
                return RG2_EXIT_FAIL;
            double gap = fabs(sum - 360.0);
            if (!o->closed && !o->open && gap > RG2_CLOSED_SUM_TOL * 360.0 && gap <= RG2_NEAR_FULL_DEG) {
                fprintf(stderr,
                        "rg2 shape: %s: the %d --%s-angles sum to %.10g degrees, %.3g from a full circle: for a "
                        "closed circle give them to 12 digits (or --%s-arcs %d); for an open ring add --%s-open\n",
                        shape, o->n_vals, D, sum, gap, D, o->n_vals, D);
                return RG2_EXIT_FAIL;
            }
            p->closed = o->closed ? 1 : o->open ? 0 : gap <= RG2_CLOSED_SUM_TOL * 360.0;
            return 0;
        }
        int n = o->arcs, open = o->has_sweep || o->open;
        if (open && !o->has_sweep) {
            fprintf(stderr, "rg2 shape: %s: an open %s direction needs --%s-sweep DEG or --%s-angles\n",
                    shape, D, D, D);
            return RG2_EXIT_USAGE;
        }
        double sweep = open ? o->sweep : 360.0;
        if (o->has_sweep && radians(shape, D, o, sweep))
            return RG2_EXIT_FAIL;
        if (n <= 0) /* open: about as fine as the default full-circle partition */
            n = open ? (int)ceil(fabs(sweep) / (360.0 / d->default_segments[dir]) - 1e-9)
                     : d->default_segments[dir];
        if (n < 1)
            n = 1;
        if (n > MAXV - 1) {
            fprintf(stderr, "rg2 shape: --%s-arcs %d: at most %d\n", D, n, MAXV - 1);
            return RG2_EXIT_USAGE;
        }
        for (int k = 0; k < n; k++) /* validated by rg2_shape_mesh, naming the direction */
            o->vals[k] = sweep / n * M_PI / 180.0;
        p->kind = RG2_PART_ANGLES;
        p->n = n;
        p->values = o->vals;
        p->start = start;
        p->closed = !open;
        return 0;
    }
    if (o->arcs || o->has_sweep || o->has_start || o->open || o->closed || o->angles) {
        fprintf(stderr, "rg2 shape: %s: %s is a polynomial direction: use --%s-knots or --%s-range "
                        "with --%s-segments\n", shape, D, D, D, D);
        return RG2_EXIT_USAGE;
    }
    if (o->knots && (o->has_range || o->segments)) {
        fprintf(stderr, "rg2 shape: %s: give --%s-knots, or --%s-range with --%s-segments, not both\n", shape, D, D, D);
        return RG2_EXIT_USAGE;
    }
    if (o->n_vals >= 0) {
        p->kind = RG2_PART_KNOTS;
        p->n = o->n_vals;
        p->values = o->vals;
        return 0;
    }
    double lo = o->has_range ? o->range[0] : d->default_range[dir][0];
    double hi = o->has_range ? o->range[1] : d->default_range[dir][1];
    int n = o->segments > 0 ? o->segments : d->default_segments[dir];
    if (n > MAXV - 1) {
        fprintf(stderr, "rg2 shape: --%s-segments %d: at most %d\n", D, n, MAXV - 1);
        return RG2_EXIT_USAGE;
    }
    if (rg2_partition_equal(p, RG2_PART_KNOTS, 0, lo, hi, n, o->vals, MAXV, &err))
        return rg2_cli_report("shape", &err);
    return 0;
}

/* --- output ---------------------------------------------------------------------------- */

static void json_scalars(const rg2_scalars *s)
{
    printf("{\"n\": %d, \"closed\": %s, \"w\": ", s->n, s->closed ? "true" : "false");
    json_doubles(s->w, rg2_scalars_num_w(s));
    printf(", \"b\": ");
    json_doubles(s->b, s->n);
    printf(", \"g\": ");
    json_doubles(s->g, s->n);
    printf("}");
}

static void json_partition(const rg2_partition *p)
{
    printf("{\"kind\": \"%s\", \"closed\": %s, \"start\": ", p->kind == RG2_PART_ANGLES ? "angles" : "knots",
           p->closed ? "true" : "false");
    json_num(p->start);
    printf(", \"values\": ");
    json_doubles(p->values, p->n);
    printf("}");
}

static void print_json(const rg2_shape *sh, const rg2_partition *pu, const rg2_partition *pv,
                       const rg2_mesh *m, const rg2_surface *s, const rg2_weight_report *rep,
                       double resid)
{
    printf("{");
    if (sh) {
        const rg2_shape_desc *d = rg2_shape_describe(sh->kind);
        printf("\"shape\": \"%s\", \"params\": {", d->name);
        for (int k = 0; k < d->n_params; k++)
        {
            printf("%s\"%s\": ", k ? ", " : "", d->param_names[k]);
            json_num(sh->param[k]);
        }
        printf("}, \"xform\": ");
        json_doubles(sh->xform, 16);
        printf(",\n \"u\": ");
        json_partition(pu);
        printf(",\n \"v\": ");
        json_partition(pv);
        printf(",\n \"max_residual\": ");
        json_num(resid);
        printf(",\n");
    } else {
        printf("\"shape\": \"nurbs\",\n");
    }
    printf(" \"min_weight\": ");
    json_num(rep->min_weight);
    printf(", \"nonpositive_patches\": %d,\n", rep->n_nonpositive);
    printf(" \"mesh\": {\"nu\": %d, \"nv\": %d, \"u\": ", m->nu, m->nv);
    json_scalars(&m->su);
    printf(", \"v\": ");
    json_scalars(&m->sv);
    printf(",\n  \"points\": [");
    for (int i = 0; i < m->nu; i++)
        for (int j = 0; j < m->nv; j++) {
            printf("%s", i || j ? ", " : "");
            json_doubles(rg2_mesh_at(m, i, j), 4);
        }
    printf("]},\n \"surface\": {\"nu\": %d, \"nv\": %d, \"closed_u\": %s, \"closed_v\": %s, \"bu\": ", s->nu,
           s->nv, s->closed_u ? "true" : "false", s->closed_v ? "true" : "false");
    json_doubles(s->bu, s->nu);
    printf(", \"gu\": ");
    json_doubles(s->gu, s->nu);
    printf(", \"bv\": ");
    json_doubles(s->bv, s->nv);
    printf(", \"gv\": ");
    json_doubles(s->gv, s->nv);
    printf(",\n  \"patches\": [");
    for (int i = 0; i < s->nu; i++)
        for (int j = 0; j < s->nv; j++) {
            rg2_xpatch P;
            rg2_surface_patch_get(s, i, j, &P);
            printf("%s\n   {\"i\": %d, \"j\": %d, ", i || j ? "," : "", i, j);
            if (rg2_surface_xpatch(s, i, j)) /* higher degree: h is (du + 1) x (dv + 1) */
                printf("\"du\": %d, \"dv\": %d, ", P.du, P.dv);
            printf("\"h\": [");
            for (int r = 0; r <= P.du; r++) {
                printf("%s[", r ? ", " : "");
                for (int t = 0; t <= P.dv; t++) {
                    printf("%s", t ? ", " : "");
                    json_doubles(P.h[r][t], 4);
                }
                printf("]");
            }
            printf("]}");
        }
    printf("\n  ]}\n}\n");
}

static void print_partition_text(const char *D, const rg2_partition *p)
{
    if (p->kind == RG2_PART_ANGLES) {
        double sum = 0.0;
        for (int k = 0; k < p->n; k++)
            sum += p->values[k];
        printf("  %s: %s circle, %d arc%s from %g deg, total %g deg:", D, p->closed ? "closed" : "open", p->n,
               p->n == 1 ? "" : "s", p->start * 180.0 / M_PI, sum * 180.0 / M_PI);
        for (int k = 0; k < p->n && k < 12; k++)
            printf(" %.6g", p->values[k] * 180.0 / M_PI);
    } else {
        printf("  %s: polynomial, %d segments, knots:", D, p->n - 1);
        for (int k = 0; k < p->n && k < 13; k++)
            printf(" %.6g", p->values[k]);
    }
    /* the first 12 arcs, or the knots of the first 12 segments; " ..." when more are left out
     * (13 arcs listed 12 and no " ...", as if complete) */
    printf("%s\n", p->n > (p->kind == RG2_PART_ANGLES ? 12 : 13) ? " ..." : "");
}

/* Largest |f| / |grad f| over samples x samples points per patch, relative to the size. */
static double max_residual(const rg2_shape *sh, const rg2_surface *s, int samples, double *size)
{
    double lo[3] = {INFINITY, INFINITY, INFINITY}, hi[3] = {-INFINITY, -INFINITY, -INFINITY}, worst = 0.0;
    for (int i = 0; i < s->nu; i++)
        for (int j = 0; j < s->nv; j++)
            for (int a = 0; a <= samples; a++)
                for (int b = 0; b <= samples; b++) {
                    rg2_eval e;
                    rg2_surface_eval(s, i, j, (double)a / samples, (double)b / samples, 0, &e);
                    double g[3], f = rg2_shape_implicit(sh, e.p, g);
                    double gn = sqrt(g[0] * g[0] + g[1] * g[1] + g[2] * g[2]);
                    double r = f == 0.0 ? 0.0 : fabs(f) / gn; /* f = 0 = grad f: a cone's apex */
                    if (!(r <= worst))
                        worst = r;
                    for (int k = 0; k < 3; k++)
                        lo[k] = fmin(lo[k], e.p[k]), hi[k] = fmax(hi[k], e.p[k]);
                }
    *size = sqrt((hi[0] - lo[0]) * (hi[0] - lo[0]) + (hi[1] - lo[1]) * (hi[1] - lo[1]) +
                 (hi[2] - lo[2]) * (hi[2] - lo[2]));
    return worst;
}

/* x in 15 significant digits, or 16 or 17 where 15 do not read back as x ("0.1", not
 * "0.10000000000000001"; "-90", not "-9e+01"). */
typedef struct {
    char s[32];
} num_text_t;
static num_text_t num_text(double x)
{
    num_text_t t;
    for (int p = 15; p <= 17; p++) {
        snprintf(t.s, sizeof t.s, "%.*g", p, x);
        if (strtod(t.s, NULL) == x)
            break;
    }
    return t;
}

/* Append "LABEL (X, Y, Z)" to the placement text t, after ", " when t has some already. */
static void placement_add(char *t, size_t size, const char *label, const double x[3])
{
    size_t n = strlen(t);
    snprintf(t + n, size - n, "%s%s (%s, %s, %s)", n ? ", " : "", label, num_text(x[0]).s, num_text(x[1]).s,
             num_text(x[2]).s);
}

/* placed: the placement options given, in the order they apply ("" when none was given) */
static void print_summary(const rg2_shape *sh, const rg2_partition *pu, const rg2_partition *pv,
                          const char *placed, const rg2_mesh *m, const rg2_surface *s,
                          const rg2_weight_report *rep, double resid, double size, int samples)
{
    if (sh) {
        const rg2_shape_desc *d = rg2_shape_describe(sh->kind);
        printf("%s", d->name);
        for (int k = 0; k < d->n_params; k++)
            printf("%s %s = %s", k ? "," : "", d->param_names[k], num_text(sh->param[k]).s);
        printf("\n  h(u, v) = %s\n", d->param_text);
        print_partition_text("u", pu);
        print_partition_text("v", pv);
        if (placed[0])
            printf("  placement: %s\n", placed);
    } else {
        printf("bi-cubic NURBS\n");
    }
    printf("  control mesh %d x %d (%s x %s)\n", m->nu, m->nv, m->su.closed ? "closed" : "open",
           m->sv.closed ? "closed" : "open");
    printf("  %d x %d rational bi-cubic patches, min homogeneous weight %.6g (patch %d,%d)%s\n", s->nu,
           s->nv, rep->min_weight, rep->patch_i, rep->patch_j,
           rep->flags & RG2_SHAPE_WARN_WEIGHT ? "" : ", all positive");
    if (sh && isfinite(resid) && isfinite(size))
        printf("  implicit %s: max |f|/|grad f| = %.3g (%.3g of the size %.6g) over %d x %d samples per "
               "patch\n",
               rg2_shape_describe(sh->kind)->implicit_text, resid, size > 0 ? resid / size : resid, size,
               samples + 1, samples + 1);
    else if (sh) /* the size is in range, but powers of it (the quartic torus) leave the doubles */
        printf("  implicit %s: max |f|/|grad f| not computable in double precision at this size (the "
               "implicit function overflows)\n",
               rg2_shape_describe(sh->kind)->implicit_text);
}

/* --- rg2 shape ------------------------------------------------------------------------- */

static int parse_one(const char *opt, const char *val, double *out)
{
    return rg2_cli_number("shape", opt, val, "a number", out);
}

int rg2_cmd_shape(int argc, char **argv)
{
    if (argc < 2 || !strcmp(argv[1], "--help") || !strcmp(argv[1], "-h")) {
        help_shape(argc < 2 ? stderr : stdout);
        return argc < 2 ? RG2_EXIT_USAGE : 0;
    }
    static dir_opts dop[2];
    memset(dop, 0, sizeof dop);
    dop[0].n_vals = dop[1].n_vals = -1;
    const char *name = argv[1], *file = NULL, *spec = NULL;
    int is_nurbs = !strcmp(name, "nurbs"), json = 0, samples = 8;
    rg2_shape sh;
    rg2_error err = {0};
    const rg2_shape_desc *d = NULL;
    if (!is_nurbs) {
        rg2_shape_kind kind;
        if (rg2_shape_from_name(name, &kind, &err)) {
            const char *names[RG2_SHAPE_COUNT + 1];
            for (int k = 0; k < RG2_SHAPE_COUNT; k++)
                names[k] = rg2_shape_describe((rg2_shape_kind)k)->name;
            names[RG2_SHAPE_COUNT] = "nurbs";
            const char *close = rg2_closest_name(name, names, RG2_SHAPE_COUNT + 1);
            fprintf(stderr, "rg2 shape: %s (or nurbs)%s%s%s\n", err.msg, close ? "; did you mean '" : "",
                    close ? close : "", close ? "'?" : "");
            return RG2_EXIT_USAGE;
        }
        rg2_shape_init(&sh, kind);
        d = rg2_shape_describe(kind);
    }
    double scale[3] = {1, 1, 1}, axis[3] = {0, 0, 1}, centre[3] = {0, 0, 0}, xf[16];
    int has_xform = 0, n_scale = 0, has_axis = 0, has_centre = 0, rc = 0; /* (which the summary names) */
    for (int i = 2; i < argc; i++) {
        const char *a = argv[i];
        const char *val = i + 1 < argc ? argv[i + 1] : NULL;
        if (!strcmp(a, "--json")) {
            json = 1;
            continue;
        }
        if (!strcmp(a, "--help") || !strcmp(a, "-h")) {
            help_shape(stdout);
            return 0;
        }
        if (strncmp(a, "--", 2)) {
            fprintf(stderr, "rg2 shape: unexpected argument '%s'\n", a);
            return RG2_EXIT_USAGE;
        }
        if (is_nurbs && strcmp(a, "--file") && strcmp(a, "--spec")) { /* placement, partitions: the exact shapes' */
            fprintf(stderr, "rg2 shape: nurbs takes --file F.json or --spec JSON and --json, not '%s' (see rg2 shape "
                            "--help)\n", a);
            return RG2_EXIT_USAGE;
        }
        /* flags without a value */
        if ((a[2] == 'u' || a[2] == 'v') && a[3] == '-' && (!strcmp(a + 4, "open") || !strcmp(a + 4, "closed"))) {
            dir_opts *o = &dop[a[2] == 'v'];
            if (a[4] == 'o')
                o->open = 1;
            else
                o->closed = 1;
            continue;
        }
        if (!val) {
            fprintf(stderr, "rg2 shape: %s needs a value\n", a);
            return RG2_EXIT_USAGE;
        }
        i++;
        int pi = -1;
        for (int k = 0; d && k < d->n_params; k++)
            if (!strcmp(a + 2, d->param_names[k]))
                pi = k;
        if (pi >= 0) {
            if (parse_one(a, val, &sh.param[pi]))
                return RG2_EXIT_USAGE;
            if ((rc = rg2_cli_check_numbers("shape", a, &sh.param[pi], 1)))
                return rc;
        } else if ((a[2] == 'u' || a[2] == 'v') && a[3] == '-') {
            dir_opts *o = &dop[a[2] == 'v'];
            const char *what = a + 4;
            if (!strcmp(what, "arcs") || !strcmp(what, "segments")) {
                char *end;
                long n = strtol(val, &end, 10);
                if (*end || n < 1 || n > MAXV - 1) {
                    fprintf(stderr, "rg2 shape: %s %s: need an integer 1..%d\n", a, val, MAXV - 1);
                    return RG2_EXIT_USAGE;
                }
                if (what[0] == 'a')
                    o->arcs = (int)n;
                else
                    o->segments = (int)n;
            } else if (!strcmp(what, "angles") || !strcmp(what, "knots")) {
                if ((o->n_vals = rg2_cli_parse_list("shape", a, val, o->vals, MAXV)) < 0)
                    return RG2_EXIT_USAGE;
                if ((rc = rg2_cli_check_numbers("shape", a, o->vals, o->n_vals)))
                    return rc;
                if (what[0] == 'k')
                    o->knots = 1;
                else
                    o->angles = 1;
            } else if (!strcmp(what, "start")) {
                if (parse_one(a, val, &o->start))
                    return RG2_EXIT_USAGE;
                if ((rc = rg2_cli_check_numbers("shape", a, &o->start, 1)))
                    return rc;
                o->has_start = 1;
            } else if (!strcmp(what, "sweep")) {
                if (parse_one(a, val, &o->sweep))
                    return RG2_EXIT_USAGE;
                if ((rc = rg2_cli_check_numbers("shape", a, &o->sweep, 1)))
                    return rc;
                if (!(o->sweep > 0.0)) { /* (it read "arc 0 has opening angle -45 deg", naming no option) */
                    fprintf(stderr, "rg2 shape: %s %s: the range is empty (a sweep of %s <= 0 degrees)\n", a, val,
                            num_text(o->sweep).s);
                    return RG2_EXIT_USAGE;
                }
                o->has_sweep = 1;
            } else if (!strcmp(what, "range")) {
                if (rg2_cli_parse_n("shape", a, val, o->range, 2, "two numbers A,B"))
                    return RG2_EXIT_USAGE;
                if ((rc = rg2_cli_check_numbers("shape", a, o->range, 2)))
                    return rc;
                if (!(o->range[0] < o->range[1])) { /* (it read "equal partition: knot 1 (= 4) is not
                                                      * greater than knot 0 (= 5)", naming no option) */
                    fprintf(stderr, "rg2 shape: %s %s: the range is empty (%s >= %s)\n", a, val,
                            num_text(o->range[0]).s, num_text(o->range[1]).s);
                    return RG2_EXIT_USAGE;
                }
                o->has_range = 1;
            } else
                return shape_unknown_option(d, a);
        } else if (!strcmp(a, "--scale")) {
            int n = rg2_cli_parse_list("shape", a, val, scale, 3);
            if (n < 0) /* (its message printed) */
                return RG2_EXIT_USAGE;
            if (n == 1)
                scale[1] = scale[2] = scale[0];
            else if (n != 3) {
                fprintf(stderr, "rg2 shape: --scale needs 1 or 3 numbers\n");
                return RG2_EXIT_USAGE;
            }
            if ((rc = rg2_cli_check_numbers("shape", a, scale, n)))
                return rc;
            if (scale[0] == 0.0 || scale[1] == 0.0 || scale[2] == 0.0) {
                fprintf(stderr, "rg2 shape: --scale %s: scale factors must be non-zero\n", val);
                return RG2_EXIT_FAIL;
            }
            n_scale = n;
        } else if (!strcmp(a, "--axis") || !strcmp(a, "--center") || !strcmp(a, "--centre")) {
            double *x = a[2] == 'a' ? axis : centre;
            if (rg2_cli_parse_n("shape", a, val, x, 3, "three numbers X,Y,Z"))
                return RG2_EXIT_USAGE;
            if ((rc = rg2_cli_check_numbers("shape", a, x, 3)))
                return rc;
            if (x == axis && axis[0] == 0.0 && axis[1] == 0.0 && axis[2] == 0.0) {
                fprintf(stderr, "rg2 shape: --axis %s: the axis is the zero vector\n", val);
                return RG2_EXIT_FAIL;
            }
            *(x == axis ? &has_axis : &has_centre) = 1;
        } else if (!strcmp(a, "--xform")) {
            if (rg2_cli_parse_n("shape", a, val, xf, 16, "16 numbers (row-major 4x4)"))
                return RG2_EXIT_USAGE;
            if ((rc = rg2_cli_check_numbers("shape", a, xf, 16)))
                return rc;
            has_xform = 1;
        } else if (!strcmp(a, "--samples")) {
            char *end;
            long n = strtol(val, &end, 10);
            if (*end || n < 1 || n > 1000) {
                fprintf(stderr, "rg2 shape: --samples %s: need an integer 1..1000\n", val);
                return RG2_EXIT_USAGE;
            }
            samples = (int)n;
        } else if (is_nurbs && !strcmp(a, "--file")) {
            file = val;
        } else if (is_nurbs && !strcmp(a, "--spec")) {
            spec = val;
        } else
            return shape_unknown_option(d, a);
    }

    rg2_mesh m = {0};
    rg2_surface s = {0};
    rg2_weight_report rep;
    rg2_partition pu, pv;
    double resid = 0.0, size = 0.0;
    rg2_status st;
    if (is_nurbs) {
        if (!file == !spec) {
            fprintf(stderr, "rg2 shape: nurbs needs exactly one of --file F.json or --spec JSON\n");
            return RG2_EXIT_USAGE;
        }
        char *text = NULL;
        rg2_error rerr;
        size_t text_len = 0; /* the file's length: a NUL byte in it is an error, not its end */
        if (file && rg2_read_text(file, &text, &text_len, &rerr)) {
            fprintf(stderr, "rg2 shape: nurbs: cannot read %s\n", rerr.msg);
            return RG2_EXIT_FAIL;
        }
        const char *src = file ? text : spec;
        st = rg2_nurbs_parse(src, file ? text_len : strlen(src), file ? file : "--spec", &m, &err);
        free(text);
        if (st) {
            rc = rg2_cli_report("shape", &err);
            goto out;
        }
    } else {
        if ((rc = make_partition(d->name, d, 0, &dop[0], &pu)) || (rc = make_partition(d->name, d, 1, &dop[1], &pv)))
            goto out;
        double S[16], R[16], T[16];
        rg2_xform_scale(S, scale[0], scale[1], scale[2]);
        rg2_xform_place(R, centre, axis);
        rg2_xform_mul(R, S, T);
        if (has_xform)
            rg2_xform_mul(xf, T, T);
        memcpy(sh.xform, T, sizeof T);
        if (rg2_shape_mesh(&sh, &pu, &pv, &m, &err)) {
            rc = rg2_cli_report("shape", &err);
            goto out;
        }
    }
    size_t patches = (size_t)rg2_scalars_num_segments(&m.su) * (size_t)rg2_scalars_num_segments(&m.sv);
    if (patches > RG2_CLI_MAX_PATCHES) { /* a design's limit, checked before the patches take memory */
        fprintf(stderr, "rg2 shape: %s: %s: %zu patches, more than the limit of %d (as in a design file)\n",
                rg2_status_str(RG2_ELIMIT), is_nurbs ? "nurbs" : d->name, patches, RG2_CLI_MAX_PATCHES);
        rc = RG2_EXIT_FAIL;
        goto out;
    }
    /* the residual's samples, bounded as rg2_check bounds its own (the default 8 stays far below) */
    double residual_samples = (double)patches * (samples + 1.0) * (samples + 1.0);
    if (!is_nurbs && residual_samples > RG2_MAX_CHECK_SAMPLES) {
        fprintf(stderr, "rg2 shape: %s: %s: --samples %d: %zu patches x %d x %d samples = %.0f, more than the limit "
                "of %d: fewer samples\n", rg2_status_str(RG2_ELIMIT), d->name, samples, patches, samples + 1,
                samples + 1, residual_samples, RG2_MAX_CHECK_SAMPLES);
        rc = RG2_EXIT_FAIL;
        goto out;
    }
    /* the range every output mesh of a design must stay in (rg2 build refuses the same) */
    if (rg2_mesh_check_range(&m, is_nurbs ? "nurbs" : d->name, &err) || rg2_surface_build(&m, &s, &err)) {
        rc = rg2_cli_report("shape", &err);
        goto out;
    }
    rg2_surface_weight_report(&s, &rep);
    if (!is_nurbs)
        resid = max_residual(&sh, &s, samples, &size);
    char placed[512] = ""; /* three placements of 3 numbers up to 24 characters each */
    if (n_scale == 1)
        snprintf(placed, sizeof placed, "scale %s", num_text(scale[0]).s);
    else if (n_scale)
        placement_add(placed, sizeof placed, "scale", scale);
    if (has_axis)
        placement_add(placed, sizeof placed, "axis", axis);
    if (has_centre)
        placement_add(placed, sizeof placed, "centre", centre);
    if (has_xform) {
        size_t n = strlen(placed);
        snprintf(placed + n, sizeof placed - n, "%s--xform matrix", n ? ", then the " : "the ");
    }
    if (json)
        print_json(is_nurbs ? NULL : &sh, &pu, &pv, &m, &s, &rep, resid);
    else
        print_summary(is_nurbs ? NULL : &sh, &pu, &pv, placed, &m, &s, &rep, resid, size, samples);
    if (rep.flags & RG2_SHAPE_WARN_WEIGHT)
        fprintf(stderr,
                "rg2 shape: warning: %d %s homogeneous weights <= 0 (min %.6g at patch "
                "%d,%d); STEP/IGES export needs positive weights: use more arcs or knots\n",
                rep.n_nonpositive, rep.n_nonpositive == 1 ? "patch has" : "patches have", rep.min_weight, rep.patch_i,
                rep.patch_j);
out:
    rg2_surface_free(&s);
    rg2_mesh_free(&m);
    return rc;
}
