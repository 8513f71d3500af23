/* Cost of the closed forms with dispersion (docs/PHYSICS.md §7, docs/PERFORMANCE.md): per study
 * plate of docs/ACCURACY-DISPERSION.md, ns per call of biref_integrate_material_spectrum with the
 * analytic method and the expansion, against the same slab with its indices fixed at 550 nm
 * (biref_slab_prepare + biref_integrate_spectrum, the same scalar path a renderer's dispersive
 * hits take). Inputs: 256 draws of optic axis (uniform on the sphere) and angle (0-70 deg) per
 * plate, cycled. Measures and never asserts; one thread.
 *
 *   bench_dispersion [--min-time S] [--runs N] [--iterations N] [--seed N] [--json] */
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "biref/biref.h"
#include "bench_clock.h"

#define DRAWS 256

static const struct {
    const char *name;
    double d_nm;
} PLATES[] = {{"calcite", 50e3}, {"quartz", 200e3}, {"rutile", 10e3}, {"linbo3", 20e3}, {"sapphire", 1e6}};
enum { NPLATE = sizeof PLATES / sizeof PLATES[0] };

typedef struct {
    const biref_integrator *it;
    const biref_material *m;
    biref_slab geo[DRAWS], fixed[DRAWS];
    double theta[DRAWS];
} bench_ctx;

static double run_material(void *p, long iters)
{
    bench_ctx *c = p;
    double sum = 0.0;
    for (long i = 0; i < iters; i++) {
        biref_spectrum x;
        const int k = (int)(i % DRAWS);
        if (biref_integrate_material_spectrum(c->it, c->m, &c->geo[k], c->theta[k], &x) == BIREF_OK) sum += x.T[0][1][1];
    }
    return sum;
}

static double run_constant(void *p, long iters)
{
    bench_ctx *c = p;
    double sum = 0.0;
    for (long i = 0; i < iters; i++) {
        biref_slab_state st;
        biref_spectrum x;
        const int k = (int)(i % DRAWS);
        if (biref_slab_prepare(&c->fixed[k], c->theta[k], &st) == BIREF_OK && biref_integrate_spectrum(c->it, &st, &x) == BIREF_OK)
            sum += x.T[0][1][1];
    }
    return sum;
}

int main(int argc, char **argv)
{
    bench_common_opts o;
    bench_common_defaults(&o);
    int json = 0;
    for (int i = 1; i < argc; i++) {
        if (bench_common_arg(&o, argc, argv, &i)) continue;
        if (!strcmp(argv[i], "--json")) {
            json = 1;
            continue;
        }
        fprintf(stderr, "usage: bench_dispersion [--min-time S] [--runs N] [--iterations N] [--seed N] [--json]\n");
        return 2;
    }
    biref_spectral *sp = NULL;
    char msg[BIREF_MSG_SIZE];
    if (biref_spectral_create(NULL, &sp, msg, sizeof msg) != BIREF_OK) {
        fprintf(stderr, "bench_dispersion: %s\n", msg);
        return 1;
    }
    const biref_method methods[2] = {BIREF_METHOD_ANALYTIC, BIREF_METHOD_EXPANSION};
    biref_integrator *it[2];
    for (int k = 0; k < 2; k++) {
        biref_integrator_options io;
        biref_integrator_options_default(&io);
        io.method = methods[k];
        if (biref_integrator_create(sp, &io, &it[k], msg, sizeof msg) != BIREF_OK) {
            fprintf(stderr, "bench_dispersion: %s\n", msg);
            return 1;
        }
    }
    static bench_ctx ctx;
    if (json) printf("{\"plates\": [");
    for (int p = 0; p < NPLATE; p++) {
        bench_rng g = {o.seed + (uint64_t)p};
        ctx.m = biref_material_find(PLATES[p].name);
        for (int k = 0; k < DRAWS; k++) {
            double a[3], n2;
            do {
                for (int q = 0; q < 3; q++) a[q] = bench_rng_uniform(&g, -1, 1);
                n2 = a[0] * a[0] + a[1] * a[1] + a[2] * a[2];
            } while (n2 > 1.0 || n2 < 0.01);
            ctx.geo[k] = (biref_slab){0, 0, {a[0], a[1], a[2]}, PLATES[p].d_nm, 1.0};
            biref_material_slab_at(ctx.m, &ctx.geo[k], 550.0, &ctx.fixed[k]);
            ctx.theta[k] = bench_rng_uniform(&g, 0, 70) * M_PI / 180.0;
        }
        bench_result r[2][2];
        for (int k = 0; k < 2; k++) {
            ctx.it = it[k];
            r[k][0] = bench_measure(run_material, &ctx, o.min_time, o.runs, o.fixed_iters);
            r[k][1] = bench_measure(run_constant, &ctx, o.min_time, o.runs, o.fixed_iters);
        }
        if (json)
            printf("%s\n  {\"plate\": \"%s\", \"thickness_um\": %g, \"analytic_ns\": %.0f, \"analytic_constant_ns\": %.0f, "
                   "\"expansion_ns\": %.0f, \"expansion_constant_ns\": %.0f, \"cpu_share\": %.2f}",
                   p ? "," : "", PLATES[p].name, PLATES[p].d_nm / 1e3, r[0][0].ns_median, r[0][1].ns_median,
                   r[1][0].ns_median, r[1][1].ns_median, fmin(r[0][0].cpu_share, r[1][0].cpu_share));
        else
            printf("%-9s %7g um  analytic %7.0f ns (constant %6.0f, x%.1f)  expansion %7.0f ns (constant %6.0f, x%.1f)%s\n",
                   PLATES[p].name, PLATES[p].d_nm / 1e3, r[0][0].ns_median, r[0][1].ns_median,
                   r[0][0].ns_median / r[0][1].ns_median, r[1][0].ns_median, r[1][1].ns_median,
                   r[1][0].ns_median / r[1][1].ns_median,
                   fmin(r[0][0].cpu_share, r[1][0].cpu_share) < BENCH_CPU_SHARE_OK ? "  (descheduled: repeat)" : "");
    }
    if (json) printf("\n], \"sink\": %g}\n", bench_sink);
    else printf("sink %g\n", bench_sink);
    for (int k = 0; k < 2; k++) biref_integrator_destroy(it[k]);
    biref_spectral_destroy(sp);
    return 0;
}
