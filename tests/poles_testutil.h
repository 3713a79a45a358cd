/* poles_testutil.h -- small helpers shared by test_poles.c and test_cap.c: random circle
 * partitions and knot sequences, 3D distance and angle. */
#ifndef RG2_POLES_TESTUTIL_H
#define RG2_POLES_TESTUTIL_H

#include "harness.h"

#include <math.h>

/* Random closed partition of the circle into n arcs (ratios within 0.6..1). */
static inline void pt_random_arcs(rg2t_rng *r, int n, double *alpha)
{
    double s = 0;
    for (int i = 0; i < n; i++)
        s += (alpha[i] = rg2t_uniform(r, 0.6, 1.0));
    for (int i = 0; i < n; i++)
        alpha[i] *= 2 * M_PI / s;
}

/* m increasing knots strictly inside (lo, hi), m < 63. */
static inline void pt_random_knots(rg2t_rng *r, int m, double lo, double hi, double *v)
{
    double s = 0, d[64], acc = 0;
    for (int k = 0; k <= m; k++)
        s += (d[k] = rg2t_uniform(r, 0.5, 1.0));
    for (int k = 0; k < m; k++)
        v[k] = lo + (hi - lo) * (acc += d[k]) / s;
}

static inline double pt_dist3(const double a[3], const double b[3])
{
    return hypot(hypot(a[0] - b[0], a[1] - b[1]), a[2] - b[2]);
}

/* Angle between two vectors, atan2(|a x b|, a . b). */
static inline double pt_angle3(const double a[3], const double b[3])
{
    double c[3] = {a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]};
    return atan2(sqrt(c[0] * c[0] + c[1] * c[1] + c[2] * c[2]), a[0] * b[0] + a[1] * b[1] + a[2] * b[2]);
}

#endif
