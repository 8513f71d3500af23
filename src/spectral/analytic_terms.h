/* Helpers shared by the analytic method's scalar workers (analytic.c, analytic_mixed.c,
 * analytic_general.c) and the expansion's incoherent tail: path energies (eqs. 20-21) and the
 * band integrals of one interference term. One copy, inline: they sit on the per-sample path. */
#ifndef BIREF_ANALYTIC_TERMS_H
#define BIREF_ANALYTIC_TERMS_H

#include <complex.h>
#include <math.h>

#include "spectral/phase_prefilter.h"
#include "spectral/spectral_internal.h"

static inline double biref_abs2(double complex z) { return creal(z) * creal(z) + cimag(z) * cimag(z); }

/* |e^{ik opl}|^2 per band at the band's centroid: 1 for propagating legs. */
static inline void biref_leg_energy(const biref_spectral *sp, double complex opl, double e[3])
{
    double im = cimag(opl);
    for (int j = 0; j < 3; j++) e[j] = im != 0.0 ? exp(-2.0 * sp->k_centroid[j] * im) : 1.0;
}

/* Energy weights of all paths reaching a reflection point, per band (eqs. 20-21), for `rows`
 * incident forms: w0[r][m][j] is the first arrival in mode m, Rin/Rout the reflections of one
 * round trip (mode m -> leg mode n via Rin, leg n, then Rout into mode m', leg m'), legs with
 * energies e_mid[n][j], e_end[m'][j]. out[r][m][j] = (w0[r] (I - Dbar_j)^{-1})[m] with
 * Dbar_j[m][m'] = sum_n |Rin[m][n]|^2 e_mid[n][j] |Rout[n][m']|^2 e_end[m'][j]. */
static inline void biref_path_energies(const double (*w0)[2][3], int rows, const double complex (*Rin)[2],
                                       const double e_mid[2][3], const double complex (*Rout)[2],
                                       const double e_end[2][3], double (*out)[2][3])
{
    double ai[2][2], ao[2][2];
    for (int m = 0; m < 2; m++)
        for (int n = 0; n < 2; n++) ai[m][n] = biref_abs2(Rin[m][n]), ao[m][n] = biref_abs2(Rout[m][n]);
    for (int j = 0; j < 3; j++) {
        double D[2][2];
        for (int m = 0; m < 2; m++)
            for (int m2 = 0; m2 < 2; m2++)
                D[m][m2] = (ai[m][0] * e_mid[0][j] * ao[0][m2] + ai[m][1] * e_mid[1][j] * ao[1][m2]) * e_end[m2][j];
        double a = 1.0 - D[0][0], b = -D[0][1], c = -D[1][0], d = 1.0 - D[1][1];
        double det = a * d - b * c;
        for (int r = 0; r < rows; r++) {
            double o0 = (w0[r][0][j] * d - w0[r][1][j] * c) / det;
            double o1 = (-w0[r][0][j] * b + w0[r][1][j] * a) / det;
            out[r][0][j] = o0;
            out[r][1][j] = o1;
        }
    }
}

/* The band integrals of one optical path difference D. */
typedef struct {
    double c[3], s[3]; /* S(cos kD), S(sin kD) per band */
    double att[3];     /* e^{-k_j Im D}: decay of evanescent legs at the band's centroid */
} biref_phase_int;

/* opd = sum_l n[l] opl_l (legs in biref_opl_footprint order), averaged over the pixel's footprint
 * fp (NULL: point values). */
static inline void biref_phase_eval(const biref_spectral *sp, const biref_opl_footprint *fp, double complex opd,
                                    const int n[4], biref_phase_int *p)
{
    biref_phase_integrals_footprint(sp, fp, creal(opd), n, p->c, p->s);
    double im = cimag(opd);
    for (int j = 0; j < 3; j++) p->att[j] = im != 0.0 ? exp(-sp->k_centroid[j] * im) : 1.0;
}

/* out_j += weight_j * S(Re(coef e^{ikD}), Λ_j) = weight_j (Re coef S(cos) - Im coef S(sin)):
 * S(Re(c e^{ikD})) = Re(c) S(cos kD) - Im(c) S(sin kD). */
static inline void biref_add_re_integral(double out[3], const double weight[3], double complex coef,
                                         const biref_phase_int *p)
{
    double a = creal(coef), b = cimag(coef);
    for (int j = 0; j < 3; j++) out[j] += weight[j] * p->att[j] * (a * p->c[j] - b * p->s[j]);
}

/* The table look-ups of one direction (analytic.c), shared by the paper's light and the general
 * one (analytic_general.c). Transmission: h0 the order-0 pair (eq. 24), trip[y][x'] the round
 * trip (bottom reflection into up mode y, top reflection into down mode x'). Reflection: p1[a]
 * the order-1 path a = (down a >> 1, up a & 1), which is also the descendants' extra round trip;
 * pair[a][b] (a < b) the pairs of order-1 paths. */
void biref_transmission_phases(const biref_spectral *sp, const biref_slab_state *st, const biref_opl_footprint *fp,
                               biref_phase_int *h0, biref_phase_int trip[2][2]);
void biref_reflection_phases(const biref_spectral *sp, const biref_slab_state *st, const biref_opl_footprint *fp,
                             biref_phase_int p1[4], biref_phase_int pair[4][4]);
/* Reflection's pairs alone: pair[a][b] (a < b) of the order-1 paths a = (down a >> 1, up a & 1).
 * They are also the lags between two last round trips (down x2, up y) of transmission's siblings. */
void biref_order1_pairs(const biref_spectral *sp, const biref_slab_state *st, const biref_opl_footprint *fp,
                        biref_phase_int pair[4][4]);
/* Transmission's order-1 pairs whose entry legs differ: ep[a][b] of the paths (down o, then the
 * round trip a) and (down e, then b), a = (down a >> 1, up a & 1) after the first reflection. */
void biref_entry_pairs(const biref_spectral *sp, const biref_slab_state *st, const biref_opl_footprint *fp,
                       biref_phase_int ep[4][4]);

/* The analytic method for a general light (analytic_general.c): incident coherency C, analyzer P
 * (NULL: none), for which = BIREF_TRANSMISSION or BIREF_REFLECTION, with every phase integral
 * averaged over the footprint fp (NULL: point values). The shader's formulas (docs/GPU.md); a
 * negative result is moved towards the incoherent path energy. */
void biref_analytic_general(const biref_spectral *sp, const biref_slab_state *st, const biref_opl_footprint *fp,
                            int which, const double complex C[2][2], const double complex P[2][2], double xyz[3]);
/* Its two terms, S = E + 2H (eqs. 19, 25), in every regime and without the limit (tests). */
void biref_analytic_general_terms(const biref_spectral *sp, const biref_slab_state *st, const biref_opl_footprint *fp,
                                  int which, const double complex C[2][2], const double complex P[2][2], double E[3],
                                  double H[3]);
/* biref_analytic_paper_terms with every phase integral averaged over the footprint fp (tests). */
void biref_analytic_paper_terms_footprint(const biref_spectral *sp, const biref_slab_state *st,
                                          const biref_opl_footprint *fp, int which, double E[2][2][3], double H[2][2][3]);

#endif
