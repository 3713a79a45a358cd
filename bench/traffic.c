/* traffic.c -- the memory traffic of the free-form grid benchmark without the evaluation: how
 * close to the write ceiling a kernel that reads each patch's control points can come at all.
 *
 * The free-form case of rg2_bench evaluates 197 x 197 patches at 8 x 8 points each: per patch it
 * reads 512 bytes (the 64 homogeneous control values) and writes 64 points of 24 bytes with
 * streaming stores. This program times, interleaved, medians of CPU time:
 *   write      streaming stores of the 1536 bytes per patch only (the write ceiling's way)
 *   read+write the same after loading the patch's 512 bytes (8 cache lines)
 *   +arith     the same with a fixed amount of dependent vector arithmetic per patch row
 *              (--arith N: N multiply-add rounds per row), computed into the stored values
 *   arith      the arithmetic alone, stores to one L1-resident patch buffer
 *   net        read+write with 288 bytes read per patch instead of 512: the 9 of its 16
 *              control points that a patch would own in a Bezier net shared with its
 *              neighbours, here contiguous (the most such a layout could save on reads)
 *   L1 read    read+write with every patch's loads taken from 16 patches that stay in L1
 *              (the same loads without their memory traffic)
 * Usage: rg2_traffic [--reps R] [--arith N]. x86-64 with AVX-512F only (else it says so). */
#define _POSIX_C_SOURCE 200809L
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "timing.h"

#if defined(__GNUC__) && defined(__x86_64__)
#include <immintrin.h>
#define TR_FN __attribute__((target("avx512f,fma")))

enum { NPATCH = 197 * 197, IN_D = 64, OUT_D = 192, NET_D = 36 }; /* doubles per patch read and written */
enum { M_WRITE, M_READ, M_ARITH_RW, M_ARITH, M_NET, M_L1READ, NMODE };

/* One pass of a mode over all patches; returns a value that depends on everything computed. */
TR_FN static double pass(int mode, int arith, const double *in, double *out, double *l1)
{
    __m512d sink = _mm512_setzero_pd();
    for (size_t k = 0; k < NPATCH; k++) {
        __m512d v = _mm512_set1_pd(1.0);
        if (mode == M_READ || mode == M_ARITH_RW || mode == M_L1READ) {
            const double *p = in + (mode == M_L1READ ? k & 15 : k) * IN_D;
            for (int q = 0; q < 8; q++)
                v = _mm512_add_pd(v, _mm512_load_pd(p + 8 * q));
        } else if (mode == M_NET) {
            const double *p = in + k * NET_D;
            for (int q = 0; q < 4; q++)
                v = _mm512_add_pd(v, _mm512_loadu_pd(p + 8 * q));
            v = _mm512_add_pd(v, _mm512_zextpd256_pd512(_mm256_loadu_pd(p + 32)));
        }
        double *d = mode == M_ARITH ? l1 : out + k * OUT_D;
        if (mode == M_WRITE || mode == M_READ || mode == M_NET || mode == M_L1READ) {
            for (int q = 0; q < 24; q++)
                _mm512_stream_pd(d + 8 * q, v);
        } else {
            __m512d a[8];
            for (int q = 0; q < 8; q++)
                a[q] = _mm512_add_pd(v, _mm512_set1_pd((double)q));
            for (int row = 0; row < 8; row++) {
                for (int it = 0; it < arith; it++)
                    for (int q = 0; q < 8; q++)
                        a[q] = _mm512_fmadd_pd(a[q], v, a[(q + 1) & 7]);
                for (int q = 0; q < 3; q++) {
                    if (mode == M_ARITH_RW)
                        _mm512_stream_pd(d + 24 * row + 8 * q, a[q]);
                    else
                        _mm512_store_pd(d + 24 * row + 8 * q, a[q]);
                }
            }
            v = a[0];
        }
        sink = _mm512_add_pd(sink, v);
    }
    _mm_sfence();
    return _mm512_reduce_add_pd(sink);
}

int main(int argc, char **argv)
{
    int reps = 21, arith = 1;
    for (int i = 1; i < argc; i++) {
        if (!strcmp(argv[i], "--reps") && i + 1 < argc)
            reps = atoi(argv[++i]);
        else if (!strcmp(argv[i], "--arith") && i + 1 < argc)
            arith = atoi(argv[++i]);
        else {
            fprintf(stderr, "usage: %s [--reps R] [--arith N]\n", argv[0]);
            return 2;
        }
    }
    if (reps < 1 || reps > 1000 || arith < 1 || arith > 100) {
        fprintf(stderr, "rg2_traffic: --reps must be 1..1000 and --arith 1..100\n");
        return 2;
    }
    __builtin_cpu_init();
    if (!__builtin_cpu_supports("avx512f")) {
        printf("rg2_traffic: this CPU has no AVX-512F; nothing measured\n");
        return 0;
    }
    double *in = aligned_alloc(64, sizeof(double) * IN_D * NPATCH);
    double *out = aligned_alloc(64, sizeof(double) * OUT_D * NPATCH);
    double *l1 = aligned_alloc(64, sizeof(double) * OUT_D);
    double *t = malloc(sizeof(double) * NMODE * (size_t)reps);
    if (!in || !out || !l1 || !t) {
        fprintf(stderr, "rg2_traffic: out of memory\n");
        return 1;
    }
    for (size_t i = 0; i < (size_t)IN_D * NPATCH; i++)
        in[i] = 1e-3 * (double)(i % 1000);
    memset(out, 1, sizeof(double) * OUT_D * NPATCH);
    double chk = 0;
    for (int r = 0; r < reps; r++)
        for (int m = 0; m < NMODE; m++) {
            chk += pass(m, arith, in, out, l1); /* untimed: warm */
            double t0 = bench_seconds(CLOCK_THREAD_CPUTIME_ID);
            chk += pass(m, arith, in, out, l1);
            t[m * reps + r] = bench_seconds(CLOCK_THREAD_CPUTIME_ID) - t0;
        }
    const char *name[NMODE] = {"write (streaming stores)",     "read 512 B + write per patch",
                               "read + write + arithmetic",    "arithmetic alone (L1)",
                               "read 288 B (shared net) + write", "read from L1 + write"};
    double med[NMODE], pts = 64.0 * NPATCH;
    printf("rg2_traffic: %d patches, 512 B read and 1536 B written per patch (%.1f MB + %.1f MB), "
           "%d repetitions, --arith %d\n",
           NPATCH, 512e-6 * NPATCH, 1536e-6 * NPATCH, reps, arith);
    for (int m = 0; m < NMODE; m++) {
        med[m] = bench_median(t + m * reps, reps);
        printf("  %-30s %8.3f ms  %7.1f M points/s  %6.1f ns per patch", name[m], 1e3 * med[m], 1e-6 * pts / med[m],
               1e9 * med[m] / NPATCH);
        if (m != M_ARITH)
            printf("  %.2f of the write ceiling", med[0] / med[m]);
        printf("\n");
    }
    printf("  (checksum %g)\n", chk);
    free(in), free(out), free(l1), free(t);
    return 0;
}
#else
int main(void)
{
    printf("rg2_traffic: x86-64 with GCC or Clang only; nothing measured\n");
    return 0;
}
#endif
