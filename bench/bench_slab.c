/* bench_slab — cost of one (theta, lambda) evaluation of the slab's Jones matrices J_T and J_R.
 *
 *   (a) prepare+at : biref_slab_prepare + biref_slab_jones_at (closed form; the full cost of a
 *                    sample whose angle differs from the previous one, as in a renderer)
 *   (b) at         : biref_slab_jones_at alone (the per-wavelength cost once theta is fixed,
 *                    i.e. the inner loop of numeric spectral integration)
 *   (c) tmm        : biref_slab_jones_tmm (4x4 Berreman matrix, LAPACK zgeev/zgetrf/zgesv)
 *
 * Measures, never asserts: single thread, one process, so the ratios between the cases are
 * comparable. Inputs (random slabs, angles, wavelengths) are generated before timing from a
 * fixed seed and cycled through a small pool that stays in L2, so neither the generator nor
 * main-memory traffic is timed.
 *
 * Heap check: with --iterations N the loop count is fixed (no calibration) and nothing is
 * allocated per iteration by this program, so under valgrind the "total heap usage" line must
 * not change between N = 1e3 and N = 1e5 if the library's closed-form path does not allocate:
 *   valgrind ./bench_slab --closed-form-only --iterations 1000
 *   valgrind ./bench_slab --closed-form-only --iterations 100000
 * (glibc has no malloc hooks any more and replacing malloc inside this executable is not
 * portable C, so the external tool is the robust way.) */
#include <complex.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "biref/biref.h"

#include "bench_clock.h"

/* Power of two (index by mask). 256 prepared states are ~350 KB: resident in L2 on common CPUs,
 * large enough that the branch predictor cannot learn one input. */
enum { POOL = 256 };

typedef struct {
    biref_slab slab[POOL];
    double theta[POOL];
    double lambda[POOL];
    biref_slab_state *state; /* prepared once, for case (b) */
    long failures;           /* non-OK statuses seen in timed loops (tmm may refuse some inputs) */
} pool;

static void make_pool(pool *p, uint64_t seed)
{
    bench_rng g = {seed};
    for (int k = 0; k < POOL; k++) {
        biref_slab *s = &p->slab[k];
        /* Indices from weakly to strongly birefringent (the paper's fig. 9c has 1.775 / 1.231). */
        s->eta_o = bench_rng_uniform(&g, 1.2, 1.8);
        s->eta_e = bench_rng_uniform(&g, 1.2, 1.8);
        /* Isotropic direction by rejection from the unit ball (no trig, exact distribution). */
        double r2;
        do {
            for (int i = 0; i < 3; i++) s->axis[i] = bench_rng_uniform(&g, -1.0, 1.0);
            r2 = s->axis[0] * s->axis[0] + s->axis[1] * s->axis[1] + s->axis[2] * s->axis[2];
        } while (r2 > 1.0 || r2 < 1e-6);
        /* Log-uniform 10 um .. 5 mm: thin films to the paper's millimetre slabs. */
        s->thickness_nm = exp(bench_rng_uniform(&g, log(1.0e4), log(5.0e6)));
        s->eta_i = 1.0;
        p->theta[k] = bench_rng_uniform(&g, 0.0, 80.0 * M_PI / 180.0);
        p->lambda[k] = bench_rng_uniform(&g, 380.0, 700.0);
    }
}

/* Checksum terms: two entries only, so the accumulation adds one dependent addition per call
 * (summing all eight would put a long add chain into the timed loop). */
static inline double jones_sum(const biref_jones *T, const biref_jones *R)
{
    return creal(T->m[0][0]) + cimag(R->m[1][0]);
}

static double case_prepare_at(void *ctx, long iters)
{
    pool *p = ctx;
    double acc = 0.0;
    for (long i = 0; i < iters; i++) {
        size_t k = (size_t)i & (POOL - 1);
        biref_slab_state st;
        biref_jones T, R;
        if (biref_slab_prepare(&p->slab[k], p->theta[k], &st) != BIREF_OK) {
            p->failures++;
            continue;
        }
        biref_slab_jones_at(&st, p->lambda[k], &T, &R);
        acc += jones_sum(&T, &R);
    }
    return acc;
}

static double case_at(void *ctx, long iters)
{
    pool *p = ctx;
    double acc = 0.0;
    for (long i = 0; i < iters; i++) {
        size_t k = (size_t)i & (POOL - 1);
        /* A different wavelength than the state's partner in (a): decorrelates the two loops. */
        size_t l = (size_t)(i * 7) & (POOL - 1);
        biref_jones T, R;
        biref_slab_jones_at(&p->state[k], p->lambda[l], &T, &R);
        acc += jones_sum(&T, &R);
    }
    return acc;
}

static double case_tmm(void *ctx, long iters)
{
    pool *p = ctx;
    double acc = 0.0;
    for (long i = 0; i < iters; i++) {
        size_t k = (size_t)i & (POOL - 1);
        biref_jones T, R;
        if (biref_slab_jones_tmm(&p->slab[k], p->theta[k], p->lambda[k], &T, &R) != BIREF_OK) {
            p->failures++;
            continue;
        }
        acc += jones_sum(&T, &R);
    }
    return acc;
}

static void usage(FILE *f)
{
    fprintf(f,
            "usage: bench_slab [--min-time S] [--runs N] [--iterations N] [--seed N]\n"
            "                  [--closed-form-only | --tmm-only | --case NAME] [--json]\n"
            "  --min-time S        seconds per timed run after calibration (default 0.5)\n"
            "  --runs N            timed runs per case; the median is reported (default 5)\n"
            "  --iterations N      fixed calls per run, no calibration (default runs 1; for valgrind)\n"
            "  --seed N            seed of the random slabs, angles and wavelengths (default 1)\n"
            "  --closed-form-only  only cases (a) prepare+at and (b) at\n"
            "  --tmm-only          only case (c) tmm\n"
            "  --case NAME         only one case: prepare+at, at or tmm (e.g. for perf record)\n"
            "  --json              machine-readable output\n");
}

int main(int argc, char **argv)
{
    bench_common_opts common;
    bench_common_defaults(&common);
    int json = 0, do_closed = 1, do_tmm = 1;
    const char *only = NULL; /* --case: a single case, e.g. to profile it under perf */
    for (int i = 1; i < argc; i++) {
        const char *a = argv[i], *v = i + 1 < argc ? argv[i + 1] : NULL;
        if (bench_common_arg(&common, argc, argv, &i)) {
            continue;
        } else if (!strcmp(a, "--case")) {
            if (!v) {
                fprintf(stderr, "--case needs a name\n");
                return 2;
            }
            only = v;
            i++;
        } else if (!strcmp(a, "--closed-form-only")) {
            do_tmm = 0;
        } else if (!strcmp(a, "--tmm-only")) {
            do_closed = 0;
        } else if (!strcmp(a, "--json")) {
            json = 1;
        } else if (!strcmp(a, "--help") || !strcmp(a, "-h")) {
            usage(stdout);
            return 0;
        } else {
            fprintf(stderr, "bench_slab: unknown option %s\n", a);
            usage(stderr);
            return 2;
        }
    }
    double min_time = common.min_time;
    int runs = common.runs, runs_given = common.runs_given;
    long fixed_iters = common.fixed_iters;
    uint64_t seed = common.seed;
    if (!do_closed && !do_tmm) {
        fprintf(stderr, "bench_slab: --closed-form-only and --tmm-only exclude each other\n");
        return 2;
    }
    /* Names checked before anything is allocated, so a typo exits cleanly (also under ASan). */
    if (only && strcmp(only, "prepare+at") && strcmp(only, "at") && strcmp(only, "tmm")) {
        fprintf(stderr, "bench_slab: unknown case %s (prepare+at, at, tmm)\n", only);
        return 2;
    }
    if (fixed_iters > 0 && !runs_given) runs = 1;

    /* The pool is allocated here, before any timed loop: its allocations are a constant of the
     * heap-usage count, independent of --iterations. */
    pool *p = calloc(1, sizeof *p);
    if (!p) return 1;
    p->state = calloc(POOL, sizeof *p->state);
    if (!p->state) return 1;
    make_pool(p, seed);
    for (int k = 0; k < POOL; k++)
        if (biref_slab_prepare(&p->slab[k], p->theta[k], &p->state[k]) != BIREF_OK) {
            fprintf(stderr, "bench_slab: random slab %d rejected by biref_slab_prepare\n", k);
            return 1;
        }

    struct {
        const char *name, *label;
        bench_case_fn fn;
        int enabled;
        bench_result r;
        long failures;
    } cases[] = {
        {.name = "prepare+at", .label = "(a) closed form: prepare + jones_at", .fn = case_prepare_at,
         .enabled = do_closed},
        {.name = "at", .label = "(b) closed form: jones_at (theta fixed)", .fn = case_at, .enabled = do_closed},
        {.name = "tmm", .label = "(c) Berreman 4x4 + LAPACK (jones_tmm)", .fn = case_tmm, .enabled = do_tmm},
    };
    const int ncases = (int)(sizeof cases / sizeof cases[0]);
    if (only) {
        for (int c = 0; c < ncases; c++) cases[c].enabled = !strcmp(only, cases[c].name);
        do_closed = do_tmm = 0; /* no ratios: they need several cases */
    }
    for (int c = 0; c < ncases; c++) {
        if (!cases[c].enabled) continue;
        p->failures = 0;
        cases[c].r = bench_measure(cases[c].fn, p, min_time, runs, fixed_iters);
        cases[c].failures = p->failures;
    }

    if (json) {
        printf("{\"benchmark\":\"bench_slab\",\"seed\":%llu,\"pool\":%d,\"cases\":[", (unsigned long long)seed, POOL);
        int first = 1;
        for (int c = 0; c < ncases; c++) {
            if (!cases[c].enabled) continue;
            printf("%s{\"case\":\"%s\",\"ns_per_call\":%.2f,\"ns_min\":%.2f,\"ns_max\":%.2f,\"iterations\":%ld,"
                   "\"runs\":%d,\"cpu_share\":%.3f,\"failures\":%ld}",
                   first ? "" : ",", cases[c].name, cases[c].r.ns_median, cases[c].r.ns_min, cases[c].r.ns_max,
                   cases[c].r.iters, cases[c].r.runs, cases[c].r.cpu_share, cases[c].failures);
            first = 0;
        }
        printf("],\"checksum\":%.17g}\n", bench_sink);
    } else {
        printf("bench_slab: one (theta, lambda) evaluation of J_T and J_R, single thread\n");
        printf("  %d random slabs (eta 1.2-1.8, random axis, d 10 um-5 mm), theta 0-80 deg, lambda 380-700 nm,"
               " seed %llu\n", POOL, (unsigned long long)seed);
        printf("  %-42s %10s %10s %10s %11s %4s %5s %8s\n", "case", "ns/call", "min", "max", "iters/run", "runs",
               "cpu%", "failures");
        double worst_share = 1.0;
        for (int c = 0; c < ncases; c++) {
            if (!cases[c].enabled) continue;
            printf("  %-42s %10.1f %10.1f %10.1f %11ld %4d %5.1f %8ld\n", cases[c].label, cases[c].r.ns_median,
                   cases[c].r.ns_min, cases[c].r.ns_max, cases[c].r.iters, cases[c].r.runs,
                   100.0 * cases[c].r.cpu_share, cases[c].failures);
            if (cases[c].r.cpu_share < worst_share) worst_share = cases[c].r.cpu_share;
        }
        if (worst_share < BENCH_CPU_SHARE_OK)
            printf("  WARNING: a run got only %.0f%% of a core (cpu%%): the machine was busy; repeat\n",
                   100.0 * worst_share);
        if (do_closed && do_tmm) {
            printf("  ratio tmm / (prepare+at) = %.2f, (prepare+at) / at = %.2f, prepare alone ~ %.1f ns\n",
                   cases[2].r.ns_median / cases[0].r.ns_median, cases[0].r.ns_median / cases[1].r.ns_median,
                   cases[0].r.ns_median - cases[1].r.ns_median);
        } else if (do_closed && !do_tmm) {
            printf("  ratio (prepare+at) / at = %.2f, prepare alone ~ %.1f ns\n",
                   cases[0].r.ns_median / cases[1].r.ns_median, cases[0].r.ns_median - cases[1].r.ns_median);
        }
        printf("  checksum %.17g\n", bench_sink);
    }
    free(p->state);
    free(p);
    return 0;
}
