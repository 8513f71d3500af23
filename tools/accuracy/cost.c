/* Cost per shading sample (see cost.h).
 *
 * Method. A case is one loop over the pool (prepare only, a method on prepared states, or prepare
 * plus the method). Its iteration count is grown until one run lasts `min_time`; then `runs` runs
 * of that count are timed with CLOCK_MONOTONIC and the median ns per sample is kept. The median,
 * because on a shared machine the noise is one-sided (a preempted run is only ever slower). Each
 * run also reads the thread's CPU clock: a CPU/wall share well below 1 means another process took
 * the core during the run. Results feed a volatile sink so that no call can be optimised away. */
#include "cost.h"

#include <complex.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <time.h>

#include "cli_common.h"

enum { MAX_RUNS = 64 };

typedef struct {
    const acc_cost_pool *pool;
    const biref_slab_state *states;    /* the pool, prepared beforehand */
    const biref_integrator *integrator; /* NULL: prepare only */
    int with_prepare;
} cost_case;

static volatile double cost_sink;

static double clock_s(clockid_t id)
{
    struct timespec ts;
    clock_gettime(id, &ts);
    return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}

/* The timed loop. Kept out of line and called exactly once per timed run so that
 * `valgrind --tool=callgrind --toggle-collect=acc_cost_loop --dump-after=acc_cost_loop` counts the
 * instructions of each case separately (one dump per call). The pool index wraps without a
 * division. */
static __attribute__((noinline)) double acc_cost_loop(const cost_case *c, long iters)
{
    double acc = 0.0;
    int k = 0;
    for (long i = 0; i < iters; i++) {
        biref_slab_state local;
        const biref_slab_state *st = &c->states[k];
        if (c->with_prepare) {
            /* Every pool entry prepared successfully before timing (acc_cost_measure). */
            (void)biref_slab_prepare(&c->pool->slab[k], c->pool->theta[k], &local);
            st = &local;
        }
        if (++k == c->pool->n) k = 0;
        if (!c->integrator) {
            acc += creal(st->top.t_down[0][0]) + creal(st->opl_down[1]);
            continue;
        }
        biref_spectrum out;
        (void)biref_integrate_spectrum(c->integrator, st, &out);
        acc += out.T[0][1][1] + out.R[1][0][2];
    }
    return acc;
}

static int cmp_double(const void *a, const void *b)
{
    double x = *(const double *)a, y = *(const double *)b;
    return (x > y) - (x < y);
}

static acc_cost_time time_case(const cost_case *c, const acc_cost_opts *o)
{
    acc_cost_time t = {0};
    long iters = o->fixed_iters > 0 ? o->fixed_iters : 1;
    int runs = o->fixed_iters > 0 ? 1 : (o->runs < 1 ? 1 : (o->runs > MAX_RUNS ? MAX_RUNS : o->runs));
    if (o->fixed_iters <= 0) {
        /* Calibration, which also warms caches and the branch predictors. */
        for (;;) {
            double t0 = clock_s(CLOCK_MONOTONIC);
            cost_sink += acc_cost_loop(c, iters);
            double dt = clock_s(CLOCK_MONOTONIC) - t0;
            if (dt >= o->min_time) break;
            double f = dt > 0.0 ? 1.2 * o->min_time / dt : 100.0;
            iters = (long)ceil((double)iters * fmin(fmax(f, 2.0), 100.0));
        }
        /* Whole passes over the pool once a run covers it: then every run averages over exactly
         * the same states, which matters when the cost varies a lot between states. */
        if (iters > c->pool->n) iters = (iters + c->pool->n - 1) / c->pool->n * c->pool->n;
    }
    double ns[MAX_RUNS];
    t.cpu_share = 1.0;
    for (int r = 0; r < runs; r++) {
        double w0 = clock_s(CLOCK_MONOTONIC), c0 = clock_s(CLOCK_THREAD_CPUTIME_ID);
        cost_sink += acc_cost_loop(c, iters);
        double cpu = clock_s(CLOCK_THREAD_CPUTIME_ID) - c0, w = clock_s(CLOCK_MONOTONIC) - w0;
        ns[r] = 1e9 * w / (double)iters;
        if (w > 0.0) t.cpu_share = fmin(t.cpu_share, cpu / w);
    }
    qsort(ns, (size_t)runs, sizeof ns[0], cmp_double);
    t.ns_median = runs % 2 ? ns[runs / 2] : 0.5 * (ns[runs / 2 - 1] + ns[runs / 2]);
    t.ns_min = ns[0];
    t.iters = iters;
    return t;
}

static void report(const acc_cost_opts *o, const char *name, const char *what, const acc_cost_time *t)
{
    biref_progress_bar_message(o->progress, "cost %-14s %-13s %12.1f ns per sample (cpu share %.2f)", name, what,
                               t->ns_median, t->cpu_share);
}

int acc_cost_measure(const acc_cost_pool *pool, const acc_cost_opts *o, acc_cost_time *prepare, acc_cost_row *rows,
                     int nrows)
{
    biref_slab_state *states = malloc((size_t)pool->n * sizeof *states);
    if (!states) return cli_error("accuracy", "out of memory"), -1;
    for (int k = 0; k < pool->n; k++)
        if (biref_slab_prepare(&pool->slab[k], pool->theta[k], &states[k]) != BIREF_OK) {
            free(states);
            return cli_error("accuracy", "--cost: cannot prepare the slab at theta %g deg",
                             pool->theta[k] * 180.0 / M_PI),
                   -1;
        }
    cost_case c = {pool, states, NULL, 1};
    if (prepare) {
        *prepare = time_case(&c, o);
        report(o, "prepare", "alone", prepare);
    }
    for (int r = 0; r < nrows; r++) {
        c.integrator = rows[r].integrator;
        c.with_prepare = 0;
        rows[r].alone = time_case(&c, o);
        report(o, rows[r].name, "alone", &rows[r].alone);
        c.with_prepare = 1;
        rows[r].with_prepare = time_case(&c, o);
        report(o, rows[r].name, "with prepare", &rows[r].with_prepare);
    }
    free(states);
    return 0;
}
