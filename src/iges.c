/* iges.c -- IGES 5.3 of rational patch surfaces: one untrimmed rational B-spline surface
 * (entity 128, form 0) per patch, of that patch's degrees, or per surface (merged net of all
 * patches elevated to the surface's degrees (du, dv), interior knots of multiplicity du, dv);
 * or (iges_brep) per surface a B-rep shell (514) of one face (510) per patch, or of one face on
 * the merged net, with shared edges (504, model curves 126) and vertices (502) and exact pcurves
 * (110); fixed 80-column
 * records, global section in mm with resolution 1e-6 (shared/spec/INTEROP.md section 3).
 * The parameter data of the many small entities (patches, edges) are formatted on the threads in
 * blocks (emit_items), a long list of reals in chunks (pw_reals), and written as they come; the
 * directory entries are kept until every entity's parameter records are counted, then formatted
 * on the threads too, into the place left for them (rg2__write_iges): the same bytes as one
 * thread's. */
#include "export_internal.h"

#include <errno.h>
#include <limits.h>
#include <stdlib.h>
#include <string.h>

/* A growable text buffer of 80-column records. */
typedef struct {
    char *s;
    size_t len, cap;
    int nlines;
    int failed; /* 1 out of memory, 2 (emit_items) a block's records out of step */
} ibuf;

static int ib_reserve(ibuf *b, size_t more)
{
    if (b->failed)
        return 0;
    if (b->len + more > b->cap) {
        size_t cap = b->cap ? 2 * b->cap : 8192;
        while (cap < b->len + more)
            cap *= 2;
        char *s = realloc(b->s, cap);
        if (!s) {
            b->failed = 1;
            return 0;
        }
        b->s = s;
        b->cap = cap;
    }
    return 1;
}

static void ib_put(ibuf *b, const char *line80)
{
    if (!ib_reserve(b, 82))
        return;
    memcpy(b->s + b->len, line80, 80);
    b->s[b->len + 80] = '\n';
    b->len += 81;
    b->nlines++;
}

/* x right-aligned in 7 columns (the low 7 digits past 9 999 999, which the record limit
 * refuses anyway). */
static void put7(char *p, int x)
{
    unsigned u = (unsigned)x;
    for (int c = 6; c >= 0; c--) {
        p[c] = (c == 6 || u) ? (char)('0' + u % 10) : ' ';
        u /= 10;
    }
}

/* The directory entry of an entity, kept until the parameter data are all written (an entity's
 * parameter lines are known only then when entities are formatted on the threads). */
typedef struct {
    int type, form, pstart, pcount;
    const char *status, *label;
} idir;

typedef struct {
    idir *d;
    int cap;
} idirs;

static int dir_reserve(idirs *D, int n)
{
    if (n <= D->cap)
        return 1;
    int cap = D->cap ? D->cap : 64;
    while (cap < n)
        cap = cap > INT_MAX / 2 ? n : 2 * cap;
    idir *d = realloc(D->d, sizeof(idir) * (size_t)cap);
    if (!d)
        return 0;
    D->d = d;
    D->cap = cap;
    return 1;
}

/* Parameter-data writer: tokens of one entity packed into columns 1-64, the records gathered in
 * P and passed to f a megabyte at a time. The file's writer numbers its records from the
 * section's first; a block's writer (emit_items; f its memory stream) from the block's first,
 * renumbered when the block goes to the file. */
typedef struct {
    ibuf *P;
    char line[72];
    int col;
    int de;      /* DE pointer of the entity being written */
    idirs *dir;  /* directory entries by entity index */
    int qlo, qhi; /* the entities this writer ended */
    FILE *f;      /* the file, or a block's memory stream */
} pwriter;

#define STAGE_BYTES ((size_t)1 << 20) /* the file's writer's records gathered before a write */

/* The gathered records to f (write errors: at the file's close, or the memory stream's flush). */
static void pw_drain(pwriter *w)
{
    if (w->P->len) {
        fwrite(w->P->s, 1, w->P->len, w->f);
        w->P->len = 0;
    }
}

static void pw_flush(pwriter *w)
{
    char rec[80];
    memset(rec, ' ', 80);
    memcpy(rec, w->line, (size_t)w->col);
    put7(rec + 65, w->de);
    rec[72] = 'P';
    put7(rec + 73, w->P->nlines + 1);
    ib_put(w->P, rec);
    w->col = 0;
    if (w->P->len >= STAGE_BYTES)
        pw_drain(w);
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

#define REALS_CHUNK 8192 /* reals formatted on the threads at a time (pw_reals) */

/* The reals x[0..n-1] as tokens, each followed by ','. A long list (the net of a surface as one
 * entity) is formatted on the threads REALS_CHUNK at a time, then packed in order: the same
 * bytes. Returns 0, or -1 out of memory (the buffer marked failed). */
static int pw_reals(pwriter *w, const double *x, size_t n)
{
    if (n < 2048) {
        for (size_t k = 0; k < n; k++)
            pw_real(w, x[k], ',');
        return 0;
    }
    char(*tok)[40] = malloc(sizeof(char[40]) * REALS_CHUNK);
    if (!tok) {
        w->P->failed = 1;
        return -1;
    }
    for (size_t k0 = 0; k0 < n; k0 += REALS_CHUNK) {
        int m = n - k0 < REALS_CHUNK ? (int)(n - k0) : REALS_CHUNK;
#ifdef RG2_HAVE_OPENMP
#pragma omp parallel
#endif
        {
            void *loc = rg2__c_numeric_begin(); /* each thread's numbers in the C locale */
#ifdef RG2_HAVE_OPENMP
#pragma omp for schedule(static)
#endif
            for (int k = 0; k < m; k++)
                rg2__real(tok[k], x[k0 + (size_t)k]);
            rg2__c_numeric_end(loc);
        }
        for (int k = 0; k < m; k++)
            pw_tok(w, tok[k], ',');
    }
    free(tok);
    return 0;
}

/*
 * The factor an entity's weights (h[0..n-1][3]) are written times. OpenCASCADE's IGES reader
 * takes a weight below 1e-9 (Precision::PConfusion) for one that is not positive: OCCT 7.6
 * silently made every weight of such a surface 1 (later versions drop the entity), though the
 * weights are positive and the geometry exact (a torus whose 4-tuples were all multiplied by
 * 1e-10, rg2_surface_transform: its faces 1.5e-3 of its size off in all four IGES forms, while
 * the STEP file read back to 1.9e-16). A rational B-spline is the same curve or surface when
 * all its weights are multiplied by one factor, and a power of two multiplies exactly (the
 * points are written as they are, affine, apart from the weights): an entity whose smallest weight is
 * below IGES_SMALL_WEIGHT gets the power of two that brings its largest weight into [0.5, 1);
 * any other keeps its weights (factor 1, the same bytes as before).
 */
#define IGES_SMALL_WEIGHT 1e-6

static double weight_factor(const double (*h)[4], size_t n)
{
    double lo = h[0][3], hi = h[0][3];
    for (size_t a = 1; a < n; a++) {
        lo = h[a][3] < lo ? h[a][3] : lo;
        hi = h[a][3] > hi ? h[a][3] : hi;
    }
    if (!(lo < IGES_SMALL_WEIGHT) || !(hi > 0.0))
        return 1.0;
    int e;
    frexp(hi, &e); /* hi = m 2^e, m in [0.5, 1) */
    return ldexp(1.0, -e);
}

/*
 * Entity 128 of degree (du, dv), piecewise Bezier, of a net of NU x NV poles h[a * NV + b] (a
 * along u), each (x, y, z, w) as written (rg2__patch_affine). IGES lists weights and poles with the u index fastest; the weights
 * times weight_factor.
 */
static void put_128(pwriter *w, const double (*h)[4], int NU, int NV, int du, int dv, int closed_u,
                    int closed_v)
{
    size_t np = (size_t)NU * (size_t)NV;
    double small[4 * (RG2_MAX_DEGREE + 1) * (RG2_MAX_DEGREE + 1)];
    double *x = np <= (RG2_MAX_DEGREE + 1) * (RG2_MAX_DEGREE + 1) ? small : malloc(sizeof(double) * 4 * np);
    if (!x) {
        w->P->failed = 1;
        return;
    }
    double f = weight_factor(h, np);
    int rational = 0;
    for (size_t a = 0; a < np; a++)
        if (h[a][3] * f != 1.0)
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
    double *wt = x, *xyz = x + np; /* weights, then points, u fastest */
    for (int b = 0; b < NV; b++)
        for (int a = 0; a < NU; a++) {
            const double *p = h[(size_t)a * (size_t)NV + (size_t)b];
            size_t k = (size_t)b * (size_t)NU + (size_t)a;
            wt[k] = p[3] * f;
            for (int d = 0; d < 3; d++)
                xyz[3 * k + (size_t)d] = p[d];
        }
    pw_reals(w, x, 4 * np);
    if (x != small)
        free(x);
    pw_real(w, 0.0, ',');
    pw_real(w, (double)((NU - 1) / du), ',');
    pw_real(w, 0.0, ',');
    pw_real(w, (double)((NV - 1) / dv), ';');
    if (w->col > 0)
        pw_flush(w);
}

/* ---------------------------------------------------------------- entities */

/* The DE pointer of the q-th entity of the file. */
static int de_of(int q) { return 2 * q + 1; }

/* Start entity q's parameter data; returns its first line (of the writer's buffer). */
static int begin_entity(pwriter *w, int q)
{
    w->de = de_of(q);
    return w->P->nlines + 1;
}

/* Close the parameter data of entity q (from line start on) and keep its directory entry:
 * status "00000000" (independent) or "00010000" (physically dependent: referenced by another
 * entity), label. */
static void end_entity(pwriter *w, int start, int type, int form, const char *status, const char *label, int q)
{
    if (w->col > 0)
        pw_flush(w);
    if (!dir_reserve(w->dir, q + 1)) {
        w->P->failed = 1;
        return;
    }
    w->dir->d[q] = (idir){type, form, start, w->P->nlines + 1 - start, status, label};
    w->qlo = q < w->qlo ? q : w->qlo;
    w->qhi = q > w->qhi ? q : w->qhi;
}

#define IGES_BLOCK 64 /* items formatted per block */

/* Items 0..n-1, each writing the entities fn(w, ctx, k), all below entity q_end, formatted on
 * the threads (rg2__write_blocks: blocks of IGES_BLOCK items, a writer of their own each, its
 * records numbered from 1; the directory entries of distinct entities, in w->dir, reserved
 * first) and renumbered as each block goes to the file (iges_fix): the same bytes as writing the
 * items one after the other. w is the file's writer. */
typedef void (*iges_item)(pwriter *w, void *ctx, int k);

typedef struct {
    pwriter *w;
    iges_item fn;
    void *ctx;
    int (*blk)[3]; /* per block: its records, its first and last entity */
} iges_blocks;

static int iges_block(FILE *m, void *arg, int b, int k0, int k1)
{
    iges_blocks *c = arg;
    ibuf buf = {0};
    pwriter bw = {&buf, {0}, 0, 0, c->w->dir, INT_MAX, -1, m};
    for (int k = k0; k < k1 && !buf.failed; k++)
        c->fn(&bw, c->ctx, k);
    pw_drain(&bw);
    c->blk[b][0] = buf.nlines;
    c->blk[b][1] = bw.qlo;
    c->blk[b][2] = bw.qhi;
    free(buf.s);
    return buf.failed ? -1 : 0;
}

/* Block b's records follow the file's so far: their sequence numbers and its entities' first
 * records moved on by as many. */
static void iges_fix(void *arg, int b, char *text, size_t len)
{
    iges_blocks *c = arg;
    ibuf *P = c->w->P;
    int off = P->nlines;
    if (len != (size_t)c->blk[b][0] * 81) { /* (a bug: fails the export, never writes past text) */
        P->failed = 2;
        return;
    }
    for (int l = 0; l < c->blk[b][0]; l++)
        put7(text + (size_t)l * 81 + 73, off + l + 1);
    for (int q = c->blk[b][1]; q <= c->blk[b][2]; q++)
        c->w->dir->d[q].pstart += off;
    P->nlines += c->blk[b][0];
}

static void emit_items(pwriter *w, int n, int q_end, iges_item fn, void *ctx)
{
    if (w->P->failed || n <= 0)
        return;
    int nblk = (n - 1) / IGES_BLOCK + 1;
    iges_blocks c = {w, fn, ctx, malloc(sizeof(int[3]) * (size_t)nblk)};
    if (!c.blk || !dir_reserve(w->dir, q_end))
        w->P->failed = 1;
    pw_drain(w);
    if (!w->P->failed && rg2__write_blocks(w->f, n, IGES_BLOCK, iges_block, iges_fix, &c) && !w->P->failed)
        w->P->failed = 1;
    free(c.blk);
}

/* ---------------------------------------------------------------- B-rep shell (iges_brep) */

/* Entity 126 (rational B-spline curve), piecewise Bezier of degree deg through the n
 * poles h (n = deg spans + 1, each (x, y, z, w) as written: rg2__patch_affine), parameter 0 .. spans: an edge's model-space curve;
 * the weights times weight_factor, as the 128's. */
static void put_126(pwriter *w, const double (*h)[4], int n, int deg)
{
    double f = weight_factor(h, (size_t)n);
    int rational = 0;
    for (int a = 0; a < n; a++)
        if (h[a][3] * f != 1.0)
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
        pw_real(w, h[a][3] * f, ',');
    for (int a = 0; a < n; a++)
        for (int d = 0; d < 3; d++)
            pw_real(w, h[a][d], ',');
    pw_real(w, 0.0, ',');
    pw_real(w, (double)((n - 1) / deg), ';');
}

/* 514: a shell of the faces with DE pointers face_de[0..n-1], each with its surface's sense. */
static void put_514(pwriter *w, int q, const int *face_q, int n, int closed)
{
    int start = begin_entity(w, q);
    pw_int(w, 514);
    pw_int(w, n);
    for (int k = 0; k < n; k++) {
        pw_int(w, de_of(face_q[k]));
        pw_int(w, 1);
    }
    pw_end(w);
    end_entity(w, start, 514, closed ? 1 : 2, "00000000", "RG2SHELL", q);
}

/* 502: the vertices, points h[0..n-1] as written (x, y, z, w: rg2__corner_affine). */
static void put_502(pwriter *w, int q, const double (*h)[4], int n)
{
    int start = begin_entity(w, q);
    pw_int(w, 502);
    pw_int(w, n);
    double *x = malloc(sizeof(double) * 3 * (size_t)(n ? n : 1));
    if (!x) {
        w->P->failed = 1;
        return;
    }
    for (int v = 0; v < n; v++)
        for (int d = 0; d < 3; d++)
            x[3 * v + d] = h[v][d];
    pw_reals(w, x, 3 * (size_t)n);
    free(x);
    pw_end(w);
    end_entity(w, start, 502, 1, "00010000", "RG2VERT", q);
}

/* 504: edge e runs along the curve entity q_curve + e from vertex ends[e][0] to ends[e][1] of
 * the vertex list q_vl (0-based indices). */
static void put_504(pwriter *w, int q, int q_vl, int q_curve, const int (*ends)[2], int n)
{
    int start = begin_entity(w, q);
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
    end_entity(w, start, 504, 1, "00010000", "RG2EDGE", q);
}

/* 126 at entity q: an edge's model curve, poles h[0..n-1] of degree deg. */
static void put_126_entity(pwriter *w, int q, const double (*h)[4], int n, int deg)
{
    int start = begin_entity(w, q);
    put_126(w, h, n, deg);
    end_entity(w, start, 126, 0, "00010000", "RG2CURVE", q);
}

/* 128 at entity q (a face's surface), 508 at q + 1 (its loop: the n uses of edges edge[k] of the
 * list q_el, orientation fwd[k], pcurve entity line_q[k]) and 510 at q + 2 (the face). */
static void put_face_entities(pwriter *w, int q, const double (*h)[4], int NU, int NV, int du, int dv,
                              int closed_u, int closed_v, int q_el, const int *edge, const int *fwd,
                              const int *line_q, int n)
{
    int start = begin_entity(w, q);
    put_128(w, h, NU, NV, du, dv, closed_u, closed_v);
    end_entity(w, start, 128, 0, "00010000", "RG2SURF", q);
    start = begin_entity(w, q + 1);
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
    end_entity(w, start, 508, 1, "00010000", "RG2LOOP", q + 1);
    start = begin_entity(w, q + 2);
    pw_int(w, 510);
    pw_int(w, de_of(q));
    pw_int(w, 1);
    pw_int(w, 1); /* the loop is the outer one */
    pw_int(w, de_of(q + 1));
    pw_end(w);
    end_entity(w, start, 510, 1, "00010000", "RG2FACE", q + 2);
}

/* What the items of brep_shell read. */
typedef struct {
    const rg2_surface *s;
    const rg2__topo *t;
    const int *line;
    int q_curve, q_el, q_patch;
} shell_items;

/* Edge e's model curve, from its defining patch side. */
static void shell_edge(pwriter *w, void *ctx, int e)
{
    const shell_items *c = ctx;
    int p = c->t->edef[2 * e], nv = c->s->nv;
    rg2_xpatch X;
    double h[RG2_MAX_DEGREE + 1][4];
    rg2__patch_affine(c->t, c->s, p / nv, p % nv, &X);
    int n = rg2__xpatch_side(&X, c->t->edef[2 * e + 1], h);
    put_126_entity(w, c->q_curve + e, (const double(*)[4])h, n, n - 1);
}

/* Patch p's surface, loop and face. */
static void shell_face(pwriter *w, void *ctx, int p)
{
    const shell_items *c = ctx;
    int nv = c->s->nv;
    rg2_xpatch X;
    double h[(RG2_MAX_DEGREE + 1) * (RG2_MAX_DEGREE + 1)][4];
    rg2__patch_affine(c->t, c->s, p / nv, p % nv, &X);
    rg2__xpatch_net(&X, h);
    int edge[4], fwd[4], lq[4], n = 0;
    for (int side = 0; side < 4; side++) {
        int e, f;
        rg2__topo_side(c->t, p / nv, p % nv, side, &e, &f);
        if (e < 0)
            continue;
        edge[n] = e;
        fwd[n] = f;
        lq[n++] = c->line[side];
    }
    put_face_entities(w, c->q_patch + 3 * p, (const double(*)[4])h, X.du + 1, X.dv + 1, X.du, X.dv, 0, 0, c->q_el,
                      edge, fwd, lq, n);
}

/* The B-rep entities of one surface, face per patch, from entity index *q on:
 *   514 shell, 502 vertex list, 504 edge list, 126 per edge, then per patch 128, 508, 510.
 * Edges and vertices come from rg2__topo as in the STEP writer (one per geometric edge /
 * corner, shared by the faces on both sides; collapsed sides left out of their loops). The
 * loops run counter-clockwise in (u, v); each edge use carries its pcurve, line[side] (the
 * file's four 110 lines along the sides of [0, 1]^2 in the loop's direction). */
static rg2_status brep_shell(pwriter *w, const rg2_surface *s, const int line[4], int *q,
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
    put_514(w, q_shell, face_q, np, closed);
    for (int v = 0; v < t.n_vertices; v++)
        rg2__corner_affine(&t, s, t.vcorner[v] / (nv + 1), t.vcorner[v] % (nv + 1), vh[v]);
    put_502(w, q_vl, (const double(*)[4])vh, t.n_vertices);
    for (int e = 0; e < t.n_edges; e++) { /* the same corners as the STEP writer's */
        int p = t.edef[2 * e], side = t.edef[2 * e + 1], i = p / nv, j = p % nv;
        int I0 = side == 1 ? i + 1 : i, J0 = side == 2 ? j + 1 : j;
        int I1 = (side == 0 || side == 2) ? i + 1 : I0, J1 = (side == 1 || side == 3) ? j + 1 : J0;
        ends[e][0] = t.vert[I0 * (nv + 1) + J0];
        ends[e][1] = t.vert[I1 * (nv + 1) + J1];
    }
    put_504(w, q_el, q_vl, q_curve, (const int(*)[2])ends, t.n_edges);
    shell_items c = {s, &t, line, q_curve, q_el, q_patch};
    emit_items(w, t.n_edges, q_patch, shell_edge, &c);
    emit_items(w, np, q_patch + 3 * np, shell_face, &c);
    *q = q_patch + 3 * np;
done:
    free(face_q);
    free(vh);
    free(ends);
    rg2__topo_free(&t);
    return st;
}

/* The pcurves of a face on [0, U1] x [0, V1]: 110 lines along the sides of the mask `sides`
 * (bit k: side k), counter-clockwise (v=0 in +u, u=U1 in +v, v=V1 in -u, u=0 in -v), as
 * entities q, q + 1, ... in side order. */
static void brep_lines(pwriter *w, int q, double U1, double V1, unsigned sides)
{
    const double ends[4][4] = {{0, 0, U1, 0}, {U1, 0, U1, V1}, {U1, V1, 0, V1}, {0, V1, 0, 0}};
    for (int k = 0; k < 4; k++) {
        if (!(sides >> k & 1u))
            continue;
        int start = begin_entity(w, q);
        pw_int(w, 110);
        pw_real(w, ends[k][0], ',');
        pw_real(w, ends[k][1], ',');
        pw_real(w, 0.0, ',');
        pw_real(w, ends[k][2], ',');
        pw_real(w, ends[k][3], ',');
        pw_real(w, 0.0, ';');
        end_entity(w, start, 110, 0, "00010000", "RG2PCURV", q);
        q++;
    }
}

/* The sides of a face per mesh that its loop uses (bit k: side k): those with an edge, not the
 * collapsed ones of poles (a line no loop used was read as a curve of its own, outside the
 * shell: two stray lines reaching (8, 11) in the capped sphere of 5.4 of Fig. 9). */
static unsigned mesh_loop_sides(const rg2__mesh_topo *t)
{
    unsigned m = 0;
    for (int sd = 0; sd < 4; sd++)
        if (t->edge[sd] >= 0)
            m |= 1u << sd;
    return m;
}

static int bit_count(unsigned m)
{
    return (int)(m & 1u) + (int)(m >> 1 & 1u) + (int)(m >> 2 & 1u) + (int)(m >> 3 & 1u);
}

/* The B-rep entities of one surface as one face on its merged net (face per mesh), from entity
 * index *q on: 514 shell, 502 vertex list, 504 edge list, 126 per edge, the face's 110 lines on
 * [0, nu] x [0, nv] (one per side its loop uses), 128, 508, 510; the topology of rg2__mesh_topo
 * (the STEP writer's): a closed direction's seam edge is used twice by the loop, once with each
 * of its lines. */
static rg2_status brep_mesh_shell(pwriter *w, const rg2_surface *s, int *q, rg2_error *err)
{
    rg2__mesh_topo t;
    rg2_status st = rg2__mesh_topo_build(s, &t, err);
    if (st)
        return st;
    int q_shell = *q, q_vl = q_shell + 1, q_el = q_shell + 2, q_curve = q_shell + 3;
    unsigned sides = mesh_loop_sides(&t);
    int q_line = q_curve + t.n_edges, q_face = q_line + bit_count(sides);
    int face_q = q_face + 2;
    put_514(w, q_shell, &face_q, 1, t.closed);
    double vh[4][4];
    for (int v = 0; v < t.n_vertices; v++) {
        int c = t.vcorner[v];
        memcpy(vh[v], t.h[(size_t)(c == 1 || c == 2 ? t.NU - 1 : 0) * (size_t)t.NV + (size_t)(c >= 2 ? t.NV - 1 : 0)],
               sizeof(double[4]));
    }
    put_502(w, q_vl, (const double(*)[4])vh, t.n_vertices);
    int ends[4][2];
    for (int e = 0; e < t.n_edges; e++) {
        ends[e][0] = t.vert[rg2__side_ends[t.eside[e]][0]];
        ends[e][1] = t.vert[rg2__side_ends[t.eside[e]][1]];
    }
    put_504(w, q_el, q_vl, q_curve, (const int(*)[2])ends, t.n_edges);
    for (int e = 0; e < t.n_edges; e++) {
        int sd = t.eside[e], n = rg2__net_side(&t, sd);
        put_126_entity(w, q_curve + e, (const double(*)[4])t.side, n, (sd & 1) ? t.dv : t.du);
    }
    brep_lines(w, q_line, (double)s->nu, (double)s->nv, sides);
    int edge[4], fwd[4], lq[4], n = 0;
    for (int sd = 0; sd < 4; sd++) {
        if (!(sides >> sd & 1u))
            continue;
        edge[n] = t.edge[sd];
        fwd[n] = sd < 2;
        lq[n] = q_line + n;
        n++;
    }
    put_face_entities(w, q_face, (const double(*)[4])t.h, t.NU, t.NV, t.du, t.dv, s->closed_u, s->closed_v, q_el,
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

/* Plain layout, face per patch: patch k of surface s (topology t: its poles) as entity q0 + k. */
typedef struct {
    const rg2_surface *s;
    const rg2__topo *t;
    int q0;
} patch_items;

static void plain_patch(pwriter *w, void *ctx, int p)
{
    const patch_items *c = ctx;
    int nv = c->s->nv, q = c->q0 + p;
    rg2_xpatch X;
    double h[(RG2_MAX_DEGREE + 1) * (RG2_MAX_DEGREE + 1)][4];
    rg2__patch_affine(c->t, c->s, p / nv, p % nv, &X);
    rg2__xpatch_net(&X, h);
    int start = begin_entity(w, q);
    put_128(w, (const double(*)[4])h, X.du + 1, X.dv + 1, X.du, X.dv, 0, 0);
    end_entity(w, start, 128, 0, "00000000", "RG2SURF", q);
}

/* The directory section: entities k0..k1-1 of dir, two records each (numbered 2 q + 1, 2 q + 2). */
static int dir_block(FILE *m, void *ctx, int b, int k0, int k1)
{
    (void)b;
    const idir *d = ctx;
    char rec[96];
    for (int q = k0; q < k1; q++) {
        snprintf(rec, sizeof rec, "%8d%8d%8d%8d%8d%8d%8d%8d%8sD%7d\n", d[q].type, d[q].pstart, 0, 0, 0, 0, 0, 0,
                 d[q].status, 2 * q + 1);
        fwrite(rec, 1, 81, m);
        snprintf(rec, sizeof rec, "%8d%8d%8d%8d%8d%8s%8s%8s%8dD%7d\n", d[q].type, 0, 0, d[q].pcount, d[q].form, "",
                 "", d[q].label, q, 2 * q + 2);
        fwrite(rec, 1, 81, m);
    }
    return 0; /* (write errors: the file's, at its close; a memory stream's, at its flush) */
}

/* The entities surface s takes in the file (*count): one per patch (plain, face per patch), one
 * (plain, face per mesh), or its shell's (B-rep; the topology built here and again when written:
 * 514, 502, 504, a 126 per edge, then 128, 508, 510 per patch, or the face's 110 per side its
 * loop uses and one 128, 508, 510). */
static rg2_status surface_entities(const rg2_surface *s, int brep, int per_mesh, int *count, rg2_error *err)
{
    int np = s->nu * s->nv;
    rg2_status st = RG2_OK;
    if (!brep) {
        *count = per_mesh ? 1 : np;
    } else if (per_mesh) {
        rg2__mesh_topo t;
        if (!(st = rg2__mesh_topo_build(s, &t, err)))
            *count = 3 + t.n_edges + bit_count(mesh_loop_sides(&t)) + 3;
        rg2__mesh_topo_free(&t);
    } else {
        rg2__topo t;
        if (!(st = rg2__topo_build(s, &t, err)))
            *count = 3 + t.n_edges + 3 * np;
        rg2__topo_free(&t);
    }
    return st;
}

/* A seek that failed: in flushing what was written (a full disk), or itself. */
static rg2_status seek_failed(const rg2__out *out, rg2_error *err)
{
    int e = errno;
    if (ferror(out->f))
        return rg2__fail(err, RG2_EIO, "%s: write failed: %s", out->path, strerror(e));
    return rg2__fail(err, RG2_EIO, "%s: cannot seek in %s: %s", out->path, out->tmp ? out->tmp : "its temporary file",
                     strerror(e));
}

/*
 * METHOD: the directory section comes before the parameter section but is known only with it.
 * The entities are counted first, so the directory's size (two records each) is known: the
 * start and global sections are written, the directory's place is skipped, the parameter
 * records are written as they are formatted (no copy of the file in memory), then the
 * terminate section, and last the directory in its place.
 */
rg2_status rg2__write_iges(const rg2_surface *surfs, int n, const rg2_export_opts *o, rg2__out *out,
                           rg2_error *err)
{
    ibuf P = {0}, G = {0};
    idirs D = {0};
    pwriter w = {&P, {0}, 0, 0, &D, INT_MAX, -1, out->f};
    double maxc = 0.0;
    int entity = 0, total = 0, line[4] = {0, 1, 2, 3};
    rg2_status st = RG2_OK;
    int per_mesh = o->layout == RG2_STEP_FACE_PER_MESH;
    if (o->iges_brep && !per_mesh)
        total = 4;
    for (int k = 0; k < n; k++) {
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
        int c = 0;
        if ((st = surface_entities(s, o->iges_brep, per_mesh, &c, err)))
            return st;
        /* each record carries its sequence number in 7 columns (and directory entries point to
         * each other by them): past 9,999,999 records in a section the file cannot be written */
        if (c > rg2__iges_max_records / 2 - total)
            return rg2__fail(err, RG2_ELIMIT,
                             "IGES: at least %lld directory records, more than the %d that IGES's 7-digit "
                             "sequence numbers allow (size limit exceeded); write STEP, or fewer patches",
                             2 * ((long long)total + c), rg2__iges_max_records);
        total += c;
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
    if (G.failed || !dir_reserve(&D, total)) {
        st = rg2__fail(err, RG2_ENOMEM, "IGES: out of memory");
        goto done;
    }
    put_section_line(out->f,
                     o->iges_brep ? "rg2: rational bi-cubic G2 spline surfaces, IGES 5.3 B-rep shells (514)"
                                  : "rg2: rational bi-cubic G2 spline surfaces, IGES 5.3 entity 128",
                     'S', 1);
    fwrite(G.s, 1, G.len, out->f);
    long d_at = ftell(out->f); /* (IGES's limits keep the file under 2 GB) */
    if (d_at < 0 || fseek(out->f, d_at + 162L * total, SEEK_SET)) {
        st = seek_failed(out, err);
        goto done;
    }
    if (o->iges_brep && !per_mesh) { /* every patch face shares the lines of [0, 1]^2 */
        brep_lines(&w, 0, 1.0, 1.0, 15u);
        entity = 4;
    }
    for (int k = 0; k < n && !P.failed; k++) {
        const rg2_surface *s = &surfs[k];
        if (o->iges_brep) {
            st = per_mesh ? brep_mesh_shell(&w, s, &entity, err) : brep_shell(&w, s, line, &entity, err);
            if (st)
                goto done;
        } else if (per_mesh) {
            int NU, NV, du, dv;
            double(*h)[4] = rg2__merged_net(s, &NU, &NV, &du, &dv);
            if (!h) {
                P.failed = 1;
                break;
            }
            if ((st = rg2__net_affine(s, h, NU, NV, du, dv, err))) {
                free(h);
                goto done;
            }
            int start = begin_entity(&w, entity);
            put_128(&w, (const double(*)[4])h, NU, NV, du, dv, s->closed_u, s->closed_v);
            end_entity(&w, start, 128, 0, "00000000", "RG2SURF", entity);
            entity++;
            free(h);
        } else {
            rg2__topo t;
            if ((st = rg2__topo_build(s, &t, err)))
                goto done;
            patch_items c = {s, &t, entity};
            emit_items(&w, s->nu * s->nv, entity + s->nu * s->nv, plain_patch, &c);
            rg2__topo_free(&t);
            entity += s->nu * s->nv;
        }
    }
    pw_drain(&w);
    if (P.failed) {
        st = P.failed == 2 ? rg2__fail(err, RG2_EINVAL, "IGES: internal error: a block's records out of step")
                           : rg2__fail(err, RG2_ENOMEM, "IGES: out of memory");
        goto done;
    }
    if (entity != total) { /* (a bug: the directory's place would not fit) */
        st = rg2__fail(err, RG2_EINVAL, "IGES: internal error: %d entities written, %d counted", entity, total);
        goto done;
    }
    if (P.nlines > rg2__iges_max_records) {
        st = rg2__fail(err, RG2_ELIMIT,
                       "IGES: %d directory and %d parameter records, more than the %d that IGES's 7-digit "
                       "sequence numbers allow (size limit exceeded); write STEP, or fewer patches",
                       2 * entity, P.nlines, rg2__iges_max_records);
        goto done;
    }
    char tl[80];
    snprintf(tl, sizeof tl, "S%7dG%7dD%7dP%7d", 1, G.nlines, 2 * entity, P.nlines);
    put_section_line(out->f, tl, 'T', 1);
    if (fseek(out->f, d_at, SEEK_SET)) {
        st = seek_failed(out, err);
        goto done;
    }
    if (rg2__write_blocks(out->f, entity, 4096, dir_block, NULL, D.d))
        st = rg2__fail(err, RG2_ENOMEM, "IGES: out of memory");
done:
    free(D.d);
    free(P.s);
    free(G.s);
    return st;
}
