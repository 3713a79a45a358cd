/* scenes.h -- surfaces built in code for the render and check tests: a torus and a sphere
 * band from circle coefficients (exact, G2), and a cylinder joined to its tangent plane
 * (G1, not G2) next to a C2 B-spline surface of the same profile (G2). */
#ifndef RG2_SCENES_H
#define RG2_SCENES_H

#include "harness.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

/* A product of two circle partitions: p_ij = ((R + r Cv_j) Cu_i, (R + r Cv_j) Su_i, r Sv_j).
 * u closed with nu arcs; v closed with nv equal arcs, or open with nv produced arcs of
 * angle dv starting at v0 (two data-only arcs on each side). */
static inline rg2_status scene_revolve(double R, double r, int nu, int nv, int closed_v, double v0, double dv,
                                       rg2_mesh *m, rg2_surface *s, rg2_error *err)
{
    double au[64], av[64], csu[128], csv[128];
    int npv = closed_v ? nv : nv + 3, nav = closed_v ? nv : nv + 4;
    for (int i = 0; i < nu; i++)
        au[i] = 2 * M_PI / nu;
    for (int j = 0; j < nav; j++)
        av[j] = closed_v ? 2 * M_PI / nv : dv;
    double th0 = closed_v ? 0.0 : v0 - 2 * dv;
    rg2_status st;
    memset(s, 0, sizeof *s);
    if ((st = rg2_mesh_init(m, nu, npv, 1, closed_v, err)))
        return st;
    rg2_scalars_free(&m->su);
    rg2_scalars_free(&m->sv);
    if ((st = rg2_scalars_from_angles(&m->su, au, nu, 1, err)) ||
        (st = rg2_scalars_from_angles(&m->sv, av, nav, closed_v, err)) ||
        (st = rg2_circle_coeffs(au, nu, 1, 0.0, csu, err)) ||
        (st = rg2_circle_coeffs(av, nav, closed_v, th0, csv, err)))
        return st;
    for (int i = 0; i < nu; i++)
        for (int j = 0; j < npv; j++) {
            double *p = rg2_mesh_at(m, i, j);
            p[0] = (R + r * csv[2 * j]) * csu[2 * i];
            p[1] = (R + r * csv[2 * j]) * csu[2 * i + 1];
            p[2] = r * csv[2 * j + 1];
            p[3] = 1.0;
        }
    return rg2_surface_build(m, s, err);
}

/* Straight extrusion of a rational cubic profile segment (homogeneous (x, z, w) Bezier
 * points prof[4][3]) along y in [0, len]: the patch's u is the profile, v is y. */
static inline void scene_extrude(double prof[4][3], double len, rg2_patch *P)
{
    for (int r = 0; r < 4; r++)
        for (int q = 0; q < 4; q++) {
            double w = prof[r][2];
            P->h[r][q][0] = prof[r][0];
            P->h[r][q][1] = w * len * q / 3.0;
            P->h[r][q][2] = prof[r][1];
            P->h[r][q][3] = w;
        }
}

/* Two patches side by side in u (one u seam, u = 1 of patch 0 on u = 0 of patch 1): the
 * straight extrusions of the profiles prof0 and prof1 along y in [0, len]. */
static inline rg2_status scene_two_extruded(double prof0[4][3], double prof1[4][3], double len, rg2_surface *s,
                                            rg2_error *err)
{
    memset(s, 0, sizeof *s);
    s->nu = 2;
    s->nv = 1;
    s->patch = calloc(2, sizeof *s->patch);
    s->bu = calloc(2, sizeof(double));
    s->gu = calloc(2, sizeof(double));
    s->bv = calloc(1, sizeof(double));
    s->gv = calloc(1, sizeof(double));
    if (!s->patch || !s->bu || !s->gu || !s->bv || !s->gv) {
        rg2_surface_free(s);
        if (err) {
            err->code = RG2_ENOMEM;
            snprintf(err->msg, sizeof err->msg, "scene: out of memory");
        }
        return RG2_ENOMEM;
    }
    scene_extrude(prof0, len, &s->patch[0]);
    scene_extrude(prof1, len, &s->patch[1]);
    s->bu[0] = s->bu[1] = 1;
    s->bv[0] = 1;
    return RG2_OK;
}

/* G1 but not G2: a quarter cylinder of radius R (x = -R sin t, z = R (1 - cos t)) whose
 * lower edge x = 0 meets the plane z = 0 (x in [0, L]) tangentially. Patch 0 is the
 * cylinder (u = 1 at the seam), patch 1 the plane; both extruded over y in [0, len]. */
static inline rg2_status scene_cyl_plane(double R, double L, double len, rg2_surface *s, rg2_error *err)
{
    /* quadratic arc from the top (-R, R) to the seam (0, 0), corner (-R, 0), weight 1/sqrt2,
     * raised to degree 3 in homogeneous form */
    double w1 = sqrt(0.5);
    double q0[3] = {-R, R, 1}, q1[3] = {-R * w1, 0, w1}, q2[3] = {0, 0, 1};
    double cyl[4][3], pl[4][3];
    for (int k = 0; k < 3; k++) {
        cyl[0][k] = q0[k];
        cyl[1][k] = (q0[k] + 2 * q1[k]) / 3;
        cyl[2][k] = (2 * q1[k] + q2[k]) / 3;
        cyl[3][k] = q2[k];
    }
    /* plane: arc-length speed matched to the cylinder's at the seam */
    for (int r = 0; r < 4; r++) {
        pl[r][0] = L * r / 3.0;
        pl[r][1] = 0;
        pl[r][2] = 1;
    }
    return scene_two_extruded(cyl, pl, len, s, err);
}

/* G2: the C2 cubic B-spline (uniform scalars) through a control polygon of the same
 * cylinder-then-plane profile, extruded along y. */
static inline rg2_status scene_bspline_profile(double R, double L, double len, rg2_mesh *m, rg2_surface *s,
                                               rg2_error *err)
{
    enum { NP = 9 };
    double px[NP], pz[NP];
    for (int i = 0; i < NP; i++) {
        double t = -1.0 + 2.0 * i / (NP - 1); /* -1 .. 1: cylinder for t < 0, plane after */
        if (t < 0) {
            double a = -t * M_PI / 2;
            px[i] = -R * sin(a);
            pz[i] = R * (1 - cos(a));
        } else {
            px[i] = L * t;
            pz[i] = 0;
        }
    }
    memset(s, 0, sizeof *s);
    rg2_status st = rg2_mesh_init(m, NP, 4, 0, 0, err);
    if (st)
        return st;
    for (int i = 0; i < NP; i++)
        for (int j = 0; j < 4; j++) {
            double *p = rg2_mesh_at(m, i, j);
            p[0] = px[i];
            p[1] = len * (j - 1.0);
            p[2] = pz[i];
            p[3] = 1;
        }
    return rg2_surface_build(m, s, err);
}

#endif
