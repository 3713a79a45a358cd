/* msh_check -- measure a gmsh mesh (.msh, format 2) of a design's STEP / IGES file against the
 * design's exact surfaces, for tests/cli/gmsh_examples.sh.
 *
 *   msh_check design.json mesh.msh [--surface K] [--list]
 *   msh_check --size design.json      (prints the design's size and its smallest surface's)
 *
 * The first form measures the mesh against every output surface of the design (with --surface,
 * only surface K, as written by rg2 build --surface K) and prints one line of key=value figures
 * (--list first names the patch of every flipped triangle and free edge off the boundary):
 *   faces              gmsh surfaces (elementary entities) that hold triangles
 *   patches, surfaces  the design's patches and surfaces (the faces of its files, face per patch
 *                      and face per mesh)
 *   nodes, tris        mesh nodes and triangles
 *   worst              the largest distance of a node from the design's surfaces (rg2's own
 *                      closest-point query, rg2_locator_closest), relative to the design's size
 *   free, free_len     triangle edges used by one triangle only, and their total length
 *   free_off           of those, the edges with an end node that is not on an open boundary of
 *                      the design (a side of a patch on the border of an open direction, not
 *                      collapsed to a pole): a seam gmsh did not see as one shared curve
 *   bnd_len            the length of the design's open boundary (every such side)
 *   nonmanifold        triangle edges used by more than two triangles
 *   misoriented        edges whose two triangles run through them the same way (faces turned
 *                      against each other across a seam)
 *   flipped            triangles whose normal points against rg2's normal Su x Sv (the mean of
 *                      the normals at their nodes' nearest points)
 *   degenerate, minq   triangles of quality 4 sqrt(3) A / (a^2 + b^2 + c^2) below 1e-3, and
 *                      the smallest quality
 *   area, area_rg2, area_rel  the mesh's area, the design's (Gauss-Legendre, 8 x 8 points a
 *                      patch) and their relative difference
 *   size               the design's size (box diagonal of its control points)
 * Exit 0 when measured, 1 when a file cannot be read. */
#include <rg2.h>

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

static _Noreturn void die(const char *what, const char *msg)
{
    fprintf(stderr, "msh_check: %s: %s\n", what, msg);
    exit(1);
}

typedef struct {
    int n_nodes, n_tris, n_faces; /* n_faces: gmsh surfaces (elementary tags) holding triangles */
    double *xyz; /* 3 per node, in node order */
    int *tri;    /* 3 node indices (0-based, node order) per triangle */
} msh;

/* Read the nodes and the 3-node triangles (type 2) of a gmsh format-2 ASCII file. */
static void read_msh(const char *path, msh *m)
{
    FILE *f = fopen(path, "r");
    if (!f)
        die(path, "cannot open");
    char line[4096];
    int *id2k = NULL, max_id = 0, cap_t = 0, cap_f = 0;
    char *seen = NULL;
    memset(m, 0, sizeof *m);
    while (fgets(line, sizeof line, f)) {
        if (!strncmp(line, "$Nodes", 6)) {
            if (!fgets(line, sizeof line, f) || sscanf(line, "%d", &m->n_nodes) != 1 || m->n_nodes < 0)
                die(path, "bad $Nodes");
            m->xyz = malloc(sizeof(double) * 3 * (size_t)(m->n_nodes + 1));
            int *ids = malloc(sizeof(int) * (size_t)(m->n_nodes + 1));
            if (!m->xyz || !ids)
                die(path, "out of memory");
            for (int k = 0; k < m->n_nodes; k++) {
                if (!fgets(line, sizeof line, f) ||
                    sscanf(line, "%d %lf %lf %lf", &ids[k], &m->xyz[3 * k], &m->xyz[3 * k + 1], &m->xyz[3 * k + 2]) != 4 ||
                    ids[k] < 1)
                    die(path, "bad node");
                if (ids[k] > max_id)
                    max_id = ids[k];
            }
            id2k = malloc(sizeof(int) * (size_t)(max_id + 1));
            if (!id2k)
                die(path, "out of memory");
            for (int k = 0; k <= max_id; k++)
                id2k[k] = -1;
            for (int k = 0; k < m->n_nodes; k++)
                id2k[ids[k]] = k;
            free(ids);
        } else if (!strncmp(line, "$Elements", 9)) {
            int n = 0;
            if (!id2k || !fgets(line, sizeof line, f) || sscanf(line, "%d", &n) != 1)
                die(path, "bad $Elements (or no $Nodes before it)");
            for (int k = 0; k < n; k++) {
                if (!fgets(line, sizeof line, f))
                    die(path, "short $Elements");
                int id, type, ntags, used, v[3], elem = -1;
                char *p = line;
                if (sscanf(p, "%d %d %d%n", &id, &type, &ntags, &used) != 3)
                    die(path, "bad element");
                if (type != 2)
                    continue;
                p += used;
                for (int t = 0; t < ntags; t++) {
                    int x;
                    if (sscanf(p, "%d%n", &x, &used) != 1)
                        die(path, "bad element tags");
                    if (t == 1)
                        elem = x;
                    p += used;
                }
                if (sscanf(p, "%d %d %d", &v[0], &v[1], &v[2]) != 3)
                    die(path, "bad triangle");
                if (m->n_tris == cap_t) {
                    cap_t = cap_t ? 2 * cap_t : 1024;
                    m->tri = realloc(m->tri, sizeof(int) * 3 * (size_t)cap_t);
                    if (!m->tri)
                        die(path, "out of memory");
                }
                if (elem >= 0) {
                    if (elem >= cap_f) {
                        int c = cap_f;
                        cap_f = elem + 1024;
                        seen = realloc(seen, (size_t)cap_f);
                        if (!seen)
                            die(path, "out of memory");
                        memset(seen + c, 0, (size_t)(cap_f - c));
                    }
                    m->n_faces += !seen[elem];
                    seen[elem] = 1;
                }
                for (int c = 0; c < 3; c++) {
                    if (v[c] < 1 || v[c] > max_id || id2k[v[c]] < 0)
                        die(path, "triangle names an unknown node");
                    m->tri[3 * m->n_tris + c] = id2k[v[c]];
                }
                m->n_tris++;
            }
        }
    }
    fclose(f);
    free(id2k);
    free(seen);
}

static double dist3(const double *a, const double *b)
{
    return sqrt((a[0] - b[0]) * (a[0] - b[0]) + (a[1] - b[1]) * (a[1] - b[1]) + (a[2] - b[2]) * (a[2] - b[2]));
}

/* A side of patch (i, j) (0 v=0, 1 u=1, 2 v=1, 3 u=0) whose control points coincide: a pole. */
static int side_collapsed(const rg2_surface *s, int i, int j, int side, double size)
{
    rg2_xpatch X;
    rg2_surface_patch_get(s, i, j, &X);
    int n = (side & 1) ? X.dv : X.du;
    double first[3] = {0, 0, 0};
    for (int a = 0; a <= n; a++) {
        int r = side == 1 ? X.du : side == 3 ? 0 : a, c = side == 0 ? 0 : side == 2 ? X.dv : a;
        double p[3];
        for (int d = 0; d < 3; d++)
            p[d] = X.h[r][c][d] / X.h[r][c][3];
        if (!a)
            memcpy(first, p, sizeof first);
        else if (dist3(p, first) > 1e-11 * size)
            return 0;
    }
    return 1;
}

/* 8-point Gauss-Legendre on [0, 1] */
static const double gx[8] = {0.019855071751231856, 0.10166676129318664, 0.2372337950418355, 0.4082826787521751,
                             0.5917173212478249,   0.7627662049581645,  0.8983332387068134, 0.9801449282487681};
static const double gw[8] = {0.050614268145188129, 0.11119051722668724, 0.15685332293894364, 0.18134189168918099,
                             0.18134189168918099,  0.15685332293894364, 0.11119051722668724, 0.050614268145188129};

static double norm3(const double *a) { return sqrt(a[0] * a[0] + a[1] * a[1] + a[2] * a[2]); }

static double surface_area(const rg2_surface *s)
{
    double A = 0;
    for (int i = 0; i < s->nu; i++)
        for (int j = 0; j < s->nv; j++)
            for (int a = 0; a < 8; a++)
                for (int b = 0; b < 8; b++) {
                    rg2_eval e;
                    rg2_surface_eval(s, i, j, gx[a], gx[b], 1, &e);
                    double c[3] = {e.su[1] * e.sv[2] - e.su[2] * e.sv[1], e.su[2] * e.sv[0] - e.su[0] * e.sv[2],
                                   e.su[0] * e.sv[1] - e.su[1] * e.sv[0]};
                    A += gw[a] * gw[b] * norm3(c);
                }
    return A;
}

/* Is (i, j, u, v) on an open boundary side of s that is not collapsed? */
static int on_open_boundary(const rg2_surface *s, int i, int j, double u, double v, double size)
{
    const double t = 1e-6;
    if (!s->closed_u && ((i == 0 && u <= t && !side_collapsed(s, i, j, 3, size)) ||
                         (i == s->nu - 1 && u >= 1 - t && !side_collapsed(s, i, j, 1, size))))
        return 1;
    if (!s->closed_v && ((j == 0 && v <= t && !side_collapsed(s, i, j, 0, size)) ||
                         (j == s->nv - 1 && v >= 1 - t && !side_collapsed(s, i, j, 2, size))))
        return 1;
    return 0;
}

/* Length of the open boundary of s (its sides not collapsed). */
static double boundary_length(const rg2_surface *s, double size)
{
    double L = 0;
    for (int i = 0; i < s->nu; i++)
        for (int j = 0; j < s->nv; j++)
            for (int side = 0; side < 4; side++) {
                int on = (side & 1) ? !s->closed_u && ((side == 3 && i == 0) || (side == 1 && i == s->nu - 1))
                                    : !s->closed_v && ((side == 0 && j == 0) || (side == 2 && j == s->nv - 1));
                if (!on || side_collapsed(s, i, j, side, size))
                    continue;
                for (int a = 0; a < 8; a++) {
                    rg2_eval e;
                    double u = side == 1 ? 1 : side == 3 ? 0 : gx[a], v = side == 0 ? 0 : side == 2 ? 1 : gx[a];
                    rg2_surface_eval(s, i, j, u, v, 1, &e);
                    L += gw[a] * norm3((side & 1) ? e.sv : e.su);
                }
            }
    return L;
}

typedef struct {
    int a, b, tri, fwd; /* a < b; fwd: the triangle runs a -> b */
} edge;

static int cmp_edge(const void *x, const void *y)
{
    const edge *p = x, *q = y;
    if (p->a != q->a)
        return p->a < q->a ? -1 : 1;
    return p->b < q->b ? -1 : p->b > q->b;
}

int main(int argc, char **argv)
{
    const char *dpath = NULL, *mpath = NULL;
    int only = -1, list = 0, size_only = 0;
    for (int k = 1; k < argc; k++) {
        if (!strcmp(argv[k], "--list"))
            list = 1;
        else if (!strcmp(argv[k], "--size"))
            size_only = 1;
        else if (!strcmp(argv[k], "--surface") && k + 1 < argc)
            only = atoi(argv[++k]);
        else if (!dpath)
            dpath = argv[k];
        else if (!mpath)
            mpath = argv[k];
        else
            die("usage", "msh_check design.json mesh.msh [--surface K]");
    }
    if (!dpath || (!mpath && !size_only))
        die("usage", "msh_check design.json mesh.msh [--surface K] [--list] | msh_check --size design.json");
    rg2_design *d;
    rg2_error err;
    if (rg2_design_load(dpath, &d, &err))
        die(dpath, err.msg);
    int ns = rg2_design_num_surfaces(d), k0 = 0, k1 = ns;
    if (only >= 0) {
        if (only >= ns)
            die(dpath, "--surface out of range");
        k0 = only, k1 = only + 1;
    }
    rg2_locator *L[64];
    if (k1 - k0 > 64)
        die(dpath, "more than 64 surfaces");
    double lo[3] = {INFINITY, INFINITY, INFINITY}, hi[3] = {-INFINITY, -INFINITY, -INFINITY};
    for (int k = k0; k < k1; k++) {
        double a[3], b[3];
        if (rg2_surface_box(rg2_design_surface(d, k), a, b))
            for (int c = 0; c < 3; c++) {
                lo[c] = fmin(lo[c], a[c]);
                hi[c] = fmax(hi[c], b[c]);
            }
    }
    double size = dist3(lo, hi), area_rg2 = 0, bnd = 0, smallest = INFINITY;
    int patches = 0;
    for (int k = k0; k < k1; k++) {
        const rg2_surface *s = rg2_design_surface(d, k);
        double a[3], b[3];
        if (rg2_surface_box(s, a, b))
            smallest = fmin(smallest, dist3(a, b));
        patches += s->nu * s->nv;
    }
    if (!mpath) { /* --size */
        printf("%.6g %.6g\n", size, smallest);
        rg2_design_free(d);
        return 0;
    }
    for (int k = k0; k < k1; k++) {
        const rg2_surface *s = rg2_design_surface(d, k);
        if (rg2_locator_build(s, &L[k - k0], &err))
            die(dpath, err.msg);
        area_rg2 += surface_area(s);
        bnd += boundary_length(s, size);
    }
    msh m;
    read_msh(mpath, &m);

    /* every node's nearest surface point: distance, normal, on an open boundary or not */
    double *nrm = calloc((size_t)m.n_nodes + 1, sizeof(double) * 3), worst = 0;
    int *where = calloc((size_t)m.n_nodes + 1, sizeof(int) * 4); /* surface, i, j of the nearest point */
    char *onb = calloc((size_t)m.n_nodes + 1, 1);
    if (!nrm || !onb || !where)
        die("msh_check", "out of memory");
    for (int n = 0; n < m.n_nodes; n++) {
        double best = INFINITY;
        rg2_hit h[64];
        for (int k = k0; k < k1; k++) {
            if (rg2_locator_closest(L[k - k0], &m.xyz[3 * n], &h[k - k0], &err))
                die(mpath, err.msg);
            if (h[k - k0].dist < best) {
                best = h[k - k0].dist;
                where[3 * n] = k, where[3 * n + 1] = h[k - k0].i, where[3 * n + 2] = h[k - k0].j;
                memcpy(&nrm[3 * n], h[k - k0].n, sizeof(double) * 3);
            }
        }
        worst = fmax(worst, best);
        for (int k = k0; k < k1; k++)
            if (h[k - k0].dist <= best + 1e-9 * size &&
                on_open_boundary(rg2_design_surface(d, k), h[k - k0].i, h[k - k0].j, h[k - k0].u, h[k - k0].v, size))
                onb[n] = 1;
    }

    /* triangles: area, quality, orientation against rg2's normal; edges */
    edge *E = malloc(sizeof(edge) * 3 * ((size_t)m.n_tris + 1));
    if (!E)
        die("msh_check", "out of memory");
    double area = 0, minq = 1;
    int degenerate = 0, flipped = 0;
    for (int t = 0; t < m.n_tris; t++) {
        const int *v = &m.tri[3 * t];
        const double *p0 = &m.xyz[3 * v[0]], *p1 = &m.xyz[3 * v[1]], *p2 = &m.xyz[3 * v[2]];
        double e1[3], e2[3], c[3];
        for (int q = 0; q < 3; q++)
            e1[q] = p1[q] - p0[q], e2[q] = p2[q] - p0[q];
        c[0] = e1[1] * e2[2] - e1[2] * e2[1];
        c[1] = e1[2] * e2[0] - e1[0] * e2[2];
        c[2] = e1[0] * e2[1] - e1[1] * e2[0];
        double A = 0.5 * norm3(c), a = dist3(p0, p1), b = dist3(p1, p2), cc = dist3(p2, p0);
        double q = a * a + b * b + cc * cc > 0 ? 4 * sqrt(3.0) * A / (a * a + b * b + cc * cc) : 0;
        area += A;
        minq = fmin(minq, q);
        degenerate += q < 1e-3;
        double nm[3] = {0, 0, 0};
        for (int k = 0; k < 3; k++)
            for (int r = 0; r < 3; r++)
                nm[r] += nrm[3 * v[k] + r];
        if (c[0] * nm[0] + c[1] * nm[1] + c[2] * nm[2] < 0) {
            flipped++;
            if (list)
                printf("flipped triangle %d: node %d on surface %d patch (%d, %d)\n", t, v[0], where[3 * v[0]],
                       where[3 * v[0] + 1], where[3 * v[0] + 2]);
        }
        for (int k = 0; k < 3; k++) {
            int x = v[k], y = v[(k + 1) % 3];
            E[3 * t + k] = (edge){x < y ? x : y, x < y ? y : x, t, x < y};
        }
    }
    size_t ne = 3 * (size_t)m.n_tris;
    qsort(E, ne, sizeof(edge), cmp_edge);
    int free_e = 0, free_off = 0, nonman = 0, misor = 0;
    double free_len = 0;
    for (size_t k = 0; k < ne;) {
        size_t r = k + 1;
        while (r < ne && E[r].a == E[k].a && E[r].b == E[k].b)
            r++;
        if (r - k == 1) {
            free_e++;
            free_len += dist3(&m.xyz[3 * E[k].a], &m.xyz[3 * E[k].b]);
            if (!onb[E[k].a] || !onb[E[k].b]) {
                free_off++;
                if (list)
                    printf("free edge off the boundary: nodes %d %d, on surface %d patch (%d, %d)\n", E[k].a, E[k].b,
                           where[3 * E[k].a], where[3 * E[k].a + 1], where[3 * E[k].a + 2]);
            }
        } else if (r - k == 2) {
            if (E[k].fwd == E[k + 1].fwd)
                misor++;
        } else
            nonman++;
        k = r;
    }
    printf("faces=%d patches=%d surfaces=%d nodes=%d tris=%d worst=%.2e free=%d free_off=%d free_len=%.6g bnd_len=%.6g nonmanifold=%d "
           "misoriented=%d flipped=%d degenerate=%d minq=%.3g area=%.8g area_rg2=%.8g area_rel=%.2e size=%.6g\n",
           m.n_faces, patches, k1 - k0, m.n_nodes, m.n_tris, worst / size, free_e, free_off, free_len, bnd, nonman, misor, flipped, degenerate,
           minq, area, area_rg2, area_rg2 > 0 ? fabs(area - area_rg2) / area_rg2 : 0.0, size);
    for (int k = k0; k < k1; k++)
        rg2_locator_free(L[k - k0]);
    rg2_design_free(d);
    free(m.xyz);
    free(m.tri);
    free(nrm);
    free(onb);
    free(where);
    free(E);
    return 0;
}
