/* alloc.c -- overflow-checked zeroed allocation, and large arrays on huge pages.
 *
 * A surface of 1000 x 1000 control points is about a million patches, 509 MB. First touching
 * memory costs a page fault per page; in virtual machines that trap every guest page fault (the
 * AMD EPYC Zen 5 guest of docs/performance.md) a fault costs about 10 us, so 4 KiB pages made
 * building such a surface 1.4 s of faults; the tessellation's arrays (a few MB each) made
 * tessellating the merged design at 32 samples per patch edge 57 ms, 18 ms on huge pages. Arrays
 * from RG2_BIG_BYTES up are therefore aligned to 2 MiB and advised as transparent huge pages: one
 * fault per 2 MiB, and fewer TLB misses when the grid evaluator walks the patches. Everything
 * here is freed with free().
 *
 * Advised only as far as the kernel has free blocks of 2 MiB or more for twice that part
 * (/proc/buddyinfo): a huge-page fault with none at hand compacts memory in the call itself
 * (the transparent_hugepage defrag setting "madvise", Debian's default), and on a KVM guest
 * where a 4 KiB fault was cheap that made the 1000 x 1000 build take 1.1-1.2 s instead of 0.24
 * (docs/performance.md). Until the twenty-fifth stop the whole array went on 4 KiB pages when
 * the free blocks did not cover twice all of it; advising the part they cover, with 600 MB
 * of free blocks (half of them advised) the 1000 x 1000 build took 0.35 s instead of 0.67 s on
 * the Zen 5 guest (0.69 s in a second, slower run), the smaller meshes' builds as on huge pages.
 *
 * The pages are then populated in one call (MADV_POPULATE_WRITE) before the memset: the kernel
 * maps them all without a fault each. On the Zen 5 guest, with 4 KiB pages forced, that made the
 * 1000 x 1000 build 0.70-0.90 s instead of 1.46-1.88 s (bench --only construction, two runs
 * each): what is left is the guest's first write to each page, which that machine traps per page
 * whether or not it is mapped. With huge pages, 509 MB took 0.037 s instead of 0.045 s.
 */
#define _DEFAULT_SOURCE /* madvise, posix_memalign */
#include "internal.h"

#include <errno.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#if defined(__linux__)
#include <stdio.h>
#include <sys/mman.h>
#include <unistd.h>
#endif

#define HUGE_PAGE ((size_t)2 << 20)
#ifndef RG2_BIG_BYTES
#define RG2_BIG_BYTES ((size_t)2 << 20)
#endif

void *rg2__calloc(size_t n, size_t size)
{
    if (n == 0)
        n = 1;
    if (size != 0 && n > SIZE_MAX / size)
        return NULL;
    return calloc(n, size);
}

#if defined(__linux__) && defined(MADV_HUGEPAGE)
/* Bytes the kernel holds free in blocks of HUGE_PAGE or more, summed over its zones
 * (/proc/buddyinfo: per zone the count of free blocks of 2^k pages, k = 0, 1, ...); 0 if unknown. */
static size_t free_huge_bytes(void)
{
    long page = sysconf(_SC_PAGESIZE);
    FILE *f = fopen("/proc/buddyinfo", "r");
    if (!f || page <= 0) {
        if (f)
            fclose(f);
        return 0;
    }
    size_t total = 0;
    char line[512];
    while (fgets(line, sizeof line, f)) {
        char *p = strstr(line, "zone");
        if (!p)
            continue;
        p += 4;
        while (*p == ' ') /* the zone's name */
            p++;
        while (*p && *p != ' ')
            p++;
        for (int k = 0; k < 20; k++) {
            char *end;
            unsigned long long c = strtoull(p, &end, 10);
            if (end == p)
                break;
            size_t block = (size_t)page << k;
            if (block >= HUGE_PAGE && c <= SIZE_MAX / block && total <= SIZE_MAX - c * block)
                total += (size_t)c * block;
            p = end;
        }
    }
    fclose(f);
    return total;
}
#endif

void *rg2__calloc_big(size_t n, size_t size)
{
    return rg2__alloc_big(n, size, RG2_BIG_BYTES, 1);
}

void *rg2__alloc_big(size_t n, size_t size, size_t from, int zero)
{
#if defined(__linux__) && defined(MADV_HUGEPAGE)
    size_t bytes = size != 0 && n <= SIZE_MAX / size ? n * size : 0; /* (0: overflow, see below) */
    if (bytes != 0 && bytes >= from && bytes <= SIZE_MAX - HUGE_PAGE) {
        size_t whole = (bytes + HUGE_PAGE - 1) & ~(HUGE_PAGE - 1); /* the last huge page too */
        void *p = NULL;
        if (posix_memalign(&p, HUGE_PAGE, whole) == 0) {
            size_t huge = (free_huge_bytes() / 2) & ~(HUGE_PAGE - 1); /* the part advised */
            if (huge > whole)
                huge = whole;
            if (huge > 0) /* advice: past it, 4 KiB pages */
                (void)madvise(p, huge, MADV_HUGEPAGE);
#ifdef MADV_POPULATE_WRITE
            (void)madvise(p, whole, MADV_POPULATE_WRITE); /* (Linux 5.14; before, EINVAL: the memset faults) */
#endif
            if (zero)
                memset(p, 0, bytes);
            return p;
        }
    }
#else
    (void)from;
#endif
    if (!zero && size != 0 && n <= SIZE_MAX / size)
        return malloc(n * size != 0 ? n * size : 1);
    return rg2__calloc(n, size); /* small, overflowing (NULL) or no huge pages */
}

#ifdef RG2_FAULT_INJECT
/* The counting wrappers of internal.h (tests only), on the real allocators. */
#undef malloc
#undef calloc
#undef realloc
#undef strdup
#undef posix_memalign
long rg2__fi_countdown = -1, rg2__fi_injected, rg2__fi_calls;
unsigned long long rg2__fi_bytes; /* bytes asked for by the allocations counted */

static int fi_fail(void)
{
    rg2__fi_calls++;
    if (rg2__fi_countdown < 0)
        return 0;
    if (rg2__fi_countdown-- > 0)
        return 0;
    rg2__fi_injected++; /* (the countdown is now -1: later allocations succeed) */
    return 1;
}

void *rg2__fi_malloc(size_t n)
{
    rg2__fi_bytes += n;
    return fi_fail() ? NULL : malloc(n);
}

void *rg2__fi_calloc(size_t n, size_t size)
{
    rg2__fi_bytes += (unsigned long long)n * size;
    return fi_fail() ? NULL : calloc(n, size);
}

void *rg2__fi_realloc(void *p, size_t n)
{
    rg2__fi_bytes += n;
    return fi_fail() ? NULL : realloc(p, n);
}

char *rg2__fi_strdup(const char *s)
{
    size_t n = strlen(s) + 1;
    rg2__fi_bytes += n;
    if (fi_fail())
        return NULL;
    char *r = malloc(n);
    return r ? memcpy(r, s, n) : NULL;
}

int rg2__fi_posix_memalign(void **p, size_t align, size_t n)
{
    rg2__fi_bytes += n;
    return fi_fail() ? ENOMEM : posix_memalign(p, align, n);
}
#endif
