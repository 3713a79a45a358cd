/* shapes.c -- exact basic shapes (paper section 3.1, MATH.md sections 3 and 5): partitions of
 * the circle and polynomial directions, the generic product (family) constructors, the named
 * shapes with their implicit equations and own parameterizations, and placement matrices. */
#include "internal.h"

#include <stdlib.h>
#include <string.h>

/* ------------------------------------------------------------------------------------- */
/* Shape descriptions                                                                     */
/* ------------------------------------------------------------------------------------- */

#define A_ RG2_PART_ANGLES
#define K_ RG2_PART_KNOTS
#define TWO_PI (2.0 * M_PI)

static const rg2_shape_desc shape_table[RG2_SHAPE_COUNT] = {
    [RG2_SHAPE_TORUS] = {"torus", 2, {"R", "r"}, {3.0, 1.0}, {A_, A_}, {{0, TWO_PI}, {0, TWO_PI}},
                         {1, 1}, {8, 6},
                         "((R + r cos v) cos u, (R + r cos v) sin u, r sin v, 1)",
                         "(x^2 + y^2 + z^2 + R^2 - r^2)^2 = 4 R^2 (x^2 + y^2)"},
    [RG2_SHAPE_CYCLIDE] = {"cyclide", 3, {"a", "c", "mu"}, {2.0, 1.0, 1.5}, {A_, A_},
                           {{0, TWO_PI}, {0, TWO_PI}}, {1, 1}, {8, 6},
                           "(mu (c - a cu cv) + b^2 cu, b su (a - mu cv), b sv (c cu - mu), "
                           "a - c cu cv), b^2 = a^2 - c^2",
                           "(x^2 + y^2 + z^2 + b^2 - mu^2)^2 = 4 (a x - c mu)^2 + 4 b^2 y^2"},
    [RG2_SHAPE_SPHERE] = {"sphere", 1, {"radius"}, {1.0}, {A_, K_}, {{0, TWO_PI}, {0.2, 0.8}},
                          {1, 0}, {6, 4},
                          "(2 rho v(1-v) cu, 2 rho v(1-v) su, rho (2v - 1), 2v^2 - 2v + 1); "
                          "rho = radius; v = 0 south pole, v = 1 north pole",
                          "x^2 + y^2 + z^2 = rho^2"},
    [RG2_SHAPE_CYLINDER] = {"cylinder", 1, {"radius"}, {1.0}, {A_, K_}, {{0, TWO_PI}, {0, 1}},
                            {1, 0}, {6, 3}, "(R cu, R su, v, 1), R = radius; v = height",
                            "x^2 + y^2 = R^2"},
    [RG2_SHAPE_CONE] = {"cone", 1, {"k"}, {1.0}, {A_, K_}, {{0, TWO_PI}, {0.5, 1.5}}, {1, 0},
                        {6, 3}, "(v cu, v su, k v, 1); v = radius", "k^2 (x^2 + y^2) = z^2"},
    [RG2_SHAPE_HYPERBOLOID1_RULED] = {"hyperboloid1_ruled", 2, {"a", "c"}, {1.0, 1.0}, {A_, K_},
                                      {{0, TWO_PI}, {-1, 1}}, {1, 0}, {6, 4},
                                      "(a (cu - v su), a (su + v cu), c v, 1)",
                                      "(x^2 + y^2) / a^2 - z^2 / c^2 = 1"},
    [RG2_SHAPE_HYPERBOLOID1] = {"hyperboloid1", 2, {"a", "c"}, {1.0, 1.0}, {A_, K_},
                                {{0, TWO_PI}, {0.5, 2.0}}, {1, 0}, {6, 4},
                                "(a (1 + v^2) cu, a (1 + v^2) su, c (1 - v^2), 2v), v > 0",
                                "(x^2 + y^2) / a^2 - z^2 / c^2 = 1"},
    [RG2_SHAPE_HYPERBOLOID2] = {"hyperboloid2", 2, {"a", "c"}, {1.0, 1.0}, {A_, K_},
                                {{0, TWO_PI}, {0.2, 0.6}}, {1, 0}, {6, 4},
                                "(2 a v cu, 2 a v su, c (1 + v^2), 1 - v^2), |v| < 1",
                                "z^2 / c^2 - (x^2 + y^2) / a^2 = 1"},
    [RG2_SHAPE_PARABOLOID] = {"paraboloid", 2, {"A", "B"}, {1.0, 1.0}, {A_, K_},
                              {{0, TWO_PI}, {0.2, 1.0}}, {1, 0}, {6, 4},
                              "(A v cu, B v su, v^2, 1)", "z = x^2 / A^2 + y^2 / B^2"},
    [RG2_SHAPE_HYPAR] = {"hypar", 2, {"A", "B"}, {1.0, 1.0}, {K_, K_}, {{-1, 1}, {-1, 1}}, {0, 0},
                         {4, 4}, "(A u, B v, u^2 - v^2, 1)", "z = x^2 / A^2 - y^2 / B^2"},
    [RG2_SHAPE_ELLIPSOID] = {"ellipsoid", 3, {"a", "b", "c"}, {2.0, 1.5, 1.0}, {A_, K_},
                             {{0, TWO_PI}, {0.2, 0.8}}, {1, 0}, {6, 4},
                             "(2 a v(1-v) cu, 2 b v(1-v) su, c (2v - 1), 2v^2 - 2v + 1)",
                             "x^2 / a^2 + y^2 / b^2 + z^2 / c^2 = 1"},
};

const rg2_shape_desc *rg2_shape_describe(rg2_shape_kind kind)
{
    if ((int)kind < 0 || kind >= RG2_SHAPE_COUNT)
        return NULL;
    return &shape_table[kind];
}

const char *rg2_shape_name(rg2_shape_kind kind)
{
    const rg2_shape_desc *d = rg2_shape_describe(kind);
    return d ? d->name : NULL;
}

rg2_status rg2_shape_from_name(const char *name, rg2_shape_kind *kind, rg2_error *err)
{
    if (!kind)
        return rg2__fail(err, RG2_EINVAL, "shape: NULL output kind");
    if (!name)
        return rg2__fail(err, RG2_EINVAL, "shape: no name (NULL name)");
    for (int k = 0; k < RG2_SHAPE_COUNT; k++)
        if (!strcmp(name, shape_table[k].name)) {
            *kind = (rg2_shape_kind)k;
            rg2__ok(err);
            return RG2_OK;
        }
    char list[400] = "";
    for (int k = 0; k < RG2_SHAPE_COUNT; k++) {
        strncat(list, shape_table[k].name, sizeof list - strlen(list) - 1);
        if (k + 1 < RG2_SHAPE_COUNT)
            strncat(list, ", ", sizeof list - strlen(list) - 1);
    }
    return rg2__fail(err, RG2_EINVAL, "unknown shape '%s' (known: %s)", name, list);
}

void rg2_shape_init(rg2_shape *s, rg2_shape_kind kind)
{
    memset(s, 0, sizeof *s);
    s->kind = kind;
    const rg2_shape_desc *d = rg2_shape_describe(kind);
    if (d)
        for (int k = 0; k < d->n_params; k++)
            s->param[k] = d->param_defaults[k];
    rg2_xform_identity(s->xform);
}

/* ------------------------------------------------------------------------------------- */
/* Partitions                                                                             */
/* ------------------------------------------------------------------------------------- */

static int is_angles(rg2_partition_kind k) { return k == RG2_PART_ANGLES || k == RG2_PART_ANGLES_FULL; }

/* The start angle of an angle partition, within one turn: with a start of many turns ("from":
 * 1e20 degrees) the junction angles round to the start itself (1e9 degrees already rounds them by
 * 3e-8 rad), and the control polygon's corners left the arcs (residual 1e-10 at 1e9 degrees, 0.11
 * at 1e20: every corner on one point). */
static double start_angle(const rg2_partition *p) { return rg2__within_turn(p->start); }

int rg2_partition_num_segments(const rg2_partition *p)
{
    if (!p || !p->values || p->n <= 0) /* (p->n - 5 of a count near INT_MIN would overflow) */
        return 0;
    int n;
    switch (p->kind) {
    case RG2_PART_ANGLES: n = p->n; break;
    case RG2_PART_KNOTS: n = p->n - 1; break;
    case RG2_PART_ANGLES_FULL: n = p->n - 4; break;
    case RG2_PART_KNOTS_FULL: n = p->n - 5; break;
    default: return 0;
    }
    return n > 0 ? n : 0;
}

/* Index range [lo, hi) of the values that are produced segments (angles) or the bounding
 * knots of produced segments (knots). */
static void visible_range(const rg2_partition *p, int *lo, int *hi)
{
    switch (p->kind) {
    case RG2_PART_ANGLES: *lo = 0, *hi = p->n; break;
    case RG2_PART_KNOTS: *lo = 0, *hi = p->n; break;
    case RG2_PART_ANGLES_FULL: *lo = 2, *hi = p->n - 2; break;
    default: *lo = 2, *hi = p->n - 2; break; /* v_1 .. v_{n-2}: values[2 .. n_values - 3] */
    }
}

rg2_status rg2_partition_check(const rg2_partition *p, const char *what, rg2_error *err)
{
    if (!what)
        what = "the";
    if (!p)
        return rg2__fail(err, RG2_EINVAL, "%s partition is NULL", what);
    const char *unit = !is_angles(p->kind) ? "knots" : "arcs";
    if (p->n <= 0)
        return rg2__fail(err, RG2_EINVAL, "%s partition is empty (n = %d: no %s given)", what, p->n, unit);
    if (!p->values)
        return rg2__fail(err, RG2_EINVAL, "%s partition: values is NULL (n = %d %s)", what, p->n, unit);
    if ((int)p->kind < 0 || p->kind > RG2_PART_KNOTS_FULL)
        return rg2__fail(err, RG2_EINVAL, "%s partition has unknown kind %d", what, (int)p->kind);
    if (p->n > RG2_MAX_POINTS)
        return rg2__fail(err, RG2_ELIMIT, "%s partition: %d values exceeds the limit %d", what, p->n,
                         RG2_MAX_POINTS);
    for (int k = 0; k < p->n; k++)
        if (!rg2__finite(p->values[k]))
            return rg2__fail(err, RG2_ENONFINITE, "%s partition: value %d is not finite", what, k);
    if (is_angles(p->kind)) {
        if (!rg2__finite(p->start))
            return rg2__fail(err, RG2_ENONFINITE, "%s partition: start angle is not finite", what);
        if (p->kind == RG2_PART_ANGLES_FULL && p->closed)
            return rg2__fail(err, RG2_EINVAL,
                             "%s partition: a full (data-arc) angle list is open only", what);
        if (p->kind == RG2_PART_ANGLES_FULL && p->n < 5)
            return rg2__fail(err, RG2_EINVAL,
                             "%s partition: %d arcs given with data arcs; need at least 5 "
                             "(2 data arcs at each end and one produced arc)",
                             what, p->n);
        int off = p->kind == RG2_PART_ANGLES_FULL ? 1 : 0;
        for (int k = 0; k < p->n; k++) {
            double a = p->values[k];
            if (!(a > 0.0 && a < M_PI))
                return rg2__fail(err, RG2_EDOMAIN,
                                 "%s partition: arc %d has opening angle %s rad (%.10g deg); it "
                                 "must lie in (0, pi)",
                                 what, k - off, rg2__num(a).s, a * 180.0 / M_PI);
            if (a < RG2_MIN_ARC) {
                /* (an arc just below the limit read "0.005 rad (0.286479 deg), below ... 0.005 rad
                 * (0.286479 deg)": then its own digits) */
                int p6 = fabs(a - RG2_MIN_ARC) >= 5e-6 * RG2_MIN_ARC;
                return rg2__fail(err, RG2_EDOMAIN,
                                 "%s partition: arc %d has opening angle %.*g rad (%.*g deg), below the "
                                 "smallest supported arc of %g rad (%g deg): the seams of smaller "
                                 "patches lose G2 accuracy in double precision",
                                 what, k - off, p6 ? 6 : 17, a, p6 ? 6 : 17, a * 180.0 / M_PI, RG2_MIN_ARC,
                                 RG2_MIN_ARC * 180.0 / M_PI);
            }
        }
        int lo, hi;
        visible_range(p, &lo, &hi);
        double sum = 0.0;
        for (int k = lo; k < hi; k++)
            sum += p->values[k];
        if (p->closed && fabs(sum - TWO_PI) > RG2_CLOSED_SUM_TOL * TWO_PI)
            return rg2__fail(err, RG2_EDOMAIN,
                             "%s partition: the %d arcs of a closed circle sum to %s rad (%.10g "
                             "deg); they must sum to 2 pi",
                             what, p->n, rg2__num(sum).s, sum * 180.0 / M_PI);
        if (!p->closed && sum > TWO_PI * (1.0 + RG2_CLOSED_SUM_TOL))
            return rg2__fail(err, RG2_EDOMAIN,
                             "%s partition: the open arcs sum to %s rad (%.*g deg), past 2 pi "
                             "(the surface would overlap itself)",
                             what, rg2__num(sum).s, sum < TWO_PI * (1.0 + 1e-9) ? 15 : 10, sum * 180.0 / M_PI);
        if (p->closed && p->n < 3)
            return rg2__fail(err, RG2_EINVAL, "%s partition: a closed circle needs at least 3 arcs",
                             what);
        /* Two neighbouring arcs (the data-only copies of an open partition's end arcs counted:
         * an open end arc alpha meets its copy, 2 alpha) that sum to nearly 2 pi: their common
         * control point is the meeting point of two nearly parallel tangent lines, about
         * 4 / (2 pi - sum) away, and the patches carry its rounding (residual about
         * 3e-16 / (2 pi - sum): 7e-5 for two open arcs of 179.9999999999 degrees, 0.08 for one
         * open arc of 180 - 3e-14 degrees, the surface off the shape). The complement must be at
         * least the smallest arc, as it is in a closed circle. */
        for (int k = 0; k <= p->n && !p->closed; k++) { /* (closed: the other arcs are the complement) */
            int a0 = k - 1, a1 = k; /* values[a0] + values[a1]; an open end meets its copy */
            if (p->kind == RG2_PART_ANGLES_FULL && (k == 0 || k == p->n))
                continue; /* (the data arcs are given) */
            if (k == 0)
                a0 = 0;
            if (k == p->n)
                a1 = p->n - 1;
            double s2 = p->values[a0] + p->values[a1];
            if (TWO_PI - s2 < RG2_MIN_ARC * (1.0 - 1e-9)) {
                char pair[96];
                if (a0 == a1)
                    snprintf(pair, sizeof pair, "arc %d at the open %s and its data-only copy beyond it", a0 - off,
                             k == 0 ? "start" : "end");
                else
                    snprintf(pair, sizeof pair, "arcs %d and %d", a0 - off, a1 - off);
                return rg2__fail(err, RG2_EDOMAIN,
                                 "%s partition: %s leave only %.3g deg of the circle: their common control "
                                 "point lies about %.3g times the radius away and the patches lose their accuracy; "
                                 "two neighbouring arcs must leave at least the smallest arc, %g deg, of the "
                                 "circle (an arc at an open end at most %.4f deg: split it)",
                                 what, pair, (TWO_PI - s2) * 180.0 / M_PI, 4.0 / (TWO_PI - s2),
                                 RG2_MIN_ARC * 180.0 / M_PI, floor((M_PI - 0.5 * RG2_MIN_ARC) * 180.0 / M_PI * 1e4) / 1e4);
            }
        }
    } else {
        if (p->closed)
            return rg2__fail(err, RG2_EINVAL,
                             "%s partition: knot partitions are open (closed is set)", what);
        int min = p->kind == RG2_PART_KNOTS ? 2 : 6;
        if (p->n < min)
            return rg2__fail(err, RG2_EINVAL, "%s partition: %d knots given, need at least %d%s",
                             what, p->n, min,
                             p->kind == RG2_PART_KNOTS ? "" : " (data knots v_-1, v_0 and v_n-1, v_n)");
        int off = p->kind == RG2_PART_KNOTS_FULL ? 1 : 0;
        for (int k = 1; k < p->n; k++)
            if (!(p->values[k] > p->values[k - 1]))
                return rg2__fail(err, RG2_EDOMAIN,
                                 "%s partition: knot %d (= %s) is not greater than knot %d (= "
                                 "%s); knots must increase strictly",
                                 what, k - off, rg2__num(p->values[k]).s, k - 1 - off, rg2__num(p->values[k - 1]).s);
    }
    rg2__ok(err);
    return RG2_OK;
}

double rg2_partition_map(const rg2_partition *p, int seg, double t)
{
    int ns = rg2_partition_num_segments(p);
    if (seg < 0 || seg >= ns)
        return NAN;
    int lo, hi;
    visible_range(p, &lo, &hi);
    if (is_angles(p->kind)) {
        double th = start_angle(p);
        for (int k = 0; k < seg; k++)
            th += p->values[lo + k];
        double beta = 0.5 * p->values[lo + seg];
        return th + beta + 2.0 * atan(tan(0.5 * beta) * (2.0 * t - 1.0));
    }
    double a = p->values[lo + seg], b = p->values[lo + seg + 1];
    return a + t * (b - a);
}

/* ("arcs": [1.5708, 1.5708, 1.5708, 1.5708] gave an open sliver of 6.28 degrees, refused only
 * later by a merge, as "8 vs 11 control points") */
const char *rg2_angle_total_in_radians(double deg)
{
    static const struct { double v; const char *name; } turns[] = {
        {TWO_PI, "2 pi (a full circle in radians)"},
        {0.5 * TWO_PI, "pi (a half circle in radians)"},
        {0.25 * TWO_PI, "pi / 2 (a quarter circle in radians)"},
        /* the other common turns, 45, 60, 30, 270 and 120 degrees: one open arc of 0.7854 "degrees"
         * built a sliver of the ring */
        {0.125 * TWO_PI, "pi / 4 (45 degrees in radians)"}, {TWO_PI / 6, "pi / 3 (60 degrees in radians)"},
        {TWO_PI / 12, "pi / 6 (30 degrees in radians)"}, {0.75 * TWO_PI, "3 pi / 2 (270 degrees in radians)"},
        {TWO_PI / 3, "2 pi / 3 (120 degrees in radians)"}};
    for (size_t k = 0; k < sizeof turns / sizeof turns[0]; k++)
        if (fabs(deg - turns[k].v) <= 1e-3 * turns[k].v)
            return turns[k].name;
    return NULL;
}

rg2_status rg2_partition_equal(rg2_partition *p, rg2_partition_kind kind, int closed, double lo,
                               double hi, int n, double *values, int cap, rg2_error *err)
{
    memset(p, 0, sizeof *p);
    if (kind != RG2_PART_ANGLES && kind != RG2_PART_KNOTS)
        return rg2__fail(err, RG2_EINVAL, "equal partition: kind must be angles or knots");
    if (n < 1)
        return rg2__fail(err, RG2_EINVAL, "equal partition: %d segments, need at least 1", n);
    if (cap <= n) /* (not cap < n + 1: n may be INT_MAX) */
        return rg2__fail(err, RG2_EINVAL, "equal partition: %d segments need %lld values, room for %d (cap)",
                         n, (long long)n + 1, cap);
    if (!rg2__finite(lo) || !rg2__finite(hi))
        return rg2__fail(err, RG2_ENONFINITE, "equal partition: range is not finite");
    p->kind = kind;
    p->values = values;
    if (kind == RG2_PART_ANGLES) {
        double sweep = closed ? TWO_PI : hi - lo;
        for (int k = 0; k < n; k++)
            values[k] = sweep / n;
        p->n = n;
        p->closed = closed ? 1 : 0;
        p->start = lo;
    } else {
        for (int k = 0; k <= n; k++)
            values[k] = k == n ? hi : lo + (hi - lo) * k / n;
        p->n = n + 1;
    }
    return rg2_partition_check(p, "equal", err);
}

/* One direction of a product mesh: scalars and the control coefficients of its basis
 * functions (1, cos, sin: nb = 3; or 1, t, t^2, t^3: nb = 4) at each control point. */
typedef struct {
    rg2_scalars sc;
    int n, nb;
    double *coef; /* n * nb */
} dir_data;

static void dir_free(dir_data *d)
{
    rg2_scalars_free(&d->sc);
    free(d->coef);
    memset(d, 0, sizeof *d);
}

/*
 * METHOD: expand the partition to the full layout of rg2_scalars_from_angles / _from_knots
 * (open angles: copies of the end arcs as the two data arcs at each end; open knots: end
 * intervals mirrored about the end knots, or copied when there is one interval), then the
 * control coefficients: (1, C_i, S_i) from rg2_circle_coeffs, or the blossoms of the
 * monomials at (v_{i-1}, v_i, v_{i+1}) (MATH.md sections 1-3).
 */
static rg2_status dir_make(const rg2_partition *p, const char *what, dir_data *d, rg2_error *err)
{
    memset(d, 0, sizeof *d);
    rg2_status st = rg2_partition_check(p, what, err);
    if (st)
        return st;
    int m = p->n;
    double *full = rg2__calloc((size_t)m + 5, sizeof(double));
    if (!full)
        return rg2__fail(err, RG2_ENOMEM, "%s partition: out of memory", what);
    int nf = 0, closed = 0;
    double theta0 = 0.0;
    switch (p->kind) {
    case RG2_PART_ANGLES:
        closed = p->closed;
        if (closed) {
            memcpy(full, p->values, sizeof(double) * (size_t)m);
            nf = m;
            theta0 = start_angle(p);
        } else {
            full[0] = full[1] = p->values[0];
            memcpy(full + 2, p->values, sizeof(double) * (size_t)m);
            full[m + 2] = full[m + 3] = p->values[m - 1];
            nf = m + 4;
            theta0 = start_angle(p) - p->values[0];
        }
        break;
    case RG2_PART_ANGLES_FULL:
        memcpy(full, p->values, sizeof(double) * (size_t)m);
        nf = m;
        theta0 = start_angle(p) - p->values[1];
        break;
    case RG2_PART_KNOTS: {
        const double *v = p->values;
        double d0 = v[1] - v[0], d1 = m > 2 ? v[2] - v[0] : 2.0 * d0;
        double e0 = v[m - 1] - v[m - 2], e1 = m > 2 ? v[m - 1] - v[m - 3] : 2.0 * e0;
        full[0] = v[0] - d1;
        full[1] = v[0] - d0;
        memcpy(full + 2, v, sizeof(double) * (size_t)m);
        full[m + 2] = v[m - 1] + e0;
        full[m + 3] = v[m - 1] + e1;
        nf = m + 4;
        break;
    }
    case RG2_PART_KNOTS_FULL:
        memcpy(full, p->values, sizeof(double) * (size_t)m);
        nf = m;
        break;
    }
    if (is_angles(p->kind)) {
        st = rg2_scalars_from_angles(&d->sc, full, nf, closed, err);
        d->nb = 3;
    } else {
        /* (open knots: full[k] = values[k - 2], and values[-2], values[-1] the mirrored ones) */
        st = rg2__scalars_from_knots_named(&d->sc, full, nf, 0, "knots", "values",
                                           p->kind == RG2_PART_KNOTS ? -2 : 0, err);
        d->nb = 4;
    }
    if (st) {
        free(full);
        return rg2__prefix(err, st, what);
    }
    d->n = d->sc.n;
    d->coef = rg2__calloc((size_t)d->n * (size_t)d->nb, sizeof(double));
    double *cs = is_angles(p->kind) ? rg2__calloc((size_t)d->n * 2, sizeof(double)) : NULL;
    if (!d->coef || (is_angles(p->kind) && !cs)) {
        free(full);
        free(cs);
        dir_free(d);
        return rg2__fail(err, RG2_ENOMEM, "%s partition: out of memory", what);
    }
    if (is_angles(p->kind)) {
        st = rg2_circle_coeffs(full, nf, closed, theta0, cs, err);
        for (int i = 0; i < d->n && !st; i++) {
            d->coef[i * 3 + 0] = 1.0;
            d->coef[i * 3 + 1] = cs[2 * i];
            d->coef[i * 3 + 2] = cs[2 * i + 1];
        }
    } else {
        for (int i = 0; i < d->n; i++)
            rg2_blossom_monomials(full[i], full[i + 1], full[i + 2], d->coef + i * 4);
    }
    free(full);
    free(cs);
    if (st) {
        dir_free(d);
        return rg2__prefix(err, st, what);
    }
    return RG2_OK;
}

/* ------------------------------------------------------------------------------------- */
/* Generic family constructors                                                            */
/* ------------------------------------------------------------------------------------- */

rg2_status rg2_product_mesh(const double coef[4][4][4], const rg2_partition *pu,
                            const rg2_partition *pv, rg2_mesh *out, rg2_error *err)
{
    memset(out, 0, sizeof *out);
    for (int k = 0; k < 4; k++)
        for (int a = 0; a < 4; a++)
            for (int b = 0; b < 4; b++)
                if (!rg2__finite(coef[k][a][b]))
                    return rg2__fail(err, RG2_ENONFINITE, "coefficient [%d][%d][%d] is not finite",
                                     k, a, b);
    dir_data du, dv;
    rg2_status st = dir_make(pu, "u", &du, err);
    if (st)
        return st;
    st = dir_make(pv, "v", &dv, err);
    if (st) {
        dir_free(&du);
        return st;
    }
    for (int k = 0; k < 4; k++)
        for (int a = 0; a < 4; a++)
            for (int b = 0; b < 4; b++)
                if (coef[k][a][b] != 0.0 && (a >= du.nb || b >= dv.nb)) {
                    st = rg2__fail(err, RG2_EINVAL,
                                   "coefficient [%d][%d][%d] = %g must be 0: the %s direction is a "
                                   "circle with basis (1, cos, sin)",
                                   k, a, b, coef[k][a][b], a >= du.nb ? "u" : "v");
                    goto done;
                }
    st = rg2_mesh_init(out, du.n, dv.n, du.sc.closed, dv.sc.closed, err);
    if (st)
        goto done;
    rg2_scalars_free(&out->su);
    rg2_scalars_free(&out->sv);
    out->su = du.sc;
    out->sv = dv.sc;
    memset(&du.sc, 0, sizeof du.sc);
    memset(&dv.sc, 0, sizeof dv.sc);
    for (int i = 0; i < out->nu; i++) {
        const double *fu = du.coef + (size_t)i * (size_t)du.nb;
        /* contract u first: cu[k][b] = sum_a coef[k][a][b] fu[a] */
        double cu[4][4] = {{0}};
        for (int k = 0; k < 4; k++)
            for (int b = 0; b < dv.nb; b++)
                for (int a = 0; a < du.nb; a++)
                    cu[k][b] += coef[k][a][b] * fu[a];
        for (int j = 0; j < out->nv; j++) {
            const double *gv = dv.coef + (size_t)j * (size_t)dv.nb;
            double *p = rg2_mesh_at(out, i, j);
            for (int k = 0; k < 4; k++) {
                double acc = 0.0;
                for (int b = 0; b < dv.nb; b++)
                    acc += cu[k][b] * gv[b];
                p[k] = acc;
            }
        }
    }
    rg2__ok(err);
done:
    dir_free(&du);
    dir_free(&dv);
    return st;
}

static rg2_status need_kinds(const rg2_partition *pu, const rg2_partition *pv, int u_angles,
                             int v_angles, const char *who, rg2_error *err)
{
    const rg2_partition *p[2] = {pu, pv};
    int want[2] = {u_angles, v_angles};
    for (int d = 0; d < 2; d++) {
        if (!p[d])
            return rg2__fail(err, RG2_EINVAL, "%s: %s partition is empty (NULL)", who, d ? "v" : "u");
        if (is_angles(p[d]->kind) != want[d])
            return rg2__fail(err, RG2_EINVAL,
                             "%s: %s is a %s direction and needs %s partition, not %s", who,
                             d ? "v" : "u", want[d] ? "circle" : "polynomial",
                             want[d] ? "an angle" : "a knot", want[d] ? "knots" : "angles");
    }
    return RG2_OK;
}

rg2_status rg2_family1_mesh(const double a[4][9], const rg2_partition *pu, const rg2_partition *pv,
                            rg2_mesh *out, rg2_error *err)
{
    memset(out, 0, sizeof *out);
    rg2_status st = need_kinds(pu, pv, 1, 1, "family 1", err);
    if (st)
        return st;
    /* [1, cu, su, cv, sv, cu cv, su cv, cu sv, su sv] -> [k][u basis][v basis] */
    static const int ua[9] = {0, 1, 2, 0, 0, 1, 2, 1, 2}, vb[9] = {0, 0, 0, 1, 2, 1, 1, 2, 2};
    double c[4][4][4] = {{{0}}};
    for (int k = 0; k < 4; k++)
        for (int q = 0; q < 9; q++)
            c[k][ua[q]][vb[q]] = a[k][q];
    return rg2_product_mesh((const double(*)[4][4])c, pu, pv, out, err);
}

rg2_status rg2_family2_mesh(const double cf[4][3][4], const rg2_partition *pu,
                            const rg2_partition *pv, rg2_mesh *out, rg2_error *err)
{
    memset(out, 0, sizeof *out);
    rg2_status st = need_kinds(pu, pv, 1, 0, "family 2", err);
    if (st)
        return st;
    double c[4][4][4] = {{{0}}};
    for (int k = 0; k < 4; k++)
        for (int a = 0; a < 3; a++)
            for (int s = 0; s < 4; s++)
                c[k][a][s] = cf[k][a][s];
    return rg2_product_mesh((const double(*)[4][4])c, pu, pv, out, err);
}

rg2_status rg2_family3_mesh(const double A[4][4][4], const rg2_partition *pu,
                            const rg2_partition *pv, rg2_mesh *out, rg2_error *err)
{
    memset(out, 0, sizeof *out);
    rg2_status st = need_kinds(pu, pv, 0, 0, "family 3", err);
    if (st)
        return st;
    return rg2_product_mesh(A, pu, pv, out, err);
}

/* ------------------------------------------------------------------------------------- */
/* Named shapes                                                                           */
/* ------------------------------------------------------------------------------------- */

static rg2_status need_positive(const char *shape, const char *name, double x, rg2_error *err)
{
    if (!(x > 0.0))
        return rg2__fail(err, RG2_EDOMAIN, "%s: parameter %s = %s must be > 0", shape, name, rg2__num(x).s);
    return RG2_OK;
}

rg2_status rg2_shape_coeffs(const rg2_shape *s, double C[4][4][4], rg2_error *err)
{
    memset(C, 0, sizeof(double[4][4][4]));
    const rg2_shape_desc *d = rg2_shape_describe(s->kind);
    if (!d)
        return rg2__fail(err, RG2_EINVAL, "unknown shape kind %d", (int)s->kind);
    const double *q = s->param;
    for (int k = 0; k < d->n_params; k++)
        if (!rg2__finite(q[k]))
            return rg2__fail(err, RG2_ENONFINITE, "%s: parameter %s is not finite", d->name,
                             d->param_names[k]);
    rg2_status st = RG2_OK;
    switch (s->kind) {
    case RG2_SHAPE_TORUS: {
        double R = q[0], r = q[1];
        if ((st = need_positive(d->name, "R", R, err)) || (st = need_positive(d->name, "r", r, err)))
            return st;
        if (!(r < R))
            return rg2__fail(err, RG2_EDOMAIN,
                             "torus: r = %s must be < R = %s (horn and spindle tori are "
                             "singular; build them with rg2_family1_mesh)",
                             rg2__num(r).s, rg2__num(R).s);
        C[0][1][0] = R, C[0][1][1] = r;
        C[1][2][0] = R, C[1][2][1] = r;
        C[2][0][2] = r;
        C[3][0][0] = 1.0;
        break;
    }
    case RG2_SHAPE_CYCLIDE: {
        double a = q[0], c = q[1], mu = q[2];
        if ((st = need_positive(d->name, "a", a, err)))
            return st;
        if (!(c >= 0.0))
            return rg2__fail(err, RG2_EDOMAIN, "cyclide: parameter c = %s must be >= 0", rg2__num(c).s);
        double b2 = a * a - c * c;
        if (!(b2 > 0.0))
            return rg2__fail(err, RG2_EDOMAIN,
                             "cyclide: b^2 = a^2 - c^2 = %s <= 0 (a = %s, c = %s); need c < a",
                             rg2__num(b2).s, rg2__num(a).s, rg2__num(c).s);
        if ((st = need_positive(d->name, "mu", mu, err)))
            return st;
        double b = sqrt(b2);
        C[0][0][0] = mu * c, C[0][1][1] = -mu * a, C[0][1][0] = b2;
        C[1][2][0] = a * b, C[1][2][1] = -b * mu;
        C[2][1][2] = b * c, C[2][0][2] = -b * mu;
        C[3][0][0] = a, C[3][1][1] = -c;
        break;
    }
    case RG2_SHAPE_SPHERE:
    case RG2_SHAPE_ELLIPSOID: {
        double ax[3];
        for (int k = 0; k < 3; k++) {
            ax[k] = s->kind == RG2_SHAPE_SPHERE ? q[0] : q[k];
            if ((st = need_positive(d->name, d->param_names[s->kind == RG2_SHAPE_SPHERE ? 0 : k],
                                    ax[k], err)))
                return st;
        }
        C[0][1][1] = 2.0 * ax[0], C[0][1][2] = -2.0 * ax[0];
        C[1][2][1] = 2.0 * ax[1], C[1][2][2] = -2.0 * ax[1];
        C[2][0][0] = -ax[2], C[2][0][1] = 2.0 * ax[2];
        C[3][0][0] = 1.0, C[3][0][1] = -2.0, C[3][0][2] = 2.0;
        break;
    }
    case RG2_SHAPE_CYLINDER:
        if ((st = need_positive(d->name, "radius", q[0], err)))
            return st;
        C[0][1][0] = q[0];
        C[1][2][0] = q[0];
        C[2][0][1] = 1.0;
        C[3][0][0] = 1.0;
        break;
    case RG2_SHAPE_CONE:
        if (!(q[0] != 0.0))
            return rg2__fail(err, RG2_EDOMAIN, "cone: slope k = 0 gives a plane, not a cone");
        C[0][1][1] = 1.0;
        C[1][2][1] = 1.0;
        C[2][0][1] = q[0];
        C[3][0][0] = 1.0;
        break;
    case RG2_SHAPE_HYPERBOLOID1_RULED:
    case RG2_SHAPE_HYPERBOLOID1:
    case RG2_SHAPE_HYPERBOLOID2: {
        double a = q[0], c = q[1];
        if ((st = need_positive(d->name, "a", a, err)) || (st = need_positive(d->name, "c", c, err)))
            return st;
        if (s->kind == RG2_SHAPE_HYPERBOLOID1_RULED) {
            C[0][1][0] = a, C[0][2][1] = -a;
            C[1][2][0] = a, C[1][1][1] = a;
            C[2][0][1] = c;
            C[3][0][0] = 1.0;
        } else if (s->kind == RG2_SHAPE_HYPERBOLOID1) {
            C[0][1][0] = a, C[0][1][2] = a;
            C[1][2][0] = a, C[1][2][2] = a;
            C[2][0][0] = c, C[2][0][2] = -c;
            C[3][0][1] = 2.0;
        } else {
            C[0][1][1] = 2.0 * a;
            C[1][2][1] = 2.0 * a;
            C[2][0][0] = c, C[2][0][2] = c;
            C[3][0][0] = 1.0, C[3][0][2] = -1.0;
        }
        break;
    }
    case RG2_SHAPE_PARABOLOID:
        if ((st = need_positive(d->name, "A", q[0], err)) || (st = need_positive(d->name, "B", q[1], err)))
            return st;
        C[0][1][1] = q[0];
        C[1][2][1] = q[1];
        C[2][0][2] = 1.0;
        C[3][0][0] = 1.0;
        break;
    case RG2_SHAPE_HYPAR:
        if ((st = need_positive(d->name, "A", q[0], err)) || (st = need_positive(d->name, "B", q[1], err)))
            return st;
        C[0][1][0] = q[0];
        C[1][0][1] = q[1];
        C[2][2][0] = 1.0, C[2][0][2] = -1.0;
        C[3][0][0] = 1.0;
        break;
    default:
        return rg2__fail(err, RG2_EINVAL, "unknown shape kind %d", (int)s->kind);
    }
    rg2__ok(err);
    return RG2_OK;
}

/* Shape-specific limits on the produced parameter range of a knot direction. */
rg2_status rg2__shape_check_range(const rg2_shape *s, const rg2_partition *pv, rg2_error *err)
{
    int lo, hi;
    visible_range(pv, &lo, &hi);
    int off = pv->kind == RG2_PART_KNOTS_FULL ? 1 : 0;
    if ((s->kind == RG2_SHAPE_SPHERE || s->kind == RG2_SHAPE_ELLIPSOID) && pv->kind == RG2_PART_KNOTS) {
        /* a band: the poles v = 0, 1 must lie outside it (polar configurations choose their
         * data knots with RG2_PART_KNOTS_FULL and reach the poles on purpose) */
        for (int k = lo; k < hi; k++)
            if (!(pv->values[k] > 0.0 && pv->values[k] < 1.0))
                return rg2__fail(err, RG2_EDOMAIN,
                                 "%s: v knot %d = %s must lie in (0, 1) (v = 0 is the south pole, "
                                 "v = 1 the north pole; a knot at or past a pole puts the pole inside "
                                 "the band: close the sphere with the polar operation)",
                                 rg2_shape_name(s->kind), k, rg2__num(pv->values[k]).s);
        return RG2_OK;
    }
    if (s->kind != RG2_SHAPE_HYPERBOLOID1 && s->kind != RG2_SHAPE_HYPERBOLOID2)
        return RG2_OK;
    /* the knot closest to the weight's zero against the others (hyperboloid1: v relative to the
     * largest produced knot; hyperboloid2: 1 - |v|): within 1e-12 the ring there lies 1e12 times
     * further out than the rest, whose coordinates it rounds away (not measurable: 1e-13 and 1e-15
     * gave undefined normals), and from about 1e-17 the control weight rounds to 0 (a point at
     * infinity: NaN in the check report, STEP refused) */
    double vmax = 0;
    for (int k = lo; k < hi; k++)
        vmax = fmax(vmax, fabs(pv->values[k]));
    for (int k = lo; k < hi; k++) {
        double v = pv->values[k];
        if (s->kind == RG2_SHAPE_HYPERBOLOID1 && v > 0.0 && v < 1e-12 * vmax)
            return rg2__fail(err, RG2_EDOMAIN,
                             "hyperboloid1: v knot %d = %s is less than 1e-12 of the largest knot, %s: next to "
                             "v = 0, where the weight 2v vanishes, its ring lies %.3g times further out than that "
                             "knot's and rounds the rest of the surface away (keep the knots' ratio below 1e12)",
                             k - off, rg2__num(v).s, rg2__num(vmax).s, vmax / v);
        if (s->kind == RG2_SHAPE_HYPERBOLOID2 && fabs(v) < 1.0 && 1.0 - fabs(v) < 1e-12)
            return rg2__fail(err, RG2_EDOMAIN,
                             "hyperboloid2: v knot %d = %s is within 1e-12 of |v| = 1, where the weight 1 - v^2 "
                             "vanishes: its ring lies about %.3g times further out than the apex and rounds "
                             "the rest of the surface away (keep 1 - |v| at least 1e-12)",
                             k - off, rg2__num(v).s, 0.5 / (1.0 - fabs(v)));
    }
    for (int k = lo; k < hi; k++) {
        double v = pv->values[k];
        if (s->kind == RG2_SHAPE_HYPERBOLOID1 && !(v > 0.0))
            return rg2__fail(err, RG2_EDOMAIN,
                             "hyperboloid1: v knot %d = %s must be > 0 (the weight 2v vanishes "
                             "at v = 0, the point at infinity)",
                             k - off, rg2__num(v).s);
        if (s->kind == RG2_SHAPE_HYPERBOLOID2 && !(fabs(v) < 1.0))
            return rg2__fail(err, RG2_EDOMAIN,
                             "hyperboloid2: v knot %d = %s must satisfy |v| < 1 (the weight "
                             "1 - v^2 vanishes at |v| = 1, the points at infinity)",
                             k - off, rg2__num(v).s);
    }
    return RG2_OK;
}

static rg2_status check_xform(const double M[16], const char *who, rg2_error *err)
{
    double inv[16];
    rg2_status st = rg2_xform_invert(M, inv, err);
    if (st)
        return rg2__prefix(err, st, who);
    return RG2_OK;
}

/* A placement must keep every positive control weight positive: its last row gives the new
 * weight W' = M[12] x + M[13] y + M[14] z + M[15] W, and W' <= 0 puts the surface through
 * infinity. (Weights the shape itself gives <= 0, on data-only points or coarse arcs, are the
 * shape's: docs/shapes.md "Homogeneous weights".) */
static rg2_status check_placed_weights(const rg2_mesh *m, const double M[16], const char *who, rg2_error *err)
{
    if (M[12] == 0.0 && M[13] == 0.0 && M[14] == 0.0 && M[15] > 0.0)
        return RG2_OK; /* every weight times M[15] > 0 */
    for (int i = 0; i < m->nu; i++)
        for (int j = 0; j < m->nv; j++) {
            const double *p = rg2_mesh_at(m, i, j);
            double W = M[12] * p[0] + M[13] * p[1] + M[14] * p[2] + M[15] * p[3];
            if (p[3] > 0.0 && !(W > 0.0))
                return rg2__fail(err, rg2__finite(W) ? RG2_EWEIGHT : RG2_ENONFINITE,
                                 "%s: the placement gives control point [%d, %d] the weight W = %.6g "
                                 "(%.6g unplaced); weights must stay > 0 (the placement matrix's last "
                                 "row must be positive on the whole mesh, or the surface passes through "
                                 "infinity)",
                                 who, i, j, W, p[3]);
        }
    return RG2_OK;
}

rg2_status rg2_shape_mesh(const rg2_shape *s, const rg2_partition *pu, const rg2_partition *pv,
                          rg2_mesh *out, rg2_error *err)
{
    memset(out, 0, sizeof *out);
    double C[4][4][4];
    rg2_status st = rg2_shape_coeffs(s, C, err);
    if (st)
        return st;
    const rg2_shape_desc *d = rg2_shape_describe(s->kind);
    if ((st = need_kinds(pu, pv, d->dir_kind[0] == RG2_PART_ANGLES, d->dir_kind[1] == RG2_PART_ANGLES,
                         d->name, err)))
        return st;
    if ((st = rg2_partition_check(pu, "u", err)) || (st = rg2_partition_check(pv, "v", err)))
        return rg2__prefix(err, st, d->name);
    if ((st = rg2__shape_check_range(s, pv, err)) || (st = check_xform(s->xform, d->name, err)))
        return st;
    st = rg2_product_mesh((const double(*)[4][4])C, pu, pv, out, err);
    if (st)
        return rg2__prefix(err, st, d->name);
    if ((st = check_placed_weights(out, s->xform, d->name, err))) {
        rg2_mesh_free(out);
        return st;
    }
    rg2_mesh_transform(out, s->xform);
    return RG2_OK;
}

static void basis(int nb, double t, double f[4])
{
    if (nb == 3) {
        f[0] = 1.0, f[1] = cos(t), f[2] = sin(t), f[3] = 0.0;
    } else {
        f[0] = 1.0, f[1] = t, f[2] = t * t, f[3] = t * t * t;
    }
}

void rg2_shape_param(const rg2_shape *s, double u, double v, double h[4])
{
    double C[4][4][4];
    if (rg2_shape_coeffs(s, C, NULL)) {
        h[0] = h[1] = h[2] = h[3] = NAN;
        return;
    }
    const rg2_shape_desc *d = rg2_shape_describe(s->kind);
    double fu[4], gv[4], hl[4];
    basis(d->dir_kind[0] == RG2_PART_ANGLES ? 3 : 4, u, fu);
    basis(d->dir_kind[1] == RG2_PART_ANGLES ? 3 : 4, v, gv);
    for (int k = 0; k < 4; k++) {
        double acc = 0.0;
        for (int a = 0; a < 4; a++)
            for (int b = 0; b < 4; b++)
                acc += C[k][a][b] * fu[a] * gv[b];
        hl[k] = acc;
    }
    for (int r = 0; r < 4; r++)
        h[r] = s->xform[4 * r] * hl[0] + s->xform[4 * r + 1] * hl[1] + s->xform[4 * r + 2] * hl[2] +
               s->xform[4 * r + 3] * hl[3];
}

/* ------------------------------------------------------------------------------------- */
/* Implicit equations: value, gradient and Hessian by second-order forward jets           */
/* ------------------------------------------------------------------------------------- */

typedef struct {
    double v, g[3], h[9];
} jet;

static jet jconst(double c)
{
    jet r;
    memset(&r, 0, sizeof r);
    r.v = c;
    return r;
}

static jet jadd(jet a, jet b)
{
    a.v += b.v;
    for (int k = 0; k < 3; k++)
        a.g[k] += b.g[k];
    for (int k = 0; k < 9; k++)
        a.h[k] += b.h[k];
    return a;
}

static jet jscale(jet a, double c)
{
    a.v *= c;
    for (int k = 0; k < 3; k++)
        a.g[k] *= c;
    for (int k = 0; k < 9; k++)
        a.h[k] *= c;
    return a;
}

static jet jsub(jet a, jet b) { return jadd(a, jscale(b, -1.0)); }

static jet jaddc(jet a, double c)
{
    a.v += c;
    return a;
}

static jet jmul(jet a, jet b)
{
    jet r;
    r.v = a.v * b.v;
    for (int k = 0; k < 3; k++)
        r.g[k] = a.g[k] * b.v + a.v * b.g[k];
    for (int i = 0; i < 3; i++)
        for (int j = 0; j < 3; j++)
            r.h[3 * i + j] = a.h[3 * i + j] * b.v + a.v * b.h[3 * i + j] + a.g[i] * b.g[j] +
                             a.g[j] * b.g[i];
    return r;
}

static jet jsq(jet a) { return jmul(a, a); }

/* sqrt(a) for a.v > 0: s' = a' / (2 s), s'' = (a'' - 2 s' s'^T) / (2 s). */
static jet jsqrt(jet a)
{
    jet r;
    r.v = sqrt(a.v);
    for (int k = 0; k < 3; k++)
        r.g[k] = a.g[k] / (2.0 * r.v);
    for (int i = 0; i < 3; i++)
        for (int j = 0; j < 3; j++)
            r.h[3 * i + j] = (a.h[3 * i + j] - 2.0 * r.g[i] * r.g[j]) / (2.0 * r.v);
    return r;
}

static jet jdiv(jet a, jet b)
{
    jet r;
    double q = a.v / b.v;
    r.v = q;
    for (int k = 0; k < 3; k++)
        r.g[k] = (a.g[k] - q * b.g[k]) / b.v;
    for (int i = 0; i < 3; i++)
        for (int j = 0; j < 3; j++)
            r.h[3 * i + j] = (a.h[3 * i + j] - q * b.h[3 * i + j] - r.g[i] * b.g[j] - r.g[j] * b.g[i]) /
                             b.v;
    return r;
}

/* The implicit function of the unplaced shape (0 on the surface). */
static jet local_implicit(const rg2_shape *s, jet x, jet y, jet z)
{
    const double *q = s->param;
    jet x2 = jsq(x), y2 = jsq(y), z2 = jsq(z);
    switch (s->kind) {
    case RG2_SHAPE_TORUS: {
        double R = q[0], r = q[1];
        jet rho2 = jadd(x2, y2);
        if (!(rho2.v > 0.0) || !(r < 1e-2 * R)) {
            /* the polynomial (on the axis the factors' rho has no derivative; a tube of r >= R / 100
             * loses at most 4e-15 of the size to its cancellation) */
            jet t = jaddc(jadd(rho2, z2), R * R - r * r);
            return jsub(jsq(t), jscale(rho2, 4.0 * R * R));
        }
        /* a thin tube: the same polynomial, (rho^2 + z^2 + R^2 - r^2)^2 - 4 R^2 rho^2, as the
         * product of its factors ((rho - R)^2 + z^2 - r^2) ((rho + R)^2 + z^2 - r^2): the first
         * vanishes on the surface without cancelling terms of size R^2 (a tube of r = 1e-6 R
         * measured 3.9e-11 of its size off itself, 1e-9 R 3.9e-8: the rounding of R^4 over a
         * gradient of 8 R^2 r) */
        jet rho = jsqrt(rho2);
        jet P = jaddc(jadd(jsq(jaddc(rho, -R)), z2), -r * r);
        jet Q = jaddc(jadd(jsq(jaddc(rho, R)), z2), -r * r);
        return jmul(P, Q);
    }
    case RG2_SHAPE_CYCLIDE: {
        double a = q[0], c = q[1], mu = q[2], b2 = a * a - c * c;
        jet t = jaddc(jadd(jadd(x2, y2), z2), b2 - mu * mu);
        jet l = jaddc(jscale(x, a), -c * mu);
        return jsub(jsub(jsq(t), jscale(jsq(l), 4.0)), jscale(y2, 4.0 * b2));
    }
    case RG2_SHAPE_SPHERE:
        return jaddc(jscale(jadd(jadd(x2, y2), z2), 1.0 / (q[0] * q[0])), -1.0);
    case RG2_SHAPE_ELLIPSOID:
        return jaddc(jadd(jadd(jscale(x2, 1.0 / (q[0] * q[0])), jscale(y2, 1.0 / (q[1] * q[1]))),
                          jscale(z2, 1.0 / (q[2] * q[2]))),
                     -1.0);
    case RG2_SHAPE_CYLINDER:
        return jaddc(jscale(jadd(x2, y2), 1.0 / (q[0] * q[0])), -1.0);
    case RG2_SHAPE_CONE:
        return jsub(jscale(jadd(x2, y2), q[0] * q[0]), z2);
    case RG2_SHAPE_HYPERBOLOID1_RULED:
    case RG2_SHAPE_HYPERBOLOID1:
        return jaddc(jsub(jscale(jadd(x2, y2), 1.0 / (q[0] * q[0])), jscale(z2, 1.0 / (q[1] * q[1]))),
                     -1.0);
    case RG2_SHAPE_HYPERBOLOID2:
        return jaddc(jsub(jscale(z2, 1.0 / (q[1] * q[1])), jscale(jadd(x2, y2), 1.0 / (q[0] * q[0]))),
                     -1.0);
    case RG2_SHAPE_PARABOLOID:
        return jsub(jadd(jscale(x2, 1.0 / (q[0] * q[0])), jscale(y2, 1.0 / (q[1] * q[1]))), z);
    case RG2_SHAPE_HYPAR:
        return jsub(jsub(jscale(x2, 1.0 / (q[0] * q[0])), jscale(y2, 1.0 / (q[1] * q[1]))), z);
    default:
        return jconst(NAN);
    }
}

/*
 * METHOD: the placed surface is M applied to the local one, so the placed implicit function
 * is f(phi(x)) with phi = M^{-1} as a projective map: y_i = N_i(x) / N_4(x), N = M^{-1} (x, 1).
 * The jets carry value, gradient and Hessian through the chain rule exactly.
 */
void rg2__implicit_prep(const rg2_shape *s, rg2__implicit *p)
{
    double C[4][4][4];
    p->s = s;
    p->ok = !rg2_shape_coeffs(s, C, NULL) && !rg2_xform_invert(s->xform, p->inv, NULL);
}

double rg2__implicit_eval(const rg2__implicit *p, const double x[3], double grad[3], double hess[9])
{
    jet f;
    if (!p->ok) {
        f = jconst(NAN);
        for (int k = 0; k < 3; k++)
            f.g[k] = NAN;
        for (int k = 0; k < 9; k++)
            f.h[k] = NAN;
    } else {
        const double *inv = p->inv;
        jet N[4];
        for (int i = 0; i < 4; i++) {
            N[i] = jconst(inv[4 * i + 3]);
            for (int j = 0; j < 3; j++) {
                N[i].v += inv[4 * i + j] * x[j];
                N[i].g[j] = inv[4 * i + j];
            }
        }
        int affine = inv[12] == 0.0 && inv[13] == 0.0 && inv[14] == 0.0 && inv[15] == 1.0;
        if (!affine)
            for (int i = 0; i < 3; i++)
                N[i] = jdiv(N[i], N[3]);
        f = local_implicit(p->s, N[0], N[1], N[2]);
    }
    if (grad)
        memcpy(grad, f.g, sizeof f.g);
    if (hess)
        memcpy(hess, f.h, sizeof f.h);
    return f.v;
}

double rg2_shape_implicit2(const rg2_shape *s, const double x[3], double grad[3], double hess[9])
{
    rg2__implicit p;
    rg2__implicit_prep(s, &p);
    return rg2__implicit_eval(&p, x, grad, hess);
}

double rg2_shape_implicit(const rg2_shape *s, const double x[3], double grad[3])
{
    return rg2_shape_implicit2(s, x, grad, NULL);
}

/* ------------------------------------------------------------------------------------- */
/* Placement matrices and exact transforms                                                */
/* ------------------------------------------------------------------------------------- */

void rg2_xform_identity(double M[16])
{
    memset(M, 0, sizeof(double) * 16);
    M[0] = M[5] = M[10] = M[15] = 1.0;
}

void rg2_xform_mul(const double A[16], const double B[16], double out[16])
{
    double r[16];
    for (int i = 0; i < 4; i++)
        for (int j = 0; j < 4; j++)
            r[4 * i + j] = A[4 * i] * B[j] + A[4 * i + 1] * B[4 + j] + A[4 * i + 2] * B[8 + j] +
                           A[4 * i + 3] * B[12 + j];
    memcpy(out, r, sizeof r);
}

void rg2_xform_translate(double M[16], double x, double y, double z)
{
    rg2_xform_identity(M);
    M[3] = x;
    M[7] = y;
    M[11] = z;
}

void rg2_xform_scale(double M[16], double sx, double sy, double sz)
{
    rg2_xform_identity(M);
    M[0] = sx;
    M[5] = sy;
    M[10] = sz;
}

void rg2_xform_rotate(double M[16], double ax, double ay, double az, double angle)
{
    rg2_xform_identity(M);
    double len = sqrt(ax * ax + ay * ay + az * az);
    if (!(len > 0.0))
        return;
    ax /= len, ay /= len, az /= len;
    double c = cos(angle), s = sin(angle), t = 1.0 - c;
    M[0] = t * ax * ax + c, M[1] = t * ax * ay - s * az, M[2] = t * ax * az + s * ay;
    M[4] = t * ax * ay + s * az, M[5] = t * ay * ay + c, M[6] = t * ay * az - s * ax;
    M[8] = t * ax * az - s * ay, M[9] = t * ay * az + s * ax, M[10] = t * az * az + c;
}

void rg2_xform_place(double M[16], const double centre[3], const double axis[3])
{
    double len = sqrt(axis[0] * axis[0] + axis[1] * axis[1] + axis[2] * axis[2]);
    double R[16], T[16];
    rg2_xform_identity(R);
    if (len > 0.0) {
        double a[3] = {axis[0] / len, axis[1] / len, axis[2] / len};
        double k[3] = {-a[1], a[0], 0.0}; /* z x a */
        double sn = sqrt(k[0] * k[0] + k[1] * k[1]);
        if (sn > 0.0)
            rg2_xform_rotate(R, k[0], k[1], k[2], atan2(sn, a[2]));
        else if (a[2] < 0.0)
            rg2_xform_rotate(R, 1.0, 0.0, 0.0, M_PI);
    }
    rg2_xform_translate(T, centre[0], centre[1], centre[2]);
    rg2_xform_mul(T, R, M);
}

/* Gauss-Jordan elimination with partial pivoting. Rows whose pivot columns hold exact
 * zeros (the (0, 0, 0, 1) row of an affine matrix) stay exact. */
/* METHOD: Gauss-Jordan with partial pivoting on the equilibrated matrix B = Dr M Dc (row and
 * column scales are powers of 2, so exact): the singularity test is then relative to each
 * row's and column's own size, and a placement such as scale 1e-60 (tiny linear part next
 * to the 1 of the homogeneous row) or a far translation is not mistaken for a singular one.
 * M^-1 = Dc B^-1 Dr. */
rg2_status rg2_xform_invert(const double M[16], double inv[16], rg2_error *err)
{
    double a[4][8];
    double mx = 1.0;
    int ec[4], er[4];
    for (int i = 0; i < 4; i++)
        for (int j = 0; j < 4; j++)
            if (!rg2__finite(M[4 * i + j]))
                return rg2__fail(err, RG2_ENONFINITE, "placement matrix entry [%d][%d] is not finite",
                                 i, j);
    for (int j = 0; j < 4; j++) {
        double m = 0.0;
        for (int i = 0; i < 4; i++)
            m = fmax(m, fabs(M[4 * i + j]));
        if (m == 0.0)
            return rg2__fail(err, RG2_EDOMAIN, "placement matrix is singular (column %d is zero)", j);
        frexp(m, &ec[j]);
        ec[j] = -ec[j];
    }
    for (int i = 0; i < 4; i++) {
        double m = 0.0;
        for (int j = 0; j < 4; j++)
            m = fmax(m, fabs(ldexp(M[4 * i + j], ec[j])));
        if (m == 0.0)
            return rg2__fail(err, RG2_EDOMAIN, "placement matrix is singular (row %d is zero)", i);
        frexp(m, &er[i]);
        er[i] = -er[i];
        for (int j = 0; j < 4; j++) {
            a[i][j] = ldexp(M[4 * i + j], ec[j] + er[i]);
            a[i][4 + j] = i == j ? 1.0 : 0.0;
        }
    }
    for (int c = 0; c < 4; c++) {
        int piv = c;
        for (int r = c + 1; r < 4; r++)
            if (fabs(a[r][c]) > fabs(a[piv][c]))
                piv = r;
        if (!(fabs(a[piv][c]) > 1e-14 * mx))
            return rg2__fail(err, RG2_EDOMAIN, "placement matrix is singular (column %d)", c);
        if (piv != c)
            for (int j = 0; j < 8; j++) {
                double t = a[c][j];
                a[c][j] = a[piv][j];
                a[piv][j] = t;
            }
        double p = a[c][c];
        for (int j = 0; j < 8; j++)
            a[c][j] /= p;
        for (int r = 0; r < 4; r++) {
            if (r == c || a[r][c] == 0.0)
                continue;
            double f = a[r][c];
            for (int j = 0; j < 8; j++)
                a[r][j] -= f * a[c][j];
        }
    }
    double r[16]; /* (inv is left as it was when the inverse is out of range) */
    for (int k = 0; k < 16; k++) {
        r[k] = ldexp(a[k / 4][4 + k % 4], ec[k / 4] + er[k % 4]);
        if (!rg2__finite(r[k]))
            return rg2__fail(err, RG2_EDOMAIN,
                             "placement matrix is singular in double precision (inverse entry [%d][%d] overflows)",
                             k / 4, k % 4);
    }
    memcpy(inv, r, sizeof r);
    rg2__ok(err);
    return RG2_OK;
}

void rg2__xform_apply(const double M[16], double p[4])
{
    double q[4];
    for (int r = 0; r < 4; r++)
        q[r] = M[4 * r] * p[0] + M[4 * r + 1] * p[1] + M[4 * r + 2] * p[2] + M[4 * r + 3] * p[3];
    memcpy(p, q, sizeof q);
}

void rg2_mesh_transform(rg2_mesh *m, const double M[16])
{
    size_t np = (size_t)m->nu * (size_t)m->nv;
    for (size_t k = 0; k < np; k++)
        rg2__xform_apply(M, m->p + 4 * k);
}

/* ------------------------------------------------------------------------------------- */
/* Weights and one-call surfaces                                                          */
/* ------------------------------------------------------------------------------------- */

void rg2_surface_weight_report(const rg2_surface *s, rg2_weight_report *rep)
{
    memset(rep, 0, sizeof *rep);
    rep->min_weight = INFINITY;
    for (int i = 0; i < s->nu; i++)
        for (int j = 0; j < s->nv; j++) {
            rg2_xpatch P;
            rg2_surface_patch_get(s, i, j, &P);
            double mn = INFINITY;
            for (int r = 0; r <= P.du; r++)
                for (int t = 0; t <= P.dv; t++)
                    if (P.h[r][t][3] < mn)
                        mn = P.h[r][t][3];
            if (!(mn > 0.0))
                rep->n_nonpositive++;
            if (mn < rep->min_weight) {
                rep->min_weight = mn;
                rep->patch_i = i;
                rep->patch_j = j;
            }
        }
    if (rep->n_nonpositive)
        rep->flags |= RG2_SHAPE_WARN_WEIGHT;
}

rg2_status rg2_shape_surface(const rg2_shape *s, const rg2_partition *pu, const rg2_partition *pv,
                             rg2_surface *out, rg2_weight_report *rep, rg2_error *err)
{
    memset(out, 0, sizeof *out);
    rg2_mesh m;
    rg2_status st = rg2_shape_mesh(s, pu, pv, &m, err);
    if (st)
        return st;
    st = rg2_surface_build(&m, out, err);
    rg2_mesh_free(&m);
    if (st)
        return st;
    /* every patch lies on the shape: tag 0, the shape in a one-shape list (rg2_check(&surface, 1,
     * s, NULL, 1, ...) found no exact patch before, the tags being NULL) */
    size_t np = (size_t)out->nu * (size_t)out->nv;
    if (!(out->tag = rg2__calloc(np, sizeof *out->tag))) {
        rg2_surface_free(out);
        return rg2__fail(err, RG2_ENOMEM, "shape surface: out of memory");
    }
    if (rep)
        rg2_surface_weight_report(out, rep);
    return RG2_OK;
}
