/* eval.c -- exact evaluation of rational bi-3 patches: position, first and second partial
 * derivatives by the quotient rule on Bernstein polynomials, unit normal, curvatures. */
#include "internal.h"

#include <string.h>

/* Homogeneous values up to `order` (rows 0; 0-2; 0-5 of out) of a rational Bezier patch of
 * degree (du, dv) whose control point (r, s) coordinate k is h[r * rs + s * ss + k]; v-sums
 * first. Serves both patch kinds (xpatch.c). */
static inline __attribute__((always_inline)) void eval_hom(const double *h, int du, int dv, size_t rs, size_t ss,
                                                           double u, double v, int order, double out[6][4])
{
    double Bu[RG2_MAX_DEGREE + 1], Du[RG2_MAX_DEGREE + 1], DDu[RG2_MAX_DEGREE + 1];
    double Bv[RG2_MAX_DEGREE + 1], Dv[RG2_MAX_DEGREE + 1], DDv[RG2_MAX_DEGREE + 1];
    if (du == 3) /* (the bi-3 call below has constant degrees: inlined, the loops unrolled) */
        rg2__bern3(u, Bu, Du, DDu);
    else
        rg2__bern(du, u, Bu, Du, DDu);
    if (dv == 3)
        rg2__bern3(v, Bv, Dv, DDv);
    else
        rg2__bern(dv, v, Bv, Dv, DDv);
    int rows = order < 1 ? 1 : order < 2 ? 3 : 6;
    memset(out, 0, sizeof(double[4]) * (size_t)rows);
    for (int r = 0; r <= du; r++) {
        /* column sums over s first: value, d/dv, d2/dv2 */
        double c0[4] = {0}, c1[4] = {0}, c2[4] = {0};
        for (int s = 0; s <= dv; s++)
            for (int k = 0; k < 4; k++) {
                double x = h[(size_t)r * rs + (size_t)s * ss + (size_t)k];
                c0[k] += x * Bv[s];
                c1[k] += x * Dv[s];
                c2[k] += x * DDv[s];
            }
        rg2__hom_row(out, rows, Bu[r], Du[r], DDu[r], c0, c1, c2);
    }
}

void rg2__eval_hom(const double *h, int du, int dv, size_t rs, size_t ss, double u, double v, int order,
                   double out[6][4])
{
    eval_hom(h, du, dv, rs, ss, u, v, order, out);
}

/* The same code with the bi-3 degrees and strides as constants. */
static void eval_h(const rg2_patch *P, double u, double v, int order, double out[6][4])
{
    eval_hom(&P->h[0][0][0], 3, 3, 16, 4, u, v, order, out);
}

void rg2_patch_eval_h(const rg2_patch *P, double u, double v, double out[6][4])
{
    eval_h(P, u, v, 2, out);
}

static double dot3(const double a[3], const double b[3])
{
    return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}

void rg2_patch_eval(const rg2_patch *P, double u, double v, int order, rg2_eval *e)
{
    double H[6][4];
    eval_h(P, u, v, order, H);
    rg2__eval_from_h(H, order, e);
    if (order >= 1 && !(e->flags & RG2_EVAL_NORMAL_UNDEFINED) && rg2__pole_suspect(u, v, e->su, e->sv) &&
        rg2__patch_pole_at(P, u, v))
        rg2__eval_undefine(e);
}

/* Position, derivatives, normal and curvatures from the homogeneous values (quotient rule). */
void rg2__eval_from_h(double H[6][4], int order, rg2_eval *e)
{
    memset(e, 0, sizeof *e);
    double W = H[0][3];
    if (!(W > 0.0))
        e->flags |= RG2_EVAL_WEIGHT_NONPOSITIVE;
    double iW = 1.0 / W;
    for (int k = 0; k < 3; k++)
        e->p[k] = H[0][k] * iW;
    if (order < 1)
        return;
    for (int k = 0; k < 3; k++) {
        e->su[k] = (H[1][k] - H[1][3] * e->p[k]) * iW;
        e->sv[k] = (H[2][k] - H[2][3] * e->p[k]) * iW;
    }
    /* The normal's test, direction and (below) K and H from copies of the derivatives scaled by
     * one power of two, so that the squares and products of squares stay in the double range
     * for any surface size (rg2__scale_pair: exact, and the identity in the usual range). A
     * common factor t on all first derivatives and t^2 on the second ones is a
     * reparameterisation (u, v) -> (u / t, v / t): n, K and H do not change. */
    double su[3], sv[3];
    memcpy(su, e->su, sizeof su);
    memcpy(sv, e->sv, sizeof sv);
    double t = rg2__scale_pair(su, sv);
    double ru = 0.0, rv = 0.0; /* the derivatives' rounding levels (rg2__normal_test) */
    for (int k = 0; k < 3; k++) {
        ru += fabs(H[1][k]) + fabs(H[1][3] * e->p[k]);
        rv += fabs(H[2][k]) + fabs(H[2][3] * e->p[k]);
    }
    double c[3], len;
    int defined = rg2__normal_test(su, sv, ru * fabs(iW) * t, rv * fabs(iW) * t, c, &len);
    if (!defined) {
        e->flags |= RG2_EVAL_NORMAL_UNDEFINED | RG2_EVAL_CURVATURE_UNDEFINED;
    } else {
        for (int k = 0; k < 3; k++)
            e->n[k] = c[k] / len;
    }
    if (order < 2)
        return;
    for (int k = 0; k < 3; k++) {
        e->suu[k] = (H[3][k] - 2.0 * H[1][3] * e->su[k] - H[3][3] * e->p[k]) * iW;
        e->suv[k] = (H[4][k] - H[1][3] * e->sv[k] - H[2][3] * e->su[k] - H[4][3] * e->p[k]) * iW;
        e->svv[k] = (H[5][k] - 2.0 * H[2][3] * e->sv[k] - H[5][3] * e->p[k]) * iW;
    }
    if (e->flags & RG2_EVAL_NORMAL_UNDEFINED)
        return;
    double suu[3], suv[3], svv[3];
    for (int k = 0; k < 3; k++) { /* (t twice: t^2 alone may overflow) */
        suu[k] = e->suu[k] * t * t;
        suv[k] = e->suv[k] * t * t;
        svv[k] = e->svv[k] * t * t;
    }
    double E = dot3(su, su), F = dot3(su, sv), G = dot3(sv, sv);
    double L = dot3(suu, e->n), M = dot3(suv, e->n), N = dot3(svv, e->n);
    double det = E * G - F * F;
    e->K = (L * N - M * M) / det;
    e->H = (E * N - 2.0 * F * M + G * L) / (2.0 * det);
    double disc = e->H * e->H - e->K;
    double sq = disc > 0.0 ? sqrt(disc) : 0.0;
    e->k1 = e->H + sq;
    e->k2 = e->H - sq;
}

double rg2_eval_normal_curvature(const rg2_eval *e, double a, double c)
{
    double t[3], d2[3];
    for (int k = 0; k < 3; k++) {
        t[k] = a * e->su[k] + c * e->sv[k];
        d2[k] = a * a * e->suu[k] + 2.0 * a * c * e->suv[k] + c * c * e->svv[k];
    }
    double tt = dot3(t, t);
    if (tt == 0.0)
        return 0.0;
    return dot3(d2, e->n) / tt;
}
