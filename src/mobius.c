/* mobius.c -- Moebius pole placement (paper eq. 16, MATH.md section 7). A Moebius map of the
 * sphere acts linearly on the sphere's homogeneous 4-tuples (x, y, z, w), x^2+y^2+z^2 = w^2:
 * it is a Lorentz transformation. Applying its 4x4 matrix to every control 4-tuple keeps an
 * exact sphere exact and moves the poles of the parameterization. */
#include "internal.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

static void matmul4(const double A[16], const double B[16], double C[16])
{
    double T[16];
    for (int r = 0; r < 4; r++)
        for (int c = 0; c < 4; c++) {
            double s = 0.0;
            for (int k = 0; k < 4; k++)
                s += A[4 * r + k] * B[4 * k + c];
            T[4 * r + c] = s;
        }
    memcpy(C, T, sizeof T);
}

/* Embed a row-major 3x3 matrix as the upper-left block of a 4x4 one. */
static void embed3(const double R[9], double M[16])
{
    memset(M, 0, 16 * sizeof(double));
    for (int r = 0; r < 3; r++)
        for (int c = 0; c < 3; c++)
            M[4 * r + c] = R[3 * r + c];
    M[15] = 1.0;
}

/*
 * METHOD: eq. (16) gives, for the sphere 4-tuple (X, Y, Z, W) of MATH.md section 5,
 *   x' = (1 - b^2) X - 2b Z,  y' = (1 + b^2) Y,  z' = 2b X + (1 - b^2) Z,  w' = (1 + b^2) W,
 * i.e. (1 + b^2) times the rotation about y by the angle 2 atan(b).
 */
void rg2_mobius_matrix(double b, const double *R, double M[16])
{
    double s = 1.0 + b * b, co = (1.0 - b * b) / s, si = 2.0 * b / s;
    if (fabs(b) > 1e150) { /* b^2 overflows (b = 1e300 gave NaN): the same rotation in 1 / b */
        double c = 1.0 / b;
        co = (c * c - 1.0) / (1.0 + c * c);
        si = 2.0 * c / (1.0 + c * c);
    }
    double B[16] = {co, 0, -si, 0, 0, 1, 0, 0, si, 0, co, 0, 0, 0, 0, 1};
    if (R) {
        double E[16];
        embed3(R, E);
        matmul4(E, B, M);
    } else {
        memcpy(M, B, sizeof B);
    }
}

static double dot3(const double a[3], const double b[3]) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }

static void cross3(const double a[3], const double b[3], double c[3])
{
    c[0] = a[1] * b[2] - a[2] * b[1];
    c[1] = a[2] * b[0] - a[0] * b[2];
    c[2] = a[0] * b[1] - a[1] * b[0];
}

static void unit3(double a[3])
{
    double l = sqrt(dot3(a, a));
    for (int k = 0; k < 3; k++)
        a[k] /= l;
}

/*
 * METHOD: a boost along x with rapidity t takes the poles (0,0,-+1) to (tanh t, 0, -+1/cosh t),
 * whose angle has cosine (sinh^2 t - 1) / (sinh^2 t + 1); choose sinh^2 t = (1 + c) / (1 - c),
 * c = south . north, then rotate the frame (a + b, a - b, x) of the boosted pair onto the frame
 * of the target pair (both pairs have the same angle). Antipodal targets need no boost.
 */
rg2_status rg2_mobius_poles_matrix(const double south[3], const double north[3], double M[16],
                                   rg2_error *err)
{
    const double *pts[2] = {south, north};
    for (int e = 0; e < 2; e++) {
        for (int k = 0; k < 3; k++)
            if (!rg2__finite(pts[e][k]))
                return rg2__fail(err, RG2_ENONFINITE, "moebius: %s pole component %d is not finite",
                                 e ? "north" : "south", k);
        double l = sqrt(dot3(pts[e], pts[e]));
        if (!(fabs(l - 1.0) <= 1e-9))
            return rg2__fail(err, RG2_EDOMAIN,
                             "moebius: %s pole (%g, %g, %g) is not on the unit sphere (|p| = %s)",
                             e ? "north" : "south", pts[e][0], pts[e][1], pts[e][2], rg2__num(l).s);
    }
    double d[3] = {north[0] - south[0], north[1] - south[1], north[2] - south[2]};
    if (!(sqrt(dot3(d, d)) > 1e-9))
        return rg2__fail(err, RG2_EDOMAIN, "moebius: the south and north poles coincide at (%g, %g, %g)",
                         south[0], south[1], south[2]);
    double n[3], s[3];
    memcpy(n, north, sizeof n);
    memcpy(s, south, sizeof s);
    unit3(n);
    unit3(s);
    /* poles less than 90 degrees apart: 1 - c = |n - s|^2 / 2 without cancellation (poles 1e-8
     * apart gave c = 1 exactly and an infinite boost, reported as "matrix entry 0 is not finite";
     * 1e-6 apart, 1 - c kept 4 digits); poles nearly opposite: 1 + c = |n + s|^2 / 2 likewise
     * (poles 1e-7 to 2e-6 rad from opposite: 1 + c kept 4 to 6 digits, both images 1e-11 to 4e-11 off) */
    double c = fmin(fmax(dot3(n, s), -1.0), 1.0);
    double dn[3] = {n[0] - s[0], n[1] - s[1], n[2] - s[2]}, omc = c > 0.0 ? 0.5 * dot3(dn, dn) : 1.0 - c;
    double ps[3] = {n[0] + s[0], n[1] + s[1], n[2] + s[2]}, opc = c > 0.0 ? 2.0 - omc : 0.5 * dot3(ps, ps);
    double sh = sqrt(opc / omc), ch = sqrt(1.0 + sh * sh);
    double B[16] = {ch, 0, 0, sh, 0, 1, 0, 0, 0, 0, 1, 0, sh, 0, 0, ch};
    /* target frame f1 ~ n + s, f2 ~ n - s, f3 = f1 x f2; source frame (1,0,0), (0,0,1), (0,-1,0).
     * Both from the normalized poles: the axis from the poles as given (up to 1e-9 off the
     * sphere) put a pole's image 6.7e-11 from its normalized point with one pole 4e-10 off,
     * 1.0e-10 with both */
    double f1[3], f2[3] = {dn[0], dn[1], dn[2]}, f3[3];
    unit3(f2);
    /* f1 along n + s whenever the boost moves the poles by more than rounding (by |n + s| / 2):
     * its direction is good to 1e-16 / |n + s|, so the images stay within rounding; another
     * perpendicular direction put them up to |n + s| / sqrt 2 off (6.4e-7 for poles 9e-7 rad from
     * opposite, when this limit was 1e-6) */
    if (sqrt(dot3(ps, ps)) > 1e-15) {
        memcpy(f1, ps, sizeof f1);
    } else { /* antipodal: any direction perpendicular to the pole axis */
        double ax[3] = {1, 0, 0};
        if (fabs(f2[0]) > 0.9)
            ax[0] = 0, ax[1] = 1;
        double t = dot3(ax, f2);
        for (int k = 0; k < 3; k++)
            f1[k] = ax[k] - t * f2[k];
    }
    /* make the frame exactly orthogonal, correcting the less accurate of the two: n - s for poles
     * less than 90 degrees apart (its component along n + s cancels: for poles 1e-8 apart it
     * rounded to 0, and f1 made perpendicular to that f2 put both images 5e-9 off), else n + s */
    if (c > 0.0) {
        unit3(f1);
        double t = dot3(f1, f2);
        for (int k = 0; k < 3; k++)
            f2[k] -= t * f1[k];
        unit3(f2);
    } else {
        double t = dot3(f1, f2);
        for (int k = 0; k < 3; k++)
            f1[k] -= t * f2[k];
        unit3(f1);
    }
    cross3(f1, f2, f3);
    /* R = F E^T with E = [e1 e2 e3] = [(1,0,0) (0,0,1) (0,-1,0)] */
    double R[9];
    for (int r = 0; r < 3; r++) {
        R[3 * r + 0] = f1[r];
        R[3 * r + 1] = -f3[r];
        R[3 * r + 2] = f2[r];
    }
    double E[16];
    embed3(R, E);
    matmul4(E, B, M);
    rg2__ok(err);
    return RG2_OK;
}

rg2_status rg2_mesh_mobius(rg2_mesh *m, const double center[3], double radius, const double M[16],
                           rg2_error *err)
{
    if (!m || !m->p)
        return rg2__fail(err, RG2_EINVAL, "moebius: empty mesh");
    if (!rg2__finite(radius))
        return rg2__fail(err, RG2_ENONFINITE, "moebius: sphere radius is not finite");
    if (!(radius > 0.0))
        return rg2__fail(err, RG2_EDOMAIN, "moebius: sphere radius %g, must be > 0", radius);
    for (int k = 0; k < 3; k++)
        if (!rg2__finite(center[k]))
            return rg2__fail(err, RG2_ENONFINITE, "moebius: center component %d is not finite", k);
    for (int k = 0; k < 16; k++)
        if (!rg2__finite(M[k]))
            return rg2__fail(err, RG2_ENONFINITE, "moebius: matrix entry %d is not finite", k);
    double T[16] = {radius, 0, 0, center[0], 0, radius, 0, center[1], 0, 0, radius, center[2], 0, 0, 0, 1};
    double Ti[16] = {1 / radius, 0, 0, -center[0] / radius, 0, 1 / radius, 0, -center[1] / radius,
                     0, 0, 1 / radius, -center[2] / radius, 0, 0, 0, 1};
    double A[16];
    matmul4(M, Ti, A);
    matmul4(T, A, A);
    size_t np = (size_t)m->nu * (size_t)m->nv;
    double *q = rg2__calloc(np * 4, sizeof(double));
    if (!q)
        return rg2__fail(err, RG2_ENOMEM, "moebius: out of memory");
    for (size_t k = 0; k < np; k++) {
        const double *p = m->p + 4 * k;
        for (int r = 0; r < 4; r++)
            q[4 * k + r] = A[4 * r] * p[0] + A[4 * r + 1] * p[1] + A[4 * r + 2] * p[2] + A[4 * r + 3] * p[3];
        if (!(q[4 * k + 3] > 0.0)) {
            int i = (int)(k / (size_t)m->nv), j = (int)(k % (size_t)m->nv);
            double w = q[4 * k + 3];
            free(q);
            return rg2__fail(err, RG2_EWEIGHT,
                             "moebius: control point [%d][%d] gets weight %g; the map sends it through "
                             "infinity (use a smaller pole displacement)",
                             i, j, w);
        }
    }
    memcpy(m->p, q, np * 4 * sizeof(double));
    free(q);
    rg2__ok(err);
    return RG2_OK;
}

/*
 * METHOD: the Moebius matrix M acts on the reference unit sphere; the shape's placement X
 * (its matrix times diag(radius) or diag(a, b, c)) maps that sphere onto the shape, so the
 * mesh gets A = X M X^-1. Poles given in world coordinates are first mapped back to the unit
 * sphere by X^-1. Messages start with what; refkey names the reference argument ("sphere" in a
 * design, "ref" in C), poleskey prefixes "south" / "north" ("poles." in a design); label is the
 * shape's name in a design, NULL in C.
 */
rg2_status rg2__mobius_world(const rg2_shape *s, const char *label, const double *b, const double *south,
                             const double *north, double A[16], const char *what, const char *refkey,
                             const char *poleskey, rg2_error *err)
{
    double X[16], Xi[16], M[16];
    rg2_xform_identity(X);
    if (s) {
        double S[16];
        if (s->kind == RG2_SHAPE_SPHERE)
            rg2_xform_scale(S, s->param[0], s->param[0], s->param[0]);
        else if (s->kind == RG2_SHAPE_ELLIPSOID)
            rg2_xform_scale(S, s->param[0], s->param[1], s->param[2]);
        else if (label)
            return rg2__fail(err, RG2_EINVAL,
                             "%s.%s: '%s' is a %s; the reference shape must be a sphere or an ellipsoid", what,
                             refkey, label, rg2_shape_name(s->kind));
        else
            return rg2__fail(err, RG2_EINVAL,
                             "%s.%s: the reference shape is a %s; it must be a sphere or an ellipsoid", what,
                             refkey, rg2_shape_name(s->kind));
        rg2_xform_mul(s->xform, S, X);
    }
    rg2_status st = rg2_xform_invert(X, Xi, err);
    if (st) {
        rg2_error e = *err;
        return rg2__fail(err, st, "%s.%s: %s", what, refkey, e.msg);
    }
    if (b) {
        rg2_mobius_matrix(*b, NULL, M);
    } else {
        const double *poles[2] = {south, north};
        double loc[2][3];
        char ref[200];
        if (s && label)
            snprintf(ref, sizeof ref, "%s '%s'", rg2_shape_name(s->kind), label);
        else if (s)
            snprintf(ref, sizeof ref, "%s", rg2_shape_name(s->kind));
        else
            snprintf(ref, sizeof ref, "unit sphere at the origin");
        for (int e = 0; e < 2; e++) {
            double h[4];
            for (int r = 0; r < 4; r++)
                h[r] = Xi[4 * r] * poles[e][0] + Xi[4 * r + 1] * poles[e][1] + Xi[4 * r + 2] * poles[e][2] + Xi[4 * r + 3];
            for (int q = 0; q < 3; q++)
                loc[e][q] = h[q] / h[3];
            /* a pole off the reference sphere: name it as given, in world coordinates, with the
             * nearest point of the sphere (rg2_mobius_poles_matrix's own message would speak of
             * the unit sphere the placement maps it to) */
            double l = sqrt(loc[e][0] * loc[e][0] + loc[e][1] * loc[e][1] + loc[e][2] * loc[e][2]);
            if (rg2__finite(l) && l > 0 && !(fabs(l - 1.0) <= 1e-9)) {
                double nq[4], u[4] = {loc[e][0] / l, loc[e][1] / l, loc[e][2] / l, 1.0};
                for (int r = 0; r < 4; r++)
                    nq[r] = X[4 * r] * u[0] + X[4 * r + 1] * u[1] + X[4 * r + 2] * u[2] + X[4 * r + 3] * u[3];
                return rg2__fail(err, RG2_EDOMAIN,
                                 "%s.%s%s: (%.9g, %.9g, %.9g) is not on the reference %s (%.9g of the way "
                                 "from its centre to its surface; it must lie on it to 1e-9): the nearest point "
                                 "on it is (%s, %s, %s)",
                                 what, poleskey, e ? "north" : "south", poles[e][0], poles[e][1], poles[e][2], ref,
                                 l, rg2__num(nq[0] / nq[3]).s, rg2__num(nq[1] / nq[3]).s, rg2__num(nq[2] / nq[3]).s);
            }
        }
        /* coincident poles: name them as given, in world coordinates (rg2_mobius_poles_matrix
         * would name the point of the unit sphere the placement maps them to) */
        double dl[3] = {loc[1][0] - loc[0][0], loc[1][1] - loc[0][1], loc[1][2] - loc[0][2]};
        if (!(sqrt(dl[0] * dl[0] + dl[1] * dl[1] + dl[2] * dl[2]) > 1e-9))
            return rg2__fail(err, RG2_EDOMAIN,
                             "%s.poles: the south and north poles coincide at (%.9g, %.9g, %.9g) on the reference %s: "
                             "give two different points of it",
                             what, south[0], south[1], south[2], ref);
        if ((st = rg2_mobius_poles_matrix(loc[0], loc[1], M, err))) {
            rg2_error e = *err;
            return rg2__fail(err, st, "%s.poles: %s (poles taken relative to the reference sphere)", what,
                             rg2__after(e.msg, "moebius: "));
        }
    }
    rg2_xform_mul(M, Xi, A);
    rg2_xform_mul(X, A, A);
    return RG2_OK;
}

rg2_status rg2_mesh_mobius_shape(rg2_mesh *m, const rg2_shape *ref, const double *b, const double south[3],
                                 const double north[3], rg2_error *err)
{
    static const char what[] = "rg2_mesh_mobius_shape";
    rg2_error local; /* (rg2__mobius_world reads back the messages it prefixes) */
    if (!err)
        err = &local;
    if (!m || !m->p || m->nu < 1 || m->nv < 1)
        return rg2__fail(err, RG2_EINVAL, "%s: empty mesh", what);
    if (!b == !(south || north))
        return rg2__fail(err, RG2_EINVAL, "%s: give either b or the poles south and north, %s", what,
                         b ? "not both" : "not neither");
    if (!b && (!south || !north))
        return rg2__fail(err, RG2_EINVAL, "%s: the %s pole is NULL (give both poles)", what, south ? "north" : "south");
    if (b && !rg2__finite(*b))
        return rg2__fail(err, RG2_ENONFINITE, "%s.b is not a finite number", what);
    for (int e = 0; !b && e < 2; e++)
        for (int k = 0; k < 3; k++)
            if (!rg2__finite((e ? north : south)[k]))
                return rg2__fail(err, RG2_ENONFINITE, "%s.%s: coordinate %d is not finite", what,
                                 e ? "north" : "south", k);
    if (ref) { /* (a NaN here was named as an entry of the product placement x scale) */
        for (int k = 0; k < 16; k++)
            if (!rg2__finite(ref->xform[k]))
                return rg2__fail(err, RG2_ENONFINITE, "%s.ref: placement entry %d is not finite", what, k);
        for (int k = 0; k < 3; k++)
            if (!rg2__finite(ref->param[k]))
                return rg2__fail(err, RG2_ENONFINITE, "%s.ref: parameter %d is not finite", what, k);
    }
    double A[16];
    rg2_status st = rg2__mobius_world(ref, NULL, b, south, north, A, what, "ref", "", err);
    if (st)
        return st;
    size_t np = (size_t)m->nu * (size_t)m->nv;
    double *q = rg2__calloc(np * 4, sizeof(double));
    if (!q)
        return rg2__fail(err, RG2_ENOMEM, "%s: out of memory", what);
    memcpy(q, m->p, np * 4 * sizeof(double));
    rg2_mesh t = *m; /* (the design's rg2_mesh_transform on a copy: the same bits, m untouched until all pass) */
    t.p = q;
    rg2_mesh_transform(&t, A);
    for (size_t k = 0; k < np; k++)
        if (!(q[4 * k + 3] > 0.0)) {
            double w = q[4 * k + 3];
            free(q);
            return rg2__fail(err, RG2_EWEIGHT,
                             "%s.%s: the Moebius map gives control point [%d, %d] the weight %g, sending it "
                             "through infinity (move the poles less far, or refine the u partition)",
                             what, b ? "b" : "poles", (int)(k / (size_t)m->nv), (int)(k % (size_t)m->nv), w);
        }
    memcpy(m->p, q, np * 4 * sizeof(double));
    free(q);
    rg2__ok(err);
    return RG2_OK;
}
