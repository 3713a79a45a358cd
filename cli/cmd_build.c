/* rg2 build -- read a design file, build its surfaces, write them in the formats the output
 * file extensions name (through rg2_export_file). */
#include "cli.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#define MAX_OUT 16

static void usage(FILE *f)
{
    fprintf(f, "usage: rg2 build design.json -o out.step [-o out.igs ...] [options]\n\n"
               "Reads a design file (docs/design-format.md), builds its output meshes into G2 rational\n"
               "bi-cubic surfaces and writes them. The format follows each -o extension: .step/.stp,\n"
               ".igs/.iges, .bv, .bez, .obj, .stl, .ply, .glb, .json. Several -o are allowed. A failed build\n"
               "writes nothing and leaves files already there as they were.\n"
               "  --face-per-mesh   STEP/IGES: one B-spline surface per mesh instead of one face per patch\n"
               "  --ap242           STEP: write AP242 instead of AP214\n"
               "  --iges-brep       IGES: a B-rep shell per mesh (faces, shared edges and vertices;\n"
               "                    no sewing needed) instead of untrimmed surfaces; either layout\n"
               "  --density N       triangle meshes: samples per patch edge (default 16)\n"
               "  --surface K       only output surface K (0-based) of the design, e.g. one of several\n"
               "                    variants listed in \"output\"\n"
               "  -q, --quiet       no progress line and no notes: neither the design's (rg2 info lists\n"
               "                    them) nor those on options that no output uses\n"
               "A progress line goes to stderr when it is a terminal.\n"
               "Exit codes: 0 ok, 1 invalid design or write error (message on stderr), 2 usage error.\n");
}

/* STEP and IGES are read by CAD kernels that merge points closer than their tolerance (the
 * files' uncertainty 1e-7 mm, OpenCASCADE's Precision::Confusion 1e-7): below this size
 * (bounding-box diagonal of the control points, mm) a note asks for a larger scale. A torus of
 * diagonal 1.2e-6 came back invalid from OpenCASCADE as plain IGES, one of 1.15e-7 as STEP. */
#define CAD_MIN_SIZE 1e-3

static void note_cad_size(const rg2_surface *surfs, int ns)
{
    double lo[3], hi[3], blo[3] = {0, 0, 0}, bhi[3] = {0, 0, 0};
    int any = 0;
    for (int k = 0; k < ns; k++) {
        if (!rg2_surface_box(&surfs[k], lo, hi))
            continue;
        for (int c = 0; c < 3; c++) {
            blo[c] = any ? (lo[c] < blo[c] ? lo[c] : blo[c]) : lo[c];
            bhi[c] = any ? (hi[c] > bhi[c] ? hi[c] : bhi[c]) : hi[c];
        }
        any = 1;
    }
    double d2 = 0;
    for (int c = 0; c < 3; c++)
        d2 += (bhi[c] - blo[c]) * (bhi[c] - blo[c]);
    if (any && d2 < CAD_MIN_SIZE * CAD_MIN_SIZE)
        fprintf(stderr,
                "rg2 build: note: the surfaces span %.3g mm (bounding-box diagonal); STEP and IGES are in mm, and "
                "CAD kernels merge points closer than 1e-07 mm (the files' uncertainty), so below %g mm they may "
                "read the file as invalid: scale the design up (a \"scale\" placement)\n",
                sqrt(d2), CAD_MIN_SIZE);
}

static void progress(int on, const char *fmt, const char *arg)
{
    if (!on)
        return;
    fprintf(stderr, "\r\033[K");
    if (fmt)
        fprintf(stderr, fmt, arg);
    fflush(stderr);
}

int rg2_cmd_build(int argc, char **argv)
{
    const char *path = NULL, *out[MAX_OUT];
    const char *only_arg = NULL;
    double only_v = -1; /* --surface as given, checked against the design's count once loaded */
    int n_out = 0, quiet = 0, density_set = 0;
    rg2_export_opts opts;
    rg2_export_opts_default(&opts);
    for (int i = 1; i < argc; i++) {
        const char *a = argv[i];
        if (!strcmp(a, "--help") || !strcmp(a, "-h")) {
            usage(stdout);
            return RG2_EXIT_OK;
        } else if (!strcmp(a, "-o")) {
            if (i + 1 >= argc) {
                fprintf(stderr, "rg2 build: -o needs a file name\n");
                return RG2_EXIT_USAGE;
            }
            if (n_out == MAX_OUT) {
                fprintf(stderr, "rg2 build: at most %d outputs\n", MAX_OUT);
                return RG2_EXIT_USAGE;
            }
            out[n_out++] = argv[++i];
        } else if (!strcmp(a, "--face-per-mesh"))
            opts.layout = RG2_STEP_FACE_PER_MESH;
        else if (!strcmp(a, "--ap242"))
            opts.ap242 = 1;
        else if (!strcmp(a, "--iges-brep"))
            opts.iges_brep = 1;
        else if (!strcmp(a, "-q") || !strcmp(a, "--quiet"))
            quiet = 1;
        else if (!strcmp(a, "--density")) {
            if (rg2_cli_int("build", a, i + 1 < argc ? argv[++i] : NULL, 1, 1024, &opts.density))
                return RG2_EXIT_USAGE;
            density_set = 1;
        } else if (!strcmp(a, "--surface")) {
            const char *prev = only_arg;
            only_arg = i + 1 < argc ? argv[++i] : NULL;
            if (rg2_cli_surface_opt("build", prev, only_arg, &only_v))
                return RG2_EXIT_USAGE;
        } else if (a[0] == '-' && a[1]) {
            static const char *const aliases[] = {"--output", "-o", "--out", "-o", NULL};
            return rg2_cli_unknown_option("build", a, usage, aliases);
        } else if (path) {
            fprintf(stderr, "rg2 build: more than one design file ('%s', '%s')\n", path, a);
            return RG2_EXIT_USAGE;
        } else
            path = a;
    }
    if (!path || !n_out) {
        fprintf(stderr, "rg2 build: %s\n", path ? "missing -o output file" : "missing the design file");
        usage(stderr);
        return RG2_EXIT_USAGE;
    }
    if (rg2_cli_check_outputs("build", path, out, n_out))
        return RG2_EXIT_USAGE;
    for (int k = 0; k < n_out; k++) { /* a mistyped extension is refused before the build */
        rg2_error ferr;
        if (rg2_export_format_check(out[k], &ferr)) {
            fprintf(stderr, "rg2 build: %s\n", ferr.msg);
            return RG2_EXIT_USAGE;
        }
    }
    int step = 0, iges = 0;
    if (!quiet) { /* options that no output uses: a note, not an error */
        int tri = 0;
        for (int k = 0; k < n_out; k++) {
            step |= rg2_cli_has_ext(out[k], ".step") || rg2_cli_has_ext(out[k], ".stp");
            iges |= rg2_cli_has_ext(out[k], ".igs") || rg2_cli_has_ext(out[k], ".iges");
            tri |= rg2_cli_has_ext(out[k], ".obj") || rg2_cli_has_ext(out[k], ".stl") ||
                   rg2_cli_has_ext(out[k], ".ply") || rg2_cli_has_ext(out[k], ".glb");
        }
        if (opts.layout == RG2_STEP_FACE_PER_MESH && !step && !iges)
            rg2_cli_no_effect("build", "--face-per-mesh", "no STEP or IGES output");
        if (opts.ap242 && !step)
            rg2_cli_no_effect("build", "--ap242", "no STEP output");
        if (opts.iges_brep && !iges)
            rg2_cli_no_effect("build", "--iges-brep", "no IGES output");
        if (density_set && !tri)
            rg2_cli_no_effect("build", "--density", "no triangle mesh output: .obj, .stl, .ply or .glb");
    }
    int tty = !quiet && isatty(2);
    progress(tty, "rg2 build: reading and building %s", path);
    rg2_design *d;
    rg2_error err;
    if (rg2_design_load(path, &d, &err)) {
        progress(tty, NULL, NULL);
        return rg2_cli_report("build", &err);
    }
    if (!quiet) {
        progress(tty, NULL, NULL);
        for (int k = 0; k < rg2_design_num_notes(d); k++)
            fprintf(stderr, "rg2 build: note: %s\n", rg2_design_note(d, k));
    }
    int ns = rg2_design_num_surfaces(d);
    if (rg2_cli_surface_in("build", only_arg, only_v, ns)) {
        rg2_design_free(d);
        progress(tty, NULL, NULL);
        return RG2_EXIT_USAGE; /* an option value out of its range */
    }
    int first = 0; /* --surface K: surface K alone */
    if (only_v >= 0) {
        first = (int)only_v;
        ns = 1;
    }
    rg2_surface *surfs = calloc((size_t)ns, sizeof *surfs);
    if (!surfs) {
        rg2_design_free(d);
        progress(tty, NULL, NULL);
        fprintf(stderr, "rg2 build: out of memory\n");
        return RG2_EXIT_FAIL;
    }
    for (int k = 0; k < ns; k++)
        surfs[k] = *rg2_design_surface(d, first + k); /* shallow views; the design owns the data */
    if (step || iges)
        note_cad_size(surfs, ns);
    int rc = RG2_EXIT_OK;
    progress(tty, n_out > 1 ? "rg2 build: writing %s and the other outputs" : "rg2 build: writing %s", out[0]);
    /* all or nothing: the files are renamed into place only when every one is written */
    if (rg2_export_files(surfs, ns, out, n_out, &opts, NULL, &err)) {
        progress(tty, NULL, NULL);
        const char *at = strstr(err.msg, ": surface ");
        int sk;
        if (at && sscanf(at, ": surface %d", &sk) == 1 && sk >= 0 && sk < ns) {
            /* say which mesh surface k is (surfs[k] is the design's first + k); printed after the
             * message, not into its buffer, which a long path may have filled */
            fprintf(stderr, "rg2 build: %s: %s", rg2_status_str(err.code), err.msg);
            if (only_v >= 0)
                fprintf(stderr, " (--surface %d: mesh '%s')\n", first, rg2_design_mesh_name(d, first + sk));
            else
                fprintf(stderr, " (surface %d is mesh '%s')\n", sk, rg2_design_mesh_name(d, sk));
            rc = RG2_EXIT_FAIL;
        } else {
            rc = rg2_cli_report("build", &err);
        }
    }
    progress(tty, NULL, NULL);
    free(surfs);
    rg2_design_free(d);
    return rc;
}
