/* iges.c -- IGES 5.3 of rational patch surfaces: one untrimmed rational B-spline surface
 * (entity 128, form 0) per patch, of that patch's degrees, or per surface (merged net of all
 * patches elevated to the surface's degrees (du, dv), interior knots of multiplicity du, dv);
 * or (iges_brep) per surface a B-rep shell (514) of one face (510) per patch, or of one face on
 * the merged net, with shared edges (504, model curves 126) and vertices (502) and exact pcurves
 * (110); fixed 80-column
 * records, global section in mm with resolution 1e-6 (shared/spec/INTEROP.md section 3). */
#include "export_internal.h"

#include <stdlib.h>
#include <string.h>

/* A growable text buffer of 80-column records. */
typedef struct {
    char *s;
    size_t len, cap;
    int nlines;
    int failed;
} ibuf;

static void ib_put(ibuf *b, const char *line80)
{
    if (b->failed)
        return;
    if (b->len + 82 > b->cap) {
        size_t cap = b->cap ? 2 * b->cap : 8192;
        char *s = realloc(b->s, cap);
        if (!s) {
            b->failed = 1;
            return;
        }
        b->s = s;
        b->cap = cap;
    }
    memcpy(b->s + b->len, line80, 80);
    b->s[b->len + 80] = '\n';
    b->len += 81;
    b->nlines++;
}

/* Parameter-data writer: tokens of one entity packed into columns 1-64. */
typedef struct {
    ibuf *P;
    char line[72];
    int col;
    int de; /* DE pointer of the entity being written */
} pwriter;

static void pw_flush(pwriter *w)
{
    char rec[81];
    memset(rec, ' ', 80);
    memcpy(rec, w->line, (size_t)w->col);
    char tail[32]; /* 15 characters used; room for any int */
    snprintf(tail, sizeof tail, "%7dP%7d", w->de, w->P->nlines + 1);
    memcpy(rec + 65, tail, 15);
    ib_put(w->P, rec);
    w->col = 0;
}

/* Add a token followed by its delimiter (',' or ';'). */
static void pw_tok(pwriter *w, const char *tok, char delim)
{
    size_t n = strlen(tok);
    if (w->col + (int)n + 1 > 64)
        pw_flush(w);
    memcpy(w->line + w->col, tok, n);
    w->col += (int)n;
    w->line[w->col++] = delim;
}

static void pw_int(pwriter *w, int x)
{
    char b[24];
    snprintf(b, sizeof b, "%d", x);
    pw_tok(w, b, ',');
}

static void pw_real(pwriter *w, double x, char delim)
{
    char b[40];
    rg2__real(b, x);
    pw_tok(w, b, delim);
}

/* End the entity: its last delimiter becomes ';' (every token is followed by one, in the current
 * line: pw_tok flushes before a token, never after it). */
static void pw_end(pwriter *w)
{
    if (w->col > 0 && w->line[w->col - 1] == ',')
        w->line[w->col - 1] = ';';
}

/* Full knot vector of n spans of degree deg: 0 (deg + 1 times), 1 (deg times), ..., n
 * (deg + 1 times); for degree 3: 0,0,0,0,1,1,1,2,2,2,...,n,n,n,n. */
static void pw_knots(pwriter *w, int n_spans, int deg)
{
    for (int k = 0; k <= n_spans; k++) {
        int m = (k == 0 || k == n_spans) ? deg + 1 : deg;
        for (int q = 0; q < m; q++)
            pw_real(w, (double)k, ',');
    }
}

/*
 * Entity 128 of degree (du, dv), piecewise Bezier, of a net of NU x NV homogeneous poles
 * h[a * NV + b] (a along u). IGES lists weights and poles with the u index fastest.
 */
static void put_128(pwriter *w, const double (*h)[4], int NU, int NV, int du, int dv, int closed_u,
                    int closed_v)
{
    int rational = 0;
    for (int a = 0; a < NU * NV; a++)
        if (h[a][3] != 1.0)
            rational = 1;
    pw_int(w, 128);
    pw_int(w, NU - 1);
    pw_int(w, NV - 1);
    pw_int(w, du);
    pw_int(w, dv);
    pw_int(w, closed_u);
    pw_int(w, closed_v);
    pw_int(w, rational ? 0 : 1);
    pw_int(w, 0);
    pw_int(w, 0);
    pw_knots(w, (NU - 1) / du, du);
    pw_knots(w, (NV - 1) / dv, dv);
    for (int b = 0; b < NV; b++)
        for (int a = 0; a < NU; a++)
            pw_real(w, h[a * NV + b][3], ',');
    for (int b = 0; b < NV; b++)
        for (int a = 0; a < NU; a++)
            for (int d = 0; d < 3; d++)
                pw_real(w, h[a * NV + b][d] / h[a * NV + b][3], ',');
    pw_real(w, 0.0, ',');
    pw_real(w, (double)((NU - 1) / du), ',');
    pw_real(w, 0.0, ',');
    pw_real(w, (double)((NV - 1) / dv), ';');
    if (w->col > 0)
        pw_flush(w);
}

/* The two directory-entry records of an entity: status "00000000" (independent) or
 * "00010000" (physically dependent: referenced by another entity), label and subscript. */
static void put_de_full(ibuf *D, int type, int pstart, int pcount, int form, const char *status, const char *label,
                        int index)
{
    char rec[96];
    snprintf(rec, sizeof rec, "%8d%8d%8d%8d%8d%8d%8d%8d%8sD%7d", type, pstart, 0, 0, 0, 0, 0, 0, status,
             D->nlines + 1);
    ib_put(D, rec);
    snprintf(rec, sizeof rec, "%8d%8d%8d%8d%8d%8s%8s%8s%8dD%7d", type, 0, 0, pcount, form, "", "", label, index,
             D->nlines + 1);
    ib_put(D, rec);
}

static void put_de(ibuf *D, int type, int pstart, int pcount, int index)
{
    put_de_full(D, type, pstart, pcount, 0, "00000000", "RG2SURF", index);
}

/* ---------------------------------------------------------------- B-rep shell (iges_brep) */

/* The DE pointer of the q-th entity of the file. */
static int de_of(int q) { return 2 * q + 1; }

/* Close the parameter data of entity q (type, form) and write its directory entry. */
static void end_entity(pwriter *w, ibuf *D, int start, int type, int form, const char *status, const char *label,
                       int q)
{
    if (w->col > 0)
        pw_flush(w);
    put_de_full(D, type, start, w->P->nlines + 1 - start, form, status, label, q);
}

/* Entity 126 (rational B-spline curve), piecewise Bezier of degree deg through the n
 * homogeneous poles h (n = deg spans + 1), parameter 0 .. spans: an edge's model-space curve. */
static void put_126(pwriter *w, const double (*h)[4], int n, int deg)
{
    int rational = 0;
    for (int a = 0; a < n; a++)
        if (h[a][3] != 1.0)
            rational = 1;
    pw_int(w, 126);
    pw_int(w, n - 1);
    pw_int(w, deg);
    pw_int(w, 0); /* not asserted planar */
    pw_int(w, 0);
    pw_int(w, rational ? 0 : 1);
    pw_int(w, 0);
    pw_knots(w, (n - 1) / deg, deg);
    for (int a = 0; a < n; a++)
        pw_real(w, h[a][3], ',');
    for (int a = 0; a < n; a++)
        for (int d = 0; d < 3; d++)
            pw_real(w, h[a][d] / h[a][3], ',');
    pw_real(w, 0.0, ',');
    pw_real(w, (double)((n - 1) / deg), ';');
}

/* 514: a shell of the faces with DE pointers face_de[0..n-1], each with its surface's sense. */
static void put_514(pwriter *w, ibuf *D, int q, const int *face_q, int n, int closed)
{
    int start = w->P->nlines + 1;
    w->de = de_of(q);
    pw_int(w, 514);
    pw_int(w, n);
    for (int k = 0; k < n; k++) {
        pw_int(w, de_of(face_q[k]));
        pw_int(w, 1);
    }
    pw_end(w);
    end_entity(w, D, start, 514, closed ? 1 : 2, "00000000", "RG2SHELL", q);
}

/* 502: the vertices, homogeneous points h[0..n-1]. */
static void put_502(pwriter *w, ibuf *D, int q, const double (*h)[4], int n)
{
    int start = w->P->nlines + 1;
    w->de = de_of(q);
    pw_int(w, 502);
    pw_int(w, n);
    for (int v = 0; v < n; v++)
        for (int d = 0; d < 3; d++)
            pw_real(w, h[v][d] / h[v][3], ',');
    pw_end(w);
    end_entity(w, D, start, 502, 1, "00010000", "RG2VERT", q);
}

/* 504: edge e runs along the curve entity q_curve + e from vertex ends[e][0] to ends[e][1] of
 * the vertex list q_vl (0-based indices). */
static void put_504(pwriter *w, ibuf *D, int q, int q_vl, int q_curve, const int (*ends)[2], int n)
{
    int start = w->P->nlines + 1;
    w->de = de_of(q);
    pw_int(w, 504);
    pw_int(w, n);
    for (int e = 0; e < n; e++) {
        pw_int(w, de_of(q_curve + e));
        pw_int(w, de_of(q_vl));
        pw_int(w, ends[e][0] + 1);
        pw_int(w, de_of(q_vl));
        pw_int(w, ends[e][1] + 1);
    }
    pw_end(w);
    end_entity(w, D, start, 504, 1, "00010000", "RG2EDGE", q);
}

/* 126 at entity q: an edge's model curve, poles h[0..n-1] of degree deg. */
static void put_126_entity(pwriter *w, ibuf *D, int q, const double (*h)[4], int n, int deg)
{
    int start = w->P->nlines + 1;
    w->de = de_of(q);
    put_126(w, h, n, deg);
    end_entity(w, D, start, 126, 0, "00010000", "RG2CURVE", q);
}

/* 128 at entity q (a face's surface), 508 at q + 1 (its loop: the n uses of edges edge[k] of the
 * list q_el, orientation fwd[k], pcurve entity line_q[k]) and 510 at q + 2 (the face). */
static void put_face_entities(pwriter *w, ibuf *D, int q, const double (*h)[4], int NU, int NV, int du, int dv,
                              int closed_u, int closed_v, int q_el, const int *edge, const int *fwd,
                              const int *line_q, int n)
{
    int start = w->P->nlines + 1;
    w->de = de_of(q);
    put_128(w, h, NU, NV, du, dv, closed_u, closed_v);
    put_de_full(D, 128, start, w->P->nlines + 1 - start, 0, "00010000", "RG2SURF", q);
    start = w->P->nlines + 1;
    w->de = de_of(q + 1);
    pw_int(w, 508);
    pw_int(w, n);
    for (int k = 0; k < n; k++) {
        pw_int(w, 0); /* an edge (not a vertex) */
        pw_int(w, de_of(q_el));
        pw_int(w, edge[k] + 1);
        pw_int(w, fwd[k]);
        pw_int(w, 1); /* one pcurve: the side of the parameter rectangle */
        pw_int(w, 0);
        pw_int(w, de_of(line_q[k]));
    }
    pw_end(w);
    end_entity(w, D, start, 508, 1, "00010000", "RG2LOOP", q + 1);
    start = w->P->nlines + 1;
    w->de = de_of(q + 2);
    pw_int(w, 510);
    pw_int(w, de_of(q));
    pw_int(w, 1);
    pw_int(w, 1); /* the loop is the outer one */
    pw_int(w, de_of(q + 1));
    pw_end(w);
    end_entity(w, D, start, 510, 1, "00010000", "RG2FACE", q + 2);
}

/* The B-rep entities of one surface, face per patch, from entity index *q on:
 *   514 shell, 502 vertex list, 504 edge list, 126 per edge, then per patch 128, 508, 510.
 * Edges and vertices come from rg2__topo as in the STEP writer (one per geometric edge /
 * corner, shared by the faces on both sides; collapsed sides left out of their loops). The
 * loops run counter-clockwise in (u, v); each edge use carries its pcurve, line[side] (the
 * file's four 110 lines along the sides of [0, 1]^2 in the loop's direction). */
static rg2_status brep_shell(pwriter *w, ibuf *D, const rg2_surface *s, const int line[4], int *q,
                             rg2_error *err)
{
    rg2__topo t;
    rg2_status st = rg2__topo_build(s, &t, err);
    if (st)
        return st;
    int nu = s->nu, nv = s->nv, np = nu * nv;
    int q_shell = *q, q_vl = q_shell + 1, q_el = q_shell + 2, q_curve = q_shell + 3;
    int q_patch = q_curve + t.n_edges; /* patch p: 128 at q_patch + 3 p, 508 + 1, 510 + 2 */
    int closed = 1;
    for (int e = 0; e < t.n_edges; e++)
        closed &= t.uses[e] == 2;
    int *face_q = malloc(sizeof(int) * (size_t)np);
    double(*vh)[4] = malloc(sizeof(double[4]) * (size_t)(t.n_vertices ? t.n_vertices : 1));
    int(*ends)[2] = malloc(sizeof(int[2]) * (size_t)(t.n_edges ? t.n_edges : 1));
    if (!face_q || !vh || !ends) {
        st = rg2__fail(err, RG2_ENOMEM, "IGES: out of memory for %d x %d patches", nu, nv);
        goto done;
    }
    for (int p = 0; p < np; p++)
        face_q[p] = q_patch + 3 * p + 2;
    put_514(w, D, q_shell, face_q, np, closed);
    for (int v = 0; v < t.n_vertices; v++)
        rg2__corner_point(s, t.vcorner[v] / (nv + 1), t.vcorner[v] % (nv + 1), vh[v]);
    put_502(w, D, q_vl, (const double(*)[4])vh, t.n_vertices);
    for (int e = 0; e < t.n_edges; e++) { /* the same corners as the STEP writer's */
        int p = t.edef[2 * e], side = t.edef[2 * e + 1], i = p / nv, j = p % nv;
        int I0 = side == 1 ? i + 1 : i, J0 = side == 2 ? j + 1 : j;
        int I1 = (side == 0 || side == 2) ? i + 1 : I0, J1 = (side == 1 || side == 3) ? j + 1 : J0;
        ends[e][0] = t.vert[I0 * (nv + 1) + J0];
        ends[e][1] = t.vert[I1 * (nv + 1) + J1];
    }
    put_504(w, D, q_el, q_vl, q_curve, (const int(*)[2])ends, t.n_edges);
    for (int e = 0; e < t.n_edges; e++) {
        int p = t.edef[2 * e];
        rg2_xpatch X;
        double h[RG2_MAX_DEGREE + 1][4];
        rg2_surface_patch_get(s, p / nv, p % nv, &X);
        int n = rg2__xpatch_side(&X, t.edef[2 * e + 1], h);
        put_126_entity(w, D, q_curve + e, (const double(*)[4])h, n, n - 1);
    }
    for (int p = 0; p < np; p++) {
        rg2_xpatch X;
        double h[(RG2_MAX_DEGREE + 1) * (RG2_MAX_DEGREE + 1)][4];
        rg2_surface_patch_get(s, p / nv, p % nv, &X);
        rg2__xpatch_net(&X, h);
        int edge[4], fwd[4], lq[4], n = 0;
        for (int side = 0; side < 4; side++) {
            int e, f;
            rg2__topo_side(&t, p / nv, p % nv, side, &e, &f);
            if (e < 0)
                continue;
            edge[n] = e;
            fwd[n] = f;
            lq[n++] = line[side];
        }
        put_face_entities(w, D, q_patch + 3 * p, (const double(*)[4])h, X.du + 1, X.dv + 1, X.du, X.dv, 0, 0, q_el,
                          edge, fwd, lq, n);
    }
    *q = q_patch + 3 * np;
done:
    free(face_q);
    free(vh);
    free(ends);
    rg2__topo_free(&t);
    return st;
}

/* The four pcurves of a face on [0, U1] x [0, V1]: 110 lines along its sides, counter-clockwise
 * (v=0 in +u, u=U1 in +v, v=V1 in -u, u=0 in -v), as entities q .. q + 3. */
static void brep_lines(pwriter *w, ibuf *D, int q, double U1, double V1)
{
    const double ends[4][4] = {{0, 0, U1, 0}, {U1, 0, U1, V1}, {U1, V1, 0, V1}, {0, V1, 0, 0}};
    for (int k = 0; k < 4; k++) {
        int start = w->P->nlines + 1;
        w->de = de_of(q + k);
        pw_int(w, 110);
        pw_real(w, ends[k][0], ',');
        pw_real(w, ends[k][1], ',');
        pw_real(w, 0.0, ',');
        pw_real(w, ends[k][2], ',');
        pw_real(w, ends[k][3], ',');
        pw_real(w, 0.0, ';');
        end_entity(w, D, start, 110, 0, "00010000", "RG2PCURV", q + k);
    }
}

/* The B-rep entities of one surface as one face on its merged net (face per mesh), from entity
 * index *q on: 514 shell, 502 vertex list, 504 edge list, 126 per edge, the face's four 110
 * lines on [0, nu] x [0, nv], 128, 508, 510; the topology of rg2__mesh_topo (the STEP writer's):
 * a closed direction's seam edge is used twice by the loop, once with each of its lines. */
static rg2_status brep_mesh_shell(pwriter *w, ibuf *D, const rg2_surface *s, int *q, rg2_error *err)
{
    rg2__mesh_topo t;
    rg2_status st = rg2__mesh_topo_build(s, &t, err);
    if (st)
        return st;
    int q_shell = *q, q_vl = q_shell + 1, q_el = q_shell + 2, q_curve = q_shell + 3;
    int q_line = q_curve + t.n_edges, q_face = q_line + 4;
    int face_q = q_face + 2;
    put_514(w, D, q_shell, &face_q, 1, t.closed);
    double vh[4][4];
    for (int v = 0; v < t.n_vertices; v++) {
        int c = t.vcorner[v];
        memcpy(vh[v], t.h[(size_t)(c == 1 || c == 2 ? t.NU - 1 : 0) * (size_t)t.NV + (size_t)(c >= 2 ? t.NV - 1 : 0)],
               sizeof(double[4]));
    }
    put_502(w, D, q_vl, (const double(*)[4])vh, t.n_vertices);
    int ends[4][2];
    for (int e = 0; e < t.n_edges; e++) {
        ends[e][0] = t.vert[rg2__side_ends[t.eside[e]][0]];
        ends[e][1] = t.vert[rg2__side_ends[t.eside[e]][1]];
    }
    put_504(w, D, q_el, q_vl, q_curve, (const int(*)[2])ends, t.n_edges);
    for (int e = 0; e < t.n_edges; e++) {
        int sd = t.eside[e], n = rg2__net_side(&t, sd);
        put_126_entity(w, D, q_curve + e, (const double(*)[4])t.side, n, (sd & 1) ? t.dv : t.du);
    }
    brep_lines(w, D, q_line, (double)s->nu, (double)s->nv);
    int edge[4], fwd[4], lq[4], n = 0;
    for (int sd = 0; sd < 4; sd++) {
        if (t.edge[sd] < 0)
            continue;
        edge[n] = t.edge[sd];
        fwd[n] = sd < 2;
        lq[n++] = q_line + sd;
    }
    put_face_entities(w, D, q_face, (const double(*)[4])t.h, t.NU, t.NV, t.du, t.dv, s->closed_u, s->closed_v, q_el,
                      edge, fwd, lq, n);
    *q = q_face + 3;
    rg2__mesh_topo_free(&t);
    return RG2_OK;
}

/* Hollerith string nHtext. */
static void hollerith(char *out, size_t cap, const char *s)
{
    char clean[64];
    size_t n = 0;
    for (; *s && n < 60; s++)
        clean[n++] = (*s >= 32 && *s < 127) ? *s : '_';
    clean[n] = '\0';
    snprintf(out, cap, "%zuH%s", n, clean);
}

static void g_flush(ibuf *G, const char *line, int col)
{
    char rec[81];
    memset(rec, ' ', 80);
    memcpy(rec, line, (size_t)col);
    char tail[16]; /* 8 characters used; room for any int */
    snprintf(tail, sizeof tail, "G%7d", G->nlines + 1);
    memcpy(rec + 72, tail, 8);
    ib_put(G, rec);
}

/* Global section: tokens wrapped into columns 1-72. */
static void put_global(ibuf *G, const char *const *tok, int n)
{
    char line[73];
    int col = 0;
    for (int k = 0; k < n; k++) {
        size_t len = strlen(tok[k]);
        if (col + (int)len + 1 > 72) {
            g_flush(G, line, col);
            col = 0;
        }
        memcpy(line + col, tok[k], len);
        col += (int)len;
        line[col++] = k + 1 < n ? ',' : ';';
    }
    g_flush(G, line, col);
}

static void put_section_line(FILE *f, const char *text, char letter, int seq)
{
    char rec[81];
    memset(rec, ' ', 80);
    size_t n = strlen(text);
    memcpy(rec, text, n > 72 ? 72 : n);
    char tail[16]; /* 8 characters used; room for any int */
    snprintf(tail, sizeof tail, "%c%7d", letter, seq);
    memcpy(rec + 72, tail, 8);
    fwrite(rec, 1, 80, f);
    fputc('\n', f);
}

int rg2__iges_max_records = 9999999;

rg2_status rg2__write_iges(const rg2_surface *surfs, int n, const rg2_export_opts *o, rg2__out *out,
                           rg2_error *err)
{
    ibuf D = {0}, P = {0}, G = {0};
    pwriter w = {&P, {0}, 0, 0};
    double maxc = 0.0;
    int entity = 0, line[4] = {0, 1, 2, 3};
    rg2_status st = RG2_OK;
    int per_mesh = o->layout == RG2_STEP_FACE_PER_MESH;
    if (o->iges_brep && !per_mesh) { /* every patch face shares the lines of [0, 1]^2 */
        brep_lines(&w, &D, 0, 1.0, 1.0);
        entity = 4;
    }
    for (int k = 0; k < n && !P.failed; k++) {
        const rg2_surface *s = &surfs[k];
        for (int p = 0; p < s->nu * s->nv; p++) {
            rg2_xpatch X;
            rg2_surface_patch_get(s, p / s->nv, p % s->nv, &X);
            for (int r = 0; r <= X.du; r++)
                for (int t = 0; t <= X.dv; t++)
                    for (int d = 0; d < 3; d++) {
                        double x = fabs(X.h[r][t][d] / X.h[r][t][3]);
                        maxc = x > maxc ? x : maxc;
                    }
        }
        if (o->iges_brep) {
            st = per_mesh ? brep_mesh_shell(&w, &D, s, &entity, err) : brep_shell(&w, &D, s, line, &entity, err);
            if (st)
                goto done;
        } else if (per_mesh) {
            int NU, NV, du, dv;
            double(*h)[4] = rg2__merged_net(s, &NU, &NV, &du, &dv);
            if (!h) {
                P.failed = 1;
                break;
            }
            int start = P.nlines + 1;
            w.de = 2 * entity + 1;
            put_128(&w, (const double(*)[4])h, NU, NV, du, dv, s->closed_u, s->closed_v);
            put_de(&D, 128, start, P.nlines + 1 - start, entity);
            entity++;
            free(h);
        } else {
            for (int p = 0; p < s->nu * s->nv; p++) {
                int start = P.nlines + 1;
                w.de = 2 * entity + 1;
                rg2_xpatch X;
                double h[(RG2_MAX_DEGREE + 1) * (RG2_MAX_DEGREE + 1)][4];
                rg2_surface_patch_get(s, p / s->nv, p % s->nv, &X);
                rg2__xpatch_net(&X, h);
                put_128(&w, (const double(*)[4])h, X.du + 1, X.dv + 1, X.du, X.dv, 0, 0);
                put_de(&D, 128, start, P.nlines + 1 - start, entity);
                entity++;
            }
        }
    }
    char stamp[32];
    rg2__utc_stamp(stamp, sizeof stamp, "15H%Y%m%d.%H%M%S");
    const char *base = strrchr(out->path, '/');
    base = base ? base + 1 : out->path;
    char hname[80], hfile[80], hsys[80], hver[80], maxs[40];
    hollerith(hname, sizeof hname, o->name);
    hollerith(hfile, sizeof hfile, base);
    hollerith(hsys, sizeof hsys, "rg2");
    char ver[32];
    snprintf(ver, sizeof ver, "rg2 %s", rg2_version());
    hollerith(hver, sizeof hver, ver);
    rg2__real(maxs, maxc);
    const char *gt[] = {"1H,", "1H;", hname, hfile, hsys, hver, "32", "38", "6", "308", "15", hname,
                        "1.", "2", "2HMM", "1", "0.01", stamp, "1.E-06", maxs, "0H", "0H", "11", "0",
                        stamp};
    put_global(&G, gt, (int)(sizeof gt / sizeof gt[0]));
    if (D.failed || P.failed || G.failed) {
        st = rg2__fail(err, RG2_ENOMEM, "IGES: out of memory");
        goto done;
    }
    /* each record carries its sequence number in 7 columns (and directory entries point to each
     * other by them): past 9,999,999 records in a section the file cannot be written */
    if (D.nlines > rg2__iges_max_records || P.nlines > rg2__iges_max_records) {
        st = rg2__fail(err, RG2_ELIMIT,
                       "IGES: %d directory and %d parameter records, more than the %d that IGES's 7-digit "
                       "sequence numbers allow (size limit exceeded); write STEP, or fewer patches",
                       D.nlines, P.nlines, rg2__iges_max_records);
        goto done;
    }
    put_section_line(out->f,
                     o->iges_brep ? "rg2: rational bi-cubic G2 spline surfaces, IGES 5.3 B-rep shells (514)"
                                  : "rg2: rational bi-cubic G2 spline surfaces, IGES 5.3 entity 128",
                     'S', 1);
    fwrite(G.s, 1, G.len, out->f);
    fwrite(D.s, 1, D.len, out->f);
    fwrite(P.s, 1, P.len, out->f);
    char tl[80];
    snprintf(tl, sizeof tl, "S%7dG%7dD%7dP%7d", 1, G.nlines, D.nlines, P.nlines);
    put_section_line(out->f, tl, 'T', 1);
done:
    free(D.s);
    free(P.s);
    free(G.s);
    return st;
}
