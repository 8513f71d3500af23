/* The shader's data for dispersive materials (docs/PHYSICS.md §7, docs/GPU.md): the sub-band
 * tables as one texture and, per slab of a dispersive material, its indices where the shader
 * needs them: at the band centroids and each band's two Gauss nodes (the band states' modes and
 * Fresnel coefficients), at the
 * sub-band sample points with their slopes (the legs' group paths and phase offsets) and at every
 * sample of the coherent regime's plans (the exact integral with n(λ)). The same numbers the CPU
 * path evaluates in double precision, handed over as floats. */
#include <math.h>
#include <string.h>

#include "biref/gpu.h"
#include "biref/material.h"
#include "spectral/spectral_internal.h"
#include "spectral/subband.h"

biref_status biref_gl_subband_table(const biref_spectral *sp, biref_gl_subband_info *info, float *texels)
{
    const int tables = (1 << (BIREF_SUBBAND_LEVELS + 1)) - 2; /* levels 1..L: 2 + 4 + ... + 2^L */
    info->width = sp->nodes;
    info->height = 3 * tables;
    info->levels = BIREF_SUBBAND_LEVELS;
    info->points = BIREF_SUBBAND_POINTS;
    if (!texels) return BIREF_OK;
    const biref_subbands *sb = biref_spectral_subbands(sp);
    if (!sb) return BIREF_ERR_NOMEM;
    const size_t W = (size_t)sp->nodes;
    for (int level = 1; level <= BIREF_SUBBAND_LEVELS; level++)
        for (int b = 0; b < (1 << level); b++) {
            const double *t = biref_subband_table(sb, level, b);
            const size_t row0 = 3 * (size_t)((1 << level) - 2 + b);
            for (size_t m = 0; m < W; m++)
                for (int j = 0; j < 3; j++)
                    for (int k = 0; k < 4; k++) texels[((row0 + (size_t)j) * W + m) * 4 + k] = (float)t[m * 12 + 4 * j + k];
        }
    return BIREF_OK;
}

/* Texel (n_o, n_e, dn_o/dλ, dn_e/dλ) at lambda; NaN where the material is unphysical. */
static biref_status indices_texel(const biref_material *m, double lambda, float out[4])
{
    double n[2], ng[2];
    biref_status s = biref_material_indices(m, lambda, n, ng);
    for (int i = 0; i < 2; i++) {
        out[i] = s == BIREF_OK ? (float)n[i] : NAN;
        /* n_g = n − λ dn/dλ */
        out[2 + i] = s == BIREF_OK ? (float)((n[i] - ng[i]) / lambda) : NAN;
    }
    return s;
}

static biref_status slab_rows(const biref_spectral *sp, const biref_material *m, int width, int plan_rows, float *rows)
{
    biref_status r = BIREF_OK, s;
    /* The coherent regime's plans, texel for texel as biref_gl_coherent_plans. */
    size_t t = 0;
    for (int i = 0; i < sp->n_coherent; i++) {
        const biref_numeric_plan *p = sp->coherent[i];
        for (int n = 0; n < p->samples; n++, t++)
            if ((s = indices_texel(m, p->lambda[n], rows + 4 * t)) != BIREF_OK) r = s;
    }
    float *last = rows + (size_t)plan_rows * width * 4;
    /* The sub-band sample points: uniform in k^2 over the range (biref_subband_points). */
    const double klo = 2.0 * M_PI / sp->cfg.lambda_max_nm, khi = 2.0 * M_PI / sp->cfg.lambda_min_nm;
    for (int p = 0; p < BIREF_SUBBAND_POINTS; p++) {
        const double k = sqrt(klo * klo + (khi * khi - klo * klo) * p / (BIREF_SUBBAND_POINTS - 1));
        if ((s = indices_texel(m, 2.0 * M_PI / k, last + 4 * p)) != BIREF_OK) r = s;
    }
    /* The band centroids, then each band's two Gauss nodes: the wavelengths of the band states. */
    for (int j = 0; j < 3; j++)
        if ((s = indices_texel(m, 2.0 * M_PI / sp->k_centroid[j], last + 4 * (BIREF_SUBBAND_POINTS + j))) != BIREF_OK) r = s;
    const biref_subbands *sb = biref_spectral_subbands(sp);
    if (!sb) return BIREF_ERR_NOMEM;
    const biref_band_nodes *bn = biref_subband_nodes(sb);
    for (int j = 0; j < 3; j++)
        for (int i = 0; i < BIREF_BAND_NODES; i++)
            if ((s = indices_texel(m, 2.0 * M_PI / bn->k[j][i], last + 4 * (BIREF_SUBBAND_POINTS + 3 + 2 * j + i))) !=
                BIREF_OK)
                r = s;
    return r;
}

biref_status biref_gl_scene_materials(const biref_scene *scene, const biref_spectral *sp, biref_gl_material_info *info,
                                      float *texels)
{
    biref_gl_plans_info pl;
    biref_gl_coherent_plans(sp, &pl, NULL);
    info->width = pl.width;
    info->rows_per_slab = pl.height + 1;
    info->height = scene->n_slabs * info->rows_per_slab;
    info->dispersive = 0;
    for (int i = 0; i < scene->n_slabs; i++) info->dispersive += scene->slabs[i].material != NULL;
    if (!texels) return BIREF_OK;
    const size_t slab_texels = (size_t)info->width * info->rows_per_slab * 4;
    memset(texels, 0, slab_texels * scene->n_slabs * sizeof *texels);
    biref_status r = BIREF_OK;
    for (int i = 0; i < scene->n_slabs; i++) {
        const biref_material *m = scene->slabs[i].material;
        biref_status s = m ? slab_rows(sp, m, info->width, pl.height, texels + slab_texels * i) : BIREF_OK;
        if (s != BIREF_OK) r = s;
    }
    return r;
}
