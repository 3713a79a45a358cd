/* examples/c/design_from_c.c -- a design file read from C: the capped sphere of
 * examples/fig9_polar_sphere.json, parsed from a string (rg2_design_load reads a file the same
 * way). Walks the design's surfaces and shapes, checks G2 and exactness with the design's tags
 * (rg2_check), counts the patches on the sphere whatever their tags
 * (rg2_surface_shape_residuals, as `rg2 check --on ball`), takes the normal at the south pole,
 * where Su x Sv vanishes (rg2_surface_eval_limit), and exports the surface as STEP.
 *
 *   cc design_from_c.c $(pkg-config --cflags --libs --static rg2) -o design_from_c
 *   ./design_from_c out.step
 */
#include <rg2.h>

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

static const char design[] =
    "{\"format\": \"rg2 design 1\",\n"
    " \"shapes\": {\"ball\": {\"kind\": \"sphere\", \"radius\": 1}},\n"
    " \"meshes\": {\n"
    "   \"band\": {\"polar\": \"ball\", \"u\": {\"arcs\": 8}, \"v\": {\"knots\": [0.15, 0.3, 0.42, 0.58, 0.7, 0.85]}},\n"
    "   \"sphere\": {\"cap\": \"band\"}},\n"
    " \"output\": [\"sphere\"]}\n";

static int fail(const char *what, const rg2_error *err)
{
    fprintf(stderr, "%s: %s: %s\n", what, rg2_status_str(err->code), err->msg);
    return 1;
}

int main(int argc, char **argv)
{
    const char *path = argc > 1 ? argv[1] : "design_from_c.step";
    rg2_design *d = NULL;
    rg2_error err;
    if (rg2_design_parse(design, strlen(design), "capped sphere", &d, &err))
        return fail("design", &err);
    int n = rg2_design_num_surfaces(d), ns = rg2_design_num_shapes(d), rc = 1;
    /* rg2_check takes arrays: the design's surfaces, shapes and their names */
    rg2_surface *surfs = calloc((size_t)n, sizeof *surfs);
    rg2_shape *shapes = calloc((size_t)ns, sizeof *shapes);
    const char **labels = calloc((size_t)ns, sizeof *labels);
    double *res = NULL;
    if (!surfs || !shapes || !labels) {
        fprintf(stderr, "out of memory\n");
        goto out;
    }
    for (int k = 0; k < n; k++) {
        surfs[k] = *rg2_design_surface(d, k); /* (shallow copies: the design owns the arrays) */
        printf("surface %d (mesh '%s'): %d x %d patches\n", k, rg2_design_mesh_name(d, k), surfs[k].nu, surfs[k].nv);
    }
    for (int k = 0; k < ns; k++) {
        shapes[k] = *rg2_design_shape(d, k);
        labels[k] = rg2_design_shape_label(d, k);
    }
    rg2_check_report rep;
    if (rg2_check(surfs, n, shapes, labels, ns, NULL, &rep, &err)) {
        fail("check", &err);
        goto out;
    }
    printf("check: %d of %d patches exact (worst residual %.2e), G1 %.2e rad, G2 %.2e\n", rep.exact_patches,
           rep.patches, rep.worst_residual, rep.g1.value, rep.g2.value);
    rc = rg2_check_failures(&rep, RG2_REQUIRE_G2 | RG2_REQUIRE_EXACT | RG2_REQUIRE_WEIGHTS) != 0;
    rg2_check_report_free(&rep);

    /* every patch against the sphere, tagged or not */
    const rg2_surface *s = &surfs[0];
    res = malloc((size_t)s->nu * (size_t)s->nv * sizeof *res);
    if (!res) {
        fprintf(stderr, "out of memory\n");
        rc = 1;
        goto out;
    }
    if (rg2_surface_shape_residuals(s, &shapes[0], 12, res, &err)) {
        rc = fail("residuals", &err);
        goto out;
    }
    int on = 0;
    for (int k = 0; k < s->nu * s->nv; k++)
        on += res[k] <= 1e-11;
    printf("on '%s': %d of %d patches\n", labels[0], on, s->nu * s->nv);
    rc |= on != s->nu * s->nv;

    /* the south pole is side v = 0 of the patches (i, 0): Su x Sv vanishes there */
    rg2_eval e, l;
    rg2_surface_eval(s, 0, 0, 0.5, 0.0, 2, &e);
    rg2_surface_eval_limit(s, 0, 0, 0.5, 0.0, 2, &l);
    double r = sqrt(l.p[0] * l.p[0] + l.p[1] * l.p[1] + l.p[2] * l.p[2]);
    double along = (l.n[0] * l.p[0] + l.n[1] * l.p[1] + l.n[2] * l.p[2]) / r;
    printf("south pole (%.3g, %.3g, %.3g): rg2_surface_eval normal %s; limit normal (%.3g, %.3g, %.3g), "
           "n . p / |p| = %.17g, K = %.6f\n",
           l.p[0], l.p[1], l.p[2], e.flags & RG2_EVAL_NORMAL_UNDEFINED ? "undefined" : "defined", l.n[0], l.n[1],
           l.n[2], along, l.K);
    rc |= !(e.flags & RG2_EVAL_NORMAL_UNDEFINED) || !(l.flags & RG2_EVAL_POLE_LIMIT) || fabs(fabs(along) - 1) > 1e-12 ||
          fabs(l.K - 1) > 1e-3;

    if (rg2_export_file(s, 1, path, NULL, &err))
        rc = fail("export", &err);
    else
        printf("wrote %s\n", path);
out:
    free(res);
    free(surfs);
    free(shapes);
    free(labels);
    rg2_design_free(d);
    return rc;
}
