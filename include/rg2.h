/*
 * rg2.h -- rational bi-cubic G2 splines (Karciauskas & Peters 2011).
 *
 * The one public header of the rg2 library.
 *
 * Index (groups in the order they appear below):
 *   Status and errors ....... rg2_status, rg2_error, rg2_status_str, rg2_version
 *   Direction scalars ....... rg2_scalars: leg weights w, junction scalars b, g
 *                             rg2_scalars_init/free/copy/check, _from_knots, _from_angles
 *   Scalar building blocks .. rg2_circle_coeffs, rg2_blossom_monomials
 *   Curves .................. rg2_curve: rational cubic G2 spline curves in R^d
 *                             rg2_curve_build/free/eval/curvature
 *   Control meshes .......... rg2_mesh: grid of homogeneous 4-tuples + u/v scalars
 *   Patches and surfaces .... rg2_patch (rational bi-3 Bezier), rg2_surface (grid of patches)
 *                             rg2_surface_build (the Bi-cubic Construction)
 *   Evaluation .............. rg2_patch_eval (position, derivatives, normal, curvatures)
 *   Picking ................. rg2_locator: the closest surface point, the first hit of a ray
 *   Shapes .................. (exact basic shapes; see the shapes section)
 *   Design .................. (JSON design files; see the design section)
 *   Poles ................... polar configurations, rg2_cap_build (polar caps), Moebius maps
 *   Grid and tessellation ... rg2_patch_grid, rg2_surface_grid, rg2_patch_point(_normal),
 *                             rg2_tessellate, rg2_retessellate
 *   Export .................. (STEP, IGES, BezierView, meshes; see the export section)
 *   Pictures and checks ..... (render, check, rg2_find_crossings; see that section)
 *
 * Conventions
 *   - Every function that can fail returns rg2_status (RG2_OK = 0) and takes a nullable
 *     rg2_error *err as its last argument; on failure err->msg names the offending item.
 *   - The library never prints and never exits.
 *   - Objects that own memory are plain structs released by their *_free function, which
 *     accepts a zeroed struct (or NULL) and leaves the struct zeroed.
 *   - Homogeneous 4-tuples are (w x, w y, w z, w).
 *   - Arrays of pointers are taken const at both levels (rg2_mesh_merge and _merge_overlap's in,
 *     rg2_export_files' paths, rg2_check's labels, rg2_closest_name's names): in C, declare them
 *     so (const rg2_mesh *in[2] = {&a, &b}; const char *paths[] = {...}); C does not add const
 *     below the first level, so a rg2_mesh *[] or a char ** such as argv needs a cast,
 *     (const char *const *)argv, or it is -Wincompatible-pointer-types (an error by default from
 *     GCC 14). C++ converts them itself.
 *   - Pointer arguments must not be NULL unless the function's comment says they may be (err
 *     always may); indices (patch i, j, segment, junction) must lie in the ranges of the object
 *     they index: functions without a status (evaluators returning void or a number) do not
 *     check them. Functions with a status check their counts and sizes.
 *   - Output structs (surfaces, meshes, scalars, tessellations, images) are filled from scratch:
 *     pass a zeroed or freed struct, or the previous contents leak. rg2_surface_rebuild and
 *     rg2_retessellate are the ones that reuse a built surface's or mesh's memory. A call that
 *     fails leaves its output struct zeroed (rg2_design_load / _parse: *out NULL), whatever it
 *     held before: nothing to free, and its *_free is harmless. (Plain result structs that own
 *     no memory, rg2_cap_info and rg2_weight_report, may hold partial values.)
 *   - Thread safety: calls may come from several threads at once. Reading one object from
 *     several threads at once is safe, writing it is not; results are the same bits as from a
 *     serial run. What the library shares between calls is internal and synchronised: the
 *     worker pool of the grid evaluator and the tessellation (one job at a time; a call that
 *     finds it busy runs alone), the grid's table cache (entries written once, published
 *     atomically), the "C" locale it formats numbers in (files, reports, error messages, design
 *     notes and the colour bars of pictures, whatever the host's LC_NUMERIC), and its use of
 *     cJSON: Debian's libcjson
 *     writes a process-wide error struct on every parse, and cJSON reads the decimal point
 *     through localeconv(), whose one result struct every caller rewrites, so rg2 runs all its
 *     cJSON parses and prints under one lock and in the "C" locale. Two writers of one path each
 *     write their own temporary file; the path ends as one whole file. Measured by
 *     tests/test_threads.c (4 threads, every bundled design, half under de_DE, every call above)
 *     and test_export (one path, two writers) under ThreadSanitizer with libomp's Archer tool
 *     and, for libcjson (not instrumented), helgrind (scripts/check_tsan.sh, make test). Not
 *     covered by the lock, since that state belongs to libcjson and the C library: a host's own
 *     cJSON calls (cJSON_InitHooks among them), or localeconv() under a locale whose decimal
 *     point is not '.', in another thread during an rg2 call that parses or writes JSON
 *     (rg2_design_load / _parse, rg2_nurbs_parse, rg2_design_write_mesh, rg2_check_format, the
 *     JSON and glTF exports); nor a host's setenv / putenv / unsetenv in another thread during a
 *     STEP or IGES export, which reads SOURCE_DATE_EPOCH with getenv (rg2_export_file).
 *   - Floating point: call rg2 in the C default environment, round to nearest. Traps: on valid
 *     input (designs, meshes and NURBS the library accepts, within the numeric range of
 *     docs/robustness.md, and the surfaces it builds from them) these calls raise none of
 *     FE_INVALID, FE_DIVBYZERO, FE_OVERFLOW, so a host may keep those trapping (feenableexcept)
 *     around them: building (rg2_design_load / _parse, rg2_surface_build / _rebuild,
 *     rg2_cap_build, rg2_nurbs_mesh / _parse), evaluating (rg2_surface_grid, rg2_patch_grid,
 *     rg2_surface_eval, rg2_patch_eval, rg2_patch_point, rg2_patch_point_normal), rg2_tessellate,
 *     rg2_export_file(s) in every format, rg2_check and rg2_check_format, rg2_render
 *     (tests/test_fptraps.c: every bundled design, 1 and 2 threads, every grid kernel; GCC and
 *     clang builds, docs/robustness.md). Not promised: other calls; builds with -ffast-math or
 *     -fno-trapping-math; invalid input (NaN, infinities, weights <= 0, numbers out of range:
 *     the checks that refuse them and the evaluators may raise them on the way); degenerate
 *     patches (tangents parallel to within rounding, where the curvature divides by an
 *     E G - F^2 that rounds to 0); FE_UNDERFLOW and FE_INEXACT, which occur anywhere. Otherwise
 *     hold the traps around rg2 calls (feholdexcept before, fesetenv after). Worker threads (the
 *     grid's pool, OpenMP's) keep the environment they were created in: enable the traps before
 *     the first rg2 call (or in each OpenMP thread) for them to trap too. Under another rounding
 *     mode the results stay accurate, but the grid's promise of the same bits for any thread
 *     count holds only for round to nearest.
 *   - fork: the grid's worker pool is rebuilt in a child, but libgomp's is not: in a child of a
 *     process that has used rg2 (building more than 256 patches, writing STEP, IGES, OBJ or
 *     JSON, rendering, checking), an rg2 call that runs OpenMP threads waits forever (a libgomp
 *     limitation). Call omp_set_num_threads(1) in the child first (or run with
 *     OMP_NUM_THREADS=1).
 *   - The AVX-512 kernels are chosen at load time (GCC function multi-versioning, an ifunc):
 *     ThreadSanitizer builds of the whole program cannot instrument that resolver; build the
 *     library with -DRG2_NO_CLONES for them.
 */
#ifndef RG2_H
#define RG2_H

#include <stddef.h>

#ifdef __cplusplus
extern "C" {
#endif

/* The inline helpers' index arithmetic: a static_cast for C++ hosts that build with
 * -Wold-style-cast -Werror (tests/header.sh compiles this header under strict warnings). */
#ifdef __cplusplus
#define RG2_SIZE(x) static_cast<size_t>(x)
#else
#define RG2_SIZE(x) ((size_t)(x))
#endif
/* and nullptr where C++ has it (-Wzero-as-null-pointer-constant) */
#if defined(__cplusplus) && __cplusplus >= 201103L
#define RG2_NULL nullptr
#else
#define RG2_NULL NULL
#endif

#if defined(RG2_BUILDING_LIBRARY) && defined(__GNUC__)
#define RG2_API __attribute__((visibility("default")))
#else
#define RG2_API
#endif

#define RG2_VERSION_MAJOR 0
#define RG2_VERSION_MINOR 1
#define RG2_VERSION_PATCH 0
#define RG2_VERSION_STR_(x) #x
#define RG2_VERSION_STR(x) RG2_VERSION_STR_(x)
/** "MAJOR.MINOR.PATCH", made from the three numbers above (the only place the version is
 *  written: CMake reads them too). */
#define RG2_VERSION_STRING                                                                         \
    RG2_VERSION_STR(RG2_VERSION_MAJOR) "." RG2_VERSION_STR(RG2_VERSION_MINOR) "." RG2_VERSION_STR(RG2_VERSION_PATCH)
/** RG2_VERSION_MAJOR * 10000 + MINOR * 100 + PATCH, for #if tests. */
#define RG2_VERSION_NUMBER (RG2_VERSION_MAJOR * 10000 + RG2_VERSION_MINOR * 100 + RG2_VERSION_PATCH)
#define RG2_PI 3.14159265358979323846
/** The arcs of a closed circle must sum to 2 pi to this relative tolerance; design files and
 *  `rg2 shape --u-angles` call a list of arcs closed when it sums to 360 degrees within it, and
 *  refuse a sum within RG2_NEAR_FULL_DEG of 360 but outside it (a mistyped full circle: open
 *  with a hairline gap, or closed and refused) unless closedness is stated. */
#define RG2_CLOSED_SUM_TOL 1e-12
#define RG2_NEAR_FULL_DEG 0.01

/* ===================================================================================== */
/** @name Status and errors */
/* ===================================================================================== */

typedef enum {
    RG2_OK = 0,
    RG2_ENOMEM,        /**< allocation failed */
    RG2_EINVAL,        /**< invalid argument (count, index, structure) */
    RG2_ENONFINITE,    /**< NaN or infinity in the input */
    RG2_EWEIGHT,       /**< weight or scalar b not > 0, or K_i <= 0 */
    RG2_EDOMAIN,       /**< value outside its allowed range (angle, knot interval, ...) */
    RG2_EINCOMPATIBLE, /**< meshes cannot be combined (merge, morph) */
    RG2_EPARSE,        /**< malformed input file */
    RG2_EIO,           /**< file could not be read or written */
    RG2_ELIMIT         /**< request exceeds a documented size limit */
} rg2_status;

/** An error report: the status code and a message naming the offending item. */
typedef struct {
    rg2_status code;
    char msg[512]; /**< UTF-8; a longer message (a long path) keeps its first 160 bytes and its
                        end, which says what went wrong, joined by " [...] " */
} rg2_error;

/** Text for a status code; never NULL. */
RG2_API const char *rg2_status_str(rg2_status code);
/** The library version, e.g. "0.1.0". */
RG2_API const char *rg2_version(void);
/** The library's RG2_VERSION_NUMBER (MAJOR * 10000 + MINOR * 100 + PATCH, 100 for 0.1.0): a
 *  program compares it with the header's macro to catch being built against one version and
 *  linked with another. */
RG2_API int rg2_version_number(void);

/* ===================================================================================== */
/** @name Direction scalars (MATH.md section 1)
 *
 * One direction of a curve or mesh: n control points, closed or open.
 *
 * Closed: n legs (leg i joins p^i and p^{i+1 mod n}), n segments, n junctions.
 *   w[i] = w_i (leg i), b[i] = b_i, g[i] = g_i (junction i at p^i).
 * Open (unclamped, like a cubic B-spline; n >= 4): the segments are those of legs 1..n-3.
 *   The construction needs weights w_{-1}..w_{n-1}: stored w[i+1] = w_i (n+1 values);
 *   junction scalars b_i, g_i for i = 0..n-1: stored b[i], g[i] (n values).
 *   Legs -1 and n-1 are virtual (beyond the end points): they carry data only.
 *
 * G2 at junction i requires K_i = 2 b_i (3 w_i - 2) + 2 b_i^2 (3 w_{i-1} - 2) + g_i > 0.
 */
/* ===================================================================================== */

typedef struct {
    int n;      /**< number of control points in this direction */
    int closed; /**< 1 closed (periodic), 0 open */
    double *w;  /**< leg weights: n values (closed) or n+1 values (open, w[i+1] = w_i) */
    double *b;  /**< junction scalar b_i > 0, n values */
    double *g;  /**< junction scalar g_i, n values */
} rg2_scalars;

/** Allocate scalars for n points with the uniform cubic B-spline values w = 1, b = 1, g = 0.
 *  @return RG2_EINVAL if n < 3 (closed) or n < 4 (open); RG2_ELIMIT past RG2_MAX_POINTS. */
RG2_API rg2_status rg2_scalars_init(rg2_scalars *s, int n, int closed, rg2_error *err);
RG2_API void rg2_scalars_free(rg2_scalars *s);
/** A copy of src into dst (as every output, filled from scratch). dst must not be src: that is
 *  refused (RG2_EINVAL) with dst left as it was; so for rg2_mesh_copy and rg2_surface_copy. */
RG2_API rg2_status rg2_scalars_copy(const rg2_scalars *src, rg2_scalars *dst, rg2_error *err);
/** Number of stored weights: n (closed) or n + 1 (open). */
RG2_API int rg2_scalars_num_w(const rg2_scalars *s);
/** Number of curve segments (patches in this direction): n (closed) or n - 3 (open). */
RG2_API int rg2_scalars_num_segments(const rg2_scalars *s);
/** Leg weight w_i for leg index i (closed: i mod n; open: -1 <= i <= n-1). */
RG2_API double rg2_scalars_leg_w(const rg2_scalars *s, int i);
/** K_i of junction i (MATH.md eq. 4). */
RG2_API double rg2_scalars_K(const rg2_scalars *s, int i);
/** Check finiteness, w > 0, b > 0, K > 0. `what` prefixes the message ("u", "mesh 2 v"...).
 *  @return RG2_ENONFINITE (also for a K that is not a finite number), RG2_EWEIGHT or RG2_EINVAL,
 *          naming the index. */
RG2_API rg2_status rg2_scalars_check(const rg2_scalars *s, const char *what, rg2_error *err);

/** Scalars of the polynomial special case (non-uniform C2 cubic B-spline): w = 1, g = 0,
 *  b_i = d_i / d_{i-1} with d_i = v_{i+1} - v_i.
 *  Open: n_knots = n + 2 knots v_{-1}..v_n (stored knots[i+1] = v_i); segment i (1..n-3)
 *        spans [v_i, v_{i+1}], so the domain is [v_1, v_{n-2}].
 *  Closed: n_knots = n + 1 knots v_0..v_n, period v_n - v_0.
 *  @return RG2_EDOMAIN for a non-increasing knot (zero-length interval), naming it, and for
 *          neighbouring intervals whose junction scalars leave the double range (b = 0 or a
 *          b, g or K that is not a finite number: intervals 1e-300 and 1 give b = 1e300 and
 *          K = inf), naming the knots, the junction and the scalars; RG2_ENONFINITE for a NaN
 *          or infinite knot; RG2_EINVAL / RG2_ELIMIT for too few / too many knots: open at
 *          least 6 (4 points), closed at least 4 (3 points), at most RG2_MAX_POINTS points; the
 *          message tells the n_knots given ("knots: 2 knots given, an open direction needs at
 *          least 6 (4 control points, 1 segment)"). */
RG2_API rg2_status rg2_scalars_from_knots(rg2_scalars *s, const double *knots, int n_knots,
                                          int closed, rg2_error *err);

/** Scalars of a circle partitioned into arcs with opening angles alpha (MATH.md section 2),
 *  0 < alpha < pi each.
 *  Closed: n_alpha = n arcs (arc i spans junction i to i+1); they need not sum to 2 pi for
 *          the scalars, but a closed circle needs sum = 2 pi (see rg2_circle_coeffs).
 *  Open: n_alpha = n + 1 arcs alpha_{-1}..alpha_{n-1} (stored alpha[i+1] = alpha_i); the
 *        produced segments 1..n-3 are exactly arcs 1..n-3.
 *  @return RG2_ENONFINITE for a NaN or infinite angle, RG2_EDOMAIN for an angle outside
 *          (0, pi), naming it, and for neighbouring arcs whose junction scalars leave the
 *          double range (an arc of 1e-320 next to one of 2: b = inf), naming the arcs, the
 *          junction and the scalars; RG2_EINVAL / RG2_ELIMIT for too few / too many arcs: open
 *          at least 5 (4 points), closed at least 3, at most RG2_MAX_POINTS points; the message
 *          tells the n_alpha given ("arcs: 2 arcs given, a closed direction needs at least 3"). */
RG2_API rg2_status rg2_scalars_from_angles(rg2_scalars *s, const double *alpha, int n_alpha,
                                           int closed, rg2_error *err);

/* ===================================================================================== */
/** @name Scalar building blocks (MATH.md section 3) */
/* ===================================================================================== */

/** Control coefficients (C_i, S_i) of (cos t, sin t) for a circle partition: the corners
 *  p^i of the conic arcs. theta0 is the angle of junction 0 (start of arc 0); arc i spans
 *  [theta_i, theta_i + alpha_i]. A theta0 beyond one turn (|theta0| > 2 pi) is taken as
 *  atan2(sin theta0, cos theta0), so 1e20 gives the corners of its reduction, bit for bit.
 *  Layout of alpha as in rg2_scalars_from_angles.
 *  cs receives n pairs: cs[2i] = C_i, cs[2i+1] = S_i (n = n_alpha closed, n_alpha - 1 open).
 *  Closed partitions must sum to 2 pi (to 1e-12 relative).
 *  @return RG2_ENONFINITE for a NaN or infinite angle or theta0, RG2_EDOMAIN for an angle
 *          outside (0, pi) or a closed sum other than 2 pi, naming the arc or the sum;
 *          RG2_EINVAL / RG2_ELIMIT for an n_alpha out of range, as rg2_scalars_from_angles. */
RG2_API rg2_status rg2_circle_coeffs(const double *alpha, int n_alpha, int closed, double theta0,
                                     double *cs, rg2_error *err);

/** Blossom (polar form) of the monomials 1, v, v^2, v^3 at (a, b, c): out = {1, (a+b+c)/3,
 *  (ab+ac+bc)/3, abc}. Control coefficient of junction i is the blossom at (v_{i-1}, v_i, v_{i+1}). */
RG2_API void rg2_blossom_monomials(double a, double b, double c, double out[4]);

/* ===================================================================================== */
/** @name Curves (MATH.md section 1): rational cubic G2 splines in R^d */
/* ===================================================================================== */

#define RG2_MAX_DIM 8
#define RG2_MAX_POINTS 4000000 /**< per direction and in total per mesh */

typedef struct {
    int dim;        /**< dimension d of the points, 1..RG2_MAX_DIM */
    int n_segments; /**< number of Bezier segments */
    int closed;
    double *bez;    /**< n_segments * 4 * dim affine Bezier coefficients, segment-major */
    double *w;      /**< n_segments middle weights: segment i has weights (1, w[i], w[i], 1) */
} rg2_curve;

/** The G2 construction (eq. 3-4) on a control polygon of s->n points in R^dim.
 *  Segment k of the result is segment k (closed) or k + 1 (open) of MATH.md. */
RG2_API rg2_status rg2_curve_build(int dim, const double *points, const rg2_scalars *s,
                                   rg2_curve *out, rg2_error *err);
RG2_API void rg2_curve_free(rg2_curve *c);
/** Position and first/second derivatives (each dim values, NULL to skip) of segment seg at
 *  t in [0, 1] (exact quotient rule). */
RG2_API void rg2_curve_eval(const rg2_curve *c, int seg, double t, double *pos, double *d1,
                            double *d2);
/** Curvature |f' x f''| / |f'|^3 (dim 2 or 3; curves of other dimensions, 1 and 4..8, return 0). */
RG2_API double rg2_curve_curvature(const rg2_curve *c, int seg, double t);

/* ===================================================================================== */
/** @name Control meshes (MATH.md sections 4 and 6) */
/* ===================================================================================== */

typedef struct {
    int nu, nv;     /**< control points in u and v */
    double *p;      /**< nu * nv homogeneous 4-tuples: p[(i * nv + j) * 4 + k], i along u */
    rg2_scalars su; /**< u-direction scalars (su.n == nu) */
    rg2_scalars sv; /**< v-direction scalars (sv.n == nv) */
} rg2_mesh;

/** Allocate a mesh with zero points and uniform scalars. */
RG2_API rg2_status rg2_mesh_init(rg2_mesh *m, int nu, int nv, int closed_u, int closed_v,
                                 rg2_error *err);
RG2_API void rg2_mesh_free(rg2_mesh *m);
/** A copy of src (dst must not be src, as for rg2_scalars_copy). */
RG2_API rg2_status rg2_mesh_copy(const rg2_mesh *src, rg2_mesh *dst, rg2_error *err);
/** Check counts, scalars of both directions, and finiteness of every 4-tuple (naming [i][j]). */
RG2_API rg2_status rg2_mesh_check(const rg2_mesh *m, rg2_error *err);
/** Check that every control point has a weight p_4 > 0 (design points d = p_{1..3} / p_4 need
 *  it; a weight <= 0 puts the surface through infinity). RG2_EWEIGHT (RG2_ENONFINITE for a
 *  non-finite weight) naming the first offending point "[i, j]" and its weight; its indices go
 *  to *wi, *wj (each nullable). */
RG2_API rg2_status rg2_mesh_check_weights(const rg2_mesh *m, int *wi, int *wj, rg2_error *err);
/** Pointer to 4-tuple (i, j). */
static inline double *rg2_mesh_at(const rg2_mesh *m, int i, int j)
{
    return m->p + (RG2_SIZE(i) * RG2_SIZE(m->nv) + RG2_SIZE(j)) * 4;
}

/** @name Mesh operations (docs/design-format.md, "The same operations from C")
 *
 * The design file's operations on plain meshes, for callers who build meshes in C: the mesh
 * each returns equals, bit for bit, the one a design file makes of the same meshes. Each
 * checks its inputs with rg2_mesh_check (the message starts with the function and the input:
 * "rg2_mesh_merge: in[1]: mesh u: ..."), writes a new mesh into *out (free it with
 * rg2_mesh_free), and leaves *out empty (zeroed) on failure. out must not be an input: that is
 * refused (RG2_EINVAL) with *out left as it was.
 * Moving a control point or a weight is a write through rg2_mesh_at; a scalar, a write to
 * su / sv (rg2_mesh_check tells whether K stays > 0). Exactness tags (rg2_surface.tag, used
 * by rg2_check to tell which patches lie on which shape) come only from a design; a surface
 * built from these meshes is checked for G2 at every seam all the same. */
/** Keep control points first[d]..last[d] (inclusive) of direction d = 0 (u), 1 (v); first[d] =
 *  -1 keeps that direction whole. A closed direction may wrap (last up to first + n + 2) and
 *  comes out open; an open one keeps at least 4 points. RG2_EINVAL naming the range; RG2_ELIMIT
 *  when a wrapping cut passes RG2_MAX_POINTS. */
RG2_API rg2_status rg2_mesh_cut(const rg2_mesh *in, const int first[2], const int last[2], rg2_mesh *out,
                                rg2_error *err);
/** Swap u and v (points and scalars). */
RG2_API rg2_status rg2_mesh_transpose(const rg2_mesh *in, rg2_mesh *out, rg2_error *err);
/** Reverse direction dir (0 u, 1 v): points and legs in reverse order, junction scalars
 *  b' = 1 / b, g' = g / b^3; every patch is the same surface traversed backwards.
 *  RG2_EDOMAIN, naming the junction, where b', g' or K' = K / b^3 is not a finite number
 *  (b = 1e-160: K' = inf). */
RG2_API rg2_status rg2_mesh_reverse(const rg2_mesh *in, int dir, rg2_mesh *out, rg2_error *err);
/** Start the closed direction dir (0 u, 1 v) `by` control points further (any sign, modulo the
 *  count): point, junction and leg j take those of j + by; every patch is the same patch,
 *  relabelled (docs/design-format.md, "roll"). RG2_EINCOMPATIBLE for an open direction. */
RG2_API rg2_status rg2_mesh_roll(const rg2_mesh *in, int dir, int by, rg2_mesh *out, rg2_error *err);
/** How a merge sets the scalars at a seam (docs/design-format.md, "Seam rule"). PRESERVE
 *  re-solves g at both seam junctions so that every patch of every part stays what it was
 *  (only the 3 patches straddling a seam change); PLAIN keeps b and g, so the parts' end
 *  patches change when the parts' end weights differ. */
typedef enum { RG2_SEAM_PRESERVE = 0, RG2_SEAM_PLAIN = 1 } rg2_seam_rule;
/** Put n >= 1 meshes side by side along dir (0 u, 1 v), no new control points: in[t]'s last
 *  line joins in[t + 1]'s first by a new leg, and with closed != 0 the last mesh joins the first
 *  (n = 1 closes a mesh). The meshes must be open along dir and agree in the other direction
 *  (counts and scalars, 1e-12 relative), and no seam may be at a polar point.
 *  RG2_EINCOMPATIBLE naming the mesh and the first difference ("rg2_mesh_merge.merge[1]:
 *  meshes 'in[0]' and 'in[1]' do not agree in v ...: 6 vs 8 control points"); RG2_ELIMIT past
 *  RG2_MAX_POINTS; RG2_EWEIGHT / RG2_ENONFINITE where a seam junction's K is not > 0 / not a
 *  finite number (RG2_SEAM_PLAIN keeps b and g, so a seam's new leg weight can make K <= 0). */
RG2_API rg2_status rg2_mesh_merge(const rg2_mesh *const *in, int n, int dir, int closed, rg2_seam_rule rule,
                                  rg2_mesh *out, rg2_error *err);
/** How far the parts of a merge overlap at their seams: the figure behind a design file's
 *  merge note (rg2_design_note), for C callers, before or after rg2_mesh_merge. back[t] (n
 *  doubles, the caller's) is for the seam between in[t - 1] and in[t]: how far the centre of
 *  in[t]'s first control line along dir lies behind the centre of in[t - 1]'s last, in units
 *  of the spacing of the two lines next to the seam in either part (the larger figure);
 *  back[0] is the closing seam in[n - 1] | in[0] when closed, else 0. About 0 or negative
 *  where the parts leave a gap (every example: at most 0.011); above RG2_MERGE_OVERLAP the
 *  parts overlap and the transition patches bend sharply or fold (rg2_check counts the folds),
 *  so end the first part earlier or start the second later. The meshes need the same number
 *  of control points across dir (as rg2_mesh_merge); they are only read.
 *  @return RG2_EINVAL (in, a mesh or back NULL, n < 1, dir not 0 or 1, a mesh rg2_mesh_check
 *  refuses, naming it), RG2_EINCOMPATIBLE (counts across dir that differ, naming both). */
#define RG2_MERGE_OVERLAP 0.05
RG2_API rg2_status rg2_mesh_merge_overlap(const rg2_mesh *const *in, int n, int dir, int closed, double *back,
                                          rg2_error *err);
/** The blend (1 - t) a + t b of the 4-tuples and the scalars w, b, g, 0 <= t <= 1 (equal values
 *  and t = 0, 1 copy without rounding). a and b need equal counts and closedness;
 *  RG2_EINCOMPATIBLE, RG2_EDOMAIN for t outside [0, 1] or NaN, RG2_EWEIGHT / RG2_ENONFINITE
 *  where a blended junction's K is not > 0 / not a finite number. */
RG2_API rg2_status rg2_mesh_morph(const rg2_mesh *a, const rg2_mesh *b, double t, rg2_mesh *out,
                                  rg2_error *err);
/** The unit normal of the control net at point (i, j), the direction of the design file's
 *  "normal" edit: (d(i+1, j) - d(i-1, j)) x (d(i, j+1) - d(i, j-1)) of the design points
 *  d = p / W, normalized; a closed direction wraps, an open one takes the one-sided difference
 *  at its ends. It points as the surface's normal Su x Sv does where the net follows the surface
 *  (on a cylinder's net, radially out, as its Su x Sv). @return RG2_EINVAL (NULL, or i, j outside
 *  the mesh, naming the ranges), RG2_EWEIGHT (a point used with weight <= 0, named), RG2_EDOMAIN
 *  where the net has no normal: the two differences are zero, parallel, or within 1e-12 of it
 *  relative to their lengths (a polar point's collapsed row; coinciding points). */
RG2_API rg2_status rg2_mesh_net_normal(const rg2_mesh *m, int i, int j, double n[3], rg2_error *err);

/* ===================================================================================== */
/** @name Patches and surfaces (MATH.md section 4) */
/* ===================================================================================== */

/** A rational bi-cubic Bezier patch: h[r][s] is the homogeneous control point
 *  (w x, w y, w z, w) for Bernstein index r in u and s in v. Domain [0,1]^2. */
typedef struct {
    double h[4][4][4];
} rg2_patch;

#define RG2_MAX_DEGREE 5 /**< highest degree per direction of an rg2_xpatch */

/** A rational Bezier patch of degree (du, dv), 1 <= du, dv <= RG2_MAX_DEGREE: h[r][s] for
 *  r <= du, s <= dv is the homogeneous control point (w x, w y, w z, w); entries beyond the
 *  degrees are zero. Surfaces hold such patches only where a construction needs a degree above
 *  3: the general-quadratic polar caps (degree 4 or 5 in u, 3 in v; docs/poles.md). */
typedef struct {
    int du, dv;
    double h[RG2_MAX_DEGREE + 1][RG2_MAX_DEGREE + 1][4];
} rg2_xpatch;

/** A grid of patches: patch (i, j) = patch[i * nv + j]; its u = 1 edge meets patch (i+1, j)'s
 *  u = 0 edge, with scalars (b, g) of the u-direction junction between them. */
typedef struct {
    int nu, nv;          /**< patches in u and v */
    int closed_u, closed_v;
    rg2_patch *patch;    /**< nu * nv patches */
    double *bu, *gu;     /**< u junction scalars: bu[i] joins patch column i-1 to i (nu values;
                              for open u, bu[0] is unused) */
    double *bv, *gv;     /**< v junction scalars likewise (nv values) */
    int *tag;            /**< nu * nv provenance tags (shape index, -1 transition); may be NULL.
                              Owned by the surface, like every array here: rg2_surface_free
                              frees them (with free()), so a caller who tags a surface itself
                              gives it a malloc'd array of nu * nv ints. rg2_check reads a
                              patch tagged s as a piece of its shapes[s]. */
    rg2_xpatch *xp;      /**< NULL for an all-bi-3 surface; else nu * nv entries: where
                              xp[k].du > 0, patch k is that higher-degree patch (the general-
                              quadratic polar caps) and patch[k] is unused (all NaN). Read
                              patches through rg2_surface_eval / rg2_surface_patch_get to
                              handle both kinds. */
} rg2_surface;

/** The Bi-cubic Construction: rows then columns of the curve construction on 4-tuples.
 *  Patch (i, j) comes from segment i in u and j in v (open directions: segments 1..n-3).
 *  What it depends on (per direction; u shown, v alike): control points i-1..i+2 (closed, indices
 *  mod n) or i..i+3 (open), the junction scalars b, g of the same indices, and the stored
 *  weights w[i-2..i+2] (closed, mod n) or w[i..i+4] (open). So moving control point (a, b)
 *  changes at most the 4 x 4 patches (a-2..a+1 or a-3..a, likewise in v; fewer at an open
 *  border), and every other patch keeps its bits (rg2_surface_rebuild: picking and editing). */
RG2_API rg2_status rg2_surface_build(const rg2_mesh *m, rg2_surface *out, rg2_error *err);
/** rg2_surface_build into a surface that already exists (from rg2_surface_build, _copy,
 *  _rebuild, or all zeros), for editing loops (move a control point, rebuild, re-tessellate):
 *  when s holds as many patches as m gives, its memory is reused (a 1000 x 1000 mesh: 0.5 GB
 *  that would otherwise be fresh pages, docs/performance.md), else it is freed and allocated
 *  anew. The result equals rg2_surface_build's bit for bit (tags and higher-degree patches of
 *  the old surface are dropped). On failure s is left empty (freed), with the errors of
 *  rg2_surface_build. */
RG2_API rg2_status rg2_surface_rebuild(const rg2_mesh *m, rg2_surface *s, rg2_error *err);
RG2_API void rg2_surface_free(rg2_surface *s);
/** A copy of src, tags and higher-degree patches included; an empty src (zero patches) gives an
 *  empty dst. dst must not be src (RG2_EINVAL, dst left as it was, as for rg2_scalars_copy). */
RG2_API rg2_status rg2_surface_copy(const rg2_surface *src, rg2_surface *dst, rg2_error *err);
/** Bi-3 patch (i, j). Where patch (i, j) is of higher degree (s->xp, general-quadratic caps)
 *  this is the unused all-NaN placeholder, and so is whatever rg2_patch_eval, rg2_patch_point
 *  or rg2_patch_grid make of it: read such surfaces through rg2_surface_eval, rg2_surface_xpatch
 *  or rg2_surface_patch_grid. */
static inline rg2_patch *rg2_surface_patch(const rg2_surface *s, int i, int j)
{
    return s->patch + RG2_SIZE(i) * RG2_SIZE(s->nv) + RG2_SIZE(j);
}
/** The higher-degree patch (i, j), or NULL when patch (i, j) is an ordinary bi-3 patch. */
static inline const rg2_xpatch *rg2_surface_xpatch(const rg2_surface *s, int i, int j)
{
    const rg2_xpatch *x = s->xp ? s->xp + RG2_SIZE(i) * RG2_SIZE(s->nv) + RG2_SIZE(j) : RG2_NULL;
    return x && x->du > 0 ? x : RG2_NULL;
}
/** Patch (i, j) in the general form, whichever kind it is (bi-3 patches with du = dv = 3). */
RG2_API void rg2_surface_patch_get(const rg2_surface *s, int i, int j, rg2_xpatch *out);
/** Highest u- and v-degree over all patches (3, 3 for an all-bi-3 surface). */
RG2_API void rg2_surface_degree(const rg2_surface *s, int *du, int *dv);
/** Apply a row-major 4x4 matrix to every homogeneous control point of every patch, as
 *  rg2_mesh_transform does to a mesh: exact for any projective map, and the same surface as
 *  rg2_surface_build of the transformed mesh (the construction is linear in the 4-tuples). A
 *  rigid motion or scaling keeps the weights; tags and junction scalars are kept. */
RG2_API void rg2_surface_transform(rg2_surface *s, const double M[16]);
/** Box [lo, hi] of the affine control points of positive weight of every patch (where all
 *  weights are positive the surface lies inside it). Returns 0, and an empty box, when none. */
RG2_API int rg2_surface_box(const rg2_surface *s, double lo[3], double hi[3]);
/** Smallest homogeneous weight over all control points of all patches. */
RG2_API double rg2_surface_min_weight(const rg2_surface *s);

/** A bi-3 patch in the general form (du = dv = 3). */
RG2_API void rg2_xpatch_from_patch(const rg2_patch *P, rg2_xpatch *out);
/** Exact degree elevation to (du, dv) >= the patch's degrees (same rational surface).
 *  @return RG2_EINVAL when a target degree is below the patch's or above RG2_MAX_DEGREE. */
RG2_API rg2_status rg2_xpatch_elevate(const rg2_xpatch *X, int du, int dv, rg2_xpatch *out,
                                      rg2_error *err);

/* ===================================================================================== */
/** @name Evaluation */
/* ===================================================================================== */

enum {
    RG2_EVAL_NORMAL_UNDEFINED = 1u << 0,    /**< Su x Sv vanishes (collapsed edge, pole; also every
                                                 point of a side whose affine control points agree
                                                 to 1e-11 of the patch's control box and where
                                                 |Su x Sv| <= 1e-6 (|Su|^2 + |Sv|^2): the derivative
                                                 along the side is the noise of the stored points) */
    RG2_EVAL_CURVATURE_UNDEFINED = 1u << 1, /**< normal undefined: K, H, k1, k2 are 0 */
    RG2_EVAL_WEIGHT_NONPOSITIVE = 1u << 2,  /**< denominator <= 0 at this point */
    RG2_EVAL_POLE_LIMIT = 1u << 3           /**< rg2_surface_eval_limit only: the point is on a
                                                 collapsed side (a pole), n is the limit normal and
                                                 K, H, k1, k2 are taken next to the pole */
};

/** Point data of a surface evaluation. Curvature sign: n = Su x Sv / |Su x Sv|, second
 *  fundamental form against n; H = (k1 + k2) / 2 (a sphere with outward n has H = -1/R),
 *  k1 >= k2. */
typedef struct {
    double p[3];
    double su[3], sv[3];
    double suu[3], suv[3], svv[3];
    double n[3];
    double K, H, k1, k2;
    unsigned flags;
} rg2_eval;

/** Evaluate a patch at (u, v): order 0 position; 1 adds su, sv and n; 2 adds suu, suv, svv,
 *  K, H, k1, k2. Fields beyond the order are zero. */
RG2_API void rg2_patch_eval(const rg2_patch *P, double u, double v, int order, rg2_eval *out);
/** Homogeneous values: out[d][k] for d = 0 value, 1 d/du, 2 d/dv, 3 d2/du2, 4 d2/dudv, 5 d2/dv2. */
RG2_API void rg2_patch_eval_h(const rg2_patch *P, double u, double v, double out[6][4]);
/** rg2_patch_eval and rg2_patch_eval_h for a patch of any degree. */
RG2_API void rg2_xpatch_eval(const rg2_xpatch *X, double u, double v, int order, rg2_eval *out);
RG2_API void rg2_xpatch_eval_h(const rg2_xpatch *X, double u, double v, double out[6][4]);
/** Evaluate patch (i, j) of a surface, whichever kind it is (rg2_patch_eval or rg2_xpatch_eval). */
RG2_API void rg2_surface_eval(const rg2_surface *s, int i, int j, double u, double v, int order,
                              rg2_eval *out);
RG2_API void rg2_surface_eval_h(const rg2_surface *s, int i, int j, double u, double v,
                                double out[6][4]);
/** rg2_surface_eval, except at order >= 1 on a side of the patch that collapses to one point (a
 *  pole; the side's control points agree to 1e-11 of the patch's control box), where the normal
 *  is undefined: there n is the limit of the normals as the point approaches the pole (for a
 *  side v = 0, Suv x Sv normalised, oriented as the normals next to it), K, H, k1 and k2
 *  (order 2) are those 3e-5 inside the patch, and flags has RG2_EVAL_POLE_LIMIT instead of
 *  RG2_EVAL_NORMAL_UNDEFINED and RG2_EVAL_CURVATURE_UNDEFINED. These are the normals and
 *  curvatures that rg2_tessellate gives its pole vertices, for a viewer's shading or picking.
 *  Where the limit is undefined too (Suv x Sv = 0), n is the normal 3e-5 inside; where that is
 *  undefined as well (a NaN parameter), the result stays undefined (no RG2_EVAL_POLE_LIMIT).
 *  Elsewhere the same bits as rg2_surface_eval. docs/poles.md. */
RG2_API void rg2_surface_eval_limit(const rg2_surface *s, int i, int j, double u, double v, int order,
                                    rg2_eval *out);
/** Normal curvature in the tangent direction t = a su + c sv of an order-2 evaluation (with
 *  the sign of its normal n); 0 when t is the zero vector (a = c = 0, for one). */
RG2_API double rg2_eval_normal_curvature(const rg2_eval *e, double a, double c);

/* ===================================================================================== */
/** @name Picking: the closest surface point, the first hit of a ray (src/locate.c)
 *
 * Both search the whole surface, not only near a guess: branch and bound over de Casteljau
 * pieces of the patches (a piece lies inside the hull of its control points, all weights being
 * positive), then Newton on the exact patch, so the point found is exact to the last bits and
 * no other point of the surface beats it by more than the tolerance: 1e-10 of (the surface's
 * box diagonal + the query point's distance from the box's centre). What is proven is reported
 * in rg2_hit.bound. Near the answer, certificates rule whole rectangles of a patch out at once
 * (the squared distance's numerator shown convex, or the ray's residuals shown one-to-one, by
 * Bernstein bounds of their derivatives; docs/picking.md). A locator reads its surface: keep the
 * surface alive and unchanged while it is used (after rg2_surface_rebuild or _transform, build a
 * new locator). Queries on one locator may run in several threads at once (each query allocates
 * its own search). */
/* ===================================================================================== */

/** Pieces one query takes at most (its time is bounded: about 0.1 s): past it the search stops
 *  with the best point so far and what it proved (rg2_hit.bound). Only a query that a whole
 *  region answers nearly equally well comes near it (a point on a torus's axis: 16 463 pieces;
 *  at a sphere's centre the bounds prove the distance to one ulp after 23). */
#define RG2_LOCATE_MAX_PIECES 50000

typedef struct rg2_locator rg2_locator;

/** A point found on a surface. */
typedef struct {
    int i, j;        /**< patch (i, j); -1, -1 when none (a ray that misses) */
    double u, v;     /**< the point's parameters in patch (i, j), in [0, 1] */
    double p[3];     /**< the point, rg2_surface_eval at (u, v) */
    double n[3];     /**< unit normal there (rg2_surface_eval_limit: at a pole the limit normal);
                          zero where undefined */
    unsigned flags;  /**< rg2_surface_eval_limit's flags at (u, v) (RG2_EVAL_*) */
    double dist;     /**< closest: |p - x|; ray: t with p = o + t d (INFINITY when none) */
    double bound;    /**< proven: closest, no surface point is nearer x than bound; ray, the ray
                          meets the surface nowhere with t < bound (normally tmax when it misses).
                          bound <= dist, and normally dist - bound <= the tolerance (scaled by
                          1 / |d| for a ray); more when RG2_LOCATE_MAX_PIECES stopped the search. */
} rg2_hit;

/** Prepare a surface for picking: a tree of the patches' control boxes, each with a slab along
 *  its patches' normal (about 224 bytes a patch).
 *  @return RG2_EINVAL (NULL, no patches), RG2_ENONFINITE (a control value, naming its patch),
 *  RG2_EWEIGHT (a control weight <= 0, naming the patch and point: the search needs the hull
 *  property), RG2_EDOMAIN (control points beyond 1e60, one whose h / w overflows, or spanning
 *  less than 1e-60: the numeric range of rg2_tessellate; past about 1e+-77 the searches' fourth
 *  powers leave the double range), RG2_ENOMEM. */
RG2_API rg2_status rg2_locator_build(const rg2_surface *s, rg2_locator **out, rg2_error *err);
RG2_API void rg2_locator_free(rg2_locator *L);
/** The surface point nearest x (the first met on ties), with its patch, parameters and normal.
 *  A nearest point inside a patch has p - x along the normal; on a patch side or corner (the
 *  surface's border, or where two patches' nearest points meet) it need not. Cost: a descent of
 *  the locator's tree of patch boxes plus the subdivision near the answer (about 14 us on a
 *  torus of 48 patches, 48 us on one of 40 000; docs/picking.md).
 *  @return RG2_EINVAL (NULL), RG2_ENONFINITE (x), RG2_EDOMAIN (a coordinate of x beyond 1e100,
 *  the numeric range of docs/robustness.md), RG2_ENOMEM. */
RG2_API rg2_status rg2_locator_closest(const rg2_locator *L, const double x[3], rg2_hit *out, rg2_error *err);
/** The first point where the ray o + t d, 0 <= t <= tmax, meets the surface (out->i = -1 when it
 *  does not); d need not be unit (t is in units of d). tmax = INFINITY for no limit. About 5 us
 *  on a torus of 48 patches, 4.4 us on one of 40 000.
 *  @return RG2_EINVAL (NULL), RG2_ENONFINITE (o, d), RG2_EDOMAIN (d = 0, or its largest component
 *  outside [1e-100, 1e100]; a coordinate of o beyond 1e100; tmax NaN or < 0), RG2_ENOMEM. */
RG2_API rg2_status rg2_locator_ray(const rg2_locator *L, const double o[3], const double d[3], double tmax,
                                   rg2_hit *out, rg2_error *err);

/* ===================================================================================== */
/** @name Shapes (exact basic shapes, paper section 3.1, MATH.md section 5) */
/* ===================================================================================== */

/* A partition of one direction of a shape.
 * Circle directions (angles): the arcs the surface covers, in radians, each in [0.005, pi)
 *   (rg2_partition_check refuses smaller arcs: their seams lose G2 accuracy, docs/robustness.md),
 *   starting at angle `start`. Closed: they must sum to 2 pi. Open: the mesh gets two extra
 *   control points at each end whose arcs (copies of the end arcs) carry data only, so the
 *   produced patches cover exactly the given arcs.
 * Polynomial directions (knots): the knot values v_0 < v_1 < ... < v_m bounding the m
 *   segments the surface covers; open only; the mesh gets extra knots at each end (mirrored
 *   end intervals) that carry data only. */
typedef enum {
    RG2_PART_ANGLES = 0,      /**< arcs of a circle direction (see above) */
    RG2_PART_KNOTS = 1,       /**< knots of a polynomial direction (see above) */
    RG2_PART_ANGLES_FULL = 2, /**< open circle direction given with its data-only arcs: n + 1
                                   arcs alpha_{-1}..alpha_{n-1} for n control points (layout of
                                   rg2_scalars_from_angles); `start` is the start angle of arc 1,
                                   the first produced arc; the surface covers arcs 1..n-3 */
    RG2_PART_KNOTS_FULL = 3   /**< polynomial direction given with its data-only knots: n + 2
                                   knots v_{-1}..v_n for n control points (layout of
                                   rg2_scalars_from_knots); the surface covers [v_1, v_{n-2}] */
} rg2_partition_kind;
typedef struct {
    rg2_partition_kind kind;
    int closed;           /**< angles only */
    int n;                /**< number of values: arcs (angles) or knots (knots, n >= 2) */
    const double *values; /**< n angles (radians, each in [0.005, pi)) or n increasing knots */
    double start;         /**< angle of the start of the first arc (angles only) */
} rg2_partition;

typedef enum {
    RG2_SHAPE_TORUS,          /**< R, r: ((R + r cv) cu, (R + r cv) su, r sv); u, v circles */
    RG2_SHAPE_CYCLIDE,        /**< a, c, mu (Dupin cyclide, b^2 = a^2 - c^2 > 0); u, v circles */
    RG2_SHAPE_SPHERE,         /**< radius: family-2 band, v in (0, 1): 0 south, 1 north pole */
    RG2_SHAPE_CYLINDER,       /**< radius: (R cu, R su, v); v knots = heights */
    RG2_SHAPE_CONE,           /**< slope k: (v cu, v su, k v); v knots = radii */
    RG2_SHAPE_HYPERBOLOID1_RULED, /**< a, c: (cu - v su, su + v cu, v); x^2 + y^2 - z^2 = 1 */
    RG2_SHAPE_HYPERBOLOID1,   /**< a, c: ((1+v^2) cu, (1+v^2) su, 1 - v^2, 2v), v > 0 */
    RG2_SHAPE_HYPERBOLOID2,   /**< a, c: (2v cu, 2v su, 1 + v^2, 1 - v^2), |v| < 1 */
    RG2_SHAPE_PARABOLOID,     /**< A, B: elliptic paraboloid (A v cu, B v su, v^2) */
    RG2_SHAPE_HYPAR,          /**< A, B: hyperbolic paraboloid (A u, B v, u^2 - v^2); u, v knots */
    RG2_SHAPE_ELLIPSOID,      /**< a, b, c: the sphere band scaled by (a, b, c); v as sphere */
    RG2_SHAPE_COUNT
} rg2_shape_kind;

/** A named shape with its parameters and placement. */
typedef struct {
    rg2_shape_kind kind;
    double param[4];   /**< shape parameters in the order documented per kind */
    double xform[16];  /**< row-major 4x4 matrix applied to every homogeneous 4-tuple */
} rg2_shape;

/** Name ("torus", ...) of a shape kind; NULL for an unknown kind. Parameter names, count and
 *  defaults: rg2_shape_describe. */
RG2_API const char *rg2_shape_name(rg2_shape_kind kind);
/** The kind named `name` ("torus", ...). @return RG2_EINVAL for an unknown name (listing the
 *  known ones), a NULL name or a NULL kind, the message saying which. */
RG2_API rg2_status rg2_shape_from_name(const char *name, rg2_shape_kind *kind, rg2_error *err);
/** Initialise a shape with default parameters and the identity placement. */
RG2_API void rg2_shape_init(rg2_shape *s, rg2_shape_kind kind);
/** Build the placed control mesh of the shape over the partitions (u, v) (docs/shapes.md).
 *  @return RG2_EDOMAIN / RG2_ENONFINITE for a bad parameter (naming it), RG2_EINVAL for a
 *  partition of the wrong kind or an empty one, the rg2_partition_check codes, RG2_EDOMAIN for
 *  a singular placement or a knot outside the shape's range (hyperboloids), RG2_EWEIGHT for a
 *  placement that turns a positive control weight <= 0 (naming the point and the weight). */
RG2_API rg2_status rg2_shape_mesh(const rg2_shape *s, const rg2_partition *pu,
                                  const rg2_partition *pv, rg2_mesh *out, rg2_error *err);
/** Implicit function of the placed shape at x (0 on the surface); gradient into grad (nullable). */
RG2_API double rg2_shape_implicit(const rg2_shape *s, const double x[3], double grad[3]);
/** The shape's own homogeneous parameterization h(u, v) (placed). */
RG2_API void rg2_shape_param(const rg2_shape *s, double u, double v, double h[4]);
/** Apply a row-major 4x4 matrix to every 4-tuple of a mesh (exact transform). */
RG2_API void rg2_mesh_transform(rg2_mesh *m, const double M[16]);

/* Parameters per kind (param[0..3], defaults in rg2_shape_describe):
 *   torus R, r (0 < r < R)            cyclide a, c, mu (0 <= c < a, mu > 0)
 *   sphere radius                     cylinder radius          cone slope k (!= 0)
 *   hyperboloid1_ruled a, c: (a (cu - v su), a (su + v cu), c v); (x^2+y^2)/a^2 - z^2/c^2 = 1
 *   hyperboloid1 a, c: (a (1+v^2) cu, a (1+v^2) su, c (1 - v^2), 2v), knots v > 0
 *   hyperboloid2 a, c: (2 a v cu, 2 a v su, c (1 + v^2), 1 - v^2), knots |v| < 1;
 *                      z^2/c^2 - (x^2+y^2)/a^2 = 1
 *   paraboloid A, B                   hypar A, B: z = x^2/A^2 - y^2/B^2
 *   ellipsoid a, b, c: x^2/a^2 + y^2/b^2 + z^2/c^2 = 1
 * With the default parameters (all 1; the ellipsoid 2, 1.5, 1) the quadrics are the ones listed
 * in the enum. */

/** Static description of a shape kind (for listings, the CLI and design files). */
typedef struct {
    const char *name;              /**< "torus", ... (rg2_shape_name) */
    int n_params;                  /**< used entries of rg2_shape.param */
    const char *param_names[4];
    double param_defaults[4];
    rg2_partition_kind dir_kind[2]; /**< u, v: RG2_PART_ANGLES (circle) or RG2_PART_KNOTS */
    double default_range[2][2];    /**< u, v: default angle range (radians) or knot range */
    int default_closed[2];         /**< u, v: closed by default (full circles) */
    int default_segments[2];       /**< u, v: default number of arcs / knot intervals */
    const char *param_text;        /**< the homogeneous parameterization h(u, v) as text */
    const char *implicit_text;     /**< the implicit equation as text */
} rg2_shape_desc;

/** Description of a kind; NULL for an unknown kind. */
RG2_API const rg2_shape_desc *rg2_shape_describe(rg2_shape_kind kind);

/** Implicit function with gradient and row-major 3x3 Hessian (each nullable). */
RG2_API double rg2_shape_implicit2(const rg2_shape *s, const double x[3], double grad[3],
                                   double hess[9]);

/** Number of segments (patches) a partition produces in its direction, from its kind and count
 *  alone; 0 for a NULL partition or values, an unknown kind or too few values. The values are not
 *  read: an arc of pi or knots out of order still count (rg2_partition_check refuses them). */
RG2_API int rg2_partition_num_segments(const rg2_partition *p);
/** Check a partition (counts, angles in [0.005, pi), closed sums = 2 pi, open sums <= 2 pi,
 *  increasing knots); `what` prefixes the message ("u", "v"). */
RG2_API rg2_status rg2_partition_check(const rg2_partition *p, const char *what, rg2_error *err);
/** Shape parameter at local parameter t in [0, 1] of produced segment seg: the arc map
 *  theta(t) = theta_a + beta + 2 atan(tan(beta/2) (2t - 1)) (beta = alpha/2) of MATH.md
 *  section 2 for circle directions, v_seg + t (v_{seg+1} - v_seg) for knot directions. */
RG2_API double rg2_partition_map(const rg2_partition *p, int seg, double t);
/** Whether an angle total given in degrees is 2 pi, pi or pi / 2, or pi / 4, pi / 3, pi / 6,
 *  3 pi / 2 or 2 pi / 3, to 1e-3 (relative): a full, half or quarter circle (or 45, 60, 30, 270,
 *  120 degrees) typed in radians. Returns its name ("2 pi (a full circle in radians)"), or NULL. A design file refuses such a total of arcs or 'from'..'to' span unless
 *  "closed" is stated, and `rg2 shape` such --D-angles or --D-sweep unless --D-open is given. */
RG2_API const char *rg2_angle_total_in_radians(double degrees);
/** A partition of [lo, hi] into n equal arcs (angles, radians) or knot intervals, written to
 *  values (capacity cap >= n + 1). Closed angle partitions ignore hi (full circle from lo).
 *  @return RG2_EINVAL for a kind other than RG2_PART_ANGLES / RG2_PART_KNOTS, n < 1 or cap <= n;
 *          RG2_ENONFINITE for a NaN or infinite lo or hi; then rg2_partition_check's codes. */
RG2_API rg2_status rg2_partition_equal(rg2_partition *p, rg2_partition_kind kind, int closed,
                                       double lo, double hi, int n, double *values, int cap,
                                       rg2_error *err);

/* Generic family constructors (paper section 3.1, MATH.md sections 3 and 5): the control
 * 4-tuple of mesh point (i, j) is the same linear combination of products of per-direction
 * control coefficients as h(u, v) is of the basis functions. A circle direction (angle
 * partition) has the basis (1, cos, sin), a polynomial direction (knot partition) the basis
 * (1, t, t^2, t^3). The meshes are not placed (no transform). */

/** General product form: h_k(u, v) = sum_{a, b} coef[k][a][b] f_a(u) g_b(v) with f, g the
 *  basis of the partition's kind; for circle directions indices 3 must have zero coefficients. */
RG2_API rg2_status rg2_product_mesh(const double coef[4][4][4], const rg2_partition *pu,
                                    const rg2_partition *pv, rg2_mesh *out, rg2_error *err);
/** Family 1: h_k = a[k] . (1, cu, su, cv, sv, cu cv, su cv, cu sv, su sv); pu, pv angles. */
RG2_API rg2_status rg2_family1_mesh(const double a[4][9], const rg2_partition *pu,
                                    const rg2_partition *pv, rg2_mesh *out, rg2_error *err);
/** Family 2: h_k = sum_{s=0..3} (c[k][0][s] + c[k][1][s] cu + c[k][2][s] su) v^s;
 *  pu angles, pv knots. */
RG2_API rg2_status rg2_family2_mesh(const double c[4][3][4], const rg2_partition *pu,
                                    const rg2_partition *pv, rg2_mesh *out, rg2_error *err);
/** Family 3: h_k = sum_{r, s = 0..3} A[k][r][s] u^r v^s; pu, pv knots. */
RG2_API rg2_status rg2_family3_mesh(const double A[4][4][4], const rg2_partition *pu,
                                    const rg2_partition *pv, rg2_mesh *out, rg2_error *err);
/** The coefficient tensor of a named shape's (unplaced) parameterization in the layout of
 *  rg2_product_mesh; validates the parameters. */
RG2_API rg2_status rg2_shape_coeffs(const rg2_shape *s, double coef[4][4][4], rg2_error *err);

/* Homogeneous weights of the built patches: CAD export needs H_rs,4 > 0. */
enum { RG2_SHAPE_WARN_WEIGHT = 1u << 0 /**< some patch weight H_rs,4 <= 0 */ };
typedef struct {
    double min_weight;  /**< smallest H_rs,4 over all patches */
    int n_nonpositive;  /**< patches with some H_rs,4 <= 0 */
    int patch_i, patch_j; /**< the patch holding min_weight */
    unsigned flags;     /**< RG2_SHAPE_WARN_* */
} rg2_weight_report;
RG2_API void rg2_surface_weight_report(const rg2_surface *s, rg2_weight_report *rep);
/** Mesh + Bi-cubic Construction in one call; rep (nullable) gets the weight report. Every
 *  patch is tagged 0 (out->tag): rg2_check(out, 1, s, NULL, 1, ...) checks it against s. */
RG2_API rg2_status rg2_shape_surface(const rg2_shape *s, const rg2_partition *pu,
                                     const rg2_partition *pv, rg2_surface *out,
                                     rg2_weight_report *rep, rg2_error *err);

/* Placement matrices (row-major 4x4, applied to column 4-tuples: p' = M p). */
RG2_API void rg2_xform_identity(double M[16]);
/** out = A B (apply B first); out may alias A or B. */
RG2_API void rg2_xform_mul(const double A[16], const double B[16], double out[16]);
RG2_API void rg2_xform_translate(double M[16], double x, double y, double z);
RG2_API void rg2_xform_scale(double M[16], double sx, double sy, double sz);
/** Rotation by angle (radians) about the axis (ax, ay, az) through the origin, counter-clockwise
 *  seen from the axis's tip (right-hand rule). A zero or NaN axis gives the identity (no error:
 *  check the axis first if it comes from user input). */
RG2_API void rg2_xform_rotate(double M[16], double ax, double ay, double az, double angle);
/** Frame placement: the shape's z axis goes to `axis` (normalised) and its origin to `centre`
 *  (the rotation taking z to axis about z x axis; for an axis along -z, the half turn about x).
 *  A zero or NaN axis keeps the orientation (a translation only; no error: check the axis first
 *  if it comes from user input). */
RG2_API void rg2_xform_place(double M[16], const double centre[3], const double axis[3]);
/** Inverse of a 4x4 matrix; RG2_EDOMAIN if singular, also in double precision (an inverse
 *  entry beyond the double range, as for a scale of 1e-310: inv is left as it was),
 *  RG2_ENONFINITE for NaN/inf. */
RG2_API rg2_status rg2_xform_invert(const double M[16], double inv[16], rg2_error *err);

/* Bi-cubic NURBS import: control points P_ij, weights w_ij, knot vectors U (nu + 4 values)
 * and V (nv + 4), non-decreasing. The domain [U_3, U_nu] x [V_3, V_nv] must have strictly
 * increasing knots (a repeated interior knot is refused with RG2_EDOMAIN naming it); the end
 * knots may be clamped (repeated) or not: clamped ends are unclamped exactly by blossoming the
 * end pieces at virtual knots continuing the end intervals. Patch (i, j) of the built surface
 * is the NURBS over [U_{i+3}, U_{i+4}] x [V_{j+3}, V_{j+4}] with linear parameter maps.
 * Weights that differ much near a clamped end make those extrapolated points cancel: when the
 * estimated rounding error exceeds 1e-10 of the coordinates' scale the NURBS is refused with
 * RG2_EDOMAIN naming two weights (docs/shapes.md). Knots whose used intervals leave the double
 * range are refused with RG2_EDOMAIN naming them: an interval of knots_u[1..nu+2] longer than
 * the largest double, an end interval continued twice past a clamped end beyond it, or
 * neighbouring intervals whose junction scalars are not finite (1e-300 next to 1: K = inf).
 * knots_u[0] and knots_u[nu+3] (likewise in v) are never read. A clamped end whose control line
 * is one point p (a pole; weights free) gives rg2_surface_build's patches a side that is p only to
 * the rounding of the extrapolated points (growing with the weights' ratio along it);
 * rg2_nurbs_surface and a design's nurbs output make that side p exactly (docs/shapes.md,
 * "Poles"). */
typedef struct {
    int nu, nv;             /**< control points (>= 4 each) */
    const double *points;   /**< nu * nv * 3: points[(i * nv + j) * 3 + d] */
    const double *weights;  /**< nu * nv weights > 0, or NULL for all 1 */
    const double *knots_u;  /**< nu + 4 */
    const double *knots_v;  /**< nv + 4 */
} rg2_nurbs;
RG2_API rg2_status rg2_nurbs_mesh(const rg2_nurbs *nb, rg2_mesh *out, rg2_error *err);
/** The surface of a NURBS: rg2_surface_build of rg2_nurbs_mesh's mesh, with every control point
 *  of a pole side (a clamped end whose control line has exactly the same x, y and z) made that
 *  point, h = h_w p with its own weight; every other control value and every weight bit for bit
 *  rg2_surface_build's. The same surface as a design's nurbs output. *out is zeroed first.
 *  @return as rg2_nurbs_mesh (RG2_EINVAL for a NULL nb or out), then as rg2_surface_build. */
RG2_API rg2_status rg2_nurbs_surface(const rg2_nurbs *nb, rg2_surface *out, rg2_error *err);
/** rg2_nurbs_mesh from a JSON text {"nu", "nv", "points": [[x, y, z], ...] (u-major),
 *  "weights" (optional), "knots_u", "knots_v"}: the spec of `rg2 shape nurbs` and of a design
 *  file's nurbs operation, read by the same code. `name` (a file name, say; NULL: "nurbs", as
 *  rg2_design_parse's NULL name is "design") starts the messages, which name the offending item
 *  (name:line:col for malformed JSON, nurbs.points[k], knots_u[k]). *out is zeroed first.
 *  @return RG2_EINVAL for a NULL text or out (the message names which), then as rg2_design_parse
 *  for the text (RG2_EPARSE, RG2_ELIMIT), then as rg2_nurbs_mesh. */
RG2_API rg2_status rg2_nurbs_parse(const char *json, size_t len, const char *name, rg2_mesh *out,
                                   rg2_error *err);


/* ===================================================================================== */
/** @name Design (JSON design files and operations, paper section 4) */
/* ===================================================================================== */

/* A design: shape meshes and operations on them (shape, cut, transpose, reverse, merge, edit,
 * transform, morph) read from a JSON design file (docs/design-format.md), built into one or
 * more patch surfaces. Every patch carries a provenance tag (rg2_surface.tag): the index of the
 * shape it reproduces exactly, or -1 for a transition patch. A patch is tagged when its 4 x 4
 * control block is a consecutive block of a shape's own mesh (in any orientation: transposed,
 * reversed) and its construction stencils equal that mesh's (to 1e-14), i.e. it is the shape's
 * own patch. The shape list holds the shapes of the file followed by the transformed copies
 * that `transform` operations create ("label@meshes.name"). The design owns everything the
 * accessors return. */
typedef struct rg2_design rg2_design;

/** Largest text file rg2 reads (design files, NURBS files): 64 MiB. */
#define RG2_TEXT_MAX_BYTES (64u << 20)
/** Read a whole text file into a NUL-terminated buffer (*out, release with free; *len its
 *  length, len may be NULL). RG2_EIO when it cannot be opened or read (also an empty name),
 *  RG2_ELIMIT past RG2_TEXT_MAX_BYTES, RG2_ENOMEM, RG2_EINVAL for a NULL path or out; the
 *  message names the file. */
RG2_API rg2_status rg2_read_text(const char *path, char **out, size_t *len, rg2_error *err);
/** The one of names[0..n) closest to word by edit distance, if within min(3, strlen(word) / 2 + 1)
 *  edits (the first of equals), else NULL: the "did you mean" of the design parser's unknown
 *  keys and of the command line's unknown shape names and commands. */
RG2_API const char *rg2_closest_name(const char *word, const char *const *names, int n);

/** The supported numeric range of every number a design (or `rg2 shape`, `rg2 curve`) gives:
 *  finite, and 0 or a magnitude within the limits of docs/robustness.md "Numeric range"
 *  (1e-100 .. 1e100).
 *  RG2_ENONFINITE / RG2_EDOMAIN, the message starting with `what` (nullable). */
RG2_API rg2_status rg2_number_check(double x, const char *what, rg2_error *err);
/** The supported range of a mesh's design points p_{1..3} / p_4: coordinates up to
 *  the largest supported magnitude, bounding-box diagonal at least the smallest and at least
 *  1e-12 of the largest coordinate (what every output mesh of a design must satisfy; below
 *  that the coordinates' rounding takes the shape apart; points of weight p_4 = 0, at infinity, have no
 *  coordinates and are skipped). RG2_EDOMAIN, the message starting with `what` (nullable); also
 *  for a mesh with no point of weight != 0 (rg2_mesh_init's), which has no design points. */
RG2_API rg2_status rg2_mesh_check_range(const rg2_mesh *m, const char *what, rg2_error *err);

/** Read and build a design file. On failure *out is NULL and err names the offending item
 *  (file, line and column for syntax errors, JSON path for semantic ones). A NULL path or out
 *  is RG2_EINVAL, as a NULL text or out is for rg2_design_parse. */
RG2_API rg2_status rg2_design_load(const char *path, rg2_design **out, rg2_error *err);
/** The same from a JSON text in memory; `name` is used in messages. The text (as the file of
 *  rg2_design_load) is UTF-8 JSON with no NUL byte (RG2_EPARSE naming the line and column of the
 *  first byte that is not; a UTF-8 byte-order mark is skipped), nested at most 1000 deep
 *  (RG2_ELIMIT); a non-zero number literal too small for a double (below 1e-323, e.g. 1e-400,
 *  which would read as 0) is RG2_EDOMAIN naming its line and column, as in rg2_nurbs_parse. */
RG2_API rg2_status rg2_design_parse(const char *json, size_t len, const char *name,
                                    rg2_design **out, rg2_error *err);
RG2_API void rg2_design_free(rg2_design *d);
/** Built surfaces (one per output mesh of the design), with tags set. The accessors below
 *  take a NULL design (or an index out of range) as empty: 0, NULL or -1. */
RG2_API int rg2_design_num_surfaces(const rg2_design *d);
RG2_API const rg2_surface *rg2_design_surface(const rg2_design *d, int k);
/** The control mesh surface k was built from; for a capped output, the body mesh before its
 *  caps (rg2_design_cap gives the caps' options). */
RG2_API const rg2_mesh *rg2_design_mesh(const rg2_design *d, int k);
/** The shapes the design uses; surface tags index this list. */
RG2_API int rg2_design_num_shapes(const rg2_design *d);
RG2_API const rg2_shape *rg2_design_shape(const rg2_design *d, int k);
RG2_API const char *rg2_design_shape_label(const rg2_design *d, int k);
/** Notes on the design that are not errors, in file order (docs/design-format.md, "merge"): a
 *  merge whose closed rows meet at a seam turned about their axis (the circles start at other
 *  angles) or running opposite ways round, which twists or pinches the transitions; a merge whose
 *  parts overlap, their control lines running back at the seam, which makes the transitions bend
 *  sharply or fold; a merge with a control weight <= 0 on a line next to a seam (a hyperboloid's
 *  data-only end rows mirrored past v = 0, say), where the transitions can pass through infinity
 *  (given instead of the other two, which measure the points p / w); each names the merge entry,
 *  both meshes, the angle, the distance or the weight and the way out. rg2 info and rg2 build
 *  print them. */
RG2_API int rg2_design_num_notes(const rg2_design *d);
RG2_API const char *rg2_design_note(const rg2_design *d, int k);
/** Name (in the design file) of the mesh surface k was built from. */
RG2_API const char *rg2_design_mesh_name(const rg2_design *d, int k);
/** Shape control point (i, j) of output mesh k came from (unchanged), or -1 if it was edited,
 *  blended or is out of range. */
RG2_API int rg2_design_point_shape(const rg2_design *d, int k, int i, int j);
/** Write the output control meshes as JSON (design coordinates d = p_{1..3} / p_4, weights
 *  W = p_4, scalars w, b, g, provenance and patch tags; docs/design-format.md). Writes a
 *  temporary file next to path, then renames (as rg2_export_file). @return RG2_EINVAL for a NULL
 *  design or a NULL or empty path (as rg2_design_load's NULL path), RG2_EIO if the file cannot be
 *  written (nothing is left), RG2_ENOMEM. */
RG2_API rg2_status rg2_design_write_mesh(const rg2_design *d, const char *path, rg2_error *err);


/* ===================================================================================== */
/** @name Poles (polar configurations, caps, Moebius, paper section 5)
 *
 * A polar configuration (MATH.md section 7) is an open-v mesh whose first and/or last row is
 * collapsed to a single polar point (a triangle fan); the construction on it yields the band
 * between the two rings next to the poles, and the caps close the band at the poles.
 * See docs/poles.md for the choices made where the paper is silent.
 */
/* ===================================================================================== */

/** Knots of a polar configuration from the interior knots v_1 < ... < v_m in (0, 1), m >= 2:
 *  writes the m + 4 knots v_{-1} = v_1 / (v_1 - 1), v_0 = 0, v_1, ..., v_m, v_{m+1} = 1,
 *  v_{m+2} = 1 / v_m (the layout of rg2_scalars_from_knots, open, for m + 2 points).
 *  @return RG2_EDOMAIN for a knot outside (0, 1) or not increasing, naming it; RG2_EINVAL for
 *  m < 2 (telling the m given) or a NULL v or knots (naming which). */
RG2_API rg2_status rg2_polar_knots(const double *v, int m, double *knots, rg2_error *err);

/** Polar control mesh of the unit sphere (family 2, MATH.md eq. 13): u a closed circle
 *  partition (n_alpha arcs summing to 2 pi, junction 0 at angle theta0), v the polar knots of
 *  rg2_polar_knots(v, m). The mesh has n_alpha x (m + 2) points; row 0 is the south polar
 *  point (0, 0, Zs, 1), row m + 1 the north polar point (0, 0, Zn, 1) (exactly collapsed).
 *  The surface built from it is the band v in [v_1, v_m] of the sphere, exactly.
 *  M (nullable): row-major 4x4 placement applied to every 4-tuple (exact; rows stay collapsed).
 *  Free out with rg2_mesh_free. @return RG2_EINVAL for a NULL alpha or n_alpha < 3 (telling the
 *  n_alpha given), RG2_ENONFINITE for a non-finite entry of M, RG2_ELIMIT for m > RG2_MAX_POINTS
 *  - 2, then as rg2_polar_knots and rg2_circle_coeffs. */
RG2_API rg2_status rg2_polar_sphere_mesh(const double *alpha, int n_alpha, double theta0,
                                         const double *v, int m, const double *M, rg2_mesh *out,
                                         rg2_error *err);

/** Polar configuration of a shape, the design file's `polar` (docs/poles.md), the same bits:
 *  the shape's own control mesh over the u partition pu and the full polar knot vector of the
 *  interior knots v_1 < ... < v_m (m >= 2), its polar rows collapsed to one point exactly.
 *  Sphere, ellipsoid: v in (0, 1), both poles, the knots of rg2_polar_knots (for the unit
 *  sphere the mesh agrees with rg2_polar_sphere_mesh's to rounding, a few ulps, not bit for bit).
 *  Paraboloid, hyperboloid2 (the pole at v = 0): all v > 0, knots -v_1, 0, v_1..v_m, v_m + d,
 *  v_m + 2d (d = v_m - v_{m-1}), the pole row 0; or all v < 0, knots v_1 - 2d, v_1 - d,
 *  v_1..v_m, 0, -v_m (d = v_2 - v_1), the pole row m + 1. The shape's placement applies.
 *  Free out with rg2_mesh_free; empty (zeroed) on failure. @return RG2_EINVAL for a NULL
 *  argument, another kind of shape or m < 2; RG2_ELIMIT for m > RG2_MAX_POINTS - 4 (the m + 4
 *  knots of the partition);
 *  RG2_ENONFINITE for a NaN or infinite knot; RG2_EDOMAIN for knots out of order, on both sides
 *  of 0 or outside (0, 1) (sphere, ellipsoid), naming the knot by its 0-based index in v, as other
 *  messages count ("rg2_polar_mesh: polar knots: knot 1 = ..." for v[1], the paper's v_2), or whose data-only end knots leave the double range; then as rg2_shape_mesh. */
RG2_API rg2_status rg2_polar_mesh(const rg2_shape *s, const rg2_partition *pu, const double *v, int m,
                                  rg2_mesh *out, rg2_error *err);

/** 1 if row j (all i) of the mesh is one point: every 4-tuple projectively equal to the first
 *  one to 1e-12 relative to the mesh size; 0 otherwise (or for a bad j). */
RG2_API int rg2_mesh_row_collapsed(const rg2_mesh *m, int j);

/** Move a polar point: end 0 sets every 4-tuple of row 0, end 1 of row nv - 1, to p
 *  (a homogeneous 4-tuple, p[3] > 0). Moving a polar point moves the whole collapsed row.
 *  @return RG2_EINVAL (bad end, closed v), RG2_ENONFINITE, RG2_EWEIGHT (p[3] <= 0). */
RG2_API rg2_status rg2_polar_set_point(rg2_mesh *m, int end, const double p[4], rg2_error *err);

/** Moebius pole placement of eq. (16), M(z) = (z - b) / (b z + 1), as the linear map of the
 *  sphere's 4-tuples it induces (divided by 1 + b^2): a rotation about the y-axis taking the
 *  south pole (0,0,-1) to (2b, 0, b^2 - 1) / (1 + b^2) and the north pole to
 *  (-2b, 0, 1 - b^2) / (1 + b^2). R (nullable, row-major 3x3 rotation) is applied after it.
 *  Writes the row-major 4x4 matrix to M; finite for every finite b. */
RG2_API void rg2_mobius_matrix(double b, const double *R, double M[16]);

/** The general Moebius transformation of the unit sphere (a Lorentz map of its 4-tuples,
 *  rotation composed with a boost) that takes the south pole (0,0,-1) to `south` and the north
 *  pole (0,0,1) to `north`: any two distinct points of the unit sphere (need not be antipodal).
 *  Points within the tolerance below are normalized first: the poles go to south / |south|
 *  and north / |north|. Writes the row-major 4x4 matrix to M.
 *  @return RG2_EDOMAIN if a point is not on the unit sphere (1e-9) or the two coincide. */
RG2_API rg2_status rg2_mobius_poles_matrix(const double south[3], const double north[3],
                                           double M[16], rg2_error *err);

/** Apply a Moebius matrix (of the unit sphere) to a sphere-like mesh whose reference sphere
 *  has the given center and radius: every 4-tuple p becomes T M T^-1 p, T = translate(center)
 *  scale(radius). An exact sphere mesh stays exact (same sphere, poles moved); a free-form
 *  sphere-like mesh moves with its poles.
 *  @return RG2_EWEIGHT if a resulting weight is not > 0 (naming the control point), then the
 *  mesh is unchanged; RG2_EDOMAIN for radius <= 0; RG2_ENONFINITE for a NaN or infinite
 *  radius, center or matrix entry. */
RG2_API rg2_status rg2_mesh_mobius(rg2_mesh *m, const double center[3], double radius,
                                   const double M[16], rg2_error *err);

/** The design file's `mobius` (docs/poles.md), the same bits: move the poles of a sphere-like
 *  mesh whose reference is the placed sphere or ellipsoid `ref` (NULL: the unit sphere at the
 *  origin), by eq. (16) with parameter *b, or (b NULL) taking the reference's south and north
 *  poles to `south` and `north` (world coordinates, on the reference to 1e-9; need not be
 *  antipodal). Every 4-tuple p becomes X M X^-1 p, X the reference's placement times
 *  diag(radius) or diag(a, b, c). On failure m is unchanged.
 *  @return RG2_EINVAL for an empty mesh, both or neither of b and the poles, one pole NULL, or a
 *  reference of another kind; RG2_ENONFINITE for a non-finite b, pole coordinate, or entry of
 *  ref's placement or parameters; RG2_EDOMAIN
 *  for a pole off the reference (naming the nearest point on it), poles that coincide or a
 *  singular placement; RG2_EWEIGHT if a resulting weight is not > 0 (naming the control point);
 *  RG2_ENOMEM. */
RG2_API rg2_status rg2_mesh_mobius_shape(rg2_mesh *m, const rg2_shape *ref, const double *b,
                                         const double south[3], const double north[3], rg2_error *err);

/** Cap ends. */
enum { RG2_CAP_SOUTH = 1, RG2_CAP_NORTH = 2 };

/** Options of the bi-3 polar cap (paper section 5.1, docs/poles.md). Index 0 south, 1 north. */
typedef struct {
    int ends;             /**< RG2_CAP_SOUTH | RG2_CAP_NORTH (default both) */
    double length[2];     /**< cap parameter length in units of the adjacent body ring;
                               0 = automatic (default) */
    double vc[2];         /**< seam position v_c in [0, 1) in the cap chart F = v^2 q(r): the cap
                               is v in [0, v_c] (0: polynomial chart, pole at r = 0); used only
                               when length > 0 */
    double jet_weight[3]; /**< multipliers of the value, first and second derivative rows of the
                               least-squares fit, each > 0 (default 1, 1, 0.25; a zero weight
                               leaves the fit rank-deficient: RG2_EDOMAIN) */
    int samples;          /**< boundary samples per patch column, 2..256 (default 8) */
    int quadratic;        /**< RG2_CAP_ROTATIONAL (default): eq. (14), q_k3 (x^2 + y^2), bi-3
                               caps; RG2_CAP_GENERAL: the general quadratic q_k3 x^2 + q_k4 x y +
                               q_k5 y^2 (6 coefficients per coordinate), for saddle-like ends
                               (paper Fig. 15c); the whole capped surface is then held as
                               rg2_xpatch of degree (4, 3) when the body's rows are family-2
                               rows (sphere, cylinder, ...), else (5, 3), the body in the
                               caps' homogeneous scaling (docs/poles.md) */
} rg2_cap_opts;

/** rg2_cap_opts.quadratic */
enum { RG2_CAP_ROTATIONAL = 0, RG2_CAP_GENERAL = 1 };

/** What the cap construction chose and measured, per end (0 south, 1 north). */
typedef struct {
    int capped[2];        /**< 1 if that end was capped */
    int polar[2];         /**< 1 if the end was a polar configuration (parameters from scalars) */
    double length[2];     /**< cap length L used (body ring units) */
    double vc[2];         /**< v_c used */
    double q[2][4][4];    /**< fitted eq. (14) coefficients q[end][k][c]: q_k = q_k0 + q_k1 x +
                               q_k2 y + q_k3 (x^2 + y^2), k = x, y, z, w; cap map
                               F = v^2 q(r(u, v)), r = ((1 - v) / v)(cos u, sin u), v = 0 at the
                               pole, u measured from junction 0; all zero when vc = 0 */
    double g[2][4][4];    /**< the same fit in the normalized chart t = v / v_c in [0, 1]:
                               G = g0 (1 - v_c t)^2 + (g1 cos u + g2 sin u) t (1 - v_c t) + g3 t^2 */
    double quad[2][4][3]; /**< coefficients of cos^2 u, cos u sin u, sin^2 u of the t^2 term of
                               G per coordinate k (general form; the rotational form has
                               g3, 0, g3); g[e][3] is then their mean (g3 + g5) / 2 */
    int du[2];            /**< u-degree of that end's cap patches (3 rotational; 4 or 5 general) */
    double residual[2];   /**< relative weighted RMS residual of the fit (0 for sphere data) */
    double pole[2][3];    /**< the pole points */
    int rows_before;      /**< cap patch rows before the body rows in the output (0 or 3) */
    int rows_after;       /**< cap patch rows after the body rows (0 or 3) */
} rg2_cap_info;

RG2_API void rg2_cap_opts_default(rg2_cap_opts *o);

/** Build the body surface of `body` (rg2_surface_build) and close its ends with bi-3 polar
 *  caps: least-squares fit of the 16 coefficients of eq. (14)-(15) to the body's boundary
 *  2-jet, trisection of the cap, each u-row a C2 cubic spline of 3 pieces with the pole 2-jet
 *  of the fitted map and the body's 2-jet at the seam. The result is one surface: 3 cap patch
 *  rows before the body rows (south) and/or 3 after (north), with bv/gv set so that every seam
 *  is G2; the pole is a collapsed patch edge (normal undefined exactly there, its limit is
 *  unique). The body needs a closed u-direction with circle scalars (arc partition) and an
 *  open v-direction. opts and info are nullable. Free out with rg2_surface_free.
 *  @return RG2_EINVAL (u open, v closed, no body patch row, ends or quadratic not one of their
 *  values), RG2_EINCOMPATIBLE (u scalars are not a circle partition), RG2_EDOMAIN (boundary
 *  ring collapsed or too small, rank-deficient fit, bad option), RG2_EWEIGHT (a boundary ring
 *  weight <= 0), RG2_ELIMIT (more than INT_MAX / 12 boundary samples), RG2_ENOMEM, or the
 *  errors of rg2_surface_build. */
RG2_API rg2_status rg2_cap_build(const rg2_mesh *body, const rg2_cap_opts *opts,
                                 rg2_surface *out, rg2_cap_info *info, rg2_error *err);
/** Whether output k of a design is capped (its `cap` operation): 1, and *opts (nullable) gets
 *  the caps' options, with which rg2_cap_build of rg2_design_mesh(d, k) builds the patches of
 *  rg2_design_surface(d, k) bit for bit; else 0 (also for a NULL design or k out of range). */
RG2_API int rg2_design_cap(const rg2_design *d, int k, rg2_cap_opts *opts);

/* ===================================================================================== */
/** @name Grid evaluation and tessellation */
/* ===================================================================================== */

/* Fast evaluation of patches on regular parameter grids: n x m points per patch at
 * u_a = a / (n - 1), v_b = b / (m - 1) (both ends included), with separable Bernstein tables
 * computed once per call (Horner forms along u), vectorised inner loops (AVX-512 / AVX2 /
 * baseline chosen at run time on x86-64) and a pool of threads over patches. Results agree
 * with rg2_patch_eval to ~1e-15 relative on well-conditioned patches (tests require <= 1e-14
 * on random patches); where the parameterization is ill-conditioned the two roundings of the
 * curvatures differ more (an embedder measured K 7e-14 on the torus_sphere design's sphere,
 * 1.5e-12 on a NURBS duct patch, 5e-7 at 1/299 from a pole: docs/poles.md); they do not depend on the
 * thread count, and positions and normals do not depend on which other outputs are requested
 * (both bitwise; a NaN that non-finite control points produce is a NaN either way, its sign and
 * payload not specified). Outputs larger than 8 MB per thread of the call are written with streaming
 * (cache-bypassing) stores where available.
 * docs/performance.md has the measured speed against SISL and OpenCASCADE.
 *
 * Layout: point (a, b) of a patch is index a * m + b; vector quantities are 3 doubles per point
 * (x, y, z interleaved), scalars 1 per point. For a surface, patch k = i * s->nv + j fills the
 * points [k * n * m, (k + 1) * n * m): seam points appear in both patches (tessellators merge
 * them). Every output array except pos may be NULL (not computed). Where Su x Sv vanishes
 * (collapsed edges, poles) the normal and K, H are 0, as in rg2_patch_eval: the points of a
 * collapsed side take rg2_patch_eval's values (it tests the side's control points there). The
 * sides tested are those on a surface's open boundary, where the poles of rg2's constructions
 * lie, and every side of a patch given alone (rg2_patch_grid).
 * Speed: outputs past 8 MB per thread bypass the caches (streaming stores); arrays that start on
 * a 64-byte boundary (aligned_alloc(64, ...)) and rows of a multiple of 8 points stream fastest,
 * others take extra shuffles (docs/performance.md). For arrays 16 bytes past a line, as large
 * malloc blocks start, against aligned ones: on the Intel Xeon machine positions 0.69-0.97x at
 * 64 x 64 points per patch, 0.85-0.95x at 16 x 16 and 24 x 24, 0.88-0.91x at 8 x 8, with normals
 * 0.76-0.90x at 64 x 64 and 0.88-1.02x at 8 x 8; on AMD Zen 5 positions 0.80-0.97x at 32 x 32 to
 * 64 x 64, 0.78-0.84x at 24 x 24, 0.60-0.62x at 16 x 16, 0.90-0.92x at 8 x 8, with normals
 * 0.78-0.87x at 32 x 32 to 64 x 64 and 0.99-1.01x at 8 x 8. Rows of 65 points (seam points
 * shared) run at 0.89-0.93 of rows of 64 on AMD Zen 5 (positions; with normals 0.72-0.81).
 * The results are the same bits either way. */

#define RG2_GRID_MAX 16384 /**< most points per patch direction */

typedef struct {
    double *pos;             /**< required: positions, 3 per point */
    double *normal;          /**< unit normals n = Su x Sv / |Su x Sv|, 3 per point */
    double *du, *dv;         /**< first partial derivatives Su, Sv, 3 per point */
    double *duu, *duv, *dvv; /**< second partial derivatives, 3 per point */
    double *K, *H;           /**< Gaussian and mean curvature (rg2_eval sign convention) */
} rg2_grid_out;

/** Evaluate one patch on an n x m grid into out (arrays of n * m points). A bi-3 patch only:
 *  the placeholder that rg2_surface_patch gives for a higher-degree patch is all NaN, and so is
 *  its grid (rg2_surface_patch_grid takes either kind).
 *  @return RG2_EINVAL for n or m < 2 or out->pos NULL; RG2_ELIMIT past RG2_GRID_MAX. */
RG2_API rg2_status rg2_patch_grid(const rg2_patch *P, int n, int m, const rg2_grid_out *out,
                                  rg2_error *err);
/** Patch (i, j) of s on an n x m grid, whichever its degree: rg2_patch_grid for a bi-3 patch,
 *  for a higher-degree one (s->xp, caps of degree 4 or 5) the values of rg2_xpatch_eval bit for
 *  bit; the same values as that patch's points of rg2_surface_grid (a viewer's level of detail
 *  or pick refinement of one patch).
 *  @return RG2_EINVAL for (i, j) outside the surface, then as rg2_patch_grid. */
RG2_API rg2_status rg2_surface_patch_grid(const rg2_surface *s, int i, int j, int n, int m,
                                          const rg2_grid_out *out, rg2_error *err);
/** Evaluate every patch of s on an n x m grid (arrays of s->nu * s->nv * n * m points).
 *  threads: 0 = the OpenMP default (OMP_NUM_THREADS, else the cores), 1 = serial, t > 1 = up to
 *  t threads (at most 64): the caller and a persistent pool of worker threads share the patches,
 *  and the call never waits for a worker that has not started (a busy core costs no more than
 *  running alone). Each thread takes the same patches call after call when the threads keep
 *  pace, so repeated calls into the same arrays find them in that thread's cache. Workers idle
 *  for more than 2 ms sleep, and the next call wakes them: in a loop with longer pauses between
 *  small calls (an interactive editor at 60 Hz, say) threads = 1 is faster (docs/performance.md).
 *  Results are identical for any t; safe to call from several threads at once.
 *  Patches of higher degree (s->xp) are evaluated too, equal to rg2_xpatch_eval bit for bit.
 *  Nothing is checked per point: where a patch's weights reach 0 its points are at infinity
 *  and the outputs not finite (rg2_tessellate refuses such vertices; weights > 0 keep every
 *  point finite).
 *  @return as rg2_patch_grid; RG2_EINVAL for an empty surface or threads < 0; RG2_ELIMIT when
 *  the total number of values does not fit in memory sizes. */
RG2_API rg2_status rg2_surface_grid(const rg2_surface *s, int n, int m, int threads,
                                    const rg2_grid_out *out, rg2_error *err);
/** Position only at one point (the fast per-point path of rg2_patch_eval order 0, equal to it
 *  to rounding). A bi-3 patch only: for a surface with higher-degree patches (s->xp) the
 *  placeholder of rg2_surface_patch gives NaN, so use rg2_surface_eval there. */
RG2_API void rg2_patch_point(const rg2_patch *P, double u, double v, double p[3]);
/** Position and unit normal at one point (normal 0 where undefined); returns the
 *  RG2_EVAL_* flags as rg2_patch_eval order 1 would set them; position and normal agree with
 *  rg2_patch_eval's to rounding (normals: a few 1e-16 apart at most points, not bit for bit).
 *  A bi-3 patch only, as rg2_patch_point. */
RG2_API unsigned rg2_patch_point_normal(const rg2_patch *P, double u, double v, double p[3],
                                        double n[3]);

/* ===================================================================================== */
/** @name Export (STEP, IGES, BezierView, OBJ, STL, PLY, glTF) */
/* ===================================================================================== */

typedef enum {
    RG2_STEP_FACE_PER_PATCH = 0, /**< one ADVANCED_FACE per Bezier patch, shared edges */
    RG2_STEP_FACE_PER_MESH = 1   /**< one B-spline surface per mesh, interior knots mult. 3 */
} rg2_step_layout;

typedef struct {
    rg2_step_layout layout; /**< STEP/IGES: faces per patch or per mesh */
    int ap242;              /**< STEP: write AP242 instead of AP214 */
    int iges_brep;          /**< IGES: a B-rep shell per surface (entity 514 of faces 510, one
                                 per patch or, with the face-per-mesh layout, one on the
                                 merged net; edges and vertices shared, exact pcurves) instead
                                 of untrimmed surfaces */
    int density;            /**< meshes: samples per patch edge (default 16; < 1: 16) */
    const char *name;       /**< product / object name (default "rg2"; NULL: "rg2"); control
                                 characters are written as '_', bytes that are not UTF-8 as '?' */
} rg2_export_opts;

RG2_API void rg2_export_opts_default(rg2_export_opts *o);

/** A triangle mesh sampled from a surface (rg2_tessellate). Vertices on seams between
 *  patches, including the closing seams of closed directions, are stored once and shared by
 *  the triangles on both sides (a watertight mesh: shared vertices are bit-identical). */
typedef struct {
    int n_vertices, n_triangles;
    double *pos;    /**< 3 per vertex: a point of the exact surface */
    double *normal; /**< 3 per vertex: exact unit normal Su x Sv / |Su x Sv| (at a collapsed
                         edge, its limit) */
    double *K, *H;  /**< per vertex Gaussian and mean curvature (rg2_eval sign), or NULL */
    int *patch;     /**< per vertex: index i * nv + j of the patch it was evaluated on */
    double *uv;     /**< 2 per vertex: the (u, v) in [0,1]^2 of that patch */
    int *tri;       /**< 3 per triangle: vertex indices, counter-clockwise about the normal */
    size_t capacity; /**< bytes of the one allocation that holds every array (pos points to it);
                          rg2_retessellate reuses it */
} rg2_tess;

/** Tessellate a surface with `density` samples per patch edge (density >= 1; quads split
 *  along the shorter diagonal). curvature != 0 fills K and H. Collapsed patch edges (all four
 *  control points of a side equal, e.g. a pole) give one vertex and no degenerate triangles.
 *  Release with rg2_tess_free: the arrays are one allocation (never free them one by one).
 *  @return RG2_EINVAL (no patches, density < 1), RG2_ELIMIT (over RG2_MAX_POINTS vertices
 *  in all or per direction), RG2_ENONFINITE (a control value not finite, naming the patch),
 *  RG2_EDOMAIN (control points beyond 1e60, one whose h / w overflows, or spanning less than
 *  1e-60: the supported numeric range of docs/robustness.md: past about 1e+-75 the normals and
 *  curvatures overflow),
 *  RG2_EWEIGHT (a vertex not finite: weights that reach 0 put the surface through infinity;
 *  names the vertex's patch and (u, v). Negative weights alone are allowed: a patch whose
 *  4-tuples are all negated is the same surface), RG2_ENOMEM. */
RG2_API rg2_status rg2_tessellate(const rg2_surface *s, int density, int curvature, rg2_tess *out,
                                  rg2_error *err);
/** rg2_tessellate into a mesh that already exists (from rg2_tessellate, _retessellate, or all
 *  zeros), for editing loops (move a control point, rg2_surface_rebuild, re-tessellate) and
 *  animations: when t's allocation holds the new mesh, it is reused (no fresh pages: the bundled
 *  120-patch design at density 64, 45 MB, in 4.5-5.9 ms instead of 7.0-8.4 ms on one thread,
 *  docs/export.md), else it is freed and allocated anew. The allocation never shrinks: after a
 *  zoom to a fine density a coarse mesh keeps the large block (t->capacity bytes) until
 *  rg2_tess_free. The result equals rg2_tessellate's bit
 *  for bit. On failure t is left empty (freed), with the errors of rg2_tessellate. */
RG2_API rg2_status rg2_retessellate(const rg2_surface *s, int density, int curvature, rg2_tess *t,
                                    rg2_error *err);
RG2_API void rg2_tess_free(rg2_tess *t);
/** Write surfaces to path; the format follows the extension: .step/.stp, .igs/.iges, .bv,
 *  .bez (geomview BEZ<Du><Dv>4, the highest degrees: BEZ334 for bi-3 surfaces), .obj, .stl,
 *  .ply, .glb, .json (docs/export.md). Writes a new temporary file next to path,
 *  "<path>.<pid>.tmp" (created exclusively, never through a symbolic link; a counter is added
 *  when another thread writes the same path), then renames it to path: a failed export leaves
 *  no file, and concurrent writers of one path leave one writer's whole file. A regular file
 *  replaced keeps its permission bits (mode & 0777, as with sed -i; not setuid, setgid or
 *  sticky) and, where the writer may give them, its owner and group (else its group bits are
 *  cut to the others'); a new file, or one replacing a symbolic link, has 0666 & ~umask.
 *  STEP and IGES headers carry the file name (without its directory) and the UTC time of the
 *  write, so two writes of the same surfaces differ in those bytes; with the environment
 *  variable SOURCE_DATE_EPOCH set (seconds since 1970, read with getenv at each STEP or IGES
 *  write) the time is that one, and the same surfaces written to the same name give the same
 *  bytes (docs/export.md). The other formats carry no time or file name.
 *  @return RG2_EIO (unwritable), RG2_EWEIGHT (non-positive weight for STEP/IGES, naming the
 *  patch), RG2_ENONFINITE (a control value not finite, in every format), RG2_EINVAL (unknown
 *  extension, a file name that is only the extension, empty input, a layout other than the two), RG2_EDOMAIN (STL, PLY and glTF store
 *  floats: surfaces reaching beyond FLT_MAX, 3.4e38, or spanning less than FLT_MIN / FLT_EPSILON,
 *  about 1e-31; and the range of rg2_tessellate), RG2_ELIMIT (too many vertices or records for
 *  the format), RG2_ENOMEM. */
RG2_API rg2_status rg2_export_file(const rg2_surface *surfs, int n_surfs, const char *path,
                                   const rg2_export_opts *opts, rg2_error *err);
/** Write surfaces into memory instead of a file, in the format named by `format`: an extension
 *  rg2_export_file knows, without its dot ("step", "stp", "igs", "iges", "bv", "bez", "obj",
 *  "stl", "ply", "glb", "json"; case-insensitive). *data gets a buffer from malloc (the caller
 *  frees it with free()) of *size bytes and a 0 byte after them (for the text formats); they are
 *  the bytes rg2_export_file writes to a file named "<opts->name>.<format>" (STEP and IGES
 *  headers carry that name, '/' written as '_', and the time as rg2_export_file does,
 *  SOURCE_DATE_EPOCH included). For a program embedding the library: a CAD kernel that reads
 *  from memory, a network reply. The data passes through an anonymous temporary file (tmpfile:
 *  the IGES writer seeks back). On failure *data is NULL and *size 0.
 *  @return the statuses of rg2_export_file; RG2_EINVAL also for data or size NULL and an
 *  unknown format; RG2_EIO when the temporary file cannot be made or written. */
RG2_API rg2_status rg2_export_memory(const rg2_surface *surfs, int n_surfs, const char *format,
                                     const rg2_export_opts *opts, char **data, size_t *size,
                                     rg2_error *err);
/** Write the same surfaces to several files as one: each is written completely to a
 *  temporary file next to its path first (as rg2_export_file), and only when all are written are they renamed to their paths. If any fails
 *  (an unknown extension, a non-positive weight for STEP/IGES, an unwritable directory), none of
 *  the paths is touched: files already there stay as they were. *failed (if not NULL) is the
 *  index of the path that failed, -1 on success. A rename failing after others succeeded (in
 *  practice only when a path's directory changes under the call) leaves the earlier ones renamed.
 *  The mesh outputs (OBJ, STL, PLY, glTF) of one call share one tessellation, with curvatures
 *  when a PLY is among them (the same bytes as each written alone: the positions, normals and
 *  triangles do not depend on the curvatures being asked for), freed once the last mesh output
 *  is written, so outputs named after it (STEP, IGES) are written without it in memory.
 *  @return the statuses of rg2_export_file; RG2_EINVAL also for n_paths < 1 and for a path given
 *  twice. */
RG2_API rg2_status rg2_export_files(const rg2_surface *surfs, int n_surfs, const char *const *paths,
                                    int n_paths, const rg2_export_opts *opts, int *failed,
                                    rg2_error *err);
/** Whether rg2_export_file knows the format of path's extension, without writing anything (to
 *  refuse a mistyped output name before a long build).
 *  @return RG2_OK, or RG2_EINVAL (no path, no extension, unknown extension, a name that is only
 *  the extension such as ".step", which would be a hidden file with no name; the message lists
 *  the known ones). */
RG2_API rg2_status rg2_export_format_check(const char *path, rg2_error *err);
/** The temporary file this process's next write of path would use (every writer writes a new
 *  file next to path, then renames it): the first free name of "<path>.<pid>.tmp",
 *  "<path>.<pid>.1.tmp", ... (a file name near its directory's file-name limit, pathconf's
 *  _PC_NAME_MAX: 255 bytes on most file systems, 143 on eCryptfs, 255 when the directory gives
 *  none or more (vfat and exfat answer 1530 but take 255 ASCII bytes), is cut before the
 *  suffix, at a UTF-8 character boundary, and a hash of the whole name, ".%08x", is added, so
 *  the temporary name fits and names that differ only past the cut keep different temporary
 *  names). For a program that writes each path from one thread and must
 *  remove its temporary files when a signal ends it (the rg2 command does). Returns 0, or -1
 *  (no path or buf, buf too small, no free name). */
RG2_API int rg2_temp_name(const char *path, char *buf, size_t cap);


/* ===================================================================================== */
/** @name Pictures and checks */
/* ===================================================================================== */

/* Pictures: per-pixel exact rendering. Every foreground pixel is resolved to the (surface,
 * patch, u, v) whose exact point lies on the pixel's centre ray (a tessellation z-buffer gives
 * the start, Newton on the exact patch refines it); shading, curvature and stripe phase come
 * from rg2_patch_eval there, never from interpolation. Output is deterministic: the same input
 * gives the same bytes for any number of threads. */
typedef enum {
    RG2_RENDER_SHADED = 0, /**< lit surface; exact pieces tinted by their shape tag */
    RG2_RENDER_MEAN,       /**< mean curvature H colour map (sign as rg2_eval) + colour bar */
    RG2_RENDER_GAUSS,      /**< Gaussian curvature K colour map (diverging, symmetric) + bar */
    RG2_RENDER_ZEBRA       /**< reflection of parallel light lines (stripes from the normal) */
} rg2_render_mode;

/* Every field's range is checked by rg2_render (the message names the field and its value):
 * RG2_EINVAL outside it, RG2_ENONFINITE for a NaN or
 * infinite azimuth, elevation or distance.
 * Flags (apart, boundaries, tint, colorbar, keep_pixels) are 0 = off, anything else = on. */
typedef struct {
    int width, height;     /**< image size in pixels (default 800 x 600), each 16..8192; about
                                131 bytes of memory per pixel (8192 x 8192: 8.8 GB) */
    rg2_render_mode mode;  /**< one of rg2_render_mode (default shaded) */
    double azimuth;        /**< degrees about +z, 0 looks from +x towards the centre (default 35);
                                any finite value (taken modulo 360) */
    double elevation;      /**< degrees above the xy plane, finite and in -90..90 (default 25) */
    double distance;       /**< eye distance from the view centre (middle of the scene's extent
                                across the view), finite; <= 0 fits the view to the scene
                                (default 0) */
    double fov;            /**< vertical field of view in degrees, strictly between 1 and 170
                                (1 and 170 themselves, and NaN, are refused; default 30) */
    int apart;             /**< n > 1: lay the surfaces out apart, in a grid across the view
                                (ceil(sqrt(n)) columns, surface 0 top left, all at one depth),
                                each moved by a translation; for outputs that overlap (default
                                0: as placed) */
    int boundaries;        /**< draw patch boundaries (seams) as thin dark lines */
    int mesh;              /**< overlay the control meshes (needs meshes != NULL) */
    int tint;              /**< shaded: tint patches by shape tag (default 1) */
    int colorbar;          /**< curvature modes: draw the colour bar and its range (default 1;
                                only in pictures of at least 221 x 120 pixels) */
    int range_set;         /**< 1: use range[] as the colour range; 0: robust range (the
                                percentiles below, at least 1e-3 of its middle and 1e-9 / rho
                                wide for H, 1e-9 / rho^2 for K; rho the scene's radius) */
    double range[2];       /**< user colour range (curvature modes), read when range_set: both
                                finite, lo < hi, and hi - lo finite (not wider than the largest
                                double) */
    double percentile;     /**< robust range: clip this fraction at each end, in [0, 0.5)
                                (default 0.02; checked in every mode) */
    double stripes;        /**< zebra: stripe pairs per full turn of the reflected ray about
                                the light-line axis, 1..1000 (rounded to the nearest whole
                                number; checked in zebra mode only; default 12) */
    int keep_pixels;       /**< fill rg2_image.pixels with the per-pixel exact data */
    int threads;           /**< OpenMP threads, 0..1024 (at most 64 run); 0 = the OpenMP default */
} rg2_render_opts;

/** Exact data of one pixel (rg2_render_opts.keep_pixels). surf < 0 marks background. */
typedef struct {
    int surf, patch;       /**< surface index and patch index (i * nv + j) in it */
    double u, v;           /**< patch parameters where the exact point projects to the centre */
    double p[3], n[3];     /**< exact point and unit normal (oriented as rg2_eval) */
    double H, K;           /**< exact mean and Gaussian curvature there */
    double phase;          /**< zebra stripe phase (radians about the light-line axis) */
    double resid;          /**< distance of the exact point from the pixel's ray */
} rg2_pixel;

typedef struct {
    int width, height;
    unsigned char *rgb;    /**< width * height * 3 bytes, row-major, top row first */
    rg2_pixel *pixels;     /**< width * height, or NULL unless keep_pixels */
    double range[2];       /**< colour range used (curvature modes), else 0 */
    int below, above;      /**< curvature modes: surface pixels whose H (mean) or K (gauss) lies
                                below range[0] / above range[1], drawn in the end colour; the
                                colour bar marks each end that has such pixels with a triangle
                                pointing away from the bar. 0 in the other modes */
    int foreground;        /**< number of surface pixels */
    int refined;           /**< pixels whose Newton refinement converged */
} rg2_image;

RG2_API void rg2_render_opts_default(rg2_render_opts *o);
/** Render n surfaces (meshes: nullable, n control meshes for the overlay, an empty (zeroed) one
 *  drawing nothing) into out (o NULL:
 *  rg2_render_opts_default). Release with rg2_image_free.
 *  @return RG2_EINVAL (no surfaces, a NULL out, a surface without patches, an rg2_render_opts
 *  field outside the range its comment gives: size, mode, fov, elevation, colour range,
 *  percentile, zebra stripes, threads, mesh overlay without meshes), RG2_ENONFINITE (a NaN or
 *  infinite azimuth, elevation or distance; a non-finite control point, naming it), RG2_EDOMAIN
 *  (a surface's control points beyond 1e60, one whose h / w overflows, or spanning less than
 *  1e-60: the numeric range of rg2_tessellate, naming the surface), RG2_ENOMEM. */
RG2_API rg2_status rg2_render(const rg2_surface *surfs, int n, const rg2_mesh *meshes,
                              const rg2_render_opts *o, rg2_image *out, rg2_error *err);
RG2_API void rg2_image_free(rg2_image *img);
/** Write an RGB image as 8-bit PNG (libpng) to a temporary file next to path, then rename (as
 *  rg2_export_file; a failed write leaves no file). The name is the caller's: a PNG is written
 *  whatever its extension (the rg2 command refuses one other than .png). @return RG2_EIO (unwritable, disk full), RG2_EINVAL (empty image, no path),
 *  RG2_ENOMEM. */
RG2_API rg2_status rg2_image_write_png(const rg2_image *img, const char *path, rg2_error *err);
/** rg2_render followed by rg2_image_write_png. */
RG2_API rg2_status rg2_render_png(const rg2_surface *surfs, int n, const rg2_mesh *meshes,
                                  const rg2_render_opts *o, const char *path, rg2_error *err);

/* Checks: a continuity and exactness report. Seams are the interior (and closing) patch
 * seams of each surface; seams between different surfaces are not measured. Gaps are taken at
 * samples along each seam: position gap relative to the surface size, angle between the unit
 * normals, and the jump of normal curvature in six tangent directions relative to
 * max(|k1|, |k2|, 1 / size). Exact pieces (tag >= 0) are sampled against their shape's
 * implicit equation: |f| / |grad f| relative to the size of that shape's patches.
 * Samples on a pole (a patch side collapsed to a point while a parallel control line of the
 * patch is not) have no normal and are not compared; an undefined normal anywhere else fails
 * G1 and G2. Next to a pole the normal and curvature lose digits like 1/v and 1/v^2: a sample
 * of a patch with a pole side whose first-order rounding bound exceeds tol_g1 / tol_g2 is
 * measured against that bound (reported apart: near_pole, g1_pole, g2_pole); so is a sample
 * elsewhere whose gap exceeds the limit on an ill-conditioned patch (ill_conditioned, g1_ill,
 * g2_ill), and one whose bound exceeds 1e-4 rad / 1e-2 there is unmeasured. Inside the
 * patches, on the (patch_samples + 1)^2 grid, a sample away from a pole without a normal
 * (singular) and a fold between neighbouring samples (the normal reverses: Su x Sv changes sign,
 * found by halving the segment) also fail G1 and G2: seams alone cannot see a surface that
 * runs back over itself inside a transition. */
/** Where two sheets of the output surfaces cross (rg2_find_crossings). The surfaces are
 *  tessellated at `density` samples per patch edge (rg2_tessellate), the vertices of all of
 *  them that coincide (to 1e-10 of the size) welded into one, and every pair of triangles that
 *  share no welded vertex and whose boxes overlap (a uniform grid) is tested for a transversal
 *  crossing of the flat triangles (coplanar or touching triangles do not cross). Each crossing
 *  pair is then CONFIRMED on the exact patches: from the point of the triangles' crossing
 *  segment, interpolated to (u, v) on both sheets, Gauss-Newton (minimum-norm steps, stepping
 *  across patch seams, clamped at open surface borders) solves S1(u1, v1) = S2(u2, v2). A pair
 *  counts as a crossing when |S1 - S2| converges to <= 1e-10 of the size within 2 triangle
 *  boxes of the start, neither point lies on an open border of its surface (surfaces that
 *  meet along an edge touch, they do not cross), both normals are defined and their angle is
 *  at least RG2_CROSSING_MIN_ANGLE (a near miss of a sheet with itself converges to one point
 *  with parallel normals). Misses: crossings shallower than the tessellation's chord error
 *  (a bulge that pokes through a wall by less than the flat triangles' distance to the
 *  surface; raise the density), tangential contact (normals closer than the minimum angle),
 *  and crossings at a pole (no normal). The result depends only on the surfaces and the
 *  density, not on the thread count (the pair tests run on threads, each keeping its least
 *  confirmed pair; the reduction takes the least). Memory: about 85 bytes per triangle, the
 *  same for any thread count (1.92 million, the 60,000-patch torus at density 4: 163 MB more
 *  than rg2_check alone). docs/render.md. */
#define RG2_CROSSING_MIN_ANGLE 1e-3  /**< radians between the normals of a confirmed crossing */
#define RG2_CROSSING_DEFAULT_DENSITY 4 /**< rg2 check --intersections without a number */
#define RG2_MAX_CROSSING_TRIANGLES 4000000 /**< budget of one rg2_find_crossings (about 340 MB) */

typedef struct {
    int surf, pi, pj;      /**< surface, patch (i, j) */
    double u, v;           /**< parameters in that patch */
} rg2_crossing_sheet;

typedef struct {
    int density;           /**< samples per patch edge used; 0: not measured */
    int triangles;         /**< triangles of all surfaces, tested */
    double pairs;          /**< triangle pairs met in the broad phase's grid lists and box-tested
                                (its work: about linear in the triangles, whatever the layout) */
    int candidates;        /**< triangle pairs (no shared welded vertex) whose flat triangles cross */
    int crossings;         /**< of them, confirmed on the exact surfaces (pass: 0) */
    /** The first confirmed pair in the order of the triangles (surface, then rg2_tessellate's
     *  triangle index; the lower triangle first), when crossings > 0: */
    rg2_crossing_sheet a, b; /**< the two sheets at the confirmed point */
    double p[3];           /**< the point (the mean of S_a and S_b there) */
    double residual;       /**< |S_a - S_b| / size there */
    double angle;          /**< angle between the two normals, in (0, pi/2] radians */
    double size;           /**< the diagonal of the box of all control points (positive weights) */
} rg2_crossing_report;

/** Find transversal crossings of n surfaces, within each and between them (the method, the
 *  tolerances and what it misses: rg2_crossing_report). density: samples per patch edge
 *  (1..1000). threads: 0 = the OpenMP default (OMP_NUM_THREADS, else the cores), 1 = serial,
 *  t > 1 = up to t (at most 64), for the tessellation, the weld, the grid and the pair tests;
 *  the report is identical, bit for bit, for any thread count. The report is written whole
 *  (no allocation to release).
 *  @return RG2_EINVAL (no surfaces or report, a surface without patches, density outside
 *  1..1000, threads < 0, naming it), RG2_ELIMIT (more than RG2_MAX_CROSSING_TRIANGLES triangles: patches x
 *  2 density^2, naming the count and the density; checked before anything is allocated), the
 *  errors of rg2_tessellate (prefixed with the surface), RG2_ENOMEM. */
RG2_API rg2_status rg2_find_crossings(const rg2_surface *surfs, int n, int density, int threads,
                                      rg2_crossing_report *out, rg2_error *err);

enum {
    RG2_REQUIRE_G0 = 1u << 0,
    RG2_REQUIRE_G1 = 1u << 1,
    RG2_REQUIRE_G2 = 1u << 2,    /**< implies G0 and G1 */
    RG2_REQUIRE_EXACT = 1u << 3, /**< every tagged patch on its shape, and at least one */
    RG2_REQUIRE_WEIGHTS = 1u << 4, /**< every homogeneous weight > 0 */
    RG2_REQUIRE_NO_CROSSINGS = 1u << 5 /**< crossings measured (crossing_density > 0) and none */
};

/** Largest number of seam samples, and of patch samples, of one rg2_check (the counts of the
 *  report are ints; about ten minutes of work per thread) */
#define RG2_MAX_CHECK_SAMPLES 1000000000

typedef struct {
    int seam_samples;      /**< seam intervals: seam_samples + 1 samples per seam, 1..10000
                                (default 16) */
    int patch_samples;     /**< samples per patch direction for residuals/curvature, 1..1000
                                (default 12) */
    double tol_g0, tol_g1, tol_g2, tol_exact; /**< pass limits (defaults 1e-12, 1e-10, 1e-8, 1e-11) */
    int threads;           /**< OpenMP threads: 0 = the OpenMP default (OMP_NUM_THREADS, else the
                                cores; the default), 1 = serial, t > 1 = up to t (at most 64).
                                The seams and the patches are measured in contiguous chunks into
                                partial reports merged in order with the serial comparisons:
                                the report is identical, bit for bit, for any thread count */
    int crossing_density;  /**< 0 (default): no crossing search; 1..1000: rg2_find_crossings at
                                this density into the report's crossings, on `threads` threads
                                (the same report for any count) */
    int surface_base;      /**< the number the report gives surfs[0] (default 0): surfs[k] is
                                named surface surface_base + k wherever the report names a
                                surface (gaps, samples, crossings, the shapes' `where`). For
                                checking part of a design's outputs under the numbers the whole
                                design's report gives them: rg2 check --surface K checks output
                                K alone, with surface_base K. 0 <= surface_base <= INT_MAX - n */
} rg2_check_opts;

typedef struct {
    int shape;             /**< index in the shape list */
    char label[64];        /**< label or shape kind name (a longer label: its first 63 bytes or
                                fewer, cut between UTF-8 characters) */
    int patches;           /**< patches tagged with it */
    double residual;       /**< worst relative implicit residual */
    char where[96];        /**< patch and (u, v) of the worst residual */
    double limit;          /**< the residual's pass limit: tol_exact, or where larger the
                                rounding of the patches' coordinates, RG2_CHECK_COORD_ROUNDING
                                x DBL_EPSILON x (largest |coordinate| of the shape's patches) /
                                (their size), when that coordinate exceeds the size: a small
                                shape far from the origin cannot lie closer to itself than its
                                coordinates round */
} rg2_check_shape;

/** The factor of rg2_check_shape.limit's coordinate rounding (measured: residuals up to 4.7 x
 *  DBL_EPSILON x the largest coordinate / size on shapes of size 1e-3 placed up to 1e4 away). */
#define RG2_CHECK_COORD_ROUNDING 16.0

typedef struct {
    double value;          /**< the worst gap */
    int surf, seam_dir;    /**< surface, 0 = u seam, 1 = v seam */
    int pi, pj, qi, qj;    /**< the two patches (i, j) */
    double t;              /**< parameter along the seam */
    double p[3];           /**< the point */
} rg2_check_gap;

/** A sample of a patch that the report points to. */
typedef struct {
    int surf, pi, pj;      /**< surface, patch (i, j) */
    double u, v;           /**< parameters in the patch */
    double p[3];           /**< the point there */
} rg2_check_sample;

typedef struct {
    int surfaces, patches, transitions, exact_patches, untagged_bad; /**< untagged_bad: tags
                              outside the shape list */
    int n_shapes;
    rg2_check_shape *shapes; /**< n_shapes entries (allocated) */
    double worst_residual;
    int seams, seam_samples; /**< seams and seam samples (seam_samples + 1 per seam) */
    int skipped;           /**< samples whose normals were not compared: pole_samples +
                                pole_unresolved + unmeasured */
    int pole_samples;      /**< samples on a collapsed patch side (a pole): no normal exists there */
    int unmeasured;        /**< samples with an undefined normal away from a pole, or a rounding
                                bound above 1e-4 rad / 1e-2 that is not the pole's (see
                                pole_unresolved): G1 and G2 fail when > 0 */
    int unmeasured_pole;   /**< of unmeasured: samples on a patch with a pole side whose rounding
                                bound past 1e-4 rad / 1e-2 would still be past them 0.25 from the
                                pole if it grew only like 1/d (normal) and 1/d^2 (curvature)
                                toward it (a very thin pole patch; docs/render.md) */
    double unmeasured_pole_dist; /**< the largest parametric distance from the pole among them */
    rg2_check_gap unmeasured_at; /**< where the first unmeasured sample is, in the order seams are
                                    measured (surface, its u seams then v seams, row by row, t
                                    along each; the same on any thread count): surface, seam,
                                    patches, t and point (the first side's). value: its rounding
                                    bound over the measurable limits, the larger of the G1 bound /
                                    1e-4 rad and the G2 bound / 1e-2 (> 1); +inf where the normal
                                    or the metric is undefined (or out of floating-point range);
                                    NaN for a bound that is not a number. Set when unmeasured > 0 */
    rg2_check_gap g0, g1, g2; /**< position (relative), normal angle (rad), curvature (relative),
                                   over the samples measured against tol_g0, tol_g1, tol_g2 */
    int near_pole;         /**< samples of patches with a pole side whose rounding bound (the
                                expected floating-point error of the two evaluations) exceeds
                                tol_g1 or tol_g2: measured against that bound instead */
    int pole_unresolved;   /**< samples next to a pole whose rounding bound exceeds 1e-4 rad /
                                1e-2 because of the pole: within 1e-3 of it (parametric), or the
                                bound, carried out like 1/d (normal) and 1/d^2 (curvature), is
                                within those limits 0.25 from it. Not compared, no failure */
    double pole_unresolved_dist; /**< the largest parametric distance from the pole among them */
    double near_pole_tol1, near_pole_tol2; /**< the largest G1 (rad) / G2 limits they got */
    rg2_check_gap g1_pole, g2_pole; /**< their worst gap / own limit (pass: <= 1) */
    int ill_conditioned;   /**< samples of patches without a pole side whose gap exceeds tol_g1
                                or tol_g2 and whose rounding bound exceeds it too and 1e-12
                                rad / 1e-10 (an ill-conditioned patch, e.g. a shape flattened by
                                its placement): measured against that bound */
    double ill_tol1, ill_tol2; /**< the largest G1 (rad) / G2 limits they got */
    rg2_check_gap g1_ill, g2_ill; /**< their worst gap / own limit (pass: <= 1) */
    int folds;             /**< pairs of neighbouring patch samples between which the surface
                                folds back (Su x Sv changes sign: the normal reverses), e.g. two
                                merged meshes that overlap: G1 and G2 fail when > 0 */
    int singular;          /**< patch samples away from any pole with an undefined normal
                                (Su x Sv = 0): G1 and G2 fail when > 0 */
    rg2_check_sample fold_at; /**< the first fold or singular sample (a fold: u, v between two
                                   samples) */
    double wmin, wmax;     /**< homogeneous weights of all control points */
    double eval_wmin;      /**< smallest weight met at the samples */
    double kmin, kmax;     /**< principal curvatures (k2 min, k1 max) over the samples */
    double Hmin, Hmax, Kmin, Kmax;
    rg2_check_sample kpeak; /**< where |k| is largest (the tightest bend): the first such sample in
                                 the order patches are listed (surface, patch i, j, then u, v), the
                                 same on any thread count; surf -1 when no sample has a curvature */
    double kpeak_k;        /**< the principal curvature there (kmin or kmax, whichever is larger in
                                magnitude; radius of curvature 1 / |k|) */
    double size;           /**< bounding-box diagonal used to scale gaps */
    rg2_crossing_report crossings; /**< with opts.crossing_density > 0 (else all zero) */
    rg2_check_opts opts;   /**< the options (tolerances) the report was made with */
} rg2_check_report;

RG2_API void rg2_check_opts_default(rg2_check_opts *o);
/** Measure surfaces against shapes (nullable if n_shapes == 0; labels nullable), on
 *  o->threads threads (o NULL: the defaults). Release the report with rg2_check_report_free.
 *  Non-finite control values are not refused (unlike rg2_tessellate, rg2_render and the
 *  exports, which name the patch): the report measures them, its gaps and residuals come out
 *  NaN and every G0, G1, G2 and EXACT promise fails (rg2_check_failures; the table says FAIL).
 *  @return RG2_EINVAL (no surfaces, samples out of range, threads < 0, a tolerance that is
 *  not a finite number >= 0, a shape of an unknown kind, naming it), RG2_ELIMIT (more than
 *  RG2_MAX_CHECK_SAMPLES seam samples, or
 *  patch samples, over all surfaces: seams x (seam_samples + 1), patches x
 *  (patch_samples + 1)^2), RG2_ENOMEM. */
RG2_API rg2_status rg2_check(const rg2_surface *surfs, int n, const rg2_shape *shapes,
                             const char *const *labels, int n_shapes, const rg2_check_opts *o,
                             rg2_check_report *out, rg2_error *err);
RG2_API void rg2_check_report_free(rg2_check_report *r);
/** Which patches of s lie on a shape, whether tagged with it or not (rg2 check --on): res[i * nv
 *  + j] (nu * nv doubles, the caller's) is the worst implicit residual |f| / |grad f| of patch
 *  (i, j) over (samples + 1)^2 points u, v = a / samples, relative to the size of s (the diagonal
 *  of the box of its control points of positive weight). Points at a singular point of the
 *  shape (a cone's apex) are skipped; a non-finite point gives NaN. rg2 check --on counts a patch
 *  on the shape at residuals <= tol_exact (1e-11). rg2_check's exact pieces divide by the size
 *  of the patches tagged with the shape instead, so where those span less than the surface, its
 *  figures for the same patches are larger by the ratio (Fig. 13's torus: 6.65e-16 there,
 *  4.22e-16 here). @return RG2_EINVAL (a surface without patches, no
 *  shape or res, samples outside 1..1000), RG2_ELIMIT (more than RG2_MAX_CHECK_SAMPLES points). */
RG2_API rg2_status rg2_surface_shape_residuals(const rg2_surface *s, const rg2_shape *shape, int samples,
                                               double *res, rg2_error *err);
/** The RG2_REQUIRE_* bits of `require` that the report fails (0: every promise holds). */
RG2_API unsigned rg2_check_failures(const rg2_check_report *r, unsigned require);
/** Format the report as a text table (json = 0) or JSON (json = 1) into a malloc'd string
 *  the caller frees with free(). A NaN figure (from a non-finite control value) reads "NaN" in
 *  the table, whatever its sign bit, and null in the JSON. @return RG2_ENOMEM. */
RG2_API rg2_status rg2_check_format(const rg2_check_report *r, int json, char **text,
                                    rg2_error *err);

#ifdef __cplusplus
}
#endif

#endif /* RG2_H */
