/* iges.c -- IGES 5.3 of rational patch surfaces: one untrimmed rational B-spline surface
 * (entity 128, form 0) per patch, of that patch's degrees, or per surface (merged net of all
 * patches elevated to the surface's degrees (du, dv), interior knots of multiplicity du, dv),
 * fixed 80-column records, global section in mm with resolution 1e-6
 * (shared/spec/INTEROP.md section 3). */
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

static void put_de(ibuf *D, int type, int pstart, int pcount, int index)
{
    char rec[96];
    snprintf(rec, sizeof rec, "%8d%8d%8d%8d%8d%8d%8d%8d%8sD%7d", type, pstart, 0, 0, 0, 0, 0, 0, "00000000",
             D->nlines + 1);
    ib_put(D, rec);
    snprintf(rec, sizeof rec, "%8d%8d%8d%8d%8d%8s%8s%8s%8dD%7d", type, 0, 0, pcount, 0, "", "", "RG2SURF",
             index, D->nlines + 1);
    ib_put(D, rec);
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

rg2_status rg2__write_iges(const rg2_surface *surfs, int n, const rg2_export_opts *o, rg2__out *out,
                           rg2_error *err)
{
    ibuf D = {0}, P = {0}, G = {0};
    pwriter w = {&P, {0}, 0, 0};
    double maxc = 0.0;
    int entity = 0;
    rg2_status st = RG2_OK;
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
        if (o->layout == RG2_STEP_FACE_PER_MESH) {
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
    put_section_line(out->f, "rg2: rational bi-cubic G2 spline surfaces, IGES 5.3 entity 128", 'S', 1);
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
