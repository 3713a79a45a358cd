/* scalars.c -- direction scalars (w, b, g): storage, validation, and the two standard
 * sources: knot vectors (polynomial mode) and circle partitions (MATH.md sections 1-2). */
#include "internal.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

int rg2_scalars_num_w(const rg2_scalars *s) { return s->closed ? s->n : s->n + 1; }

int rg2_scalars_num_segments(const rg2_scalars *s) { return s->closed ? s->n : s->n - 3; }

static rg2_status check_count(int n, int closed, const char *what, rg2_error *err)
{
    int min = closed ? 3 : 4;
    if (n < min)
        return rg2__fail(err, RG2_EINVAL, "%s: %d control points, a%s direction needs at least %d",
                         what, n, closed ? " closed" : "n open", min);
    if (n > RG2_MAX_POINTS)
        return rg2__fail(err, RG2_ELIMIT, "%s: %d control points exceeds the limit %d", what, n,
                         RG2_MAX_POINTS);
    return RG2_OK;
}

/* The count of values a caller passed (n_knots, n_alpha): `given` of them make given - extra
 * control points. Too few or too many are told in the caller's unit, with the minimum it needs
 * (an open direction 4 points, a closed one 3): "knots: 2 knots given, an open direction needs
 * at least 6 (4 control points, 1 segment)" (the messages spoke of given - extra control points,
 * "-3 control points" for n_knots = -1). */
static rg2_status check_given(int given, int extra, int closed, const char *what, const char *unit,
                              rg2_error *err)
{
    int min_points = closed ? 3 : 4, min = min_points + extra;
    if (given < min)
        return rg2__fail(err, RG2_EINVAL, "%s: %d %s given, a%s direction needs at least %d (%d control points, %s)",
                         what, given, unit, closed ? " closed" : "n open", min, min_points,
                         closed ? "3 segments" : "1 segment");
    if (given - extra > RG2_MAX_POINTS)
        return rg2__fail(err, RG2_ELIMIT, "%s: %d %s given, more than the limit %d (%d control points)", what,
                         given, unit, RG2_MAX_POINTS + extra, RG2_MAX_POINTS);
    return RG2_OK;
}

/* An opening angle outside (0, pi), in radians and in the degrees the user likely gave. */
static rg2_status bad_arc(int k, double a, rg2_error *err)
{
    return rg2__fail(err, RG2_EDOMAIN,
                     "arcs: arc %d has opening angle %s rad (%.10g deg); it must lie in (0, pi)", k, rg2__num(a).s,
                     a * 180.0 / M_PI);
}

rg2_status rg2_scalars_init(rg2_scalars *s, int n, int closed, rg2_error *err)
{
    memset(s, 0, sizeof *s);
    rg2_status st = check_count(n, closed, "scalars", err);
    if (st)
        return st;
    s->n = n;
    s->closed = closed ? 1 : 0;
    int nw = rg2_scalars_num_w(s);
    s->w = rg2__calloc((size_t)nw, sizeof(double));
    s->b = rg2__calloc((size_t)n, sizeof(double));
    s->g = rg2__calloc((size_t)n, sizeof(double));
    if (!s->w || !s->b || !s->g) {
        rg2_scalars_free(s);
        return rg2__fail(err, RG2_ENOMEM, "scalars: out of memory for %d points", n);
    }
    for (int i = 0; i < nw; i++)
        s->w[i] = 1.0;
    for (int i = 0; i < n; i++)
        s->b[i] = 1.0;
    rg2__ok(err);
    return RG2_OK;
}

void rg2_scalars_free(rg2_scalars *s)
{
    if (!s)
        return;
    free(s->w);
    free(s->b);
    free(s->g);
    memset(s, 0, sizeof *s);
}

rg2_status rg2_scalars_copy(const rg2_scalars *src, rg2_scalars *dst, rg2_error *err)
{
    if (src == dst) /* (filling dst from scratch zeroed src first: uniform scalars, returning RG2_OK) */
        return rg2__fail(err, RG2_EINVAL, "scalars copy: the destination is the source; give a struct of its own");
    rg2_status st = rg2_scalars_init(dst, src->n, src->closed, err);
    if (st)
        return st;
    memcpy(dst->w, src->w, sizeof(double) * (size_t)rg2_scalars_num_w(src));
    memcpy(dst->b, src->b, sizeof(double) * (size_t)src->n);
    memcpy(dst->g, src->g, sizeof(double) * (size_t)src->n);
    return RG2_OK;
}

double rg2_scalars_leg_w(const rg2_scalars *s, int i)
{
    if (s->closed)
        return s->w[rg2__wrap(i, s->n, 1)];
    return s->w[i + 1];
}

int rg2__prev_leg(const rg2_scalars *s, int i)
{
    return s->closed ? rg2__wrap(i - 1, s->n, 1) : i - 1;
}

double rg2_scalars_K(const rg2_scalars *s, int i)
{
    int j = rg2__wrap(i, s->n, s->closed);
    double b = s->b[j], g = s->g[j];
    double wi = rg2_scalars_leg_w(s, j), wm = rg2_scalars_leg_w(s, j - 1);
    return 2.0 * b * (3.0 * wi - 2.0) + 2.0 * b * b * (3.0 * wm - 2.0) + g;
}

rg2_status rg2_scalars_check(const rg2_scalars *s, const char *what, rg2_error *err)
{
    if (!what)
        what = "scalars";
    rg2_status st = check_count(s->n, s->closed, what, err);
    if (st)
        return st;
    if (!s->w || !s->b || !s->g)
        return rg2__fail(err, RG2_EINVAL, "%s: scalars not allocated", what);
    int nw = rg2_scalars_num_w(s), off = s->closed ? 0 : 1;
    for (int k = 0; k < nw; k++) {
        if (!rg2__finite(s->w[k]))
            return rg2__fail(err, RG2_ENONFINITE, "%s: weight w[%d] is not finite", what, k - off);
        if (!(s->w[k] > 0.0))
            return rg2__fail(err, RG2_EWEIGHT, "%s: weight w[%d] = %g, must be > 0", what, k - off,
                             s->w[k]);
    }
    for (int i = 0; i < s->n; i++) {
        if (!rg2__finite(s->b[i]))
            return rg2__fail(err, RG2_ENONFINITE, "%s: scalar b[%d] is not finite", what, i);
        if (!rg2__finite(s->g[i]))
            return rg2__fail(err, RG2_ENONFINITE, "%s: scalar g[%d] is not finite", what, i);
        if (!(s->b[i] > 0.0))
            return rg2__fail(err, RG2_EWEIGHT, "%s: scalar b[%d] = %g, must be > 0", what, i,
                             s->b[i]);
    }
    for (int i = 0; i < s->n; i++) {
        double K = rg2_scalars_K(s, i);
        if (!(K > 0.0) || !rg2__finite(K))
            return rg2__fail(err, rg2__finite(K) ? RG2_EWEIGHT : RG2_ENONFINITE,
                             "%s: junction %d has K = %g (from w[%d] = %g, w[%d] = %g, b = %g, g = %g);"
                             " K must be %s",
                             what, i, K, rg2__prev_leg(s, i), rg2_scalars_leg_w(s, i - 1), i,
                             rg2_scalars_leg_w(s, i), s->b[i], s->g[i],
                             rg2__finite(K) ? "> 0" : "a finite number > 0 (the scalars leave the double range)");
    }
    rg2__ok(err);
    return RG2_OK;
}

/* The first junction of scalars just made from finite knots or arcs whose b, g or K is not a
 * finite number (b also 0: a ratio below the double range), or -1; *which names those scalars
 * ("K is", "b and K are", ...). Lengths or angles on the two sides of a junction that differ by
 * about the double range give them: intervals 1e-300 and 1 give b = 1e300, a double, but
 * K = 2 b (3 w - 2) + 2 b^2 (3 w' - 2) + g = inf. */
static int out_of_range(const rg2_scalars *s, char which[32])
{
    for (int i = 0; i < s->n; i++) {
        double b = s->b[i], g = s->g[i], K = rg2_scalars_K(s, i);
        int bad[3] = {!(b > 0.0 && rg2__finite(b)), !rg2__finite(g), !rg2__finite(K)};
        if (!bad[0] && !bad[1] && !bad[2])
            continue;
        static const char *const names[3] = {"b", "g", "K"};
        int nb = bad[0] + bad[1] + bad[2], k = 0;
        which[0] = '\0';
        for (int j = 0; j < 3; j++)
            if (bad[j]) {
                strcat(which, k == 0 ? "" : k + 1 < nb ? ", " : " and ");
                strcat(which, names[j]);
                k++;
            }
        strcat(which, nb > 1 ? " are" : " is");
        return i;
    }
    return -1;
}

/* The interval knots[k..k+1] in the caller's terms: name[k + first .. k + first + 1]; with
 * first < 0 the caller gave knots[-first .. n_knots - 1 + first] and the ends around them are
 * mirrored (a shape's open knot partition), named as such. */
static void interval_name(char *buf, size_t cap, const char *name, int k, int first, int n_knots)
{
    int j = k + first, last = n_knots - 1 + 2 * first;
    if (first < 0 && j < 0)
        snprintf(buf, cap, "%s mirrored before %s[0]", j == -1 ? "the first" : "the second", name);
    else if (first < 0 && j + 1 > last)
        snprintf(buf, cap, "%s mirrored after %s[%d]", j == last ? "the first" : "the second", name, last);
    else
        snprintf(buf, cap, "%s[%d..%d]", name, j, j + 1);
}

rg2_status rg2__scalars_from_knots_named(rg2_scalars *s, const double *knots, int n_knots, int closed,
                                         const char *who, const char *name, int first, rg2_error *err)
{
    memset(s, 0, sizeof *s);
    rg2_status st = check_given(n_knots, closed ? 1 : 2, closed, "knots", "knots", err);
    if (st)
        return st;
    int n = n_knots - (closed ? 1 : 2);
    for (int k = 0; k < n_knots; k++)
        if (!rg2__finite(knots[k]))
            return rg2__fail(err, RG2_ENONFINITE, "knots: knot %d is not finite", k);
    for (int k = 0; k + 1 < n_knots; k++)
        if (!(knots[k + 1] > knots[k])) {
            char iv[64] = "";
            if (first < 0) /* (the mirrored ends of values that are themselves increasing) */
                interval_name(iv, sizeof iv, name, k, first, n_knots);
            return rg2__fail(err, RG2_EDOMAIN,
                             "knots: interval %s%s [%s, %s] has zero or negative length "
                             "(repeated knots are not supported: split the spline there)",
                             first < 0 ? "" : rg2__num(k).s, iv, rg2__num(knots[k]).s, rg2__num(knots[k + 1]).s);
        }
    st = rg2_scalars_init(s, n, closed, err);
    if (st)
        return st;
    for (int i = 0; i < n; i++) {
        double d, dm;
        if (closed) {
            d = knots[i + 1] - knots[i];
            int im = (i + n - 1) % n;
            dm = knots[im + 1] - knots[im];
        } else {
            /* knots[k] = v_{k-1}: d_i = v_{i+1} - v_i = knots[i+2] - knots[i+1] */
            d = knots[i + 2] - knots[i + 1];
            dm = knots[i + 1] - knots[i];
        }
        s->b[i] = d / dm;
        s->g[i] = 0.0;
    }
    char which[32];
    int i = out_of_range(s, which);
    if (i < 0)
        return RG2_OK;
    double b = s->b[i], g = s->g[i], K = rg2_scalars_K(s, i);
    int k0 = closed ? (i + n - 1) % n : i, k1 = closed ? i : i + 1; /* the intervals' first knots */
    char junction[32] = "";
    if (first == 0)
        snprintf(junction, sizeof junction, " (junction %d)", i);
    char iv0[64], iv1[64];
    interval_name(iv0, sizeof iv0, name, k0, first, n_knots);
    interval_name(iv1, sizeof iv1, name, k1, first, n_knots);
    rg2_scalars_free(s);
    return rg2__fail(err, RG2_EDOMAIN,
                     "%s: the knot intervals %s = [%s, %s] and %s = [%s, %s]%s give b = %g, g = %g, K = %g: %s "
                     "out of the double range",
                     who, iv0, rg2__num(knots[k0]).s, rg2__num(knots[k0 + 1]).s, iv1, rg2__num(knots[k1]).s,
                     rg2__num(knots[k1 + 1]).s, junction, b, g, K, which);
}

rg2_status rg2_scalars_from_knots(rg2_scalars *s, const double *knots, int n_knots, int closed,
                                  rg2_error *err)
{
    return rg2__scalars_from_knots_named(s, knots, n_knots, closed, "knots", "knots", 0, err);
}

rg2_status rg2_scalars_from_angles(rg2_scalars *s, const double *alpha, int n_alpha, int closed,
                                   rg2_error *err)
{
    memset(s, 0, sizeof *s);
    rg2_status st = check_given(n_alpha, closed ? 0 : 1, closed, "arcs", "arcs", err);
    if (st)
        return st;
    int n = n_alpha - (closed ? 0 : 1);
    int off = closed ? 0 : 1;
    for (int k = 0; k < n_alpha; k++) {
        if (!rg2__finite(alpha[k]))
            return rg2__fail(err, RG2_ENONFINITE, "arcs: angle of arc %d is not finite", k - off);
        if (!(alpha[k] > 0.0 && alpha[k] < M_PI))
            return bad_arc(k - off, alpha[k], err);
    }
    st = rg2_scalars_init(s, n, closed, err);
    if (st)
        return st;
    for (int k = 0; k < n_alpha; k++)
        s->w[k] = (1.0 + 2.0 * cos(0.5 * alpha[k])) / 3.0;
    for (int i = 0; i < n; i++) {
        /* junction i joins arc i-1 and arc i */
        double ai = closed ? alpha[i] : alpha[i + 1];
        double am = closed ? alpha[(i + n - 1) % n] : alpha[i];
        double bi = 0.5 * ai, bm = 0.5 * am;
        double b = sin(bi) / sin(bm);
        s->b[i] = b;
        s->g[i] = 2.0 * b * sin(bi) * (tan(0.5 * bi) + tan(0.5 * bm));
    }
    char which[32];
    int i = out_of_range(s, which);
    if (i < 0)
        return RG2_OK;
    double b = s->b[i], g = s->g[i], K = rg2_scalars_K(s, i);
    int k0 = closed ? (i + n - 1) % n : i, k1 = closed ? i : i + 1; /* alpha[] of arcs i - 1 and i */
    rg2_scalars_free(s);
    return rg2__fail(err, RG2_EDOMAIN,
                     "arcs: arcs %d and %d (angles %s and %s) give junction %d b = %g, g = %g, K = %g: %s out "
                     "of the double range",
                     k0 - off, k1 - off, rg2__num(alpha[k0]).s, rg2__num(alpha[k1]).s, i, b, g, K, which);
}

void rg2_blossom_monomials(double a, double b, double c, double out[4])
{
    out[0] = 1.0;
    out[1] = (a + b + c) / 3.0;
    out[2] = (a * b + a * c + b * c) / 3.0;
    out[3] = a * b * c;
}

rg2_status rg2_circle_coeffs(const double *alpha, int n_alpha, int closed, double theta0,
                             double *cs, rg2_error *err)
{
    rg2_status st = check_given(n_alpha, closed ? 0 : 1, closed, "arcs", "arcs", err);
    if (st)
        return st;
    int n = n_alpha - (closed ? 0 : 1);
    int off = closed ? 0 : 1;
    double sum = 0.0;
    for (int k = 0; k < n_alpha; k++) {
        if (!rg2__finite(alpha[k]))
            return rg2__fail(err, RG2_ENONFINITE, "arcs: angle of arc %d is not finite", k - off);
        if (!(alpha[k] > 0.0 && alpha[k] < M_PI))
            return bad_arc(k - off, alpha[k], err);
        sum += alpha[k];
    }
    if (!rg2__finite(theta0))
        return rg2__fail(err, RG2_ENONFINITE, "arcs: start angle is not finite");
    if (closed && fabs(sum - 2.0 * M_PI) > RG2_CLOSED_SUM_TOL * 2.0 * M_PI)
        return rg2__fail(err, RG2_EDOMAIN,
                         "arcs: a closed circle needs opening angles that sum to 2 pi; these sum to "
                         "%s rad (%.10g deg)",
                         rg2__num(sum).s, sum * 180.0 / M_PI);
    /* Junction i sits at theta_i (start of arc i). Its control point is the intersection of
     * the lines through (b1, b2) of arcs i-1 and i; in a frame rotated by theta_i the line of
     * arc i is {x : x . m_i = c_i}, m_i = (cos beta_i, sin beta_i),
     * c_i = (cos beta_i + 2) / (1 + 2 cos beta_i), and arc i-1 has m = (cos bm, -sin bm). */
    double theta = rg2__within_turn(theta0); /* (1e20 rad put every corner on one ray) */
    double comp = 0.0; /* Kahan compensation of the running angle */
    for (int i = 0; i < n; i++) {
        double ai = closed ? alpha[i] : alpha[i + 1];
        double am = closed ? alpha[(i + n - 1) % n] : alpha[i];
        double bi = 0.5 * ai, bm = 0.5 * am;
        double ci = (cos(bi) + 2.0) / (1.0 + 2.0 * cos(bi));
        double cm = (cos(bm) + 2.0) / (1.0 + 2.0 * cos(bm));
        /* [cos bm, -sin bm; cos bi, sin bi] x = [cm; ci] */
        double det = cos(bm) * sin(bi) + sin(bm) * cos(bi); /* = sin(bm + bi) > 0 */
        double x = (cm * sin(bi) + sin(bm) * ci) / det;
        double y = (cos(bm) * ci - cos(bi) * cm) / det;
        double ct = cos(theta), stt = sin(theta);
        cs[2 * i] = ct * x - stt * y;
        cs[2 * i + 1] = stt * x + ct * y;
        /* advance theta by arc i */
        double yk = ai - comp;
        double tk = theta + yk;
        comp = (tk - theta) - yk;
        theta = tk;
    }
    rg2__ok(err);
    return RG2_OK;
}
