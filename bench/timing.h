/* timing.h -- the clock and the median shared by the benchmark programs (bench.c, traffic.c). */
#ifndef RG2_BENCH_TIMING_H
#define RG2_BENCH_TIMING_H

#include <stdlib.h>
#include <string.h>
#include <time.h>

/* Seconds on clock c (CLOCK_MONOTONIC: wall time; CLOCK_THREAD_CPUTIME_ID: the calling thread's
 * CPU time). */
static inline double bench_seconds(clockid_t c)
{
    struct timespec t;
    clock_gettime(c, &t);
    return (double)t.tv_sec + 1e-9 * (double)t.tv_nsec;
}

static inline int bench_cmp_d(const void *a, const void *b)
{
    double x = *(const double *)a, y = *(const double *)b;
    return (x > y) - (x < y);
}

/* The median of v[0..n-1] (n >= 1; v is left as it is; NaN if out of memory). */
static inline double bench_median(const double *v, int n)
{
    double *w = malloc(sizeof(double) * (size_t)n);
    if (!w)
        return 0.0 / 0.0;
    memcpy(w, v, sizeof(double) * (size_t)n);
    qsort(w, (size_t)n, sizeof(double), bench_cmp_d);
    double m = n % 2 ? w[n / 2] : 0.5 * (w[n / 2 - 1] + w[n / 2]);
    free(w);
    return m;
}

#endif
