/* export_internal.h -- private helpers shared by the export writers (export.c, step.c,
 * iges.c, bezierview.c, meshio.c) and the tessellator (tess.c); never installed. */
#ifndef RG2_EXPORT_INTERNAL_H
#define RG2_EXPORT_INTERNAL_H

#include "internal.h"

#include <stdio.h>

/* Items 0..n-1 written to f in order, formatted on the threads: blocks of `block` items, block b
 * (items k0..k1-1) formatted by fn(m, ctx, b, k0, k1) into a memory stream m of its own, a few
 * blocks per thread at a time (the streams kept from one round to the next, so their pages are
 * faulted in once), then copied into f block by block: the same bytes as formatting the items
 * one after the other into f. For text whose numbers printf formats (17 digits: nearly all of a
 * big export's time). fn returns 0 or a negative code, which stops the writing and is returned
 * (-1 also when a stream fails). With fix, each block's text (len bytes) is handed to
 * fix(ctx, b, text, len) in block order, on the calling thread, right before it is copied (to
 * number what only the blocks before it determine); without, n <= block: fn(f, ctx, 0, 0, n)
 * straight into f. */
typedef int (*rg2__block_fn)(FILE *m, void *ctx, int b, int k0, int k1);
typedef void (*rg2__block_fix)(void *ctx, int b, char *text, size_t len);
int rg2__write_blocks(FILE *f, int n, int block, rg2__block_fn fn, rg2__block_fix fix, void *ctx);

/* Union-find over int arrays (parent[a] == a for roots); the smaller index becomes the root. */
int rg2__uf_find(int *parent, int a);
void rg2__uf_union(int *parent, int a, int b);

/* The current UTC time formatted with strftime's fmt (2000-01-01 if the clock fails). */
void rg2__utc_stamp(char *buf, size_t cap, const char *fmt);

/* A real for STEP and IGES: 17 significant digits (round-trips exactly), always with a
 * '.' and an upper-case 'E' when there is an exponent ("13.", "1.E-07", "-0.25"). */
void rg2__real(char buf[40], double x);

/* Check that every coordinate is finite (RG2_ENONFINITE, checked over all surfaces first) and
 * every homogeneous weight > 0 (RG2_EWEIGHT); the message names the surface, patch and control
 * point ("surface 0 patch (2, 3) point [1][0]"). */
rg2_status rg2__check_weights(const rg2_surface *surfs, int n_surfs, const char *format,
                              rg2_error *err);
/* Check surfs != NULL, n_surfs >= 1 and every surface has at least one patch. */
rg2_status rg2__check_nonempty(const rg2_surface *surfs, int n_surfs, rg2_error *err);

/* Sides of a patch, counter-clockwise in (u, v): 0 v=0, 1 u=1, 2 v=1, 3 u=0 (the control points
 * of a side: rg2__xpatch_side). */
/* Whether side `side` of P collapses to a point (all four affine points within tol). */
int rg2__patch_side_collapsed(const rg2_patch *P, int side, double tol);
/* The same for a patch of any degree: side `side` of X (du + 1 points on sides 0 and 2,
 * dv + 1 on 1 and 3); returns the count. */
int rg2__xpatch_side(const rg2_xpatch *X, int side, double out[RG2_MAX_DEGREE + 1][4]);
/* The (du + 1) x (dv + 1) homogeneous control points of X as a net out[r * (dv + 1) + t], u
 * outer (the layout of the merged net); returns their count. */
int rg2__xpatch_net(const rg2_xpatch *X, double (*out)[4]);
/* Collapse tolerance of a surface: 1e-11 times the bounding-box diagonal of its control points
 * (of patches of any degree). */
double rg2__collapse_tol(const rg2_surface *s);

/* Topology of one surface as a grid of corners and edges (shared by the STEP and IGES writers).
 * Corner (I, J), I = 0..nu, J = 0..nv; closed directions wrap (I = nu is I = 0).
 * Edges along u-line I (constant u, running in +v) over span j: ue[I * nv + j];
 * edges along v-line J (constant v, running in +u) over span i: ve[J * nu + i].
 * Collapsed edges have id -1 and merge their end corners into one vertex.
 * Poles: a vertex holding a collapsed edge whose control points (those on its collapsed edges
 * and at its corners, in every patch) all lie within RG2__POLE_ULPS roundings of the surface's
 * largest coordinate, times their weights' ratio (largest / smallest, at least 1), of its point
 * pole[v] (h / w of the corner vcorner[v]) is a pole (snap[v]);
 * the writers write every one of those control points as pole[v] (rg2__patch_affine). */
typedef struct {
    int nu, nv;
    int n_vertices, n_edges;
    int *vert;   /* (nu + 1) * (nv + 1): vertex id of corner (I, J) */
    int *ue;     /* (nu + 1) * nv edge ids, -1 collapsed */
    int *ve;     /* (nv + 1) * nu edge ids, -1 collapsed */
    int *vcorner; /* n_vertices: a corner index I * (nv + 1) + J holding each vertex */
    int *edef;   /* n_edges * 2: defining patch index and side of each edge (the patch of
                    lowest degree along the edge among those using it) */
    int *uses;   /* n_edges: how many patch sides use each edge (1 boundary, 2 shared) */
    unsigned char *snap; /* n_vertices: 1 for a pole (NULL: the surface has none) */
    double (*pole)[3];   /* n_vertices: a pole's one point (NULL likewise) */
} rg2__topo;

/* How far (in roundings of the surface's largest affine coordinate, DBL_EPSILON times it, times
 * the ratio of the largest to the smallest weight among the points) the control points of a
 * collapsed side may lie from its vertex's point to be written as that point: the construction
 * leaves a pole's points one point to a few roundings (their weights differ), to more where
 * weights of different sizes meet in its sums (a clamped NURBS pole with weights 1 and 32: 21
 * roundings); a side that is merely short is farther and keeps its points. */
#define RG2__POLE_ULPS 16

rg2_status rg2__topo_build(const rg2_surface *s, rg2__topo *t, rg2_error *err);
void rg2__topo_free(rg2__topo *t);
/* The edge id on side `side` of patch (i, j) (-1 collapsed) and whether the patch's
 * counter-clockwise loop runs along the edge (1: sides 0, 1) or against it (0: sides 2, 3). */
void rg2__topo_side(const rg2__topo *t, int i, int j, int side, int *edge, int *forward);
/* The control points as the STEP and IGES writers write them: (x, y, z, w), the affine point
 * h / w (correctly rounded) and the weight, except that every control point of a pole (t->snap)
 * is its pole's one point, the same double triple in every patch and layout, so that a collapsed
 * row is one point in the file exactly (a row of points h / w is one only to rounding, which
 * made the normal's and the curvature's rounding next to the pole grow as 1 / eps and
 * 1 / eps^2; docs/robustness.md). rg2__patch_affine: patch (i, j) of s into X in that form.
 * rg2__corner_affine: corner (I, J) of the patch grid (I = 0..nu, J = 0..nv) as the corner
 * control point of a patch holding it. rg2__net_affine: a merged net of s (rg2__merged_net, of
 * degrees (du, dv)) in place, its topology built here (RG2_ENOMEM). */
void rg2__patch_affine(const rg2__topo *t, const rg2_surface *s, int i, int j, rg2_xpatch *X);
void rg2__corner_affine(const rg2__topo *t, const rg2_surface *s, int I, int J, double out[4]);
rg2_status rg2__net_affine(const rg2_surface *s, double (*h)[4], int NU, int NV, int du, int dv, rg2_error *err);

/* Topology of one surface as one face on its merged net (the face-per-mesh layouts of the STEP
 * and IGES B-rep writers). Corners 0 (u0 v0), 1 (u1 v0), 2 (u1 v1), 3 (u0 v1), merged into
 * vertices where a direction closes or a side collapses; sides counter-clockwise 0 (v = 0, from
 * corner 0 to 1), 1 (u = U1, 1 to 2), 2 (v = V1, 3 to 2), 3 (u = 0, 0 to 3), each running in +u or
 * +v; the loop uses sides 0 and 1 forward, 2 and 3 reversed. A closed direction's closing side
 * (1 or 2) uses the edge of its partner (3 or 0): a seam, on the face twice. */
typedef struct {
    int NU, NV, du, dv;
    double (*h)[4];  /* the merged net (rg2__merged_net) as written (rg2__net_affine) */
    double (*side)[4]; /* room for one side of it (rg2__net_side) */
    int n_vertices, n_edges;
    int vert[4];     /* vertex of each corner */
    int vcorner[4];  /* a corner of each vertex */
    int edge[4];     /* edge of each side, -1 where the side collapses */
    int eside[4];    /* the side whose control points are each edge's curve */
    int closed;      /* no free edge: a closed shell */
} rg2__mesh_topo;

extern const int rg2__side_ends[4][2]; /* the corners each side runs between, in its direction */
rg2_status rg2__mesh_topo_build(const rg2_surface *s, rg2__mesh_topo *t, rg2_error *err);
void rg2__mesh_topo_free(rg2__mesh_topo *t);
/* Side sd of the merged net into t->side; returns its number of control points. */
int rg2__net_side(rg2__mesh_topo *t, int sd);

/* The whole surface as one net of (du nu + 1) x (dv nv + 1) homogeneous poles h[a * NV + b],
 * a along u (MATH.md section 4), where (du, dv) = rg2_surface_degree (3, 3 for all-bi-3
 * surfaces) and every patch is exactly degree-elevated to it: patch boundary rows are shared,
 * taken from the first patch holding them; the closing row of a closed direction is a copy of
 * row 0. Caller frees; NULL when out of memory. */
double (*rg2__merged_net(const rg2_surface *s, int *NU, int *NV, int *du, int *dv))[4];

/* The tessellation of several surfaces concatenated (meshio writers). */
rg2_status rg2__tess_all(const rg2_surface *surfs, int n_surfs, int density, int curvature,
                         rg2_tess **out, rg2_error *err);
void rg2__tess_all_free(rg2_tess *t, int n);
/* Test hook: how many times rg2__tess_all has run in this process. */
unsigned long rg2__tess_all_calls(void);

/* Writers, called by rg2_export_file after the common checks. */
rg2_status rg2__write_step(const rg2_surface *surfs, int n, const rg2_export_opts *o, rg2__out *out,
                           rg2_error *err);
rg2_status rg2__write_iges(const rg2_surface *surfs, int n, const rg2_export_opts *o, rg2__out *out,
                           rg2_error *err);
rg2_status rg2__write_bv(const rg2_surface *surfs, int n, rg2__out *out, rg2_error *err);
rg2_status rg2__write_bez(const rg2_surface *surfs, int n, rg2__out *out, rg2_error *err);
rg2_status rg2__write_obj(const rg2_tess *t, int n, const rg2_export_opts *o, rg2__out *out,
                          rg2_error *err);
rg2_status rg2__write_stl(const rg2_tess *t, int n, const rg2_export_opts *o, rg2__out *out,
                          rg2_error *err);
rg2_status rg2__write_ply(const rg2_tess *t, int n, const rg2_export_opts *o, rg2__out *out,
                          rg2_error *err);
rg2_status rg2__write_glb(const rg2_tess *t, int n, const rg2_export_opts *o, rg2__out *out,
                          rg2_error *err);

#endif
