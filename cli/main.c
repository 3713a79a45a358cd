/* rg2 command line: thin shell over the library (parses arguments, calls, prints). */
#define _POSIX_C_SOURCE 200809L /* sigaction */
#include "cli.h"

#include <signal.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

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

/* Every output is written to "<path>.tmp" and renamed when complete. An interrupted run
 * (Ctrl-C, kill, a closed terminal) removes those temporary files before it dies, so nothing
 * half-written is left behind; the paths are taken from the -o options up front, as only
 * async-signal-safe calls (unlink, raise) may run in the handler. */
#define MAX_TMP 64
static char *tmp_paths[MAX_TMP];
static volatile sig_atomic_t n_tmp;

static void on_signal(int sig)
{
    for (int i = 0; i < n_tmp; i++)
        unlink(tmp_paths[i]);
    signal(sig, SIG_DFL);
    raise(sig);
}

static void guard_outputs(int argc, char **argv)
{
    for (int i = 1; i + 1 < argc && n_tmp < MAX_TMP; i++)
        if (!strcmp(argv[i], "-o")) {
            size_t n = strlen(argv[i + 1]);
            char *t = malloc(n + 5);
            if (!t)
                return;
            memcpy(t, argv[i + 1], n);
            memcpy(t + n, ".tmp", 5);
            tmp_paths[n_tmp] = t;
            n_tmp = n_tmp + 1;
        }
    if (!n_tmp)
        return;
    struct sigaction sa;
    memset(&sa, 0, sizeof sa);
    sa.sa_handler = on_signal;
    sigemptyset(&sa.sa_mask);
    const int sigs[] = {SIGINT, SIGTERM, SIGHUP, SIGQUIT};
    for (size_t k = 0; k < sizeof sigs / sizeof sigs[0]; k++) {
        struct sigaction old;
        if (sigaction(sigs[k], NULL, &old) == 0 && old.sa_handler != SIG_IGN) /* (nohup, & jobs) */
            sigaction(sigs[k], &sa, NULL);
    }
}

static void free_guards(void)
{
    int n = n_tmp;
    n_tmp = 0;
    for (int i = 0; i < n; i++)
        free(tmp_paths[i]);
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
        if (!strcmp(argv[1], commands[i].name)) {
            guard_outputs(argc, argv);
            int rc = commands[i].run(argc - 1, argv + 1);
            free_guards();
            return rc;
        }
    fprintf(stderr, "rg2: unknown command '%s'\n", argv[1]);
    usage(stderr);
    return 2;
}
