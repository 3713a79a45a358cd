/* test_tess.c -- watertight tessellation: shared seam vertices, every edge in two triangles
 * on a closed torus, vertices and normals and curvatures on the exact torus, equal to
 * (to 1e-14) re-evaluation on an open random surface, and a pole without degenerate triangles.
 * Every check runs again on the same surfaces with a mixed pattern of patches replaced by
 * their exact degree elevations ((4,3), (5,3), (4,4), (3,5) next to bi-3: xmix.h), and the
 * two tessellations are compared. */
#define _POSIX_C_SOURCE 200809L /* mkdtemp */
#include "export_fixtures.h"
#include "xmix.h"

#include <stdio.h>
#include <stdlib.h>
#include <unistd.h>

/* Count how many triangles use each undirected edge: returns the number of edges used once
 * (boundary), and sets *over to the number used more than twice and *dup_dir to the number
 * of directed edges used twice in the same direction (inconsistent orientation). */
typedef struct {
    long long key;
    int dir;
} edge_rec;

static int cmp_edge(const void *a, const void *b)
{
    long long x = ((const edge_rec *)a)->key, y = ((const edge_rec *)b)->key;
    return x < y ? -1 : x > y;
}

static int edge_census(const rg2_tess *t, int *over, int *twice, int *same_dir)
{
    size_t ne = 3 * (size_t)t->n_triangles;
    edge_rec *e = malloc(ne * sizeof *e);
    for (int q = 0; q < t->n_triangles; q++)
        for (int k = 0; k < 3; k++) {
            int a = t->tri[3 * q + k], b = t->tri[3 * q + (k + 1) % 3];
            int lo = a < b ? a : b, hi = a < b ? b : a;
            e[3 * q + k].key = (long long)lo * t->n_vertices + hi;
            e[3 * q + k].dir = a < b;
        }
    qsort(e, ne, sizeof *e, cmp_edge);
    int once = 0;
    *over = *twice = *same_dir = 0;
    for (size_t i = 0; i < ne;) {
        size_t j = i;
        while (j < ne && e[j].key == e[i].key)
            j++;
        if (j - i == 1)
            once++;
        else if (j - i == 2) {
            (*twice)++;
            if (e[i].dir == e[i + 1].dir)
                (*same_dir)++;
        } else
            (*over)++;
        i = j;
    }
    free(e);
    return once;
}

/* Triangles counter-clockwise about the vertex normals, and none degenerate. */
static void check_orientation(const rg2_tess *t, const char *what)
{
    int bad = 0, degenerate = 0;
    for (int q = 0; q < t->n_triangles; q++) {
        const int *c = t->tri + 3 * q;
        if (c[0] == c[1] || c[1] == c[2] || c[0] == c[2])
            degenerate++;
        const double *a = t->pos + 3 * c[0], *b = t->pos + 3 * c[1], *d = t->pos + 3 * c[2];
        double e1[3] = {b[0] - a[0], b[1] - a[1], b[2] - a[2]}, e2[3] = {d[0] - a[0], d[1] - a[1], d[2] - a[2]};
        double n[3] = {e1[1] * e2[2] - e1[2] * e2[1], e1[2] * e2[0] - e1[0] * e2[2], e1[0] * e2[1] - e1[1] * e2[0]};
        double s = 0;
        for (int k = 0; k < 3; k++)
            s += n[k] * (t->normal[3 * c[0] + k] + t->normal[3 * c[1] + k] + t->normal[3 * c[2] + k]);
        if (!(s > 0))
            bad++;
    }
    CHECK(bad == 0, "%s: %d of %d triangles not counter-clockwise about the normal", what, bad, t->n_triangles);
    CHECK(degenerate == 0, "%s: %d degenerate triangles", what, degenerate);
}

static int cmp_int(const void *a, const void *b) { return *(const int *)a - *(const int *)b; }

static double dist2(const double *a, const double *b)
{
    double d0 = a[0] - b[0], d1 = a[1] - b[1], d2 = a[2] - b[2];
    return d0 * d0 + d1 * d1 + d2 * d2;
}

/* A vertex's grid line along one direction: its patch's index p that way, its parameter x there. */
static int grid_at(int p, double x, int d) { return p * d + (int)lround(x * d); }

/* b - a on a grid line of n intervals, wrapped to (-n/2, n/2] when the direction is closed. */
static int grid_step(int a, int b, int n, int closed)
{
    int s = b - a;
    if (closed) {
        s = ((s % n) + n) % n;
        if (2 * s > n)
            s -= n;
    }
    return s;
}

/* Quads split along the shorter diagonal (rg2.h): every grid quad whose four corners are distinct
 * vertices is cut by exactly one diagonal, and that one is no longer than the other (a tie to
 * 1e-12 of size^2 may go either way). The grid point (I, J) of a vertex comes from its patch and
 * (u, v); the lengths are measured here from the vertex positions. Returns bit 0 when some quad's
 * v00-v11 diagonal is the shorter one beyond a tie, bit 1 when some quad's v10-v01 is. */
static int check_diagonals(const rg2_surface *s, const rg2_tess *t, int d, double size, const char *what)
{
    int NU = s->nu * d, NV = s->nv * d, GU = NU + !s->closed_u, GV = NV + !s->closed_v;
    int *at = malloc(sizeof(int) * (size_t)GU * (size_t)GV), *cut = calloc((size_t)GU * (size_t)GV, sizeof(int));
    int *I = malloc(sizeof(int) * (size_t)t->n_vertices), *J = malloc(sizeof(int) * (size_t)t->n_vertices);
    CHECK(at && cut && I && J, "%s: out of memory", what);
    int checked = 0, bad = 0, longer = 0, both = 0;
    if (!at || !cut || !I || !J)
        goto out;
    for (int k = 0; k < GU * GV; k++)
        at[k] = -1;
    for (int v = 0; v < t->n_vertices; v++) {
        I[v] = grid_at(t->patch[v] / s->nv, t->uv[2 * v], d) % (s->closed_u ? NU : GU);
        J[v] = grid_at(t->patch[v] % s->nv, t->uv[2 * v + 1], d) % (s->closed_v ? NV : GV);
        at[I[v] * GV + J[v]] = v;
    }
    /* cut[quad] |= 1 for the v00-v11 diagonal, 2 for v10-v01 (quad = its corner (I0, J0)) */
    for (int q = 0; q < t->n_triangles; q++)
        for (int e = 0; e < 3; e++) {
            int a = t->tri[3 * q + e], b = t->tri[3 * q + (e + 1) % 3];
            int di = grid_step(I[a], I[b], NU, s->closed_u), dj = grid_step(J[a], J[b], NV, s->closed_v);
            if ((di != 1 && di != -1) || (dj != 1 && dj != -1))
                continue;
            int I0 = di > 0 ? I[a] : I[b], J0 = dj > 0 ? J[a] : J[b];
            cut[I0 * GV + J0] |= di == dj ? 1 : 2;
        }
    for (int i0 = 0; i0 < NU; i0++)
        for (int j0 = 0; j0 < NV; j0++) {
            int i1 = (i0 + 1) % GU, j1 = (j0 + 1) % GV;
            int v00 = at[i0 * GV + j0], v10 = at[i1 * GV + j0], v11 = at[i1 * GV + j1], v01 = at[i0 * GV + j1];
            if (v00 < 0 || v10 < 0 || v11 < 0 || v01 < 0) /* merged into a pole vertex */
                continue;
            checked++;
            int c = cut[i0 * GV + j0];
            double dm = dist2(t->pos + 3 * v00, t->pos + 3 * v11), da = dist2(t->pos + 3 * v10, t->pos + 3 * v01);
            bad += c != 1 && c != 2;
            if ((c == 1 && dm > da + 1e-12 * size * size) || (c == 2 && da > dm + 1e-12 * size * size))
                longer++;
            both |= dm < da - 1e-12 * size * size ? 1 : da < dm - 1e-12 * size * size ? 2 : 0;
        }
    CHECK(checked > 0 && bad == 0 && longer == 0,
          "%s: of %d quads, %d not cut by exactly one diagonal, %d cut along the longer one", what, checked, bad,
          longer);
out:
    free(at);
    free(cut);
    free(I);
    free(J);
    return both;
}

/* Same vertices (to 1e-15 of the size), normals (1e-13) and curvatures (1e-10 relative to
 * max(|value|, 1 / size): next to a pole |Su| ~ v |Suv| amplifies the rounding of either form;
 * the pole itself, the vertex of more than 8 triangles, is left out: its curvature is taken
 * 1e-6 inside the patch, where the amplification is ~1e12) and triangles: a surface with
 * elevated patches tessellates like the original. The triangles come quad by quad in the same
 * order; a quad may take the other diagonal only where its two diagonals are equally long to
 * rounding (1e-12 of size^2). */
static void same_tess(const rg2_tess *a, const rg2_tess *b, double size, const char *what)
{
    CHECK(a->n_vertices == b->n_vertices && a->n_triangles == b->n_triangles, "%s: %d/%d vertices, %d/%d triangles",
          what, a->n_vertices, b->n_vertices, a->n_triangles, b->n_triangles);
    if (a->n_vertices != b->n_vertices || a->n_triangles != b->n_triangles)
        return;
    double dp = 0, dn = 0, dk = 0;
    int *valence = calloc((size_t)a->n_vertices, sizeof *valence);
    for (int q = 0; q < 3 * a->n_triangles; q++)
        valence[a->tri[q]]++;
    for (int v = 0; v < a->n_vertices; v++)
        for (int k = 0; k < 3; k++) {
            dp = fmax(dp, fabs(a->pos[3 * v + k] - b->pos[3 * v + k]) / size);
            dn = fmax(dn, fabs(a->normal[3 * v + k] - b->normal[3 * v + k]));
            if (a->K && b->K && valence[v] <= 8)
                dk = fmax(dk, fmax(fabs(a->K[v] - b->K[v]) / (fabs(b->K[v]) + 1 / (size * size)),
                                   fabs(a->H[v] - b->H[v]) / (fabs(b->H[v]) + 1 / size)));
        }
    free(valence);
    int flips = 0, same_tri = 1;
    for (int q = 0; q < a->n_triangles; q++) {
        int x[3], y[3];
        memcpy(x, a->tri + 3 * q, sizeof x);
        memcpy(y, b->tri + 3 * q, sizeof y);
        qsort(x, 3, sizeof(int), cmp_int);
        qsort(y, 3, sizeof(int), cmp_int);
        if (!memcmp(x, y, sizeof x))
            continue;
        /* X, Y: the vertices only in a's / b's triangle; P, Q the two shared ones. One of
         * (XP, YQ), (XQ, YP) is the pair of diagonals of the quad. */
        int X = -1, Y = -1, PQ[2], np = 0;
        for (int k = 0; k < 3; k++) {
            int in_y = x[k] == y[0] || x[k] == y[1] || x[k] == y[2];
            int in_x = y[k] == x[0] || y[k] == x[1] || y[k] == x[2];
            if (!in_y)
                X = x[k];
            else if (np < 2)
                PQ[np++] = x[k];
            if (!in_x)
                Y = y[k];
        }
        flips++;
        if (X < 0 || Y < 0 || np != 2) {
            same_tri = 0;
            continue;
        }
        double xp = dist2(a->pos + 3 * X, a->pos + 3 * PQ[0]), yq = dist2(a->pos + 3 * Y, a->pos + 3 * PQ[1]);
        double xq = dist2(a->pos + 3 * X, a->pos + 3 * PQ[1]), yp = dist2(a->pos + 3 * Y, a->pos + 3 * PQ[0]);
        if (!(fmin(fabs(xp - yq), fabs(xq - yp)) <= 1e-12 * size * size))
            same_tri = 0;
    }
    int same_uv = !memcmp(a->uv, b->uv, 2 * sizeof(double) * (size_t)a->n_vertices) &&
                  !memcmp(a->patch, b->patch, sizeof(int) * (size_t)a->n_vertices);
    printf("%s: elevated vs original tessellation: position %.1e, normal %.1e, curvature %.1e (relative), "
           "triangles the same but %d diagonal flips at ties, (patch, u, v) %s\n",
           what, dp, dn, dk, flips, same_uv ? "identical" : "differ");
    CHECK(dp <= 1e-15 && dn <= 1e-13 && dk <= 1e-10, "%s: elevated tessellation differs: p %.3g n %.3g K/H %.3g",
          what, dp, dn, dk);
    CHECK(same_tri && same_uv, "%s: same triangles but for diagonals at ties %d (%d flips), same (patch, u, v) %d",
          what, same_tri, flips, same_uv);
}

/* Every vertex is the grid evaluator's point of its patch and (u, v), bit for bit
 * (rg2_surface_grid at d + 1 points per patch edge: the vertices are copied from the grid into
 * the mesh's arrays): positions, normals and, when t has them, K and H. Vertices on a patch side
 * (a or b at 0 or d) are exempt where `sides_exempt` (collapsed sides are re-evaluated at their
 * limit). Each grid point of the surface is some vertex's: every (patch, a, b) owned is counted. */
static void check_vs_grid(const rg2_surface *s, const rg2_tess *t, int d, int sides_exempt, const char *what)
{
    int n = d + 1;
    size_t pts = (size_t)s->nu * (size_t)s->nv * (size_t)n * (size_t)n;
    double *pos = malloc(3 * pts * sizeof(double)), *nrm = malloc(3 * pts * sizeof(double));
    double *K = malloc(pts * sizeof(double)), *H = malloc(pts * sizeof(double));
    rg2_grid_out go = {.pos = pos, .normal = nrm, .K = t->K ? K : NULL, .H = t->K ? H : NULL};
    rg2_error err;
    CHECK(pos && nrm && K && H, "%s: out of memory", what);
    if (!pos || !nrm || !K || !H)
        goto out;
    CHECK_OK(rg2_surface_grid(s, n, n, 1, &go, &err), &err);
    int differ = 0, compared = 0, bad_uv = 0;
    for (int v = 0; v < t->n_vertices; v++) {
        double ua = t->uv[2 * v] * d, vb = t->uv[2 * v + 1] * d;
        int a = (int)lround(ua), b = (int)lround(vb);
        if (fabs(ua - a) > 1e-12 || fabs(vb - b) > 1e-12 || a < 0 || a > d || b < 0 || b > d || t->patch[v] < 0 ||
            t->patch[v] >= s->nu * s->nv) {
            bad_uv++;
            continue;
        }
        if (sides_exempt && (a == 0 || a == d || b == 0 || b == d))
            continue;
        size_t k = ((size_t)t->patch[v] * (size_t)n + (size_t)a) * (size_t)n + (size_t)b;
        compared++;
        differ += memcmp(t->pos + 3 * v, pos + 3 * k, 3 * sizeof(double)) != 0 ||
                  memcmp(t->normal + 3 * v, nrm + 3 * k, 3 * sizeof(double)) != 0 ||
                  (t->K && (memcmp(&t->K[v], &K[k], sizeof(double)) != 0 || memcmp(&t->H[v], &H[k], sizeof(double)) != 0));
    }
    CHECK(bad_uv == 0, "%s: %d vertices with a (patch, u, v) off the grid", what, bad_uv);
    CHECK(differ == 0 && compared > 0, "%s: %d of %d vertices differ from the grid evaluator's point", what, differ,
          compared);
out:
    free(pos);
    free(nrm);
    free(K);
    free(H);
}

static void torus_mesh(int mixed)
{
    const double R = 13.0, r = 4.0;
    rg2_surface s;
    rg2_error err;
    rg2_tess t;
    CHECK_OK(fx_torus(R, r, 8, 6, &s, &err), &err);
    if (mixed)
        CHECK_OK(xmix_elevate(&s, &err), &err);
    int d = 8;
    CHECK_OK(rg2_tessellate(&s, d, 1, &t, &err), &err);
    CHECK(t.n_vertices == 8 * d * 6 * d, "torus: %d vertices, expected %d (seams shared)", t.n_vertices, 8 * d * 6 * d);
    CHECK(t.n_triangles == 2 * 8 * d * 6 * d, "torus: %d triangles", t.n_triangles);
    int over, twice, same;
    int once = edge_census(&t, &over, &twice, &same);
    CHECK(once == 0 && over == 0, "torus: %d edges in one triangle, %d in more than two (not watertight)", once, over);
    CHECK(same == 0, "torus: %d edges used twice in the same direction", same);
    CHECK(twice == 3 * t.n_triangles / 2, "torus: %d edges in two triangles", twice);
    check_orientation(&t, "torus");
    check_vs_grid(&s, &t, d, 0, "torus");
    double worst_p = 0, worst_n = 0, worst_k = 0, worst_h = 0, sign = 0;
    for (int v = 0; v < t.n_vertices; v++) {
        const double *p = t.pos + 3 * v, *n = t.normal + 3 * v;
        worst_p = fmax(worst_p, fx_torus_dist(R, r, p) / R);
        double rho = hypot(p[0], p[1]), cv = (rho - R) / r;
        double ex[3] = {(p[0] - R * p[0] / rho) / r, (p[1] - R * p[1] / rho) / r, p[2] / r};
        double dp = n[0] * ex[0] + n[1] * ex[1] + n[2] * ex[2];
        if (sign == 0)
            sign = dp > 0 ? 1 : -1;
        worst_n = fmax(worst_n, fabs(sign * dp - 1.0));
        double K = cv / (r * (R + r * cv)), H = (R + 2 * r * cv) / (2 * r * (R + r * cv));
        worst_k = fmax(worst_k, fabs(t.K[v] - K) * r * r);
        worst_h = fmax(worst_h, fabs(fabs(t.H[v]) - fabs(H)) * r);
    }
    CHECK(worst_p <= 1e-14, "torus: vertex off the torus by %.3g relative", worst_p);
    CHECK(worst_n <= 1e-13, "torus: normal off the exact normal by %.3g", worst_n);
    CHECK(worst_k <= 1e-10 && worst_h <= 1e-10, "torus: curvature K %.3g H %.3g off (relative)", worst_k, worst_h);
    printf("torus d=%d%s: %d vertices, %d triangles, watertight; on-surface %.1e, normal %.1e, K %.1e, H %.1e\n", d,
           mixed ? " (mixed degrees)" : "", t.n_vertices, t.n_triangles, worst_p, worst_n, worst_k, worst_h);
    if (mixed) {
        rg2_surface b;
        rg2_tess tb;
        CHECK_OK(fx_torus(R, r, 8, 6, &b, &err), &err);
        CHECK_OK(rg2_tessellate(&b, d, 1, &tb, &err), &err);
        same_tess(&t, &tb, 2 * (R + r), "torus");
        rg2_tess_free(&tb);
        rg2_surface_free(&b);
    }
    rg2_tess_free(&t);
    rg2_surface_free(&s);
}

/* An open random surface of nu x nv control points ((nu - 3) x (nv - 3) patches: 4 gives a single
 * patch row, which must tessellate like any other). */
static void random_mesh(int nu, int nv, int mixed)
{
    rg2_surface s;
    rg2_error err;
    rg2_tess t;
    CHECK_OK(fx_random(7, nu, nv, &s, &err), &err);
    if (mixed)
        CHECK_OK(xmix_elevate(&s, &err), &err);
    int d = 5;
    CHECK_OK(rg2_tessellate(&s, d, 0, &t, &err), &err);
    int GU = s.nu * d + 1, GV = s.nv * d + 1;
    CHECK(t.n_vertices == GU * GV, "random: %d vertices, expected %d", t.n_vertices, GU * GV);
    CHECK(t.K == NULL && t.H == NULL, "random: curvature arrays without request");
    check_vs_grid(&s, &t, d, 0, "random");
    /* vertices come from the grid evaluator (grid.c): equal to the independent per-point
     * evaluation at their (u, v) to rounding (<= 1e-14 relative) */
    double scale = rg2t_surface_scale(&s), dev_p = 0, dev_n = 0;
    for (int v = 0; v < t.n_vertices; v++) {
        rg2_eval e;
        rg2_surface_eval(&s, t.patch[v] / s.nv, t.patch[v] % s.nv, t.uv[2 * v], t.uv[2 * v + 1], 1, &e);
        for (int k = 0; k < 3; k++) {
            dev_p = fmax(dev_p, fabs(e.p[k] - t.pos[3 * v + k]) / scale);
            dev_n = fmax(dev_n, fabs(e.n[k] - t.normal[3 * v + k]));
        }
    }
    CHECK(dev_p <= 1e-14 && dev_n <= 1e-14, "random: vertices differ from the patch evaluation at their (u, v): "
          "position %.3g, normal %.3g", dev_p, dev_n);
    /* seam vertices: the neighbour patch's evaluation of the same seam point is within rounding */
    double gap = 0;
    for (int v = 0; v < t.n_vertices; v++) {
        int p = t.patch[v], i = p / s.nv, j = p % s.nv;
        if (t.uv[2 * v] == 0.0 && i > 0) {
            rg2_eval e;
            rg2_surface_eval(&s, i - 1, j, 1.0, t.uv[2 * v + 1], 0, &e);
            for (int k = 0; k < 3; k++)
                gap = fmax(gap, fabs(e.p[k] - t.pos[3 * v + k]));
        }
    }
    CHECK(gap <= 1e-12 * rg2t_surface_scale(&s), "random: seam evaluated from both sides differs by %.3g", gap);
    int over, twice, same;
    int once = edge_census(&t, &over, &twice, &same);
    CHECK(once == 2 * (GU - 1) + 2 * (GV - 1), "random: %d boundary edges, expected %d", once, 2 * (GU - 1) + 2 * (GV - 1));
    CHECK(over == 0 && same == 0, "random: %d edges over-used, %d mis-oriented", over, same);
    check_orientation(&t, "random");
    CHECK(check_diagonals(&s, &t, d, scale, "random") == 3, "random: no quad with a diagonal shorter than the other");
    printf("random open %d x %d patches d=%d%s: %d vertices, = rg2_surface_eval to 1e-14, seam gap %.1e\n", s.nu, s.nv,
           d, mixed ? " (mixed degrees)" : "", t.n_vertices, gap);
    rg2_tess_free(&t);
    rg2_surface_free(&s);
}

static void pole_mesh(int mixed)
{
    rg2_surface s;
    rg2_error err;
    rg2_tess t;
    CHECK_OK(fx_pole(6, 7, &s, &err), &err);
    if (mixed == 2) /* every patch of degree (5,3): no bi-3 patch left to size the tolerances */
        CHECK_OK(rg2t_elevate_some(&s, 5, 3, 1, 0, &err), &err);
    if (mixed) {
        if (mixed == 1)
            CHECK_OK(xmix_elevate(&s, &err), &err);
        int fan = 0; /* patches of the pole row (j = 0) that are of higher degree */
        for (int i = 0; i < s.nu; i++)
            fan += rg2_surface_xpatch(&s, i, 0) != NULL;
        CHECK(fan >= 4, "%d of %d pole patches elevated", fan, s.nu);
    }
    int d = 6;
    CHECK_OK(rg2_tessellate(&s, d, 1, &t, &err), &err);
    int ring = s.nu * d, rows = s.nv * d + 1;
    CHECK(t.n_vertices == ring * (rows - 1) + 1, "pole: %d vertices, expected %d (pole row merged)", t.n_vertices,
          ring * (rows - 1) + 1);
    CHECK(t.n_triangles == 2 * ring * (rows - 1) - ring, "pole: %d triangles, expected %d", t.n_triangles,
          2 * ring * (rows - 1) - ring);
    check_orientation(&t, "pole");
    check_diagonals(&s, &t, d, rg2t_surface_scale(&s), "pole");
    check_vs_grid(&s, &t, d, 1, "pole");
    int over, twice, same;
    int once = edge_census(&t, &over, &twice, &same);
    CHECK(once == ring && over == 0 && same == 0, "pole: %d boundary edges (expected %d), %d over-used, %d mis-oriented",
          once, ring, over, same);
    /* the pole vertex: on the axis, normal along the axis (exact limit) */
    double worst = 1;
    for (int v = 0; v < t.n_vertices; v++)
        if (hypot(t.pos[3 * v], t.pos[3 * v + 1]) < 1e-9)
            worst = fmin(worst, fabs(t.normal[3 * v + 2]));
    CHECK(fabs(worst - 1.0) <= 1e-12, "pole: pole normal z %.17g, expected +-1", worst);
    /* rg2_surface_eval_limit gives the pole vertex's normal and curvatures at every u of the fan
     * (the surface is one of revolution: K, H are the same all round, up to their rounding of
     * about 1e-14 / 3e-5^2 next to the pole) */
    int pv = -1;
    for (int v = 0; v < t.n_vertices && pv < 0; v++)
        if (hypot(t.pos[3 * v], t.pos[3 * v + 1]) < 1e-9)
            pv = v;
    double dn = 0, dK = 0, dH = 0;
    for (int i = 0; pv >= 0 && i < s.nu; i++)
        for (int a = 0; a <= 4; a++) {
            rg2_eval e;
            rg2_surface_eval_limit(&s, i, 0, a / 4.0, 0.0, 2, &e);
            CHECK(e.flags == RG2_EVAL_POLE_LIMIT, "pole: eval_limit flags %#x at patch %d, u = %g", e.flags, i, a / 4.0);
            for (int k = 0; k < 3; k++)
                dn = fmax(dn, fabs(e.n[k] - t.normal[3 * pv + k]));
            dK = fmax(dK, fabs(e.K - t.K[pv]) / fabs(t.K[pv]));
            dH = fmax(dH, fabs(e.H - t.H[pv]) / fabs(t.H[pv]));
        }
    rg2_eval en; /* a NaN parameter on the pole side: undefined, no pole limit (the limit is NaN) */
    rg2_surface_eval_limit(&s, 0, 0, NAN, 0.0, 2, &en);
    CHECK((en.flags & (RG2_EVAL_NORMAL_UNDEFINED | RG2_EVAL_POLE_LIMIT)) == RG2_EVAL_NORMAL_UNDEFINED,
          "pole: eval_limit at u = NaN: flags %#x", en.flags);
    CHECK(pv >= 0 && dn <= 1e-12 && dK <= 1e-4 && dH <= 1e-4,
          "pole: rg2_surface_eval_limit vs the pole vertex: normal %.3g, K %.3g, H %.3g (relative)", dn, dK, dH);
    printf("pole%s: rg2_surface_eval_limit vs the pole vertex over the fan: normal %.2g, K %.2g, H %.2g (relative)\n",
           mixed == 2 ? " (all (5,3))" : mixed ? " (mixed degrees)" : "", dn, dK, dH);
    printf("pole%s: %d vertices, %d triangles, no degenerate triangle, pole normal |z| = %.17g\n",
           mixed == 2 ? " (all (5,3))" : mixed ? " (mixed degrees)" : "", t.n_vertices, t.n_triangles, worst);
    if (mixed) {
        rg2_surface b;
        rg2_tess tb;
        CHECK_OK(fx_pole(6, 7, &b, &err), &err);
        CHECK_OK(rg2_tessellate(&b, d, 1, &tb, &err), &err);
        same_tess(&t, &tb, rg2t_surface_scale(&b), mixed == 2 ? "pole, all (5,3)" : "pole");
        rg2_tess_free(&tb);
        rg2_surface_free(&b);
    }
    rg2_tess_free(&t);
    rg2_surface_free(&s);
}

/* The general-quadratic saddle cap of Fig. 15 (cap patches of degree (5,3) next to bi-3 body
 * patches, one pole): watertight, the pole one vertex, vertices equal to the exact evaluation
 * at their (patch, u, v), and the same tessellation with every patch elevated to (5,5). */
static void cap_mesh(void)
{
    rg2_design *dz = NULL;
    rg2_error err;
    CHECK_OK(rg2_design_load("examples/fig15_saddle_caps.json", &dz, &err), &err);
    if (!dz)
        return;
    const rg2_surface *s = rg2_design_surface(dz, 1);
    int n5 = 0, cap5 = 0;
    for (int i = 0; i < s->nu; i++)
        for (int j = 0; j < s->nv; j++)
            if (rg2_surface_xpatch(s, i, j) && rg2_surface_xpatch(s, i, j)->du == 5) {
                n5++;
                cap5 += j < 3; /* the cap: the first three patch rows (south end) */
            }
    CHECK(cap5 == 3 * s->nu, "Fig. 15 general cap: %d cap patches of degree (5,3), expected %d", cap5, 3 * s->nu);
    int d = 6;
    rg2_tess t;
    CHECK_OK(rg2_tessellate(s, d, 1, &t, &err), &err);
    int ring = s->nu * d, rows = s->nv * d + 1;
    CHECK(t.n_vertices == ring * (rows - 1) + 1 && t.n_triangles == 2 * ring * (rows - 1) - ring,
          "cap: %d vertices (expected %d, pole merged), %d triangles (expected %d)", t.n_vertices,
          ring * (rows - 1) + 1, t.n_triangles, 2 * ring * (rows - 1) - ring);
    int over, twice, same;
    int once = edge_census(&t, &over, &twice, &same);
    CHECK(once == ring && over == 0 && same == 0, "cap: %d boundary edges (expected %d), %d over-used, %d mis-oriented",
          once, ring, over, same);
    check_orientation(&t, "cap");
    double scale = rg2t_surface_scale(s), dev = 0, devn = 0;
    CHECK(check_diagonals(s, &t, d, scale, "cap") == 3, "cap: no quad with a diagonal shorter than the other");
    for (int v = 0; v < t.n_vertices; v++) {
        rg2_eval e;
        rg2_surface_eval(s, t.patch[v] / s->nv, t.patch[v] % s->nv, t.uv[2 * v], t.uv[2 * v + 1], 1, &e);
        for (int k = 0; k < 3; k++)
            dev = fmax(dev, fabs(e.p[k] - t.pos[3 * v + k]) / scale);
        if (!(e.flags & RG2_EVAL_NORMAL_UNDEFINED))
            for (int k = 0; k < 3; k++)
                devn = fmax(devn, fabs(e.n[k] - t.normal[3 * v + k]));
    }
    CHECK(dev <= 1e-15 && devn <= 1e-14, "cap: vertices off the exact evaluation by %.3g, normals by %.3g", dev, devn);
    printf("Fig. 15 general cap (%d patches of degree (5,3)) d=%d: %d vertices, %d triangles, watertight, "
           "vertices = rg2_surface_eval to %.1e, normals %.1e\n",
           n5, d, t.n_vertices, t.n_triangles, dev, devn);
    rg2_surface x;
    rg2_tess tx;
    CHECK_OK(xmix_raise_copy(s, 5, 5, &x, &err), &err);
    CHECK_OK(rg2_tessellate(&x, d, 1, &tx, &err), &err);
    same_tess(&tx, &t, scale, "cap, every patch elevated to (5,5)");
    rg2_tess_free(&tx);
    rg2_surface_free(&x);
    rg2_tess_free(&t);
    rg2_design_free(dz);
}

/* The unit sphere closed by bi-3 caps: the pole vertices carry the limit normal (n = p) and the
 * sphere's curvatures (K = 1, H = -1), taken a short step inside the pole patches. */
static void sphere_poles_kh(void)
{
    rg2_mesh m;
    rg2_surface s;
    rg2_error err;
    rg2_tess t;
    CHECK_OK(rg2t_capped_sphere(&m, &s, &err), &err);
    CHECK_OK(rg2_tessellate(&s, 4, 1, &t, &err), &err);
    double nerr = 0, kerr = 0, kpole = 0;
    int poles = 0;
    for (int i = 0; i < t.n_vertices; i++) {
        const double *p = t.pos + 3 * i, *n = t.normal + 3 * i;
        nerr = fmax(nerr, fabs(1.0 - (n[0] * p[0] + n[1] * p[1] + n[2] * p[2])));
        double e = fmax(fabs(t.K[i] - 1.0), fabs(t.H[i] + 1.0));
        kerr = fmax(kerr, e);
        if (fabs(p[2]) > 1.0 - 1e-12) {
            poles++;
            kpole = fmax(kpole, e);
        }
    }
    printf("capped unit sphere: %d pole vertices, normals n.p within %.1e of 1, K and H at the poles within %.1e "
           "(elsewhere %.1e)\n",
           poles, nerr, kpole, kerr);
    CHECK(poles == 2, "capped sphere: %d pole vertices", poles);
    CHECK(nerr <= 1e-13 && kpole <= 1e-3, "capped sphere poles: normal %.3g, K/H %.3g (the step inside was too short)",
          nerr, kpole);
    rg2_tess_free(&t);
    rg2_surface_free(&s);
    rg2_mesh_free(&m);
}

/* The control points of patch i of the surfaces made patch by patch below (weights 1):
 * `which` 0: patch 0 the unit square, patch 1 a triangle whose v = 1 side is patch 0's corner
 * (1, 1); 1: a bow tie, two triangles whose shared side (patch 0's u = 1, patch 1's u = 0) is
 * the point (1, 0.5); 2: one patch closed in u (its u = 0 and u = 1 columns equal), a tube
 * along z around a teardrop. */
static void hand_point(int which, int i, int r, int c, double p[3])
{
    double x = r / 3.0, y = c / 3.0;
    if (which == 0) {
        p[0] = i ? 1.0 + x * (1.0 - y) : x;
        p[1] = y;
        p[2] = 0.0;
    } else if (which == 1) {
        p[0] = i + x;
        p[1] = 0.5 + (y - 0.5) * (i ? x : 1.0 - x);
        p[2] = 0.0;
    } else {
        static const double loop[4][2] = {{0, 0}, {2, 2}, {-2, 2}, {0, 0}};
        p[0] = loop[r][0];
        p[1] = loop[r][1];
        p[2] = y;
    }
}

static void hand_surface(int which, rg2_surface *s)
{
    memset(s, 0, sizeof *s);
    s->nu = which == 2 ? 1 : 2;
    s->nv = 1;
    s->closed_u = which == 2;
    s->patch = calloc((size_t)s->nu, sizeof *s->patch);
    for (int i = 0; s->patch && i < s->nu; i++)
        for (int r = 0; r < 4; r++)
            for (int c = 0; c < 4; c++) {
                hand_point(which, i, r, c, s->patch[i].h[r][c]);
                s->patch[i].h[r][c][3] = 1.0;
            }
}

/* Collapsed sides that are not a whole pole row (a surface made patch by patch): a triangle
 * patch's v = 1 side in patch column 1 alone, and a u = 0 side past column 0 (a bow tie's
 * waist). Only the d + 1 grid points of the collapsed side are merged into one vertex: the
 * vertex count is the grid's less d, and every grid point of every patch has a vertex at its
 * surface point (a merge of other grid points loses one). And a tube of one patch closed in u
 * at density 1: one grid line in u, so every quad's corners repeat and no triangle is left (a
 * degenerate triangle is never written, rg2.h). */
static void lone_collapsed_sides(void)
{
    rg2_error err;
    for (int which = 0; which < 2; which++) {
        const char *what = which ? "bow tie (a collapsed u = 0 side in column 1)" : "a triangle patch's v = 1 side";
        rg2_surface s;
        rg2_tess t;
        hand_surface(which, &s);
        CHECK(s.patch != NULL, "%s: out of memory", what);
        int d = 4;
        if (!s.patch || rg2_tessellate(&s, d, 0, &t, &err) != RG2_OK) {
            CHECK(0, "%s: %s", what, err.msg);
            rg2_surface_free(&s);
            continue;
        }
        int grid = (2 * d + 1) * (d + 1);
        CHECK(t.n_vertices == grid - d, "%s: %d vertices, want %d (the side's %d grid points in one)", what,
              t.n_vertices, grid - d, d + 1);
        int missing = 0;
        for (int i = 0; i < 2; i++)
            for (int a = 0; a <= d; a++)
                for (int b = 0; b <= d; b++) {
                    rg2_eval e;
                    rg2_surface_eval(&s, i, 0, (double)a / d, (double)b / d, 0, &e);
                    double near = INFINITY;
                    for (int v = 0; v < t.n_vertices; v++)
                        near = fmin(near, dist2(t.pos + 3 * v, e.p));
                    missing += !(near <= 1e-24);
                }
        CHECK(missing == 0, "%s: %d grid points without a vertex at their surface point", what, missing);
        check_orientation(&t, what);
        rg2_tess_free(&t);
        rg2_surface_free(&s);
    }
    rg2_surface tube;
    rg2_tess t;
    hand_surface(2, &tube);
    CHECK(tube.patch != NULL, "tube: out of memory");
    if (tube.patch && rg2_tessellate(&tube, 1, 0, &t, &err) == RG2_OK) {
        CHECK(t.n_vertices == 2 && t.n_triangles == 0,
              "one patch closed in u at density 1: %d vertices, %d triangles (want 2, 0: every quad's corners repeat)",
              t.n_vertices, t.n_triangles);
        check_orientation(&t, "one patch closed in u at density 1");
        rg2_tess_free(&t);
    } else
        CHECK(0, "one patch closed in u at density 1: %s", err.msg);
    rg2_surface_free(&tube);
}

/* x -> A (x, 1) applied to the homogeneous control points (h, w): still rational bi-cubic, and
 * sides collapsed before stay collapsed. */
static void affine_map(rg2_surface *s, const double A[3][4])
{
    for (int p = 0; p < s->nu * s->nv; p++)
        for (int a = 0; a < 4; a++)
            for (int b = 0; b < 4; b++) {
                double *h = s->patch[p].h[a][b], x[4] = {h[0], h[1], h[2], h[3]};
                for (int k = 0; k < 3; k++)
                    h[k] = A[k][0] * x[0] + A[k][1] * x[1] + A[k][2] * x[2] + A[k][3] * x[3];
            }
}

/* The pole surface under an affine map (sheared, stretched and moved off the axis, applied to the
 * homogeneous control points: still rational bi-cubic, the pole still collapsed): its quads are
 * no longer symmetric trapezoids, so next to merged vertices (the general triangle path) the
 * choice of the shorter diagonal is measured for real. */
static void sheared_pole(void)
{
    static const double A[3][4] = {{1.0, 0.7, 0.3, 5.0}, {0.2, 2.5, 0.4, 40.0}, {-0.3, 0.1, 1.5, -7.0}};
    rg2_surface s;
    rg2_error err;
    rg2_tess t;
    CHECK_OK(fx_pole(6, 7, &s, &err), &err);
    affine_map(&s, A);
    int d = 6;
    CHECK_OK(rg2_tessellate(&s, d, 0, &t, &err), &err);
    int ring = s.nu * d, rows = s.nv * d + 1;
    CHECK(t.n_vertices == ring * (rows - 1) + 1, "sheared pole: %d vertices, expected %d", t.n_vertices,
          ring * (rows - 1) + 1);
    check_orientation(&t, "sheared pole");
    CHECK(check_diagonals(&s, &t, d, rg2t_surface_scale(&s), "sheared pole") == 3,
          "sheared pole: no quad with a diagonal shorter than the other");
    rg2_tess_free(&t);
    rg2_surface_free(&s);
}

/* The torus under the same kind of affine map: closed in u and v with quads that are no longer
 * symmetric trapezoids (on the torus itself both diagonals of every quad are equally long), so
 * the branch-free path's choice is measured for real where a row wraps to its grid column 0, and
 * at density 48, where a row of 288 quads is compared in chunks of 256 (the second chunk's points
 * start at quad 256). */
static void sheared_torus(void)
{
    static const double A[3][4] = {{1.0, 0.6, 0.2, 3.0}, {0.1, 1.8, 0.5, -20.0}, {0.4, -0.3, 2.2, 6.0}};
    rg2_surface s;
    rg2_error err;
    CHECK_OK(fx_torus(13.0, 4.0, 8, 6, &s, &err), &err);
    affine_map(&s, A);
    static const int dens[2] = {5, 48};
    for (int q = 0; q < 2; q++) {
        int d = dens[q];
        char what[64];
        snprintf(what, sizeof what, "sheared torus, density %d", d);
        rg2_tess t;
        CHECK_OK(rg2_tessellate(&s, d, 0, &t, &err), &err);
        CHECK(t.n_vertices == s.nu * d * s.nv * d && t.n_triangles == 2 * t.n_vertices, "%s: %d vertices, %d triangles",
              what, t.n_vertices, t.n_triangles);
        check_orientation(&t, what);
        CHECK(check_diagonals(&s, &t, d, rg2t_surface_scale(&s), what) == 3,
              "%s: no quad with a diagonal shorter than the other", what);
        rg2_tess_free(&t);
    }
    rg2_surface_free(&s);
}

/* Bitwise the same mesh: counts, every array (K and H when asked). */
static void identical(const rg2_tess *a, const rg2_tess *b, int curvature, const char *what)
{
    CHECK(a->n_vertices == b->n_vertices && a->n_triangles == b->n_triangles, "%s: %d/%d vertices, %d/%d triangles",
          what, a->n_vertices, b->n_vertices, a->n_triangles, b->n_triangles);
    if (a->n_vertices != b->n_vertices || a->n_triangles != b->n_triangles)
        return;
    size_t nv = (size_t)a->n_vertices, nt = (size_t)a->n_triangles;
    size_t d3 = 3 * nv * sizeof(double);
    int same = !memcmp(a->pos, b->pos, d3) && !memcmp(a->normal, b->normal, d3) &&
               !memcmp(a->uv, b->uv, 2 * nv * sizeof(double)) && !memcmp(a->patch, b->patch, nv * sizeof(int)) &&
               !memcmp(a->tri, b->tri, 3 * nt * sizeof(int));
    if (curvature)
        same = same && a->K && b->K && !memcmp(a->K, b->K, nv * sizeof(double)) &&
               !memcmp(a->H, b->H, nv * sizeof(double));
    else
        same = same && !a->K && !a->H;
    CHECK(same, "%s: differs from rg2_tessellate's mesh", what);
}

/* rg2_retessellate into one mesh again and again (torus, pole, random; densities up and down;
 * with and without curvatures): each result bit for bit rg2_tessellate's, the allocation kept
 * when it is large enough, a failure leaving the mesh empty (the leak checkers see the rest). */
static void retessellate(void)
{
    rg2_surface s[3];
    rg2_error err;
    CHECK_OK(fx_torus(13.0, 4.0, 8, 6, &s[0], &err), &err);
    CHECK_OK(fx_pole(6, 7, &s[1], &err), &err);
    CHECK_OK(fx_random(7, 8, 7, &s[2], &err), &err);
    static const struct {
        int surf, d, curvature, reuse; /* reuse: the previous allocation must be kept */
    } step[] = {{0, 8, 1, 0}, {0, 8, 1, 1}, {0, 5, 0, 1}, {1, 6, 1, 1}, {2, 3, 0, 1}, {0, 12, 1, 0},
                {2, 5, 1, 1}, {1, 2, 0, 1}, {1, 6, 1, 1}, {0, 1, 0, 1}};
    rg2_tess t = {0};
    int n = (int)(sizeof step / sizeof step[0]), reused = 0;
    for (int k = 0; k < n; k++) {
        char what[64];
        snprintf(what, sizeof what, "retessellate step %d (surface %d, density %d)", k, step[k].surf, step[k].d);
        void *before = t.pos;
        size_t cap = t.capacity;
        rg2_tess fresh;
        CHECK_OK(rg2_retessellate(&s[step[k].surf], step[k].d, step[k].curvature, &t, &err), &err);
        CHECK_OK(rg2_tessellate(&s[step[k].surf], step[k].d, step[k].curvature, &fresh, &err), &err);
        identical(&t, &fresh, step[k].curvature, what);
        if (step[k].reuse)
            CHECK(t.pos == before && t.capacity == cap, "%s: the allocation of %zu bytes was not reused", what, cap);
        reused += t.pos == before;
        CHECK(t.capacity >= fresh.capacity, "%s: capacity %zu below the mesh's %zu bytes", what, t.capacity,
              fresh.capacity);
        rg2_tess_free(&fresh);
    }
    printf("rg2_retessellate: %d meshes into one, each bit for bit rg2_tessellate's, the allocation reused in %d\n",
           n, reused);
    CHECK(rg2_retessellate(&s[0], 0, 0, &t, &err) == RG2_EINVAL && strstr(err.msg, "density"),
          "retessellate, density 0: %s", err.msg);
    CHECK(t.pos == NULL && t.tri == NULL && t.capacity == 0 && t.n_vertices == 0, "failed retessellate left a mesh");
    CHECK_OK(rg2_retessellate(&s[1], 4, 1, &t, &err), &err); /* from the emptied struct */
    rg2_tess fresh;
    CHECK_OK(rg2_tessellate(&s[1], 4, 1, &fresh, &err), &err);
    identical(&t, &fresh, 1, "retessellate after a failure");
    rg2_tess_free(&fresh);
    rg2_tess_free(&t);
    for (int k = 0; k < 3; k++)
        rg2_surface_free(&s[k]);
}

static void bad_input(void)
{
    rg2_surface s, empty;
    rg2_error err;
    rg2_tess t;
    memset(&empty, 0, sizeof empty);
    CHECK(rg2_tessellate(&empty, 4, 0, &t, &err) == RG2_EINVAL, "empty surface accepted");
    CHECK_OK(fx_random(3, 5, 5, &s, &err), &err);
    /* NULL arguments: named, no crash (a NULL out and a NULL mesh crashed) */
    CHECK(rg2_tessellate(NULL, 4, 0, &t, &err) == RG2_EINVAL && !strcmp(err.msg, "tessellate: no surface (s is NULL)"),
          "NULL surface: %s", err.msg);
    CHECK(rg2_tessellate(&s, 4, 0, NULL, &err) == RG2_EINVAL && !strcmp(err.msg, "tessellate: no output (out is NULL)"),
          "NULL out: %s", err.msg);
    CHECK(rg2_retessellate(&s, 4, 0, NULL, &err) == RG2_EINVAL && !strcmp(err.msg, "retessellate: no mesh (t is NULL)"),
          "NULL mesh: %s", err.msg);
    CHECK(rg2_tessellate(&s, 0, 0, &t, &err) == RG2_EINVAL && strstr(err.msg, "density"), "density 0: %s", err.msg);
    CHECK(t.pos == NULL && t.tri == NULL, "failed tessellation left arrays");
    CHECK(rg2_tessellate(&s, 5000, 0, &t, &err) == RG2_ELIMIT, "huge density: %s", err.msg);
    rg2_tess_free(&t);
    char where[32];
    snprintf(where, sizeof where, "patch (%d,%d)", s.nu - 1, s.nv - 1);
    s.patch[s.nu * s.nv - 1].h[1][2][0] = NAN; /* refused like render and export, not NaN vertices */
    CHECK(rg2_tessellate(&s, 4, 0, &t, &err) == RG2_ENONFINITE && strstr(err.msg, where), "NaN control value: %s",
          err.msg);
    rg2_tess_free(&t);
    rg2_surface_free(&s);
    /* weights through 0: patch (2, 1)'s 4-tuples times 0 put its points at 0 / 0 (75 of 2304
     * coordinates NaN came back with RG2_OK, and OBJ wrote them); times -1 is the same surface
     * (projectively), finite with negative weights, and tessellates as before */
    for (int q = 0; q < 2; q++) {
        rg2_tess ref;
        CHECK_OK(fx_torus(3.0, 1.0, 8, 6, &s, &err), &err);
        CHECK_OK(rg2_tessellate(&s, 4, 1, &ref, &err), &err);
        for (int r = 0; r < 4; r++)
            for (int c = 0; c < 4; c++)
                for (int k = 0; k < 4; k++)
                    s.patch[2 * s.nv + 1].h[r][c][k] *= q ? -1.0 : 0.0;
        rg2_status st = rg2_tessellate(&s, 4, 1, &t, &err);
        if (q == 0) {
            CHECK(st == RG2_EWEIGHT && strstr(err.msg, "the vertex at patch (2, 1)") && strstr(err.msg, "is not finite") &&
                      t.pos == NULL && t.n_vertices == 0,
                  "weights 0: %s '%s'", rg2_status_str(st), err.msg);
            char dir[] = "/tmp/rg2_tess_inf_XXXXXX", path[64];
            CHECK(mkdtemp(dir) != NULL, "mkdtemp");
            snprintf(path, sizeof path, "%s/w0.obj", dir);
            st = rg2_export_file(&s, 1, path, NULL, &err);
            CHECK(st == RG2_EWEIGHT && access(path, F_OK) != 0 && rmdir(dir) == 0, "weights 0 to OBJ: %s '%s'",
                  rg2_status_str(st), err.msg);
        } else {
            double dp = 0.0;
            for (int v = 0; st == RG2_OK && v < t.n_vertices && v < ref.n_vertices; v++)
                for (int c = 0; c < 3; c++)
                    dp = fmax(dp, fabs(t.pos[3 * v + c] - ref.pos[3 * v + c]));
            CHECK(st == RG2_OK && t.n_vertices == ref.n_vertices && dp <= 1e-14,
                  "weights -1 (the same surface): %s, positions %.3g off", err.msg, dp);
        }
        rg2_tess_free(&t);
        rg2_tess_free(&ref);
        rg2_surface_free(&s);
    }
    /* sizes: up to the supported 1e60 (and down to 1e-60) every normal, K and H is finite and
     * the normals are those of the unit torus; a torus of size 1e80 gave NaN normals with status
     * ok, and is refused now, as is one of size 1e-80 */
    const double scale[] = {1e-59, 1e-30, 1e30, 2e59, 1e80, 1e-80};
    rg2_tess unit;
    CHECK_OK(fx_torus(3.0, 1.0, 4, 4, &s, &err), &err);
    CHECK_OK(rg2_tessellate(&s, 8, 1, &unit, &err), &err);
    rg2_surface_free(&s);
    for (int q = 0; q < 6; q++) {
        CHECK_OK(fx_torus(3.0 * scale[q], 1.0 * scale[q], 4, 4, &s, &err), &err);
        rg2_status st = rg2_tessellate(&s, 8, 1, &t, &err);
        if (q >= 4) {
            CHECK(st == RG2_EDOMAIN && strstr(err.msg, "surface 0") && strstr(err.msg, "scale it"),
                  "torus of size %g: %s '%s'", scale[q], rg2_status_str(st), err.msg);
        } else if (st == RG2_OK) {
            double dn = 0.0, dk = 0.0;
            for (int v = 0; v < t.n_vertices && v < unit.n_vertices; v++) {
                for (int c = 0; c < 3; c++)
                    dn = fmax(dn, fabs(t.normal[3 * v + c] - unit.normal[3 * v + c]));
                dk = fmax(dk, fabs(t.K[v] * scale[q] * scale[q] - unit.K[v]) + fabs(t.H[v] * scale[q] - unit.H[v]));
            }
            CHECK(t.n_vertices == unit.n_vertices && dn < 1e-14 && dk < 1e-13,
                  "torus of size %g: normals %.3g, K and H %.3g from the unit torus's", scale[q], dn, dk);
        } else
            CHECK(0, "torus of size %g refused: %s", scale[q], err.msg);
        rg2_tess_free(&t);
        rg2_surface_free(&s);
    }
    rg2_tess_free(&unit);
    /* a control point whose h and w are finite but whose h / w overflows (x 1e308 at weight 0.5)
     * has no coordinates; the box of the others is in range, and it was tessellated with status ok */
    CHECK_OK(fx_torus(3.0, 1.0, 4, 4, &s, &err), &err);
    s.patch[5].h[1][2][0] = 1e308, s.patch[5].h[1][2][3] = 0.5;
    rg2_status st = rg2_tessellate(&s, 8, 1, &t, &err);
    CHECK(st == RG2_EDOMAIN && strstr(err.msg, "tessellate: surface 0 patch (1,1)") && strstr(err.msg, "overflow"),
          "a control point at x = 2e308: %s '%s'", rg2_status_str(st), err.msg);
    if (st == RG2_OK)
        rg2_tess_free(&t);
    rg2_surface_free(&s);
}

int main(void)
{
    for (int mixed = 0; mixed < 2; mixed++) {
        torus_mesh(mixed);
        random_mesh(8, 7, mixed);
        pole_mesh(mixed);
    }
    pole_mesh(2);
    random_mesh(4, 5, 0); /* 1 x 2 patches */
    random_mesh(5, 4, 0); /* 2 x 1 */
    sheared_pole();
    sheared_torus();
    lone_collapsed_sides();
    cap_mesh();
    sphere_poles_kh();
    retessellate();
    bad_input();
    return rg2t_done("test_tess");
}
