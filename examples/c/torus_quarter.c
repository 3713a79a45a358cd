/* examples/c/torus_quarter.c -- embedding rg2: build a quarter torus from its exact control
 * mesh, check it against the torus equation, and export it as STEP.
 *
 *   cmake --install build --prefix /usr/local        (or any prefix; add it to PKG_CONFIG_PATH)
 *   cc torus_quarter.c $(pkg-config --cflags --libs --static rg2) -o torus_quarter
 *   ./torus_quarter out.step
 * (librg2 is a static library: --static adds cJSON, libpng, OpenMP and threads; tests/embed.sh)
 */
#include <rg2.h>

#include <math.h>
#include <stdio.h>

int main(int argc, char **argv)
{
    const char *path = argc > 1 ? argv[1] : "torus_quarter.step";
    rg2_error err;

    /* A torus R = 3, r = 1: a quarter in u (3 arcs of 30 degrees), the full tube in v (6 arcs). */
    rg2_shape torus;
    rg2_shape_init(&torus, RG2_SHAPE_TORUS);
    torus.param[0] = 3.0;
    torus.param[1] = 1.0;
    double au[3] = {RG2_PI / 6, RG2_PI / 6, RG2_PI / 6}, av[6];
    for (int j = 0; j < 6; j++)
        av[j] = RG2_PI / 3;
    rg2_partition pu = {RG2_PART_ANGLES, 0, 3, au, 0.0};
    rg2_partition pv = {RG2_PART_ANGLES, 1, 6, av, 0.0};

    rg2_surface s;
    rg2_weight_report w;
    if (rg2_shape_surface(&torus, &pu, &pv, &s, &w, &err)) {
        fprintf(stderr, "build failed: %s: %s\n", rg2_status_str(err.code), err.msg);
        return 1;
    }

    /* Every point lies on the torus: residual of the implicit equation over |gradient|. */
    double worst = 0.0;
    for (int i = 0; i < s.nu; i++)
        for (int j = 0; j < s.nv; j++)
            for (int a = 0; a <= 8; a++)
                for (int b = 0; b <= 8; b++) {
                    rg2_eval e;
                    double g[3];
                    rg2_surface_eval(&s, i, j, a / 8.0, b / 8.0, 2, &e);
                    double f = rg2_shape_implicit(&torus, e.p, g);
                    double d = fabs(f) / sqrt(g[0] * g[0] + g[1] * g[1] + g[2] * g[2]);
                    if (d > worst)
                        worst = d;
                }
    printf("%d x %d patches, min weight %.4f, max distance from the torus %.2e\n", s.nu, s.nv,
           w.min_weight, worst);

    rg2_export_opts opts;
    rg2_export_opts_default(&opts);
    opts.name = "quarter torus";
    rg2_status st = rg2_export_file(&s, 1, path, &opts, &err);
    if (st)
        fprintf(stderr, "export failed: %s\n", err.msg);
    else
        printf("wrote %s\n", path);
    rg2_surface_free(&s);
    return st || worst > 1e-12 ? 1 : 0;
}
