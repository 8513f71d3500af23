/* bench_stack — cost of the colours of one stack at one angle (biref_stack_spectrum: the four s/p
 * pairs and one light, transmission and reflection) by the path expansion, numeric integration
 * with 64 samples and the ground truth (16384), on the example stacks (examples/stacks/, run from
 * the source tree) at 0, 30 and 60 degrees; the state is prepared once. Single thread; the
 * median of 5 runs of at least 0.2 s each. Measures, never asserts (docs/STACKS.md §2).
 *
 *   build/bench_stack [--json] */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "biref/biref.h"

static double now(void)
{
    struct timespec t;
    clock_gettime(CLOCK_MONOTONIC, &t);
    return t.tv_sec + 1e-9 * t.tv_nsec;
}

static int cmp(const void *a, const void *b)
{
    double x = *(const double *)a, y = *(const double *)b;
    return (x > y) - (x < y);
}

/* Median seconds per call. */
static double time_call(const biref_spectral *sp, const biref_stack_state *st, const biref_stack_spectrum_opts *o,
                        const biref_light *l, biref_stack_spectrum_info *info)
{
    double runs[5];
    biref_spectrum out;
    double mt[3], mr[3];
    for (int r = 0; r < 5; r++) {
        long n = 0;
        double t0 = now(), t;
        do {
            if (biref_stack_spectrum(sp, st, o, l, &out, mt, mr, info, NULL, 0) != BIREF_OK) return NAN;
            n++;
        } while ((t = now() - t0) < 0.2);
        runs[r] = t / n;
    }
    qsort(runs, 5, sizeof *runs, cmp);
    return runs[2];
}

int main(int argc, char **argv)
{
    const int json = argc > 1 && !strcmp(argv[1], "--json");
    static const char *const names[] = {"lyot_stage1", "film_on_glass",
                                        "solc_folded", "cellophane3",
                                        "quartz_zero_order_halfwave", "quartz_multi_order_halfwave"};
    biref_spectral *sp;
    if (biref_spectral_create(NULL, &sp, NULL, 0) != BIREF_OK) return 1;
    biref_light light;
    const double s_only[2] = {1, 0}, p_only[2] = {0, 1};
    biref_light_sp(s_only, p_only, &light);
    if (json) printf("[\n");
    int first = 1;
    for (int e = 0; e < (int)(sizeof names / sizeof names[0]); e++) {
        char path[256], msg[BIREF_MSG_SIZE];
        snprintf(path, sizeof path, "examples/stacks/%s.json", names[e]);
        biref_stack s;
        if (biref_stack_load(path, &s, msg, sizeof msg) != BIREF_OK) {
            fprintf(stderr, "bench_stack: %s: %s (run from the source tree)\n", path, msg);
            return 1;
        }
        for (int a = 0; a <= 60; a += 30) {
            biref_stack_state st;
            if (biref_stack_prepare(&s, a * M_PI / 180, &st) != BIREF_OK) return 1;
            biref_stack_spectrum_opts ox, on, og;
            biref_stack_spectrum_opts_default(&ox);
            on = og = ox;
            on.method = BIREF_METHOD_NUMERIC;
            og.method = BIREF_METHOD_GROUND_TRUTH;
            biref_stack_spectrum_info info, dummy;
            const double tx = time_call(sp, &st, &ox, &light, &info);
            const double tn = time_call(sp, &st, &on, &light, &dummy);
            const double tg = time_call(sp, &st, &og, &light, &dummy);
            if (json)
                printf("%s  {\"stack\": \"%s\", \"theta_deg\": %d, \"expansion_ms\": %.4f, \"numeric64_ms\": %.4f, "
                       "\"ground_truth_ms\": %.4f, \"groups\": [%d, %d], \"fallback\": %s}",
                       first ? "" : ",\n", names[e], a, 1e3 * tx, 1e3 * tn, 1e3 * tg, info.groups[0], info.groups[1],
                       info.fallback ? "true" : "false");
            else
                printf("%-27s %2d deg: expansion %8.3f ms (%4d + %4d groups%s)  numeric-64 %7.3f ms  ground truth "
                       "%8.3f ms\n",
                       names[e], a, 1e3 * tx, info.groups[0], info.groups[1], info.fallback ? ", FALLBACK" : "",
                       1e3 * tn, 1e3 * tg);
            first = 0;
        }
    }
    if (json) printf("\n]\n");
    biref_spectral_destroy(sp);
    return 0;
}
