/* step.c -- STEP AP214 / AP242 (ISO 10303-21) of rational patch surfaces as a shell of
 * ADVANCED_FACEs on rational B-spline surfaces (bi-3 patches, and rg2_xpatch patches with their
 * own degrees per face, or all elevated to the surface's degrees on one face per mesh),
 * following docs/export.md and shared/spec/INTEROP.md: complex instances in alphabetical
 * order, control nets LIST[u] OF LIST[v], one EDGE_CURVE / VERTEX_POINT per geometric edge /
 * vertex shared by the faces on both sides, each edge's curve a SURFACE_CURVE with the exact
 * pcurve (a side of the parameter rectangle) on every face it bounds, loops counter-clockwise in
 * (u, v), product structure, mm units. */
#include "export_internal.h"

#include <stdlib.h>
#include <string.h>

typedef struct {
    FILE *f;
    int next;    /* next entity id */
    int ctx2d;   /* the parameter-space context of the pcurves (0: not written yet) */
    int unit[4]; /* the lines along the sides of [0, 1]^2 that every face of the face-per-patch
                    layout uses, of all its surfaces (0: not written yet) */
} stepw;

static int new_id(stepw *w) { return w->next++; }

static void put_real(FILE *f, double x)
{
    char b[40];
    rg2__real(b, x);
    fputs(b, f);
}

/* A control point as written (x, y, z, w): its affine point (rg2__patch_affine). */
static int put_point(stepw *w, const double p[4])
{
    int id = new_id(w);
    fprintf(w->f, "#%d=CARTESIAN_POINT('',(", id);
    for (int d = 0; d < 3; d++) {
        if (d)
            fputc(',', w->f);
        put_real(w->f, p[d]);
    }
    fputs("));\n", w->f);
    return id;
}

/* Multiplicities "(4,3,3,4)" (degree 3) and knot values "(0.,1.,2.,3.)" of n_spans Bezier
 * spans of degree deg: end knots deg + 1, interior knots deg. */
static void put_mults(FILE *f, int n_spans, int deg)
{
    fputc('(', f);
    for (int k = 0; k <= n_spans; k++)
        fprintf(f, "%s%d", k ? "," : "", (k == 0 || k == n_spans) ? deg + 1 : deg);
    fputc(')', f);
}

static void put_knot_values(FILE *f, int n_spans)
{
    fputc('(', f);
    for (int k = 0; k <= n_spans; k++)
        fprintf(f, "%s%d.", k ? "," : "", k);
    fputc(')', f);
}

/* A rational B-spline curve of degree deg, piecewise Bezier, through the poles h[0..n-1]
 * (n = deg spans + 1), each (x, y, z, w) as written (rg2__patch_affine). */
static int put_curve(stepw *w, const double (*h)[4], int n, int deg)
{
    int *pt = malloc(sizeof(int) * (size_t)n);
    if (!pt)
        return -1;
    for (int a = 0; a < n; a++)
        pt[a] = put_point(w, h[a]);
    int id = new_id(w);
    fprintf(w->f, "#%d=( BOUNDED_CURVE() B_SPLINE_CURVE(%d,(", id, deg);
    for (int a = 0; a < n; a++)
        fprintf(w->f, "%s#%d%s", a ? "," : "", pt[a], (a % 12 == 11) ? "\n" : "");
    fputs("),.UNSPECIFIED.,.F.,.F.)\n B_SPLINE_CURVE_WITH_KNOTS(", w->f);
    put_mults(w->f, (n - 1) / deg, deg);
    fputc(',', w->f);
    put_knot_values(w->f, (n - 1) / deg);
    fputs(",.PIECEWISE_BEZIER_KNOTS.)\n CURVE() GEOMETRIC_REPRESENTATION_ITEM() RATIONAL_B_SPLINE_CURVE((", w->f);
    for (int a = 0; a < n; a++) {
        if (a)
            fputs(a % 8 == 0 ? ",\n" : ",", w->f);
        put_real(w->f, h[a][3]);
    }
    fputs(")) REPRESENTATION_ITEM('') );\n", w->f);
    free(pt);
    return id;
}

static int put_vertex(stepw *w, const double h[4])
{
    int p = put_point(w, h);
    int id = new_id(w);
    fprintf(w->f, "#%d=VERTEX_POINT('',#%d);\n", id, p);
    return id;
}

static int put_edge(stepw *w, int v0, int v1, int curve)
{
    int id = new_id(w);
    fprintf(w->f, "#%d=EDGE_CURVE('',#%d,#%d,#%d,.T.);\n", id, v0, v1, curve);
    return id;
}

/* The line (u0, v0) + t (du, dv) of a surface's parameter space (unit direction), as the
 * DEFINITIONAL_REPRESENTATION a PCURVE refers to. Every face of one layout shares the four
 * lines of its boundary. */
static int put_line2d(stepw *w, double u0, double v0, double du, double dv)
{
    if (!w->ctx2d) {
        w->ctx2d = new_id(w);
        fprintf(w->f, "#%d=( GEOMETRIC_REPRESENTATION_CONTEXT(2) PARAMETRIC_REPRESENTATION_CONTEXT() "
                      "REPRESENTATION_CONTEXT('2D SPACE','') );\n",
                w->ctx2d);
    }
    int p = new_id(w), d = new_id(w), vec = new_id(w), line = new_id(w), rep = new_id(w);
    fprintf(w->f, "#%d=CARTESIAN_POINT('',(", p);
    put_real(w->f, u0);
    fputc(',', w->f);
    put_real(w->f, v0);
    fprintf(w->f, "));\n#%d=DIRECTION('',(", d);
    put_real(w->f, du);
    fputc(',', w->f);
    put_real(w->f, dv);
    fprintf(w->f, "));\n#%d=VECTOR('',#%d,1.);\n#%d=LINE('',#%d,#%d);\n", vec, d, line, p, vec);
    fprintf(w->f, "#%d=DEFINITIONAL_REPRESENTATION('',(#%d),#%d);\n", rep, line, w->ctx2d);
    return rep;
}

/* The boundary lines of a parameter rectangle [0, U1] x [0, V1], side sd (0 v=0, 1 u=U1, 2 v=V1,
 * 3 u=0), each running in +u or +v with the parameter of the boundary's edge curve (whose knots
 * are the surface's along that side). */
static void put_side_lines(stepw *w, double U1, double V1, int rep[4])
{
    rep[0] = put_line2d(w, 0, 0, 1, 0);
    rep[1] = put_line2d(w, U1, 0, 0, 1);
    rep[2] = put_line2d(w, 0, V1, 1, 0);
    rep[3] = put_line2d(w, 0, 0, 0, 1);
}

/* The 3D curve of an edge with its pcurves on the n (1 or 2) surfaces of the faces it bounds
 * (surf[k], parameter line rep[k]); a SEAM_CURVE when both pcurves lie on one surface. */
static int put_surface_curve(stepw *w, int curve, int n, const int *surf, const int *rep)
{
    int pc[2] = {0, 0};
    for (int k = 0; k < n; k++) {
        pc[k] = new_id(w);
        fprintf(w->f, "#%d=PCURVE('',#%d,#%d);\n", pc[k], surf[k], rep[k]);
    }
    int id = new_id(w);
    fprintf(w->f, "#%d=%s('',#%d,(#%d", id, n == 2 && surf[0] == surf[1] ? "SEAM_CURVE" : "SURFACE_CURVE", curve,
            pc[0]);
    if (n == 2)
        fprintf(w->f, ",#%d", pc[1]);
    fputs("),.CURVE_3D.);\n", w->f);
    return id;
}

/* Face bounded by the oriented edges (edge ids, orientation flags). */
static int put_face(stepw *w, int surface, const int *edge, const int *fwd, int n)
{
    int oe[4];
    for (int k = 0; k < n; k++) {
        oe[k] = new_id(w);
        fprintf(w->f, "#%d=ORIENTED_EDGE('',*,*,#%d,%s);\n", oe[k], edge[k], fwd[k] ? ".T." : ".F.");
    }
    int loop = new_id(w);
    fprintf(w->f, "#%d=EDGE_LOOP('',(", loop);
    for (int k = 0; k < n; k++)
        fprintf(w->f, "%s#%d", k ? "," : "", oe[k]);
    fputs("));\n", w->f);
    int bound = new_id(w);
    fprintf(w->f, "#%d=FACE_OUTER_BOUND('',#%d,.T.);\n", bound, loop);
    int face = new_id(w);
    fprintf(w->f, "#%d=ADVANCED_FACE('',(#%d),#%d,.T.);\n", face, bound, surface);
    return face;
}

static int put_shell(stepw *w, const int *faces, int n, int closed)
{
    int id = new_id(w);
    fprintf(w->f, "#%d=%s('',(", id, closed ? "CLOSED_SHELL" : "OPEN_SHELL");
    for (int k = 0; k < n; k++)
        fprintf(w->f, "%s#%d%s", k ? "," : "", faces[k], (k % 12 == 11 && k + 1 < n) ? "\n" : "");
    fputs("));\n", w->f);
    return id;
}

/*
 * Items 0..n-1 written by emit(w, ctx, k), which returns the item's entity id (negative: out of
 * memory) and uses count[k] entity ids (one each if count is NULL), on the threads
 * (rg2__write_blocks, STEP_BLOCK items a block, each block numbering its entities from its own
 * first id on). Returns 0, -1 out of memory, -2 an item that used other than count[k] ids (a
 * bug: references would be wrong).
 */
typedef int (*step_emit)(stepw *w, void *ctx, int k);
#define STEP_BLOCK 256

typedef struct {
    stepw *w;
    const int *count, *start; /* start[b]: block b's first entity id */
    step_emit emit;
    void *ctx;
    int *id;
} step_items;

static int step_block(FILE *m, void *arg, int b, int k0, int k1)
{
    step_items *it = arg;
    stepw wb = {m, it->start[b], it->w->ctx2d, {0, 0, 0, 0}};
    for (int k = k0; k < k1; k++) {
        int next = wb.next;
        if ((it->id[k] = it->emit(&wb, it->ctx, k)) < 0)
            return -1;
        if (wb.next != next + (it->count ? it->count[k] : 1))
            return -2;
    }
    return 0;
}

static int emit_all(stepw *w, int n, const int *count, step_emit emit, void *ctx, int *id)
{
    int nblk = n > 0 ? (n - 1) / STEP_BLOCK + 1 : 1;
    int *start = malloc(sizeof(int) * ((size_t)nblk + 1));
    if (!start)
        return -1;
    start[0] = w->next;
    for (int b = 0; b < nblk; b++) { /* each block's first entity id */
        start[b + 1] = start[b];
        for (int k = b * STEP_BLOCK; k < n && k < (b + 1) * STEP_BLOCK; k++)
            start[b + 1] += count ? count[k] : 1;
    }
    step_items it = {w, count, start, emit, ctx, id};
    int st = rg2__write_blocks(w->f, n, STEP_BLOCK, step_block, NULL, &it);
    if (!st)
        w->next = start[nblk];
    free(start);
    return st;
}

#define NET_BIG 4096 /* control points from which a net's points and lists go on the threads */

/* A net's control points h[k] as entities (one each, ids into pt[k]). */
static int emit_point(stepw *w, void *ctx, int k) { return put_point(w, ((const double(*)[4])ctx)[k]); }

/* Rows k0..k1-1 of a net's control point ids (weights: its weights) as in the surface entity
 * (rg2__write_blocks' block function). */
typedef struct {
    const double (*h)[4];
    const int *pt;
    int NV, weights;
} net_rows;

static int put_rows(FILE *f, void *ctx, int blk, int k0, int k1)
{
    (void)blk;
    const net_rows *r = ctx;
    int NV = r->NV;
    for (int a = k0; a < k1; a++) {
        fputs(a ? ",\n(" : "(", f);
        for (int b = 0; b < NV; b++)
            if (r->weights) {
                if (b)
                    fputs(b % 8 == 0 ? ",\n" : ",", f);
                put_real(f, r->h[a * NV + b][3]);
            } else {
                fprintf(f, "%s#%d%s", b ? "," : "", r->pt[a * NV + b], (b % 12 == 11 && b + 1 < NV) ? "\n" : "");
            }
        fputc(')', f);
    }
    return 0;
}

/* All NU rows, a big net's on the threads (NET_BIG / NV rows a block). */
static int put_all_rows(stepw *w, const double (*h)[4], const int *pt, int NU, int NV, int weights)
{
    net_rows r = {h, pt, NV, weights};
    if (NU * NV < NET_BIG)
        return put_rows(w->f, &r, 0, 0, NU);
    return rg2__write_blocks(w->f, NU, NET_BIG / NV > 1 ? NET_BIG / NV : 1, put_rows, NULL, &r);
}

/* A rational B-spline surface of degree (du, dv), piecewise Bezier, from a net of NU x NV
 * poles h[a * NV + b], u outer, each (x, y, z, w) as written (rg2__patch_affine); a big net's points, pole list and weights formatted
 * on the threads (the surface of the face-per-mesh layout). Returns its id, or -1 out of memory,
 * -2 entity numbers out of step (emit_all). */
static int put_surface(stepw *w, const double (*h)[4], int NU, int NV, int du, int dv, int closed_u,
                       int closed_v)
{
    int *pt = malloc(sizeof(int) * (size_t)NU * (size_t)NV), st = 0;
    if (!pt)
        return -1;
    if (NU * NV < NET_BIG)
        for (int a = 0; a < NU * NV; a++)
            pt[a] = put_point(w, h[a]);
    else if ((st = emit_all(w, NU * NV, NULL, emit_point, (void *)h, pt))) {
        free(pt);
        return st;
    }
    int id = new_id(w);
    fprintf(w->f, "#%d=( BOUNDED_SURFACE() B_SPLINE_SURFACE(%d,%d,(", id, du, dv);
    st = put_all_rows(w, h, pt, NU, NV, 0);
    fprintf(w->f, "),.UNSPECIFIED.,%s,%s,.F.)\n B_SPLINE_SURFACE_WITH_KNOTS(", closed_u ? ".T." : ".F.",
            closed_v ? ".T." : ".F.");
    /* u multiplicities, v multiplicities, u knots, v knots */
    put_mults(w->f, (NU - 1) / du, du);
    fputc(',', w->f);
    put_mults(w->f, (NV - 1) / dv, dv);
    fputc(',', w->f);
    put_knot_values(w->f, (NU - 1) / du);
    fputc(',', w->f);
    put_knot_values(w->f, (NV - 1) / dv);
    fputs(",.PIECEWISE_BEZIER_KNOTS.)\n GEOMETRIC_REPRESENTATION_ITEM() RATIONAL_B_SPLINE_SURFACE((", w->f);
    if (!st)
        st = put_all_rows(w, h, pt, NU, NV, 1);
    fputs(")) REPRESENTATION_ITEM('') SURFACE() );\n", w->f);
    free(pt);
    return st ? st : id;
}

/* Degrees of patch (i, j): its own for a higher-degree patch, else 3. */
static void patch_degree(const rg2_surface *s, int i, int j, int *du, int *dv)
{
    const rg2_xpatch *x = rg2_surface_xpatch(s, i, j);
    *du = x ? x->du : 3;
    *dv = x ? x->dv : 3;
}

/* What the items of shell_per_patch's parallel parts read. */
typedef struct {
    const rg2_surface *s;
    const rg2__topo *t;
    const int *vid, *sid, *nuse, *user, *uside, *line;
} patch_shell;

static int emit_vertex(stepw *w, void *ctx, int v)
{
    const patch_shell *c = ctx;
    int corner = c->t->vcorner[v], nv = c->s->nv;
    double h[4];
    rg2__corner_affine(c->t, c->s, corner / (nv + 1), corner % (nv + 1), h);
    return put_vertex(w, h);
}

static int emit_surface(stepw *w, void *ctx, int p)
{
    const patch_shell *c = ctx;
    rg2_xpatch X;
    double h[(RG2_MAX_DEGREE + 1) * (RG2_MAX_DEGREE + 1)][4];
    rg2__patch_affine(c->t, c->s, p / c->s->nv, p % c->s->nv, &X);
    rg2__xpatch_net(&X, h);
    return put_surface(w, (const double(*)[4])h, X.du + 1, X.dv + 1, X.du, X.dv, 0, 0);
}

/* Edge e: its curve through the side's control points, the SURFACE_CURVE with its pcurves on
 * the faces it bounds, the EDGE_CURVE between its vertices. */
static int emit_edge(stepw *w, void *ctx, int e)
{
    const patch_shell *c = ctx;
    const rg2__topo *t = c->t;
    int nv = c->s->nv, p = t->edef[2 * e], side = t->edef[2 * e + 1], i = p / nv, j = p % nv;
    rg2_xpatch X;
    double h[RG2_MAX_DEGREE + 1][4];
    rg2__patch_affine(c->t, c->s, i, j, &X);
    int n = rg2__xpatch_side(&X, side, h);
    int I0 = side == 1 ? i + 1 : i, J0 = side == 2 ? j + 1 : j;
    int I1 = (side == 0 || side == 2) ? i + 1 : I0, J1 = (side == 1 || side == 3) ? j + 1 : J0;
    int curve = put_curve(w, (const double(*)[4])h, n, n - 1);
    if (curve < 0)
        return -1;
    /* every edge runs in +u or +v on both sides with knots (0, 1): the pcurve on a patch
     * is its side's boundary line of the unit square */
    int surf[2], rep[2];
    for (int k = 0; k < c->nuse[e]; k++) {
        surf[k] = c->sid[c->user[2 * e + k]];
        rep[k] = c->line[c->uside[2 * e + k]];
    }
    curve = put_surface_curve(w, curve, c->nuse[e], surf, rep);
    return put_edge(w, c->vid[t->vert[I0 * (nv + 1) + J0]], c->vid[t->vert[I1 * (nv + 1) + J1]], curve);
}

/* One face per patch, sharing edges and vertices through rg2__topo. Returns the shell id. The
 * vertices, the surfaces and the edges are written on the threads (emit_all). */
static rg2_status shell_per_patch(stepw *w, const rg2_surface *s, int *shell, rg2_error *err)
{
    rg2__topo t;
    rg2_status st = rg2__topo_build(s, &t, err);
    if (st)
        return st;
    int nu = s->nu, nv = s->nv, np = nu * nv;
    int *vid = malloc(sizeof(int) * (size_t)(t.n_vertices ? t.n_vertices : 1));
    int *eid = malloc(sizeof(int) * (size_t)(t.n_edges ? t.n_edges : 1));
    int *fid = malloc(sizeof(int) * (size_t)np);
    int *sid = malloc(sizeof(int) * (size_t)np);
    size_t ne = (size_t)(t.n_edges ? t.n_edges : 1), nmax = (size_t)np > ne ? (size_t)np : ne;
    if (nmax < (size_t)t.n_vertices)
        nmax = (size_t)t.n_vertices;
    int *nuse = malloc(sizeof(int) * ne), *user = malloc(sizeof(int) * 2 * ne), *uside = malloc(sizeof(int) * 2 * ne);
    int *count = malloc(sizeof(int) * nmax);
    int line[4], emitted = 0;
    patch_shell ctx = {s, &t, vid, sid, nuse, user, uside, line};
    if (!vid || !eid || !fid || !sid || !nuse || !user || !uside || !count) {
        st = rg2__fail(err, RG2_ENOMEM, "STEP: out of memory for %d x %d patches", nu, nv);
        goto done;
    }
    for (int v = 0; v < t.n_vertices; v++)
        count[v] = 2; /* CARTESIAN_POINT, VERTEX_POINT */
    emitted = emit_all(w, t.n_vertices, count, emit_vertex, &ctx, vid);
    /* the surfaces first: each edge's pcurves refer to the surfaces of the faces it bounds */
    for (int p = 0; p < np && !emitted; p++) {
        int du, dv;
        patch_degree(s, p / nv, p % nv, &du, &dv);
        count[p] = (du + 1) * (dv + 1) + 1; /* the control points, the surface */
    }
    if (!emitted)
        emitted = emit_all(w, np, count, emit_surface, &ctx, sid);
    if (emitted)
        goto failed;
    /* the (at most 2) patch sides using each edge, in grid order */
    for (int e = 0; e < t.n_edges; e++)
        nuse[e] = 0;
    for (int p = 0; p < np; p++)
        for (int side = 0; side < 4; side++) {
            int e, f;
            rg2__topo_side(&t, p / nv, p % nv, side, &e, &f);
            if (e >= 0 && nuse[e] < 2) {
                user[2 * e + nuse[e]] = p;
                uside[2 * e + nuse[e]++] = side;
            }
        }
    if (!w->unit[0]) /* every patch's parameter square is [0, 1]^2: one set for the file */
        put_side_lines(w, 1, 1, w->unit);
    memcpy(line, w->unit, sizeof line);
    int closed = 1;
    for (int e = 0; e < t.n_edges; e++) {
        int p = t.edef[2 * e], side = t.edef[2 * e + 1], du, dv;
        patch_degree(s, p / nv, p % nv, &du, &dv);
        /* the curve's points and itself, its pcurves, the SURFACE_CURVE, the EDGE_CURVE */
        count[e] = ((side & 1) ? dv : du) + 2 + nuse[e] + 2;
        if (t.uses[e] != 2)
            closed = 0;
    }
    emitted = emit_all(w, t.n_edges, count, emit_edge, &ctx, eid);
    if (emitted)
        goto failed;
    for (int i = 0; i < nu; i++)
        for (int j = 0; j < nv; j++) {
            int edge[4], fwd[4], n = 0;
            for (int side = 0; side < 4; side++) {
                int e, f;
                rg2__topo_side(&t, i, j, side, &e, &f);
                if (e < 0)
                    continue;
                edge[n] = eid[e];
                fwd[n++] = f;
            }
            fid[i * nv + j] = put_face(w, sid[i * nv + j], edge, fwd, n);
        }
    *shell = put_shell(w, fid, np, closed);
    goto done;
failed:
    st = emitted == -2 ? rg2__fail(err, RG2_EINVAL, "STEP: internal error: entity numbers out of step")
                       : rg2__fail(err, RG2_ENOMEM, "STEP: out of memory");
done:
    free(vid);
    free(eid);
    free(fid);
    free(sid);
    free(nuse);
    free(user);
    free(uside);
    free(count);
    rg2__topo_free(&t);
    return st;
}

/* One face per surface on the merged net (MATH.md section 4), on rg2__mesh_topo: closed
 * directions' seam edges appear twice in the loop (.T. and .F.) as SEAM_CURVEs; collapsed
 * boundary curves are left out. */
static rg2_status shell_per_mesh(stepw *w, const rg2_surface *s, int *shell, rg2_error *err)
{
    rg2__mesh_topo t;
    rg2_status st = rg2__mesh_topo_build(s, &t, err);
    if (st)
        return st;
    int vid[4], eid[4];
    for (int v = 0; v < t.n_vertices; v++) {
        int c = t.vcorner[v];
        vid[v] = put_vertex(w, t.h[(size_t)(c == 1 || c == 2 ? t.NU - 1 : 0) * (size_t)t.NV +
                                   (size_t)(c >= 2 ? t.NV - 1 : 0)]);
    }
    int surf = put_surface(w, (const double(*)[4])t.h, t.NU, t.NV, t.du, t.dv, s->closed_u, s->closed_v);
    if (surf == -2) {
        rg2__mesh_topo_free(&t);
        return rg2__fail(err, RG2_EINVAL, "STEP: internal error: entity numbers out of step");
    }
    if (surf < 0)
        goto oom;
    int line[4]; /* the parameter rectangle [0, nu] x [0, nv] (knots 0, 1, ..., as the edge curves') */
    put_side_lines(w, s->nu, s->nv, line);
    for (int e = 0; e < t.n_edges; e++) {
        int sd = t.eside[e], n = rg2__net_side(&t, sd);
        int c = put_curve(w, (const double(*)[4])t.side, n, (sd & 1) ? t.dv : t.du);
        if (c < 0)
            goto oom;
        /* the pcurves of the sides using the edge (a closed direction's seam: u = 0 and u = nu) */
        int surfs[2] = {surf, surf}, rep[2], k = 0;
        for (int q = 0; q < 4; q++)
            if (t.edge[(sd + q) % 4] == e)
                rep[k++] = line[(sd + q) % 4];
        c = put_surface_curve(w, c, k, surfs, rep);
        eid[e] = put_edge(w, vid[t.vert[rg2__side_ends[sd][0]]], vid[t.vert[rg2__side_ends[sd][1]]], c);
    }
    int edge[4], fwd[4], n = 0;
    for (int sd = 0; sd < 4; sd++) {
        if (t.edge[sd] < 0)
            continue;
        edge[n] = eid[t.edge[sd]];
        fwd[n++] = sd < 2;
    }
    int face = put_face(w, surf, edge, fwd, n);
    *shell = put_shell(w, &face, 1, t.closed);
    rg2__mesh_topo_free(&t);
    return RG2_OK;
oom:
    rg2__mesh_topo_free(&t);
    return rg2__fail(err, RG2_ENOMEM, "STEP: out of memory");
}

/* A STEP string: printable ASCII, apostrophes doubled. */
static void put_string(FILE *f, const char *s)
{
    fputc('\'', f);
    for (; *s; s++) {
        unsigned char c = (unsigned char)*s;
        if (c == '\'')
            fputs("''", f);
        else if (c == '\\')
            fputs("\\\\", f);
        else
            fputc(c >= 32 && c < 127 ? c : '_', f);
    }
    fputc('\'', f);
}

rg2_status rg2__write_step(const rg2_surface *surfs, int n, const rg2_export_opts *o, rg2__out *out,
                           rg2_error *err)
{
    FILE *f = out->f;
    const char *base = strrchr(out->path, '/');
    base = base ? base + 1 : out->path;
    char stamp[32];
    rg2__utc_stamp(stamp, sizeof stamp, "%Y-%m-%dT%H:%M:%S");
    fputs("ISO-10303-21;\nHEADER;\nFILE_DESCRIPTION(('rational bi-cubic G2 spline surfaces (rg2)'),'2;1');\n"
          "FILE_NAME(",
          f);
    put_string(f, base);
    fprintf(f, ",'%s',(''),(''),'rg2 %s','rg2','');\n", stamp, rg2_version());
    fprintf(f, "FILE_SCHEMA(('%s'));\nENDSEC;\nDATA;\n",
            o->ap242 ? "AP242_MANAGED_MODEL_BASED_3D_ENGINEERING_MIM_LF { 1 0 10303 442 1 1 4 }"
                     : "AUTOMOTIVE_DESIGN { 1 0 10303 214 1 1 1 1 }");
    stepw w = {f, 1, 0, {0, 0, 0, 0}};
    int *shells = malloc(sizeof(int) * (size_t)n);
    if (!shells)
        return rg2__fail(err, RG2_ENOMEM, "STEP: out of memory");
    for (int k = 0; k < n; k++) {
        rg2_status st = o->layout == RG2_STEP_FACE_PER_MESH ? shell_per_mesh(&w, &surfs[k], &shells[k], err)
                                                            : shell_per_patch(&w, &surfs[k], &shells[k], err);
        if (st) {
            free(shells);
            return st;
        }
    }
    int model = new_id(&w);
    fprintf(f, "#%d=SHELL_BASED_SURFACE_MODEL('',(", model);
    for (int k = 0; k < n; k++)
        fprintf(f, "%s#%d", k ? "," : "", shells[k]);
    fputs("));\n", f);
    free(shells);
    int origin = new_id(&w), zdir = new_id(&w), xdir = new_id(&w), axis = new_id(&w);
    fprintf(f, "#%d=CARTESIAN_POINT('',(0.,0.,0.));\n#%d=DIRECTION('',(0.,0.,1.));\n"
               "#%d=DIRECTION('',(1.,0.,0.));\n#%d=AXIS2_PLACEMENT_3D('',#%d,#%d,#%d);\n",
            origin, zdir, xdir, axis, origin, zdir, xdir);
    int ulen = new_id(&w), uang = new_id(&w), usol = new_id(&w), unc = new_id(&w), ctx = new_id(&w);
    fprintf(f, "#%d=( LENGTH_UNIT() NAMED_UNIT(*) SI_UNIT(.MILLI.,.METRE.) );\n", ulen);
    fprintf(f, "#%d=( NAMED_UNIT(*) PLANE_ANGLE_UNIT() SI_UNIT($,.RADIAN.) );\n", uang);
    fprintf(f, "#%d=( NAMED_UNIT(*) SI_UNIT($,.STERADIAN.) SOLID_ANGLE_UNIT() );\n", usol);
    fprintf(f, "#%d=UNCERTAINTY_MEASURE_WITH_UNIT(LENGTH_MEASURE(1.E-07),#%d,'distance_accuracy_value',"
               "'confusion accuracy');\n",
            unc, ulen);
    fprintf(f, "#%d=( GEOMETRIC_REPRESENTATION_CONTEXT(3) GLOBAL_UNCERTAINTY_ASSIGNED_CONTEXT((#%d))\n"
               " GLOBAL_UNIT_ASSIGNED_CONTEXT((#%d,#%d,#%d)) REPRESENTATION_CONTEXT('Context #1',"
               "'3D Context with UNIT and UNCERTAINTY') );\n",
            ctx, unc, ulen, uang, usol);
    int rep = new_id(&w);
    fprintf(f, "#%d=MANIFOLD_SURFACE_SHAPE_REPRESENTATION(", rep);
    put_string(f, o->name);
    fprintf(f, ",(#%d,#%d),#%d);\n", axis, model, ctx);
    int app = new_id(&w), apd = new_id(&w), pctx = new_id(&w), prod = new_id(&w), cat = new_id(&w);
    int pdf = new_id(&w), pdctx = new_id(&w), pd = new_id(&w), pds = new_id(&w), sdr = new_id(&w);
    if (o->ap242) {
        fprintf(f, "#%d=APPLICATION_CONTEXT('managed model based 3d engineering');\n", app);
        fprintf(f, "#%d=APPLICATION_PROTOCOL_DEFINITION('international standard',"
                   "'ap242_managed_model_based_3d_engineering',2011,#%d);\n",
                apd, app);
    } else {
        fprintf(f, "#%d=APPLICATION_CONTEXT('automotive_design');\n", app);
        fprintf(f, "#%d=APPLICATION_PROTOCOL_DEFINITION('international standard','automotive_design',2000,#%d);\n",
                apd, app);
    }
    fprintf(f, "#%d=PRODUCT_CONTEXT('',#%d,'mechanical');\n#%d=PRODUCT(", pctx, app, prod);
    put_string(f, o->name);
    fputc(',', f);
    put_string(f, o->name);
    fprintf(f, ",'',(#%d));\n", pctx);
    fprintf(f, "#%d=PRODUCT_RELATED_PRODUCT_CATEGORY('part',$,(#%d));\n", cat, prod);
    fprintf(f, "#%d=PRODUCT_DEFINITION_FORMATION('','',#%d);\n", pdf, prod);
    fprintf(f, "#%d=PRODUCT_DEFINITION_CONTEXT('part definition',#%d,'design');\n", pdctx, app);
    fprintf(f, "#%d=PRODUCT_DEFINITION('design','',#%d,#%d);\n", pd, pdf, pdctx);
    fprintf(f, "#%d=PRODUCT_DEFINITION_SHAPE('','',#%d);\n", pds, pd);
    fprintf(f, "#%d=SHAPE_DEFINITION_REPRESENTATION(#%d,#%d);\n", sdr, pds, rep);
    fputs("ENDSEC;\nEND-ISO-10303-21;\n", f);
    return RG2_OK;
}
