/* examples/c/ring_and_ball.c -- the design of examples/torus_sphere.json (the paper's Fig. 8)
 * built in C: a torus ring cut open, a sphere band put into the gap with rg2_mesh_merge, no new
 * control points. Prints how many patches lie on each shape and the worst G2 gaps, and exports
 * the one surface as STEP.
 *
 *   cc ring_and_ball.c $(pkg-config --cflags --libs --static rg2) -o ring_and_ball
 *   ./ring_and_ball out.step
 */
#include <rg2.h>

#include <math.h>
#include <stdio.h>

static int fail(const char *what, const rg2_error *err)
{
    fprintf(stderr, "%s: %s: %s\n", what, rg2_status_str(err->code), err->msg);
    return 1;
}

/* Patches of s whose 9 x 9 samples lie on the shape within 1e-14 of the model's size. */
static int patches_on(const rg2_surface *s, const rg2_shape *shape, double size)
{
    int count = 0;
    for (int i = 0; i < s->nu; i++)
        for (int j = 0; j < s->nv; j++) {
            int on = 1;
            for (int a = 0; a <= 8 && on; a++)
                for (int b = 0; b <= 8 && on; b++) {
                    rg2_eval e;
                    double g[3];
                    rg2_surface_eval(s, i, j, a / 8.0, b / 8.0, 0, &e);
                    double f = rg2_shape_implicit(shape, e.p, g);
                    on = fabs(f) <= 1e-14 * size * sqrt(g[0] * g[0] + g[1] * g[1] + g[2] * g[2]);
                }
            count += on;
        }
    return count;
}

int main(int argc, char **argv)
{
    const char *path = argc > 1 ? argv[1] : "ring_and_ball.step";
    const double deg = RG2_PI / 180.0;
    rg2_error err;

    /* The ring: torus R = 3, r = 0.6; u: 8 arcs of 30 degrees then 7 of 120/7, v: 8 of 45. */
    rg2_shape ring;
    rg2_shape_init(&ring, RG2_SHAPE_TORUS);
    ring.param[0] = 3.0;
    ring.param[1] = 0.6;
    double au[15], av[8];
    double sum = 0.0;
    for (int k = 0; k < 14; k++)
        sum += au[k] = (k < 8 ? 30.0 : 120.0 / 7.0) * deg;
    au[14] = 2.0 * RG2_PI - sum; /* the arcs sum to 2 pi */
    for (int k = 0; k < 8; k++)
        av[k] = 45.0 * deg;
    rg2_partition pu = {RG2_PART_ANGLES, 1, 15, au, 0.0}, pv = {RG2_PART_ANGLES, 1, 8, av, 0.0};
    rg2_mesh ring_mesh, tube;
    if (rg2_shape_mesh(&ring, &pu, &pv, &ring_mesh, &err))
        return fail("ring", &err);
    /* Keep u points 0..8: open, its patch columns are arcs 1 to 6 of the ring. */
    const int first[2] = {0, -1}, last[2] = {8, 0};
    if (rg2_mesh_cut(&ring_mesh, first, last, &tube, &err))
        return fail("cut", &err);

    /* The ball: a sphere of radius 1.3 centred on the ring's centre circle at 300 degrees,
     * placed so that its circle direction runs across the ring (a reflection: its v runs with
     * the ring's u); v is the band between heights 0.35 and 0.65 of the sphere's parameter. */
    rg2_shape ball;
    rg2_shape_init(&ball, RG2_SHAPE_SPHERE);
    ball.param[0] = 1.3;
    const double c = cos(300.0 * deg), s = sin(300.0 * deg);
    const double place[16] = {c, 0, -s, 3.0 * c, s, 0, c, 3.0 * s, 0, 1, 0, 0, 0, 0, 0, 1};
    for (int k = 0; k < 16; k++)
        ball.xform[k] = place[k];
    double bu[8], knots[4] = {0.35, 0.45, 0.55, 0.65};
    for (int k = 0; k < 8; k++)
        bu[k] = 45.0 * deg;
    rg2_partition qu = {RG2_PART_ANGLES, 1, 8, bu, 0.0}, qv = {RG2_PART_KNOTS, 0, 4, knots, 0.0};
    rg2_mesh ball_mesh, band;
    if (rg2_shape_mesh(&ball, &qu, &qv, &ball_mesh, &err))
        return fail("ball", &err);
    if (rg2_mesh_transpose(&ball_mesh, &band, &err)) /* its circle becomes v, as the tube's */
        return fail("transpose", &err);

    /* Side by side along u, closed into a ring: one mesh, one G2 surface. */
    const rg2_mesh *parts[2] = {&tube, &band};
    rg2_mesh joined;
    if (rg2_mesh_merge(parts, 2, 0, 1, RG2_SEAM_PRESERVE, &joined, &err))
        return fail("merge", &err);
    rg2_surface surf;
    if (rg2_surface_build(&joined, &surf, &err))
        return fail("build", &err);

    rg2_check_report rep;
    if (rg2_check(&surf, 1, NULL, NULL, 0, NULL, &rep, &err))
        return fail("check", &err);
    int on_ring = patches_on(&surf, &ring, rep.size), on_ball = patches_on(&surf, &ball, rep.size);
    printf("%d x %d patches: %d on the torus, %d on the sphere, %d transitions\n", surf.nu, surf.nv, on_ring,
           on_ball, surf.nu * surf.nv - on_ring - on_ball);
    printf("%d seams: position %.1e, normal angle %.1e rad, normal curvature %.1e (relative)\n", rep.seams,
           rep.g0.value, rep.g1.value, rep.g2.value);
    unsigned bad = rg2_check_failures(&rep, RG2_REQUIRE_G2 | RG2_REQUIRE_WEIGHTS);
    rg2_check_report_free(&rep);

    rg2_export_opts opts;
    rg2_export_opts_default(&opts);
    opts.name = "ring and ball";
    rg2_status st = rg2_export_file(&surf, 1, path, &opts, &err);
    if (st)
        fail("export", &err);
    else
        printf("wrote %s\n", path);

    rg2_surface_free(&surf);
    rg2_mesh_free(&joined);
    rg2_mesh_free(&band);
    rg2_mesh_free(&ball_mesh);
    rg2_mesh_free(&tube);
    rg2_mesh_free(&ring_mesh);
    /* 6 patch columns of the ring, 3 of the ball, 3 transition columns at each seam; 8 rows */
    return st || bad || on_ring != 48 || on_ball != 24 ? 1 : 0;
}
