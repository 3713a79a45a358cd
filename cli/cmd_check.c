/* rg2 check -- the continuity and exactness report of a design (rg2_check). */
#include "cli.h"

#include <cjson/cJSON.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

int rg2_cli_load_surfaces(const char *cmd, const char *path, rg2_design **d, rg2_surface **surfs, rg2_mesh **meshes,
                          int *n)
{
    rg2_error err = {0};
    *surfs = NULL;
    *meshes = NULL;
    if (rg2_design_load(path, d, &err))
        return rg2_cli_report(cmd, &err);
    *n = rg2_design_num_surfaces(*d);
    if (*n <= 0) {
        fprintf(stderr, "rg2 %s: %s: the design has no output surface\n", cmd, path);
        return RG2_EXIT_FAIL;
    }
    *surfs = calloc((size_t)*n, sizeof **surfs);
    *meshes = calloc((size_t)*n, sizeof **meshes);
    if (!*surfs || !*meshes) {
        fprintf(stderr, "rg2 %s: out of memory\n", cmd);
        return RG2_EXIT_FAIL;
    }
    /* shallow copies: the design keeps owning the arrays */
    for (int k = 0; k < *n; k++) {
        (*surfs)[k] = *rg2_design_surface(*d, k);
        (*meshes)[k] = *rg2_design_mesh(*d, k);
    }
    return RG2_EXIT_OK;
}

static void usage(FILE *f)
{
    fprintf(f, "usage: rg2 check design.json [--json] [--require g0|g1|g2|exact|weights|no-crossings[,...]]\n"
               "                 [--samples N] [--tol KIND=X] [--threads N] [--on SHAPE]\n"
               "                 [--intersections [DENSITY]] [--surface K]\n\n"
               "Measures the built surfaces of a design: patches, exact pieces per shape with their worst\n"
               "implicit residual (|f| / |grad f| / shape size), transitions, the worst G0/G1/G2 gaps over\n"
               "all patch seams (position / size, normal angle in radians, normal-curvature jump relative\n"
               "to the principal curvatures) with where they occur, homogeneous weights, the curvature\n"
               "range and where |k| is largest (the tightest bend, radius 1 / |k|).\n"
               "Samples on a pole (a collapsed patch side) have no normal and are not compared; next to a\n"
               "pole each sample is measured against its own rounding bound where that exceeds the limit\n"
               "(reported as 'next to a pole'); an undefined normal anywhere else fails g1 and g2.\n"
               "  --json              the report as JSON\n"
               "  --require LIST      promises that must hold (g2 implies g0, g1); repeatable\n"
               "  --samples N         seam intervals: N + 1 samples per seam, both ends included\n"
               "                      (default 16: 17 samples; at most 1e9 samples over all seams)\n"
               "  --tol KIND=X        pass limit for g0, g1, g2 or exact (defaults 1e-12, 1e-10, 1e-8,\n"
               "                      1e-11); repeatable\n"
               "  --threads N         threads, up to 64 used (default: all cores, or OMP_NUM_THREADS);\n"
               "                      the report does not depend on it\n"
               "  --intersections [D] also search the output surfaces for places where they cross\n"
               "                      themselves or each other (tessellated at D samples per patch edge,\n"
               "                      1..1000, default 4; each crossing of the triangles confirmed on the\n"
               "                      exact patches; misses crossings shallower than the triangles' chord\n"
               "                      error, and tangential contact); --require no-crossings implies it\n"
               "  --on SHAPE          also measure every patch, tagged or not, against the design's\n"
               "                      shape SHAPE (its name under \"shapes\"): how many lie on it (residual\n"
               "                      relative to the surface's size, not the shape's patches', <= the\n"
               "                      exact limit); repeatable\n"
               "  --surface K         only output surface K (0-based) of the design, named K in the\n"
               "                      report as in the whole design's; --intersections then looks for\n"
               "                      crossings of K with itself only (outputs that overlap on purpose,\n"
               "                      such as variants of one part, cross each other)\n"
               "Exit codes: 0 ok, 1 invalid design or a failed write of the report, 2 usage error,\n"
               "3 a required promise fails.\n");
}

static int parse_require(const char *s, unsigned *req)
{
    int any = 0;
    for (const char *q = s; *q; q++)
        any |= *q != ',' && *q != ' ';
    if (!any || strstr(s, ",,") || s[0] == ',' || s[strlen(s) - 1] == ',') {
        fprintf(stderr, "rg2 check: --require '%s': needs a comma-separated list of g0, g1, g2, exact, weights, "
                        "no-crossings\n", s);
        return -1;
    }
    char *buf = malloc(strlen(s) + 1); /* the whole list, however long (a fixed buffer dropped its end) */
    if (!buf) {
        fprintf(stderr, "rg2 check: out of memory\n");
        return -1;
    }
    memcpy(buf, s, strlen(s) + 1);
    int rc = 0;
    for (char *tok = strtok(buf, ","); tok && !rc; tok = strtok(NULL, ",")) {
        /* "g2, exact" (a space after the comma, the list quoted) reads as "g2,exact" */
        while (*tok == ' ' || *tok == '\t')
            tok++;
        for (size_t e = strlen(tok); e > 0 && (tok[e - 1] == ' ' || tok[e - 1] == '\t');)
            tok[--e] = '\0';
        if (!*tok) {
            fprintf(stderr, "rg2 check: --require '%s': needs a comma-separated list of g0, g1, g2, exact, weights, "
                            "no-crossings (an empty item)\n", s);
            rc = -1;
        } else if (!strcmp(tok, "g0"))
            *req |= RG2_REQUIRE_G0;
        else if (!strcmp(tok, "g1"))
            *req |= RG2_REQUIRE_G1;
        else if (!strcmp(tok, "g2"))
            *req |= RG2_REQUIRE_G2;
        else if (!strcmp(tok, "exact"))
            *req |= RG2_REQUIRE_EXACT;
        else if (!strcmp(tok, "weights"))
            *req |= RG2_REQUIRE_WEIGHTS;
        else if (!strcmp(tok, "no-crossings"))
            *req |= RG2_REQUIRE_NO_CROSSINGS;
        else {
            fprintf(stderr, "rg2 check: --require: unknown promise '%s' (g0, g1, g2, exact, weights, no-crossings)\n",
                    tok);
            rc = -1;
        }
    }
    free(buf);
    return rc;
}

#define MAX_ON 16

/* Append line to the malloc'd text *t of length *len. Returns 0, or -1 out of memory. */
static int append(char **t, size_t *len, const char *line)
{
    size_t l = strlen(line);
    char *g = realloc(*t, *len + l + 1);
    if (!g)
        return -1;
    memcpy(g + *len, line, l + 1);
    *t = g;
    *len += l;
    return 0;
}

/* --on: every patch of surface s against shape `shape` (rg2_surface_shape_residuals): a line
 * appended to the text report *text, or an entry of the JSON report's "on" array. */
static int on_one(const rg2_surface *surf, int s, const rg2_shape *shape, const char *label, const rg2_check_opts *o,
                  cJSON *arr, char **text, size_t *len)
{
    size_t np = (size_t)surf->nu * (size_t)surf->nv;
    double *res = malloc(np * sizeof *res);
    rg2_error err = {0};
    if (!res)
        return -1;
    if (rg2_surface_shape_residuals(surf, shape, o->patch_samples, res, &err)) {
        free(res);
        return rg2_cli_report("check", &err);
    }
    size_t count = 0, w_on = 0, w_off = 0;
    double worst = -1, nearest = INFINITY;
    for (size_t k = 0; k < np; k++)
        if (res[k] <= o->tol_exact) {
            count++;
            if (res[k] > worst)
                worst = res[k], w_on = k;
        } else if (!(res[k] >= nearest) && !(isnan(res[k]) && w_off != k && nearest < INFINITY)) {
            nearest = res[k], w_off = k; /* (a NaN patch is the nearest only if no other is off) */
        }
    free(res);
    int nv = surf->nv, off = count < np, rc = 0;
    char on_at[48] = "", off_at[48] = "";
    if (count)
        snprintf(on_at, sizeof on_at, "patch (%d,%d)", (int)(w_on / (size_t)nv), (int)(w_on % (size_t)nv));
    if (off)
        snprintf(off_at, sizeof off_at, "patch (%d,%d)", (int)(w_off / (size_t)nv), (int)(w_off % (size_t)nv));
    if (arr) {
        const char *kind = rg2_shape_name(shape->kind);
        cJSON *e = cJSON_CreateObject();
        if (!e || !cJSON_AddItemToArray(arr, e)) {
            cJSON_Delete(e);
            return -1;
        }
        rc = !cJSON_AddStringToObject(e, "shape", label) || !cJSON_AddStringToObject(e, "kind", kind ? kind : "shape") ||
             !cJSON_AddNumberToObject(e, "surface", s) || !cJSON_AddNumberToObject(e, "patches", (double)np) ||
             !cJSON_AddNumberToObject(e, "on", (double)count);
        if (!rc && count)
            rc = !cJSON_AddNumberToObject(e, "worst_on", worst) || !cJSON_AddStringToObject(e, "worst_on_where", on_at);
        if (!rc && off) /* (JSON has no NaN: null) */
            rc = !(isnan(nearest) ? cJSON_AddNullToObject(e, "nearest_off")
                                  : cJSON_AddNumberToObject(e, "nearest_off", nearest)) ||
                 !cJSON_AddStringToObject(e, "nearest_off_where", off_at);
        return rc ? -1 : 0;
    }
    char line[400], *p = line;
    size_t room = sizeof line;
    int m = snprintf(p, room, "on shape %-10s surface %d: %zu of %zu patches within %g of its size", label, s, count, np,
                     o->tol_exact);
    if (count && m >= 0 && (size_t)m < room)
        m += snprintf(p + m, room - (size_t)m, ", worst %.2e at %s", worst, on_at);
    if (off && m >= 0 && (size_t)m < room)
        m += snprintf(p + m, room - (size_t)m, "; nearest off it %.2e at %s", nearest, off_at);
    if (m >= 0 && (size_t)m < room)
        snprintf(p + m, room - (size_t)m, "\n");
    return append(text, len, line);
}

/* Every number under item as a raw item with the shortest of 15, 16 and 17 digits that reads
 * back to the same double, as rg2_check_format writes them. (cJSON prints 15 digits whenever
 * they read back within about an ulp: reparsing the report and printing it again with the "on"
 * array made 4 of the 135 numbers of torus_sphere's report an ulp off.) -1 when out of memory. */
static int exact_numbers(cJSON *item)
{
    for (cJSON *c = item->child; c; c = c->next) {
        if (cJSON_IsNumber(c) && isfinite(c->valuedouble)) {
            char buf[40];
            for (int digits = 15; digits <= 17; digits++) {
                snprintf(buf, sizeof buf, "%.*g", digits, c->valuedouble);
                if (strtod(buf, NULL) == c->valuedouble)
                    break;
            }
            char *raw = cJSON_malloc(strlen(buf) + 1); /* (cJSON_Delete frees it) */
            if (!raw)
                return -1;
            c->valuestring = strcpy(raw, buf);
            c->type = (c->type & ~0xFF) | cJSON_Raw; /* (in place: it keeps its key) */
        } else if (exact_numbers(c)) {
            return -1;
        }
    }
    return 0;
}

/* The --on lines or the JSON "on" array for every shape asked for and every surface (surfs[s] is
 * the design's surface o->surface_base + s). */
static int on_report(const rg2_surface *surfs, int n, const rg2_shape *shapes, const char **labels,
                     const int *on_shape, int n_on, const rg2_check_opts *o, int json, char **text)
{
    cJSON *root = NULL, *arr = NULL;
    size_t len = strlen(*text);
    int rc = 0;
    if (json) {
        root = cJSON_Parse(*text);
        arr = cJSON_CreateArray();
        if (!root || !arr || !cJSON_AddItemToObject(root, "on", arr)) {
            cJSON_Delete(arr);
            rc = -1;
        }
    }
    for (int q = 0; q < n_on && !rc; q++)
        for (int s = 0; s < n && !rc; s++)
            rc = on_one(&surfs[s], o->surface_base + s, &shapes[on_shape[q]], labels[on_shape[q]], o, arr, text, &len);
    if (json && !rc && !(rc = exact_numbers(root))) {
        char *p = cJSON_Print(root);
        size_t l = p ? strlen(p) : 0;
        if (!p || append(&p, &l, "\n")) {
            free(p);
            rc = -1;
        } else {
            free(*text);
            *text = p;
        }
    }
    cJSON_Delete(root);
    if (rc < 0) {
        fprintf(stderr, "rg2 check: out of memory\n");
        rc = RG2_EXIT_FAIL;
    }
    return rc;
}

int rg2_cmd_check(int argc, char **argv)
{
    const char *path = NULL, *on[MAX_ON], *only_arg = NULL;
    double only_v = -1; /* --surface as given, checked against the design's count once loaded */
    int json = 0, n_on = 0;
    unsigned req = 0;
    rg2_check_opts o;
    rg2_check_opts_default(&o);
    for (int i = 1; i < argc; i++) {
        const char *a = argv[i];
        if (!strcmp(a, "--help") || !strcmp(a, "-h")) {
            usage(stdout);
            return RG2_EXIT_OK;
        } else if (!strcmp(a, "--json"))
            json = 1;
        else if (!strcmp(a, "--require")) {
            if (i + 1 >= argc) {
                fprintf(stderr, "rg2 check: --require needs a comma-separated list of g0, g1, g2, exact, weights, "
                                "no-crossings\n");
                return RG2_EXIT_USAGE;
            }
            if (parse_require(argv[++i], &req))
                return RG2_EXIT_USAGE;
        } else if (!strcmp(a, "--samples")) {
            if (rg2_cli_int("check", a, i + 1 < argc ? argv[++i] : NULL, 1, 10000, &o.seam_samples))
                return RG2_EXIT_USAGE;
        } else if (!strcmp(a, "--intersections")) {
            /* the number is optional: the next argument is it when it is a number as a whole (a
             * design named 2cyl.json begins with a digit but is the design) */
            o.crossing_density = RG2_CROSSING_DEFAULT_DENSITY;
            char *end = NULL;
            if (i + 1 < argc && argv[i + 1][0] && (strtod(argv[i + 1], &end), end != argv[i + 1] && !*end) &&
                rg2_cli_int("check", a, argv[++i], 1, 1000, &o.crossing_density))
                return RG2_EXIT_USAGE;
        } else if (!strcmp(a, "--threads")) {
            /* the numbers rg2 render --threads takes */
            if (rg2_cli_int("check", a, i + 1 < argc ? argv[++i] : NULL, 1, 1024, &o.threads))
                return RG2_EXIT_USAGE;
        } else if (!strcmp(a, "--tol")) {
            const char *t = i + 1 < argc ? argv[++i] : "";
            const char *eq = strchr(t, '=');
            double v;
            double *dst = !eq                               ? NULL
                          : !strncmp(t, "g0=", 3)          ? &o.tol_g0
                          : !strncmp(t, "g1=", 3)          ? &o.tol_g1
                          : !strncmp(t, "g2=", 3)          ? &o.tol_g2
                          : !strncmp(t, "exact=", 6)       ? &o.tol_exact
                                                           : NULL;
            if (!dst) {
                fprintf(stderr, "rg2 check: --tol needs g0=X, g1=X, g2=X or exact=X with X >= 0, not '%s'\n", t);
                return RG2_EXIT_USAGE;
            }
            char kind[16];
            snprintf(kind, sizeof kind, "--tol %.*s", (int)(eq - t), t);
            if (rg2_cli_number("check", kind, eq + 1, "a finite number >= 0", &v))
                return RG2_EXIT_USAGE;
            if (v < 0) {
                fprintf(stderr, "rg2 check: %s needs a finite number >= 0, not '%s'\n", kind, eq + 1);
                return RG2_EXIT_USAGE;
            }
            *dst = v;
        } else if (!strcmp(a, "--surface")) {
            const char *prev = only_arg;
            only_arg = i + 1 < argc ? argv[++i] : NULL;
            if (rg2_cli_surface_opt("check", prev, only_arg, &only_v))
                return RG2_EXIT_USAGE;
        } else if (!strcmp(a, "--on")) {
            if (i + 1 >= argc || !argv[i + 1][0]) {
                fprintf(stderr, "rg2 check: --on needs the name of one of the design's shapes\n");
                return RG2_EXIT_USAGE;
            }
            if (n_on == MAX_ON) {
                fprintf(stderr, "rg2 check: --on given more than %d times\n", MAX_ON);
                return RG2_EXIT_USAGE;
            }
            int dup = 0; /* (a name given twice is measured once) */
            for (int q = 0; q < n_on; q++)
                dup |= !strcmp(on[q], argv[i + 1]);
            if (!dup)
                on[n_on++] = argv[i + 1];
            i++;
        } else if (a[0] == '-' && a[1]) {
            return rg2_cli_unknown_option("check", a, usage, NULL);
        } else if (path) {
            fprintf(stderr, "rg2 check: more than one design file ('%s', '%s')\n", path, a);
            return RG2_EXIT_USAGE;
        } else
            path = a;
    }
    if (!path) {
        usage(stderr);
        return RG2_EXIT_USAGE;
    }
    rg2_design *d = NULL;
    rg2_surface *surfs = NULL;
    rg2_mesh *meshes = NULL;
    rg2_shape *shapes = NULL;
    const char **labels = NULL;
    rg2_check_report rep = {0};
    char *text = NULL;
    int n = 0, rc = rg2_cli_load_surfaces("check", path, &d, &surfs, &meshes, &n);
    if (rc)
        goto out;
    if (rg2_cli_surface_in("check", only_arg, only_v, n)) {
        rc = RG2_EXIT_USAGE; /* an option value out of its range */
        goto out;
    }
    /* --surface K: surface K alone, the report naming it K */
    const rg2_surface *chk = surfs;
    int n_chk = n;
    if (only_v >= 0) {
        o.surface_base = (int)only_v;
        chk = surfs + o.surface_base;
        n_chk = 1;
    }
    int ns = rg2_design_num_shapes(d);
    shapes = calloc((size_t)(ns > 0 ? ns : 1), sizeof *shapes);
    labels = calloc((size_t)(ns > 0 ? ns : 1), sizeof *labels);
    if (!shapes || !labels) {
        fprintf(stderr, "rg2 check: out of memory\n");
        rc = RG2_EXIT_FAIL;
        goto out;
    }
    for (int k = 0; k < ns; k++) {
        shapes[k] = *rg2_design_shape(d, k);
        labels[k] = rg2_design_shape_label(d, k);
    }
    int on_shape[MAX_ON];
    for (int q = 0; q < n_on; q++) {
        on_shape[q] = -1;
        for (int k = 0; k < ns && on_shape[q] < 0; k++)
            if (labels[k] && !strcmp(labels[k], on[q]))
                on_shape[q] = k;
        if (on_shape[q] < 0) {
            fprintf(stderr, "rg2 check: --on '%s': %s: the design has no shape of that name (its shapes:", on[q], path);
            for (int k = 0; k < ns; k++)
                fprintf(stderr, "%s %s", k ? "," : "", labels[k] ? labels[k] : "?");
            fprintf(stderr, "%s)\n", ns ? "" : " none");
            rc = RG2_EXIT_USAGE;
            goto out;
        }
    }
    rg2_error err = {0};
    if ((req & RG2_REQUIRE_NO_CROSSINGS) && o.crossing_density == 0)
        o.crossing_density = RG2_CROSSING_DEFAULT_DENSITY;
    if (rg2_check(chk, n_chk, shapes, labels, ns, &o, &rep, &err) || rg2_check_format(&rep, json, &text, &err)) {
        rc = rg2_cli_report("check", &err);
        goto out;
    }
    if (n_on && (rc = on_report(chk, n_chk, shapes, labels, on_shape, n_on, &o, json, &text)))
        goto out;
    fputs(text, stdout);
    unsigned f = rg2_check_failures(&rep, req);
    if (f) {
        fprintf(stderr, "rg2 check: %s: required promise%s failed:%s%s%s%s%s%s\n", path, (f & (f - 1)) ? "s" : "",
                f & RG2_REQUIRE_G0 ? " g0" : "", f & RG2_REQUIRE_G1 ? " g1" : "", f & RG2_REQUIRE_G2 ? " g2" : "",
                f & RG2_REQUIRE_EXACT ? " exact" : "", f & RG2_REQUIRE_WEIGHTS ? " weights" : "",
                f & RG2_REQUIRE_NO_CROSSINGS ? " no-crossings" : "");
        rc = RG2_EXIT_CHECK;
    }
out:
    free(text);
    rg2_check_report_free(&rep);
    free(shapes);
    free(labels);
    free(surfs);
    free(meshes);
    rg2_design_free(d);
    return rc;
}
