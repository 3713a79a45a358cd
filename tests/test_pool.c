/* test_pool.c -- the grid evaluator's worker pool (src/pool.c): every chunk runs exactly once
 * and its writes are visible when rg2__pool_run returns, for any thread and chunk count, after
 * the workers fell asleep, with several application threads calling at once, and in a forked
 * child; rg2_surface_grid gives the same bits through all of it. */
#define _POSIX_C_SOURCE 200809L /* nanosleep under -std=c11 */
#include "../src/internal.h"
#include "harness.h"

#include <dirent.h>
#include <pthread.h>
#include <stdatomic.h>
#include <stdlib.h>
#include <string.h>
#include <sys/wait.h>
#include <time.h>
#include <unistd.h>

typedef struct {
    uint32_t n;
    unsigned *hits;  /* per chunk: times run (plain writes; each chunk owns its slot) */
    double *work;    /* per chunk: a result that must be visible to the caller */
} count_job;

static void count_chunk(void *arg, uint32_t c)
{
    count_job *j = arg;
    double x = c;
    for (uint32_t i = 0; i < (c % 7) * 200; i++) /* uneven chunks */
        x = x * 0.999 + 1.0;
    j->work[c] = x;
    j->hits[c]++;
}

static double expect(uint32_t c)
{
    double x = c;
    for (uint32_t i = 0; i < (c % 7) * 200; i++)
        x = x * 0.999 + 1.0;
    return x;
}

static void sleep_ms(int ms)
{
    struct timespec ts = {0, (long)ms * 1000000L};
    nanosleep(&ts, NULL);
}

/* One pool call of n chunks on th threads; the number of chunks run other than once or with
 * their result not visible on return. */
static int one_call(int th, uint32_t n)
{
    count_job j = {n, calloc(n + 1, sizeof(unsigned)), calloc(n + 1, sizeof(double))};
    rg2__pool_run(th, n, count_chunk, &j);
    int bad = 0;
    for (uint32_t c = 0; c < n; c++)
        if (j.hits[c] != 1 || j.work[c] != expect(c))
            bad++;
    free(j.hits);
    free(j.work);
    return bad;
}

/* Every chunk exactly once, for thread counts 0..5 and chunk counts 0..600 (and 70001, more than
 * one job holds); some calls after a pause longer than the workers' spin (they sleep and must be
 * woken). */
static void chunks_once(void)
{
    int bad = 0, calls = 0;
    for (int th = 0; th <= 5; th++)
        for (uint32_t n = 0; n <= 600; n += n < 20 ? 1 : 97) {
            if (n == 301)
                sleep_ms(5);
            bad += one_call(th, n);
            calls++;
        }
    /* more chunks than one job's 16-bit block positions hold: run as consecutive jobs */
    for (int th = 2; th <= 3; th++, calls++)
        bad += one_call(th, 70001);
    printf("pool: %d calls (threads 0..5, 0..600 and 70001 chunks): %d chunks run other than once or not "
           "visible\n",
           calls, bad);
    CHECK(bad == 0, "%d chunks run other than once or with their result not visible", bad);
}

/* The grid on the torus with n x n points per patch, all outputs, into a fresh buffer. */
typedef struct {
    const rg2_surface *s;
    int n, threads, calls;
    const double *ref;
    size_t doubles;
    int mismatches, errors;
} grid_task;

static void *grid_calls(void *arg)
{
    grid_task *t = arg;
    size_t pts = (size_t)t->s->nu * t->s->nv * t->n * t->n;
    double *mem = malloc(t->doubles * sizeof(double));
    for (int c = 0; c < t->calls; c++) {
        memset(mem, 0, t->doubles * sizeof(double));
        rg2_grid_out o = {.pos = mem, .normal = mem + 3 * pts, .K = mem + 6 * pts, .H = mem + 7 * pts};
        rg2_error err;
        if (rg2_surface_grid(t->s, t->n, t->n, t->threads + c % 3, &o, &err))
            t->errors++;
        else if (memcmp(mem, t->ref, t->doubles * sizeof(double)))
            t->mismatches++;
        if (c % 16 == 15)
            sleep_ms(3); /* the workers go to sleep */
    }
    free(mem);
    return NULL;
}

static void grid_under_load(void)
{
    rg2_surface s;
    rg2_error err;
    CHECK_OK(rg2t_torus(3.0, 1.0, 8, 6, NULL, &s, &err), &err);
    int n = 9;
    size_t pts = (size_t)s.nu * s.nv * n * n, doubles = 8 * pts;
    double *ref = malloc(doubles * sizeof(double));
    rg2_grid_out o = {.pos = ref, .normal = ref + 3 * pts, .K = ref + 6 * pts, .H = ref + 7 * pts};
    CHECK_OK(rg2_surface_grid(&s, n, n, 1, &o, &err), &err);

    /* one caller, thread counts 1..3 in turn */
    grid_task one = {&s, n, 1, 96, ref, doubles, 0, 0};
    grid_calls(&one);
    CHECK(one.errors == 0 && one.mismatches == 0, "one caller: %d errors, %d results differing from 1 thread",
          one.errors, one.mismatches);

    /* three application threads calling at once (the pool runs one job; the others run alone) */
    grid_task many[3];
    pthread_t tid[3];
    for (int i = 0; i < 3; i++) {
        many[i] = (grid_task){&s, n, 2, 64, ref, doubles, 0, 0};
        pthread_create(&tid[i], NULL, grid_calls, &many[i]);
    }
    int errs = 0, mism = 0;
    for (int i = 0; i < 3; i++) {
        pthread_join(tid[i], NULL);
        errs += many[i].errors, mism += many[i].mismatches;
    }
    printf("pool: rg2_surface_grid, 1 caller x 96 calls and 3 concurrent callers x 64 calls (1-4 threads): "
           "%d errors, %d results differing from 1 thread\n", one.errors + errs, one.mismatches + mism);
    CHECK(errs == 0 && mism == 0, "concurrent callers: %d errors, %d results differing from 1 thread", errs, mism);

    /* a forked child has no workers: the pool starts over there */
    fflush(NULL);
    pid_t pid = fork();
    if (pid == 0) {
        grid_task child = {&s, n, 2, 20, ref, doubles, 0, 0};
        grid_calls(&child);
        _exit(child.errors || child.mismatches ? 3 : 0);
    }
    int status = 0;
    CHECK(pid > 0 && waitpid(pid, &status, 0) == pid && WIFEXITED(status) && WEXITSTATUS(status) == 0,
          "grid calls with 2 threads in a forked child: status %d", status);
    free(ref);
    rg2_surface_free(&s);
}

/* A worker asleep (after a pause longer than its 2 ms spin) is woken by the next call and takes
 * part in it: chunk 0, the caller's first, waits (up to 5 s) until a chunk has run on another
 * thread, which a worker that slept through the call never does (the caller alone still gets
 * every chunk right, so chunks_once cannot tell). */
typedef struct {
    pthread_t caller;
    atomic_int other; /* chunks run on another thread */
    int wait_ms;      /* how long chunk 0 waits for one */
} wake_job;

static void wake_chunk(void *arg, uint32_t c)
{
    wake_job *j = arg;
    if (!pthread_equal(pthread_self(), j->caller))
        atomic_fetch_add(&j->other, 1);
    else if (c == 0)
        for (int ms = 0; ms < j->wait_ms && !atomic_load(&j->other); ms++)
            sleep_ms(1);
}

/* Threads of this process (the entries of /proc/self/task), or 0 where that is not known. */
static int process_threads(void)
{
    DIR *d = opendir("/proc/self/task");
    int n = 0;
    if (!d)
        return 0;
    for (struct dirent *e; (e = readdir(d)) != NULL;)
        n += e->d_name[0] != '.';
    closedir(d);
    return n;
}

static void woken_workers(void)
{
    CHECK(one_call(2, 64) == 0, "2 threads, 64 chunks"); /* the worker exists */
    /* a library built without threads (the portable build without OpenMP and pthreads) runs
     * every chunk on the caller: nothing to wake. A worker just used is awake (spinning). */
    wake_job probe = {pthread_self(), 0, 2000};
    rg2__pool_run(2, 64, wake_chunk, &probe);
    if (!atomic_load(&probe.other)) {
        /* (not for want of a worker: the pool has made its threads; a worker that once fell
         * asleep in chunks_once and never woke again looked like a library without threads) */
        int th = process_threads();
        CHECK(th <= 1, "every chunk of 64 ran on the caller, chunk 0 waiting 2 s, although the pool has made "
                       "its workers (%d threads in the process): a worker that fell asleep does not wake", th);
        if (th <= 1)
            printf("pool: every chunk ran on the caller (a library without threads): waking not tested\n");
        return;
    }
    int joined = 0;
    for (int round = 0; round < 3; round++) {
        sleep_ms(20); /* the worker falls asleep */
        wake_job j = {pthread_self(), 0, 5000};
        rg2__pool_run(2, 64, wake_chunk, &j);
        joined += atomic_load(&j.other) > 0;
    }
    CHECK(joined == 3, "a sleeping worker took part in %d of 3 calls after a pause", joined);
}

int main(void)
{
    chunks_once();
    woken_workers();
    grid_under_load();
    return rg2t_done("test_pool");
}
