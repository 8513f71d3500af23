/* Numeric spectral integration of the closed-form Jones matrices (paper §6: "numeric" with N
 * samples and the ground truth with 16384): N midpoint samples, uniform in wavelength. */
#include <complex.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "error.h"
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
    p->lambda = malloc((size_t)samples * sizeof *p->lambda);
    p->weight = malloc((size_t)samples * sizeof *p->weight);
    if (!p->lambda || !p->weight) {
        biref_numeric_plan_destroy(p);
        return biref_fail_status(BIREF_ERR_NOMEM, msg, msg_len, "out of memory");
    }
    const double lmin = sp->cfg.lambda_min_nm, lmax = sp->cfg.lambda_max_nm, dl = (lmax - lmin) / samples;
    double sum[3] = {0, 0, 0};
    for (int i = 0; i < samples; i++) {
        p->lambda[i] = lmin + (i + 0.5) * dl;
        biref_cmf_band_eval(&sp->band, p->lambda[i], p->weight[i]);
        for (int j = 0; j < 3; j++) sum[j] += p->weight[i][j];
    }
    /* Normalise by the discrete sum so that a flat spectrum gives exactly (1, 1, 1) for any N
     * (with few samples a band may get no weight at all; then it stays 0). */
    for (int i = 0; i < samples; i++)
        for (int j = 0; j < 3; j++) p->weight[i][j] = sum[j] > 0 ? p->weight[i][j] / sum[j] : 0.0;
    *out = p;
    return BIREF_OK;
}

void biref_numeric_plan_destroy(biref_numeric_plan *plan)
{
    if (!plan) return;
    free(plan->lambda);
    free(plan->weight);
    free(plan);
}

int biref_numeric_plan_samples(const biref_numeric_plan *plan) { return plan->samples; }

void biref_spectrum_numeric(const biref_numeric_plan *plan, const biref_slab_state *st, biref_spectrum *out)
{
    memset(out, 0, sizeof *out);
    for (int n = 0; n < plan->samples; n++) {
        biref_jones T, R;
        biref_slab_jones_at(st, plan->lambda[n], &T, &R);
        double PT[2][2], PR[2][2];
        biref_jones_intensity(&T, PT);
        biref_jones_intensity(&R, PR);
        const double *w = plan->weight[n];
        for (int i = 0; i < 2; i++)
            for (int o = 0; o < 2; o++)
                for (int j = 0; j < 3; j++) {
                    out->T[i][o][j] += w[j] * PT[i][o];
                    out->R[i][o][j] += w[j] * PR[i][o];
                }
    }
}

void biref_spectrum_numeric_polarized(const biref_numeric_plan *plan, const biref_slab_state *st, int which,
                                      const double complex C[2][2], const double complex P[2][2], double xyz[3])
{
    xyz[0] = xyz[1] = xyz[2] = 0.0;
    for (int n = 0; n < plan->samples; n++) {
        biref_jones J;
        if (which == BIREF_REFLECTION)
            biref_slab_jones_at(st, plan->lambda[n], NULL, &J);
        else
            biref_slab_jones_at(st, plan->lambda[n], &J, NULL);
        double complex M[2][2];
        for (int i = 0; i < 2; i++)
            for (int k = 0; k < 2; k++)
                M[i][k] = P ? J.m[i][0] * P[0][k] + J.m[i][1] * P[1][k] : J.m[i][k];
        /* <|e M|^2> over the input ensemble = sum_{i,j} C[i][j] sum_k M[i][k] conj(M[j][k]). */
        double I_det = 0.0;
        for (int i = 0; i < 2; i++)
            for (int j = 0; j < 2; j++)
                for (int k = 0; k < 2; k++) I_det += creal(C[i][j] * M[i][k] * conj(M[j][k]));
        for (int b = 0; b < 3; b++) xyz[b] += plan->weight[n][b] * I_det;
    }
}
