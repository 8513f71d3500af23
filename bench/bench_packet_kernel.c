/* The analytic method's packet kernel alone: ns per hit (transmission of the hit's state and
 * reflection of its flip) for every instruction set this CPU runs.
 *
 *   bench_packet_kernel [--thickness NM] [--runs N] [--min-time S] [--prefilter]
 *
 * The hits are a row of a fig9a-like frame: the slab of examples/fig9a.json (eta_o 1.40,
 * eta_e 1.38, 1.25 mm by default) with its optic axis turning once around the normal and the
 * angle of incidence rising from 11 to 46 degrees along 4096 hits, so that neighbouring lanes
 * see neighbouring path differences as in a rendered row. With --prefilter every phase integral
 * is a box average over a footprint of ~one fringe (the default of `biref render`). Each of N
 * runs (default 9) calls the kernel on all hits often enough to last --min-time seconds
 * (default 0.05); the minimum and the median ns per hit are printed. The minimum is the figure
 * to compare on a shared machine (noise only ever adds time); compare builds by running them
 * alternately. This is the kernel only: the frame's other work is `biref bench`'s. */
#define _POSIX_C_SOURCE 200809L /* clock_gettime */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "bench_clock.h"
#include "biref/biref.h"
#include "spectral/analytic_packet.h"
#include "spectral/phase_prefilter.h"

enum { HITS = 4096 };

typedef struct {
    const biref_spectral *sp;
    biref_packet_hits_kernel kernel;
    const biref_packet_hits *hits;
    const biref_opl_footprint *fp;
    double (*T)[3], (*R)[3];
    unsigned char *scalar;
} kernel_case;

static double run_kernel(void *ctx, long iters)
{
    kernel_case *c = ctx;
    const double w_in[2] = {0.75, 0.25}, mask[2] = {1.0, 1.0};
    double sum = 0.0;
    for (long k = 0; k < iters; k++) {
        c->kernel(c->sp, w_in, mask, c->hits, HITS, c->T, c->R, c->scalar, c->fp, NULL);
        sum += c->T[k % HITS][1] + c->R[k % HITS][1];
    }
    return sum;
}

int main(int argc, char **argv)
{
    double thickness = 1.25e6, min_time = 0.05;
    int runs = 9, prefilter = 0;
    for (int i = 1; i < argc; i++) {
        if (!strcmp(argv[i], "--thickness") && i + 1 < argc)
            thickness = bench_arg_number(argv[i], argv[i + 1]), i++;
        else if (!strcmp(argv[i], "--runs") && i + 1 < argc)
            runs = (int)bench_arg_number(argv[i], argv[i + 1]), i++;
        else if (!strcmp(argv[i], "--min-time") && i + 1 < argc)
            min_time = bench_arg_number(argv[i], argv[i + 1]), i++;
        else if (!strcmp(argv[i], "--prefilter"))
            prefilter = 1;
        else {
            fprintf(stderr, "usage: %s [--thickness NM] [--runs N] [--min-time S] [--prefilter]\n", argv[0]);
            return 2;
        }
    }
    biref_spectral *sp = NULL;
    biref_phase_prefilter *pf = NULL;
    if (biref_spectral_create(NULL, &sp, NULL, 0) != BIREF_OK ||
        (prefilter && biref_phase_prefilter_create(sp, &pf) != BIREF_OK)) {
        fprintf(stderr, "bench_packet_kernel: set-up failed\n");
        return 1;
    }
    static double hits[BIREF_PACKET_HIT_FIELDS][HITS];
    static biref_opl_footprint fp[HITS];
    static double T[HITS][3], R[HITS][3];
    static unsigned char scalar[HITS];
    const double axis[3] = {-0.54, 0.80, 0.27}, len = sqrt(0.54 * 0.54 + 0.80 * 0.80 + 0.27 * 0.27);
    for (int k = 0; k < HITS; k++) {
        const double phi = 2.0 * M_PI * k / HITS, theta = 0.2 + 0.6 * k / HITS;
        const double c = cos(phi) / len, s = sin(phi) / len;
        const biref_packet_hit h = {1.40, 1.38, {axis[0] * c - axis[1] * s, axis[1] * c + axis[0] * s, axis[2] / len},
                                    thickness, 1.0, sin(theta)};
        biref_packet_hit_put(&hits[0][0], HITS, (size_t)k, &h);
        fp[k].pf = pf;
        fp[k].disp = NULL;
        for (int leg = 0; leg < 4; leg++) /* a fringe's worth of path across the pixel */
            fp[k].grad[leg][0] = fp[k].grad[leg][1] = (leg & 1 ? 260.0 : 250.0) * thickness / 1.25e6;
    }
    printf("packet kernel, %d fig9a-like hits, %.4g nm slab%s\n", HITS, thickness, prefilter ? ", prefiltered" : "");
    for (int isa = BIREF_SIMD_BASELINE; isa < BIREF_SIMD_COUNT; isa++) {
        if (!biref_simd_isa_supported((biref_simd_isa)isa)) continue;
        /* The integrator's kernel (float lanes where the set has them), then the double one. */
        for (int f64 = 0; f64 < 2; f64++) {
            biref_packet_hits_kernel kernel = f64 ? biref_simd_hits_kernel_f64((biref_simd_isa)isa)
                                                  : biref_simd_hits_kernel((biref_simd_isa)isa);
            const int float_lanes = kernel != biref_simd_hits_kernel_f64((biref_simd_isa)isa);
            if (f64 && !float_lanes && kernel == biref_simd_hits_kernel((biref_simd_isa)isa)) continue;
            const biref_packet_hits in = {&hits[0][0], HITS};
            kernel_case c = {sp, kernel, &in, prefilter ? fp : NULL, T, R, scalar};
            bench_result r = bench_measure(run_kernel, &c, min_time, runs, 0);
            int declined = 0;
            for (int k = 0; k < HITS; k++) declined += scalar[k];
            char name[32];
            snprintf(name, sizeof name, "%s%s", biref_simd_isa_name((biref_simd_isa)isa),
                     float_lanes ? " f32" : f64 ? " f64" : "");
            printf("%-12s %7.1f ns per hit (min), %7.1f (median)%s%s\n", name, r.ns_min / HITS, r.ns_median / HITS,
                   declined ? ", some hits declined" : "", r.cpu_share < BENCH_CPU_SHARE_OK ? " [descheduled: repeat]" : "");
        }
    }
    printf("(checksum %g)\n", bench_sink);
    biref_phase_prefilter_destroy(pf);
    biref_spectral_destroy(sp);
    return 0;
}
