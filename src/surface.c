/* surface.c -- the Bi-cubic Construction (paper section 3, MATH.md section 4): a control
 * mesh of 4-tuples becomes a grid of rational bi-3 Bezier patches. */
#include "internal.h"
#include "xpatch_util.h"

#include <float.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

void rg2_surface_free(rg2_surface *s)
{
    if (!s)
        return;
    free(s->patch);
    free(s->bu);
    free(s->gu);
    free(s->bv);
    free(s->gv);
    free(s->tag);
    free(s->xp);
    memset(s, 0, sizeof *s);
}

static rg2_status surface_alloc(rg2_surface *s, int nu, int nv, int with_tag, rg2_error *err)
{
    memset(s, 0, sizeof *s);
    s->patch = rg2__calloc_big((size_t)nu * (size_t)nv, sizeof(rg2_patch));
    s->bu = rg2__calloc((size_t)nu, sizeof(double));
    s->gu = rg2__calloc((size_t)nu, sizeof(double));
    s->bv = rg2__calloc((size_t)nv, sizeof(double));
    s->gv = rg2__calloc((size_t)nv, sizeof(double));
    if (with_tag)
        s->tag = rg2__calloc((size_t)nu * (size_t)nv, sizeof(int));
    if (!s->patch || !s->bu || !s->gu || !s->bv || !s->gv || (with_tag && !s->tag)) {
        rg2_surface_free(s);
        return rg2__fail(err, RG2_ENOMEM, "surface: out of memory for %d x %d patches", nu, nv);
    }
    s->nu = nu;
    s->nv = nv;
    return RG2_OK;
}

rg2_status rg2_surface_copy(const rg2_surface *src, rg2_surface *dst, rg2_error *err)
{
    if (!src || !dst) {
        if (dst)
            memset(dst, 0, sizeof *dst);
        return rg2__fail(err, RG2_EINVAL, "surface copy: NULL %s", src ? "destination" : "source");
    }
    if (src == dst) /* (filling dst from scratch zeroed src first: an all-zero surface, returning RG2_OK) */
        return rg2__fail(err, RG2_EINVAL, "surface copy: the destination is the source; give a surface of its own");
    if (src->nu < 0 || src->nv < 0 || ((size_t)src->nu * (size_t)src->nv > 0 && !src->patch)) {
        memset(dst, 0, sizeof *dst); /* (a failed call leaves its output zeroed, rg2.h) */
        return rg2__fail(err, RG2_EINVAL, "surface copy: the source is not a surface (%d x %d patches, patch array %s)",
                         src->nu, src->nv, src->patch ? "set" : "NULL");
    }
    if (src->nu == 0 || src->nv == 0 || !src->patch) { /* an empty surface (e.g. after a failed build) */
        memset(dst, 0, sizeof *dst);
        rg2__ok(err);
        return RG2_OK;
    }
    rg2_status st = surface_alloc(dst, src->nu, src->nv, src->tag != NULL, err);
    if (st)
        return st;
    size_t np = (size_t)src->nu * (size_t)src->nv;
    dst->closed_u = src->closed_u;
    dst->closed_v = src->closed_v;
    memcpy(dst->patch, src->patch, np * sizeof(rg2_patch));
    memcpy(dst->bu, src->bu, (size_t)src->nu * sizeof(double));
    memcpy(dst->gu, src->gu, (size_t)src->nu * sizeof(double));
    memcpy(dst->bv, src->bv, (size_t)src->nv * sizeof(double));
    memcpy(dst->gv, src->gv, (size_t)src->nv * sizeof(double));
    if (src->tag)
        memcpy(dst->tag, src->tag, np * sizeof(int));
    if (src->xp) {
        dst->xp = rg2__calloc(np, sizeof(rg2_xpatch));
        if (!dst->xp) {
            rg2_surface_free(dst);
            return rg2__fail(err, RG2_ENOMEM, "surface: out of memory for %zu patches", np);
        }
        memcpy(dst->xp, src->xp, np * sizeof(rg2_xpatch));
    }
    rg2__ok(err);
    return RG2_OK;
}

/*
 * METHOD: the curve construction is linear in the points, so it is a stencil per direction
 * (rg2__stencil_make). Rows first: for u-segment k, R[r][j] = sum_a cu[k][r][a] p^{iu+a, j}
 * for every mesh column j; then columns: b_rs = sum_c cv[l][s][c] R[r][jv+c]. Homogeneous
 * control points H_rs = omega_r omega'_s b_rs with omega = (1, w, w, 1). With AVX-512 each patch
 * is made whole in registers from its 4 x 4 mesh points, both stages over 8 values a vector, the
 * rows stage again for each patch, streamed past RG2_BUILD_STREAM_BYTES (build 2x and rebuild 3x
 * faster at 1000 x 1000 on the Intel Xeon machine, docs/performance.md); the same operations in
 * the same order per value, so the same bits as the portable path (tests/test_surface.c compares
 * them).
 *
 * build_into: out holds a surface (or zeros); its arrays are kept when its patch counts are those
 * of m (no fresh memory, so no page faults: an editing loop), else freed and allocated anew. On
 * failure out is left empty.
 */
/* The homogeneous values of n doubles (4-tuples, weight last) times 2^-e, where 2^e <= the largest
 * weight < 2^(e+1), if that weight lies outside [2^-32, 2^32]. */
static void normalize_weights(double *h, int n)
{
    double m = 0.0;
    for (int q = 3; q < n; q += 4)
        m = fmax(m, fabs(h[q]));
    if (!(m > 0.0) || (m >= 0x1p-32 && m <= 0x1p32) || !(m <= DBL_MAX))
        return;
    double t = ldexp(1.0, -ilogb(m));
    for (int q = 0; q < n; q++)
        h[q] *= t;
}

/* Rows stage at mesh column j for u-segment k: R[r * nv + j][q] = sum_a cu[k][r][a] p^{first + a, j}[q]. */
static inline void rows_at(const rg2_mesh *m, const rg2__stencil *su, int k, int j, double (*R)[4])
{
    for (int r = 0; r < 4; r++) {
        double acc[4] = {0, 0, 0, 0};
        for (int a = 0; a < 4; a++) {
            double c = su->c[k][r][a];
            if (c == 0.0)
                continue;
            const double *p = rg2_mesh_at(m, rg2__wrap(su->first[k] + a, m->nu, su->closed), j);
            for (int q = 0; q < 4; q++)
                acc[q] += c * p[q];
        }
        memcpy(R[(size_t)r * (size_t)m->nv + (size_t)j], acc, sizeof acc);
    }
}

/* Columns stage of patch (k, l) from the rows R[r * nv + jc[c]] of its four mesh columns (nv of
 * them in all), times the weights omega_r omega'_s. */
static inline void columns_at(double (*R)[4], size_t nv, const int jc[4], const rg2__stencil *su, int k,
                              const rg2__stencil *sv, int l, rg2_patch *P)
{
    double omu[4] = {1.0, su->w[k], su->w[k], 1.0};
    double omv[4] = {1.0, sv->w[l], sv->w[l], 1.0};
    for (int r = 0; r < 4; r++)
        for (int s = 0; s < 4; s++) {
            double acc[4] = {0, 0, 0, 0};
            for (int c = 0; c < 4; c++) {
                double cc = sv->c[l][s][c];
                if (cc == 0.0)
                    continue;
                const double *q = R[(size_t)r * nv + (size_t)jc[c]];
                for (int d = 0; d < 4; d++)
                    acc[d] += cc * q[d];
            }
            double om = omu[r] * omv[s];
            for (int d = 0; d < 4; d++)
                P->h[r][s][d] = om * acc[d];
        }
}

#if defined(__GNUC__) && defined(__x86_64__) && !defined(RG2_NO_CLONES)
#include <immintrin.h>

/* The patch's 4 x 4 control points of m gathered where its columns wrap around a closed v:
 * Q[a][4 c + d] is value d of point (first_u + a, first_v + c). */
static inline void mesh_patch_points(const rg2_mesh *m, const rg2__stencil *su, const rg2__stencil *sv, int k,
                                     int l, double Q[4][16])
{
    for (int a = 0; a < 4; a++) {
        int i = rg2__wrap(su->first[k] + a, m->nu, su->closed);
        for (int c = 0; c < 4; c++)
            memcpy(Q[a] + 4 * c, rg2_mesh_at(m, i, rg2__wrap(sv->first[l] + c, m->nv, sv->closed)),
                   4 * sizeof(double));
    }
}

/* Patch (k, l) of the surface of m with AVX-512: the same multiplications and additions, value by
 * value, in the same order as rows_at and columns_at (so the same bits; the sums start from +0 as
 * theirs do), the finiteness test and normalize_weights' range test on the registers; stream:
 * streaming stores. 0 if a control value is not finite (P as computed), else 1 (P normalized). */
__attribute__((target("avx512f"))) static int mesh_patch_avx512(const rg2_mesh *m, const rg2__stencil *su,
                                                                const rg2__stencil *sv, int k, int l,
                                                                rg2_patch *P, int stream)
{
    const double *row[4];
    _Alignas(64) double Q[4][16];
    int j0 = sv->first[l];
    if (j0 >= 0 && j0 + 3 < m->nv) /* the usual case: each row's 4 points lie side by side */
        for (int a = 0; a < 4; a++)
            row[a] = rg2_mesh_at(m, rg2__wrap(su->first[k] + a, m->nu, su->closed), j0);
    else {
        mesh_patch_points(m, su, sv, k, l, Q);
        for (int a = 0; a < 4; a++)
            row[a] = Q[a];
    }
    const __m512d zero = _mm512_setzero_pd();
    __m512d Rlo[4], Rhi[4];
    for (int r = 0; r < 4; r++) { /* R[r][4 c + d] = sum_a cu[r][a] Q[a][4 c + d] */
        __m512d lo = zero, hi = zero;
        for (int a = 0; a < 4; a++) {
            __m512d cf = _mm512_set1_pd(su->c[k][r][a]);
            lo = _mm512_add_pd(lo, _mm512_mul_pd(cf, _mm512_loadu_pd(row[a])));
            hi = _mm512_add_pd(hi, _mm512_mul_pd(cf, _mm512_loadu_pd(row[a] + 8)));
        }
        Rlo[r] = lo, Rhi[r] = hi;
    }
    /* X[c] over (s, d): cv[s][c]; the stencil row-major as two vectors [s 0..1][c], [s 2..3][c] */
    __m512d cva = _mm512_loadu_pd(&sv->c[l][0][0]), cvb = _mm512_loadu_pd(&sv->c[l][2][0]), Xlo[4], Xhi[4];
    for (int c = 0; c < 4; c++) {
        __m512i idx = _mm512_set_epi64(4 + c, 4 + c, 4 + c, 4 + c, c, c, c, c);
        Xlo[c] = _mm512_permutexvar_pd(idx, cva);
        Xhi[c] = _mm512_permutexvar_pd(idx, cvb);
    }
    double w = sv->w[l];
    __m512d omlo = _mm512_set_pd(w, w, w, w, 1, 1, 1, 1), omhi = _mm512_set_pd(1, 1, 1, 1, w, w, w, w);
    __m512d h[8];
    for (int r = 0; r < 4; r++) { /* h[r][s][d] = (om_r om_s) sum_c cv[s][c] R[r][4 c + d] */
        __m512d x[4] = {_mm512_shuffle_f64x2(Rlo[r], Rlo[r], 0x44), _mm512_shuffle_f64x2(Rlo[r], Rlo[r], 0xEE),
                        _mm512_shuffle_f64x2(Rhi[r], Rhi[r], 0x44), _mm512_shuffle_f64x2(Rhi[r], Rhi[r], 0xEE)};
        __m512d lo = zero, hi = zero;
        for (int c = 0; c < 4; c++) {
            lo = _mm512_add_pd(lo, _mm512_mul_pd(Xlo[c], x[c]));
            hi = _mm512_add_pd(hi, _mm512_mul_pd(Xhi[c], x[c]));
        }
        __m512d ou = _mm512_set1_pd(r == 1 || r == 2 ? su->w[k] : 1.0);
        h[2 * r] = _mm512_mul_pd(_mm512_mul_pd(ou, omlo), lo);
        h[2 * r + 1] = _mm512_mul_pd(_mm512_mul_pd(ou, omhi), hi);
    }
    __mmask8 finite = 0xFF, big = 0, small = 0;
    for (int q = 0; q < 8; q++) {
        __m512d a = _mm512_abs_pd(h[q]);
        finite &= _mm512_cmp_pd_mask(a, _mm512_set1_pd(DBL_MAX), _CMP_LE_OQ);
        big |= _mm512_cmp_pd_mask(a, _mm512_set1_pd(0x1p32), _CMP_GT_OQ);
        small |= _mm512_cmp_pd_mask(a, _mm512_set1_pd(0x1p-32), _CMP_GE_OQ);
    }
    double *dst = &P->h[0][0][0];
    if (finite != 0xFF || big & 0x88 || !(small & 0x88)) { /* not finite, or the largest weight
                                                               outside [2^-32, 2^32]: rare */
        for (int q = 0; q < 8; q++)
            _mm512_storeu_pd(dst + 8 * q, h[q]);
        if (finite != 0xFF)
            return 0;
        normalize_weights(dst, 64);
        return 1;
    }
    for (int q = 0; q < 8; q++)
        if (stream)
            _mm512_stream_pd(dst + 8 * q, h[q]);
        else
            _mm512_storeu_pd(dst + 8 * q, h[q]);
    return 1;
}
#define RG2_MESH_AVX512 1
#else
#define RG2_MESH_AVX512 0
#endif

static int patch_finite(const rg2_patch *P)
{
    const double *h = &P->h[0][0][0];
    for (int q = 0; q < 64; q++)
        if (!rg2__finite(h[q]))
            return 0;
    return 1;
}

/* Surfaces larger than this are written with streaming (cache-bypassing) stores on the AVX-512
 * path: a rebuild of 1000 x 1000 control points (0.5 GB of patches) took 97-98 ms instead of
 * 142-163, one of 316 x 316 (50 MB) 9.2-9.5 instead of 13.5-14.5 (Intel Xeon machine, 1 thread). */
#define RG2_BUILD_STREAM_BYTES ((size_t)16 << 20)
/* Test hook (tests/test_surface.c): 1 builds on the portable path on any CPU. */
int rg2__surface_portable = 0;

/* The patches of row k of the surface of m into out: mesh_patch_avx512 for each, or on the
 * portable path rows_at once per mesh column (into R, 4 nv 4-tuples) and columns_at for each
 * patch (the same bits). 0 if a patch overflows (its values left as computed), else 1. */
static int build_row(const rg2_mesh *m, const rg2__stencil *su, const rg2__stencil *sv, int k, double (*R)[4],
                     int stream, rg2_surface *out)
{
    int ok = 1, nv = m->nv;
#if RG2_MESH_AVX512
    if (!R) {
        for (int l = 0; l < sv->n_segments; l++)
            ok &= mesh_patch_avx512(m, su, sv, k, l, rg2_surface_patch(out, k, l), stream);
        if (stream)
            _mm_sfence();
        return ok;
    }
#else
    (void)stream;
#endif
    for (int j = 0; j < nv; j++)
        rows_at(m, su, k, j, R);
    for (int l = 0; l < sv->n_segments; l++) {
        int jc[4];
        for (int c = 0; c < 4; c++)
            jc[c] = rg2__wrap(sv->first[l] + c, nv, sv->closed);
        rg2_patch *P = rg2_surface_patch(out, k, l);
        columns_at(R, (size_t)nv, jc, su, k, sv, l, P);
        if (patch_finite(P))
            normalize_weights(&P->h[0][0][0], 64);
        else
            ok = 0;
    }
    return ok;
}

static rg2_status build_into(const rg2_mesh *m, rg2_surface *out, rg2_error *err)
{
    rg2__stencil su, sv;
    rg2_status st = rg2_mesh_check(m, err);
    if (!st && !(st = rg2__stencil_make(&m->su, &su, err)) && (st = rg2__stencil_make(&m->sv, &sv, err)))
        rg2__stencil_free(&su);
    if (st) {
        rg2_surface_free(out);
        return st;
    }
    int nsu = su.n_segments, nsv = sv.n_segments;
    if (out->patch && out->bu && out->gu && out->bv && out->gv && out->nu == nsu && out->nv == nsv) {
        free(out->tag); /* a built surface has neither tags nor higher-degree patches */
        free(out->xp);
        out->tag = NULL;
        out->xp = NULL;
    } else {
        rg2_surface_free(out);
        st = surface_alloc(out, nsu, nsv, 0, err);
        if (st)
            goto done;
    }
    out->closed_u = m->su.closed;
    out->closed_v = m->sv.closed;
    for (int k = 0; k < nsu; k++) {
        out->bu[k] = su.bj[k];
        out->gu[k] = su.gj[k];
    }
    for (int l = 0; l < nsv; l++) {
        out->bv[l] = sv.bj[l];
        out->gv[l] = sv.gj[l];
    }
    int portable = 1, overflow = 0, failed = 0, stream = 0;
#if RG2_MESH_AVX512
    portable = rg2__surface_portable || !__builtin_cpu_supports("avx512f");
    stream = !portable && ((uintptr_t)out->patch & 63) == 0 &&
             (size_t)nsu * (size_t)nsv * sizeof(rg2_patch) > RG2_BUILD_STREAM_BYTES;
#endif
#ifdef RG2_HAVE_OPENMP
#pragma omp parallel for schedule(static) if (nsu * nsv > 256)
#endif
    for (int k = 0; k < nsu; k++) {
        double(*R)[4] = NULL; /* the portable path's rows: R[r * nv + j][comp] */
        if (portable && !(R = malloc(sizeof(double[4]) * 4 * (size_t)m->nv))) {
#ifdef RG2_HAVE_OPENMP
#pragma omp atomic write
#endif
            failed = 1;
            continue;
        }
        if (!build_row(m, &su, &sv, k, R, stream, out)) {
#ifdef RG2_HAVE_OPENMP
#pragma omp atomic write
#endif
            overflow = 1;
        }
        free(R);
    }
    if (failed) {
        rg2_surface_free(out);
        st = rg2__fail(err, RG2_ENOMEM, "surface: out of memory during construction");
        goto done;
    }
    /* finite control points in, but the construction may overflow: refuse such a surface, naming
     * the first patch that did */
    for (size_t k = 0; overflow && k < (size_t)nsu * (size_t)nsv; k++)
        if (!patch_finite(&out->patch[k])) {
            int pi = (int)(k / (size_t)nsv), pj = (int)(k % (size_t)nsv);
            rg2_surface_free(out);
            st = rg2__fail(err, RG2_ENONFINITE,
                           "surface: patch (%d, %d) overflows (a control value is not finite); "
                           "the mesh coordinates or scalars are too large",
                           pi, pj);
            goto done;
        }
done:
    rg2__stencil_free(&su);
    rg2__stencil_free(&sv);
    return st;
}

void rg2__surface_normalize_weights(rg2_surface *s)
{
    size_t np = (size_t)s->nu * (size_t)s->nv;
    for (size_t k = 0; k < np; k++) {
        if (s->xp && s->xp[k].du > 0)
            normalize_weights(&s->xp[k].h[0][0][0], (RG2_MAX_DEGREE + 1) * (RG2_MAX_DEGREE + 1) * 4);
        else
            normalize_weights(&s->patch[k].h[0][0][0], 64);
    }
}

rg2_status rg2_surface_build(const rg2_mesh *m, rg2_surface *out, rg2_error *err)
{
    memset(out, 0, sizeof *out); /* out may hold garbage: nothing of it is kept */
    return build_into(m, out, err);
}

rg2_status rg2_surface_rebuild(const rg2_mesh *m, rg2_surface *s, rg2_error *err)
{
    if (!s)
        return rg2__fail(err, RG2_EINVAL, "surface: rebuild into a NULL surface");
    return build_into(m, s, err);
}

void rg2_surface_transform(rg2_surface *s, const double M[16])
{
    size_t np = (size_t)s->nu * (size_t)s->nv;
    for (size_t k = 0; k < np; k++) {
        if (rg2_surface_xpatch(s, (int)(k / (size_t)s->nv), (int)(k % (size_t)s->nv))) {
            rg2_xpatch *x = s->xp + k;
            for (int r = 0; r <= x->du; r++)
                for (int t = 0; t <= x->dv; t++)
                    rg2__xform_apply(M, x->h[r][t]);
        } else
            for (int r = 0; r < 4; r++)
                for (int t = 0; t < 4; t++)
                    rg2__xform_apply(M, s->patch[k].h[r][t]);
    }
}

int rg2_surface_box(const rg2_surface *s, double lo[3], double hi[3])
{
    return rg2__surface_ctrl_box(s, 1, lo, hi);
}

double rg2_surface_min_weight(const rg2_surface *s)
{
    double mn = INFINITY;
    size_t np = (size_t)s->nu * (size_t)s->nv;
    for (size_t k = 0; k < np; k++) {
        if (s->xp && s->xp[k].du > 0)
            continue; /* its bi-3 slots are NaN (and a NaN comparison raises FE_INVALID) */
        for (int r = 0; r < 4; r++)
            for (int t = 0; t < 4; t++)
                if (s->patch[k].h[r][t][3] < mn)
                    mn = s->patch[k].h[r][t][3];
    }
    if (s->xp)
        for (size_t k = 0; k < np; k++)
            for (int r = 0; r <= s->xp[k].du; r++)
                for (int t = 0; t <= s->xp[k].dv; t++)
                    if (s->xp[k].du > 0 && s->xp[k].h[r][t][3] < mn)
                        mn = s->xp[k].h[r][t][3];
    return mn;
}

rg2_status rg2__surface_check_finite(const rg2_surface *s, const char *what, int index, rg2_error *err)
{
    size_t np = (size_t)s->nu * (size_t)s->nv;
    for (size_t k = 0; k < np; k++) {
        int du, dv, st, ok = 1;
        const double *net = rg2__patch_net(s, k, &du, &dv, &st);
        for (int r = 0; r <= du; r++)
            for (int q = 0; q < 4 * (dv + 1); q++)
                ok &= rg2__finite(net[4 * r * st + q]);
        if (!ok)
            return rg2__fail(err, RG2_ENONFINITE, "%s: surface %d patch (%zu,%zu) has a non-finite control point",
                                 what, index, k / (size_t)s->nv, k % (size_t)s->nv);
    }
    return RG2_OK;
}

rg2_status rg2__surface_check_range(const rg2_surface *s, const char *what, int index, rg2_error *err)
{
    rg2__box box; /* (points of weight 0, at infinity, have no coordinates and are skipped) */
    size_t of;
    rg2__surface_ctrl_box_ex(s, 0, box.lo, box.hi, &of);
    if (of) /* finite h and w != 0 whose h / w overflows: no coordinates either */
        return rg2__fail(err, RG2_EDOMAIN,
                         "%s: surface %d patch (%zu,%zu) has a control point whose coordinates h / w overflow: "
                         "outside the range its normals and curvatures are evaluated in (coordinates up to %g); "
                         "scale it",
                         what, index, (of - 1) / (size_t)s->nv, (of - 1) % (size_t)s->nv, RG2_DESIGN_MAX_COORD);
    double big, diag;
    rg2__box_extent(&box, &big, &diag);
    if (!(big <= RG2_DESIGN_MAX_COORD) || !(diag >= RG2_DESIGN_MIN_SIZE))
        return rg2__fail(err, RG2_EDOMAIN,
                         "%s: surface %d has control points up to %g, spanning %g: outside the range its "
                         "normals and curvatures are evaluated in (coordinates up to %g, size at least %g); "
                         "scale it",
                         what, index, big, diag, RG2_DESIGN_MAX_COORD, RG2_DESIGN_MIN_SIZE);
    return RG2_OK;
}
