/* harness.h -- the rg2 test harness: checks that count, fixed-seed random numbers, and
 * geometric measurements shared by the tests (G2 gaps across seams). */
#ifndef RG2_HARNESS_H
#define RG2_HARNESS_H

#include "rg2.h"

#include <stdint.h>
#include <stdio.h>

#ifndef M_PI
#define M_PI 3.14159265358979323846

#endif

extern int rg2t_passed, rg2t_failed;

/* CHECK(cond, fmt, ...): count a pass, or print the failure with its measured values. */
#define CHECK(cond, ...)                                                                       \
    do {                                                                                       \
        if (cond) {                                                                            \
            rg2t_passed++;                                                                     \
        } else {                                                                               \
            rg2t_failed++;                                                                     \
            fprintf(stderr, "FAIL %s:%d: ", __FILE__, __LINE__);                               \
            fprintf(stderr, __VA_ARGS__);                                                      \
            fprintf(stderr, "\n");                                                             \
        }                                                                                      \
    } while (0)

/* Check that an rg2 call returned RG2_OK, printing the error message otherwise. */
#define CHECK_OK(call, err)                                                                    \
    do {                                                                                       \
        rg2_status st_ = (call);                                                               \
        CHECK(st_ == RG2_OK, "%s -> %s: %s", #call, rg2_status_str(st_), (err)->msg);          \
    } while (0)

/* Print the summary line "name: N passed, M failed" and return the exit code. */
int rg2t_done(const char *name);
/* A full disk for the writers: files this process writes fail past `bytes` with EFBIG
 * (RLIMIT_FSIZE, with SIGXFSZ ignored); bytes < 0 lifts the limit again. 0 on success. */
int rg2t_file_limit(long long bytes);

/* The example designs, examples/NAME.json sorted by name (tests run in the source tree), into
 * names (malloc'd each, the caller frees them): how many, at most max. */
int rg2t_example_names(char **names, int max);

/* Deterministic random numbers (splitmix64); every test prints its seed. */
typedef struct {
    uint64_t s;
} rg2t_rng;
void rg2t_seed(rg2t_rng *r, uint64_t seed);
double rg2t_uniform(rg2t_rng *r, double lo, double hi);
int rg2t_int(rg2t_rng *r, int lo, int hi); /* inclusive */

/* Worst G0/G1/G2 gaps over all interior seams of a surface (and the closing seams of
 * closed directions), sampled at `samples` points along each seam.
 *   pos:     position gap / scale (scale = bounding-box diagonal)
 *   angle:   angle between the unit normals (rad)
 *   curv:    normal-curvature jump in 6 tangent directions, relative to
 *            max(|k1|, |k2|, 1/scale) at the point
 *   param1:  |p_R' - b p_L'| / |p_L'|   (transversal derivative, Definition 1)
 *   param2:  |p_R'' - b^2 p_L'' - g p_L'| / (|b^2 p_L''| + |g p_L'| + |p_L'|)
 * Points where a normal is undefined (collapsed edges) are skipped and counted. */
typedef struct {
    double pos, angle, curv, param1, param2;
    int seams, samples, skipped;
    char where[128]; /* the seam with the worst curvature jump */
} rg2t_seams;
void rg2t_surface_seams(const rg2_surface *s, int samples, rg2t_seams *out);

/* The bounding-box diagonal of the patches' control points (a size scale). */
double rg2t_surface_scale(const rg2_surface *s);

/* The torus ((R + r cos v) cos u, (R + r cos v) sin u, r sin v) as a closed mesh of nu x nv
 * equal arcs (exact circle scalars), built into nu x nv rational bi-cubic patches. The mesh is
 * kept in *mesh if not NULL (caller frees). Returns the status; err names a failure. */
/* Replace every `stride`-th patch (k % stride == phase, k = i * nv + j) of s by its exact
 * degree elevation to (du, dv) held in s->xp (patch[k] set to NaN): the same geometry, so
 * every exactness/G2 test of s must still pass through the higher-degree code paths. */
rg2_status rg2t_elevate_some(rg2_surface *s, int du, int dv, int stride, int phase, rg2_error *err);
rg2_status rg2t_torus(double R, double r, int nu, int nv, rg2_mesh *mesh, rg2_surface *out, rg2_error *err);
/* The unit sphere as a polar mesh (6 arcs, v knots 0.2 .. 0.8) closed by bi-3 rotational caps:
 * pole patches with sides collapsed to the poles (Su x Sv at rounding-noise level there). */
rg2_status rg2t_capped_sphere(rg2_mesh *mesh, rg2_surface *out, rg2_error *err);

/* A design's surfaces, control meshes, shapes and shape labels as arrays of shallow copies (read
 * only, owned by the design; the shape arrays have at least one entry). 0 on success, -1 out of
 * memory (nothing left to free). Release the arrays with rg2t_design_parts_free. */
typedef struct {
    int n, ns;
    rg2_surface *s;
    rg2_mesh *meshes;
    rg2_shape *shapes;
    const char **labels;
} rg2t_parts;
int rg2t_design_parts(const rg2_design *d, rg2t_parts *p);
void rg2t_design_parts_free(rg2t_parts *p);

#endif
