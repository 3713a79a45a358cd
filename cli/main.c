/* rg2 command line: thin shell over the library (parses arguments, calls, prints). */
#define _POSIX_C_SOURCE 200809L /* sigaction */
#include "cli.h"

#include <errno.h>
#include <signal.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

static const rg2_cli_command commands[] = {
    {"build", "build a design file into surfaces and write them (STEP, IGES, ...)", rg2_cmd_build,
     "--face-per-mesh --ap242 --iges-brep --quiet --help"},
    {"check", "report exactness and G0/G1/G2 gaps of a design; fail on a broken promise", rg2_cmd_check,
     "--json --help"},
    {"render", "render a design as a PNG: shaded, curvature maps, zebra stripes", rg2_cmd_render,
     "--boundaries --mesh --apart --no-tint --no-colorbar --help"},
    {"info", "show a design's meshes, patch counts, exact pieces and transitions", rg2_cmd_info, "--map --help"},
    {"mesh", "write a design's control mesh (d, W, scalars) as JSON", rg2_cmd_mesh, "--help"},
    {"shapes", "list the exact basic shapes with their parameters", rg2_cmd_shapes, "--json --help"},
    {"shape", "build an exact shape or a bi-cubic NURBS into patches", rg2_cmd_shape,
     "--json --help --u-open --v-open --u-closed --v-closed"},
    {"curve", "print the exact Bezier segments of a circle or a control polygon", rg2_cmd_curve,
     "--json --open --closed --help"},
    {"demo", "print a circle's Bezier form and a torus surface summary", rg2_cmd_demo, "--help"},
};

/* The arguments with every "--name=value" split into "--name" "value" (the form GNU tools
 * accept); a flag given a value is a usage error. Returns the new argc, or -1 (message printed;
 * *out NULL when out of memory). The strings are in *out and *names; free both lists with
 * free_split. */
static int split_values(const rg2_cli_command *c, int argc, char **argv, char ***out, char ***names)
{
    *out = calloc((size_t)argc * 2 + 1, sizeof **out);
    *names = calloc((size_t)argc + 1, sizeof **names);
    if (!*out || !*names) {
        fprintf(stderr, "rg2: out of memory\n");
        return -1;
    }
    int n = 0, nn = 0;
    for (int i = 0; i < argc; i++) {
        const char *eq = strncmp(argv[i], "--", 2) ? NULL : strchr(argv[i], '=');
        if (!eq || i == 0) {
            (*out)[n++] = argv[i];
            continue;
        }
        size_t len = (size_t)(eq - argv[i]);
        char *name = malloc(len + 1);
        if (!name) {
            fprintf(stderr, "rg2: out of memory\n");
            return -1;
        }
        memcpy(name, argv[i], len);
        name[len] = 0;
        (*names)[nn++] = name;
        for (const char *f = strstr(c->flags, name); f; f = strstr(f + 1, name))
            if ((f == c->flags || f[-1] == ' ') && (f[len] == ' ' || !f[len])) {
                fprintf(stderr, "rg2 %s: %s takes no value ('%s')\n", c->name, name, argv[i]);
                return -1;
            }
        (*out)[n++] = name;
        (*out)[n++] = (char *)(eq + 1);
    }
    return n;
}

static void free_split(char **out, char **names)
{
    for (int k = 0; names && names[k]; k++)
        free(names[k]);
    free(names);
    free(out);
}

/* The exit code once the output is flushed: a write error on stdout (a full disk, /dev/full, a
 * closed pipe's EPIPE when SIGPIPE is ignored) is a failure, named, never exit 0 with the report
 * lost. */
static int finish_stdout(const char *cmd, int rc)
{
    errno = 0;
    int flushed = fflush(stdout) == 0, e = errno;
    if (flushed && !ferror(stdout))
        return rc;
    fprintf(stderr, "rg2%s%s: cannot write the standard output: %s\n", cmd ? " " : "", cmd ? cmd : "",
            !flushed && e ? strerror(e) : "write error");
    return rc ? rc : RG2_EXIT_FAIL;
}

static void usage(FILE *f)
{
    fprintf(f, "usage: rg2 [--version] [--help] <command> [options]\n\ncommands:\n");
    for (size_t i = 0; i < sizeof commands / sizeof commands[0]; i++)
        fprintf(f, "  %-10s %s\n", commands[i].name, commands[i].help);
    fprintf(f, "\n'rg2 <command> --help' describes a command.\n");
}

/* Every output is written to a new temporary file and renamed when complete; the rg2 command
 * writes each path once, from one thread, so rg2_temp_name says which file that will be. An interrupted run
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
            size_t n = strlen(argv[i + 1]) + 48;
            char *t = malloc(n);
            if (!t)
                return;
            if (rg2_temp_name(argv[i + 1], t, n)) {
                free(t);
                continue;
            }
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
        return finish_stdout(NULL, 0);
    }
    if (!strcmp(argv[1], "--help") || !strcmp(argv[1], "-h") || !strcmp(argv[1], "help")) {
        usage(stdout);
        return finish_stdout(NULL, 0);
    }
    for (size_t i = 0; i < sizeof commands / sizeof commands[0]; i++)
        if (!strcmp(argv[1], commands[i].name)) {
            char **args, **names;
            int n = split_values(&commands[i], argc - 1, argv + 1, &args, &names);
            if (n < 0) {
                free_split(args, names);
                return RG2_EXIT_USAGE;
            }
            guard_outputs(n, args);
            int rc = commands[i].run(n, args);
            free_guards();
            free_split(args, names);
            return finish_stdout(commands[i].name, rc);
        }
    const char *names[sizeof commands / sizeof commands[0]];
    for (size_t i = 0; i < sizeof commands / sizeof commands[0]; i++)
        names[i] = commands[i].name;
    const char *close = rg2_closest_name(argv[1], names, (int)(sizeof names / sizeof names[0]));
    if (close)
        fprintf(stderr, "rg2: unknown command '%s' (did you mean '%s'?)\n", argv[1], close);
    else
        fprintf(stderr, "rg2: unknown command '%s'\n", argv[1]);
    usage(stderr);
    return 2;
}
