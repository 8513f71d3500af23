/* bench_spectral — cost of one shading sample: the band-normalised XYZ integrals of |J|^2 for one
 * angle of incidence, all four input/output polarisation pairs, transmission and reflection
 * (one biref_spectrum, biref_integrate_spectrum of an integrator of each method), by each
 * spectral integration method of the paper's table 1:
 *
 *   analytic      eq. 26, m = 1; five/fourteen table look-ups
 *   numeric-N     N = 3, 8, 32, 128, 512 midpoint samples
 *   ground-truth  numeric with N = 16384 (paper §6)
 *
 * Every method is timed twice: with biref_slab_prepare in the loop (a renderer's shading sample:
 * a new angle per pixel, so modes and Fresnel coefficients are recomputed) and on states prepared
 * beforehand (the integration alone). Ratios are taken within one run of one process, so they are
 * comparable; the paper's comparison is analytic vs numeric-8 (1.09 ms vs 1.73 ms per frame).
 *
 *   expansion     the exact integral of the path-group expansion (beyond the paper; default options)
 *
 * Inputs: the paper's fig. 9 materials at random angles 0-70 deg (the analytic method's stated
 * domain; --theta-max-deg 85 for the expansion's acceptance range, where the expansion's cost rises) and random
 * rotations of the optic axis about the surface normal y, generated before timing from a fixed
 * seed. Single thread; measures, never asserts.
 *
 * --truncation measures accuracy instead of time: the expansion's adaptive orders against order
 * 8 on the same draws (docs/PHYSICS.md section 5). */
/* Times the methods one by one and the expansion's tail: unstable API. */
#define BIREF_EXPERIMENTAL_API
#include <complex.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "biref/biref.h"

#include "bench_clock.h"

enum { POOL_DEFAULT = 256, POOL_MAX = 1 << 16 }; /* powers of two; 256 prepared states (~350 KB) stay in L2 */

/* Fig. 9 (a), (b), (c): eta_o, eta_e, A, d. */
static const struct {
    double eta_o, eta_e, axis[3], d_nm;
} FIG9[3] = {
    {1.40, 1.38, {-0.54, 0.80, 0.27}, 1.25e6},
    {1.50, 1.51, {0.25, 0.97, 0.0}, 3.5e6},
    {1.775, 1.231, {0.084, 0.979, -0.187}, 1.15e6},
};

typedef enum { M_PREPARE, M_ANALYTIC, M_NUMERIC, M_EXPANSION } kind;

typedef struct {
    int pool; /* number of draws, a power of two */
    biref_slab *slab;
    double *theta;
    biref_slab_state *state;
    const biref_spectral *sp;
    const biref_integrator *integrator; /* NULL: prepare only */
    int with_prepare;
    long failures;
} ctx;

static void make_pool(ctx *c, uint64_t seed, double theta_max_deg)
{
    bench_rng g = {seed};
    for (int k = 0; k < c->pool; k++) {
        int m = (int)(bench_rng_next(&g) % 3);
        double phi = bench_rng_uniform(&g, 0.0, 2.0 * M_PI), cp = cos(phi), sp = sin(phi);
        const double *A = FIG9[m].axis;
        biref_slab *s = &c->slab[k];
        s->eta_o = FIG9[m].eta_o;
        s->eta_e = FIG9[m].eta_e;
        /* Rotation about y (the surface normal): the slab turned in its own plane. */
        s->axis[0] = cp * A[0] + sp * A[2];
        s->axis[1] = A[1];
        s->axis[2] = -sp * A[0] + cp * A[2];
        s->thickness_nm = FIG9[m].d_nm;
        s->eta_i = 1.0;
        c->theta[k] = bench_rng_uniform(&g, 0.0, theta_max_deg * M_PI / 180.0);
    }
}

/* One shading sample per iteration: the four s/p pairs of T and R through the method's integrator
 * (biref_integrate_spectrum); the checksum adds one dependent addition per sample. */
static double run(void *vctx, long iters)
{
    ctx *c = vctx;
    double acc = 0.0;
    for (long i = 0; i < iters; i++) {
        size_t k = (size_t)i & (size_t)(c->pool - 1);
        biref_slab_state local;
        const biref_slab_state *st = &c->state[k];
        if (c->with_prepare) {
            if (biref_slab_prepare(&c->slab[k], c->theta[k], &local) != BIREF_OK) {
                c->failures++;
                continue;
            }
            st = &local;
        }
        if (!c->integrator) {
            acc += creal(st->top.t_down[0][0]);
            continue;
        }
        biref_spectrum out;
        (void)biref_integrate_spectrum(c->integrator, st, &out);
        acc += out.T[0][1][1] + out.R[1][0][2];
    }
    return acc;
}

static void usage(FILE *f)
{
    fprintf(f,
            "usage: bench_spectral [--min-time S] [--runs N] [--iterations N] [--seed N] [--no-ground-truth]\n"
            "                      [--theta-max-deg A] [--draws N] [--truncation] [--method NAME] [--json]\n"
            "  --min-time S        seconds per timed run after calibration (default 0.5)\n"
            "  --runs N            timed runs per method; the median is reported (default 5;\n"
            "                      ground truth uses min(N, 3))\n"
            "  --iterations N      fixed samples per run, no calibration (default runs 1; for\n"
            "                      valgrind --tool=callgrind, whose counts do not depend on load)\n"
            "  --seed N            seed of the random angles and axis rotations (default 1)\n"
            "  --theta-max-deg A   angles uniform in 0-A deg, 0 < A < 90 (default 70; 85 for the expansion's range)\n"
            "  --draws N           random slab states cycled through, a power of two <= 65536\n"
            "                      (default 256; more for a steadier mean when the cost varies)\n"
            "  --no-ground-truth   skip the 16384-sample reference (about 10 s)\n"
            "  --truncation        no timing: the expansion's default (adaptive) result against order 8\n"
            "                      on the draws, relative to the light of the orders it covers\n"
            "  --method NAME       only prepare, analytic and NAME (numeric-8, ground-truth, ...),\n"
            "                      e.g. to profile one method under perf\n"
            "  --json              {\"methods\":[{\"method\",\"ns_per_sample\",\"ratio_to_analytic\",...}]}\n");
}

/* Worst relative difference, per form (input s/p x output s/p, T and R) and band, between the
 * expansion with default options and with every pair up to order 8, divided by the incoherent
 * energy of the orders the expansion covers (reflection: without the direct reflection, which
 * both include exactly). Split at theta = 70 deg. */
static int truncation(const ctx *c, double theta_max_deg, int json)
{
    biref_expansion_opts adaptive, full;
    biref_expansion_opts_default(&adaptive);
    biref_expansion_opts_default(&full);
    full.order = BIREF_EXPANSION_MAX_ORDER;
    double worst[2] = {0, 0};
    long over[2][3] = {{0}}, n[2] = {0, 0}; /* states with a worst error > 1e-3, 1e-2, 3e-2 */
    for (int k = 0; k < c->pool; k++) {
        biref_spectrum a, f;
        if (biref_spectrum_expansion(c->sp, &c->state[k], &adaptive, &a) != BIREF_OK ||
            biref_spectrum_expansion(c->sp, &c->state[k], &full, &f) != BIREF_OK)
            return 1;
        double w = 0;
        for (int which = 0; which < 2; which++)
            for (int i = 0; i < 2; i++)
                for (int o = 0; o < 2; o++) {
                    const double complex Ci[2][2] = {{i == 0, 0}, {0, i == 1}}, Po[2][2] = {{o == 0, 0}, {0, o == 1}};
                    double covered[3];
                    biref_expansion_tail(c->sp, &c->state[k], which, Ci, Po, which == BIREF_TRANSMISSION ? -1 : 0,
                                         covered);
                    const double *x = which ? a.R[i][o] : a.T[i][o], *y = which ? f.R[i][o] : f.T[i][o];
                    for (int j = 0; j < 3; j++) w = fmax(w, fabs(x[j] - y[j]) / covered[j]);
                }
        int r = c->theta[k] >= 70.0 * M_PI / 180.0;
        n[r]++;
        worst[r] = fmax(worst[r], w);
        over[r][0] += w > 1e-3, over[r][1] += w > 1e-2, over[r][2] += w > 3e-2;
    }
    static const char *const RANGE[2] = {"0-70", "70-max"};
    if (json) {
        printf("{\"benchmark\":\"bench_spectral\",\"truncation\":[");
        for (int r = 0; r < 2; r++)
            printf("%s{\"theta_deg\":\"%s\",\"states\":%ld,\"worst_relative\":%.6g,\"over_1e-3\":%ld,"
                   "\"over_1e-2\":%ld,\"over_3e-2\":%ld}",
                   r ? "," : "", RANGE[r], n[r], worst[r], over[r][0], over[r][1], over[r][2]);
        printf("],\"theta_max_deg\":%g,\"pool\":%d}\n", theta_max_deg, c->pool);
        return 0;
    }
    printf("bench_spectral --truncation: expansion, default options vs order %d, %d draws, theta 0-%g deg\n",
           BIREF_EXPANSION_MAX_ORDER, c->pool, theta_max_deg);
    printf("  theta range  states  worst relative error  states > 1e-3  > 1e-2  > 3e-2\n");
    for (int r = 0; r < 2; r++)
        printf("  %-11s %7ld  %20.4g  %13ld  %6ld  %6ld\n", RANGE[r], n[r], worst[r], over[r][0], over[r][1],
               over[r][2]);
    return 0;
}

typedef struct {
    const char *name;
    kind what;
    int samples; /* numeric only */
    int enabled;
    bench_result with, without;
} row;

int main(int argc, char **argv)
{
    bench_common_opts common;
    bench_common_defaults(&common);
    int json = 0, ground_truth = 1, truncation_only = 0;
    const char *only = NULL; /* --method: measure prepare, analytic and this one (for profiling) */
    double theta_max_deg = 70.0;
    int pool = POOL_DEFAULT;
    for (int i = 1; i < argc; i++) {
        const char *a = argv[i], *v = i + 1 < argc ? argv[i + 1] : NULL;
        if (bench_common_arg(&common, argc, argv, &i)) {
            continue;
        } else if (!strcmp(a, "--method")) {
            if (!v) {
                fprintf(stderr, "--method needs a name\n");
                return 2;
            }
            only = v;
            i++;
        } else if (!strcmp(a, "--theta-max-deg")) {
            theta_max_deg = bench_arg_number(a, v);
            if (!(theta_max_deg > 0.0 && theta_max_deg < 90.0)) {
                fprintf(stderr, "bench_spectral: --theta-max-deg must be in (0, 90)\n");
                return 2;
            }
            i++;
        } else if (!strcmp(a, "--draws")) {
            double n = bench_arg_number(a, v);
            pool = (int)n;
            if (!(n >= 1 && n <= POOL_MAX) || n != pool || (pool & (pool - 1))) {
                fprintf(stderr, "bench_spectral: --draws must be a power of two in 1-%d\n", POOL_MAX);
                return 2;
            }
            i++;
        } else if (!strcmp(a, "--truncation")) {
            truncation_only = 1;
        } else if (!strcmp(a, "--no-ground-truth")) {
            ground_truth = 0;
        } else if (!strcmp(a, "--json")) {
            json = 1;
        } else if (!strcmp(a, "--help") || !strcmp(a, "-h")) {
            usage(stdout);
            return 0;
        } else {
            fprintf(stderr, "bench_spectral: unknown option %s\n", a);
            usage(stderr);
            return 2;
        }
    }
    double min_time = common.min_time;
    int runs = common.runs, runs_given = common.runs_given;
    long fixed_iters = common.fixed_iters;
    uint64_t seed = common.seed;

    /* Method names checked before anything is allocated, so a typo exits cleanly. */
    static const char *const NAMES[] = {"analytic",    "numeric-3",   "numeric-8", "numeric-32",
                                        "numeric-128", "numeric-512", "expansion", "ground-truth"};
    if (only) {
        int known = 0;
        for (size_t n = 0; n < sizeof NAMES / sizeof NAMES[0]; n++) known |= !strcmp(only, NAMES[n]);
        if (!known) {
            fprintf(stderr, "bench_spectral: unknown method %s\n", only);
            return 2;
        }
    }
    if (fixed_iters > 0 && !runs_given) runs = 1;

    biref_spectral *sp = NULL;
    char why[BIREF_MSG_SIZE];
    if (biref_spectral_create(NULL, &sp, why, sizeof why) != BIREF_OK) {
        fprintf(stderr, "bench_spectral: %s\n", why);
        return 1;
    }
    ctx *c = calloc(1, sizeof *c);
    if (!c) return 1;
    c->pool = pool;
    c->state = calloc((size_t)pool, sizeof *c->state);
    c->slab = calloc((size_t)pool, sizeof *c->slab);
    c->theta = calloc((size_t)pool, sizeof *c->theta);
    if (!c->state || !c->slab || !c->theta) return 1;
    c->sp = sp;
    make_pool(c, seed, theta_max_deg);
    for (int k = 0; k < pool; k++)
        if (biref_slab_prepare(&c->slab[k], c->theta[k], &c->state[k]) != BIREF_OK) {
            fprintf(stderr, "bench_spectral: input %d rejected by biref_slab_prepare\n", k);
            return 1;
        }
    if (truncation_only) {
        int rc = truncation(c, theta_max_deg, json);
        free(c->state);
        free(c->slab);
        free(c->theta);
        free(c);
        biref_spectral_destroy(sp);
        return rc;
    }

    /* Rows 0 (prepare) and 1 (analytic) are always measured: every ratio refers to row 1. */
    row rows[] = {
        {.name = "prepare", .what = M_PREPARE},
        {.name = "analytic", .what = M_ANALYTIC},
        {.name = "numeric-3", .what = M_NUMERIC, .samples = 3},
        {.name = "numeric-8", .what = M_NUMERIC, .samples = 8},
        {.name = "numeric-32", .what = M_NUMERIC, .samples = 32},
        {.name = "numeric-128", .what = M_NUMERIC, .samples = 128},
        {.name = "numeric-512", .what = M_NUMERIC, .samples = 512},
        {.name = "expansion", .what = M_EXPANSION},
        {.name = "ground-truth", .what = M_NUMERIC, .samples = BIREF_GROUND_TRUTH_SAMPLES},
    };
    const int nrows = (int)(sizeof rows / sizeof rows[0]);
    for (int r = 0; r < nrows; r++)
        rows[r].enabled = r < 2 || (only ? !strcmp(only, rows[r].name) : ground_truth || r < nrows - 1);

    for (int r = 0; r < nrows; r++) {
        if (!rows[r].enabled) continue;
        biref_integrator *integrator = NULL;
        if (rows[r].what != M_PREPARE) {
            /* The expansion with its default options (adaptive, tolerance 1e-3). */
            biref_integrator_options io;
            biref_integrator_options_default(&io);
            io.method = rows[r].what == M_ANALYTIC    ? BIREF_METHOD_ANALYTIC
                        : rows[r].what == M_EXPANSION ? BIREF_METHOD_EXPANSION
                                                      : BIREF_METHOD_NUMERIC;
            io.samples = rows[r].samples;
            if (biref_integrator_create(sp, &io, &integrator, why, sizeof why) != BIREF_OK) {
                fprintf(stderr, "bench_spectral: cannot set up %s: %s\n", rows[r].name, why);
                return 1;
            }
        }
        c->integrator = integrator;
        /* Fewer repetitions for the 16384-sample reference: one run already takes min_time. */
        int n_runs = rows[r].samples == BIREF_GROUND_TRUTH_SAMPLES && runs > 3 ? 3 : runs;
        c->with_prepare = 1;
        rows[r].with = bench_measure(run, c, min_time, n_runs, fixed_iters);
        if (rows[r].what != M_PREPARE) {
            c->with_prepare = 0;
            rows[r].without = bench_measure(run, c, min_time, n_runs, fixed_iters);
        }
        biref_integrator_destroy(integrator);
    }
    const double ref = rows[1].with.ns_median, ref_np = rows[1].without.ns_median;

    if (json) {
        printf("{\"benchmark\":\"bench_spectral\",\"seed\":%llu,\"pool\":%d,\"theta_max_deg\":%g,\"prepare_ns\":%.2f,\"methods\":[",
               (unsigned long long)seed, pool, theta_max_deg, rows[0].with.ns_median);
        for (int r = 1; r < nrows; r++) { /* row 1 (analytic) is always enabled: it opens the list */
            if (!rows[r].enabled) continue;
            printf("%s{\"method\":\"%s\",\"ns_per_sample\":%.2f,\"ratio_to_analytic\":%.4f,"
                   "\"ns_per_sample_no_prepare\":%.2f,\"ratio_to_analytic_no_prepare\":%.4f,\"runs\":%d,"
                   "\"cpu_share\":%.3f}",
                   r > 1 ? "," : "", rows[r].name, rows[r].with.ns_median, rows[r].with.ns_median / ref,
                   rows[r].without.ns_median, rows[r].without.ns_median / ref_np, rows[r].with.runs,
                   fmin(rows[r].with.cpu_share, rows[r].without.cpu_share));
        }
        printf("],\"failures\":%ld,\"checksum\":%.17g}\n", c->failures, bench_sink);
    } else {
        printf("bench_spectral: one shading sample = XYZ of |J|^2 for 2 inputs x 2 outputs, T and R; single thread\n");
        printf("  inputs: %d draws of the fig. 9 slabs, theta 0-%g deg, axis rotated about y, seed %llu\n", pool,
               theta_max_deg, (unsigned long long)seed);
        printf("  biref_slab_prepare alone: %.1f ns (median of %d runs)\n", rows[0].with.ns_median, rows[0].with.runs);
        printf("  %-14s %14s %10s %16s %10s %5s %6s\n", "method", "ns/sample", "ratio", "ns w/o prepare", "ratio",
               "runs", "cpu%");
        double worst_share = rows[0].with.cpu_share;
        for (int r = 1; r < nrows; r++) {
            if (!rows[r].enabled) continue;
            double share = fmin(rows[r].with.cpu_share, rows[r].without.cpu_share);
            printf("  %-14s %14.1f %10.2f %16.1f %10.2f %5d %6.1f\n", rows[r].name, rows[r].with.ns_median,
                   rows[r].with.ns_median / ref, rows[r].without.ns_median, rows[r].without.ns_median / ref_np,
                   rows[r].with.runs, 100.0 * share);
            if (share < worst_share) worst_share = share;
        }
        printf("  ratio = ns / ns(analytic) in the same column; with prepare = full shading sample\n");
        if (rows[3].enabled)
            printf("  paper table 1 (GPU frame times): numeric-8 / analytic = 1.73 / 1.09 = %.2f; here %.2f (with "
                   "prepare), %.2f (without)\n",
                   1.73 / 1.09, rows[3].with.ns_median / ref, rows[3].without.ns_median / ref_np);
        if (worst_share < BENCH_CPU_SHARE_OK)
            printf("  WARNING: a run got only %.0f%% of a core (cpu%%): the machine was busy; repeat\n",
                   100.0 * worst_share);
        printf("  failures %ld, checksum %.17g\n", c->failures, bench_sink);
    }
    free(c->state);
    free(c->slab);
    free(c->theta);
    free(c);
    biref_spectral_destroy(sp);
    return 0;
}
