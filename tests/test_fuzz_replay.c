/* test_fuzz_replay.c -- replays the fuzz corpus: every file in tests/data/fuzz/<harness>/
 * (seeds from the examples and the minimized crashers the fuzzer found, fuzz/README.md) runs
 * through the same harness code as `make fuzz` (fuzz/harness.c), here under the test build's
 * ASan + UBSan. A broken contract aborts; a memory error or leak fails through the sanitizers. */
#define _POSIX_C_SOURCE 200809L
#include "../fuzz/harness.c"

#include "harness.h"

#include <dirent.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

static int cmp(const void *a, const void *b) { return strcmp(*(char *const *)a, *(char *const *)b); }

/* Run every file of dir through fn; returns the number of files. */
static int replay(const char *dir, int (*fn)(const uint8_t *, size_t))
{
    DIR *dp = opendir(dir);
    CHECK(dp != NULL, "cannot open %s", dir);
    if (!dp)
        return 0;
    char *names[4096];
    int n = 0;
    for (struct dirent *e; (e = readdir(dp)) && n < 4096;)
        if (e->d_name[0] != '.')
            names[n++] = strdup(e->d_name);
    closedir(dp);
    qsort(names, (size_t)n, sizeof names[0], cmp);
    for (int k = 0; k < n; k++) {
        char path[1024];
        snprintf(path, sizeof path, "%s/%s", dir, names[k]);
        FILE *f = fopen(path, "rb");
        CHECK(f != NULL, "cannot open %s", path);
        if (f) {
            uint8_t *buf = malloc(RG2F_MAX_INPUT + 1);
            size_t len = buf ? fread(buf, 1, RG2F_MAX_INPUT + 1, f) : 0;
            fclose(f);
            CHECK(buf && len <= RG2F_MAX_INPUT, "%s: larger than the harness limit %d", path, RG2F_MAX_INPUT);
            rg2f_input_name = path;
            CHECK(fn(buf, len) == 0, "%s: harness returned non-zero", path);
            rg2f_input_name = NULL;
            free(buf);
        }
        free(names[k]);
    }
    return n;
}

int main(void)
{
    const char *src = getenv("RG2_SRC");
    char dir[1024];
    snprintf(dir, sizeof dir, "%s/tests/data/fuzz/design", src ? src : ".");
    int nd = replay(dir, rg2f_design);
    snprintf(dir, sizeof dir, "%s/tests/data/fuzz/nurbs", src ? src : ".");
    int nn = replay(dir, rg2f_nurbs);
    snprintf(dir, sizeof dir, "%s/tests/data/fuzz/meshops", src ? src : ".");
    int nm = replay(dir, rg2f_meshops);
    printf("replayed %d design inputs, %d NURBS inputs and %d mesh-operation inputs\n", nd, nn, nm);
    CHECK(nd >= 10 && nn >= 4 && nm >= 4, "corpus too small: %d design, %d NURBS, %d mesh-operation inputs", nd, nn,
          nm);
    return rg2t_done("test_fuzz_replay");
}
