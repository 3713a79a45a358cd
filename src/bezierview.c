/* bezierview.c -- rational Bezier patches for BezierView (.bv, patch type 8) and geomview
 * (.bez, BEZuv4). Both store homogeneous control points (w x, w y, w z, w) with 17
 * significant digits, so the patches round-trip exactly. BezierView gives every patch its own
 * degrees, so each patch keeps its own; a geomview file has one header, so every patch is
 * degree-elevated (exactly) to the highest degrees over all surfaces (BEZ334 when all
 * patches are bi-3). */
#include "export_internal.h"

static void put_h(FILE *f, const double h[4])
{
    fprintf(f, "%.17g %.17g %.17g %.17g\n", h[0], h[1], h[2], h[3]);
}

/*
 * BezierView: a sequence of patches, each "8" (rational tensor-product), "deg_u deg_v", then
 * (deg_u + 1) rows of (deg_v + 1) points, row i = u index, each point "wx wy wz w".
 * A "Group k name" line before a surface's first patch groups the patches of one surface.
 */
rg2_status rg2__write_bv(const rg2_surface *surfs, int n, rg2__out *out, rg2_error *err)
{
    (void)err;
    for (int k = 0; k < n; k++) {
        const rg2_surface *s = &surfs[k];
        fprintf(out->f, "Group %d surface_%d\n", k, k);
        for (int p = 0; p < s->nu * s->nv; p++) {
            rg2_xpatch X;
            rg2_surface_patch_get(s, p / s->nv, p % s->nv, &X);
            fprintf(out->f, "8\n%d %d\n", X.du, X.dv);
            for (int r = 0; r <= X.du; r++)
                for (int t = 0; t <= X.dv; t++)
                    put_h(out->f, X.h[r][t]);
        }
    }
    return RG2_OK;
}

/*
 * geomview BEZuv4 (u, v the degrees, single digits 1..6; 4-d homogeneous vertices): one
 * header, then per patch (u + 1)(v + 1) vertices with u fastest: vertex(u=0,v=0)
 * vertex(1,0) ... vertex(u,0) vertex(0,1) ... All patches of all surfaces are elevated to
 * the largest degrees (Du, Dv) among them.
 */
rg2_status rg2__write_bez(const rg2_surface *surfs, int n, rg2__out *out, rg2_error *err)
{
    int Du = 3, Dv = 3;
    for (int k = 0; k < n; k++) {
        int a, b;
        rg2_surface_degree(&surfs[k], &a, &b);
        Du = a > Du ? a : Du;
        Dv = b > Dv ? b : Dv;
    }
    fprintf(out->f, "BEZ%d%d4\n", Du, Dv);
    for (int k = 0; k < n; k++) {
        const rg2_surface *s = &surfs[k];
        for (int p = 0; p < s->nu * s->nv; p++) {
            rg2_xpatch X, E;
            rg2_surface_patch_get(s, p / s->nv, p % s->nv, &X);
            rg2_status st = rg2_xpatch_elevate(&X, Du, Dv, &E, err);
            if (st)
                return st;
            for (int t = 0; t <= Dv; t++)
                for (int r = 0; r <= Du; r++)
                    put_h(out->f, E.h[r][t]);
            fputc('\n', out->f);
        }
    }
    return RG2_OK;
}
