/* export_fixtures.h -- test surfaces for the export tests (C and C++): a torus (closed in u
 * and v, exact), an open random mesh, and a surface of revolution whose first patch row
 * collapses to a pole on the axis (closed u, open v). Header-only: static functions. */
#ifndef RG2_EXPORT_FIXTURES_H
#define RG2_EXPORT_FIXTURES_H

#include "harness.h"

#include <math.h>
#include <string.h>

/* Torus (R + r cos v)(cos u, sin u), r sin v from nu x nv arcs (the demo's construction). */
static inline rg2_status fx_torus(double R, double r, int nu, int nv, rg2_surface *out, rg2_error *err)
{
    return rg2t_torus(R, r, nu, nv, NULL, out, err);
}

/* Torus implicit distance estimate: | |(hypot(x,y) - R, z)| - r |. */
static inline double fx_torus_dist(double R, double r, const double p[3])
{
    double q = hypot(p[0], p[1]) - R;
    return fabs(hypot(q, p[2]) - r);
}

/* Open nu x nv mesh with random points, weights in [0.6, 1.6] and random scalars. */
static inline rg2_status fx_random(uint64_t seed, int nu, int nv, rg2_surface *out, rg2_error *err)
{
    rg2t_rng r;
    rg2t_seed(&r, seed);
    rg2_mesh m;
    memset(&m, 0, sizeof m);
    rg2_status st = rg2_mesh_init(&m, nu, nv, 0, 0, err);
    if (st)
        return st;
    rg2_scalars *sc[2] = {&m.su, &m.sv};
    for (int d = 0; d < 2; d++) {
        int nw = rg2_scalars_num_w(sc[d]);
        for (int k = 0; k < nw; k++)
            sc[d]->w[k] = rg2t_uniform(&r, 0.8, 1.3);
        for (int i = 0; i < sc[d]->n; i++) {
            sc[d]->b[i] = rg2t_uniform(&r, 0.7, 1.5);
            sc[d]->g[i] = rg2t_uniform(&r, -0.4, 0.4);
        }
    }
    for (int i = 0; i < nu; i++)
        for (int j = 0; j < nv; j++) {
            double *p = rg2_mesh_at(&m, i, j);
            double W = rg2t_uniform(&r, 0.7, 1.4);
            p[0] = W * (10.0 * i + rg2t_uniform(&r, -2, 2));
            p[1] = W * (10.0 * j + rg2t_uniform(&r, -2, 2));
            p[2] = W * rg2t_uniform(&r, -4, 4);
            p[3] = W;
        }
    st = rg2_surface_build(&m, out, err);
    rg2_mesh_free(&m);
    return st;
}

/* Surface of revolution about z: u a circle of nu arcs, v an open uniform cubic profile with
 * radii -1, 0, 1, 2, ... (mirrored through the axis) so that the v = 0 side of the first patch
 * row collapses to the point on the axis: a pole. */
static inline rg2_status fx_pole(int nu, int nv, rg2_surface *out, rg2_error *err)
{
    double au[32], csu[64], knots[40];
    rg2_mesh m;
    memset(&m, 0, sizeof m);
    for (int i = 0; i < nu; i++)
        au[i] = 2 * M_PI / nu;
    for (int k = 0; k < nv + 2; k++)
        knots[k] = k;
    rg2_status st = rg2_mesh_init(&m, nu, nv, 1, 0, err);
    if (!st)
        st = rg2_circle_coeffs(au, nu, 1, 0.0, csu, err);
    if (!st) {
        rg2_scalars_free(&m.su);
        rg2_scalars_free(&m.sv);
        st = rg2_scalars_from_angles(&m.su, au, nu, 1, err);
    }
    if (!st)
        st = rg2_scalars_from_knots(&m.sv, knots, nv + 2, 0, err);
    if (!st) {
        for (int i = 0; i < nu; i++)
            for (int j = 0; j < nv; j++) {
                double *p = rg2_mesh_at(&m, i, j);
                double rad = 4.0 * (j - 1), z = 0.5 * (j - 1) * (j - 1);
                p[0] = rad * csu[2 * i];
                p[1] = rad * csu[2 * i + 1];
                p[2] = z;
                p[3] = 1.0;
            }
        st = rg2_surface_build(&m, out, err);
    }
    rg2_mesh_free(&m);
    return st;
}

/* fx_pole with the directions exchanged, built from the transposed mesh: u the open profile
 * (the first patch column's u = 0 side collapses to the pole), v the closed circle. */
static inline rg2_status fx_pole_t(int nu, int nv, rg2_surface *out, rg2_error *err)
{
    double av[32], csv[64], knots[40];
    rg2_mesh m;
    memset(&m, 0, sizeof m);
    for (int j = 0; j < nv; j++)
        av[j] = 2 * M_PI / nv;
    for (int k = 0; k < nu + 2; k++)
        knots[k] = k;
    rg2_status st = rg2_mesh_init(&m, nu, nv, 0, 1, err);
    if (!st)
        st = rg2_circle_coeffs(av, nv, 1, 0.0, csv, err);
    if (!st) {
        rg2_scalars_free(&m.su);
        rg2_scalars_free(&m.sv);
        st = rg2_scalars_from_knots(&m.su, knots, nu + 2, 0, err);
    }
    if (!st)
        st = rg2_scalars_from_angles(&m.sv, av, nv, 1, err);
    if (!st) {
        for (int i = 0; i < nu; i++)
            for (int j = 0; j < nv; j++) {
                double *p = rg2_mesh_at(&m, i, j);
                double rad = 4.0 * (i - 1), z = 0.5 * (i - 1) * (i - 1);
                p[0] = rad * csv[2 * j];
                p[1] = rad * csv[2 * j + 1];
                p[2] = z;
                p[3] = 1.0;
            }
        st = rg2_surface_build(&m, out, err);
    }
    rg2_mesh_free(&m);
    return st;
}

#endif
