/* Timing helpers shared by bench_slab.c and bench_spectral.c.
 *
 * Header-only on purpose: CMakeLists.txt builds every bench/bench_*.c as its own executable from
 * that one source, so shared code cannot live in a second .c file.
 *
 * Method. A case is a function that performs `iters` calls of the operation under test and returns
 * a checksum of the results (accumulated into a global sink and printed, so the work is observable
 * and cannot be dropped). The iteration count is calibrated once so that one run lasts at least
 * `min_time` seconds; then `runs` runs of that many iterations are timed with CLOCK_MONOTONIC and
 * the median ns/call is reported. The median, not the mean, because on a shared (virtualised)
 * machine the noise is one-sided: preemptions only ever make a run slower. Each run also reads
 * the thread's CPU clock: cpu_share = CPU time / wall time well below 1 means the benchmark was
 * descheduled (another process competed for the core) and the run should be repeated. */
#ifndef BIREF_BENCH_CLOCK_H
#define BIREF_BENCH_CLOCK_H

#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

/* Runs `iters` calls of the operation under test on `ctx`; returns a checksum of the outputs. */
typedef double (*bench_case_fn)(void *ctx, long iters);

typedef struct {
    double ns_median, ns_min, ns_max; /* per call, over the runs */
    double cpu_share;                 /* lowest CPU time / wall time over the runs */
    long iters;                       /* iterations per run */
    int runs;
} bench_result;

/* Every checksum ends up here and is printed by the benchmarks. */
static double bench_sink;

static inline double bench_clock(clockid_t id)
{
    struct timespec ts;
    clock_gettime(id, &ts);
    return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}

static inline double bench_now(void) { return bench_clock(CLOCK_MONOTONIC); }

static int bench_cmp_double(const void *a, const void *b)
{
    double x = *(const double *)a, y = *(const double *)b;
    return (x > y) - (x < y);
}

enum { BENCH_MAX_RUNS = 64 };

/* Below this CPU share a run was visibly descheduled: the benchmarks print a warning. */
#define BENCH_CPU_SHARE_OK 0.95

/* fixed_iters > 0 skips the calibration (used under valgrind, where only the call count matters). */
static bench_result bench_measure(bench_case_fn fn, void *ctx, double min_time, int runs, long fixed_iters)
{
    bench_result r = {0};
    if (runs < 1) runs = 1;
    if (runs > BENCH_MAX_RUNS) runs = BENCH_MAX_RUNS;
    long iters = fixed_iters;
    if (iters <= 0) {
        /* Pilot: double the count until a run is long enough (20 ms) for the clock's resolution
         * and the first-call effects (page faults, cold caches) to be negligible, then scale. */
        long n = 1;
        double t = 0.0;
        for (;;) {
            double t0 = bench_now();
            bench_sink += fn(ctx, n);
            t = bench_now() - t0;
            if (t >= 0.02 || n >= (1L << 40)) break;
            n *= 2;
        }
        double want = min_time > 0.0 ? min_time : 0.0;
        iters = (long)ceil((double)n * want / t * 1.05);
        if (iters < n) iters = n;
    }
    double ns[BENCH_MAX_RUNS];
    r.cpu_share = 1.0;
    for (int k = 0; k < runs; k++) {
        double c0 = bench_clock(CLOCK_THREAD_CPUTIME_ID), t0 = bench_now();
        bench_sink += fn(ctx, iters);
        double wall = bench_now() - t0, cpu = bench_clock(CLOCK_THREAD_CPUTIME_ID) - c0;
        ns[k] = wall * 1e9 / (double)iters;
        if (wall > 0.0 && cpu / wall < r.cpu_share) r.cpu_share = cpu / wall;
    }
    qsort(ns, (size_t)runs, sizeof ns[0], bench_cmp_double);
    r.ns_min = ns[0];
    r.ns_max = ns[runs - 1];
    r.ns_median = runs % 2 ? ns[runs / 2] : 0.5 * (ns[runs / 2 - 1] + ns[runs / 2]);
    r.iters = iters;
    r.runs = runs;
    return r;
}

/* splitmix64: a small, seedable generator, so every run and machine draws the same inputs. */
typedef struct {
    uint64_t s;
} bench_rng;

static inline uint64_t bench_rng_next(bench_rng *g)
{
    uint64_t z = (g->s += 0x9E3779B97F4A7C15ull);
    z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
    z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
    return z ^ (z >> 31);
}

/* Uniform in [a, b). */
static inline double bench_rng_uniform(bench_rng *g, double a, double b)
{
    return a + (b - a) * (double)(bench_rng_next(g) >> 11) * (1.0 / 9007199254740992.0);
}

/* Parses a positive number argument or exits with a message (benchmarks have no other error path). */
static double bench_arg_number(const char *opt, const char *val)
{
    char *end = NULL;
    double v = val ? strtod(val, &end) : NAN;
    if (!val || end == val || *end != '\0' || !(v > 0.0) || !isfinite(v)) {
        fprintf(stderr, "%s needs a positive number (got %s)\n", opt, val ? val : "nothing");
        exit(2);
    }
    return v;
}

/* Options every benchmark takes: calibration time, runs, a fixed call count, the RNG seed. */
typedef struct {
    double min_time;
    int runs, runs_given;
    long fixed_iters;
    uint64_t seed;
} bench_common_opts;

static inline void bench_common_defaults(bench_common_opts *o)
{
    o->min_time = 0.5;
    o->runs = 5;
    o->runs_given = 0;
    o->fixed_iters = 0;
    o->seed = 1;
}

/* Consumes argv[*i] (and its value) if it is a common option; returns 1 if it did. */
static inline int bench_common_arg(bench_common_opts *o, int argc, char **argv, int *i)
{
    const char *a = argv[*i], *v = *i + 1 < argc ? argv[*i + 1] : NULL;
    if (!strcmp(a, "--min-time"))
        o->min_time = bench_arg_number(a, v);
    else if (!strcmp(a, "--runs"))
        o->runs = (int)bench_arg_number(a, v), o->runs_given = 1;
    else if (!strcmp(a, "--iterations"))
        o->fixed_iters = (long)bench_arg_number(a, v);
    else if (!strcmp(a, "--seed"))
        o->seed = (uint64_t)bench_arg_number(a, v);
    else
        return 0;
    (*i)++;
    return 1;
}

#endif
