/* rg2 render -- per-pixel exact pictures of a design (rg2_render_png). */
#include "cli.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

static void usage(FILE *f)
{
    fprintf(f, "usage: rg2 render design.json -o pic.png [options]\n\n"
               "Renders the built surfaces of a design as an 8-bit RGB PNG. Every pixel is computed from\n"
               "the exact surface point on its centre ray (not interpolated across triangles).\n"
               "  --mode M            shaded (default), mean, gauss or zebra\n"
               "  --size WxH          image size (default 800x600)\n"
               "  --azimuth A         view azimuth about +z in degrees (default 35)\n"
               "  --elevation E       view elevation in degrees, -90..90 (default 25)\n"
               "  --distance D        eye distance from the view centre, > 0 (default: fit to view)\n"
               "  --fov F             vertical field of view in degrees, in (1, 170) (default 30)\n"
               "  --range lo,hi       curvature colour range (default: 2%%..98%% robust range;\n"
               "                      Gauss symmetric about 0)\n"
               "  --stripes N         zebra: stripe pairs per turn of the reflected ray, 1..1000 (default 12)\n"
               "  --boundaries        draw the patch boundaries\n"
               "  --mesh              overlay the control meshes\n"
               "  --no-tint           shaded: do not tint exact pieces by their shape\n"
               "  --no-colorbar       curvature modes: no colour bar\n"
               "  --surface K         only output surface K (0-based) of the design\n"
               "  --apart             lay the output surfaces out apart, in a grid across the view\n"
               "                      (surface 0 top left); for outputs that overlap\n"
               "  --threads N         OpenMP threads (default: all); the picture does not depend on it\n"
               "Exit codes: 0 ok, 1 invalid design or write error, 2 usage error.\n");
}

static int number(const char *opt, int argc, char **argv, int *i, double *v)
{
    if (rg2_cli_number("render", opt, *i + 1 < argc ? argv[*i + 1] : NULL, "a number", v))
        return -1;
    (*i)++;
    return 0;
}

/* A number option within [lo, hi] (open ends where lo_open / hi_open): a bad value is a usage
 * error (exit 2), like --size and --threads, not left to the renderer. */
static int ranged(const char *opt, int argc, char **argv, int *i, double *v, double lo, int lo_open, double hi,
                  int hi_open, const char *what)
{
    if (number(opt, argc, argv, i, v))
        return -1;
    if ((lo_open ? !(*v > lo) : !(*v >= lo)) || (hi_open ? !(*v < hi) : !(*v <= hi))) {
        fprintf(stderr, "rg2 render: %s %s: %s\n", opt, argv[*i], what);
        return -1;
    }
    return 0;
}

/* Two output surfaces whose control boxes overlap by half or more along every axis (relative to
 * the smaller extent) are drawn on top of each other: say so, and how to see them. */
static void overlap_note(const rg2_surface *surfs, int n)
{
    double(*box)[2][3] = calloc((size_t)n, sizeof *box);
    if (!box)
        return;
    for (int s = 0; s < n; s++)
        if (!rg2_surface_box(&surfs[s], box[s][0], box[s][1]))
            box[s][0][0] = NAN; /* no control point of positive weight: compared with none */
    int a, b;
    if (rg2_cli_first_overlap((const double(*)[2][3])box, n, &a, &b, NULL))
        fprintf(stderr,
                "rg2 render: note: output surfaces %d and %d overlap, and are drawn on top of each "
                "other; --apart lays the surfaces out side by side, --surface K draws one\n",
                b, a);
    free(box);
}

int rg2_cmd_render(int argc, char **argv)
{
    const char *path = NULL, *out = NULL;
    int only = -1, stripes_set = 0, tint_set = 0, colorbar_set = 0;
    double only_v = -1; /* --surface as given, checked against the design's count once loaded */
    const char *only_arg = NULL;
    rg2_render_opts o;
    rg2_render_opts_default(&o);
    for (int i = 1; i < argc; i++) {
        const char *a = argv[i];
        if (!strcmp(a, "--help") || !strcmp(a, "-h")) {
            usage(stdout);
            return RG2_EXIT_OK;
        } else if (!strcmp(a, "-o")) {
            if (i + 1 >= argc || out) { /* one picture per run, as rg2 mesh writes one file */
                fprintf(stderr, "rg2 render: %s\n", out ? "only one -o (one picture per run)" : "-o needs a file name");
                return RG2_EXIT_USAGE;
            }
            out = argv[++i];
        } else if (!strcmp(a, "--mode")) {
            const char *m = i + 1 < argc ? argv[++i] : "";
            if (!strcmp(m, "shaded"))
                o.mode = RG2_RENDER_SHADED;
            else if (!strcmp(m, "mean"))
                o.mode = RG2_RENDER_MEAN;
            else if (!strcmp(m, "gauss"))
                o.mode = RG2_RENDER_GAUSS;
            else if (!strcmp(m, "zebra"))
                o.mode = RG2_RENDER_ZEBRA;
            else {
                fprintf(stderr, "rg2 render: --mode '%s': expected shaded, mean, gauss or zebra\n", m);
                return RG2_EXIT_USAGE;
            }
        } else if (!strcmp(a, "--size")) {
            /* strtol, not sscanf's %d: that wrapped 4294967312 to 16; each number starts with a digit
             * (strtol alone takes a sign or blanks) */
            long w = 0, h = 0;
            char *end = NULL;
            if (i + 1 < argc) {
                end = argv[i + 1];
                if (*end >= '0' && *end <= '9')
                    w = strtol(end, &end, 10);
                if (w && *end == 'x' && end[1] >= '0' && end[1] <= '9')
                    h = strtol(end + 1, &end, 10);
            }
            if (i + 1 >= argc || *end || w < 16 || h < 16 || w > 8192 || h > 8192) {
                fprintf(stderr, "rg2 render: --size needs WxH, each 16..8192 (e.g. 800x600)%s%s%s\n",
                        i + 1 < argc ? ", not '" : "", i + 1 < argc ? argv[i + 1] : "", i + 1 < argc ? "'" : "");
                return RG2_EXIT_USAGE;
            }
            o.width = (int)w;
            o.height = (int)h;
            i++;
        } else if (!strcmp(a, "--azimuth")) {
            if (number(a, argc, argv, &i, &o.azimuth))
                return RG2_EXIT_USAGE;
        } else if (!strcmp(a, "--elevation")) {
            if (ranged(a, argc, argv, &i, &o.elevation, -90, 0, 90, 0, "the elevation must lie in [-90, 90] degrees"))
                return RG2_EXIT_USAGE;
        } else if (!strcmp(a, "--distance")) {
            if (ranged(a, argc, argv, &i, &o.distance, 0, 1, 1e100, 0,
                       "the eye distance must be > 0 and at most 1e100 (leave it out to fit the view)"))
                return RG2_EXIT_USAGE;
        } else if (!strcmp(a, "--fov")) {
            if (ranged(a, argc, argv, &i, &o.fov, 1, 1, 170, 1, "the field of view must lie in (1, 170) degrees"))
                return RG2_EXIT_USAGE;
        } else if (!strcmp(a, "--stripes")) {
            if (ranged(a, argc, argv, &i, &o.stripes, 1, 0, 1000, 0, "needs 1..1000 stripe pairs"))
                return RG2_EXIT_USAGE;
            if (o.stripes != floor(o.stripes)) { /* the renderer rounds: 2.5 drew 3 pairs, silently */
                fprintf(stderr, "rg2 render: --stripes %s: needs a whole number of stripe pairs, 1..1000\n", argv[i]);
                return RG2_EXIT_USAGE;
            }
            stripes_set = 1;
        } else if (!strcmp(a, "--threads")) {
            if (rg2_cli_int("render", a, i + 1 < argc ? argv[++i] : NULL, 1, 1024, &o.threads))
                return RG2_EXIT_USAGE;
        } else if (!strcmp(a, "--surface")) {
            const char *prev = only_arg;
            only_arg = i + 1 < argc ? argv[++i] : NULL;
            if (rg2_cli_surface_opt("render", prev, only_arg, &only_v))
                return RG2_EXIT_USAGE;
        } else if (!strcmp(a, "--range")) {
            if (rg2_cli_parse_n("render", "--range", i + 1 < argc ? argv[i + 1] : "", o.range, 2, "lo,hi"))
                return RG2_EXIT_USAGE;
            if (!(o.range[0] < o.range[1]) || !isfinite(o.range[1] - o.range[0])) {
                fprintf(stderr, "rg2 render: --range %s: needs lo < hi, with hi - lo a finite number\n", argv[i + 1]);
                return RG2_EXIT_USAGE;
            }
            o.range_set = 1;
            i++;
        } else if (!strcmp(a, "--boundaries"))
            o.boundaries = 1;
        else if (!strcmp(a, "--mesh"))
            o.mesh = 1;
        else if (!strcmp(a, "--apart"))
            o.apart = 1;
        else if (!strcmp(a, "--no-tint"))
            o.tint = 0, tint_set = 1;
        else if (!strcmp(a, "--no-colorbar"))
            o.colorbar = 0, colorbar_set = 1;
        else if (a[0] == '-' && a[1]) {
            static const char *const aliases[] = {"--width", "--size WxH", "--height", "--size WxH",
                                                   "--resolution", "--size WxH", "--output", "-o",
                                                   "--out", "-o", "--view", "--azimuth A --elevation E",
                                                   "--angle", "--azimuth A --elevation E",
                                                   "--zebra", "--mode zebra", "--mean", "--mode mean",
                                                   "--gauss", "--mode gauss", "--gaussian", "--mode gauss",
                                                   "--curvature", "--mode mean or --mode gauss",
                                                   "--shaded", "--mode shaded", NULL};
            return rg2_cli_unknown_option("render", a, usage, aliases);
        } else if (path) {
            fprintf(stderr, "rg2 render: more than one design file ('%s', '%s')\n", path, a);
            return RG2_EXIT_USAGE;
        } else
            path = a;
    }
    if (!path || !out) {
        fprintf(stderr, "rg2 render: need a design file and -o pic.png\n");
        usage(stderr);
        return RG2_EXIT_USAGE;
    }
    if (rg2_cli_check_outputs("render", path, &out, 1))
        return RG2_EXIT_USAGE;
    if (!rg2_cli_has_ext(out, ".png")) {
        fprintf(stderr, "rg2 render: output '%s': the picture is a PNG; give it a .png name\n", out);
        return RG2_EXIT_USAGE;
    }
    int curv = o.mode == RG2_RENDER_MEAN || o.mode == RG2_RENDER_GAUSS;
    if (stripes_set && o.mode != RG2_RENDER_ZEBRA) /* options this mode does not use: a note */
        rg2_cli_no_effect("render", "--stripes", "it sets the zebra mode's stripes");
    if (o.range_set && !curv)
        rg2_cli_no_effect("render", "--range", "it sets the mean and gauss modes' colours");
    if (colorbar_set && !curv)
        rg2_cli_no_effect("render", "--no-colorbar", "only the mean and gauss modes draw a colour bar");
    if (tint_set && o.mode != RG2_RENDER_SHADED)
        rg2_cli_no_effect("render", "--no-tint", "only the shaded mode tints");
    if (curv && o.colorbar && !(o.width > 220 && o.height >= 120)) /* render.c: BAR_MARGIN, BAR_MIN_HEIGHT */
        fprintf(stderr, "rg2 render: note: no colour bar at %dx%d (it needs at least 221x120 pixels)\n", o.width,
                o.height);
    rg2_design *d = NULL;
    rg2_surface *surfs = NULL;
    rg2_mesh *meshes = NULL;
    int n = 0, rc = rg2_cli_load_surfaces("render", path, &d, &surfs, &meshes, &n);
    if (!rc && rg2_cli_surface_in("render", only_arg, only_v, n))
        rc = RG2_EXIT_USAGE; /* an option value out of its range, like --size */
    else if (only_v >= 0)
        only = (int)only_v;
    if (!rc && only < 0 && !o.apart && n > 1)
        overlap_note(surfs, n);
    if (!rc && o.apart && (only >= 0 || n == 1))
        rg2_cli_no_effect("render", "--apart", "one surface to draw");
    if (!rc) {
        rg2_error err = {0};
        rg2_image img;
        if (only >= 0 ? rg2_render(surfs + only, 1, meshes + only, &o, &img, &err)
                      : rg2_render(surfs, n, meshes, &o, &img, &err))
            rc = rg2_cli_report("render", &err);
        else {
            if (rg2_image_write_png(&img, out, &err))
                rc = rg2_cli_report("render", &err);
            else if (img.foreground == 0) /* a blank picture, silently (--distance 1e6) */
                fprintf(stderr, "rg2 render: note: no pixel shows the surface (it is smaller than a pixel or out of the "
                                "view: see --distance)\n");
            rg2_image_free(&img);
        }
    }
    free(surfs);
    free(meshes);
    rg2_design_free(d);
    return rc;
}
