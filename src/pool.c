/* pool.c -- a persistent pool of worker threads for short parallel calls (the grid evaluator,
 * the tessellation).
 *
 * rg2_surface_grid's calls are short (0.05-1 ms). An OpenMP parallel region joins every thread
 * of its team at its end: when another process holds the second core, the OpenMP worker reaches
 * the closing barrier only after the scheduler gives it a time slice (milliseconds), and a 0.1 ms
 * call took 8 ms (docs/performance.md). Here the caller and the workers claim chunks of the work
 * themselves. The caller runs chunks and returns as soon as every chunk is done; it never waits
 * for a worker that has not claimed one, and a worker that wakes up late finds nothing left. A
 * call is therefore never much slower than the caller alone.
 *
 * Home blocks. A job of n chunks on T threads is split into T contiguous blocks; thread k (the
 * caller is 0, worker i is i + 1) claims the chunks of its own block first, from the front, then
 * those left in the other blocks (k + 1, k + 2, ... mod T). When the threads keep pace, each runs
 * the same chunks call after call, so an application that evaluates into the same arrays again
 * finds its part of them in its own core's cache: with one shared counter the chunks fell to the
 * threads at random, half of each thread's output lines were last written by the other core, and
 * 2 threads evaluating 9.4 MB of positions and normals (L3) reached only 1.3-1.5x of one instead
 * of 1.9x (docs/performance.md). A busy or late thread's block is taken by the others.
 *
 * Each block is one 64-bit word on its own cache line: the job's generation (high 32 bits), the
 * block's end and its next chunk (16 bits each, so at most 65535 chunks per job; longer jobs run
 * as several). A chunk is claimed by a compare-and-swap of the whole word, so a worker holding an
 * old generation can never claim a chunk of a newer job, and a finished job's words have no chunk
 * left. The job is announced by a separate word (generation, block count T, or CLOSED while the
 * job is being set up); the job's fields are written before it is published (release) and read
 * after it is seen (acquire).
 *
 * Workers are created on first use, spin for a short while after a job (the next call is often
 * right behind), then sleep on a condition variable. One job runs at a time; a call that finds
 * the pool busy (another thread of the application is in a grid call) runs its chunks alone.
 */
#define _POSIX_C_SOURCE 200809L /* clock_gettime, CLOCK_MONOTONIC under -std=c11 (any compiler, OpenMP or not) */
#include "internal.h"

#if RG2_HAVE_PTHREAD

#include <pthread.h>
#include <sched.h>
#include <stdatomic.h>
#include <stdint.h>
#include <time.h>

#if defined(__x86_64__) || defined(__i386__)
#include <immintrin.h>
#define cpu_relax() _mm_pause()
#else
#define cpu_relax() ((void)0)
#endif

#define POOL_MAX 63               /* workers; the caller is one more thread */
#define CLOSED 0xffffffffu        /* announcement's low word while a job is being set up */
#define MAX_CHUNKS 0xffffu        /* chunks per job (16-bit block positions) */
#ifndef RG2_POOL_SPIN_US          /* how long an idle worker spins before it sleeps */
#define RG2_POOL_SPIN_US 2000
#endif
#define LINE 64

typedef struct {
    _Alignas(LINE) _Atomic uint64_t w; /* generation << 32 | end << 16 | next */
} block;

static struct {
    pthread_mutex_t submit; /* held by the one caller whose job runs */
    pthread_mutex_t m;      /* with cv: sleeping workers */
    pthread_cond_t cv;
    _Alignas(LINE) _Atomic uint64_t state; /* generation << 32 | blocks T (CLOSED: setting up) */
    _Alignas(LINE) _Atomic uint32_t done;  /* chunks finished (added once per thread and job) */
    _Alignas(LINE) _Atomic(rg2__pool_fn) fn;
    _Atomic(void *) arg;
    _Alignas(LINE) _Atomic int quit; /* read by spinning workers: not on the line of fn, arg */
    _Atomic int sleepers;
    uint32_t gen;           /* under submit */
    int nworkers;           /* under submit */
    pthread_t tid[POOL_MAX];
    block blk[POOL_MAX + 1];
} pool = {.submit = PTHREAD_MUTEX_INITIALIZER, .m = PTHREAD_MUTEX_INITIALIZER, .cv = PTHREAD_COND_INITIALIZER};

static uint32_t gen_of(uint64_t s) { return (uint32_t)(s >> 32); }
static uint32_t low_of(uint64_t s) { return (uint32_t)s; }
static uint32_t next_of(uint64_t w) { return (uint32_t)w & 0xffffu; }
static uint32_t end_of(uint64_t w) { return ((uint32_t)w >> 16) & 0xffffu; }

static uint64_t now_ns(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return (uint64_t)ts.tv_sec * 1000000000u + (uint64_t)ts.tv_nsec;
}

/* Claim and run chunks of generation g on T blocks, from block home on, until none is left;
 * returns how many this thread ran. */
static uint32_t run_chunks(uint32_t g, uint32_t T, uint32_t home)
{
    uint32_t ran = 0;
    rg2__pool_fn fn = atomic_load_explicit(&pool.fn, memory_order_acquire);
    void *arg = atomic_load_explicit(&pool.arg, memory_order_acquire);
    /* fn and arg may already belong to a newer job; then every block word holds a newer
     * generation, or this generation with no chunk left, and no compare-and-swap succeeds */
    for (uint32_t k = 0; k < T; k++) {
        _Atomic uint64_t *w = &pool.blk[(home + k) % T].w;
        uint64_t s = atomic_load_explicit(w, memory_order_acquire);
        while (gen_of(s) == g && next_of(s) < end_of(s)) {
            if (atomic_compare_exchange_weak_explicit(w, &s, s + 1, memory_order_acq_rel, memory_order_acquire)) {
                fn(arg, next_of(s));
                ran++;
                s = atomic_load_explicit(w, memory_order_acquire);
            }
        }
    }
    return ran;
}

/* A published job newer than generation seen (not CLOSED), or 0 if none. */
static int fresh(uint64_t s, uint32_t seen) { return gen_of(s) != seen && low_of(s) != CLOSED; }

static void *worker(void *index)
{
    uint32_t me = (uint32_t)(uintptr_t)index + 1; /* home block; the caller's is 0 */
    uint32_t seen = gen_of(atomic_load(&pool.state));
    for (;;) {
        uint64_t s = atomic_load_explicit(&pool.state, memory_order_acquire);
        if (!fresh(s, seen)) { /* spin a while, then sleep */
            uint64_t t0 = now_ns();
            for (unsigned i = 1; !fresh(s, seen); i++) {
                if (atomic_load_explicit(&pool.quit, memory_order_relaxed))
                    return NULL;
                cpu_relax();
                if (!(i & 255) && now_ns() - t0 > (uint64_t)RG2_POOL_SPIN_US * 1000u) {
                    atomic_fetch_add(&pool.sleepers, 1);
                    pthread_mutex_lock(&pool.m);
                    while (!fresh(atomic_load(&pool.state), seen) && !atomic_load(&pool.quit))
                        pthread_cond_wait(&pool.cv, &pool.m);
                    pthread_mutex_unlock(&pool.m);
                    atomic_fetch_sub(&pool.sleepers, 1);
                    t0 = now_ns();
                }
                s = atomic_load_explicit(&pool.state, memory_order_acquire);
            }
        }
        seen = gen_of(s);
        if (me < low_of(s)) { /* this job has a block for this worker */
            uint32_t ran = run_chunks(seen, low_of(s), me); /* only chunks of generation seen */
            if (ran)
                atomic_fetch_add_explicit(&pool.done, ran, memory_order_release);
        }
    }
}

/* Stop and join the workers at exit (so memory checkers see no live threads). */
__attribute__((destructor)) static void pool_stop(void)
{
    if (pthread_mutex_trylock(&pool.submit))
        return; /* a job is running in another thread: leave the workers alone */
    atomic_store(&pool.quit, 1);
    pthread_mutex_lock(&pool.m);
    pthread_cond_broadcast(&pool.cv);
    pthread_mutex_unlock(&pool.m);
    for (int i = 0; i < pool.nworkers; i++)
        pthread_join(pool.tid[i], NULL);
    pool.nworkers = 0;
    atomic_store(&pool.quit, 0);
    pthread_mutex_unlock(&pool.submit);
}

/* In a child of fork() the workers do not exist: start over. */
static void pool_atfork_child(void)
{
    pthread_mutex_init(&pool.submit, NULL);
    pthread_mutex_init(&pool.m, NULL);
    pthread_cond_init(&pool.cv, NULL);
    pool.nworkers = 0;
    atomic_store(&pool.sleepers, 0);
}

static void pool_atfork_prepare(void) { pthread_mutex_lock(&pool.submit); }
static void pool_atfork_parent(void) { pthread_mutex_unlock(&pool.submit); }

static pthread_once_t pool_once = PTHREAD_ONCE_INIT;
static void pool_register(void) { pthread_atfork(pool_atfork_prepare, pool_atfork_parent, pool_atfork_child); }

/* One job of n <= MAX_CHUNKS chunks on T = 1 + workers blocks (pool.submit held). */
static void run_job(uint32_t T, uint32_t n, rg2__pool_fn fn, void *arg)
{
    uint32_t g = ++pool.gen;
    if (g == 0 || g == gen_of(atomic_load(&pool.state))) /* never reuse the idle word's generation */
        g = ++pool.gen;
    /* release stores: a sequentially consistent store (xchg) waits for its cache line, which a
     * spinning worker holds (0.3 us between the two vCPUs of the AMD Zen 5 machine); two of them
     * here delayed the worker's first chunk of every call by 0.3 us. The publication below stays
     * sequentially consistent: it orders the store before the load of sleepers. */
    atomic_store_explicit(&pool.state, (uint64_t)g << 32 | CLOSED, memory_order_release);
    atomic_store_explicit(&pool.fn, fn, memory_order_release);
    atomic_store_explicit(&pool.arg, arg, memory_order_release);
    atomic_store_explicit(&pool.done, 0, memory_order_release);
    for (uint32_t b = 0; b < T; b++) {
        uint64_t lo = (uint64_t)b * n / T, hi = (uint64_t)(b + 1) * n / T;
        atomic_store_explicit(&pool.blk[b].w, (uint64_t)g << 32 | hi << 16 | lo, memory_order_release);
    }
    atomic_store(&pool.state, (uint64_t)g << 32 | T); /* published */
    if (atomic_load(&pool.sleepers) > 0) {
        pthread_mutex_lock(&pool.m);
        pthread_cond_broadcast(&pool.cv);
        pthread_mutex_unlock(&pool.m);
    }
    uint32_t mine = run_chunks(g, T, 0);
    /* the rest was claimed by workers that are running it */
    for (unsigned i = 1; atomic_load_explicit(&pool.done, memory_order_acquire) != n - mine; i++) {
        cpu_relax();
        if (!(i & 4095))
            sched_yield(); /* the worker may have lost its core mid-chunk */
    }
}

/* Jobs of more than MAX_CHUNKS chunks run as consecutive jobs over ranges of chunks. */
typedef struct {
    rg2__pool_fn fn;
    void *arg;
    uint32_t first;
} range_job;

static void range_chunk(void *arg, uint32_t c)
{
    range_job *r = arg;
    r->fn(r->arg, r->first + c);
}

void rg2__pool_run(int nthreads, uint32_t n, rg2__pool_fn fn, void *arg)
{
    if (nthreads <= 1 || n <= 1 || pthread_mutex_trylock(&pool.submit)) {
        for (uint32_t c = 0; c < n; c++)
            fn(arg, c);
        return;
    }
    pthread_once(&pool_once, pool_register);
    int want = nthreads - 1 < POOL_MAX ? nthreads - 1 : POOL_MAX;
    while (pool.nworkers < want &&
           pthread_create(&pool.tid[pool.nworkers], NULL, worker, (void *)(uintptr_t)pool.nworkers) == 0)
        pool.nworkers++;
    uint32_t T = 1 + (uint32_t)(want < pool.nworkers ? want : pool.nworkers);
    if (n <= MAX_CHUNKS)
        run_job(T, n, fn, arg);
    else
        for (uint32_t first = 0; first < n; first += MAX_CHUNKS) {
            range_job r = {fn, arg, first};
            run_job(T, n - first < MAX_CHUNKS ? n - first : MAX_CHUNKS, range_chunk, &r);
        }
    pthread_mutex_unlock(&pool.submit);
}

#else /* no threads */

void rg2__pool_run(int nthreads, uint32_t n, rg2__pool_fn fn, void *arg)
{
    (void)nthreads;
    for (uint32_t c = 0; c < n; c++)
        fn(arg, c);
}

#endif
