/* examples/c/edit_loop.c -- an editing loop: pull one control point of a torus's mesh out step
 * by step, rebuild the surface and re-tessellate it into the same memory each time
 * (rg2_surface_rebuild, rg2_retessellate), as an interactive modeller does between frames.
 *
 *   cc edit_loop.c $(pkg-config --cflags --libs --static rg2) -o edit_loop
 *   ./edit_loop [out.obj]
 *
 * It checks what the paper promises a designer: only the patches near the moved point change,
 * and every vertex of the others stays on the exact torus; moving the point back gives the
 * first mesh again, bit for bit. The last frame is written to the file named (the format follows
 * the extension, rg2_export_file).
 */
#define _POSIX_C_SOURCE 200809L /* clock_gettime */
#include <rg2.h>

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

static double seconds(void)
{
    struct timespec t;
    clock_gettime(CLOCK_MONOTONIC, &t);
    return (double)t.tv_sec + 1e-9 * (double)t.tv_nsec;
}

static int fail(const char *what, const rg2_error *err)
{
    fprintf(stderr, "%s failed: %s: %s\n", what, rg2_status_str(err->code), err->msg);
    return 1;
}

int main(int argc, char **argv)
{
    const char *path = argc > 1 ? argv[1] : "edit_loop.obj";
    enum { FRAMES = 20, DENSITY = 16 };
    rg2_error err;

    /* The whole torus R = 3, r = 1: 8 arcs of 45 degrees around, 6 of 60 degrees across. */
    rg2_shape torus;
    rg2_shape_init(&torus, RG2_SHAPE_TORUS);
    torus.param[0] = 3.0;
    torus.param[1] = 1.0;
    double au[8], av[6];
    for (int i = 0; i < 8; i++)
        au[i] = RG2_PI / 4;
    for (int j = 0; j < 6; j++)
        av[j] = RG2_PI / 3;
    rg2_partition pu = {RG2_PART_ANGLES, 1, 8, au, 0.0};
    rg2_partition pv = {RG2_PART_ANGLES, 1, 6, av, 0.0};

    rg2_mesh m;
    rg2_surface s = {0}, orig = {0};
    rg2_tess t = {0}, first = {0};
    if (rg2_shape_mesh(&torus, &pu, &pv, &m, &err))
        return fail("rg2_shape_mesh", &err);
    if (rg2_surface_rebuild(&m, &s, &err) || rg2_surface_copy(&s, &orig, &err) ||
        rg2_tessellate(&s, DENSITY, 0, &first, &err))
        return fail("build", &err);

    /* The point to pull: (2, 1) of the mesh, moved along z by up to 0.5 (homogeneous: w dz). */
    const int pi = 2, pj = 1;
    double *q = rg2_mesh_at(&m, pi, pj), z0 = q[2];
    double t_rebuild = 0.0, t_tess = 0.0, worst = 0.0;
    int changed = 0, status = 0;
    for (int f = 1; f <= FRAMES; f++) {
        q[2] = z0 + q[3] * 0.5 * f / FRAMES;
        double t0 = seconds();
        if (rg2_surface_rebuild(&m, &s, &err))
            return fail("rg2_surface_rebuild", &err);
        double t1 = seconds();
        if (rg2_retessellate(&s, DENSITY, 0, &t, &err))
            return fail("rg2_retessellate", &err);
        t_rebuild += t1 - t0;
        t_tess += seconds() - t1;
    }

    /* Which patches the pull changed; every vertex of the others on the exact torus. */
    int np = s.nu * s.nv;
    char *moved = calloc((size_t)np, 1);
    if (!moved)
        return 1;
    for (int k = 0; k < np; k++) {
        moved[k] = memcmp(s.patch[k].h, orig.patch[k].h, sizeof s.patch[k].h) != 0;
        changed += moved[k];
    }
    for (int v = 0; v < t.n_vertices; v++) {
        if (moved[t.patch[v]])
            continue;
        double g[3], f = rg2_shape_implicit(&torus, t.pos + 3 * v, g);
        double d = fabs(f) / sqrt(g[0] * g[0] + g[1] * g[1] + g[2] * g[2]);
        if (d > worst)
            worst = d;
    }
    free(moved);
    printf("%d frames of %d x %d patches, %d vertices: rebuild %.3f ms, re-tessellate %.3f ms per frame\n",
           FRAMES, s.nu, s.nv, t.n_vertices, 1e3 * t_rebuild / FRAMES, 1e3 * t_tess / FRAMES);
    printf("the pull changed %d of %d patches; the vertices of the others lie within %.1e of the torus\n",
           changed, np, worst);
    if (changed == 0 || changed > 16 || worst > 1e-13) {
        fprintf(stderr, "expected 1 to 16 changed patches (the point's 4 x 4 support) and the rest on the torus\n");
        status = 1;
    }
    if (rg2_export_file(&s, 1, path, NULL, &err)) {
        fprintf(stderr, "export failed: %s\n", err.msg);
        status = 1;
    } else {
        printf("wrote %s\n", path);
    }

    /* The point back where it was: the first mesh again, bit for bit. */
    q[2] = z0;
    if (rg2_surface_rebuild(&m, &s, &err) || rg2_retessellate(&s, DENSITY, 0, &t, &err))
        return fail("rebuild", &err);
    size_t nv = (size_t)t.n_vertices;
    int same = t.n_vertices == first.n_vertices && t.n_triangles == first.n_triangles &&
               !memcmp(t.pos, first.pos, 3 * nv * sizeof(double)) &&
               !memcmp(t.tri, first.tri, 3 * (size_t)t.n_triangles * sizeof(int));
    printf("point moved back: %s\n", same ? "the first mesh again, bit for bit" : "a DIFFERENT mesh");
    if (!same)
        status = 1;

    rg2_tess_free(&t);
    rg2_tess_free(&first);
    rg2_surface_free(&s);
    rg2_surface_free(&orig);
    rg2_mesh_free(&m);
    return status;
}
