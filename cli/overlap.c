/* overlap.c -- which output surfaces rg2 render draws on top of each other: the first pair of
 * boxes (in the order a = 1, 2, ..., b = 0 .. a - 1) that overlap by half or more of the smaller
 * extent along every axis. Comparing every pair made the note O(n^2): 64 000 outputs took
 * 19.5 s of a 22.5 s render in it. Two boxes that overlap so intersect along every axis, so the
 * pairs compared are those whose intervals intersect along one axis, found by a sweep over the
 * boxes sorted by their start there (the axis with the fewest such pairs); the first pair in
 * the old order among those that overlap is the pair the old loop found. */
#include "cli.h"

#include <math.h>
#include <stdlib.h>

int rg2_cli_box_overlap(const double (*A)[3], const double (*B)[3])
{
    for (int k = 0; k < 3; k++) {
        double ea = A[1][k] - A[0][k], eb = B[1][k] - B[0][k];
        double common = fmin(A[1][k], B[1][k]) - fmax(A[0][k], B[0][k]);
        if (!(common >= 0.5 * fmin(ea, eb)))
            return 0;
    }
    return 1;
}

static const double (*sort_box)[2][3];
static int sort_axis;

static int by_start(const void *x, const void *y)
{
    double a = sort_box[*(const int *)x][0][sort_axis], b = sort_box[*(const int *)y][0][sort_axis];
    return (a > b) - (a < b);
}

static int cmp_double(const void *x, const void *y)
{
    double a = *(const double *)x, b = *(const double *)y;
    return (a > b) - (a < b);
}

/* The first index of the sorted v[0..n) above x (upper bound). */
static size_t above(const double *v, size_t n, double x)
{
    size_t lo = 0, hi = n;
    while (lo < hi) {
        size_t m = lo + (hi - lo) / 2;
        if (v[m] <= x)
            lo = m + 1;
        else
            hi = m;
    }
    return lo;
}

/* The first index of the sorted v[0..n) at or above x (lower bound). */
static size_t from(const double *v, size_t n, double x)
{
    size_t lo = 0, hi = n;
    while (lo < hi) {
        size_t m = lo + (hi - lo) / 2;
        if (v[m] < x)
            lo = m + 1;
        else
            hi = m;
    }
    return lo;
}

static int first_overlap_all(const double (*box)[2][3], int n, int *pa, int *pb, long *compared)
{
    for (int a = 0; a < n; a++)
        for (int b = 0; b < a; b++) {
            if (isnan(box[a][0][0]) || isnan(box[b][0][0]))
                continue;
            ++*compared;
            if (rg2_cli_box_overlap(box[a], box[b])) {
                *pa = a, *pb = b;
                return 1;
            }
        }
    return 0;
}

int rg2_cli_first_overlap(const double (*box)[2][3], int n, int *pa, int *pb, long *compared)
{
    long count = 0;
    if (!compared)
        compared = &count;
    *compared = 0;
    /* the boxes drawn (a NaN first coordinate: no point of positive weight, compared with none) */
    int m = 0, *idx = malloc(((size_t)n + 1) * sizeof *idx);
    double *lo = malloc(((size_t)n + 1) * sizeof *lo), *hi = malloc(((size_t)n + 1) * sizeof *hi);
    int finite = idx && lo && hi;
    for (int s = 0; finite && s < n; s++) {
        if (isnan(box[s][0][0]))
            continue;
        for (int k = 0; k < 3; k++)
            finite = finite && isfinite(box[s][0][k]) && isfinite(box[s][1][k]) && box[s][0][k] <= box[s][1][k];
        idx[m++] = s;
    }
    if (!finite) { /* (out of memory, or a box the sweep cannot order: every pair, as before) */
        free(idx);
        free(lo);
        free(hi);
        return first_overlap_all(box, n, pa, pb, compared);
    }
    /* the axis along which the fewest pairs intersect: pairs = sum over the boxes of the others
     * starting at or before its end and ending at or after its start, halved */
    double best_pairs = INFINITY;
    int axis = 0;
    for (int k = 0; k < 3; k++) {
        for (int q = 0; q < m; q++) {
            lo[q] = box[idx[q]][0][k];
            hi[q] = box[idx[q]][1][k];
        }
        qsort(lo, (size_t)m, sizeof *lo, cmp_double);
        qsort(hi, (size_t)m, sizeof *hi, cmp_double);
        double pairs = 0;
        for (int q = 0; q < m; q++) {
            double l = box[idx[q]][0][k], h = box[idx[q]][1][k];
            pairs += (double)above(lo, (size_t)m, h) - (double)from(hi, (size_t)m, l) - 1.0;
        }
        if (pairs < best_pairs)
            best_pairs = pairs, axis = k;
    }
    sort_box = box;
    sort_axis = axis;
    qsort(idx, (size_t)m, sizeof *idx, by_start);
    int fa = -1, fb = -1;
    for (int p = 0; p < m; p++)
        for (int q = p + 1; q < m && box[idx[q]][0][axis] <= box[idx[p]][1][axis]; q++) {
            int a = idx[p] > idx[q] ? idx[p] : idx[q], b = idx[p] > idx[q] ? idx[q] : idx[p];
            if (fa >= 0 && (a > fa || (a == fa && b > fb)))
                continue; /* (not before the pair found) */
            ++*compared;
            if (rg2_cli_box_overlap(box[a], box[b]))
                fa = a, fb = b;
        }
    free(idx);
    free(lo);
    free(hi);
    if (fa < 0)
        return 0;
    *pa = fa, *pb = fb;
    return 1;
}
