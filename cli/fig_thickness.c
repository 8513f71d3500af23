/* Figure "stress-thickness": a disk under diametral compression whose stress varies through its
 * thickness, in a dark-field plane polariscope in white light, computed layer by layer with the
 * stack machinery (docs/STACKS.md §3). (a) uniform stress; (b) the same mean stress with a
 * parabolic profile through the thickness and fixed principal directions: the picture of (a),
 * because retardations add (integrated photoelasticity); (c) the stress of (a) with principal
 * directions turning by 90 degrees through the thickness: a different picture. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "cli_common.h"
#include "fig_common.h"
#include "fig_stacks.h"

enum { THICK_SAMPLES = 48, THICK_PANELS = 3 };

typedef struct {
    biref_pe_material m;
    double R, h, P; /* disk radius and thickness (m), load (N) */
    int layers;
    double lambda[THICK_SAMPLES], w[THICK_SAMPLES][3];
} thick_setup;

/* The stress of layer k of n (z from -1 to 1 through the thickness) for panel p. */
static biref_pe_stress layer_stress(const biref_pe_stress *s, int p, int k, int n)
{
    const double z = (k + 0.5) / n * 2 - 1;
    biref_pe_stress o = *s;
    if (p == 1) { /* parabolic magnitude, mean 1 over the layers: about 0.4 at mid-plane, 2.2 at the faces */
        const double mean_z2 = 1.0 / 3 - 1.0 / (3.0 * n * n); /* of the layers' mid-points */
        const double f = 1 + 1.8 * (z * z - mean_z2);
        o.sxx *= f, o.syy *= f, o.txy *= f;
    } else if (p == 2) { /* principal directions turned by beta = 45 deg * z */
        const double b = z * M_PI / 4, c = cos(b), sn = sin(b);
        o.sxx = c * c * s->sxx + sn * sn * s->syy - 2 * c * sn * s->txy;
        o.syy = sn * sn * s->sxx + c * c * s->syy + 2 * c * sn * s->txy;
        o.txy = c * sn * (s->sxx - s->syy) + (c * c - sn * sn) * s->txy;
    }
    return o;
}

/* XYZ of one point of panel p between crossed polarizers (s in, p out), white light. */
static int point_xyz(const thick_setup *t, int p, double x, double y, double xyz[3])
{
    biref_pe_stress s, st[BIREF_STACK_MAX_LAYERS];
    biref_pe_disk_stress(t->R, t->h, t->P, x, y, &s);
    const int n = p == 0 ? 1 : t->layers;
    for (int k = 0; k < n; k++) st[k] = layer_stress(&s, p, k, n);
    biref_stack stack;
    biref_stack_state state;
    if (biref_pe_stack(&t->m, t->h, 1.0, n, st, &stack, NULL, 0) != BIREF_OK ||
        biref_stack_prepare(&stack, 0.0, &state) != BIREF_OK)
        return -1;
    xyz[0] = xyz[1] = xyz[2] = 0.0;
    for (int i = 0; i < THICK_SAMPLES; i++) {
        biref_jones T;
        biref_stack_jones_at(&state, t->lambda[i], &T, NULL);
        const double power = creal(T.m[0][1] * conj(T.m[0][1]));
        for (int j = 0; j < 3; j++) xyz[j] += t->w[i][j] * power;
    }
    return 0;
}

static int setup(thick_setup *t, int quick)
{
    if (biref_pe_material_preset("epoxy", &t->m) != BIREF_OK) return -1;
    t->R = 0.02, t->h = 0.006, t->P = 700.0, t->layers = quick ? 6 : 16;
    biref_cmf_band band;
    if (biref_cmf_band_init(&band, BIREF_CMF_CIE1931, 380, 700, NULL, 0) != BIREF_OK) return -1;
    double sum[3] = {0, 0, 0};
    for (int i = 0; i < THICK_SAMPLES; i++) {
        t->lambda[i] = 380 + 320.0 * (i + 0.5) / THICK_SAMPLES;
        biref_cmf_band_eval(&band, t->lambda[i], t->w[i]);
        for (int j = 0; j < 3; j++) sum[j] += t->w[i][j];
    }
    for (int i = 0; i < THICK_SAMPLES; i++)
        for (int j = 0; j < 3; j++) t->w[i][j] /= sum[j];
    return 0;
}

int fig_stress_thickness(const fig_ctx *c)
{
    thick_setup t;
    if (setup(&t, c->quick)) return cli_error(FIG_CMD, "stress-thickness: set-up failed"), CLI_EXIT_FAIL;
    const int S = c->quick ? 96 : 260, gap = 8, W = THICK_PANELS * S + (THICK_PANELS - 1) * gap;
    unsigned char *img = malloc((size_t)W * S * 3);
    double *xyz = malloc(sizeof(double) * 3 * (size_t)S * S * THICK_PANELS);
    if (!img || !xyz) return free(img), free(xyz), cli_error(FIG_CMD, "out of memory"), CLI_EXIT_FAIL;
    memset(img, 255, (size_t)W * S * 3);
    long failed = 0;
#pragma omp parallel for schedule(dynamic, 4) reduction(+ : failed)
    for (int row = 0; row < S * THICK_PANELS; row++) {
        const int p = row / S, y = row % S;
        for (int x = 0; x < S; x++) {
            const double px = (2.0 * (x + 0.5) / S - 1) * t.R * 1.05, py = (1 - 2.0 * (y + 0.5) / S) * t.R * 1.05;
            double *o = xyz + 3 * ((size_t)p * S * S + (size_t)y * S + x);
            unsigned char *pix = img + 3 * ((size_t)y * W + (size_t)p * (S + gap) + x);
            if (px * px + py * py > 0.97 * t.R * t.R) { /* outside, and the singular load points */
                o[0] = NAN;
                pix[0] = pix[1] = pix[2] = 90;
                continue;
            }
            if (point_xyz(&t, p, px, py, o)) {
                failed++;
                continue;
            }
            double rgb[3];
            biref_xyz_to_srgb(o, rgb);
            for (int j = 0; j < 3; j++) pix[j] = (unsigned char)lrint(255 * fmin(fmax(rgb[j], 0.0), 1.0));
        }
    }
    if (failed) return free(img), free(xyz), cli_error(FIG_CMD, "stress-thickness: %ld points failed", failed), CLI_EXIT_FAIL;
    /* How far (b) and (c) are from (a): integrated photoelasticity says (b) = (a). */
    double mean[2] = {0, 0}, worst[2] = {0, 0};
    long count = 0;
    for (size_t i = 0; i < (size_t)S * S; i++) {
        if (isnan(xyz[3 * i])) continue;
        for (int q = 0; q < 2; q++) {
            const double e = biref_delta_e00_xyz(xyz + 3 * i, xyz + 3 * ((size_t)(q + 1) * S * S + i));
            mean[q] += e, worst[q] = fmax(worst[q], e);
        }
        count++;
    }
    char path[4096];
    biref_outfile *out = fig_open_csv(c, "stress_thickness.csv", path, sizeof path);
    if (!out) return free(img), free(xyz), CLI_EXIT_FAIL;
    FILE *f = biref_outfile_stream(out);
    fprintf(f, "panel,against,layers,mean_dE00,max_dE00,points\n");
    fprintf(f, "b_parabolic_fixed_directions,a_uniform,%d,%.4f,%.4f,%ld\n", t.layers, mean[0] / count, worst[0], count);
    fprintf(f, "c_directions_turning_90deg,a_uniform,%d,%.4f,%.4f,%ld\n", t.layers, mean[1] / count, worst[1], count);
    if (fig_close_csv(out, path)) return free(img), free(xyz), CLI_EXIT_FAIL;
    printf("stress-thickness: (b) vs (a) mean dE00 %.3f (max %.3f); (c) vs (a) mean %.2f (max %.1f)\n",
           mean[0] / count, worst[0], mean[1] / count, worst[1]);
    fig_out_path(c, "stress_thickness.png", path, sizeof path);
    char msg[BIREF_MSG_SIZE];
    biref_status s = biref_png_write_rgb8(path, W, S, img, msg, sizeof msg);
    free(img);
    free(xyz);
    if (s != BIREF_OK) return cli_error(FIG_CMD, "%s", msg), CLI_EXIT_FAIL;
    printf("wrote %s\n", path);
    return CLI_EXIT_OK;
}
