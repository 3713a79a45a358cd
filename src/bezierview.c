/* bezierview.c -- rational bi-cubic Bezier patches for BezierView (.bv, patch type 8) and
 * geomview (.bez, BEZ334). Both store homogeneous control points (w x, w y, w z, w) with
 * 17 significant digits, so the patches round-trip exactly. */
#include "export_internal.h"

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
            fprintf(out->f, "8\n3 3\n");
            for (int r = 0; r < 4; r++)
                for (int t = 0; t < 4; t++) {
                    const double *h = s->patch[p].h[r][t];
                    fprintf(out->f, "%.17g %.17g %.17g %.17g\n", h[0], h[1], h[2], h[3]);
                }
        }
    }
    return RG2_OK;
}

/*
 * geomview BEZ334: header "BEZ334" (degree 3 x 3, 4-d homogeneous vertices), then per patch
 * 16 vertices with u fastest: vertex(u=0,v=0) vertex(1,0) ... vertex(3,0) vertex(0,1) ...
 */
rg2_status rg2__write_bez(const rg2_surface *surfs, int n, rg2__out *out, rg2_error *err)
{
    (void)err;
    fprintf(out->f, "BEZ334\n");
    for (int k = 0; k < n; k++) {
        const rg2_surface *s = &surfs[k];
        for (int p = 0; p < s->nu * s->nv; p++) {
            for (int t = 0; t < 4; t++)
                for (int r = 0; r < 4; r++) {
                    const double *h = s->patch[p].h[r][t];
                    fprintf(out->f, "%.17g %.17g %.17g %.17g\n", h[0], h[1], h[2], h[3]);
                }
            fputc('\n', out->f);
        }
    }
    return RG2_OK;
}
