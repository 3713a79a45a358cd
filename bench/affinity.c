/* affinity.c -- pinning the calling thread to one CPU for a while (rg2_bench's threads table:
 * each vCPU's speed alone). Linux; elsewhere bench_cpus finds none and nothing is pinned. */
#define _GNU_SOURCE /* pthread_{get,set}affinity_np, CPU_* */
#include "bench.h"

#include <pthread.h>
#include <sched.h>

#ifdef __linux__
static cpu_set_t saved;
static int have_saved = 0;
#endif

int bench_cpus(int *cpu, int max)
{
    int n = 0;
#ifdef __linux__
    cpu_set_t s;
    if (pthread_getaffinity_np(pthread_self(), sizeof s, &s))
        return 0;
    for (int c = 0; c < CPU_SETSIZE && n < max; c++)
        if (CPU_ISSET(c, &s))
            cpu[n++] = c;
#else
    (void)cpu;
    (void)max;
#endif
    return n;
}

int bench_pin(int cpu)
{
#ifdef __linux__
    if (!have_saved) {
        if (pthread_getaffinity_np(pthread_self(), sizeof saved, &saved))
            return -1;
        have_saved = 1;
    }
    cpu_set_t s;
    CPU_ZERO(&s);
    CPU_SET(cpu, &s);
    return pthread_setaffinity_np(pthread_self(), sizeof s, &s) ? -1 : 0;
#else
    (void)cpu;
    return -1;
#endif
}

void bench_unpin(void)
{
#ifdef __linux__
    if (have_saved)
        (void)pthread_setaffinity_np(pthread_self(), sizeof saved, &saved);
#endif
}
