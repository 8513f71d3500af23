/* Pre-integrated phase table for spatial anti-aliasing (docs/PHYSICS.md, "Spatial anti-aliasing").
 *
 * The box average of S(e^{ikD}) over [a, b] is (Q(b) - Q(a)) / (b - a) with Q an antiderivative:
 *     Q(D) = S(e^{2 pi i D / lambda} lambda / (2 pi i)),   dQ/dD = S(e^{2 pi i D / lambda}).
 * Q is tabulated like the point table (spectral_context.c): demodulated by the band-centre
 * frequency nu_c, on the same nodes, with its derivative for cubic Hermite interpolation. Beyond
 * the table, the endpoint asymptotics of S integrated once more. */
#include "spectral/phase_prefilter.h"

#include <complex.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "spectral/phase_tables.h"
#include "spectral/spectral_internal.h"
#include "spectral/subband.h"
#include "spectral/table_build.h"

struct biref_phase_prefilter {
    const biref_spectral *sp;
    double *table; /* [m][band][re, im, dre/dD, dim/dD] of q(D) = e^{-2 pi i nu_c D} Q(D) */
    double *packet_table; /* the same for the packet kernel (biref_table_packet_layout) */
};

biref_status biref_phase_prefilter_create(const biref_spectral *sp, biref_phase_prefilter **out)
{
    if (!sp || !out) return BIREF_ERR_INVALID;
    *out = NULL;
    biref_phase_prefilter *pf = calloc(1, sizeof *pf);
    if (!pf) return BIREF_ERR_NOMEM;
    pf->sp = sp;
    pf->table = calloc((size_t)sp->nodes * BIREF_TABLE_ROW, sizeof *pf->table);
    if (!pf->table) {
        free(pf);
        return BIREF_ERR_NOMEM;
    }
    /* The copy generated at build time for the default band, else by quadrature (phase_tables.h). */
    const biref_phase_tables_builtin *gen = biref_phase_tables_builtin_for(&sp->cfg, sp->nodes);
    biref_phase_grid grid;
    biref_phase_grid_init(&grid, &sp->band, sp->cfg.lambda_min_nm, sp->cfg.lambda_max_nm);
    if (gen)
        memcpy(pf->table, gen->prefilter, (size_t)sp->nodes * BIREF_TABLE_ROW * sizeof *pf->table);
    else if (biref_phase_table_prefilter(&grid, pf->table) != BIREF_OK) {
        biref_phase_prefilter_destroy(pf);
        return BIREF_ERR_NOMEM;
    }
    /* Aligned for the kernel's whole-vector loads (as the point table's copy, spectral_context.c). */
    pf->packet_table = aligned_alloc(64, (size_t)sp->nodes * BIREF_PACKET_TABLE_STRIDE * sizeof *pf->packet_table);
    if (!pf->packet_table) {
        biref_phase_prefilter_destroy(pf);
        return BIREF_ERR_NOMEM;
    }
    biref_table_packet_layout(pf->table, sp->carrier, sp->nodes, pf->packet_table);
    *out = pf;
    return BIREF_OK;
}

void biref_phase_prefilter_destroy(biref_phase_prefilter *pf)
{
    if (!pf) return;
    free(pf->table);
    free(pf->packet_table);
    free(pf);
}

const double *biref_phase_prefilter_packet_table(const biref_phase_prefilter *pf) { return pf->packet_table; }

/* Q_j(D) for D >= 0. */
static void antiderivative(const biref_phase_prefilter *pf, double d, double complex q[3])
{
    const biref_spectral *sp = pf->sp;
    if (!(d <= sp->d_max)) {
        /* S's endpoint asymptotics i/(2 pi D) [Λ λ^2 e^{2 pi i D/λ}] integrated once more. */
        const double lmin = sp->cfg.lambda_min_nm, lmax = sp->cfg.lambda_max_nm;
        double complex ph_hi = cycles_exp(d / lmax), ph_lo = cycles_exp(d / lmin);
        double e = 1.0 / (4.0 * M_PI * M_PI * d);
        for (int j = 0; j < 3; j++) q[j] = e * (sp->edge_hi[j] * lmax * ph_hi - sp->edge_lo[j] * lmin * ph_lo);
        return;
    }
    spectral_table_eval(sp, pf->table, d, q);
}

/* Q_j(D) for any D: S(e^{-ikD}) = conj S(e^{ikD}) gives Q(-D) = -conj Q(D). */
static void antiderivative_signed(const biref_phase_prefilter *pf, double d, double complex q[3])
{
    antiderivative(pf, fabs(d), q);
    if (d < 0.0)
        for (int j = 0; j < 3; j++) q[j] = -conj(q[j]);
}

void biref_phase_integrals_box(const biref_phase_prefilter *pf, double opd, double width, double c[3], double s[3])
{
    width = fabs(width);
    if (!(width > BIREF_PREFILTER_POINT_WIDTH_NM)) {
        biref_spectral_phase_integrals(pf->sp, opd, c, s);
        return;
    }
    double lo = opd - 0.5 * width, hi = opd + 0.5 * width;
    const double far = pf->sp->d_far;
    if (lo > far || hi < -far) {
        for (int j = 0; j < 3; j++) c[j] = s[j] = 0.0;
        return;
    }
    double complex qa[3], qb[3];
    antiderivative_signed(pf, lo, qa);
    antiderivative_signed(pf, hi, qb);
    for (int j = 0; j < 3; j++) {
        double complex v = (qb[j] - qa[j]) / width;
        c[j] = creal(v);
        s[j] = cimag(v);
    }
}

void biref_opl_footprint_flip(const biref_opl_footprint *in, biref_opl_footprint *out)
{
    static const int swap[4] = {BIREF_LEG_UP_O, BIREF_LEG_UP_E, BIREF_LEG_DOWN_O, BIREF_LEG_DOWN_E};
    out->pf = in->pf;
    /* The legs' dispersion is per face: a flipped dispersive slab is integrated from its own
     * flipped geometry (analytic_dispersive.c), never through a flipped footprint. */
    out->disp = NULL;
    for (int l = 0; l < 4; l++) {
        out->grad[l][0] = in->grad[swap[l]][0];
        out->grad[l][1] = in->grad[swap[l]][1];
    }
}

void biref_phase_integrals_footprint(const biref_spectral *sp, const biref_opl_footprint *fp, double opd,
                                     const int n[4], double c[3], double s[3])
{
    if (fp && fp->disp) {
        biref_lag_integrals(sp, fp->disp, opd, n, c, s, NULL, NULL);
        return;
    }
    if (!fp || !fp->pf) {
        biref_spectral_phase_integrals(sp, opd, c, s);
        return;
    }
    double gx = 0.0, gy = 0.0;
    for (int l = 0; l < 4; l++) {
        gx += n[l] * fp->grad[l][0];
        gy += n[l] * fp->grad[l][1];
    }
    /* A box of the variance of the pixel's (trapezoidal) distribution of D: (gx^2 + gy^2) / 12. */
    biref_phase_integrals_box(fp->pf, opd, sqrt(gx * gx + gy * gy), c, s);
}
