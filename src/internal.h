/* internal.h -- private helpers shared by the rg2 modules; never installed. */
#ifndef RG2_INTERNAL_H
#define RG2_INTERNAL_H

#include "rg2.h"

#include <math.h>
#include <stdio.h>
#include <stdarg.h>
#include <string.h>

/* Function multi-versioning on x86-64 ELF with GCC: the hot kernels and the per-point
 * evaluators (src/grid.c) and the tessellation's diagonal test (src/tess.c) get AVX-512, AVX2
 * and baseline clones; the loader picks one per machine, so the library stays portable. The
 * clones give the same bits as the baseline: -ffp-contract=off, and none of them holds a
 * multiply-add (tests/clones.sh checks the built library; GCC's vectoriser can form a
 * vfmaddsub even so, as it did in a clone of rg2_patch_eval's curvatures, which is therefore
 * not cloned). */
#if defined(__GNUC__) && !defined(__clang__) && defined(__x86_64__) && defined(__ELF__) &&     \
    !defined(RG2_NO_CLONES) && !defined(__AVX2__)
#define RG2_HOT __attribute__((target_clones("arch=x86-64-v4", "arch=x86-64-v3", "default")))
#else
#define RG2_HOT
#endif

#ifndef M_PI
#define M_PI 3.14159265358979323846
#endif

/* Size limits of a design (README "Limits and errors"): control points of all its meshes
 * together, and patches of all its output surfaces together. Past them a design is refused
 * with RG2_ELIMIT before memory runs out. The fuzz build (scripts/fuzz.sh) lowers them. */
#ifndef RG2_DESIGN_MAX_POINTS
#define RG2_DESIGN_MAX_POINTS 4000000
#endif
#ifndef RG2_DESIGN_MAX_PATCHES
#define RG2_DESIGN_MAX_PATCHES 1000000
#endif

/* Supported numeric range of design files: every number is 0 or has a magnitude in
 * [RG2_DESIGN_MIN_ABS, RG2_DESIGN_MAX_ABS]; every output mesh's coordinates stay below
 * RG2_DESIGN_MAX_COORD and its size (bounding-box diagonal) is at least RG2_DESIGN_MIN_SIZE.
 * Beyond 1e+-75 the fourth powers of the implicit equations (torus, cyclide) and of the
 * normal formulas (|Su x Sv|^2) leave the double range; 1e+-60 keeps a margin of 1e15 for
 * patches much smaller than their surface and for curvature radii. */
#define RG2_DESIGN_MAX_ABS 1e100
#define RG2_DESIGN_MIN_ABS 1e-100
#define RG2_DESIGN_MAX_COORD 1e60
#define RG2_DESIGN_MIN_SIZE 1e-60

/* Smallest circle arc a shape partition accepts (radians; docs/robustness.md): below it the
 * seam curvature of the tiny patches agrees only to about 2e-15 / alpha^2 (measured), worse
 * than the 1e-10 the library states. Arcs up to pi (exclusive) are exact to the last double. */
#define RG2_MIN_ARC 5e-3

/* Pieces a picking query takes at most (src/locate.c): RG2_LOCATE_MAX_PIECES; the fuzz harness
 * lowers it, so that a degenerate input does not slow the fuzzing of everything else. */
extern long rg2__locate_max_pieces;
/* The nearest-point search's convexity certificate (locate.c) on patch `patch` over
 * [uf - r, uf + r] x [vf - r, vf + r] for the squared distance c from x: 1 if one is made, and
 * then *bound, its lower bound of the distance over the rectangle rect = {u0, u1, v0, v1} (0
 * where rect is not inside). For test_locate. */
int rg2__locate_cert(const rg2_locator *L, int patch, double uf, double vf, double r, const double x[3], double c,
                     const double rect[4], double *bound);
/* The same for the ray o + t d (d != 0) based at (uf, vf): *bound is the smallest t where the ray
 * can meet the rectangle (INFINITY: nowhere). */
int rg2__locate_ray_cert(const rg2_locator *L, int patch, double uf, double vf, double r, const double o[3],
                         const double d[3], const double rect[4], double *bound);

/* rg2_locator_closest, adding to *evals (not NULL) the patch evaluations of its Newton runs: a
 * count of its work that test_locate bounds (a Newton run that cycled between two points a
 * rounding apart took all 60 steps; the answers were the same). */
rg2_status rg2__locate_closest(const rg2_locator *L, const double x[3], rg2_hit *out, long *evals, rg2_error *err);
/* The tree's slabs (locate.c: each node's range of n . P over its patches' control points): the
 * smallest margin by which the exact control points (in long double) lie inside their nodes'
 * slabs, relative to their coordinates' size (negative: a point outside), over the *slabs
 * nodes that have one. For test_locate and the fuzz harness. */
double rg2__locate_slab_margin(const rg2_locator *L, int *slabs);

/* Fill err (if not NULL) with code and a printf-style message; returns code. */
rg2_status rg2__fail(rg2_error *err, rg2_status code, const char *fmt, ...)
#if defined(__GNUC__)
    __attribute__((format(printf, 3, 4)))
#endif
    ;
/* Prefix err's message with "what: " when st is an error (a too long result shortened as
 * rg2__fail shortens, keeping the message's end); returns st. */
rg2_status rg2__prefix(rg2_error *err, rg2_status st, const char *what);
/* Set err to RG2_OK with an empty message. */
void rg2__ok(rg2_error *err);
/* Drop an incomplete UTF-8 sequence from the end of s, as snprintf leaves one when it cuts a
 * text short in the middle of a character (src/status.c). */
void rg2__utf8_cut(char *s);

/* A double for a message: the fewest significant digits (up to 17) that read back as exactly x,
 * so a knot of 0.45 reads "0.45", not "0.45000000000000001". Use as rg2__num(x).s inside the
 * call's argument list (the text lives until the end of that full expression). */
typedef struct {
    char s[32];
} rg2__numtext;
rg2__numtext rg2__num(double x);

/* Fault injection (tests only: the rg2_fi library of tests/CMakeLists.txt defines
 * RG2_FAULT_INJECT; the library itself has none of this). Every malloc, calloc, realloc, strdup
 * and posix_memalign of src/ goes through a counting wrapper (alloc.c): while rg2__fi_countdown
 * is >= 0 each allocation counts it down, and the one that finds it at 0 fails (NULL, or ENOMEM
 * from posix_memalign) and sets it to -1, so exactly the (N + 1)-th allocation after setting it
 * to N fails. rg2__fi_injected counts the failures injected, rg2__fi_calls the allocations,
 * rg2__fi_bytes the bytes they asked for (tests/test_scaling.c: work that must grow linearly).
 * Allocations inside cJSON, libpng, libc (fopen) and the thread runtimes are not counted. */
#ifdef RG2_FAULT_INJECT
#include <stdlib.h>
extern long rg2__fi_countdown, rg2__fi_injected, rg2__fi_calls;
extern unsigned long long rg2__fi_bytes;
void *rg2__fi_malloc(size_t n);
void *rg2__fi_calloc(size_t n, size_t size);
void *rg2__fi_realloc(void *p, size_t n);
char *rg2__fi_strdup(const char *s);
int rg2__fi_posix_memalign(void **p, size_t align, size_t n);
#define malloc(n) rg2__fi_malloc(n)
#define calloc(n, size) rg2__fi_calloc(n, size)
#define realloc(p, n) rg2__fi_realloc(p, n)
#define strdup(s) rg2__fi_strdup(s)
#define posix_memalign(p, align, n) rg2__fi_posix_memalign(p, align, n)
#endif

/* Overflow-checked allocation of n * size bytes (zeroed); NULL on failure or overflow. */
void *rg2__calloc(size_t n, size_t size);
/* The same for large arrays (src/alloc.c): from 2 MiB up, 2 MiB-aligned on transparent huge
 * pages where the system has them. Freed with free(). */
void *rg2__calloc_big(size_t n, size_t size);
/* The same from `from` bytes up instead of 2 MiB (arrays allocated and freed at every call),
 * zeroed only when zero is non-zero (else memory the caller overwrites); NULL on overflow. */
void *rg2__alloc_big(size_t n, size_t size, size_t from, int zero);

/* An output file written whole or not at all (src/outfile.c): data goes to a new temporary
 * file next to path, "<path>.<pid>.tmp" (f), renamed to path when complete, removed on
 * failure, so a failed write leaves no file. Or an output into memory (mem): f an anonymous
 * temporary file (tmpfile: the writers seek), read into data (size bytes and a 0) when
 * finished; path is then only the name the headers and messages give. */
typedef struct {
    FILE *f;
    const char *path;
    char *tmp;
    int mem;
    char *data;
    size_t size;
} rg2__out;

rg2_status rg2__out_open(rg2__out *o, const char *path, rg2_error *err);
rg2_status rg2__out_open_memory(rg2__out *o, const char *name, rg2_error *err);
/* Finish writing: if st == RG2_OK, flush and check for write errors (the complete file stays
 * at o->tmp for rg2__out_commit); otherwise, or on a write error, remove it. Returns the final
 * status. */
rg2_status rg2__out_finish(rg2__out *o, rg2_status st, rg2_error *err);
/* Rename a finished file to its path. */
rg2_status rg2__out_commit(rg2__out *o, rg2_error *err);
/* Close (if open) and remove the temporary file (free the data of an output into memory). */
void rg2__out_discard(rg2__out *o);
/* rg2__out_finish, then rg2__out_commit on success. */
rg2_status rg2__out_close(rg2__out *o, rg2_status st, rg2_error *err);

/* Run fn(arg, c) for the chunks c = 0..n-1 on up to nthreads threads (src/pool.c): the caller
 * and persistent workers claim chunks, each from its own contiguous home block first, then from
 * the others'; the call returns when every chunk is done and never waits for a worker that has
 * not claimed one. Chunks must be independent. */
#include <stdint.h>
typedef void (*rg2__pool_fn)(void *arg, uint32_t chunk);
void rg2__pool_run(int nthreads, uint32_t n, rg2__pool_fn fn, void *arg);
/* rg2_tessellate (no curvature) on up to `threads` threads of the pool (0: the OpenMP default,
 * 1: serial); the same mesh, bit for bit, for any count. */
rg2_status rg2__tessellate_threads(const rg2_surface *s, int density, int threads, rg2_tess *out, rg2_error *err);
/* rg2_find_crossings runs the steps after the tessellation on one thread below this many
 * triangles (src/intersect.c; tests set it to 0 before their threads start). */
extern int rg2__crossing_threads_from;

/* The curve construction of MATH.md eq. 3-4 as a linear stencil: Bezier coefficient r
 * (0..3) of output segment k is sum_a c[k][r][a] * p^{first[k] + a}, a = 0..3 (indices
 * mod n for closed directions). w[k] is the segment's middle weight. */
typedef struct {
    int n_segments;
    int n, closed;
    int *first;             /* n_segments: index of p^{i-1} (may be -1..n-1 before wrapping) */
    double (*c)[4][4];      /* n_segments x 4 x 4 */
    double *w;              /* n_segments */
    double *bj, *gj;        /* n_segments: scalars of the junction at the segment's start */
} rg2__stencil;

rg2_status rg2__stencil_make(const rg2_scalars *s, rg2__stencil *st, rg2_error *err);
void rg2__stencil_free(rg2__stencil *st);
/* Wrap control point index a into 0..n-1 (closed) or assert range (open). */
static inline int rg2__wrap(int a, int n, int closed)
{
    if (closed) {
        a %= n;
        if (a < 0)
            a += n;
    }
    return a;
}

static inline int rg2__finite(double x) { return isfinite(x); }

/* An angle within one turn: a start angle of many turns (1e20 rad) has junction angles a +
 * alpha_0 + ... that round to a itself; sin and cos reduce it exactly, and an angle within one
 * turn keeps its bits. */
static inline double rg2__within_turn(double a)
{
    return fabs(a) <= 2.0 * M_PI ? a : atan2(sin(a), cos(a));
}

/* Position, derivatives, normal and curvatures of an evaluation from the homogeneous values
 * H[d][k] (d = value, d/du, d/dv, d2/du2, d2/dudv, d2/dv2) up to `order` (eval.c). */
void rg2__eval_from_h(double H[6][4], int order, rg2_eval *e);

/* Row r's share of the homogeneous values in rg2__eval_hom's order: H[0] += B c0, then (rows >= 3)
 * H[1] += D c0, H[2] += B c1, then (rows == 6) H[3] += DD c0, H[4] += D c1, H[5] += B c2, where
 * B, D, DD are row r's Bernstein value and derivatives and c0, c1, c2 its column sums. */
static inline void rg2__hom_row(double H[6][4], int rows, double B, double D, double DD, const double c0[4],
                                const double c1[4], const double c2[4])
{
    for (int k = 0; k < 4; k++)
        H[0][k] += B * c0[k];
    if (rows < 3)
        return;
    for (int k = 0; k < 4; k++) {
        H[1][k] += D * c0[k];
        H[2][k] += B * c1[k];
    }
    if (rows < 6)
        return;
    for (int k = 0; k < 4; k++) {
        H[3][k] += DD * c0[k];
        H[4][k] += D * c1[k];
        H[5][k] += B * c2[k];
    }
}

/* Homogeneous values (value, d/du, d/dv, d2/du2, d2/dudv, d2/dv2) up to `order` of a rational
 * Bezier patch of degree (du, dv) with control point (r, s) coordinate k at h[r rs + s ss + k]
 * (eval.c; both patch kinds). */
void rg2__eval_hom(const double *h, int du, int dv, size_t rs, size_t ss, double u, double v, int order,
                   double out[6][4]);

/* Bernstein basis of degree n <= RG2_MAX_DEGREE and its first two derivatives at t (D, DD
 * nullable), in the summation order of rg2__bern3 for n = 3 (xpatch.c). */
void rg2__bern(int n, double t, double *B, double *D, double *DD);

/* Test hook (grid.c): non-zero makes the grid evaluator use its portable kernels even on CPUs
 * with AVX-512, so tests cover both. */
extern int rg2__grid_portable;
extern int rg2__grid_hwdiv; /* test hook: -1 by CPU, 0 Newton steps, 1 hardware division */
extern int rg2__grid_spread; /* test hook: 0 keeps the normals of wide rows in two phases (grid.c) */
extern size_t rg2__grid_stream_bytes; /* test hook: outputs past this per thread stream (grid.c) */
extern int rg2__grid_pages; /* test hook: -1 by CPU, 0/1 streamed outputs touch their pages ahead (grid.c) */
extern int rg2__surface_portable; /* test hook: 1 builds surfaces on the portable path (surface.c) */
/* Test hook: whether the grid's tables cache (grid.c) holds the tables of n x m points. */
int rg2__grid_tables_cached(int n, int m);
/* Test hook (outfile.c): the longest file name in directory dir, -1 for none known; pathconf's
 * _PC_NAME_MAX unless a test sets another. */
extern long (*rg2__dir_name_max)(const char *dir);
/* Test hook (iges.c): the largest sequence number of an IGES section, 9,999,999 (7 columns). */
extern int rg2__iges_max_records;

/* The grid evaluator for higher-degree patches (xpatch.c; rg2_surface_grid calls it for the
 * patches with xp[k].du > 0): Bernstein tables of the degrees present at the n x m grid
 * parameters (make: RG2_ENOMEM), then all points of one patch written at point index `first` of
 * out, each equal to rg2_xpatch_eval's bit for bit. */
typedef struct {
    int n, m, order;
    double *tab[2][RG2_MAX_DEGREE + 1]; /* [u or v][degree d]: per parameter B, D, DD (3 (d + 1)) */
    double *mem;
} rg2__xgrid;
rg2_status rg2__xgrid_make(const rg2_surface *s, int n, int m, const rg2_grid_out *out, rg2__xgrid *t,
                           rg2_error *err);
void rg2__xgrid_free(rg2__xgrid *t);
void rg2__xgrid_patch(const rg2_xpatch *x, const rg2__xgrid *t, const rg2_grid_out *out, size_t first);

/* Each patch's homogeneous control values times one power of two (projectively the same patch;
 * positions, normals and curvatures evaluate to the same bits) where its largest weight lies
 * outside [2^-32, 2^32]: the grid kernels' normal formulas carry w^8 (w^2 Su x w^2 Sv, squared),
 * which leaves the double range for weights as far out as 1e-40 or 1e40. */
void rg2__surface_normalize_weights(rg2_surface *s);
/* RG2_ENONFINITE naming "<what>: surface <index> patch (i,j)" if a control value is not finite. */
rg2_status rg2__surface_check_finite(const rg2_surface *s, const char *what, int index, rg2_error *err);
/* The leg before junction i as users number legs: i - 1, wrapped in a closed direction (junction
 * 0 of a closed u follows leg n - 1, not -1; open directions have the data-only leg -1). */
int rg2__prev_leg(const rg2_scalars *s, int i);
/* rg2_scalars_from_knots whose refusal of junction scalars out of the double range names the
 * knots as "<name>[k + first]" after "<who>: " (rg2_nurbs_mesh: "nurbs: knots_u", "knots_u", 1;
 * a shape's open knots partition: "knots", "values", -2); first = 0 also names the junction. */
rg2_status rg2__scalars_from_knots_named(rg2_scalars *s, const double *knots, int n_knots, int closed,
                                         const char *who, const char *name, int first, rg2_error *err);

/* Switch this thread to the "C" locale for numbers written into files (src/clocale.c); pass
 * the returned value to rg2__c_numeric_end to switch back. */
void *rg2__c_numeric_begin(void);
void rg2__c_numeric_end(void *old);

/* cJSON's parse (ParseWithLengthOpts, NUL required at text[len - 1]) and print (formatted or
 * not), serialised and in the "C" locale (src/json.c); print's text is freed with cJSON_free. */
struct cJSON;
/* The length of the UTF-8 sequence at p (at most n bytes there), 0 if it is not one
 * (src/textfile.c). */
size_t rg2__utf8_len(const unsigned char *p, size_t n);
/* A copy of s (free it) with each byte that is not UTF-8 replaced by '?' and, when control is
 * not 0, each control character by control; NULL when out of memory. */
char *rg2__text_clean(const char *s, char control);
struct cJSON *rg2__json_parse(const char *text, size_t len, const char **end);
char *rg2__json_print(const struct cJSON *item, int formatted);
/* A number item (an array of n) whose printed text reads back to the same double (cJSON's own
 * printing may drop an ulp; src/json.c). */
struct cJSON *rg2__json_double(double x);
/* Its text for a finite x: the shortest of 15, 16 and 17 digits (%.*g) that reads back to x, in
 * the calling thread's locale (call it in the "C" locale, rg2__c_numeric_begin). */
void rg2__json_number_text(double x, char buf[40]);
struct cJSON *rg2__json_doubles(const double *x, int n);

/* A bounding box grown point by point: its largest |coordinate| and its diagonal. */
typedef struct {
    double lo[3], hi[3];
} rg2__box;
static inline void rg2__box_init(rg2__box *b)
{
    for (int q = 0; q < 3; q++) {
        b->lo[q] = INFINITY;
        b->hi[q] = -INFINITY;
    }
}
/* Add the point x / w (w = 1 for a Euclidean point). */
static inline void rg2__box_add(rg2__box *b, const double *x, double w)
{
    for (int q = 0; q < 3; q++) {
        b->lo[q] = fmin(b->lo[q], x[q] / w);
        b->hi[q] = fmax(b->hi[q], x[q] / w);
    }
}
static inline void rg2__box_extent(const rg2__box *b, double *big, double *diag)
{
    *big = *diag = 0.0;
    for (int q = 0; q < 3; q++) {
        *big = fmax(*big, fmax(fabs(b->lo[q]), fabs(b->hi[q])));
        *diag = hypot(*diag, b->hi[q] - b->lo[q]);
    }
}
/* RG2_EDOMAIN naming "<what>: surface <index>" if its control points (weight 0 skipped) reach
 * beyond RG2_DESIGN_MAX_COORD or span less than RG2_DESIGN_MIN_SIZE: past about 1e+-75 the
 * grid kernels' normal and curvature formulas leave the double range (a torus of size 1e80
 * tessellated to NaN normals). */
rg2_status rg2__surface_check_range(const rg2_surface *s, const char *what, int index, rg2_error *err);
/* p = M p for a homogeneous 4-tuple p (row-major M), as rg2_mesh_transform does per point. */
void rg2__xform_apply(const double M[16], double p[4]);
/* The world matrix A = X M X^-1 of a Moebius map about the reference s (a placed sphere or
 * ellipsoid, X its placement; NULL: the unit sphere): M by eq. (16) from *b, or (b NULL) taking
 * the reference's poles to south and north (world coordinates). The design's `mobius` and
 * rg2_mesh_mobius_shape (mobius.c: the messages' keys). */
rg2_status rg2__mobius_world(const rg2_shape *s, const char *label, const double *b, const double *south,
                             const double *north, double A[16], const char *what, const char *refkey,
                             const char *poleskey, rg2_error *err);

/* Two tangent vectors a, b scaled in place by one power of two 2^-e (exact), when the largest
 * |component| m lies outside [2^-128, 2^128]: then m becomes 1 <= m < 2 and the squares and
 * products of squares of the normal and curvature formulas stay inside the double range (they
 * over- or underflow past |a| |b| ~ 1e+-154 otherwise). Returns the factor 2^-e (1.0 in the usual
 * range, where nothing changes). */
static inline double rg2__scale_pair(double a[3], double b[3])
{
    double m = 0.0;
    for (int k = 0; k < 3; k++) { /* m = fmax(m, fmax(|a_k|, |b_k|)), inline (no libm call) */
        double x = fabs(a[k]), y = fabs(b[k]);
        x = y > x || x != x ? y : x;
        m = x > m || m != m ? x : m;
    }
    if (!(m > 0x1p-128 && m < 0x1p128) && m > 0.0 && m <= 1.79e308) {
        int e = ilogb(m);
        double t = ldexp(1.0, e < -1000 ? 1000 : -e); /* (subnormal m: 2^1000, not past the range) */
        for (int k = 0; k < 3; k++) {
            a[k] *= t;
            b[k] *= t;
        }
        return t;
    }
    return 1.0;
}

/* The normal test of rg2_patch_eval, shared with rg2_patch_point_normal so their flags agree:
 * c = su x sv, *len = |c|; defined (returns 1) when |c| > 1e-14 (|su|^2 + |sv|^2) (relative to
 * the sum, not |su| |sv|: on a collapsed edge one derivative is rounding noise) and neither
 * derivative is at the level of its own rounding error, |su| > 1e-13 ru and |sv| > 1e-13 rv
 * (a pole with a short transversal derivative would pass the first test). su, sv may carry a
 * common positive factor (w, or rg2__scale_pair's) if ru, rv carry it too. */
static inline int rg2__normal_test_weak(const double su[3], const double sv[3], double ru, double rv, double c[3],
                                        double *len);
static inline int rg2__normal_test(const double su[3], const double sv[3], double ru, double rv, double c[3],
                                   double *len)
{
    return rg2__normal_test_weak(su, sv, ru, rv, c, len) != 0;
}
/* rg2__normal_test, returning 2 instead of 1 where the tangents are weak (rg2__tangents_weak, below:
 * |c| <= 1e-6 (|su|^2 + |sv|^2)), from the sums it has formed anyway. */
static inline int rg2__normal_test_weak(const double su[3], const double sv[3], double ru, double rv, double c[3],
                                        double *len)
{
    c[0] = su[1] * sv[2] - su[2] * sv[1];
    c[1] = su[2] * sv[0] - su[0] * sv[2];
    c[2] = su[0] * sv[1] - su[1] * sv[0];
    *len = sqrt(c[0] * c[0] + c[1] * c[1] + c[2] * c[2]);
    double E = su[0] * su[0] + su[1] * su[1] + su[2] * su[2], G = sv[0] * sv[0] + sv[1] * sv[1] + sv[2] * sv[2];
    if (!(*len > 1e-14 * (E + G) && !(sqrt(E) <= 1e-13 * ru) && !(sqrt(G) <= 1e-13 * rv)))
        return 0;
    return __builtin_expect(*len <= 1e-6 * (E + G), 0) ? 2 : 1;
}

/* On a side of a patch that collapses to a point (a pole) the derivative along the side is the
 * noise of the side's stored control points, which are equal only projectively (up to about
 * 1e-12 of the size after the construction's rounding), not of the evaluation: the rounding
 * levels of rg2__normal_test do not see it, and it can pass (Fig. 14's second sphere, patch
 * (5, 0) at u = 63/128, v = 0: a normal 77 degrees off and K = -1.5e29). The cheap trigger is a
 * point on a side (u or v exactly 0 or 1, rg2__on_side) whose tangents span almost no area,
 * |su x sv| <= 1e-6 (|su|^2 + |sv|^2) (rg2__tangents_weak: at the poles one tangent is about
 * 1e-13 of the other; at ordinary points the ratio is half the sine of their angle); then
 * rg2__xpatch_pole_at / rg2__patch_pole_at (xpatch_util.c) test the sides the point is on as the
 * exporters, the tessellation and the grid do (rg2__xpatch_side_collapsed with rg2__collapse_tol
 * over the patch alone), and rg2__eval_undefine makes the normal and the curvatures undefined
 * there, as rg2.h promises for poles. */
static inline int rg2__on_side(double u, double v)
{
    return u == 0.0 || u == 1.0 || v == 0.0 || v == 1.0;
}
static inline int rg2__tangents_weak(const double su[3], const double sv[3])
{
    double c0 = su[1] * sv[2] - su[2] * sv[1], c1 = su[2] * sv[0] - su[0] * sv[2], c2 = su[0] * sv[1] - su[1] * sv[0];
    double E = su[0] * su[0] + su[1] * su[1] + su[2] * su[2], G = sv[0] * sv[0] + sv[1] * sv[1] + sv[2] * sv[2];
    return sqrt(c0 * c0 + c1 * c1 + c2 * c2) <= 1e-6 * (E + G);
}
static inline int rg2__pole_suspect(double u, double v, const double su[3], const double sv[3])
{
    return rg2__on_side(u, v) && rg2__tangents_weak(su, sv);
}
int rg2__patch_pole_at(const rg2_patch *P, double u, double v);
int rg2__xpatch_pole_at(const rg2_xpatch *X, double u, double v);
/* The sides (bit k: 0 v=0, 1 u=1, 2 v=1, 3 u=0) that (u, v) lies on and that collapse, tested as
 * rg2__xpatch_pole_at does. */
unsigned rg2__xpatch_pole_sides(const rg2_xpatch *X, double u, double v);
/* The sides among `cand` (the same bits) that collapse, with rg2__collapse_tol taken over this
 * patch alone (xpatch_util.c; also the grid's pole_sides). */
unsigned rg2__xpatch_collapsed_among(const rg2_xpatch *X, unsigned cand);
/* The limit normal and the curvatures next to the pole on collapsed side `side` of patch (i, j)
 * (limit.c), into e, an order-2 evaluation at (u, v) on that side: n, K, H, k1, k2 (curvatures of
 * `order` 1 or 2) and flags (RG2_EVAL_POLE_LIMIT where the normal is defined). The tessellation's and
 * rg2_surface_eval_limit's. */
void rg2__pole_limit(const rg2_surface *s, int i, int j, double u, double v, int side, int order, rg2_eval *e);
/* The grid calls' argument checks (grid.c: out, out->pos, n and m), shared with
 * rg2__surface_patch_grid. */
rg2_status rg2__grid_check_args(int n, int m, const rg2_grid_out *out, rg2_error *err);
static inline void rg2__eval_undefine(rg2_eval *e)
{
    e->flags |= RG2_EVAL_NORMAL_UNDEFINED | RG2_EVAL_CURVATURE_UNDEFINED;
    e->n[0] = e->n[1] = e->n[2] = 0.0;
    e->K = e->H = e->k1 = e->k2 = 0.0;
}

/* Bernstein cubic basis and derivatives at t. */
static inline void rg2__bern3(double t, double B[4], double D[4], double DD[4])
{
    double s = 1.0 - t;
    B[0] = s * s * s;
    B[1] = 3.0 * t * s * s;
    B[2] = 3.0 * t * t * s;
    B[3] = t * t * t;
    if (D) {
        D[0] = -3.0 * s * s;
        D[1] = 3.0 * s * s - 6.0 * t * s;
        D[2] = 6.0 * t * s - 3.0 * t * t;
        D[3] = 3.0 * t * t;
    }
    if (DD) {
        DD[0] = 6.0 * s;
        DD[1] = 18.0 * t - 12.0;
        DD[2] = 6.0 - 18.0 * t;
        DD[3] = 6.0 * t;
    }
}

/* Whether line idx across direction dir of m (dir 1: the u-row j = idx, all i; dir 0: the
 * v-column i = idx, all j) is collapsed to one point: all its 4-tuples projectively equal to
 * 1e-12 of the mesh size (its largest affine coordinate). rg2_mesh_row_collapsed is dir 1. */
int rg2__mesh_line_collapsed(const rg2_mesh *m, int dir, int idx);
/* The full knot vector (m + 4 knots, RG2_PART_KNOTS_FULL) of a polar configuration of the
 * interior knots v_1..v_m (poles.c, docs/poles.md): sphere, ellipsoid rg2_polar_knots; paraboloid,
 * hyperboloid2 -v_1, 0, v_1..v_m, v_m + d, v_m + 2d (d = v_m - v_{m-1}; *north = 0), or for knots
 * below 0 v_1 - 2d, v_1 - d, v_1..v_m, 0, -v_m (d = v_2 - v_1; *north = 1, the pole is the last
 * row). Messages start "polar knots: ". */
rg2_status rg2__polar_full_knots(rg2_shape_kind kind, const double *v, int m, double *k, int *north,
                                 rg2_error *err);
/* The clamped ends of a NURBS (rg2_nurbs_mesh accepted it) whose control line is one point: bit k
 * (the sides of a patch: 0 v = 0, 1 u = 1, 2 v = 1, 3 u = 0) where the end is clamped (U_1 = U_2 =
 * U_3, or U_n = U_{n+1} = U_{n+2}) and every point of its first / last line has exactly the same
 * x, y and z (weights may differ); p[k] that point (nurbs.c). */
unsigned rg2__nurbs_pole_ends(const rg2_nurbs *nb, double p[4][3]);
/* Make the open sides `sides` (bits as above) of a bi-3 surface the points p[k]: each control
 * point h on side k becomes (h_w p[k], h_w), keeping its weight (nurbs.c). */
void rg2__surface_set_poles(rg2_surface *s, unsigned sides, const double p[4][3]);
/* Row j of m made its first point, bit for bit (a polar row). */
void rg2__collapse_row(rg2_mesh *m, int j);

/* A shape's implicit function with its placement inverted once (rg2_shape_implicit2 inverts
 * it per call): prep once per shape, then evaluate at many points, with the same bits. */
typedef struct {
    const rg2_shape *s;
    double inv[16];
    int ok; /* 0: invalid parameters or singular placement (every value NaN) */
} rg2__implicit;
void rg2__implicit_prep(const rg2_shape *s, rg2__implicit *p);
double rg2__implicit_eval(const rg2__implicit *p, const double x[3], double grad[3], double hess[9]);

/* The shape's limits on the produced knots of its v partition (sphere and ellipsoid bands in
 * (0, 1), hyperboloid1 v > 0, hyperboloid2 |v| < 1), as rg2_shape_mesh checks them: RG2_EDOMAIN
 * naming the kind and the knot ("sphere: v knot 0 = 0 must lie in (0, 1) (...)"). */
rg2_status rg2__shape_check_range(const rg2_shape *s, const rg2_partition *pv, rg2_error *err);

/* msg past its leading `prefix` (a context a caller's own prefix replaces), or msg itself when it
 * does not start with it. */
static inline const char *rg2__after(const char *msg, const char *prefix)
{
    size_t n = strlen(prefix);
    return strncmp(msg, prefix, n) ? msg : msg + n;
}

#endif
