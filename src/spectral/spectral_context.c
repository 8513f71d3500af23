/* The spectral context: band-normalised colour-matching functions and the look-up table of
 * S(cos(k D), Λ) and S(sin(k D), Λ) used by the analytic method (paper §5.2). */
#include <complex.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "error.h"
#include "spectral/spectral_internal.h"
#include "spectral/phase_tables.h"
#include "spectral/subband.h"
#include "spectral/table_build.h"

/* Quadrature step for the direct (reference) evaluation. */
#define DIRECT_DLAMBDA_NM 0.002
/* |S(e^{ikD})| <= (edge_lo + edge_hi) / (2 pi D) beyond the table; below this bound it is dropped. */
#define FAR_FIELD_BOUND 1e-5

void biref_spectral_config_default(biref_spectral_config *cfg)
{
    cfg->cmf = BIREF_CMF_CIE1931;
    cfg->lambda_min_nm = BIREF_CMF_DEFAULT_LMIN_NM;
    cfg->lambda_max_nm = BIREF_CMF_DEFAULT_LMAX_NM;
}

static const char *const METHOD_NAMES[] = {"analytic", "numeric", "ground-truth", "expansion", "analytic-pairs"};
#define N_METHODS ((int)(sizeof METHOD_NAMES / sizeof METHOD_NAMES[0]))

biref_status biref_method_from_name(const char *name, biref_method *out)
{
    if (!name || !out) return BIREF_ERR_INVALID;
    for (int i = 0; i < N_METHODS; i++)
        if (!strcmp(name, METHOD_NAMES[i])) {
            *out = (biref_method)i;
            return BIREF_OK;
        }
    return BIREF_ERR_INVALID;
}

const char *biref_method_name(biref_method m)
{
    return ((int)m >= 0 && (int)m < N_METHODS) ? METHOD_NAMES[m] : NULL;
}

const biref_cmf_band *biref_spectral_band(const biref_spectral *sp) { return &sp->band; }

/* The point table of a band: the copy generated at build time for the default band
 * (phase_tables.h), else by quadrature. */
static biref_status fill_table(biref_spectral *sp, const biref_phase_grid *g)
{
    const biref_phase_tables_builtin *gen = biref_phase_tables_builtin_for(&sp->cfg, g->nodes);
    if (gen) {
        memcpy(sp->table, gen->point, (size_t)g->nodes * BIREF_TABLE_ROW * sizeof *sp->table);
        return BIREF_OK;
    }
    return biref_phase_table_point(g, sp->table);
}

const biref_phase_tables_builtin *biref_phase_tables_builtin_for(const biref_spectral_config *cfg, int nodes)
{
    const biref_phase_tables_builtin *gen = &biref_phase_tables_generated;
    if (gen->nodes == 0 || gen->nodes != nodes || gen->cmf != cfg->cmf || gen->lambda_min_nm != cfg->lambda_min_nm ||
        gen->lambda_max_nm != cfg->lambda_max_nm)
        return NULL;
    return gen;
}

biref_status biref_spectral_create(const biref_spectral_config *cfg_in, biref_spectral **out, char *msg, size_t msg_len)
{
    if (!out) return biref_fail(msg, msg_len, "no output");
    *out = NULL;
    biref_spectral_config cfg;
    if (cfg_in)
        cfg = *cfg_in;
    else
        biref_spectral_config_default(&cfg);
    if (!isfinite(cfg.lambda_min_nm) || !isfinite(cfg.lambda_max_nm) || cfg.lambda_min_nm <= 0.0 ||
        cfg.lambda_max_nm <= cfg.lambda_min_nm)
        return biref_fail(msg, msg_len, "%g-%g nm is not a band (expected 0 < min < max, both finite)", cfg.lambda_min_nm,
                          cfg.lambda_max_nm);
    /* Only where the colour-matching data is defined: the table resolution and the far limit
     * below assume a visible band (half-width in 1/lambda <= 8e-4 / nm), and every sample count
     * below is then small (<= 9400 build samples). */
    double dom_lo, dom_hi;
    if (biref_cmf_domain(cfg.cmf, &dom_lo, &dom_hi) != BIREF_OK)
        return biref_fail(msg, msg_len, "unknown colour-matching functions (%d)", (int)cfg.cmf);
    if (cfg.lambda_min_nm < dom_lo || cfg.lambda_max_nm > dom_hi)
        return biref_fail(msg, msg_len, "%g-%g nm is not covered by the %s colour-matching functions (%g-%g nm)",
                          cfg.lambda_min_nm, cfg.lambda_max_nm, biref_cmf_kind_name(cfg.cmf), dom_lo, dom_hi);
    biref_spectral *sp = calloc(1, sizeof *sp);
    if (!sp) return biref_fail_status(BIREF_ERR_NOMEM, msg, msg_len, "out of memory");
    sp->cfg = cfg;
    biref_status s = biref_cmf_band_init(&sp->band, cfg.cmf, cfg.lambda_min_nm, cfg.lambda_max_nm, msg, msg_len);
    if (s != BIREF_OK) {
        free(sp);
        return s;
    }
    biref_phase_grid grid;
    biref_phase_grid_init(&grid, &sp->band, cfg.lambda_min_nm, cfg.lambda_max_nm);
    sp->nu_c = grid.nu_c;
    sp->step = grid.step;
    sp->inv_step = 1.0 / grid.step;
    sp->nodes = grid.nodes;
    sp->d_max = (sp->nodes - 1) * sp->step;
    sp->table = calloc((size_t)sp->nodes * BIREF_TABLE_ROW, sizeof *sp->table);
    if (!sp->table) {
        free(sp);
        return biref_fail_status(BIREF_ERR_NOMEM, msg, msg_len, "out of memory");
    }
    if (fill_table(sp, &grid) != BIREF_OK) {
        biref_spectral_destroy(sp);
        return biref_fail_status(BIREF_ERR_NOMEM, msg, msg_len, "out of memory");
    }
    sp->carrier = malloc((size_t)sp->nodes * 2 * sizeof *sp->carrier);
    if (!sp->carrier) {
        biref_spectral_destroy(sp);
        return biref_fail_status(BIREF_ERR_NOMEM, msg, msg_len, "out of memory");
    }
    for (int m = 0; m < sp->nodes; m++) {
        double complex z = cexp(2.0 * M_PI * I * sp->nu_c * m * sp->step);
        sp->carrier[2 * m] = creal(z);
        sp->carrier[2 * m + 1] = cimag(z);
    }
    /* Nodes * 128 bytes: a whole number of 64-byte lines, as aligned_alloc requires. */
    sp->packet_table = aligned_alloc(64, (size_t)sp->nodes * BIREF_PACKET_TABLE_STRIDE * sizeof *sp->packet_table);
    if (!sp->packet_table) {
        biref_spectral_destroy(sp);
        return biref_fail_status(BIREF_ERR_NOMEM, msg, msg_len, "out of memory");
    }
    biref_table_packet_layout(sp->table, sp->carrier, sp->nodes, sp->packet_table);
    /* Nodes * 128 bytes. */
    sp->packet_table_f32 =
        aligned_alloc(64, (size_t)sp->nodes * BIREF_PACKET_TABLE_F32_STRIDE * sizeof *sp->packet_table_f32);
    if (!sp->packet_table_f32) {
        biref_spectral_destroy(sp);
        return biref_fail_status(BIREF_ERR_NOMEM, msg, msg_len, "out of memory");
    }
    biref_table_packet_layout_f32(sp->packet_table, sp->nodes, sp->packet_table_f32);
    double lo[3], hi[3];
    biref_cmf_band_eval(&sp->band, cfg.lambda_min_nm, lo);
    biref_cmf_band_eval(&sp->band, cfg.lambda_max_nm, hi);
    for (int j = 0; j < 3; j++) {
        sp->edge_lo[j] = lo[j] * cfg.lambda_min_nm * cfg.lambda_min_nm;
        sp->edge_hi[j] = hi[j] * cfg.lambda_max_nm * cfg.lambda_max_nm;
    }
    double edge = 0.0;
    for (int j = 0; j < 3; j++) edge = fmax(edge, sp->edge_lo[j] + sp->edge_hi[j]);
    sp->d_far = fmax(sp->d_max, edge / (2.0 * M_PI * FAR_FIELD_BOUND));
    /* Wavenumber centroids by the same fine midpoint rule. */
    const int n = (int)ceil((cfg.lambda_max_nm - cfg.lambda_min_nm) / BIREF_TABLE_BUILD_DLAMBDA_NM);
    const double dl = (cfg.lambda_max_nm - cfg.lambda_min_nm) / n;
    for (int i = 0; i < n; i++) {
        double lambda = cfg.lambda_min_nm + (i + 0.5) * dl, lam[3];
        biref_cmf_band_eval(&sp->band, lambda, lam);
        for (int j = 0; j < 3; j++) sp->k_centroid[j] += lam[j] * dl * 2.0 * M_PI / lambda;
    }
    for (int i = 0; i < BIREF_COHERENT_PLANS; i++) {
        s = biref_numeric_plan_create(sp, 48 << i, &sp->coherent[i], msg, msg_len);
        if (s != BIREF_OK) {
            biref_spectral_destroy(sp);
            return s;
        }
        sp->n_coherent = i + 1;
    }
    *out = sp;
    return BIREF_OK;
}

void biref_spectral_destroy(biref_spectral *sp)
{
    if (!sp) return;
    free(sp->table);
    free(sp->carrier);
    free(sp->packet_table);
    free(sp->packet_table_f32);
    for (int i = 0; i < sp->n_coherent; i++) biref_numeric_plan_destroy(sp->coherent[i]);
    biref_subbands_destroy(atomic_load_explicit(&sp->subbands, memory_order_acquire));
    free(sp);
}

void biref_spectral_phase_integrals(const biref_spectral *sp, double opd, double c[3], double s[3])
{
    double sign = 1.0;
    if (opd < 0.0) {
        opd = -opd;
        sign = -1.0; /* cos is even in D, sin odd */
    }
    if (opd > sp->d_far) {
        for (int j = 0; j < 3; j++) c[j] = s[j] = 0.0;
        return;
    }
    if (!(opd <= sp->d_max)) {
        /* Endpoint asymptotics (integration by parts once; next term is O(1/D^2)). */
        double complex e = I / (2.0 * M_PI * opd);
        double complex ph_hi = cycles_exp(opd / sp->cfg.lambda_max_nm);
        double complex ph_lo = cycles_exp(opd / sp->cfg.lambda_min_nm);
        for (int j = 0; j < 3; j++) {
            double complex v = e * (sp->edge_hi[j] * ph_hi - sp->edge_lo[j] * ph_lo);
            c[j] = creal(v);
            s[j] = sign * cimag(v);
        }
        return;
    }
    double complex v[3];
    spectral_table_eval(sp, sp->table, opd, v);
    for (int j = 0; j < 3; j++) {
        c[j] = creal(v[j]);
        s[j] = sign * cimag(v[j]);
    }
}

void biref_spectral_phase_integrals_direct(const biref_spectral *sp, double opd, double c[3], double s[3])
{
    const double lmin = sp->cfg.lambda_min_nm, lmax = sp->cfg.lambda_max_nm;
    const int n = (int)ceil((lmax - lmin) / DIRECT_DLAMBDA_NM);
    const double dl = (lmax - lmin) / n;
    for (int j = 0; j < 3; j++) c[j] = s[j] = 0.0;
    for (int i = 0; i < n; i++) {
        double lambda = lmin + (i + 0.5) * dl, lam[3];
        biref_cmf_band_eval(&sp->band, lambda, lam);
        double ph = 2.0 * M_PI * opd / lambda, cp = cos(ph), spn = sin(ph);
        for (int j = 0; j < 3; j++) {
            c[j] += lam[j] * dl * cp;
            s[j] += lam[j] * dl * spn;
        }
    }
}
