/* alloc.c -- overflow-checked zeroed allocation, and large arrays on huge pages.
 *
 * A surface of 1000 x 1000 control points is about a million patches, 509 MB. First touching
 * memory costs a page fault per page; in virtual machines that trap every guest page fault (the
 * AMD EPYC Zen 5 guest of docs/performance.md) a fault costs about 10 us, so 4 KiB pages made
 * building such a surface 1.4 s of faults. Arrays from RG2_BIG_BYTES up are therefore aligned to
 * 2 MiB and advised as transparent huge pages: one fault per 2 MiB, and fewer TLB misses when the
 * grid evaluator walks the patches. Everything here is freed with free().
 */
#define _DEFAULT_SOURCE /* madvise, posix_memalign */
#include "internal.h"

#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#if defined(__linux__)
#include <sys/mman.h>
#endif

#define HUGE_PAGE ((size_t)2 << 20)
#ifndef RG2_BIG_BYTES
#define RG2_BIG_BYTES ((size_t)4 << 20)
#endif

void *rg2__calloc(size_t n, size_t size)
{
    if (n == 0)
        n = 1;
    if (size != 0 && n > SIZE_MAX / size)
        return NULL;
    return calloc(n, size);
}

void *rg2__calloc_big(size_t n, size_t size)
{
    if (n == 0)
        n = 1;
    if (size != 0 && n > SIZE_MAX / size)
        return NULL;
#if defined(__linux__) && defined(MADV_HUGEPAGE)
    size_t bytes = n * size;
    if (bytes >= RG2_BIG_BYTES && bytes <= SIZE_MAX - HUGE_PAGE) {
        size_t whole = (bytes + HUGE_PAGE - 1) & ~(HUGE_PAGE - 1); /* the last huge page too */
        void *p = NULL;
        if (posix_memalign(&p, HUGE_PAGE, whole) == 0) {
            (void)madvise(p, whole, MADV_HUGEPAGE); /* advice: without THP, 4 KiB pages */
            memset(p, 0, bytes);
            return p;
        }
    }
#endif
    return calloc(n, size);
}
