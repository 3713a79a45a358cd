/* rg2 mesh -- write a design's control meshes (d, W, scalars, provenance) as JSON. */
#include "cli.h"

#include <stdio.h>
#include <string.h>

static void usage(FILE *f)
{
    fprintf(f, "usage: rg2 mesh design.json -o mesh.json\n\n"
               "Reads and builds a design file and writes its output control meshes for other tools:\n"
               "design points d = (p1, p2, p3) / p4 and weights W = p4 (paper eq. 11), the scalars\n"
               "w, b, g of both directions, and which shape every point, scalar and patch came from\n"
               "(docs/design-format.md, \"The mesh file\"); the output name ends in .json. Nothing is\n"
               "written if the design is invalid.\n"
               "Exit codes: 0 ok, 1 invalid design or unwritable output, 2 usage error.\n");
}

int rg2_cmd_mesh(int argc, char **argv)
{
    const char *path = NULL, *out = NULL;
    for (int i = 1; i < argc; i++) {
        if (!strcmp(argv[i], "--help") || !strcmp(argv[i], "-h")) {
            usage(stdout);
            return RG2_EXIT_OK;
        } else if (!strcmp(argv[i], "-o")) {
            if (i + 1 >= argc || out) {
                fprintf(stderr, "rg2 mesh: %s\n", out ? "only one -o" : "-o needs a file name");
                return RG2_EXIT_USAGE;
            }
            out = argv[++i];
        } else if (argv[i][0] == '-' && argv[i][1]) {
            static const char *const aliases[] = {"--output", "-o", "--out", "-o", NULL};
            return rg2_cli_unknown_option("mesh", argv[i], usage, aliases);
        } else if (path) {
            fprintf(stderr, "rg2 mesh: more than one design file ('%s', '%s')\n", path, argv[i]);
            return RG2_EXIT_USAGE;
        } else
            path = argv[i];
    }
    if (!path || !out) {
        fprintf(stderr, "rg2 mesh: %s\n", path ? "missing -o mesh.json" : "missing the design file");
        usage(stderr);
        return RG2_EXIT_USAGE;
    }
    if (rg2_cli_check_outputs("mesh", path, &out, 1))
        return RG2_EXIT_USAGE;
    if (!rg2_cli_has_ext(out, ".json")) {
        fprintf(stderr, "rg2 mesh: output '%s': the control mesh is JSON; give it a .json name (rg2 build writes "
                        "the surfaces as STEP, IGES, ...)\n", out);
        return RG2_EXIT_USAGE;
    }
    rg2_design *d;
    rg2_error err;
    if (rg2_design_load(path, &d, &err))
        return rg2_cli_report("mesh", &err);
    rg2_status st = rg2_design_write_mesh(d, out, &err);
    rg2_design_free(d);
    if (st)
        return rg2_cli_report("mesh", &err);
    return RG2_EXIT_OK;
}
