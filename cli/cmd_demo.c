/* rg2 demo -- a circle's exact Bezier form and a torus built by the Bi-cubic Construction. */
#include "cli.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

int rg2_cmd_demo(int argc, char **argv)
{
    if (argc > 1 && (!strcmp(argv[1], "--help") || !strcmp(argv[1], "-h"))) {
        printf("usage: rg2 demo\n\nPrints the exact Bezier form of a unit circle in 4 arcs and builds a torus\n"
               "(R = 3, r = 1; 8 x 6 arcs) from its control mesh, reporting the patches and the\n"
               "largest deviation from the torus over 33 x 33 samples per patch (a 32 x 32 grid, ends\n"
               "included).\n");
        return 0;
    }
    if (argc > 1) {
        fprintf(stderr, "rg2 demo: %s '%s' (rg2 demo takes no arguments; see rg2 demo --help)\n",
                argv[1][0] == '-' ? "unknown option" : "unexpected argument", argv[1]);
        return RG2_EXIT_USAGE;
    }
    rg2_error err = {0};
    double a4[4] = {M_PI / 2, M_PI / 2, M_PI / 2, M_PI / 2}, cs4[8];
    rg2_scalars s = {0};
    rg2_curve c = {0};
    if (rg2_scalars_from_angles(&s, a4, 4, 1, &err) || rg2_circle_coeffs(a4, 4, 1, 0.0, cs4, &err) ||
        rg2_curve_build(2, cs4, &s, &c, &err))
        return rg2_cli_report("demo", &err);
    printf("Unit circle, 4 arcs of 90 degrees: control points and Bezier segments\n");
    for (int i = 0; i < 4; i++)
        printf("  p%d = (%.17g, %.17g)\n", i, cs4[2 * i], cs4[2 * i + 1]);
    for (int k = 0; k < c.n_segments; k++) {
        printf("  segment %d (weights 1, %.17g, %.17g, 1):", k, c.w[k], c.w[k]);
        for (int r = 0; r < 4; r++)
            printf(" (%.6f, %.6f)", c.bez[(k * 4 + r) * 2], c.bez[(k * 4 + r) * 2 + 1]);
        printf("\n");
    }
    rg2_curve_free(&c);
    rg2_scalars_free(&s);

    /* Torus (R + r cos v) (cos u, sin u), r sin v from its exact control mesh. */
    const double R = 3.0, r = 1.0;
    int nu = 8, nv = 6;
    double au[8], av[6];
    for (int i = 0; i < nu; i++)
        au[i] = 2 * M_PI / nu;
    for (int j = 0; j < nv; j++)
        av[j] = 2 * M_PI / nv;
    rg2_shape torus;
    rg2_shape_init(&torus, RG2_SHAPE_TORUS);
    torus.param[0] = R;
    torus.param[1] = r;
    rg2_partition pu = {RG2_PART_ANGLES, 1, nu, au, 0.0}, pv = {RG2_PART_ANGLES, 1, nv, av, 0.0};
    rg2_surface surf = {0};
    int rc = 0;
    if (rg2_shape_surface(&torus, &pu, &pv, &surf, NULL, &err)) {
        rc = rg2_cli_report("demo", &err);
        goto out;
    }
    double worst = 0.0;
    for (int i = 0; i < surf.nu; i++)
        for (int j = 0; j < surf.nv; j++)
            for (int a = 0; a <= 32; a++)
                for (int b = 0; b <= 32; b++) {
                    rg2_eval e;
                    rg2_surface_eval(&surf, i, j, a / 32.0, b / 32.0, 0, &e);
                    double q = hypot(e.p[0], e.p[1]) - R;
                    double d = fabs(hypot(q, e.p[2]) - r);
                    if (d > worst)
                        worst = d;
                }
    printf("\nTorus R = %g, r = %g from a %d x %d closed control mesh:\n", R, r, nu, nv);
    printf("  %d x %d rational bi-cubic patches, min homogeneous weight %.6f\n", surf.nu, surf.nv,
           rg2_surface_min_weight(&surf));
    printf("  largest distance from the torus over 33 x 33 samples per patch: %.3g\n", worst);
out:
    rg2_surface_free(&surf);
    return rc;
}
