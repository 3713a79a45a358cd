/* export_fixtures.h -- test surfaces for the export tests (C and C++): a torus (closed in u
 * and v, exact), an open random mesh, and a surface of revolution whose first (or last) patch
 * row or column collapses to a pole on the axis. Header-only: static functions. */
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

/* Surface of revolution about z: a circle of nc arcs and an open uniform cubic profile of np
 * control points with radii -1, 0, 1, 2, ... (mirrored through the axis) so that the side of the
 * first patch row (column) at the profile's start collapses to the point on the axis: a pole.
 * t = 0: u the circle, v the profile; t = 1: the transposed mesh (u the profile). end = 1: the
 * profile reversed, the pole on the last patch row's (column's) side at the profile's end. */
static inline rg2_status fx_revolved(int nc, int np, int t, int end, rg2_surface *out, rg2_error *err)
{
    double ac[32], cs[64], knots[40];
    rg2_mesh m;
    memset(&m, 0, sizeof m);
    for (int i = 0; i < nc; i++)
        ac[i] = 2 * M_PI / nc;
    for (int k = 0; k < np + 2; k++)
        knots[k] = k;
    rg2_status st = t ? rg2_mesh_init(&m, np, nc, 0, 1, err) : rg2_mesh_init(&m, nc, np, 1, 0, err);
    if (!st)
        st = rg2_circle_coeffs(ac, nc, 1, 0.0, cs, err);
    if (!st) {
        rg2_scalars_free(&m.su);
        rg2_scalars_free(&m.sv);
        st = rg2_scalars_from_angles(t ? &m.sv : &m.su, ac, nc, 1, err);
    }
    if (!st)
        st = rg2_scalars_from_knots(t ? &m.su : &m.sv, knots, np + 2, 0, err);
    if (!st) {
        for (int c = 0; c < nc; c++)
            for (int q = 0; q < np; q++) {
                double *p = t ? rg2_mesh_at(&m, q, c) : rg2_mesh_at(&m, c, q);
                double q1 = end ? np - 2 - q : q - 1;
                double rad = 4.0 * q1, z = 0.5 * q1 * q1;
                p[0] = rad * cs[2 * c];
                p[1] = rad * cs[2 * c + 1];
                p[2] = z;
                p[3] = 1.0;
            }
        st = rg2_surface_build(&m, out, err);
    }
    rg2_mesh_free(&m);
    return st;
}

/* u a circle of nu arcs, v the profile of nv points: the v = 0 side of the first patch row is
 * the pole. */
static inline rg2_status fx_pole(int nu, int nv, rg2_surface *out, rg2_error *err)
{
    return fx_revolved(nu, nv, 0, 0, out, err);
}

/* fx_pole with the directions exchanged, built from the transposed mesh: u the open profile of
 * nu points (the first patch column's u = 0 side collapses to the pole), v the circle of nv arcs. */
static inline rg2_status fx_pole_t(int nu, int nv, rg2_surface *out, rg2_error *err)
{
    return fx_revolved(nv, nu, 1, 0, out, err);
}

#endif
