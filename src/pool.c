/* pool.c -- a persistent pool of worker threads for short parallel calls (the grid evaluator).
 *
 * rg2_surface_grid's calls are short (0.05-1 ms). An OpenMP parallel region joins every thread
 * of its team at its end: when another process holds the second core, the OpenMP worker reaches
 * the closing barrier only after the scheduler gives it a time slice (milliseconds), and a 0.1 ms
 * call took 8 ms (docs/performance.md). Here the caller and the workers claim chunks of the work
 * from one atomic counter. The caller runs chunks itself and returns as soon as every chunk is
 * done; it never waits for a worker that has not claimed one, and a worker that wakes up late
 * finds nothing left. A call is therefore never much slower than the caller alone.
 *
 * The shared state is one 64-bit word: the job's generation (high 32 bits) and the next chunk
 * to hand out (low 32 bits; CLOSED while the next job is being set up). A chunk is claimed by a
 * compare-and-swap of the whole word, so a worker still holding an old generation can never
 * claim a chunk of a newer job. The job's fields are written between closing and publishing
 * the word (release), read after seeing it (acquire).
 *
 * Workers are created on first use, spin for a short while after a job (the next call is often
 * right behind), then sleep on a condition variable. One job runs at a time; a call that finds
 * the pool busy (another thread of the application is in a grid call) runs its chunks alone.
 */
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
#define CLOSED 0xffffffffu        /* low word while a job is being set up */
#ifndef RG2_POOL_SPIN_US          /* how long an idle worker spins before it sleeps */
#define RG2_POOL_SPIN_US 2000
#endif

static struct {
    pthread_mutex_t submit; /* held by the one caller whose job runs */
    pthread_mutex_t m;      /* with cv: sleeping workers */
    pthread_cond_t cv;
    _Atomic uint64_t state; /* generation << 32 | next chunk */
    _Atomic(rg2__pool_fn) fn;
    _Atomic(void *) arg;
    _Atomic uint32_t n;     /* chunks of the job */
    _Atomic uint32_t done;  /* chunks finished */
    _Atomic int slots;      /* workers still allowed to join the job */
    _Atomic int sleepers;
    _Atomic int quit;
    uint32_t gen;           /* under submit */
    int nworkers;           /* under submit */
    pthread_t tid[POOL_MAX];
} pool = {.submit = PTHREAD_MUTEX_INITIALIZER, .m = PTHREAD_MUTEX_INITIALIZER, .cv = PTHREAD_COND_INITIALIZER};

static uint32_t gen_of(uint64_t s) { return (uint32_t)(s >> 32); }
static uint32_t next_of(uint64_t s) { return (uint32_t)s; }

static uint64_t now_ns(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return (uint64_t)ts.tv_sec * 1000000000u + (uint64_t)ts.tv_nsec;
}

/* Claim and run chunks of the job of generation gen_of(s) until none is left. */
static void run_chunks(uint64_t s)
{
    uint32_t g = gen_of(s);
    rg2__pool_fn fn = atomic_load_explicit(&pool.fn, memory_order_acquire);
    void *arg = atomic_load_explicit(&pool.arg, memory_order_acquire);
    uint32_t n = atomic_load_explicit(&pool.n, memory_order_acquire);
    /* fn, arg, n may already belong to a newer job; then the word holds a newer generation
     * (or CLOSED) and no compare-and-swap below succeeds */
    while (gen_of(s) == g && next_of(s) < n) {
        if (atomic_compare_exchange_weak_explicit(&pool.state, &s, s + 1, memory_order_acq_rel,
                                                  memory_order_acquire)) {
            fn(arg, next_of(s));
            atomic_fetch_add_explicit(&pool.done, 1, memory_order_release);
            s = atomic_load_explicit(&pool.state, memory_order_acquire);
        }
    }
}

/* A published job newer than generation seen (not CLOSED), or 0 if none. */
static int fresh(uint64_t s, uint32_t seen) { return gen_of(s) != seen && next_of(s) != CLOSED; }

static void *worker(void *unused)
{
    (void)unused;
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
        if (atomic_fetch_sub(&pool.slots, 1) > 0)
            run_chunks(s);
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

void rg2__pool_run(int nthreads, uint32_t n, rg2__pool_fn fn, void *arg)
{
    if (nthreads <= 1 || n <= 1 || pthread_mutex_trylock(&pool.submit)) {
        for (uint32_t c = 0; c < n; c++)
            fn(arg, c);
        return;
    }
    pthread_once(&pool_once, pool_register);
    int want = nthreads - 1 < POOL_MAX ? nthreads - 1 : POOL_MAX;
    while (pool.nworkers < want && pthread_create(&pool.tid[pool.nworkers], NULL, worker, NULL) == 0)
        pool.nworkers++;
    uint32_t g = ++pool.gen;
    if (g == 0 || g == gen_of(atomic_load(&pool.state))) /* never reuse the idle word's generation */
        g = ++pool.gen;
    atomic_store(&pool.state, (uint64_t)g << 32 | CLOSED);
    atomic_store_explicit(&pool.fn, fn, memory_order_release);
    atomic_store_explicit(&pool.arg, arg, memory_order_release);
    atomic_store_explicit(&pool.n, n, memory_order_release);
    atomic_store(&pool.done, 0);
    atomic_store(&pool.slots, want < pool.nworkers ? want : pool.nworkers);
    uint64_t s = (uint64_t)g << 32;
    atomic_store(&pool.state, s); /* published */
    if (atomic_load(&pool.sleepers) > 0) {
        pthread_mutex_lock(&pool.m);
        pthread_cond_broadcast(&pool.cv);
        pthread_mutex_unlock(&pool.m);
    }
    run_chunks(s);
    /* the rest was claimed by workers that are running it */
    for (unsigned i = 1; atomic_load_explicit(&pool.done, memory_order_acquire) != n; i++) {
        cpu_relax();
        if (!(i & 4095))
            sched_yield(); /* the worker may have lost its core mid-chunk */
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
