/* The numeric methods in lanes across wavelengths (numeric_lanes.h): a state's
 * wavelength-independent parts gathered once, the kernel of the plan's instruction set run over
 * all of the plan's samples. */
#include <complex.h>
#include <math.h>
#include <string.h>

#include "spectral/analytic_packet.h"
#include "spectral/numeric_lanes.h"
#include "spectral/spectral_internal.h"

static void split(const biref_complex m[2][2], biref_nl_cm2 *out)
{
    for (int a = 0; a < 2; a++)
        for (int b = 0; b < 2; b++) out->r[a][b] = creal(m[a][b]), out->i[a][b] = cimag(m[a][b]);
}

/* out[c][a][b] = x[a][c] y[c][b]: the product x diag(p) y is sum_c p[c] out[c]. */
static void through_mode(const biref_complex x[2][2], const biref_complex y[2][2], int real, biref_nl_cm2 out[2])
{
    for (int c = 0; c < 2; c++)
        for (int a = 0; a < 2; a++)
            for (int b = 0; b < 2; b++) {
                if (real) {
                    out[c].r[a][b] = creal(x[a][c]) * creal(y[c][b]), out[c].i[a][b] = 0.0;
                    continue;
                }
                const double complex v = x[a][c] * y[c][b];
                out[c].r[a][b] = creal(v), out[c].i[a][b] = cimag(v);
            }
}

static int real_matrix(const biref_complex m[2][2])
{
    return cimag(m[0][0]) == 0.0 && cimag(m[0][1]) == 0.0 && cimag(m[1][0]) == 0.0 && cimag(m[1][1]) == 0.0;
}

static int is_real(const double im[2][2]) { return im[0][0] == 0.0 && im[0][1] == 0.0 && im[1][0] == 0.0 && im[1][1] == 0.0; }

void biref_numeric_lanes_light(biref_numeric_lanes_job *job, const double complex C[2][2],
                               const double complex P[2][2])
{
    job->pairs = 0;
    biref_nl_light *l = &job->light[0];
    l->has_P = P != NULL;
    for (int a = 0; a < 2; a++)
        for (int b = 0; b < 2; b++) {
            l->Cr[a][b] = creal(C[a][b]), l->Ci[a][b] = cimag(C[a][b]);
            l->Pr[a][b] = P ? creal(P[a][b]) : a == b, l->Pi[a][b] = P ? cimag(P[a][b]) : 0.0;
        }
    if (P && is_real(l->Pi)) l->has_P = 2;
    job->light[1] = job->light[2] = *l;
}

int biref_numeric_lanes_run(const biref_numeric_plan *plan, const biref_slab_state *st, biref_numeric_lanes_job *job)
{
    if (plan->isa == BIREF_SIMD_SCALAR) return 0;
    /* Real paths only (an evanescent leg's factor also decays), phases within the kernel's
     * reduction (|k opl| < 2^30 rad: a path of ~1.6e10 nm at 380 nm); NaN fails the test too. */
    for (int x = 0; x < 2; x++) {
        const double complex p[2] = {st->opl_down[x], st->opl_up[x]};
        for (int j = 0; j < 2; j++)
            if (cimag(p[j]) != 0.0 || !(fabs(creal(p[j])) * plan->k_max < 0x1p30)) return 0;
        job->opl_down[x] = creal(st->opl_down[x]);
        job->opl_up[x] = creal(st->opl_up[x]);
    }
    const biref_interface *top = &st->top, *bottom = &st->bottom;
    /* Real coefficients (every wave propagating) take the kernel's real instantiation. */
    const int real = real_matrix(top->t_down) && real_matrix(top->r_down) && real_matrix(top->r_up) &&
                     real_matrix(top->t_up) && real_matrix(bottom->t_down) && real_matrix(bottom->r_down) &&
                     real_matrix(bottom->r_up) && real_matrix(bottom->t_up);
    through_mode(bottom->r_down, top->r_up, real, job->M); /* r12 diag(P_up) r10 */
    through_mode(bottom->r_down, top->t_up, real, job->Q); /* r12 diag(P_up) t10 */
    through_mode(bottom->t_up, top->r_up, real, job->N);   /* t21 diag(P_up) r10 */
    split(top->t_down, &job->t01);
    split(bottom->t_down, &job->t12);
    split(top->r_down, &job->r01);
    split(bottom->r_up, &job->r21);
    job->real = real;
    job->k = plan->k;
    for (int b = 0; b < 3; b++) job->w[b] = plan->wband[b];
    job->n = plan->padded;
    switch (plan->isa) {
    case BIREF_SIMD_AVX512: biref_numeric_lanes_avx512(job); break;
    case BIREF_SIMD_AVX2: biref_numeric_lanes_avx2(job); break;
    default: biref_numeric_lanes_baseline(job); break;
    }
    return 1;
}

void biref_numeric_packet_hits(const biref_numeric_plan *plan, const double complex C[2][2],
                               const double complex P[2][2], const biref_packet_hit_light *lights,
                               const biref_packet_hits *hits, size_t n, double (*T)[3], double (*R)[3],
                               unsigned char *scalar)
{
    if (plan->isa == BIREF_SIMD_SCALAR) {
        memset(scalar, 1, n);
        return;
    }
    biref_numeric_lanes_job job;
    static const double complex unpolarized[2][2] = {{0.5, 0}, {0, 0.5}};
    biref_numeric_lanes_light(&job, lights ? unpolarized : C, lights ? NULL : P);
    job.k = plan->k;
    for (int b = 0; b < 3; b++) job.w[b] = plan->wband[b];
    job.n = plan->padded;
    switch (plan->isa) {
    case BIREF_SIMD_AVX512: biref_numeric_hits_avx512(&job, hits, lights, n, T, R, scalar); break;
    case BIREF_SIMD_AVX2: biref_numeric_hits_avx2(&job, hits, lights, n, T, R, scalar); break;
    default: biref_numeric_hits_baseline(&job, hits, lights, n, T, R, scalar); break;
    }
}
