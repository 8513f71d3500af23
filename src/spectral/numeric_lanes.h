/* Numeric integration in SIMD lanes across wavelengths (numeric_lanes.c, numeric_lanes.inc).
 *
 * For a slab of constant indices everything in eq. 17 but the legs' phase factors e^{i k opl} is
 * independent of the wavelength: the interface coefficients and the optical paths are the
 * prepared state's. Per wavelength only the phases and the 2 x 2 multiple-reflection solve
 * remain. The kernel takes the state's coefficients once (as products that enter the round trip
 * and the exits, biref_numeric_lanes_job), computes the phases of W wavelengths at once in
 * double (a Cody-Waite reduction by pi/2 with fused multiply-adds and minimax polynomials of
 * sin and cos on |r| <= pi/4), the Jones matrices, the detected intensities and the band sums,
 * all in lanes; a rendered hit under real analyzers folds the detection into its coefficients
 * (numeric_lanes_hits.inc). It is not bitwise the scalar path (other association, another sincos): it agrees
 * with it to ~1e-15 relative (test_numeric_lanes). */
#ifndef BIREF_SPECTRAL_NUMERIC_LANES_H
#define BIREF_SPECTRAL_NUMERIC_LANES_H

#include <complex.h>

#include <stddef.h>

#include "biref/optics.h"
#include "spectral/analytic_packet.h"

/* Wavelengths a plan's arrays are padded to (the widest lane count; padded samples weigh 0). */
#define BIREF_NUMERIC_LANES_PAD 8

/* A 2 x 2 complex matrix [row][col] in real and imaginary parts. */
typedef struct {
    double r[2][2], i[2][2];
} biref_nl_cm2;

/* The outputs one pass can give: transmission of the state, its reflection, and the reflection
 * of the flipped state (biref_slab_state_flip: the same hit lit from the other face), which
 * shares the state's round trip (below). */
enum { BIREF_NL_T = 1, BIREF_NL_R = 2, BIREF_NL_RFLIP = 4 };

/* A light: incident coherency C and analyzer P (has_P 0: none, 1: complex, 2: real). */
typedef struct {
    double Cr[2][2], Ci[2][2];
    double Pr[2][2], Pi[2][2];
    int has_P;
} biref_nl_light;

/* One state's wavelength-independent parts and what to compute. With A = diag(P_down) r12,
 * B = diag(P_up) r10 (rows scaled by the legs' phase factors), the round trip is D = A B and
 *   T      = t01 (I - D)^{-1} diag(P_down) t12                        (eq. 17)
 *   R      = r01 + t01 (I - D)^{-1} diag(P_down) r12 diag(P_up) t10
 *   R_flip = r21 + t21 (I - B A)^{-1} B diag(P_down) t12
 *          = r21 + (t21 diag(P_up) r10) (I - D)^{-1} diag(P_down) t12   ((I - BA)^{-1} B = B (I - AB)^{-1})
 * so that a hit's transmission and its flipped reflection share one inverse. Products through
 * one diagonal phase matrix are sums over the mode c in the middle: r12 diag(P_up) r10 =
 * sum_c P_up[c] M[c] with M[c][a][b] = r12[a][c] r10[c][b], likewise Q (r12 .. t10) and
 * N (t21 .. r10). */
typedef struct {
    double opl_down[2], opl_up[2]; /* real optical paths [o, e], nm */
    biref_nl_cm2 M[2], Q[2], N[2];
    biref_nl_cm2 t01, t12, r01, r21;
    int outputs; /* BIREF_NL_* */
    int pairs;   /* 1: the four |J[in][out]|^2 of each output; 0: one intensity under its light */
    biref_nl_light light[3]; /* per output (pairs = 0) */
    int real;  /* every coefficient matrix above is real (set by biref_numeric_lanes_run) */
    const double *k;        /* vacuum wavenumbers, n of them, n a multiple of BIREF_NUMERIC_LANES_PAD */
    const double *w[3];     /* band weights per sample (0 on padding) */
    int n;
    /* out[output][in][out][band]: output 0 = T, 1 = R, 2 = R_flip; with pairs = 0 the intensity's
     * band sums are out[output][0][0][band]. */
    double out[3][2][2][3];
} biref_numeric_lanes_job;

/* The kernel per instruction set (numeric_lanes_<isa>.c): fills job->out. */
void biref_numeric_lanes_baseline(biref_numeric_lanes_job *job);
void biref_numeric_lanes_avx2(biref_numeric_lanes_job *job);
void biref_numeric_lanes_avx512(biref_numeric_lanes_job *job);

/* sin and cos of n values in the lanes of the set (for tests): |x| < 2^30. */
void biref_numeric_lanes_sincos_baseline(const double *x, int n, double *s, double *c);
void biref_numeric_lanes_sincos_avx2(const double *x, int n, double *s, double *c);
void biref_numeric_lanes_sincos_avx512(const double *x, int n, double *s, double *c);

/* A packet of hits (analytic_packet.h): each hit's state set up in lanes across hits (the analytic
 * kernel's v_prepare), then its wavelengths in lanes: T of the state and R of the flipped state
 * under job's lights (lights NULL) or each hit's own (lights[k].T and .R: a world-fixed polarizer
 * and analyzer resolved in the hit's frames), as biref_numeric_hit gives them; scalar[k] = 1 for a hit the set-up cannot
 * take (as for the analytic kernel), whose T and R are left undefined. */
#define BIREF_NUMERIC_HITS_ARGS                                                                                   \
    biref_numeric_lanes_job *job, const biref_packet_hits *hits, const biref_packet_hit_light *lights, size_t n,    \
        double(*T)[3], double(*R)[3], unsigned char *scalar
void biref_numeric_hits_baseline(BIREF_NUMERIC_HITS_ARGS);
void biref_numeric_hits_avx2(BIREF_NUMERIC_HITS_ARGS);
void biref_numeric_hits_avx512(BIREF_NUMERIC_HITS_ARGS);

struct biref_numeric_plan;

/* The renderer's door for the numeric methods (biref_integrate_packet_hits and _lit): the hits of a
 * tile under the coherency C and analyzer P (NULL: none), or under each hit's own light (lights not
 * NULL; C, P unused), on the plan's instruction set; on the scalar path (BIREF_SIMD=scalar) every
 * hit is marked scalar. */
void biref_numeric_packet_hits(const struct biref_numeric_plan *plan, const double complex C[2][2],
                               const double complex P[2][2], const biref_packet_hit_light *lights,
                               const biref_packet_hits *hits, size_t n, double (*T)[3], double (*R)[3],
                               unsigned char *scalar);

/* The lanes path for one state: fills job (outputs, pairs, light as set by the caller) with
 * st's parts and runs the plan's kernel. 0 when the state or the plan cannot take it (a complex
 * optical path, i.e. an evanescent leg; a phase beyond 2^30 rad; a plan on the scalar path):
 * then the caller takes the per-wavelength blocks (numeric_jones.c). */
int biref_numeric_lanes_run(const struct biref_numeric_plan *plan, const biref_slab_state *st,
                            biref_numeric_lanes_job *job);

/* The light of a job from a coherency C and an analyzer P (NULL: none). */
void biref_numeric_lanes_light(biref_numeric_lanes_job *job, const double complex C[2][2],
                               const double complex P[2][2]);

#endif
