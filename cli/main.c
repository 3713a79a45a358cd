/* rg2 command line: thin shell over the library (parses arguments, calls, prints). */
#include "cli.h"

#include <stdio.h>
#include <string.h>

static const rg2_cli_command commands[] = {
    {"build", "build a design file into surfaces and write them (STEP, IGES, ...)", rg2_cmd_build},
    {"check", "report exactness and G0/G1/G2 gaps of a design; fail on a broken promise", rg2_cmd_check},
    {"render", "render a design as a PNG: shaded, curvature maps, zebra stripes", rg2_cmd_render},
    {"info", "show a design's meshes, patch counts, exact pieces and transitions", rg2_cmd_info},
    {"mesh", "write a design's control mesh (d, W, scalars) as JSON", rg2_cmd_mesh},
    {"shapes", "list the exact basic shapes with their parameters", rg2_cmd_shapes},
    {"shape", "build an exact shape or a bi-cubic NURBS into patches", rg2_cmd_shape},
    {"curve", "print the exact Bezier segments of a circle or a control polygon", rg2_cmd_curve},
    {"demo", "print a circle's Bezier form and a torus surface summary", rg2_cmd_demo},
};

static void usage(FILE *f)
{
    fprintf(f, "usage: rg2 [--version] [--help] <command> [options]\n\ncommands:\n");
    for (size_t i = 0; i < sizeof commands / sizeof commands[0]; i++)
        fprintf(f, "  %-10s %s\n", commands[i].name, commands[i].help);
    fprintf(f, "\n'rg2 <command> --help' describes a command.\n");
}

int main(int argc, char **argv)
{
    if (argc < 2) {
        usage(stderr);
        return 2;
    }
    if (!strcmp(argv[1], "--version") || !strcmp(argv[1], "-V")) {
        printf("rg2 %s\n", rg2_version());
        return 0;
    }
    if (!strcmp(argv[1], "--help") || !strcmp(argv[1], "-h") || !strcmp(argv[1], "help")) {
        usage(stdout);
        return 0;
    }
    for (size_t i = 0; i < sizeof commands / sizeof commands[0]; i++)
        if (!strcmp(argv[1], commands[i].name))
            return commands[i].run(argc - 1, argv + 1);
    fprintf(stderr, "rg2: unknown command '%s'\n", argv[1]);
    usage(stderr);
    return 2;
}
