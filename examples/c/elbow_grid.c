/* examples/c/elbow_grid.c -- a pipe elbow from C: a quarter of a torus and a straight cylinder
 * put side by side in one control mesh (rg2_mesh_merge), one G2 surface, evaluated on a grid
 * of every patch into the program's own arrays (rg2_surface_grid: positions, normals, K, H),
 * and measured with the program's own formulas: the distance of the torus patches' points from
 * the exact torus, of the cylinder patches' from the exact cylinder, and their curvatures
 * against the closed forms. Exports the surface as STEP.
 *
 *   cc elbow_grid.c $(pkg-config --cflags --libs --static rg2) -o elbow_grid
 *   ./elbow_grid out.step
 */
#include <rg2.h>

#include <math.h>
#include <stdio.h>
#include <stdlib.h>

static int fail(const char *what, const rg2_error *err)
{
    fprintf(stderr, "%s: %s: %s\n", what, rg2_status_str(err->code), err->msg);
    return 1;
}

int main(int argc, char **argv)
{
    const char *path = argc > 1 ? argv[1] : "elbow_grid.step";
    const double R = 3.0, r = 1.0, deg = RG2_PI / 180.0;
    rg2_error err;

    /* The bend: torus R = 3, r = 1; u (round the ring) 6 open arcs of 15 degrees, 0 to 90;
     * v (round the tube) closed, 8 arcs of 45 degrees. */
    rg2_shape torus;
    rg2_shape_init(&torus, RG2_SHAPE_TORUS);
    torus.param[0] = R;
    torus.param[1] = r;
    double au[6], av[8];
    for (int k = 0; k < 6; k++)
        au[k] = 15.0 * deg;
    for (int k = 0; k < 8; k++)
        av[k] = 45.0 * deg;
    rg2_partition pu = {RG2_PART_ANGLES, 0, 6, au, 0.0}, pv = {RG2_PART_ANGLES, 1, 8, av, 0.0};

    /* The straight part: a cylinder of radius r whose circle is the tube's circle at 90 degrees,
     * (cos, sin) -> (y, z) about (0, R, 0), and whose axis z runs along -x, the direction the
     * ring goes on in; heights 2.5 .. 5.5. Its circle has the tube's partition, so the two
     * meshes agree along v and merge along u. The gap between the parts (the torus ends at
     * x = 0) is bridged by the transition patches; started at height 0.8 instead, the parts'
     * data-only end control points overlap and the transitions fold (rg2_check: 8 folds), which
     * rg2_mesh_merge_overlap tells before the merge (below). */
    rg2_shape pipe;
    rg2_shape_init(&pipe, RG2_SHAPE_CYLINDER);
    pipe.param[0] = r;
    const double place[16] = {0, 0, -1, 0, 1, 0, 0, R, 0, 1, 0, 0, 0, 0, 0, 1};
    for (int k = 0; k < 16; k++)
        pipe.xform[k] = place[k];
    double heights[7];
    for (int k = 0; k < 7; k++)
        heights[k] = 2.5 + 0.5 * k;
    rg2_partition qu = {RG2_PART_ANGLES, 1, 8, av, 0.0}, qv = {RG2_PART_KNOTS, 0, 7, heights, 0.0};

    rg2_mesh bend = {0}, straight = {0}, straight_t = {0}, elbow = {0};
    rg2_surface s = {0};
    double *pos = NULL, *nrm = NULL, *K = NULL, *H = NULL;
    int rc = 1;
    if (rg2_shape_mesh(&torus, &pu, &pv, &bend, &err)) {
        fail("torus", &err);
        goto out;
    }
    if (rg2_shape_mesh(&pipe, &qu, &qv, &straight, &err) ||
        rg2_mesh_transpose(&straight, &straight_t, &err)) { /* its circle becomes v, as the bend's */
        fail("cylinder", &err);
        goto out;
    }
    const rg2_mesh *parts[2] = {&bend, &straight_t};
    /* Whether the parts overlap at the seam (a design file's merge note): how far the cylinder's
     * first control line lies behind the bend's last, in line spacings; above RG2_MERGE_OVERLAP
     * the transitions would bend sharply or fold. */
    double back[2];
    if (rg2_mesh_merge_overlap(parts, 2, 0, 0, back, &err)) {
        fail("overlap", &err);
        goto out;
    }
    printf("seam: the cylinder starts %.2f line spacings %s the bend's end\n", fabs(back[1]),
           back[1] > 0 ? "behind" : "beyond");
    if (back[1] > RG2_MERGE_OVERLAP) {
        fprintf(stderr, "the parts overlap: start the cylinder later\n");
        goto out;
    }
    if (rg2_mesh_merge(parts, 2, 0, 0, RG2_SEAM_PRESERVE, &elbow, &err) || rg2_surface_build(&elbow, &s, &err)) {
        fail("merge and build", &err);
        goto out;
    }
    /* Open u: patch column i comes from control points i..i+3, so the bend's nu - 3 columns come
     * first, then 3 transition columns at the seam, then the cylinder's. */
    const int bend_cols = bend.nu - 3, pipe_first = bend_cols + 3;
    printf("%d x %d patches: columns 0..%d on the torus, %d..%d transitions, %d..%d on the cylinder\n", s.nu, s.nv,
           bend_cols - 1, bend_cols, pipe_first - 1, pipe_first, s.nu - 1);

    /* N x N points per patch, patch k = i * nv + j at [k N^2, (k + 1) N^2), point (a, b) at
     * u = a / (N - 1), v = b / (N - 1): index a N + b; vectors are 3 doubles per point. */
    enum { N = 17 };
    size_t np = (size_t)s.nu * (size_t)s.nv * N * N;
    pos = malloc(3 * np * sizeof *pos);
    nrm = malloc(3 * np * sizeof *nrm);
    K = malloc(np * sizeof *K);
    H = malloc(np * sizeof *H);
    if (!pos || !nrm || !K || !H) {
        fprintf(stderr, "out of memory\n");
        goto out;
    }
    rg2_grid_out g = {pos, nrm, NULL, NULL, NULL, NULL, NULL, K, H};
    if (rg2_surface_grid(&s, N, N, 0, &g, &err)) {
        fail("grid", &err);
        goto out;
    }

    double d_torus = 0, n_torus = 0, K_torus = 0, H_torus = 0, d_pipe = 0, n_pipe = 0, K_pipe = 0;
    for (int i = 0; i < s.nu; i++)
        for (int j = 0; j < s.nv; j++)
            for (int a = 0; a < N * N; a++) {
                size_t q = (size_t)(i * s.nv + j) * N * N + (size_t)a;
                const double *p = pos + 3 * q, *n = nrm + 3 * q;
                if (i < bend_cols) {
                    /* the torus: distance | |p - c| - r | from the tube's centre circle point c */
                    double rho = hypot(p[0], p[1]), c[3] = {R * p[0] / rho, R * p[1] / rho, 0.0};
                    double e[3] = {p[0] - c[0], p[1] - c[1], p[2]}, le = sqrt(e[0] * e[0] + e[1] * e[1] + e[2] * e[2]);
                    d_torus = fmax(d_torus, fabs(le - r));
                    /* the normal is +-(p - c) / |p - c|; principal curvatures 1 / r and
                     * cos v / (R + r cos v), cos v = (rho - R) / r */
                    n_torus = fmax(n_torus, 1.0 - fabs(e[0] * n[0] + e[1] * n[1] + e[2] * n[2]) / le);
                    double cv = (rho - R) / r, k1 = 1.0 / r, k2 = cv / (R + r * cv);
                    K_torus = fmax(K_torus, fabs(K[q] - k1 * k2));
                    H_torus = fmax(H_torus, fabs(fabs(H[q]) - 0.5 * (k1 + k2))); /* sign: orientation */
                } else if (i >= pipe_first) {
                    /* the cylinder: axis y = R, z = 0; K = 0, |H| = 1 / (2 r) */
                    double ly = p[1] - R, l = hypot(ly, p[2]);
                    d_pipe = fmax(d_pipe, fabs(l - r));
                    n_pipe = fmax(n_pipe, 1.0 - fabs(ly * n[1] + p[2] * n[2]) / l);
                    K_pipe = fmax(K_pipe, fmax(fabs(K[q]), fabs(fabs(H[q]) - 0.5 / r)));
                }
            }
    printf("torus columns, %d points each: distance from the exact torus %.1e, normal 1 - |cos| %.1e, "
           "K %.1e, |H| %.1e off\n", N * N, d_torus, n_torus, K_torus, H_torus);
    printf("cylinder columns: distance from the exact cylinder %.1e, normal 1 - |cos| %.1e, K and |H| %.1e off\n",
           d_pipe, n_pipe, K_pipe);

    rg2_check_report rep;
    if (rg2_check(&s, 1, NULL, NULL, 0, NULL, &rep, &err)) {
        fail("check", &err);
        goto out;
    }
    printf("%d seams: position %.1e, normal angle %.1e rad, normal curvature %.1e (relative); %d folds\n", rep.seams,
           rep.g0.value, rep.g1.value, rep.g2.value, rep.folds);
    unsigned bad = rg2_check_failures(&rep, RG2_REQUIRE_G2 | RG2_REQUIRE_WEIGHTS);
    rg2_check_report_free(&rep);

    rg2_export_opts opts;
    rg2_export_opts_default(&opts);
    opts.name = "elbow";
    if (rg2_export_file(&s, 1, path, &opts, &err)) {
        fail("export", &err);
        goto out;
    }
    printf("wrote %s\n", path);
    rc = bad || d_torus > 1e-13 || d_pipe > 1e-13 || n_torus > 1e-13 || n_pipe > 1e-13 || K_torus > 1e-10 ||
         H_torus > 1e-10 || K_pipe > 1e-10;
out:
    free(pos);
    free(nrm);
    free(K);
    free(H);
    rg2_surface_free(&s);
    rg2_mesh_free(&elbow);
    rg2_mesh_free(&straight_t);
    rg2_mesh_free(&straight);
    rg2_mesh_free(&bend);
    return rc;
}
