/* rg2 curve -- the exact Bezier segments of a circle partition or a control polygon. */
#include "cli.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#define MAXV (RG2_CLI_MAX_ARCS + 1) /* values of a list: n arcs, or n + 1 knots */

static void help(void)
{
    printf("usage: rg2 curve [--arcs N | --angles A1,A2,...] [--radius R] [--start DEG] [--open] [--json]\n"
           "       rg2 curve --points X,Y[,Z..];X,Y;... --dim D [--closed] [--w ...] [--b ...] [--g ...] [--json]\n\n"
           "Prints the rational cubic Bezier segments (4 control points, weights 1,w,w,1) of\n"
           "  - a circle of radius R split into N equal arcs, or into arcs with the given opening\n"
           "    angles in degrees (each in (0,180); closed: they sum to 360; --open: n+1 angles for\n"
           "    n control points, the first and last two carry data only), or\n"
           "  - the G2 spline of a control polygon with leg weights w, junction scalars b, g\n"
           "    (defaults 1, 1, 0: the uniform cubic B-spline). Open: n+1 weights w_-1..w_n-1.\n"
           "Every number is 0 or of magnitude 1e-100..1e100 (as in design files); R > 0.\n");
}

static void print_curve(const rg2_curve *c, int json)
{
    if (json) {
        printf("{\"dim\": %d, \"closed\": %s, \"segments\": [", c->dim, c->closed ? "true" : "false");
        for (int k = 0; k < c->n_segments; k++) {
            printf("%s\n  {\"w\": [1, %.17g, %.17g, 1], \"points\": [", k ? "," : "", c->w[k], c->w[k]);
            for (int r = 0; r < 4; r++) {
                printf("%s[", r ? ", " : "");
                for (int d = 0; d < c->dim; d++)
                    printf("%s%.17g", d ? ", " : "", c->bez[(k * 4 + r) * c->dim + d]);
                printf("]");
            }
            printf("]}");
        }
        printf("\n]}\n");
        return;
    }
    printf("%d rational cubic Bezier segments (dim %d, %s)\n", c->n_segments, c->dim,
           c->closed ? "closed" : "open");
    for (int k = 0; k < c->n_segments; k++) {
        printf("segment %d  weights 1 %.17g %.17g 1\n", k, c->w[k], c->w[k]);
        for (int r = 0; r < 4; r++) {
            printf("  b%d", r);
            for (int d = 0; d < c->dim; d++)
                printf(" %.17g", c->bez[(k * 4 + r) * c->dim + d]);
            printf("\n");
        }
    }
}

int rg2_cmd_curve(int argc, char **argv)
{
    static double angles[MAXV], pts[MAXV * 4], w[MAXV], b[MAXV], g[MAXV];
    int n_angles = 0, n_pts = -1, dim = 2, closed = -1, json = 0, open = 0;
    int nw = -1, nb = -1, ng = -1;
    double radius = 1.0, start = 0.0;
    const char *circle_opt = NULL, *poly_opt = NULL, *arcs_opt = NULL; /* the first given of each kind */
    for (int i = 1; i < argc; i++) {
        const char *a = argv[i];
        const char *val = i + 1 < argc ? argv[i + 1] : NULL;
#define NEED()                                                                 \
    do {                                                                       \
        if (!val) {                                                            \
            fprintf(stderr, "rg2 curve: %s needs a value\n", a);               \
            return RG2_EXIT_USAGE;                                             \
        }                                                                      \
        i++;                                                                   \
    } while (0)
        if (!strcmp(a, "--help") || !strcmp(a, "-h")) {
            help();
            return 0;
        } else if (!strcmp(a, "--json")) {
            json = 1;
        } else if (!strcmp(a, "--open")) {
            open = 1;
        } else if (!strcmp(a, "--closed")) {
            closed = 1;
        } else if (!strcmp(a, "--arcs")) {
            NEED();
            if (arcs_opt && strcmp(arcs_opt, a)) {
                fprintf(stderr, "rg2 curve: give --arcs (a count) or --angles (the arcs' angles), not both\n");
                return RG2_EXIT_USAGE;
            }
            arcs_opt = a;
            char *end;
            long n = strtol(val, &end, 10);
            if (end == val || *end || n < 3 || n > MAXV - 1) {
                fprintf(stderr, "rg2 curve: --arcs %s: need 3..%d arcs\n", val, MAXV - 1);
                return RG2_EXIT_USAGE;
            }
            for (int k = 0; k < n; k++)
                angles[k] = 360.0 / (double)n;
            n_angles = (int)n;
        } else if (!strcmp(a, "--angles")) {
            NEED();
            if (arcs_opt && strcmp(arcs_opt, a)) {
                fprintf(stderr, "rg2 curve: give --arcs (a count) or --angles (the arcs' angles), not both\n");
                return RG2_EXIT_USAGE;
            }
            arcs_opt = a;
            if ((n_angles = rg2_cli_parse_list("curve", a, val, angles, MAXV)) < 0)
                return RG2_EXIT_USAGE;
            if (rg2_cli_check_numbers("curve", a, angles, n_angles))
                return RG2_EXIT_USAGE;
            if (n_angles == 0) { /* not the default circle: an empty list is a mistake */
                fprintf(stderr, "rg2 curve: --angles '%s': no angles given\n", val);
                return RG2_EXIT_USAGE;
            }
        } else if (!strcmp(a, "--radius")) {
            NEED();
            if (rg2_cli_number("curve", a, val, "a number", &radius) || rg2_cli_check_numbers("curve", a, &radius, 1))
                return RG2_EXIT_USAGE;
            if (!(radius > 0.0)) { /* (0 printed all-zero segments, -1 a reflected circle) */
                fprintf(stderr, "rg2 curve: --radius %s: the radius must be > 0\n", val);
                return RG2_EXIT_USAGE;
            }
        } else if (!strcmp(a, "--start")) {
            NEED();
            if (rg2_cli_number("curve", a, val, "a number", &start) || rg2_cli_check_numbers("curve", a, &start, 1))
                return RG2_EXIT_USAGE;
        } else if (!strcmp(a, "--dim")) {
            NEED();
            char *end;
            long d = strtol(val, &end, 10);
            if (end == val || *end || d < 1 || d > 4) {
                fprintf(stderr, "rg2 curve: --dim %s: need an integer 1..4\n", val);
                return RG2_EXIT_USAGE;
            }
            dim = (int)d;
        } else if (!strcmp(a, "--points")) {
            NEED();
            if ((n_pts = rg2_cli_parse_list("curve", a, val, pts, MAXV * 4)) < 0 ||
                rg2_cli_check_numbers("curve", a, pts, n_pts))
                return RG2_EXIT_USAGE;
        } else if (!strcmp(a, "--w")) {
            NEED();
            if ((nw = rg2_cli_parse_list("curve", a, val, w, MAXV)) < 0 || rg2_cli_check_numbers("curve", a, w, nw))
                return RG2_EXIT_USAGE;
        } else if (!strcmp(a, "--b")) {
            NEED();
            if ((nb = rg2_cli_parse_list("curve", a, val, b, MAXV)) < 0 || rg2_cli_check_numbers("curve", a, b, nb))
                return RG2_EXIT_USAGE;
        } else if (!strcmp(a, "--g")) {
            NEED();
            if ((ng = rg2_cli_parse_list("curve", a, val, g, MAXV)) < 0 || rg2_cli_check_numbers("curve", a, g, ng))
                return RG2_EXIT_USAGE;
        } else {
            static const char *const opts[] = {"--arcs", "--angles", "--radius", "--start", "--points", "--dim",
                                               "--w",    "--b",      "--g",      "--open",  "--closed", "--json",
                                               "--help"};
            return rg2_cli_unknown_option_of("curve", a, opts, (int)(sizeof opts / sizeof *opts));
        }
#undef NEED
        /* the options of one kind of curve only: the other kind ignored them */
        static const char *const circ[] = {"--arcs", "--angles", "--radius", "--start"};
        static const char *const poly[] = {"--points", "--dim", "--w", "--b", "--g"};
        for (size_t k = 0; k < sizeof circ / sizeof *circ; k++)
            if (!strcmp(a, circ[k]) && !circle_opt)
                circle_opt = a;
        for (size_t k = 0; k < sizeof poly / sizeof *poly; k++)
            if (!strcmp(a, poly[k]) && !poly_opt)
                poly_opt = a;
    }
    if (open && closed > 0) {
        fprintf(stderr, "rg2 curve: --open and --closed contradict each other\n");
        return RG2_EXIT_USAGE;
    }
    if (circle_opt && poly_opt) {
        fprintf(stderr, "rg2 curve: %s is for a circle and %s for a control polygon: give one or the other\n",
                circle_opt, poly_opt);
        return RG2_EXIT_USAGE;
    }
    if (poly_opt && n_pts < 0) {
        fprintf(stderr, "rg2 curve: %s needs --points (it is for a control polygon)\n", poly_opt);
        return RG2_EXIT_USAGE;
    }
    rg2_error err = {0};
    rg2_scalars s = {0};
    rg2_curve c = {0};
    double *cp = NULL;
    int rc = RG2_EXIT_OK, n;
    if (n_pts >= 0) {
        if (n_pts % dim) {
            fprintf(stderr, "rg2 curve: --points has %d numbers, not a multiple of --dim %d\n", n_pts, dim);
            return RG2_EXIT_USAGE;
        }
        n = n_pts / dim;
        if (closed < 0)
            closed = 0;
        if (rg2_scalars_init(&s, n, closed, &err))
            return rg2_cli_report("curve", &err);
        int need_w = rg2_scalars_num_w(&s);
        if ((nw >= 0 && nw != need_w) || (nb >= 0 && nb != n) || (ng >= 0 && ng != n)) {
            fprintf(stderr, "rg2 curve: %d %s points need %d weights (--w) and %d values of --b and --g\n",
                    n, closed ? "closed" : "open", need_w, n);
            rg2_scalars_free(&s);
            return RG2_EXIT_USAGE;
        }
        if (nw >= 0)
            memcpy(s.w, w, sizeof(double) * (size_t)nw);
        if (nb >= 0)
            memcpy(s.b, b, sizeof(double) * (size_t)nb);
        if (ng >= 0)
            memcpy(s.g, g, sizeof(double) * (size_t)ng);
        cp = pts;
    } else {
        if (n_angles == 0) {
            for (int k = 0; k < 4; k++)
                angles[k] = 90.0;
            n_angles = 4;
        }
        closed = !open;
        /* counted in arcs, as given (the library counts control points: n, or n - 1 open) */
        if (n_angles < (closed ? 3 : 5)) {
            fprintf(stderr,
                    closed ? "rg2 curve: %d arc%s given; a closed circle (the default without --open) needs at "
                             "least 3 arcs\n"
                           : "rg2 curve: --open: %d arc%s given; an open curve needs at least 5 arcs (the "
                             "first and last two carry data only, so 5 arcs give one segment)\n",
                    n_angles, n_angles == 1 ? "" : "s");
            return RG2_EXIT_FAIL;
        }
        for (int k = 0; k < n_angles; k++)
            angles[k] *= M_PI / 180.0;
        if (rg2_scalars_from_angles(&s, angles, n_angles, closed, &err))
            return rg2_cli_report("curve", &err);
        n = s.n;
        dim = 2;
        cp = malloc(sizeof(double) * 2 * (size_t)n);
        if (!cp || rg2_circle_coeffs(angles, n_angles, closed, start * M_PI / 180.0, cp, &err)) {
            if (!cp)
                err.code = RG2_ENOMEM, snprintf(err.msg, sizeof err.msg, "out of memory");
            rc = rg2_cli_report("curve", &err);
            goto out;
        }
        for (int k = 0; k < 2 * n; k++)
            cp[k] *= radius;
    }
    if (rg2_curve_build(dim, cp, &s, &c, &err)) {
        rc = rg2_cli_report("curve", &err);
        goto out;
    }
    print_curve(&c, json);
out:
    if (cp != pts)
        free(cp);
    rg2_curve_free(&c);
    rg2_scalars_free(&s);
    return rc;
}
