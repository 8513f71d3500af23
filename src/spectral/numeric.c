/* Numeric spectral integration of the closed-form Jones matrices (paper §6: "numeric" with N
 * samples and the ground truth with 16384): N midpoint samples, uniform in wavelength, each an
 * exact evaluation of eq. 17. States with real optical paths go through the lanes across
 * wavelengths (numeric_lanes.h: the state's coefficients once, per wavelength its phase factors
 * and the 2 x 2 solve); evanescent legs, and every state under BIREF_SIMD=scalar, through the
 * Jones matrices a block of wavelengths at a time (numeric_jones.c), equal to the per-wavelength
 * scalar path to the bit, transmission and reflection sharing each wavelength's phase factors
 * and (I - D)^{-1}; there the sums run over the wavelengths in ascending order. */
#include <complex.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "error.h"
#include "spectral/analytic_packet.h"
#include "spectral/numeric_jones.h"
#include "spectral/numeric_lanes.h"
#include "spectral/spectral_internal.h"

biref_status biref_numeric_plan_create(const biref_spectral *sp, int samples, biref_numeric_plan **out, char *msg,
                                       size_t msg_len)
{
    if (!out) return biref_fail(msg, msg_len, "no output");
    *out = NULL;
    if (!sp) return biref_fail(msg, msg_len, "no spectral context");
    if (samples <= 0 || samples > (1 << 24))
        return biref_fail(msg, msg_len, "%d samples: the numeric method needs 1 to %d", samples, 1 << 24);
    biref_numeric_plan *p = calloc(1, sizeof *p);
    if (!p) return biref_fail_status(BIREF_ERR_NOMEM, msg, msg_len, "out of memory");
    p->samples = samples;
    p->padded = (samples + BIREF_NUMERIC_LANES_PAD - 1) / BIREF_NUMERIC_LANES_PAD * BIREF_NUMERIC_LANES_PAD;
    p->lambda = malloc((size_t)samples * sizeof *p->lambda);
    p->weight = malloc((size_t)samples * sizeof *p->weight);
    p->k = malloc((size_t)p->padded * sizeof *p->k);
    for (int b = 0; b < 3; b++) p->wband[b] = calloc((size_t)p->padded, sizeof *p->wband[b]);
    if (!p->lambda || !p->weight || !p->k || !p->wband[0] || !p->wband[1] || !p->wband[2]) {
        biref_numeric_plan_destroy(p);
        return biref_fail_status(BIREF_ERR_NOMEM, msg, msg_len, "out of memory");
    }
    const double lmin = sp->cfg.lambda_min_nm, lmax = sp->cfg.lambda_max_nm, dl = (lmax - lmin) / samples;
    double sum[3] = {0, 0, 0};
    for (int i = 0; i < samples; i++) {
        p->lambda[i] = lmin + (i + 0.5) * dl;
        p->k[i] = 2.0 * M_PI / p->lambda[i]; /* as biref_slab_jones_at computes it */
        biref_cmf_band_eval(&sp->band, p->lambda[i], p->weight[i]);
        for (int j = 0; j < 3; j++) sum[j] += p->weight[i][j];
    }
    /* Normalise by the discrete sum so that a flat spectrum gives exactly (1, 1, 1) for any N
     * (with few samples a band may get no weight at all; then it stays 0). */
    for (int i = 0; i < samples; i++)
        for (int j = 0; j < 3; j++) p->weight[i][j] = sum[j] > 0 ? p->weight[i][j] / sum[j] : 0.0;
    for (int i = 0; i < samples; i++)
        for (int j = 0; j < 3; j++) p->wband[j][i] = p->weight[i][j];
    for (int i = samples; i < p->padded; i++) p->k[i] = p->k[samples - 1];
    p->k_max = p->k[0];
    p->isa = (int)biref_simd_isa_choose();
    *out = p;
    return BIREF_OK;
}

void biref_numeric_plan_destroy(biref_numeric_plan *plan)
{
    if (!plan) return;
    free(plan->lambda);
    free(plan->weight);
    free(plan->k);
    for (int b = 0; b < 3; b++) free(plan->wband[b]);
    free(plan);
}

int biref_numeric_plan_samples(const biref_numeric_plan *plan) { return plan->samples; }

void biref_spectrum_numeric(const biref_numeric_plan *plan, const biref_slab_state *st, biref_spectrum *out)
{
    biref_numeric_lanes_job job;
    job.outputs = BIREF_NL_T | BIREF_NL_R;
    job.pairs = 1;
    if (biref_numeric_lanes_run(plan, st, &job)) {
        memcpy(out->T, job.out[0], sizeof out->T);
        memcpy(out->R, job.out[1], sizeof out->R);
        return;
    }
    memset(out, 0, sizeof *out);
    biref_jones_block T, R;
    for (int n0 = 0; n0 < plan->samples; n0 += BIREF_NUMERIC_BLOCK) {
        const int nb = plan->samples - n0 < BIREF_NUMERIC_BLOCK ? plan->samples - n0 : BIREF_NUMERIC_BLOCK;
        biref_numeric_jones_block(st, plan->k + n0, nb, &T, &R);
        for (int l = 0; l < nb; l++) {
            const double *w = plan->weight[n0 + l];
            for (int i = 0; i < 2; i++)
                for (int o = 0; o < 2; o++) {
                    const double PT = T.re[i][o][l] * T.re[i][o][l] + T.im[i][o][l] * T.im[i][o][l];
                    const double PR = R.re[i][o][l] * R.re[i][o][l] + R.im[i][o][l] * R.im[i][o][l];
                    for (int j = 0; j < 3; j++) {
                        out->T[i][o][j] += w[j] * PT;
                        out->R[i][o][j] += w[j] * PR;
                    }
                }
        }
    }
}

void biref_spectrum_numeric_polarized(const biref_numeric_plan *plan, const biref_slab_state *st, int which,
                                      const double complex C[2][2], const double complex P[2][2], double xyz[3])
{
    biref_numeric_lanes_job job;
    job.outputs = which == BIREF_REFLECTION ? BIREF_NL_R : BIREF_NL_T;
    biref_numeric_lanes_light(&job, C, P);
    if (biref_numeric_lanes_run(plan, st, &job)) {
        memcpy(xyz, job.out[which == BIREF_REFLECTION][0][0], 3 * sizeof *xyz);
        return;
    }
    xyz[0] = xyz[1] = xyz[2] = 0.0;
    biref_jones_block B;
    for (int n0 = 0; n0 < plan->samples; n0 += BIREF_NUMERIC_BLOCK) {
        const int nb = plan->samples - n0 < BIREF_NUMERIC_BLOCK ? plan->samples - n0 : BIREF_NUMERIC_BLOCK;
        if (which == BIREF_REFLECTION)
            biref_numeric_jones_block(st, plan->k + n0, nb, NULL, &B);
        else
            biref_numeric_jones_block(st, plan->k + n0, nb, &B, NULL);
        for (int l = 0; l < nb; l++) {
            const double I_det = biref_numeric_block_detected(&B, l, C, P);
            for (int b = 0; b < 3; b++) xyz[b] += plan->weight[n0 + l][b] * I_det;
        }
    }
}

void biref_numeric_hit(const biref_numeric_plan *plan, const biref_slab_state *st, const double complex C[2][2],
                       const double complex P[2][2], double T[3], double R[3])
{
    biref_numeric_lanes_job job;
    job.outputs = BIREF_NL_T | BIREF_NL_RFLIP;
    biref_numeric_lanes_light(&job, C, P);
    if (biref_numeric_lanes_run(plan, st, &job)) {
        memcpy(T, job.out[0][0][0], 3 * sizeof *T);
        memcpy(R, job.out[2][0][0], 3 * sizeof *R);
        return;
    }
    biref_spectrum_numeric_polarized(plan, st, BIREF_TRANSMISSION, C, P, T);
    biref_slab_state fl;
    biref_slab_state_flip(st, &fl);
    biref_spectrum_numeric_polarized(plan, &fl, BIREF_REFLECTION, C, P, R);
}
