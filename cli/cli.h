/* cli.h -- the rg2 command's subcommands and shared argument helpers. */
#ifndef RG2_CLI_H
#define RG2_CLI_H

#include "rg2.h"

#include <stdio.h>

#ifndef M_PI
#define M_PI 3.14159265358979323846
#endif

typedef struct {
    const char *name;
    const char *help;
    int (*run)(int argc, char **argv); /* argv[0] is the command name */
    const char *flags; /* its "--" options that take no value, space-separated; every other
                        * "--name=value" is passed to it as "--name" "value" */
} rg2_cli_command;

/* Limits a design file has (README "Size limits"), kept by rg2 shape and rg2 curve too: arcs or
 * knot intervals per direction, and patches of one output. */
#define RG2_CLI_MAX_ARCS 100000
#define RG2_CLI_MAX_PATCHES 1000000

/* Exit codes of the rg2 command. */
enum { RG2_EXIT_OK = 0, RG2_EXIT_FAIL = 1, RG2_EXIT_USAGE = 2, RG2_EXIT_CHECK = 3 };

/* Whether two boxes ({lo, hi} x {x, y, z}) overlap by half or more of the smaller extent along
 * every axis (cli/overlap.c), and the first pair (a, b), b < a, in the order a = 1, 2, ..., b = 0
 * .. a - 1, of boxes that do (boxes with a NaN first coordinate left out): 1 and the pair, or 0.
 * compared (nullable) gets the number of pairs it compared. */
int rg2_cli_box_overlap(const double (*A)[3], const double (*B)[3]);
int rg2_cli_first_overlap(const double (*box)[2][3], int n, int *a, int *b, long *compared);

int rg2_cmd_curve(int argc, char **argv);
int rg2_cmd_demo(int argc, char **argv);
int rg2_cmd_build(int argc, char **argv);
int rg2_cmd_info(int argc, char **argv);
int rg2_cmd_mesh(int argc, char **argv);
int rg2_cmd_shapes(int argc, char **argv);
int rg2_cmd_shape(int argc, char **argv);
int rg2_cmd_render(int argc, char **argv);
int rg2_cmd_check(int argc, char **argv);
/* Load a design and shallow-copy its surfaces and meshes into arrays (free them, then the
 * design); returns an exit code, message printed. */
int rg2_cli_load_surfaces(const char *cmd, const char *path, rg2_design **d, rg2_surface **surfs,
                          rg2_mesh **meshes, int *n);

/* Parse "a,b,c" into at most max doubles; returns the count or -1 (message printed, starting
 * "rg2 <cmd>: <opt>:"). */
int rg2_cli_parse_list(const char *cmd, const char *opt, const char *s, double *out, int max);
/* Exactly n numbers "a,b,..." (rg2_cli_parse_list); 0, or -1 with one line printed: a bad
 * item's, or "rg2 <cmd>: <opt> needs <need>". */
int rg2_cli_parse_n(const char *cmd, const char *opt, const char *s, double *out, int n, const char *need);
/* One number of a single-number option (s NULL: the value is missing): 0, or -1 with one line
 * printed, "rg2 <cmd>: <opt> needs <rule>, not '<s>'". A subnormal number is accepted. */
int rg2_cli_number(const char *cmd, const char *opt, const char *s, const char *rule, double *v);

/* --surface K of rg2 build, render and check: K as given, any integer >= 0 (*v; a usage message
 * and -1 otherwise, and when an earlier --surface gave prev). The design's count bounds it once
 * loaded: rg2_cli_surface_in. */
int rg2_cli_surface_opt(const char *cmd, const char *prev, const char *s, double *v);
/* Whether --surface s (v as rg2_cli_surface_opt read it) names one of the design's n surfaces:
 * 0, or a usage message and -1. */
int rg2_cli_surface_in(const char *cmd, const char *s, double v, int n);
/* Each of x[0..n) in the numeric range of a design file's numbers (rg2_number_check: 0 or a
 * magnitude from 1e-100 to 1e100): 0, or RG2_EXIT_USAGE with one line printed, "rg2 <cmd>: value
 * out of range: <opt>[ item k]: number ... is outside the supported range (...)". */
int rg2_cli_check_numbers(const char *cmd, const char *opt, const double *x, int n);
/* An integer lo..hi of an option (s NULL: missing): 0, or -1 with one line printed. */
int rg2_cli_int(const char *cmd, const char *opt, const char *s, int lo, int hi, int *v);
/* 1 if the file name's extension is ext (".png"), in any case. */
int rg2_cli_has_ext(const char *path, const char *ext);
/* Say on stderr that an option given has no effect in this run (it is not an error: scripts
 * pass one option set to several commands): "rg2 CMD: note: OPT has no effect (WHY)". */
void rg2_cli_no_effect(const char *cmd, const char *opt, const char *why);
/* An unknown option: "rg2 <cmd>: unknown option '<arg>' (did you mean '<opt>'?)" on stderr, then the
 * usage. The suggestion is the closest (rg2_closest_name) of the "--" options that usage() itself
 * lists, so it cannot name an option the command does not have; aliases (nullable, pairs
 * "wrong", "right", NULL-terminated) map a word users try to the option that does it ("--width",
 * "--size WxH"). Returns RG2_EXIT_USAGE. */
int rg2_cli_unknown_option(const char *cmd, const char *arg, void (*usage)(FILE *), const char *const *aliases);
/* The unknown option arg of a command whose options are the n names given ("--arcs", ...), on
 * stderr: "rg2 <cmd>: unknown option '<arg>' (did you mean '<opt>'? see rg2 <cmd> --help)", the
 * suggestion the closest name (rg2_closest_name), none when nothing is close. Returns
 * RG2_EXIT_USAGE. */
int rg2_cli_unknown_option_of(const char *cmd, const char *arg, const char *const *names, int n);
/* Print "rg2 <cmd>: <status text>: <message>" to stderr; returns RG2_EXIT_FAIL. */
int rg2_cli_report(const char *cmd, const rg2_error *err);
/* 1 if the paths name the same existing file (an output that would overwrite an input). */
int rg2_cli_same_file(const char *a, const char *b);
/* 1 if the names mean the same file, existing or not (rg2_cli_same_file, or the same real
 * directory and last component: "a.step" and "./a.step"). */
int rg2_cli_same_path(const char *a, const char *b);
/* The outputs of a command that reads the design file: 0, or RG2_EXIT_USAGE with a message when
 * one is the design file or two are the same file. */
int rg2_cli_check_outputs(const char *cmd, const char *design, const char *const *out, int n);

#endif
