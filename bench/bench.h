/* bench.h -- shared types of rg2_bench (bench.c, C) and its OpenCASCADE side (occt.cpp). */
#ifndef RG2_BENCH_H
#define RG2_BENCH_H

#include <stddef.h>

#ifdef __cplusplus
extern "C" {
#endif

/* One B-spline surface of degree 3 x 3 holding a patchwork exactly: interior knots of
 * multiplicity 3 at 1, 2, ..., spans - 1 (clamped ends), in1 = 3 spans1 + 1 homogeneous
 * poles (w x, w y, w z, w) with the first direction running fastest (SISL order). */
typedef struct {
    int spans1, spans2, in1, in2;
    double *knots1, *knots2; /* in + 4 values each */
    double *hcoef;           /* in1 * in2 * 4 */
} bspline;

/* Evaluation points: pu x pv patches, n x n points per patch at local t[a] = a / (n - 1). */
typedef struct {
    int pu, pv, n;
    double *t;
} grid_params;

typedef enum {
    OCCT_BSPLINE_D0,
    OCCT_BSPLINE_D1,
    OCCT_ADAPTOR_D0,
    OCCT_ADAPTOR_D1,
    OCCT_SLPROPS
} occt_method;

typedef struct occt_surf occt_surf;
occt_surf *occt_make(const bspline *b);
void occt_free(occt_surf *s);
/* Evaluate every grid point in patch layout (patch i * pv + j, then a * n + b); nrm is
 * unit normals (D1, SLProps), K and H only for SLProps. */
void occt_eval(occt_surf *s, occt_method meth, const grid_params *g, double *pos, double *nrm, double *K,
               double *H);

/* The surface as one face written by OpenCASCADE's STEPControl_Writer (iges 0) or
 * IGESControl_Writer (iges 1); 0 or -1. A file read back by OpenCASCADE: its number of faces
 * (-1 unreadable) and the first face's B-spline pole counts (0 if not a B-spline). */
int occt_write(occt_surf *s, const char *path, int iges);
int occt_read_poles(const char *path, int iges, int *nu, int *nv);

/* Picking. occt_proj: a GeomAPI_ProjectPointOnSurf initialised once on the whole surface
 * (Extrema_ExtAlgo_Grad, or _Tree when tree is 1; default tolerances); occt_closest: the nearest
 * point of x (LowerDistance and the point at its parameters), 1, or 0 when none was found.
 * The first hit of the ray o + t d, t >= 0 (t in units of d): occt_ray_intcs by GeomAPI_IntCS
 * per ray (a Geom_Line through o along d / |d|); occt_ray_hinter by IntCurveSurface_HInter with
 * the surface's adaptor and polyhedron made once (occt_rayer) and the line clipped to the box of
 * the poles. 1 hit (point and t), 0 none. */
typedef struct occt_proj occt_proj;
occt_proj *occt_proj_make(occt_surf *s, int tree);
void occt_proj_free(occt_proj *p);
int occt_closest(occt_proj *p, const double x[3], double pt[3], double *dist);
int occt_ray_intcs(occt_surf *s, const double o[3], const double d[3], double pt[3], double *t);
typedef struct occt_rayer occt_rayer;
occt_rayer *occt_rayer_make(occt_surf *s);
void occt_rayer_free(occt_rayer *r);
int occt_ray_hinter(occt_rayer *r, const double o[3], const double d[3], double pt[3], double *t);

/* affinity.c: the CPUs the calling thread may run on (at most max; 0 where unknown); pin the
 * calling thread to one of them (0 on success); give it back the affinity it had before the
 * first bench_pin. */
int bench_cpus(int *cpu, int max);
int bench_pin(int cpu);
void bench_unpin(void);

#ifdef __cplusplus
}
#endif

#endif
