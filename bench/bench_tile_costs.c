/* The cost of a frame's tiles, and what sharing them out over P processes would take.
 *
 *   bench_tile_costs [--scene FILE] [--width W] [--height H] [--method analytic|numeric|ground-truth]
 *                    [--samples N] [--antialias none|prefilter] [--tile S] [--json]
 *
 * Renders the frame (default examples/fig9a.json at 1920 x 1080, analytic, prefilter: `biref
 * render`'s defaults) tile by tile on one thread (biref_renderer_render_rect, S x S pixels, default
 * 32 as `mpirun -n P biref render` cuts it) and measures each tile's thread CPU time. Prints the
 * distribution of the tile costs and, for P processes, the efficiency (work / (P x the slowest
 * process's work)) of three ways to give out the tiles, simulated on the measured costs:
 *   contiguous   P equal runs of consecutive tiles (row-major), fixed in advance
 *   interleaved  tile i to process i mod P, fixed in advance
 *   dynamic      the next tile to the first process that is free (what rank 0 does)
 * The simulation leaves out messages and start-up (see docs/CLUSTER.md). */
#define _POSIX_C_SOURCE 200809L /* clock_gettime */
#define BIREF_EXPERIMENTAL_API   /* biref_renderer_render_rect */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "biref/biref.h"

static double thread_ms(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_THREAD_CPUTIME_ID, &ts);
    return 1e3 * (double)ts.tv_sec + 1e-6 * (double)ts.tv_nsec;
}

static int cmp_double(const void *a, const void *b)
{
    const double x = *(const double *)a, y = *(const double *)b;
    return (x > y) - (x < y);
}

/* Efficiency of giving out the tiles one way to p processes: 0 contiguous, 1 interleaved, 2 dynamic. */
static double efficiency(const double *cost, long n, int p, int way)
{
    double *load = calloc((size_t)p, sizeof *load), total = 0;
    for (long i = 0; i < n; i++) {
        int k = 0;
        if (way == 0) k = (int)(i * p / n);
        if (way == 1) k = (int)(i % p);
        if (way == 2)
            for (int q = 1; q < p; q++)
                if (load[q] < load[k]) k = q;
        load[k] += cost[i];
        total += cost[i];
    }
    double worst = 0;
    for (int q = 0; q < p; q++)
        if (load[q] > worst) worst = load[q];
    free(load);
    return worst > 0 ? total / (p * worst) : 1.0;
}

int main(int argc, char **argv)
{
    const char *scene_path = "examples/fig9a.json", *method = "analytic", *aa = "prefilter";
    int W = 1920, H = 1080, T = 32, samples = 64, json = 0;
    for (int i = 1; i < argc; i++) {
        const char *a = argv[i], *v = i + 1 < argc ? argv[i + 1] : NULL;
        if (!strcmp(a, "--json")) json = 1;
        else if (v && !strcmp(a, "--scene")) scene_path = argv[++i];
        else if (v && !strcmp(a, "--width")) W = atoi(argv[++i]);
        else if (v && !strcmp(a, "--height")) H = atoi(argv[++i]);
        else if (v && !strcmp(a, "--tile")) T = atoi(argv[++i]);
        else if (v && !strcmp(a, "--samples")) samples = atoi(argv[++i]);
        else if (v && !strcmp(a, "--method")) method = argv[++i];
        else if (v && !strcmp(a, "--antialias")) aa = argv[++i];
        else {
            fprintf(stderr, "usage: bench_tile_costs [--scene FILE] [--width W] [--height H] [--method M] "
                            "[--samples N] [--antialias none|prefilter] [--tile S] [--json]\n");
            return 2;
        }
    }
    char msg[512];
    biref_scene sc;
    biref_spectral *sp = NULL;
    biref_renderer *r = NULL;
    biref_render_options opt;
    biref_render_options_default(&opt);
    opt.threads = 1;
    opt.samples = samples;
    opt.antialias = strcmp(aa, "none") ? BIREF_ANTIALIAS_PREFILTER : BIREF_ANTIALIAS_NONE;
    if (biref_scene_load(scene_path, &sc, msg, sizeof msg) != BIREF_OK || biref_method_from_name(method, &opt.method) ||
        T < 1 || W < 1 || H < 1) {
        fprintf(stderr, "bench_tile_costs: %s: %s\n", scene_path, msg);
        return 2;
    }
    if (opt.method != BIREF_METHOD_ANALYTIC && opt.method != BIREF_METHOD_EXPANSION) opt.antialias = BIREF_ANTIALIAS_NONE;
    sc.camera.width = W;
    sc.camera.height = H;
    if (biref_spectral_create(NULL, &sp, msg, sizeof msg) != BIREF_OK ||
        biref_renderer_create(sp, &sc, &opt, &r, msg, sizeof msg) != BIREF_OK) {
        fprintf(stderr, "bench_tile_costs: %s\n", msg);
        return 1;
    }
    const int tx = (W + T - 1) / T, ty = (H + T - 1) / T;
    const long n = (long)tx * ty;
    double *cost = malloc((size_t)n * sizeof *cost), *sorted = malloc((size_t)n * sizeof *sorted);
    float *buf = malloc((size_t)T * T * 3 * sizeof *buf);
    if (!cost || !sorted || !buf) return 1;
    double total = 0;
    for (long i = 0; i < n; i++) {
        const int x = (int)(i % tx) * T, y = (int)(i / tx) * T;
        const int w = W - x < T ? W - x : T, h = H - y < T ? H - y : T;
        const double t0 = thread_ms();
        biref_renderer_render_rect(r, x, y, w, h, buf, 3 * (size_t)T, NULL);
        cost[i] = thread_ms() - t0;
        total += cost[i];
    }
    memcpy(sorted, cost, (size_t)n * sizeof *cost);
    qsort(sorted, (size_t)n, sizeof *sorted, cmp_double);
    const double q[5] = {sorted[0], sorted[n / 10], sorted[n / 2], sorted[(n * 9) / 10], sorted[n - 1]};
    static const int P[] = {2, 4, 8, 16, 64};
    static const char *const WAY[] = {"contiguous", "interleaved", "dynamic"};
    if (json) {
        printf("{\"scene\": \"%s\", \"width\": %d, \"height\": %d, \"method\": \"%s\", \"tile\": %d, \"tiles\": %ld, "
               "\"cpu_ms_total\": %.1f, \"tile_ms\": {\"min\": %.3f, \"p10\": %.3f, \"median\": %.3f, \"p90\": %.3f, "
               "\"max\": %.3f}, \"efficiency\": {",
               scene_path, W, H, method, T, n, total, q[0], q[1], q[2], q[3], q[4]);
        for (int k = 0; k < 3; k++) {
            printf("%s\"%s\": {", k ? ", " : "", WAY[k]);
            for (int j = 0; j < 5; j++) printf("%s\"%d\": %.3f", j ? ", " : "", P[j], efficiency(cost, n, P[j], k));
            printf("}");
        }
        printf("}}\n");
    } else {
        printf("%s %dx%d %s, %ld tiles of %dx%d, %.0f ms of CPU on one thread\n", scene_path, W, H, method, n, T, T,
               total);
        printf("tile CPU ms: min %.3f, 10%% %.3f, median %.3f, 90%% %.3f, max %.3f (max/min %.0f)\n", q[0], q[1], q[2],
               q[3], q[4], q[0] > 0 ? q[4] / q[0] : 0.0);
        printf("efficiency   ");
        for (int j = 0; j < 5; j++) printf("  P=%-4d", P[j]);
        printf("\n");
        for (int k = 0; k < 3; k++) {
            printf("%-12s ", WAY[k]);
            for (int j = 0; j < 5; j++) printf("  %5.1f%%", 100.0 * efficiency(cost, n, P[j], k));
            printf("\n");
        }
    }
    free(cost), free(sorted), free(buf);
    biref_renderer_destroy(r);
    biref_spectral_destroy(sp);
    return 0;
}
