/* cap.c -- bi-3 polar caps (paper section 5.1, eq. 14-15, MATH.md section 7): least-squares fit
 * of the 16 coefficients of the cap map to the body's boundary 2-jet, trisection of the cap
 * interval, and C2 rows in v joining the pole 2-jet of the cap map to the body's 2-jet. */
#include "internal.h"

#include <limits.h>
#include <stdlib.h>
#include <string.h>

void rg2_cap_opts_default(rg2_cap_opts *o)
{
    memset(o, 0, sizeof *o);
    o->ends = RG2_CAP_SOUTH | RG2_CAP_NORTH;
    o->jet_weight[0] = o->jet_weight[1] = 1.0;
    o->jet_weight[2] = 0.25; /* docs/poles.md: a dome, not a bullet, on a cylinder */
    o->samples = 8;
}

/* The body's u-circle: per patch column, affine Bezier coefficients of (1, cos u, sin u) and
 * the column's middle weight, from the construction with the body's own u-scalars. */
typedef struct {
    rg2_curve c; /* dim 3, one segment per patch column */
} ucircle;

static const char *end_name(int e) { return e ? "north" : "south"; }

/*
 * METHOD: a circle partition has w_i = (1 + 2 cos beta_i) / 3 (MATH.md section 2), so the arc
 * angles are recovered from the leg weights, checked against b_i and g_i of the scalars and
 * against the 2 pi sum; the circle coefficients (C_i, S_i) with junction 0 at angle 0 then
 * give, under the body's scalars, the exact rational cubic arcs of (cos u, sin u).
 */
static rg2_status ucircle_make(const rg2_scalars *su, ucircle *uc, rg2_error *err)
{
    memset(uc, 0, sizeof *uc);
    int n = su->n;
    double *alpha = rg2__calloc((size_t)n, sizeof(double));
    double *pts = rg2__calloc((size_t)n * 3, sizeof(double));
    double *cs = rg2__calloc((size_t)n * 2, sizeof(double));
    rg2_status st = RG2_OK;
    if (!alpha || !pts || !cs) {
        st = rg2__fail(err, RG2_ENOMEM, "cap: out of memory");
        goto done;
    }
    double sum = 0.0;
    for (int i = 0; i < n; i++) {
        double w = su->w[i], cb = (3.0 * w - 1.0) / 2.0;
        if (!(cb > -1.0 && cb < 1.0)) {
            st = rg2__fail(err, RG2_EINCOMPATIBLE,
                           "cap: body u leg %d has weight %s; a circle arc needs 1/3 < w < 1 "
                           "(the body's u-direction must be a circle partition)",
                           i, rg2__num(w).s);
            goto done;
        }
        alpha[i] = 2.0 * acos(cb);
        sum += alpha[i];
    }
    if (!(fabs(sum - 2.0 * M_PI) <= 1e-8 * 2.0 * M_PI)) {
        st = rg2__fail(err, RG2_EINCOMPATIBLE,
                       "cap: the body's u arcs (from the leg weights) sum to %s rad, not 2 pi: "
                       "the u-direction is not a full circle",
                       rg2__num(sum).s);
        goto done;
    }
    for (int i = 0; i < n; i++)
        alpha[i] *= 2.0 * M_PI / sum;
    for (int i = 0; i < n; i++) {
        double bi = 0.5 * alpha[i], bm = 0.5 * alpha[(i + n - 1) % n];
        double b = sin(bi) / sin(bm), g = 2.0 * b * sin(bi) * (tan(0.5 * bi) + tan(0.5 * bm));
        if (!(fabs(b - su->b[i]) <= 1e-8 * fmax(1.0, b) && fabs(g - su->g[i]) <= 1e-8 * fmax(1.0, fabs(g)))) {
            st = rg2__fail(err, RG2_EINCOMPATIBLE,
                           "cap: body u junction %d has b = %s, g = %s but its arcs need b = %s, "
                           "g = %s: the u-direction is not a circle partition",
                           i, rg2__num(su->b[i]).s, rg2__num(su->g[i]).s, rg2__num(b).s, rg2__num(g).s);
            goto done;
        }
    }
    if ((st = rg2_circle_coeffs(alpha, n, 1, 0.0, cs, err)))
        goto done;
    for (int i = 0; i < n; i++) {
        pts[3 * i] = 1.0;
        pts[3 * i + 1] = cs[2 * i];
        pts[3 * i + 2] = cs[2 * i + 1];
    }
    st = rg2_curve_build(3, pts, su, &uc->c, err);
done:
    free(alpha);
    free(pts);
    free(cs);
    return st;
}

/* Homogeneous u-coefficient r of (1, cos, sin) on column i: omega_r * affine coefficient. */
static void ucircle_h(const ucircle *uc, int i, int r, double h[3])
{
    double om = (r == 0 || r == 3) ? 1.0 : uc->c.w[i];
    const double *b = uc->c.bez + ((size_t)i * 4 + (size_t)r) * 3;
    for (int k = 0; k < 3; k++)
        h[k] = om * b[k];
}

/* One boundary sample: cos, sin of the circle, and the body's v-jet (value, d/ds, d2/ds2 in
 * the body ring's own parameter, pointing away from the cap) divided by the circle's
 * denominator. */
typedef struct {
    double c, s;
    double J[3][4];
} sample;

/* Fit data of one end. */
typedef struct {
    int n;
    sample *smp;
    double jw[3];
    double c[3], rho; /* the ring's frame (ring_frame), set by sample_end */
} fitdata;

/*
 * Cap chart (docs/poles.md): t in [0, 1] from the pole (t = 0) to the seam (t = 1),
 *   G(u, t) = g0 (1 - vc t)^2 + (g1 cos u + g2 sin u) t (1 - vc t) + g3 t^2,
 * i.e. F = v^2 q(r) of eq. (15) with v = vc t (reparameterized so the pole is at r = 0 when
 * vc = 0). Basis values and t-derivatives at t = 1 (seam) and t = 0 (pole).
 */
static void basis_at(double vc, double t, double phi0[3], double psi[3], double phi3[3])
{
    phi0[0] = (1.0 - vc * t) * (1.0 - vc * t);
    phi0[1] = -2.0 * vc * (1.0 - vc * t);
    phi0[2] = 2.0 * vc * vc;
    psi[0] = t * (1.0 - vc * t);
    psi[1] = 1.0 - 2.0 * vc * t;
    psi[2] = -2.0 * vc;
    phi3[0] = t * t;
    phi3[1] = 2.0 * t;
    phi3[2] = 2.0;
}

/* Least squares min |A x - b| by Householder QR; A is rows x (nc + 1) (row-major, b in its
 * last column), overwritten; nc <= 31. Returns the residual norm, or -1 if a column is
 * dependent (relative 1e-12).
 * Each reflection makes two passes over the rows: one for |v|^2 and the dot products of v
 * (column c) with all later columns, one for their updates and the next column's norm. Each
 * sum still runs over the rows in order, so the bits are those of one column at a time (a dot
 * product reads only column c and its own column, which the reflection's other updates leave
 * alone). Column at a time, the 24 576 x 27 matrix of a general cap on 256 columns (5.3 MB) was
 * read column-strided 2 (nc - c) + 2 times per reflection: 8x slower. */
static double lsq_qr(double *A, int rows, int nc, double *x)
{
    const size_t w = (size_t)nc + 1;
    double Rd[32], s[32], amax = 0.0, nrm = 0.0;
    for (int r = 0; r < rows; r++)
        nrm += A[(size_t)r * w] * A[(size_t)r * w];
    for (int c = 0; c < nc; c++) {
        nrm = sqrt(nrm);
        amax = fmax(amax, nrm);
        if (!(nrm > 1e-12 * amax))
            return -1.0;
        double alpha = A[(size_t)c * w + c] > 0 ? -nrm : nrm;
        A[(size_t)c * w + c] -= alpha;
        double vv = 0.0;
        for (int cc = c + 1; cc <= nc; cc++) /* cc == nc is the right-hand side */
            s[cc] = 0.0;
        for (int r = c; r < rows; r++) {
            const double *a = A + (size_t)r * w;
            vv += a[c] * a[c];
            for (int cc = c + 1; cc <= nc; cc++)
                s[cc] += a[c] * a[cc];
        }
        for (int cc = c + 1; cc <= nc; cc++)
            s[cc] *= 2.0 / vv;
        nrm = 0.0;
        for (int r = c; r < rows; r++) {
            double *a = A + (size_t)r * w;
            for (int cc = c + 1; cc <= nc; cc++)
                a[cc] -= s[cc] * a[c];
            if (r > c)
                nrm += a[c + 1] * a[c + 1];
        }
        Rd[c] = alpha;
    }
    for (int c = nc - 1; c >= 0; c--) {
        double t = A[(size_t)c * w + nc];
        for (int cc = c + 1; cc < nc; cc++)
            t -= A[(size_t)c * w + cc] * x[cc];
        x[c] = t / Rd[c];
    }
    double rr = 0.0;
    for (int r = nc; r < rows; r++)
        rr += A[(size_t)r * w + nc] * A[(size_t)r * w + nc];
    return sqrt(rr);
}

/* Centre (mean of the sample points) and RMS radius about it of a boundary ring: the frame the
 * fit works in, and the rho of the open-ring cap length (sample_end keeps them in fd). */
static void ring_frame(const fitdata *fd, double c[3], double *rho)
{
    c[0] = c[1] = c[2] = 0.0;
    for (int q = 0; q < fd->n; q++) {
        const double *J0 = fd->smp[q].J[0];
        for (int k = 0; k < 3; k++)
            c[k] += J0[k] / J0[3] / fd->n;
    }
    double r2 = 0.0;
    for (int q = 0; q < fd->n; q++) {
        const double *J0 = fd->smp[q].J[0];
        for (int k = 0; k < 3; k++) {
            double x = J0[k] / J0[3] - c[k];
            r2 += x * x / fd->n;
        }
    }
    *rho = sqrt(r2);
}

/*
 * METHOD: weighted linear least squares (Householder QR) for the 16 coefficients g[c][d]
 * (c: basis function, d: homogeneous coordinate) and the two derivatives lambda1, lambda2 of a
 * scalar factor lambda(s) = 1 + lambda1 s + lambda2 s^2 / 2 on the body's 4-tuples (4-tuples
 * are defined only up to a scalar function; lambda(0) = 1 keeps the boundary values). Row
 * (sample, order k, coordinate d): weight jw[k] / k! times
 *   sum_c basis_c^(k)(t = 1) g[c][d] - L^k (d^k/ds^k of lambda H - H) = L^k d^k H/ds^k,
 * with d/dt = L d/ds. The 1/k! makes each order count by the size of its Taylor term over the
 * cap (t-length 1). Sphere data are matched exactly with lambda = 1. The fit runs in the
 * ring's own frame, x' = (x - c) / rho (ring_frame: c its centre, rho its RMS radius), and g
 * is mapped back: the rows weigh x, y, z against W, so in world coordinates the cap of a body
 * moved or scaled was not the moved or scaled cap (a unit cylinder's dome 1.0625 deep at the
 * origin, 1.0103 with the ring at z = 10, 1.1318 scaled by 10). Returns the relative residual,
 * -1 when rank deficient, -2 when out of memory.
 */
static double fit_solve(const fitdata *fd, double L, double vc, int nb, double g[6][4], double lam[2])
{
    const int nc = 4 * nb + 2;
    const double *fc = fd->c, rho = fd->rho;
    int rows = 12 * fd->n;
    /* [A | B], 5.3 MB for a general cap on 256 columns: on huge pages, as 4 KiB pages its first
     * writes were most of the fit's time */
    double *A = rg2__alloc_big((size_t)rows, sizeof(double) * (size_t)(nc + 1), (size_t)2 << 20, 1);
    if (!A)
        return -2.0;
    double phi0[3], psi[3], phi3[3];
    basis_at(vc, 1.0, phi0, psi, phi3);
    const double fact[3] = {1.0, 1.0, 0.5};
    double bnorm = 0.0;
    for (int q = 0; q < fd->n; q++) {
        const sample *sm = fd->smp + q;
        double Lk = 1.0;
        for (int k = 0; k < 3; k++) {
            double W = fd->jw[k] * fact[k];
            for (int d = 0; d < 4; d++) {
                int row = 12 * q + 4 * k + d;
                double *a = A + (size_t)row * (size_t)(nc + 1);
                a[4 * 0 + d] = W * phi0[k];
                a[4 * 1 + d] = W * sm->c * psi[k];
                a[4 * 2 + d] = W * sm->s * psi[k];
                if (nb == 4) {
                    a[4 * 3 + d] = W * phi3[k];
                } else {
                    a[4 * 3 + d] = W * sm->c * sm->c * phi3[k];
                    a[4 * 4 + d] = W * sm->c * sm->s * phi3[k];
                    a[4 * 5 + d] = W * sm->s * sm->s * phi3[k];
                }
                double J[3];
                for (int o = 0; o < 3; o++)
                    J[o] = d < 3 ? (sm->J[o][d] - fc[d] * sm->J[o][3]) / rho : sm->J[o][3];
                /* (the unknowns are L lambda1 and L^2 lambda2, per unit of the cap's t: with lambda1,
                 * lambda2 themselves the columns held L and L^2, and a thin tube's cap (L = 8e-7 on a
                 * cylinder of radius 1e-7 over intervals of 0.25) was "rank-deficient") */
                if (k == 1)
                    a[4 * nb] = -W * J[0];
                if (k == 2) {
                    a[4 * nb] = -W * L * 2.0 * J[1];
                    a[4 * nb + 1] = -W * J[0];
                }
                a[nc] = W * Lk * J[k];
                bnorm += a[nc] * a[nc];
            }
            Lk *= L;
        }
    }
    double x[26];
    double res = lsq_qr(A, rows, nc, x);
    if (res >= 0.0) {
        for (int c = 0; c < nb; c++) {
            g[c][3] = x[4 * c + 3];
            for (int d = 0; d < 3; d++)
                g[c][d] = rho * x[4 * c + d] + fc[d] * x[4 * c + 3];
        }
        lam[0] = x[4 * nb] / L;
        lam[1] = x[4 * nb + 1] / L / L;
        res = bnorm > 0.0 ? res / sqrt(bnorm) : 0.0;
    }
    free(A);
    return res;
}

/* Patch row of the body next to end e and the parameter of its boundary. */
static int body_row(const rg2_surface *S, int e) { return e ? S->nv - 1 : 0; }

static rg2_status sample_end(const rg2_surface *S, const ucircle *uc, int e, int ns, fitdata *fd,
                             rg2_error *err)
{
    if ((double)S->nu * ns * 12.0 > INT_MAX) /* the fit's rows (12 per sample) are counted in int */
        return rg2__fail(err, RG2_ELIMIT,
                         "cap: %d columns x %d samples give %.0f fit rows, more than %d (use fewer samples)",
                         S->nu, ns, (double)S->nu * ns * 12.0, INT_MAX);
    fd->n = S->nu * ns;
    fd->smp = rg2__calloc((size_t)fd->n, sizeof(sample));
    if (!fd->smp)
        return rg2__fail(err, RG2_ENOMEM, "cap: out of memory for %d samples", fd->n);
    int j = body_row(S, e);
    double t = e ? 1.0 : 0.0, sg = e ? -1.0 : 1.0;
    for (int i = 0; i < S->nu; i++)
        for (int k = 0; k < ns; k++) {
            double u = (k + 0.5) / ns, B[4], H[6][4];
            rg2__bern3(u, B, NULL, NULL);
            double D = 0.0, C = 0.0, Sn = 0.0;
            for (int r = 0; r < 4; r++) {
                double h[3];
                ucircle_h(uc, i, r, h);
                D += B[r] * h[0];
                C += B[r] * h[1];
                Sn += B[r] * h[2];
            }
            rg2_patch_eval_h(rg2_surface_patch(S, i, j), u, t, H);
            sample *sm = fd->smp + i * ns + k;
            sm->c = C / D;
            sm->s = Sn / D;
            for (int d = 0; d < 4; d++) {
                sm->J[0][d] = H[0][d] / D;
                sm->J[1][d] = sg * H[2][d] / D;
                sm->J[2][d] = H[5][d] / D;
            }
        }
    ring_frame(fd, fd->c, &fd->rho);
    return RG2_OK;
}

/* Extent of the boundary ring relative to the body's size; both in 3D. */
static void ring_extent(const fitdata *fd, double *extent, double *center_w)
{
    const double *c = fd->c;
    double wmin = INFINITY;
    for (int q = 0; q < fd->n; q++)
        wmin = fmin(wmin, fd->smp[q].J[0][3]);
    double ext = 0.0;
    for (int q = 0; q < fd->n; q++) {
        const double *J = fd->smp[q].J[0];
        double d2 = 0.0;
        for (int k = 0; k < 3; k++)
            d2 += (J[k] / J[3] - c[k]) * (J[k] / J[3] - c[k]);
        ext = fmax(ext, sqrt(d2));
    }
    *extent = ext;
    *center_w = wmin;
}

/*
 * METHOD (automatic parameters, docs/poles.md): for a polar configuration the band's scalars
 * encode the cap. With b~0, b~1 the v scalars of the polar junction and the next one, oriented
 * from the pole (north: reciprocals of the last two), the polar knots give v_1 = 1 - b~0 and
 * cap length v_1 / (v_2 - v_1) = 1 / b~1. So L = 1 / b~1, vc = 1 - b~0; this makes the sphere
 * (b~0 = 1 - v_1) and the paraboloid/two-sheeted hyperboloid polar configurations (symmetric
 * knots, b~0 = 1) exact. Otherwise (an open ring) vc = 1/2, the seam at the equator of a
 * hemisphere-like cap, and L = 2 rho / sigma with rho the RMS radius of the boundary ring and
 * sigma the RMS speed |dX/ds| of the body across it: the length at which a hemisphere of
 * radius rho (speed 2 rho per unit of its chart) meets the body with matching speed; on a
 * circular cylinder the fitted cap is then tangent to a hemisphere.
 */
static rg2_status choose_params(const rg2_mesh *body, const fitdata *fd, int e, const rg2_cap_opts *o,
                                double *L, double *vc, int *polar, rg2_error *err)
{
    *polar = 0;
    if (o->length[e] > 0.0) {
        *L = o->length[e];
        *vc = o->vc[e];
        return RG2_OK;
    }
    int n = body->sv.n;
    if (rg2_mesh_row_collapsed(body, e ? n - 1 : 0)) {
        double b0 = e ? 1.0 / body->sv.b[n - 1] : body->sv.b[0];
        double b1 = e ? 1.0 / body->sv.b[n - 2] : body->sv.b[1];
        *polar = 1;
        *L = 1.0 / b1;
        *vc = 1.0 - b0;
        return RG2_OK;
    }
    *vc = 0.5;
    double rho = fd->rho, sigma = 0.0;
    for (int q = 0; q < fd->n; q++) {
        const double *J0 = fd->smp[q].J[0], *J1 = fd->smp[q].J[1];
        for (int k = 0; k < 3; k++) {
            double x = J0[k] / J0[3], dx = (J1[k] - J1[3] * x) / J0[3];
            sigma += dx * dx / fd->n;
        }
    }
    sigma = sqrt(sigma);
    if (!(sigma > 0.0) || !(rho > 0.0))
        return rg2__fail(err, RG2_EDOMAIN,
                         "cap: the body does not move away from its %s boundary ring (speed %g); "
                         "give the cap length in the options",
                         end_name(e), sigma);
    *L = 2.0 * rho / sigma;
    return RG2_OK;
}

/*
 * METHOD (trisection): per patch column i and u-Bernstein index r, the homogeneous v-curve of
 * the cap is a uniform C2 cubic spline of 3 pieces (6 de Boor points d0..d5). Its 2-jet at the
 * pole is that of G's column-r coefficient (fixes d0, d1, d2); its 2-jet at the seam is the
 * body's (fixes d3, d4, d5), taken from lambda H (lambda from the fit; lambda H and H have
 * the same 3D jets) and converted with the seam scalars b = 3 / L, g = 0 (a piece has length
 * L/3 in body-ring units). The end Bezier points are taken from the jets directly so the
 * pole and the seam row are exact. Every coefficient is the same linear combination for all
 * r and i, so the u-direction G2 structure of the body and of G carries over to the cap.
 * row_pieces does it for one scalar coefficient: G[k] the pole jet (t-derivatives), h0, h1, h2
 * the body's Bezier v-points at the seam (h0 on it), oriented away from the cap; bz[k][s] is
 * piece k (k = 0 at the pole) oriented from the pole.
 */
static void row_pieces(const double G[3], double h0, double h1, double h2, double L, const double lam[2],
                       double bz[3][4])
{
    double A[3], C[4];
    /* pole jet in the piece parameter (t = sigma / 3) */
    double P0 = G[0], P1 = G[1] / 3.0, P2 = G[2] / 9.0;
    A[0] = P0;
    A[1] = P0 + P1 / 3.0;
    A[2] = 2.0 * A[1] - A[0] + P2 / 6.0;
    /* body jet at the seam, oriented away from the cap, in the piece parameter */
    double sc = L / 3.0;
    double J1 = 3.0 * (h1 - h0), J2 = 6.0 * (h2 - 2.0 * h1 + h0);
    /* jets of lambda H (lambda(0) = 1): the same 3D jets, scaled like the fit */
    double Q1 = sc * (J1 + lam[0] * h0), Q2 = sc * sc * (J2 + 2.0 * lam[0] * J1 + lam[1] * h0);
    /* the piece parameter runs from the pole into the body: C'(1) = Q1, C''(1) = Q2 */
    C[3] = h0;
    C[2] = h0 - Q1 / 3.0;
    C[1] = 2.0 * C[2] - C[3] + Q2 / 6.0;
    double db[6];
    db[1] = 2.0 * A[1] - A[2];
    db[2] = 2.0 * A[2] - A[1];
    db[0] = 6.0 * A[0] - 4.0 * db[1] - db[2];
    db[3] = 2.0 * C[1] - C[2];
    db[4] = 2.0 * C[2] - C[1];
    db[5] = 6.0 * C[3] - db[3] - 4.0 * db[4];
    for (int k = 0; k < 3; k++) {
        double *x = db + k;
        bz[k][0] = (x[0] + 4.0 * x[1] + x[2]) / 6.0;
        bz[k][1] = (2.0 * x[1] + x[2]) / 3.0;
        bz[k][2] = (x[1] + 2.0 * x[2]) / 3.0;
        bz[k][3] = (x[1] + 4.0 * x[2] + x[3]) / 6.0;
    }
    bz[0][0] = A[0], bz[0][1] = A[1], bz[0][2] = A[2];
    bz[2][1] = C[1], bz[2][2] = C[2], bz[2][3] = C[3];
}

/* Body Bezier v-points of u-index r and coordinate d at the seam of end e: h[0] on the seam,
 * h[1], h[2] going into the body. */
static void seam_rows(const rg2_patch *Bp, int e, int r, int d, double h[3])
{
    for (int q = 0; q < 3; q++)
        h[q] = e ? Bp->h[r][3 - q][d] : Bp->h[r][q][d];
}

static void cap_column(const rg2_surface *S, const ucircle *uc, int e, int i, double L, double vc,
                       double g[6][4], const double lam[2], rg2_patch P[3])
{
    double phi0[3], psi[3], phi3[3];
    basis_at(vc, 0.0, phi0, psi, phi3);
    const rg2_patch *Bp = rg2_surface_patch(S, i, body_row(S, e));
    for (int r = 0; r < 4; r++) {
        double uh[3];
        ucircle_h(uc, i, r, uh);
        for (int d = 0; d < 4; d++) {
            double G[3], h[3], bz[3][4];
            for (int k = 0; k < 3; k++)
                G[k] = uh[0] * g[0][d] * phi0[k] + (uh[1] * g[1][d] + uh[2] * g[2][d]) * psi[k] +
                       uh[0] * g[3][d] * phi3[k];
            seam_rows(Bp, e, r, d, h);
            row_pieces(G, h[0], h[1], h[2], L, lam, bz);
            for (int k = 0; k < 3; k++)
                for (int s = 0; s < 4; s++)
                    P[k].h[r][s][d] = bz[k][s];
        }
    }
}

/* ---- the general-quadratic cap (degree 4 or 5 in u) ------------------------------------ */

/* fmax(a, b) for a not NaN, inline (glibc's fmax is a call; the loops over every body patch
 * make millions): b when it is greater, else a (also when b is NaN). */
static inline double max_of(double a, double b) { return isgreater(b, a) ? b : a; }

static double binom(int n, int k)
{
    double b = 1.0;
    for (int q = 1; q <= k; q++)
        b = b * (n - k + q) / q;
    return b;
}

/* Weights of the Bernstein product of degree 2 by degree nb, per pair of indices (computed
 * once per build: 16 products per body patch, each with up to 12 weights). */
typedef struct {
    double w[2][3][4]; /* [nb - 2][i][j] = binom(2, i) binom(nb, j) / binom(2 + nb, i + j) */
} bweights;

static void bweights_make(bweights *bw)
{
    memset(bw, 0, sizeof *bw);
    for (int nb = 2; nb <= 3; nb++)
        for (int i = 0; i <= 2; i++)
            for (int j = 0; j <= nb; j++)
                bw->w[nb - 2][i][j] = binom(2, i) * binom(nb, j) / binom(2 + nb, i + j);
}

/* Bernstein product: c (degree 2 + nb) = a (degree 2) * b (degree nb), nb = 2 or 3. */
static void bmul(const bweights *bw, const double a[3], const double *b, int nb, double *c)
{
    const double(*w)[4] = bw->w[nb - 2];
    for (int k = 0; k <= 2 + nb; k++)
        c[k] = 0.0;
    for (int i = 0; i <= 2; i++)
        for (int j = 0; j <= nb; j++)
            c[i + j] += w[i][j] * a[i] * b[j];
}

/* One degree elevation n -> n + 1 of Bernstein coefficients (in place, a has room). */
static void belevate(double *a, int n)
{
    double t[RG2_MAX_DEGREE + 2];
    for (int i = 0; i <= n + 1; i++) {
        double f = (double)i / (n + 1);
        t[i] = i == 0 ? a[0] : i > n ? a[n] : a[i] + f * (a[i - 1] - a[i]);
    }
    for (int i = 0; i <= n + 1; i++)
        a[i] = t[i];
}

/* Whether the cubic Bernstein coefficients c are a degree-raised quadratic (third difference
 * at rounding level against their size). */
static int cubic_is_quadratic(const double c[4])
{
    double m = max_of(max_of(fabs(c[0]), fabs(c[1])), max_of(fabs(c[2]), fabs(c[3])));
    return fabs(c[3] - 3.0 * c[2] + 3.0 * c[1] - c[0]) <= 1e-13 * m;
}

/* The quadratic (D, C, S) of the body's u-circle on column i (its cubic is a degree-raised
 * conic arc: weights (1, w, w, 1) with w = (1 + 2 cos beta) / 3). */
static void ucircle_quadratic(const ucircle *uc, int i, double q[3][3])
{
    double c[4][3];
    for (int r = 0; r < 4; r++)
        ucircle_h(uc, i, r, c[r]);
    for (int k = 0; k < 3; k++) {
        q[k][0] = c[0][k];
        q[k][1] = 0.5 * (3.0 * c[1][k] - c[0][k]);
        q[k][2] = c[3][k];
    }
}

/* One pass over the body's patches: the body's size, the largest |coordinate| of an affine
 * control point, and for a general cap (general != 0) the u-degree of the capped surface in *du:
 * D times the body is degree 4 when every body patch row is a degree-raised quadratic in u
 * (family-2 rows: sphere, cylinder, ...), else 5. In parallel over the columns: a largest value
 * and an "every" are the same in any order (NaN quotients are skipped, as fmax does). */
static void body_scan(const rg2_surface *S, int general, double *scale, int *du)
{
    double m0 = 0.0, m1 = 0.0, m2 = 0.0; /* per coordinate: three independent chains */
    int quad = general;
    /* reductions, not a critical section: clang's libomp makes an unnamed critical's lock a
     * global symbol (.gomp_critical_user_.var) that librg2.so would export */
#ifdef RG2_HAVE_OPENMP
#pragma omp parallel for schedule(static) reduction(max : m0, m1, m2) reduction(&& : quad) \
    if ((size_t)S->nu * (size_t)S->nv > 256)
#endif
    for (int i = 0; i < S->nu; i++)
        for (int j = 0; j < S->nv; j++) {
            const rg2_patch *P = rg2_surface_patch(S, i, j);
            for (int r = 0; r < 4; r++)
                for (int s = 0; s < 4; s++) {
                    const double *h = P->h[r][s];
                    m0 = max_of(m0, fabs(h[0] / h[3]));
                    m1 = max_of(m1, fabs(h[1] / h[3]));
                    m2 = max_of(m2, fabs(h[2] / h[3]));
                }
            for (int t = 0; general && quad && t < 4; t++)
                for (int d = 0; quad && d < 4; d++) {
                    double c[4];
                    for (int r = 0; r < 4; r++)
                        c[r] = P->h[r][t][d];
                    quad = cubic_is_quadratic(c);
                }
        }
    *scale = max_of(max_of(m0, m1), m2);
    *du = quad ? 4 : 5;
}

/* Body patch P of column i times D_i(u), the column's circle denominator (its quadratic
 * Bernstein coefficients D): the same rational surface of degree (du, 3), in the homogeneous
 * scaling of the general caps (so that every seam of the output, cap/body included, has one
 * homogeneous form and the surface is one B-spline). */
static void body_times_d(const rg2_patch *P, const double D[3], const bweights *bw, int du, rg2_xpatch *X)
{
    memset(X, 0, sizeof *X);
    X->du = du;
    X->dv = 3;
    for (int t = 0; t < 4; t++)
        for (int d = 0; d < 4; d++) {
            double c[4], out[RG2_MAX_DEGREE + 1];
            for (int r = 0; r < 4; r++)
                c[r] = P->h[r][t][d];
            if (du == 4) {
                double c2[3] = {c[0], 0.5 * (3.0 * c[1] - c[0]), c[3]};
                bmul(bw, D, c2, 2, out);
            } else {
                bmul(bw, D, c, 3, out);
            }
            for (int r = 0; r <= du; r++)
                X->h[r][t][d] = out[r];
        }
}

/*
 * METHOD (general quadratic, docs/poles.md): G = g0 phi0 + (g1 c + g2 s) psi + (g3 c^2 +
 * g4 c s + g5 s^2) phi3 has c^2 = C^2 / D^2 with (D, C, S) the quadratic conic arcs of the
 * u-circle, so its homogeneous form is D^2 G: degree 4 in u. The fit matched G to H / D, so
 * the body side of the C2 rows is D H (lambda H likewise): degree 4 when the body's seam rows
 * are quadratics in u (family-2 rings), else 5, and the pole side is elevated to match. Rows
 * in v are as in the bi-3 cap, per u-coefficient (row_pieces).
 */
static void cap_column_x(const rg2_surface *S, double q[3][3], const bweights *bw, int e, int i, int du, double L,
                         double vc, double g[6][4], const double lam[2], rg2_xpatch X[3])
{
    double phi0[3], psi[3], phi3[3];
    basis_at(vc, 0.0, phi0, psi, phi3);
    double DD[5], DC[5], DS[5], CC[5], CS[5], SS[5];
    bmul(bw, q[0], q[0], 2, DD);
    bmul(bw, q[0], q[1], 2, DC);
    bmul(bw, q[0], q[2], 2, DS);
    bmul(bw, q[1], q[1], 2, CC);
    bmul(bw, q[1], q[2], 2, CS);
    bmul(bw, q[2], q[2], 2, SS);
    const rg2_patch *Bp = rg2_surface_patch(S, i, body_row(S, e));
    for (int k = 0; k < 3; k++) {
        memset(&X[k], 0, sizeof X[k]);
        X[k].du = du;
        X[k].dv = 3;
    }
    for (int d = 0; d < 4; d++) {
        /* pole jet per order: Bernstein coefficients in u, degree 4 (then du) */
        double G[3][RG2_MAX_DEGREE + 2];
        for (int k = 0; k < 3; k++) {
            for (int r = 0; r <= 4; r++)
                G[k][r] = DD[r] * g[0][d] * phi0[k] + (DC[r] * g[1][d] + DS[r] * g[2][d]) * psi[k] +
                          (CC[r] * g[3][d] + CS[r] * g[4][d] + SS[r] * g[5][d]) * phi3[k];
            if (du == 5)
                belevate(G[k], 4);
        }
        /* body seam rows times D */
        double H[3][RG2_MAX_DEGREE + 2];
        for (int qq = 0; qq < 3; qq++) {
            double c[4], h[3];
            for (int r = 0; r < 4; r++) {
                seam_rows(Bp, e, r, d, h);
                c[r] = h[qq];
            }
            if (du == 4) {
                double c2[3] = {c[0], 0.5 * (3.0 * c[1] - c[0]), c[3]};
                bmul(bw, q[0], c2, 2, H[qq]);
            } else {
                bmul(bw, q[0], c, 3, H[qq]);
            }
        }
        for (int r = 0; r <= du; r++) {
            double Gr[3] = {G[0][r], G[1][r], G[2][r]}, bz[3][4];
            row_pieces(Gr, H[0][r], H[1][r], H[2][r], L, lam, bz);
            for (int k = 0; k < 3; k++)
                for (int s = 0; s < 4; s++)
                    X[k].h[r][s][d] = bz[k][s];
        }
    }
}

/* Convert the normalized-chart coefficients to eq. (14) (v = vc t): q0 = g3 / vc^2,
 * q1,2 = g1,2 / vc, q3 = g0 (q_k3 multiplies (1 - v)^2, the pole value). */
static void chart_to_q(double g[4][4], double vc, double q[4][4])
{
    memset(q, 0, sizeof(double[4][4]));
    if (!(vc > 0.0))
        return;
    for (int k = 0; k < 4; k++) {
        q[k][0] = g[3][k] / (vc * vc);
        q[k][1] = g[1][k] / vc;
        q[k][2] = g[2][k] / vc;
        q[k][3] = g[0][k];
    }
}

/* The body's surface S, built into an array with room for `rows` more patch rows per column:
 * the output's patch array, which the assembly rewrites in place, so that a capped surface
 * takes no second copy of its body (for 256 x 400 patches, 52 MB of fresh pages each build).
 * rg2_surface_rebuild reuses S's arrays as they are counted by the same segment counts. */
static rg2_status body_build(const rg2_mesh *body, int rows, rg2_surface *S, rg2_error *err)
{
    memset(S, 0, sizeof *S);
    rg2_status st = rg2_mesh_check(body, err); /* (first, as rg2_surface_build does) */
    if (st)
        return st;
    int nu = rg2_scalars_num_segments(&body->su), nv = rg2_scalars_num_segments(&body->sv);
    S->patch = rg2__alloc_big((size_t)nu * ((size_t)nv + (size_t)rows), sizeof(rg2_patch), (size_t)2 << 20, 0);
    S->bu = rg2__calloc((size_t)nu, sizeof(double));
    S->gu = rg2__calloc((size_t)nu, sizeof(double));
    S->bv = rg2__calloc((size_t)nv, sizeof(double));
    S->gv = rg2__calloc((size_t)nv, sizeof(double));
    if (!S->patch || !S->bu || !S->gu || !S->bv || !S->gv) {
        rg2_surface_free(S);
        return rg2__fail(err, RG2_ENOMEM, "cap: out of memory for %d x %d patches", nu, nv + rows);
    }
    S->nu = nu;
    S->nv = nv;
    return rg2_surface_rebuild(body, S, err);
}

rg2_status rg2_cap_build(const rg2_mesh *body, const rg2_cap_opts *opts, rg2_surface *out,
                         rg2_cap_info *info, rg2_error *err)
{
    memset(out, 0, sizeof *out);
    rg2_cap_opts o;
    if (opts)
        o = *opts;
    else
        rg2_cap_opts_default(&o);
    rg2_cap_info inf;
    memset(&inf, 0, sizeof inf);
    if (!body || !body->p)
        return rg2__fail(err, RG2_EINVAL, "cap: empty body mesh");
    if (!(o.ends & (RG2_CAP_SOUTH | RG2_CAP_NORTH)) || (o.ends & ~(RG2_CAP_SOUTH | RG2_CAP_NORTH)))
        return rg2__fail(err, RG2_EINVAL, "cap: ends = %d, must be a non-empty combination of south (1) and north (2)",
                         o.ends);
    if (o.quadratic != RG2_CAP_ROTATIONAL && o.quadratic != RG2_CAP_GENERAL)
        return rg2__fail(err, RG2_EINVAL, "cap: quadratic = %d, must be RG2_CAP_ROTATIONAL (0) or RG2_CAP_GENERAL (1)",
                         o.quadratic);
    if (o.samples < 2 || o.samples > 256)
        return rg2__fail(err, RG2_EDOMAIN, "cap: %d boundary samples per column, must be in 2..256", o.samples);
    for (int k = 0; k < 3; k++)
        if (!rg2__finite(o.jet_weight[k]) || !(o.jet_weight[k] > 0.0))
            return rg2__fail(err, RG2_EDOMAIN,
                             "cap: jet weight %d is %g, must be finite and > 0 (a zero weight leaves the "
                             "least-squares fit rank-deficient)",
                             k, o.jet_weight[k]);
    for (int e = 0; e < 2; e++)
        if (o.length[e] != 0.0 && (!rg2__finite(o.length[e]) || !(o.length[e] > 0.0) ||
                                   !(o.vc[e] >= 0.0 && o.vc[e] < 1.0)))
            return rg2__fail(err, RG2_EDOMAIN,
                             "cap: %s cap length %g and v_c %s: need length > 0 and 0 <= v_c < 1",
                             end_name(e), o.length[e], rg2__num(o.vc[e]).s);
    if (!body->su.closed)
        return rg2__fail(err, RG2_EINVAL,
                         "cap: the body's u-direction is open; a cap closes a closed ring (closed u)");
    if (body->nu < 3)
        return rg2__fail(err, RG2_EINVAL, "cap: the body's ring has %d control points, too small (at least 3)",
                         body->nu);
    if (body->sv.closed)
        return rg2__fail(err, RG2_EINVAL, "cap: the body's v-direction is closed; it has no end to cap");
    if (body->nv < 4)
        return rg2__fail(err, RG2_EINVAL,
                         "cap: the body has %d rows in v; at least 4 are needed for one ring of patches",
                         body->nv);
    /* the rows of the caps asked for (a cap fails or is built) */
    int rows_cap = (o.ends & RG2_CAP_SOUTH ? 3 : 0) + (o.ends & RG2_CAP_NORTH ? 3 : 0);
    rg2_surface S;
    rg2_status st = body_build(body, rows_cap, &S, err);
    if (st)
        return st;
    ucircle uc;
    fitdata fd[2];
    rg2_patch *caps = NULL; /* bi-3 caps: column i's cap patches, south rows then north rows */
    memset(fd, 0, sizeof fd);
    double L[2] = {0, 0}, vc[2] = {0, 0}, g[2][6][4], lam[2][2] = {{0, 0}, {0, 0}};
    int general = o.quadratic == RG2_CAP_GENERAL, nb = general ? 6 : 4;
    memset(g, 0, sizeof g);
    if ((st = ucircle_make(&body->su, &uc, err)))
        goto done;
    double scale;
    int du_general;
    body_scan(&S, general, &scale, &du_general);
    for (int e = 0; e < 2; e++) {
        if (!(o.ends & (1 << e)))
            continue;
        fd[e].jw[0] = o.jet_weight[0];
        fd[e].jw[1] = o.jet_weight[1];
        fd[e].jw[2] = o.jet_weight[2];
        if ((st = sample_end(&S, &uc, e, o.samples, &fd[e], err)))
            goto done;
        double ext, wmin;
        ring_extent(&fd[e], &ext, &wmin);
        if (!(wmin > 0.0)) {
            st = rg2__fail(err, RG2_EWEIGHT, "cap: the body's %s boundary ring has weight %g <= 0",
                           end_name(e), wmin);
            goto done;
        }
        if (!(ext > 1e-9 * fmax(scale, 1e-300))) {
            st = rg2__fail(err, RG2_EDOMAIN,
                           "cap: the body's %s boundary ring is collapsed (extent %.3g of body size %.3g): "
                           "the body already ends in a point; cap the band of a polar configuration "
                           "(knots v_1 > 0, v_m < 1) instead",
                           end_name(e), ext, scale);
            goto done;
        }
        int polar = 0;
        if ((st = choose_params(body, &fd[e], e, &o, &L[e], &vc[e], &polar, err)))
            goto done;
        if (!(L[e] > 0.0) || !rg2__finite(L[e]) || !(vc[e] < 1.0)) {
            st = rg2__fail(err, RG2_EDOMAIN,
                           "cap: %s end: cap length %g and v_c %g from the body's v scalars are unusable "
                           "(need length > 0, v_c < 1); give them in the options",
                           end_name(e), L[e], vc[e]);
            goto done;
        }
        double res = fit_solve(&fd[e], L[e], vc[e], nb, g[e], lam[e]);
        if (res < -1.5) {
            st = rg2__fail(err, RG2_ENOMEM, "cap: out of memory in the fit");
            goto done;
        }
        if (res < 0.0) { /* (the jet weights are > 0, checked above) */
            /* (a given length of 1e100 read as a degenerate ring: name the length when it was given) */
            if (o.length[e] > 0.0)
                st = rg2__fail(err, RG2_EDOMAIN,
                               "cap: the %s boundary ring does not determine the cap map at the given cap length "
                               "%g (rank-deficient least-squares fit: a length far from the ring's own scale, "
                               "about 2 rho / sigma, or a degenerate ring; omit the length for the automatic one)",
                               end_name(e), L[e]);
            else
                st = rg2__fail(err, RG2_EDOMAIN,
                               "cap: the %s boundary ring does not determine the cap map (rank-deficient "
                               "least-squares fit; is the ring degenerate?)",
                               end_name(e));
            goto done;
        }
        if (!(g[e][0][3] > 0.0)) {
            st = rg2__fail(err, RG2_EDOMAIN,
                           "cap: the fitted %s pole has weight %g <= 0 (the body's end does not close "
                           "like a cap)",
                           end_name(e), g[e][0][3]);
            goto done;
        }
        inf.capped[e] = 1;
        inf.polar[e] = polar;
        inf.length[e] = L[e];
        inf.vc[e] = vc[e];
        inf.residual[e] = res;
        for (int d = 0; d < 4; d++) {
            for (int k = 0; k < 3; k++)
                inf.g[e][k][d] = g[e][k][d];
            if (general) {
                inf.quad[e][d][0] = g[e][3][d];
                inf.quad[e][d][1] = g[e][4][d];
                inf.quad[e][d][2] = g[e][5][d];
                inf.g[e][3][d] = 0.5 * (g[e][3][d] + g[e][5][d]);
            } else {
                inf.quad[e][d][0] = inf.quad[e][d][2] = inf.g[e][3][d] = g[e][3][d];
            }
        }
        inf.du[e] = general ? du_general : 3;
        chart_to_q(inf.g[e], vc[e], inf.q[e]);
        for (int k = 0; k < 3; k++)
            inf.pole[e][k] = g[e][0][k] / g[e][0][3];
    }
    int rb = inf.capped[0] ? 3 : 0, ra = inf.capped[1] ? 3 : 0;
    inf.rows_before = rb;
    inf.rows_after = ra;
    /* assemble: cap rows, body rows, cap rows, in S's patch array (room for rb + ra more rows
     * per column, body_build) */
    int nv = S.nv + rb + ra, nc = rb + ra;
    out->bu = rg2__calloc((size_t)S.nu, sizeof(double));
    out->gu = rg2__calloc((size_t)S.nu, sizeof(double));
    out->bv = rg2__calloc((size_t)nv, sizeof(double));
    out->gv = rg2__calloc((size_t)nv, sizeof(double));
    if (general) /* written whole below, on huge pages (103 936 general patches: 120 MB) */
        out->xp = rg2__alloc_big((size_t)S.nu * (size_t)nv, sizeof(rg2_xpatch), (size_t)2 << 20, 0);
    else
        caps = rg2__calloc((size_t)S.nu * (size_t)nc, sizeof(rg2_patch));
    if (!out->bu || !out->gu || !out->bv || !out->gv || (general ? !out->xp : !caps)) {
        rg2_surface_free(out);
        st = rg2__fail(err, RG2_ENOMEM, "cap: out of memory for %d x %d patches", S.nu, nv);
        goto done;
    }
    out->nu = S.nu;
    out->nv = nv;
    out->closed_u = S.closed_u;
    out->closed_v = 0;
    memcpy(out->bu, S.bu, sizeof(double) * (size_t)S.nu);
    memcpy(out->gu, S.gu, sizeof(double) * (size_t)S.nu);
    for (int j = 0; j < nv; j++)
        out->bv[j] = 1.0;
    for (int j = 0; j < S.nv; j++) {
        out->bv[rb + j] = S.bv[j];
        out->gv[rb + j] = S.gv[j];
    }
    if (rb)
        out->bv[rb] = 3.0 / L[0], out->gv[rb] = 0.0;
    if (ra)
        out->bv[rb + S.nv] = L[1] / 3.0, out->gv[rb + S.nv] = 0.0;
    /* the new patches, each on its own (the same bits on any number of threads), from the body's
     * patches, which stay in place until the last loop */
    bweights bw;
    bweights_make(&bw);
    int du_body = inf.du[inf.capped[0] ? 0 : 1];
#ifdef RG2_HAVE_OPENMP
#pragma omp parallel for schedule(static) if ((size_t)S.nu * (size_t)nv > 256)
#endif
    for (int i = 0; i < S.nu; i++) {
        double q[3][3]; /* the column's quadratic (D, C, S) (used by general caps) */
        ucircle_quadratic(&uc, i, q);
        if (general)
            for (int j = 0; j < S.nv; j++)
                body_times_d(rg2_surface_patch(&S, i, j), q[0], &bw, du_body, out->xp + (size_t)i * nv + rb + j);
        for (int e = 0; e < 2; e++) {
            if (!inf.capped[e])
                continue;
            if (general) {
                rg2_xpatch X[3];
                cap_column_x(&S, q, &bw, e, i, inf.du[e], L[e], vc[e], g[e], lam[e], X);
                for (int k = 0; k < 3; k++) {
                    rg2_xpatch *D = out->xp + (size_t)i * nv + (e == 0 ? k : nv - 1 - k);
                    *D = X[k];
                    if (e)
                        for (int r = 0; r <= X[k].du; r++)
                            for (int t = 0; t <= 3; t++)
                                memcpy(D->h[r][t], X[k].h[r][3 - t], sizeof(double[4]));
                }
                continue;
            }
            rg2_patch P[3];
            cap_column(&S, &uc, e, i, L[e], vc[e], g[e], lam[e], P);
            for (int k = 0; k < 3; k++) {
                rg2_patch *D = caps + (size_t)i * nc + (e == 0 ? k : rb + k);
                if (e == 0)
                    *D = P[k];
                else
                    for (int r = 0; r < 4; r++)
                        for (int s = 0; s < 4; s++)
                            memcpy(D->h[r][s], P[k].h[r][3 - s], sizeof(double[4]));
            }
        }
    }
    out->patch = S.patch;
    S.patch = NULL; /* out's now */
    if (general) { /* the bi-3 slots of higher-degree patches are NaN */
        rg2_patch nanp;
        for (int r = 0; r < 4; r++)
            for (int t = 0; t < 4; t++)
                for (int d = 0; d < 4; d++)
                    nanp.h[r][t][d] = NAN;
#ifdef RG2_HAVE_OPENMP
#pragma omp parallel for schedule(static) if ((size_t)S.nu * (size_t)nv > 256)
#endif
        for (int i = 0; i < S.nu; i++)
            for (int j = 0; j < nv; j++)
                out->patch[(size_t)i * nv + j] = nanp;
    } else {
        /* body column i moves up to rows rb.. of output column i, from the last column to the
         * first: the output column starts at or past its body column, which ends before the
         * columns already moved; the caps go in after their column has moved */
        for (int i = S.nu - 1; i >= 0; i--) {
            rg2_patch *col = out->patch + (size_t)i * nv;
            memmove(col + rb, out->patch + (size_t)i * S.nv, sizeof(rg2_patch) * (size_t)S.nv);
            for (int k = 0; k < rb; k++)
                col[k] = caps[(size_t)i * nc + k];
            for (int k = 0; k < ra; k++)
                col[nv - 1 - k] = caps[(size_t)i * nc + rb + k];
        }
    }
    if (info)
        *info = inf;
    rg2__ok(err);
done:
    free(caps);
    for (int e = 0; e < 2; e++)
        free(fd[e].smp);
    rg2_curve_free(&uc.c);
    rg2_surface_free(&S);
    return st;
}
