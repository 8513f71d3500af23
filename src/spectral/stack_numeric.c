/* Numeric spectral integration of a stack's exact Jones matrices (docs/STACKS.md §2): a plan's
 * midpoint samples, the four s/p pair intensities and any light's detected intensity, and the
 * adaptive fallback of the path expansion (samples doubled until two runs agree). */
#include <complex.h>
#include <math.h>
#include <string.h>

#include "biref/stack.h"
#include "spectral/spectral_internal.h"
#include "spectral/stack_internal.h"

/* sum_{i,j,o} C_ij (J P)_io conj((J P)_jo): the light's detected intensity of a Jones matrix. */
double biref_stack_detected(const biref_light *light, const double complex J[2][2])
{
    double complex N[2][2];
    for (int i = 0; i < 2; i++)
        for (int o = 0; o < 2; o++)
            N[i][o] = light->has_analyzer ? J[i][0] * light->P[0][o] + J[i][1] * light->P[1][o] : J[i][o];
    double sum = 0.0;
    for (int i = 0; i < 2; i++)
        for (int j = 0; j < 2; j++)
            for (int o = 0; o < 2; o++) sum += creal(light->C[i][j] * N[i][o] * conj(N[j][o]));
    return sum;
}

void biref_stack_spectrum_numeric(const biref_numeric_plan *plan, const biref_stack_state *st,
                                  const biref_light *light, biref_spectrum *out, double mixed_T[3], double mixed_R[3])
{
    memset(out, 0, sizeof *out);
    double mt[3] = {0, 0, 0}, mr[3] = {0, 0, 0};
    for (int n = 0; n < plan->samples; n++) {
        biref_jones T, R;
        biref_stack_jones_at(st, plan->lambda[n], &T, &R);
        double PT[2][2], PR[2][2];
        biref_jones_intensity(&T, PT);
        biref_jones_intensity(&R, PR);
        const double *w = plan->weight[n];
        for (int i = 0; i < 2; i++)
            for (int o = 0; o < 2; o++)
                for (int b = 0; b < 3; b++) {
                    out->T[i][o][b] += w[b] * PT[i][o];
                    out->R[i][o][b] += w[b] * PR[i][o];
                }
        if (light) {
            const double it = biref_stack_detected(light, (const double complex(*)[2])T.m);
            const double ir = biref_stack_detected(light, (const double complex(*)[2])R.m);
            for (int b = 0; b < 3; b++) mt[b] += w[b] * it, mr[b] += w[b] * ir;
        }
    }
    if (mixed_T) memcpy(mixed_T, mt, sizeof mt);
    if (mixed_R) memcpy(mixed_R, mr, sizeof mr);
}

/* Largest difference between two results (the pairs and the light's). */
static double result_diff(const biref_spectrum *a, const biref_spectrum *b, const double am[2][3],
                          const double bm[2][3])
{
    double d = 0.0;
    for (int i = 0; i < 2; i++)
        for (int o = 0; o < 2; o++)
            for (int c = 0; c < 3; c++)
                d = fmax(d, fmax(fabs(a->T[i][o][c] - b->T[i][o][c]), fabs(a->R[i][o][c] - b->R[i][o][c])));
    for (int s = 0; s < 2; s++)
        for (int c = 0; c < 3; c++) d = fmax(d, fabs(am[s][c] - bm[s][c]));
    return d;
}

biref_status biref_stack_numeric_adaptive(const biref_spectral *sp, const biref_stack_state *st,
                                          const biref_light *light, double tolerance, biref_spectrum *out,
                                          double mixed[2][3], int *samples, int *converged)
{
    biref_spectrum prev, cur;
    double pm[2][3], cm[2][3];
    *converged = 0;
    for (int n = BIREF_STACK_ADAPTIVE_FIRST; n <= BIREF_STACK_ADAPTIVE_MAX; n *= 2) {
        biref_numeric_plan *plan = NULL;
        biref_status s = biref_numeric_plan_create(sp, n, &plan, NULL, 0);
        if (s != BIREF_OK) return s;
        biref_stack_spectrum_numeric(plan, st, light, &cur, cm[0], cm[1]);
        biref_numeric_plan_destroy(plan);
        *samples = n;
        if (n > BIREF_STACK_ADAPTIVE_FIRST && result_diff(&prev, &cur, (const double(*)[3])pm,
                                                          (const double(*)[3])cm) <= tolerance) {
            *converged = 1;
            break;
        }
        prev = cur;
        memcpy(pm, cm, sizeof pm);
    }
    *out = cur;
    memcpy(mixed, cm, sizeof cm);
    return BIREF_OK;
}
