/* rg2 info -- what a design builds: meshes, patch counts, which patches are exact pieces of
 * which shape and which are transitions. */
#include "cli.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* " (24 of degree (5,3), 12 of degree (4,3))" for the patches of higher degree than bi-3 in
 * s (general-quadratic polar caps), nothing for an all-bi-3 surface. */
static void print_degrees(const rg2_surface *s)
{
    int count[RG2_MAX_DEGREE + 1][RG2_MAX_DEGREE + 1] = {{0}}, first = 1;
    for (int i = 0; i < s->nu; i++)
        for (int j = 0; j < s->nv; j++) {
            const rg2_xpatch *x = rg2_surface_xpatch(s, i, j);
            if (x && x->du <= RG2_MAX_DEGREE && x->dv <= RG2_MAX_DEGREE)
                count[x->du][x->dv]++;
        }
    for (int a = 1; a <= RG2_MAX_DEGREE; a++)
        for (int b = 1; b <= RG2_MAX_DEGREE; b++)
            if (count[a][b]) {
                printf("%s%d of degree (%d,%d)", first ? " (" : ", ", count[a][b], a, b);
                first = 0;
            }
    if (!first)
        printf(")");
}

static int cmp_int(const void *a, const void *b)
{
    int x = *(const int *)a, y = *(const int *)b;
    return (x > y) - (x < y);
}

static void usage(FILE *f)
{
    fprintf(f, "usage: rg2 info [--map] [--near X,Y,Z] [--ray X,Y,Z,DX,DY,DZ] design.json\n\n"
               "Reads and builds a design file (docs/design-format.md) and prints its shapes (kind and\n"
               "parameters before placement, and whether the placement scales, stretches or shears them\n"
               "or is projective), its output meshes with their control point and patch counts, how\n"
               "many patches are exact pieces of each shape and how many are transitions, and the\n"
               "smallest homogeneous patch weight.\n"
               "For a tube (u closed, v open) it says what closes its two v ends: a cap, nothing (an\n"
               "open end), or nothing at a polar point, which leaves a hole around the pole.\n"
               "For a closed surface (u closed; v closed or capped at both ends) it says whether the\n"
               "normal points out or in (the sign of the volume its tessellation encloses).\n"
               "Notes follow that are not errors: a merge whose circles meet turned or running\n"
               "opposite ways round (rg2_design_note).\n"
               "Patches of a degree above bi-3 (general-quadratic polar caps) are counted per degree,\n"
               "e.g. \"-> 8 x 12 = 96 patches (96 of degree (5,3))\" (general-quadratic caps raise the\n"
               "whole surface).\n"
               "  --map   also print a map of the patches (line 'u i' for patches (i, 0..); its j-th\n"
               "          character, from 0, for patch (i, j): a letter per shape as listed, '.' for a\n"
               "          transition patch)\n"
               "  --near X,Y,Z  also name the control point nearest to (X, Y, Z) (its design point d,\n"
               "          over the output meshes): the mesh, its indices [i, j] from 0, d, W and the\n"
               "          distance, the edit that moves it, and the patches that edit changes (e.g.\n"
               "          the point rg2 check gives for a gap or the largest |k|), and the surface point\n"
               "          nearest to it over every output surface: its patch, u, v, the distance, the\n"
               "          normal, and whether the patch is exact on a shape or a transition\n"
               "  --ray X,Y,Z,DX,DY,DZ  also give the first point where the ray from (X, Y, Z) along\n"
               "          (DX, DY, DZ) meets an output surface: its patch, u, v, the point, t and the\n"
               "          distance along the ray, the normal, exact or transition (picking)\n"
               "          Both are exact to the last digits, found over the whole surface (docs/picking.md)\n"
               "Exit codes: 0 ok, 1 the design is invalid or the report cannot be written (message on\n"
               "stderr), 2 usage error.\n");
}

/* The v ends of a tube (u closed, v open): capped, open, or a polar point left uncapped, which
 * is a hole (the construction makes no patch that touches a pole; only a cap closes it): a cap
 * with "ends": "north" on a mesh whose south end is polar left one that no other line showed. */
static void print_ends(const rg2_design *d, int o, const rg2_mesh *m)
{
    if (!m->su.closed || m->sv.closed)
        return;
    rg2_cap_opts co;
    int capped = rg2_design_cap(d, o, &co);
    printf("  ends:");
    for (int e = 0; e < 2; e++) {
        int cap = capped && (co.ends & (e ? RG2_CAP_NORTH : RG2_CAP_SOUTH));
        int pole = rg2_mesh_row_collapsed(m, e ? m->nv - 1 : 0);
        printf("%s %s %s", e ? ";" : "", e ? "north (v end)" : "south (v start)",
               cap ? "capped" : pole ? "a polar point, not capped: a hole around the pole" : "open");
    }
    printf("\n");
}

/* A closed surface (u closed; v closed, or capped at both ends): which way its normal points, by
 * the sign of the volume its tessellation encloses (watertight: the seams share their vertices),
 * sum over the triangles of a . (b x c) / 6. A solid read from STEP/IGES with the normal pointing
 * in has a negative volume (FreeCAD's Part.Solid turns it round without a word). */
static void print_orientation(const rg2_design *d, int o, const rg2_surface *s, const rg2_mesh *m)
{
    rg2_cap_opts co;
    int capped = rg2_design_cap(d, o, &co);
    int closed = m->su.closed && (m->sv.closed || (capped && (co.ends & RG2_CAP_SOUTH) && (co.ends & RG2_CAP_NORTH)));
    enum { DENSITY = 4 };
    if (!closed || (long)s->nu * s->nv > 20000) /* (a sign, not worth a large tessellation) */
        return;
    rg2_tess t;
    rg2_error err;
    if (rg2_tessellate(s, DENSITY, 0, &t, &err))
        return;
    double vol = 0.0;
    for (int k = 0; k < t.n_triangles; k++) {
        const double *a = t.pos + 3 * t.tri[3 * k], *b = t.pos + 3 * t.tri[3 * k + 1], *c = t.pos + 3 * t.tri[3 * k + 2];
        vol += (a[0] * (b[1] * c[2] - b[2] * c[1]) - a[1] * (b[0] * c[2] - b[2] * c[0]) +
                a[2] * (b[0] * c[1] - b[1] * c[0])) / 6.0;
    }
    rg2_tess_free(&t);
    if (vol > 0.0)
        printf("  closed: the normal points out (enclosed volume about %.4g)\n", vol);
    else if (vol < 0.0)
        printf("  closed: the normal points IN (enclosed volume about %.4g, negative): STEP/IGES solids "
               "come out inside out; reverse the mesh along u or v\n", vol);
}

/* The patches of a direction of n control points (closed or open) that point i touches, shifted
 * by off: a closed direction's segment s reads points s - 1..s + 2, an open one's s..s + 3
 * (docs/design-format.md, "edit"), as "6, 7, 0, 1" or "5..8"; returns their count, and in *ends
 * whether they include the first (1) and the last (2) segment of an open direction. */
static int touched(int i, int n, int closed, int off, char *buf, size_t size, int *ends)
{
    int count = 0;
    size_t len = 0;
    buf[0] = 0;
    *ends = 0;
    if (closed) {
        for (int s = i - 2; s <= i + 1; s++) {
            int k = ((s % n) + n) % n, dup = 0;
            for (int t = i - 2; t < s; t++)
                dup |= ((t % n) + n) % n == k;
            if (dup)
                continue;
            len += (size_t)snprintf(buf + len, len < size ? size - len : 0, "%s%d", count ? ", " : "", k + off);
            count++;
        }
        return count;
    }
    int lo = i - 3 < 0 ? 0 : i - 3, hi = i > n - 4 ? n - 4 : i;
    *ends = (lo == 0) | (hi == n - 4) << 1;
    snprintf(buf, size, lo == hi ? "%d" : "%d..%d", lo + off, hi + off);
    return hi - lo + 1;
}

/* --near: the control point of the output meshes whose design point d = p / W lies nearest to
 * x (positive weights only; the first in the order surface, i, j), the edit that moves it and
 * the patches that changes: a point edit changes exactly its 4 x 4 support, and a cap, fitted to
 * the 2-jet of the body's end row of patches, changes whole when the support reaches that row. */
static void print_nearest(const rg2_design *d, const double x[3])
{
    int bo = -1, bi = 0, bj = 0;
    double best = INFINITY;
    for (int o = 0; o < rg2_design_num_surfaces(d); o++) {
        const rg2_mesh *m = rg2_design_mesh(d, o);
        for (int i = 0; i < m->nu; i++)
            for (int j = 0; j < m->nv; j++) {
                const double *p = rg2_mesh_at(m, i, j);
                double e = 0.0;
                for (int k = 0; k < 3 && p[3] > 0.0; k++)
                    e += (p[k] / p[3] - x[k]) * (p[k] / p[3] - x[k]);
                if (p[3] > 0.0 && e < best) {
                    best = e;
                    bo = o, bi = i, bj = j;
                }
            }
    }
    printf("nearest control point to (%.10g, %.10g, %.10g):", x[0], x[1], x[2]);
    if (bo < 0) {
        printf(" none (no control point of positive weight)\n");
        return;
    }
    const rg2_mesh *m = rg2_design_mesh(d, bo);
    const char *name = rg2_design_mesh_name(d, bo);
    const double *p = rg2_mesh_at(m, bi, bj);
    printf(" surface %d, mesh '%s' [%d, %d], d = (%.10g, %.10g, %.10g), W = %.10g, %.4g away\n", bo, name, bi, bj,
           p[0] / p[3], p[1] / p[3], p[2] / p[3], p[3], sqrt(best));
    if (!m->sv.closed && (bj == 0 || bj == m->nv - 1) && rg2_mesh_row_collapsed(m, bj)) {
        printf("  it is the %s polar point (the whole collapsed row v %d): edit it with {\"edit\": \"%s\", "
               "\"points\": [{\"pole\": \"%s\", \"move\": [dx, dy, dz]}]} (docs/poles.md)\n",
               bj ? "north" : "south", bj, name, bj ? "north" : "south");
        return;
    }
    rg2_cap_opts co;
    unsigned caps = rg2_design_cap(d, bo, &co) ? (unsigned)co.ends : 0u;
    printf("  edit it with {\"edit\": \"%s\", \"points\": [{\"at\": [%d, %d], \"move\": [dx, dy, dz]}]} (or "
           "\"normal\": t, along the net's normal)", name, bi, bj);
    if (caps) /* an operation takes a capped mesh uncapped (design-format.md, "cap") */
        printf(", then cap that edit as '%s' is capped ({\"cap\": <the edit>, \"ends\": \"%s\"}, the same options)", name,
               caps == (RG2_CAP_SOUTH | RG2_CAP_NORTH) ? "both" : caps == RG2_CAP_SOUTH ? "south" : "north");
    printf("\n");
    int south = (caps & RG2_CAP_SOUTH) ? 3 : 0, ends;
    char bu[64], bv[64], cap[80] = "";
    int cu = touched(bi, m->nu, m->su.closed, 0, bu, sizeof bu, &ends);
    int cv = touched(bj, m->nv, m->sv.closed, south, bv, sizeof bv, &ends);
    int n = cu * cv;
    if ((caps & RG2_CAP_SOUTH) && (ends & 1)) {
        snprintf(cap, sizeof cap, ", and the south cap's (j in 0..2, every i)");
        n += 3 * m->nu;
    }
    if ((caps & RG2_CAP_NORTH) && (ends & 2)) {
        int j0 = south + m->nv - 3;
        size_t len = strlen(cap);
        snprintf(cap + len, sizeof cap - len, "%s the north cap's (j in %d..%d, every i)", cap[0] ? " and" : ", and",
                 j0, j0 + 2);
        n += 3 * m->nu;
    }
    printf("  that edit changes %d patches: (i, j) with i in %s, j in %s%s\n", n, bu, bv, cap);
}

/* Where a found point lies: on a patch exact on a shape, or on a transition patch. */
static void print_place(const rg2_design *d, const rg2_surface *s, const rg2_hit *h)
{
    int tag = s->tag ? s->tag[h->i * s->nv + h->j] : -1;
    printf("%s%s%s", tag >= 0 ? "exact on '" : "a transition patch", tag >= 0 ? rg2_design_shape_label(d, tag) : "",
           tag >= 0 ? "'" : "");
}

/* The output surfaces' locators, built on first use and kept for the other query (--near and
 * --ray in one call); a surface the locator refuses keeps its error. */
typedef struct {
    int n, built;
    rg2_locator **L;
    rg2_status *st;
    rg2_error *err;
} locators;

static void locators_free(locators *ls)
{
    for (int k = 0; ls->L && k < ls->n; k++)
        rg2_locator_free(ls->L[k]);
    free(ls->L);
    free(ls->st);
    free(ls->err);
}

/* Search every output surface with its locator (src/locate.c): the nearest point (ray = NULL)
 * or the first hit of the ray x + t ray; *o gets the surface (-1: none, or every surface
 * refused). A surface the locator refuses (a weight <= 0) is named and skipped. */
static void locate_all(const rg2_design *d, locators *ls, const double x[3], const double *ray, int *o, rg2_hit *best)
{
    *o = -1;
    if (!ls->built) {
        ls->built = 1;
        ls->n = rg2_design_num_surfaces(d);
        ls->L = calloc((size_t)ls->n + 1, sizeof *ls->L);
        ls->st = calloc((size_t)ls->n + 1, sizeof *ls->st);
        ls->err = calloc((size_t)ls->n + 1, sizeof *ls->err);
        if (!ls->L || !ls->st || !ls->err) {
            printf("  (no surface searched: out of memory)\n");
            ls->n = 0;
            return;
        }
        for (int k = 0; k < ls->n; k++)
            ls->st[k] = rg2_locator_build(rg2_design_surface(d, k), &ls->L[k], &ls->err[k]);
    }
    for (int k = 0; k < ls->n; k++) {
        rg2_error err = ls->err[k];
        rg2_hit h;
        rg2_status st = ls->st[k];
        if (!st)
            st = ray ? rg2_locator_ray(ls->L[k], x, ray, INFINITY, &h, &err) : rg2_locator_closest(ls->L[k], x, &h, &err);
        if (st) {
            printf("  (surface %d not searched: %s)\n", k, err.msg);
            continue;
        }
        if (h.i >= 0 && (*o < 0 || h.dist < best->dist))
            *o = k, *best = h;
    }
}

/* --near on the surface: the output surface point nearest to x, over all of every surface
 * (rg2_locator_closest: exact, and no point nearer by more than its tolerance), with its patch,
 * u, v, normal, and whether the patch is exact on a shape or a transition. */
static void print_nearest_surface(const rg2_design *d, locators *ls, const double x[3])
{
    int o;
    rg2_hit h;
    locate_all(d, ls, x, NULL, &o, &h);
    if (o < 0)
        return;
    printf("  nearest surface point: surface %d patch (%d,%d) u=%.6g v=%.6g, point (%.10g, %.10g, %.10g), %.10g "
           "away, normal (%.6g, %.6g, %.6g), ", o, h.i, h.j, h.u, h.v, h.p[0], h.p[1], h.p[2], h.dist, h.n[0], h.n[1],
           h.n[2]);
    print_place(d, rg2_design_surface(d, o), &h);
    printf("\n");
}

/* --ray: the first point where the ray x + t dir, t >= 0, meets an output surface. */
static void print_ray(const rg2_design *d, locators *ls, const double r[6])
{
    int o;
    rg2_hit h;
    printf("ray from (%.10g, %.10g, %.10g) along (%.10g, %.10g, %.10g):\n", r[0], r[1], r[2], r[3], r[4], r[5]);
    locate_all(d, ls, r, r + 3, &o, &h);
    if (o < 0) {
        printf("  meets no surface\n");
        return;
    }
    double len = sqrt(r[3] * r[3] + r[4] * r[4] + r[5] * r[5]);
    printf("  first hit: surface %d patch (%d,%d) u=%.6g v=%.6g, point (%.10g, %.10g, %.10g), t = %.10g (%.10g "
           "along the ray), normal (%.6g, %.6g, %.6g), ", o, h.i, h.j, h.u, h.v, h.p[0], h.p[1], h.p[2], h.dist,
           h.dist * len, h.n[0], h.n[1], h.n[2]);
    print_place(d, rg2_design_surface(d, o), &h);
    printf("\n");
}

/* What a shape's placement does to the kind and parameters info prints: a similarity
 * (rotation, reflection, translation) keeps them, a uniform scale s scales the lengths by s
 * (", scaled by 2 by its placement"), a non-uniform scale or a shear changes the proportions (a
 * "transform" of a sphere with "scale": [2, 1, 1] is an ellipsoid, and was listed as
 * "ball@meshes.t sphere radius=1"); a projective matrix (a Mobius map) is only named. */
static const char *placement_note(const double M[16], char *buf, size_t size)
{
    if (M[12] != 0.0 || M[13] != 0.0 || M[14] != 0.0 || M[15] != 1.0)
        return ", placed by a projective matrix";
    double g[3][3], s2 = 0.0, off = 0.0;
    for (int a = 0; a < 3; a++)
        for (int b = 0; b < 3; b++) {
            g[a][b] = M[a] * M[b] + M[4 + a] * M[4 + b] + M[8 + a] * M[8 + b]; /* L^T L */
            s2 += a == b ? g[a][b] / 3.0 : 0.0;
        }
    for (int a = 0; a < 3; a++)
        for (int b = 0; b < 3; b++)
            off = fmax(off, fabs(g[a][b] - (a == b ? s2 : 0.0)));
    if (off > 1e-12 * s2)
        return ", stretched or sheared by its placement (not these proportions)";
    if (fabs(s2 - 1.0) <= 1e-12)
        return "";
    snprintf(buf, size, ", scaled by %g by its placement", sqrt(s2));
    return buf;
}

int rg2_cmd_info(int argc, char **argv)
{
    const char *path = NULL;
    int map = 0, near = 0, ray = 0;
    double x[3], r[6];
    for (int i = 1; i < argc; i++) {
        if (!strcmp(argv[i], "--help") || !strcmp(argv[i], "-h")) {
            usage(stdout);
            return RG2_EXIT_OK;
        } else if (!strcmp(argv[i], "--map"))
            map = 1;
        else if (!strcmp(argv[i], "--near")) {
            if (i + 1 >= argc) {
                fprintf(stderr, "rg2 info: --near needs three numbers X,Y,Z\n");
                return RG2_EXIT_USAGE;
            }
            if (rg2_cli_parse_n("info", "--near", argv[++i], x, 3, "three numbers X,Y,Z") ||
                rg2_cli_check_numbers("info", "--near", x, 3))
                return RG2_EXIT_USAGE;
            near = 1;
        } else if (!strcmp(argv[i], "--ray")) {
            if (i + 1 >= argc) {
                fprintf(stderr, "rg2 info: --ray needs six numbers X,Y,Z,DX,DY,DZ\n");
                return RG2_EXIT_USAGE;
            }
            if (rg2_cli_parse_n("info", "--ray", argv[++i], r, 6, "six numbers X,Y,Z,DX,DY,DZ") ||
                rg2_cli_check_numbers("info", "--ray", r, 6))
                return RG2_EXIT_USAGE;
            if (r[3] == 0 && r[4] == 0 && r[5] == 0) {
                fprintf(stderr, "rg2 info: --ray: the direction (DX, DY, DZ) is zero\n");
                return RG2_EXIT_USAGE;
            }
            ray = 1;
        }
        else if (argv[i][0] == '-' && argv[i][1]) {
            return rg2_cli_unknown_option("info", argv[i], usage, NULL);
        } else if (path) {
            fprintf(stderr, "rg2 info: more than one design file ('%s', '%s')\n", path, argv[i]);
            return RG2_EXIT_USAGE;
        } else
            path = argv[i];
    }
    if (!path) {
        usage(stderr);
        return RG2_EXIT_USAGE;
    }
    rg2_design *d;
    rg2_error err;
    if (rg2_design_load(path, &d, &err))
        return rg2_cli_report("info", &err);
    int ns = rg2_design_num_shapes(d);
    printf("design %s\nshapes:\n", path);
    for (int k = 0; k < ns; k++) {
        const rg2_shape *s = rg2_design_shape(d, k);
        const rg2_shape_desc *desc = rg2_shape_describe(s->kind);
        printf("  %c %-16s %s", 'A' + k % 26, rg2_design_shape_label(d, k), desc->name);
        for (int p = 0; p < desc->n_params; p++)
            printf(" %s=%g", desc->param_names[p], s->param[p]);
        char note[64];
        printf("%s\n", placement_note(s->xform, note, sizeof note));
    }
    /* counts per shape, reset after each surface through the list of the shapes it has (a
     * design of many one-shape surfaces went through every shape for every surface) */
    int *count = calloc((size_t)ns + 1, sizeof(int)), *seen = calloc((size_t)ns + 1, sizeof(int));
    if (!count || !seen) {
        free(count);
        free(seen);
        rg2_design_free(d);
        fprintf(stderr, "rg2 info: out of memory\n");
        return RG2_EXIT_FAIL;
    }
    for (int o = 0; o < rg2_design_num_surfaces(d); o++) {
        const rg2_mesh *m = rg2_design_mesh(d, o);
        const rg2_surface *s = rg2_design_surface(d, o);
        int nseen = 0;
        count[ns] = 0;
        for (int k = 0; k < s->nu * s->nv; k++) {
            int t = s->tag[k] < 0 ? ns : s->tag[k];
            if (t < ns && !count[t])
                seen[nseen++] = t;
            count[t]++;
        }
        qsort(seen, (size_t)nseen, sizeof *seen, cmp_int);
        printf("surface %d: mesh '%s': %d x %d control points (u %s, v %s) -> %d x %d = %d patches", o,
               rg2_design_mesh_name(d, o), m->nu, m->nv, m->su.closed ? "closed" : "open",
               m->sv.closed ? "closed" : "open", s->nu, s->nv, s->nu * s->nv);
        print_degrees(s);
        printf("\n");
        for (int q = 0; q < nseen; q++) {
            printf("  exact on %-16s %d patches\n", rg2_design_shape_label(d, seen[q]), count[seen[q]]);
            count[seen[q]] = 0;
        }
        printf("  %-25s %d patches\n", "transition", count[ns]);
        print_ends(d, o, m);
        print_orientation(d, o, s, m);
        printf("  smallest patch weight %.6g%s\n", rg2_surface_min_weight(s),
               rg2_surface_min_weight(s) > 0 ? "" : " (not positive: STEP/IGES export will refuse it)");
        if (map)
            for (int i = 0; i < s->nu; i++) {
                printf("    u %3d  ", i);
                for (int j = 0; j < s->nv; j++) {
                    int t = s->tag[i * s->nv + j];
                    putchar(t < 0 ? '.' : 'A' + t % 26);
                }
                putchar('\n');
            }
    }
    locators ls = {0, 0, NULL, NULL, NULL};
    if (near) {
        print_nearest(d, x);
        print_nearest_surface(d, &ls, x);
    }
    if (ray)
        print_ray(d, &ls, r);
    locators_free(&ls);
    for (int k = 0; k < rg2_design_num_notes(d); k++)
        printf("note: %s\n", rg2_design_note(d, k));
    free(count);
    free(seen);
    rg2_design_free(d);
    return RG2_EXIT_OK;
}
