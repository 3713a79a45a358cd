/* util.c -- argument helpers shared by the subcommands. */
#include "cli.h"

#include <errno.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <sys/stat.h>

int rg2_cli_parse_list(const char *cmd, const char *opt, const char *s, double *out, int max)
{
    int n = 0;
    const char *p = s;
    while (*p) {
        char *end;
        errno = 0;
        double x = strtod(p, &end);
        if (end == p || errno == ERANGE || !isfinite(x)) {
            fprintf(stderr, "rg2 %s: %s: item %d of '%s' is not a finite number\n", cmd, opt, n, s);
            return -1;
        }
        if (n == max) {
            fprintf(stderr, "rg2 %s: %s: more than %d value%s\n", cmd, opt, max, max == 1 ? "" : "s");
            return -1;
        }
        out[n++] = x;
        p = end;
        while (*p == ' ')
            p++;
        if (*p == ',' || *p == ';')
            p++;
        else if (*p) {
            fprintf(stderr, "rg2 %s: %s: unexpected '%c' after item %d of '%s'\n", cmd, opt, *p, n - 1, s);
            return -1;
        }
    }
    return n;
}

int rg2_cli_report(const char *cmd, const rg2_error *err)
{
    fprintf(stderr, "rg2 %s: %s: %s\n", cmd, rg2_status_str(err->code), err->msg);
    return RG2_EXIT_FAIL;
}

int rg2_cli_same_file(const char *a, const char *b)
{
    struct stat sa, sb;
    if (stat(a, &sa) || stat(b, &sb))
        return 0;
    return sa.st_dev == sb.st_dev && sa.st_ino == sb.st_ino;
}
