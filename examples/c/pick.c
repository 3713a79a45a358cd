/* examples/c/pick.c -- picking on the exact surface, as a modeller does under the mouse: the
 * first point a view ray meets, the surface point nearest a spot, and a pick-and-pull of the
 * control point under the cursor (rg2_locator_ray, rg2_locator_closest).
 *
 *   cc pick.c $(pkg-config --cflags --libs --static rg2) -o pick
 *   ./pick [out.step]
 *
 * It checks the answers against the torus's own equations: the hit lies on the torus and on the
 * ray, the nearest point is the closed-form one. Then it pulls the control point nearest the hit
 * out along the hit's normal, rebuilds, and casts the same ray again: it now meets the pulled
 * surface earlier. The pulled surface is written to the file named (the format follows the
 * extension, rg2_export_file).
 */
#include <rg2.h>

#include <math.h>
#include <stdio.h>

static int fail(const char *what, const rg2_error *err)
{
    fprintf(stderr, "%s failed: %s: %s\n", what, rg2_status_str(err->code), err->msg);
    return 1;
}

int main(int argc, char **argv)
{
    const char *path = argc > 1 ? argv[1] : "pick.step";
    const double R = 3.0, r = 1.0;
    rg2_error err;

    /* The whole torus R = 3, r = 1: 8 arcs of 45 degrees around, 6 of 60 degrees across. */
    rg2_shape torus;
    rg2_shape_init(&torus, RG2_SHAPE_TORUS);
    torus.param[0] = R;
    torus.param[1] = r;
    double au[8], av[6];
    for (int i = 0; i < 8; i++)
        au[i] = RG2_PI / 4;
    for (int j = 0; j < 6; j++)
        av[j] = RG2_PI / 3;
    rg2_partition pu = {RG2_PART_ANGLES, 1, 8, au, 0.0};
    rg2_partition pv = {RG2_PART_ANGLES, 1, 6, av, 0.0};
    rg2_mesh m;
    rg2_surface s;
    if (rg2_shape_mesh(&torus, &pu, &pv, &m, &err) || rg2_surface_build(&m, &s, &err))
        return fail("build", &err);

    /* A locator reads the surface: build it once, query it as often as the mouse moves. */
    rg2_locator *L;
    if (rg2_locator_build(&s, &L, &err))
        return fail("rg2_locator_build", &err);

    /* 1. The view ray from the eye through the cursor: its first hit. */
    const double eye[3] = {9.0, 4.0, 5.0}, dir[3] = {-6.6, -2.4, -4.6}; /* toward (2.4, 1.6, 0.4), inside the tube */
    rg2_hit hit;
    if (rg2_locator_ray(L, eye, dir, INFINITY, &hit, &err))
        return fail("rg2_locator_ray", &err);
    if (hit.i < 0) {
        fprintf(stderr, "the ray missed the torus\n");
        return 1;
    }
    double g[3], on_torus = fabs(rg2_shape_implicit(&torus, hit.p, g)) / sqrt(g[0] * g[0] + g[1] * g[1] + g[2] * g[2]);
    double off_ray = 0.0;
    for (int k = 0; k < 3; k++)
        off_ray = fmax(off_ray, fabs(eye[k] + hit.dist * dir[k] - hit.p[k]));
    printf("ray: first hit on patch (%d,%d) at u = %.6f, v = %.6f, point (%.12f, %.12f, %.12f), t = %.15f\n", hit.i,
           hit.j, hit.u, hit.v, hit.p[0], hit.p[1], hit.p[2], hit.dist);
    printf("     %.1e from the torus, %.1e from the ray; normal (%.6f, %.6f, %.6f)\n", on_torus, off_ray, hit.n[0],
           hit.n[1], hit.n[2]);

    /* 2. The surface point nearest a spot (a point the user typed, or a vertex of another part). */
    const double spot[3] = {2.2, -1.9, 1.4};
    rg2_hit foot;
    if (rg2_locator_closest(L, spot, &foot, &err))
        return fail("rg2_locator_closest", &err);
    double rho = hypot(spot[0], spot[1]), tube = hypot(rho - R, spot[2]);
    double exact = fabs(tube - r); /* the torus's distance in closed form */
    printf("nearest to (%.1f, %.1f, %.1f): patch (%d,%d), point (%.12f, %.12f, %.12f), %.15f away "
           "(closed form %.15f; no point nearer than %.15f)\n",
           spot[0], spot[1], spot[2], foot.i, foot.j, foot.p[0], foot.p[1], foot.p[2], foot.dist, exact, foot.bound);

    /* 3. Pick and pull: the control point whose design point lies nearest the hit, moved out
     *    along the hit's normal by 0.3 (homogeneous: W times the move), then the same ray. */
    int bi = 0, bj = 0;
    double best = INFINITY;
    for (int i = 0; i < m.nu; i++)
        for (int j = 0; j < m.nv; j++) {
            const double *q = rg2_mesh_at(&m, i, j);
            double e = 0.0;
            for (int k = 0; k < 3; k++)
                e += (q[k] / q[3] - hit.p[k]) * (q[k] / q[3] - hit.p[k]);
            if (e < best)
                best = e, bi = i, bj = j;
        }
    double *q = rg2_mesh_at(&m, bi, bj);
    for (int k = 0; k < 3; k++)
        q[k] += q[3] * 0.3 * hit.n[k];
    rg2_locator_free(L); /* (it read the old surface) */
    rg2_hit again;
    if (rg2_surface_rebuild(&m, &s, &err) || rg2_locator_build(&s, &L, &err))
        return fail("rebuild", &err);
    if (rg2_locator_ray(L, eye, dir, INFINITY, &again, &err))
        return fail("rg2_locator_ray", &err);
    printf("pulled control point [%d, %d] out by 0.3: the ray now meets patch (%d,%d) at t = %.15f (was %.15f)\n", bi,
           bj, again.i, again.j, again.dist, hit.dist);

    int status = 0;
    if (on_torus > 1e-13 || off_ray > 1e-13 || fabs(foot.dist - exact) > 1e-13 || !(foot.bound <= foot.dist) ||
        !(again.i >= 0 && again.dist < hit.dist)) {
        fprintf(stderr, "expected the hit on the torus and the ray, the closed-form distance, and an earlier hit "
                        "after the pull\n");
        status = 1;
    }
    if (rg2_export_file(&s, 1, path, NULL, &err)) {
        fprintf(stderr, "export failed: %s\n", err.msg);
        status = 1;
    } else
        printf("wrote %s\n", path);
    rg2_locator_free(L);
    rg2_surface_free(&s);
    rg2_mesh_free(&m);
    return status;
}
