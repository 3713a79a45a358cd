/* poles.c -- polar configurations (paper section 5, MATH.md section 7): polar knots, the
 * polar control mesh of the sphere, collapsed-row detection and polar point edits. */
#include "internal.h"

#include <stdlib.h>
#include <string.h>

rg2_status rg2_polar_knots(const double *v, int m, double *knots, rg2_error *err)
{
    if (!v)
        return rg2__fail(err, RG2_EINVAL, "polar knots: no interior knots (NULL v)");
    if (!knots)
        return rg2__fail(err, RG2_EINVAL, "polar knots: NULL output knots");
    if (m < 2)
        return rg2__fail(err, RG2_EINVAL,
                         "polar knots: %d interior knots given; a polar configuration needs at least "
                         "2 (v_1 < v_2) for one band ring",
                         m);
    for (int k = 0; k < m; k++) {
        if (!rg2__finite(v[k]))
            return rg2__fail(err, RG2_ENONFINITE, "polar knots: knot %d is not finite", k);
        if (!(v[k] > 0.0 && v[k] < 1.0))
            return rg2__fail(err, RG2_EDOMAIN,
                             "polar knots: knot %d = %s must lie strictly between the poles 0 and 1",
                             k, rg2__num(v[k]).s);
        if (k > 0 && !(v[k] > v[k - 1]))
            return rg2__fail(err, RG2_EDOMAIN, "polar knots: knot %d = %s is not above knot %d = %s",
                             k, rg2__num(v[k]).s, k - 1, rg2__num(v[k - 1]).s);
    }
    knots[0] = v[0] / (v[0] - 1.0);
    knots[1] = 0.0;
    for (int k = 0; k < m; k++)
        knots[k + 2] = v[k];
    knots[m + 2] = 1.0;
    knots[m + 3] = 1.0 / v[m - 1];
    rg2__ok(err);
    return RG2_OK;
}

rg2_status rg2__polar_full_knots(rg2_shape_kind kind, const double *v, int m, double *k, int *north,
                                 rg2_error *err)
{
    *north = 0;
    if (kind == RG2_SHAPE_SPHERE || kind == RG2_SHAPE_ELLIPSOID)
        return rg2_polar_knots(v, m, k, err);
    if (m < 2)
        return rg2__fail(err, RG2_EINVAL,
                         "polar knots: %d interior knots given; a polar configuration needs at least 2", m);
    for (int q = 0; q < m; q++)
        if (!rg2__finite(v[q]))
            return rg2__fail(err, RG2_ENONFINITE, "polar knots: knot %d is not finite", q);
    int nth = v[m - 1] < 0.0; /* knots below 0: the pole v = 0 is at the end */
    for (int q = 0; q < m; q++)
        if (!(nth ? v[q] < 0.0 : v[q] > 0.0) || (q && !(v[q] > v[q - 1])))
            return rg2__fail(err, RG2_EDOMAIN,
                             "polar knots: knot %d = %s: the knots must increase and all lie on one side of the "
                             "pole v = 0",
                             q, rg2__num(v[q]).s);
    if (!nth) {
        double dl = v[m - 1] - v[m - 2];
        k[0] = -v[0];
        k[1] = 0.0;
        memcpy(k + 2, v, (size_t)m * sizeof(double));
        k[m + 2] = v[m - 1] + dl;
        k[m + 3] = v[m - 1] + 2.0 * dl;
    } else {
        double dl = v[1] - v[0];
        k[0] = v[0] - 2.0 * dl;
        k[1] = v[0] - dl;
        memcpy(k + 2, v, (size_t)m * sizeof(double));
        k[m + 2] = 0.0;
        k[m + 3] = -v[m - 1];
    }
    for (int q = 0; q < m + 4; q++) /* (the data-only knots v_m + 2d of knots near 1e308) */
        if (!rg2__finite(k[q]))
            return rg2__fail(err, RG2_EDOMAIN,
                             "polar knots: the data-only end knots %s leave the double range (d = %s)",
                             nth ? "v_1 - 2d, v_1 - d" : "v_m + d, v_m + 2d",
                             rg2__num(nth ? v[1] - v[0] : v[m - 1] - v[m - 2]).s);
    *north = nth;
    return RG2_OK;
}

void rg2__collapse_row(rg2_mesh *m, int j)
{
    for (int i = 1; i < m->nu; i++)
        memcpy(rg2_mesh_at(m, i, j), rg2_mesh_at(m, 0, j), 4 * sizeof(double));
}

/*
 * METHOD: the design file's `polar` (design_poles.c): the shape's own mesh over the full polar
 * knot vector (rg2__polar_full_knots), its polar rows made one point to the last bit.
 */
rg2_status rg2_polar_mesh(const rg2_shape *s, const rg2_partition *pu, const double *v, int m, rg2_mesh *out,
                          rg2_error *err)
{
    if (!out)
        return rg2__fail(err, RG2_EINVAL, "rg2_polar_mesh: out is NULL");
    memset(out, 0, sizeof *out);
    if (!s || !pu || !v)
        return rg2__fail(err, RG2_EINVAL, "rg2_polar_mesh: %s is NULL", !s ? "s" : !pu ? "pu" : "v");
    rg2_shape_kind kind = s->kind;
    int both = kind == RG2_SHAPE_SPHERE || kind == RG2_SHAPE_ELLIPSOID;
    if (!both && kind != RG2_SHAPE_PARABOLOID && kind != RG2_SHAPE_HYPERBOLOID2) {
        const char *name = rg2_shape_name(kind);
        return rg2__fail(err, RG2_EINVAL,
                         "rg2_polar_mesh: a %s has no polar configuration (sphere, ellipsoid: both poles; "
                         "paraboloid, hyperboloid2: the pole at v = 0)",
                         name ? name : "shape of an unknown kind");
    }
    if (m < 2) /* (before the knots' allocation: m + 4 of a negative m) */
        return rg2__fail(err, RG2_EINVAL,
                         "rg2_polar_mesh: %d interior knots given; a polar configuration needs at least 2", m);
    if (m > RG2_MAX_POINTS - 4) /* (the partition's m + 4 knots, at most RG2_MAX_POINTS values) */
        return rg2__fail(err, RG2_ELIMIT, "rg2_polar_mesh: %d interior knots give %lld knots with the 4 data-only "
                         "ones, more than the limit of %d", m, (long long)m + 4, RG2_MAX_POINTS);
    double *k = rg2__calloc((size_t)m + 4, sizeof(double));
    if (!k)
        return rg2__fail(err, RG2_ENOMEM, "rg2_polar_mesh: out of memory for %d knots", m);
    int north = 0;
    rg2_status st = rg2__polar_full_knots(kind, v, m, k, &north, err);
    rg2_partition pv = {RG2_PART_KNOTS_FULL, 0, m + 4, k, 0.0};
    if (!st)
        st = rg2__shape_check_range(s, &pv, err);
    if (!st)
        st = rg2_shape_mesh(s, pu, &pv, out, err);
    free(k);
    if (st)
        return rg2__prefix(err, st, "rg2_polar_mesh");
    for (int e = 0; e < 2; e++)
        if (both || e == north)
            rg2__collapse_row(out, e ? out->nv - 1 : 0);
    return RG2_OK;
}

/*
 * METHOD: family 2 (MATH.md section 5), h = (2v(1-v) cu, 2v(1-v) su, 2v - 1, 2v^2 - 2v + 1).
 * Control 4-tuple (i, j) = products of the circle coefficients (C_i, S_i) and the blossoms
 * B1, B2 of v, v^2 at (v_{j-1}, v_j, v_{j+1}) (Corollary 1). With the polar knots B1 = B2 on
 * rows 0 and m + 1, so x, y vanish there: those rows are written as the exact polar points of
 * eq. (13) so that they are collapsed to the last bit.
 */
rg2_status rg2_polar_sphere_mesh(const double *alpha, int n_alpha, double theta0, const double *v,
                                 int m, const double *M, rg2_mesh *out, rg2_error *err)
{
    memset(out, 0, sizeof *out);
    if (!alpha) /* (it was "0 arcs", whatever n_alpha said) */
        return rg2__fail(err, RG2_EINVAL, "polar sphere: no arcs (NULL alpha)");
    if (n_alpha < 3)
        return rg2__fail(err, RG2_EINVAL, "polar sphere: %d arcs given, a closed circle needs at least 3",
                         n_alpha);
    if (M)
        for (int k = 0; k < 16; k++)
            if (!rg2__finite(M[k]))
                return rg2__fail(err, RG2_ENONFINITE, "polar sphere: placement entry %d is not finite", k);
    /* (m < 2 is rg2_polar_knots' error: (size_t)m + 4 of m <= -5 wrapped to an impossible
     * size, reported as out of memory) */
    if (m > RG2_MAX_POINTS - 2)
        return rg2__fail(err, RG2_ELIMIT, "polar sphere: %d interior knots give %lld control points in v, more "
                         "than the limit of %d", m, (long long)m + 2, RG2_MAX_POINTS);
    double *knots = rg2__calloc((size_t)(m > 0 ? m : 0) + 4, sizeof(double));
    double *cs = rg2__calloc((size_t)n_alpha * 2, sizeof(double));
    rg2_status st = RG2_OK;
    if (!knots || !cs) {
        st = rg2__fail(err, RG2_ENOMEM, "polar sphere: out of memory");
        goto done;
    }
    if ((st = rg2_polar_knots(v, m, knots, err)) ||
        (st = rg2_circle_coeffs(alpha, n_alpha, 1, theta0, cs, err)))
        goto done;
    if ((st = rg2_mesh_init(out, n_alpha, m + 2, 1, 0, err)))
        goto done;
    rg2_scalars_free(&out->su);
    rg2_scalars_free(&out->sv);
    if ((st = rg2_scalars_from_angles(&out->su, alpha, n_alpha, 1, err)) ||
        (st = rg2_scalars_from_knots(&out->sv, knots, m + 4, 0, err))) {
        rg2_mesh_free(out);
        goto done;
    }
    double Zs = (3.0 - 3.0 * v[0] + 2.0 * v[0] * v[0]) / (3.0 * (v[0] - 1.0));
    double Zn = (2.0 - v[m - 1] + 2.0 * v[m - 1] * v[m - 1]) / (3.0 * v[m - 1]);
    for (int j = 0; j < m + 2; j++) {
        double bl[4];
        rg2_blossom_monomials(knots[j], knots[j + 1], knots[j + 2], bl);
        double rad = 2.0 * (bl[1] - bl[2]), z = 2.0 * bl[1] - 1.0, w = 2.0 * bl[2] - 2.0 * bl[1] + 1.0;
        for (int i = 0; i < n_alpha; i++) {
            double *p = rg2_mesh_at(out, i, j);
            if (j == 0 || j == m + 1) {
                p[0] = p[1] = 0.0;
                p[2] = j == 0 ? Zs : Zn;
                p[3] = 1.0;
            } else {
                p[0] = rad * cs[2 * i];
                p[1] = rad * cs[2 * i + 1];
                p[2] = z;
                p[3] = w;
            }
            if (M)
                rg2__xform_apply(M, p);
        }
    }
done:
    free(knots);
    free(cs);
    return st;
}

int rg2__mesh_line_collapsed(const rg2_mesh *m, int dir, int idx)
{
    int n = dir ? m->nu : m->nv, across = dir ? m->nv : m->nu;
    if (!m->p || idx < 0 || idx >= across || n < 1)
        return 0;
    /* mesh size: largest affine coordinate over the mesh */
    double size = 0.0;
    for (int i = 0; i < m->nu; i++)
        for (int j = 0; j < m->nv; j++) {
            const double *p = rg2_mesh_at(m, i, j);
            if (p[3] != 0.0)
                for (int k = 0; k < 3; k++)
                    size = fmax(size, fabs(p[k] / p[3]));
        }
    if (size == 0.0)
        size = 1.0;
    const double *p0 = dir ? rg2_mesh_at(m, 0, idx) : rg2_mesh_at(m, idx, 0);
    if (!(p0[3] != 0.0))
        return 0;
    for (int k = 1; k < n; k++) {
        const double *p = dir ? rg2_mesh_at(m, k, idx) : rg2_mesh_at(m, idx, k);
        if (!(p[3] != 0.0))
            return 0;
        for (int d = 0; d < 3; d++)
            if (!(fabs(p[d] / p[3] - p0[d] / p0[3]) <= 1e-12 * size))
                return 0;
    }
    return 1;
}

int rg2_mesh_row_collapsed(const rg2_mesh *m, int j)
{
    return m && rg2__mesh_line_collapsed(m, 1, j);
}

rg2_status rg2_polar_set_point(rg2_mesh *m, int end, const double p[4], rg2_error *err)
{
    if (!m || !m->p)
        return rg2__fail(err, RG2_EINVAL, "polar point: empty mesh");
    if (end != 0 && end != 1)
        return rg2__fail(err, RG2_EINVAL, "polar point: end %d, must be 0 (south) or 1 (north)", end);
    if (m->sv.closed)
        return rg2__fail(err, RG2_EINVAL, "polar point: the mesh's v-direction is closed; it has no poles");
    for (int k = 0; k < 4; k++)
        if (!rg2__finite(p[k]))
            return rg2__fail(err, RG2_ENONFINITE, "polar point: component %d is not finite", k);
    if (!(p[3] > 0.0))
        return rg2__fail(err, RG2_EWEIGHT, "polar point: weight %g, must be > 0", p[3]);
    int j = end == 0 ? 0 : m->nv - 1;
    for (int i = 0; i < m->nu; i++)
        memcpy(rg2_mesh_at(m, i, j), p, 4 * sizeof(double));
    rg2__ok(err);
    return RG2_OK;
}
