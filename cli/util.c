/* util.c -- argument helpers shared by the subcommands. */
#define _XOPEN_SOURCE 700 /* realpath */
#include "cli.h"

#include <ctype.h>
#include <errno.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <strings.h>
#include <limits.h>
#include <sys/stat.h>

/* strtod with the rules of every numeric option: 0 for a finite number (a subnormal one too:
 * glibc sets ERANGE on underflow, but the value is finite, and the numeric range check names
 * it), 1 for none or NaN / infinity, 2 for a literal past the double range (1e999), 3 for one
 * so small that it reads as 0 (1e-400: it would pass as the number 0, which the range allows). */
static int scan(const char *p, char **end, double *x)
{
    errno = 0;
    *x = strtod(p, end);
    if (*end == p || !isfinite(*x))
        return errno == ERANGE && *end != p ? 2 : 1;
    if (errno == ERANGE && *x == 0.0)
        return 3;
    return errno == ERANGE && fabs(*x) > 1.0 ? 2 : 0;
}

static const char *scan_why(int bad)
{
    return bad == 2   ? "is past the double range (about 1.8e308)"
           : bad == 3 ? "is below the smallest double (about 4.9e-324) and would read as 0 (write 0 for zero)"
                      : "is not a finite number";
}

int rg2_cli_parse_list(const char *cmd, const char *opt, const char *s, double *out, int max)
{
    int n = 0;
    const char *p = s;
    while (*p) {
        char *end;
        double x;
        int bad = scan(p, &end, &x);
        if (bad) {
            fprintf(stderr, "rg2 %s: %s: item %d of '%s' %s\n", cmd, opt, n, s, scan_why(bad));
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

int rg2_cli_parse_n(const char *cmd, const char *opt, const char *s, double *out, int n, const char *need)
{
    int k = rg2_cli_parse_list(cmd, opt, s, out, n);
    if (k == n)
        return 0;
    if (k >= 0) /* (a bad item has its own message) */
        fprintf(stderr, "rg2 %s: %s needs %s\n", cmd, opt, need);
    return -1;
}

int rg2_cli_number(const char *cmd, const char *opt, const char *s, const char *rule, double *v)
{
    char *end = NULL;
    int bad = s ? scan(s, &end, v) : 1;
    if (!bad && *end)
        bad = 1;
    if (!bad)
        return 0;
    if (!s)
        fprintf(stderr, "rg2 %s: %s needs %s\n", cmd, opt, rule);
    else
        fprintf(stderr, "rg2 %s: %s needs %s, not '%s'%s\n", cmd, opt, rule, s,
                bad == 2   ? " (past the double range, about 1.8e308)"
                : bad == 3 ? " (below the smallest double, about 4.9e-324: it would read as 0; write 0 for zero)"
                           : "");
    return -1;
}

int rg2_cli_surface_opt(const char *cmd, const char *prev, const char *s, double *v)
{
    const char *rule = "a surface index (an integer >= 0)";
    if (prev) { /* (the second would silently replace the first) */
        fprintf(stderr, "rg2 %s: --surface given twice ('%s', then '%s'); it takes one surface (without it: all)\n",
                cmd, prev, s ? s : "");
        return -1;
    }
    if (rg2_cli_number(cmd, "--surface", s, rule, v))
        return -1;
    if (*v < 0 || *v != floor(*v)) {
        fprintf(stderr, "rg2 %s: --surface needs %s, not '%s'\n", cmd, rule, s);
        return -1;
    }
    return 0;
}

int rg2_cli_surface_in(const char *cmd, const char *s, double v, int n)
{
    if (v < n)
        return 0;
    fprintf(stderr, "rg2 %s: --surface %s: the design has %d surface%s (0..%d)\n", cmd, s, n, n == 1 ? "" : "s", n - 1);
    return -1;
}

int rg2_cli_check_numbers(const char *cmd, const char *opt, const double *x, int n)
{
    for (int k = 0; k < n; k++) {
        char what[96];
        rg2_error err;
        if (n > 1)
            snprintf(what, sizeof what, "%s item %d", opt, k);
        else
            snprintf(what, sizeof what, "%s", opt);
        if (rg2_number_check(x[k], what, &err)) {
            rg2_cli_report(cmd, &err);
            return RG2_EXIT_USAGE;
        }
    }
    return 0;
}

int rg2_cli_int(const char *cmd, const char *opt, const char *s, int lo, int hi, int *v)
{
    double x = 0.0;
    char *end = NULL;
    if (!s || scan(s, &end, &x) || *end || x < lo || x > hi || x != (int)x) {
        fprintf(stderr, "rg2 %s: %s needs an integer %d..%d%s%s%s\n", cmd, opt, lo, hi, s ? ", not '" : "",
                s ? s : "", s ? "'" : "");
        return -1;
    }
    *v = (int)x;
    return 0;
}

int rg2_cli_has_ext(const char *path, const char *ext)
{
    const char *dot = strrchr(path, '.'), *slash = strrchr(path, '/');
    return dot && !(slash && dot < slash) && !strcasecmp(dot, ext);
}

void rg2_cli_no_effect(const char *cmd, const char *opt, const char *why)
{
    fprintf(stderr, "rg2 %s: note: %s has no effect (%s)\n", cmd, opt, why);
}

int rg2_cli_unknown_option_of(const char *cmd, const char *arg, const char *const *names, int n)
{
    const char *close = n > 0 && arg[0] == '-' && arg[1] == '-' ? rg2_closest_name(arg, names, n) : NULL;
    if (close)
        fprintf(stderr, "rg2 %s: unknown option '%s' (did you mean '%s'? see rg2 %s --help)\n", cmd, arg, close, cmd);
    else
        fprintf(stderr, "rg2 %s: unknown option '%s' (see rg2 %s --help)\n", cmd, arg, cmd);
    return RG2_EXIT_USAGE;
}

int rg2_cli_unknown_option(const char *cmd, const char *arg, void (*usage)(FILE *), const char *const *aliases)
{
    enum { MAX_OPTS = 64, MAX_LEN = 32 };
    char opts[MAX_OPTS][MAX_LEN];
    const char *names[2 * MAX_OPTS];
    int n = 0;
    FILE *t = tmpfile(); /* (the usage text is the one list of the options; none: no suggestion) */
    if (t) {
        usage(t);
        rewind(t);
        int c, prev = ' ';
        while ((c = getc(t)) != EOF) {
            /* a "--name" token not inside a word: --size, --iges-brep */
            if (c == '-' && !(isalnum(prev) || prev == '-') && (c = getc(t)) == '-') {
                char w[MAX_LEN] = "--";
                int len = 2;
                while ((c = getc(t)) != EOF && (isalnum(c) || c == '-') && len < MAX_LEN - 1)
                    w[len++] = (char)c;
                w[len] = 0;
                int dup = !isalpha((unsigned char)w[2]) || n == MAX_OPTS;
                for (int k = 0; k < n && !dup; k++)
                    dup = !strcmp(opts[k], w);
                if (!dup) {
                    memcpy(opts[n], w, sizeof w);
                    names[n] = opts[n];
                    n++;
                }
            }
            if (c == EOF)
                break;
            prev = c;
        }
        fclose(t);
    }
    int n_names = n;
    for (int k = 0; aliases && aliases[k] && n_names < 2 * MAX_OPTS; k += 2)
        names[n_names++] = aliases[k];
    const char *close = n_names && arg[0] == '-' && arg[1] == '-' ? rg2_closest_name(arg, names, n_names) : NULL;
    for (int k = n; close && k < n_names; k++)
        if (close == names[k])
            close = aliases[2 * (k - n) + 1];
    if (close)
        fprintf(stderr, "rg2 %s: unknown option '%s' (did you mean '%s'?)\n", cmd, arg, close);
    else
        fprintf(stderr, "rg2 %s: unknown option '%s'\n", cmd, arg);
    usage(stderr);
    return RG2_EXIT_USAGE;
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

/* The path the name p means, for comparing names of files that may not exist yet: the real
 * path of its directory (when that exists) and its last component, else p with "." and empty
 * components dropped lexically. 0, or -1 if it does not fit. */
static int canonical(const char *p, char *out, size_t cap)
{
    const char *slash = strrchr(p, '/');
    char dir[PATH_MAX], real[PATH_MAX];
    size_t n = slash ? (size_t)(slash - p) + 1 : 0;
    if (n >= sizeof dir)
        return -1;
    memcpy(dir, slash ? p : ".", slash ? n : 2);
    dir[slash ? n : 1] = 0;
    const char *base = slash ? slash + 1 : p;
    if (realpath(dir, real))
        return snprintf(out, cap, "%s/%s", real, base) < (int)cap ? 0 : -1;
    size_t k = 0; /* lexical: "a//b/./c" is "a/b/c" */
    for (const char *q = p; *q;) {
        const char *e = strchr(q, '/');
        size_t len = e ? (size_t)(e - q) : strlen(q);
        if (len && !(len == 1 && q[0] == '.')) {
            if (k + len + 2 > cap)
                return -1;
            if (k || p[0] == '/')
                out[k++] = '/';
            memcpy(out + k, q, len);
            k += len;
        }
        q += len + (e != NULL);
    }
    out[k] = 0;
    return 0;
}

int rg2_cli_same_path(const char *a, const char *b)
{
    char ca[PATH_MAX + 256], cb[PATH_MAX + 256];
    if (rg2_cli_same_file(a, b) || !strcmp(a, b))
        return 1;
    return !canonical(a, ca, sizeof ca) && !canonical(b, cb, sizeof cb) && !strcmp(ca, cb);
}

int rg2_cli_check_outputs(const char *cmd, const char *design, const char *const *out, int n)
{
    for (int k = 0; k < n; k++) {
        const char *slash = strrchr(out[k], '/'), *base = slash ? slash + 1 : out[k];
        if (base[0] == '.' && base[1] && !strchr(base + 1, '.')) { /* ".png": a hidden file with no name */
            fprintf(stderr,
                    "rg2 %s: output '%s': the file name is only the extension '%s' (a hidden file with no name); "
                    "give it a name, e.g. 'design%s'\n",
                    cmd, out[k], base, base);
            return RG2_EXIT_USAGE;
        }
        if (rg2_cli_same_path(design, out[k])) {
            fprintf(stderr, "rg2 %s: output '%s' is the design file itself; choose another name\n", cmd, out[k]);
            return RG2_EXIT_USAGE;
        }
        for (int j = 0; j < k; j++)
            if (rg2_cli_same_path(out[j], out[k])) {
                fprintf(stderr, "rg2 %s: output '%s' is listed twice%s%s%s\n", cmd, out[k],
                        strcmp(out[j], out[k]) ? " (as '" : "", strcmp(out[j], out[k]) ? out[j] : "",
                        strcmp(out[j], out[k]) ? "')" : "");
                return RG2_EXIT_USAGE;
            }
    }
    return RG2_EXIT_OK;
}
