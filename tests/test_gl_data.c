/* The data the GLSL shader gets for dispersive materials (gpu.h): the sub-band tables sum to the
 * band's own table at every level, a slab's indices are the material's at the plans' samples,
 * the sub-band points, the band centroids and their Gauss nodes (a user Sellmeier material as well
 * as a named one),
 * a constant slab's rows are zero, an unphysical material is reported; the scene uniforms say
 * which slabs are dispersive, and only whole s/p masks reach the scene shader. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "biref/biref.h"
#include "biref/gpu.h"
#include "biref/material.h"
#include "test_cases.h"

static biref_spectral *context(void)
{
    biref_spectral *sp = NULL;
    char msg[BIREF_MSG_SIZE];
    CHECK(biref_spectral_create(NULL, &sp, msg, sizeof msg) == BIREF_OK);
    return sp;
}

/* Level L's 2^L sub-bands add up to the band's table (rows 0-2 of biref_gl_table), texel for
 * texel: the sub-bands split the same midpoint rule. */
static void test_subband_tables_sum_to_the_band_table(void)
{
    biref_spectral *sp = context();
    biref_gl_table_info ti;
    biref_gl_table(sp, &ti, NULL);
    float *band = malloc((size_t)ti.width * ti.height * 4 * sizeof *band);
    biref_gl_table(sp, &ti, band);
    biref_gl_subband_info si;
    CHECK(biref_gl_subband_table(sp, &si, NULL) == BIREF_OK);
    CHECK(si.width == ti.width && si.levels == 5 && si.points == 65 && si.height == 3 * 62);
    float *sub = malloc((size_t)si.width * si.height * 4 * sizeof *sub);
    CHECK(biref_gl_subband_table(sp, &si, sub) == BIREF_OK);
    const size_t W = (size_t)si.width;
    const int stride = test_quick() ? 37 : 1;
    for (int level = 1; level <= si.levels; level++) {
        double worst = 0.0, scale = 0.0;
        for (int j = 0; j < 3; j++)
            for (size_t m = 0; m < W; m += (size_t)stride)
                for (int k = 0; k < 2; k++) { /* the values (the slopes scale with D) */
                    double sum = 0.0;
                    for (int b = 0; b < (1 << level); b++)
                        sum += sub[((3 * (size_t)((1 << level) - 2 + b) + (size_t)j) * W + m) * 4 + (size_t)k];
                    const double ref = band[((size_t)j * W + m) * 4 + (size_t)k];
                    worst = fmax(worst, fabs(sum - ref));
                    scale = fmax(scale, fabs(ref));
                }
        CHECK(scale > 0.1);
        CHECK(worst <= 1e-5 * scale);
    }
    /* A split that is not the band's: one sub-band alone is far from the whole band. */
    CHECK(fabs(sub[4] - band[4]) > 1e-3 || fabs(sub[0] - band[0]) > 1e-3);
    free(band);
    free(sub);
    biref_spectral_destroy(sp);
}

static const char SCENE[] = "{\"camera\": {\"position\": [0, 2, 2], \"look_at\": [0, 0, 0], \"up\": [0, 1, 0],"
                            " \"fov_deg\": 40, \"width\": 16, \"height\": 9},"
                            " \"slabs\": [{\"center\": [0, 0, 0], \"size\": [1, 1], \"thickness_um\": 40,"
                            " \"normal\": [0, 1, 0], \"tangent\": [1, 0, 0], \"axis\": [1, 0, 0], \"eta_o\": 1.5,"
                            " \"eta_e\": 1.6},"
                            " {\"center\": [0, 0.5, 0], \"size\": [1, 1], \"thickness_um\": 40, \"normal\": [0, 1, 0],"
                            " \"tangent\": [1, 0, 0], \"axis\": [1, 0, 0], \"material\": \"calcite\"}],"
                            " \"light\": {\"panels\": [], \"environment\": {\"type\": \"gradient\"}}}";

/* Texel (n_o, n_e, dn_o/dλ, dn_e/dλ) against the material at lambda (float precision). */
static void check_texel(const float *t, const biref_material *m, double lambda)
{
    double n[2], ng[2];
    CHECK(biref_material_indices(m, lambda, n, ng) == BIREF_OK);
    for (int i = 0; i < 2; i++) {
        CHECK_NEAR(t[i], n[i], 1e-6 * n[i]);
        const double slope = (n[i] - ng[i]) / lambda;
        CHECK_NEAR(t[2 + i], slope, 1e-6 * fabs(slope) + 1e-12);
    }
}

/* The nodes' wavenumbers from the scene uniforms (u_band_node_k: node 0's three, then node 1's). */
static float g_node_k[6];

static void grab_nodes(void *user, const char *name, int comps, int count, const float *v)
{
    if (!strcmp(name, "u_band_node_k") && comps == 3 && count == 2) {
        memcpy(g_node_k, v, sizeof g_node_k);
        *(int *)user = 1;
    }
}

static void check_slab_rows(const biref_spectral *sp, const biref_gl_material_info *mi, const float *rows,
                            const biref_material *m)
{
    biref_gl_plans_info pl;
    biref_gl_coherent_plans(sp, &pl, NULL);
    float *plans = malloc((size_t)pl.width * pl.height * 4 * sizeof *plans);
    biref_gl_coherent_plans(sp, &pl, plans);
    CHECK(mi->rows_per_slab == pl.height + 1 && mi->width == pl.width);
    /* Every plan's first and last sample, at the plans' own wavelengths. */
    for (int p = 0, t = 0; p < pl.plans; t += pl.first_samples << p, p++) {
        const int last = t + (pl.first_samples << p) - 1;
        check_texel(rows + 4 * (size_t)t, m, plans[4 * (size_t)t]);
        check_texel(rows + 4 * (size_t)last, m, plans[4 * (size_t)last]);
    }
    const float *pts = rows + (size_t)pl.height * mi->width * 4;
    biref_gl_table_info ti;
    biref_gl_table(sp, &ti, NULL);
    const double klo = 2 * M_PI / ti.lambda_max_nm, khi = 2 * M_PI / ti.lambda_min_nm;
    for (int p = 0; p < 65; p += 8)
        check_texel(pts + 4 * p, m, 2 * M_PI / sqrt(klo * klo + (khi * khi - klo * klo) * p / 64.0));
    for (int j = 0; j < 3; j++) check_texel(pts + 4 * (65 + j), m, 2 * M_PI / ti.k_centroid[j]);
    /* Each band's two Gauss nodes, the wavenumbers the shader is told (u_band_node_k). */
    for (int j = 0; j < 3; j++)
        for (int i = 0; i < 2; i++) check_texel(pts + 4 * (68 + 2 * j + i), m, 2 * M_PI / g_node_k[3 * i + j]);
    free(plans);
}

static void test_material_rows_hold_the_indices(void)
{
    biref_spectral *sp = context();
    biref_scene sc;
    char msg[BIREF_MSG_SIZE];
    CHECK(biref_scene_parse(SCENE, strlen(SCENE), &sc, msg, sizeof msg) == BIREF_OK);
    /* A user Sellmeier material (quartz-like o index, e index 0.009 higher). */
    biref_index_formula o = {BIREF_FORMULA_SELLMEIER, 1.0, 2, {1.35, 0.1}, {0.0107, 100.0}, 0, {0}, {0}, 0.0};
    biref_index_formula e = o;
    e.a = 1.028;
    biref_material *user = NULL;
    CHECK(biref_material_from_formulas("user", &o, &e, NULL, &user, msg, sizeof msg) == BIREF_OK);
    int seen = 0;
    sc.slabs[1].material = biref_material_find("calcite");
    biref_gl_scene_uniforms(&sc, sp, grab_nodes, &seen);
    CHECK(seen);
    /* Two nodes per band, about its centroid, inside the band's range. */
    for (int j = 0; j < 3; j++) {
        biref_gl_table_info ti;
        biref_gl_table(sp, &ti, NULL);
        CHECK(g_node_k[j] < ti.k_centroid[j] && ti.k_centroid[j] < g_node_k[3 + j]);
        CHECK(g_node_k[j] > 2 * M_PI / ti.lambda_max_nm && g_node_k[3 + j] < 2 * M_PI / ti.lambda_min_nm);
    }
    const biref_material *mats[2] = {biref_material_find("calcite"), user};
    for (int k = 0; k < 2; k++) {
        sc.slabs[1].material = mats[k];
        biref_gl_material_info mi;
        CHECK(biref_gl_scene_materials(&sc, sp, &mi, NULL) == BIREF_OK);
        CHECK(mi.dispersive == 1 && mi.height == 2 * mi.rows_per_slab);
        float *t = malloc((size_t)mi.width * mi.height * 4 * sizeof *t);
        CHECK(biref_gl_scene_materials(&sc, sp, &mi, t) == BIREF_OK);
        const size_t slab = (size_t)mi.width * mi.rows_per_slab * 4;
        int zero = 1;
        for (size_t i = 0; i < slab; i++) zero = zero && t[i] == 0.0f; /* the constant slab */
        CHECK(zero);
        check_slab_rows(sp, &mi, t + slab, mats[k]);
        free(t);
    }
    /* Unphysical inside the band (n^2 < 1 below ~430 nm): reported, the texels NaN there. */
    biref_index_formula low = {BIREF_FORMULA_CAUCHY, 1.3, 1, {-0.06}, {0}, 0, {0}, {0}, 0.0};
    biref_material *bad = NULL;
    CHECK(biref_material_from_formulas("low", &low, NULL, NULL, &bad, msg, sizeof msg) == BIREF_OK);
    sc.slabs[1].material = bad;
    biref_gl_material_info mi;
    biref_gl_scene_materials(&sc, sp, &mi, NULL);
    float *t = malloc((size_t)mi.width * mi.height * 4 * sizeof *t);
    CHECK(biref_gl_scene_materials(&sc, sp, &mi, t) == BIREF_ERR_INVALID);
    free(t);
    biref_material_destroy(bad);
    biref_material_destroy(user);
    biref_spectral_destroy(sp);
}

typedef struct {
    float material[2], mask[2];
    int seen;
} uniforms;

static void grab(void *user, const char *name, int comps, int count, const float *v)
{
    uniforms *u = user;
    if (!strcmp(name, "u_slab_material") && comps == 1 && count == 2) {
        memcpy(u->material, v, sizeof u->material);
        u->seen |= 1;
    }
    if (!strcmp(name, "u_mask") && comps == 2 && count == 1) {
        memcpy(u->mask, v, sizeof u->mask);
        u->seen |= 2;
    }
}

/* The shader is told which slabs are dispersive and gets the s/p mask as power fractions. A
 * fractional mask cannot reach it through a scene (biref_scene_validate passes s, p or both
 * only); an embedder's BirefLight.mask is a power fraction, as biref_light_sp's (docs/GPU.md). */
static void test_scene_uniforms_flag_materials_and_pass_the_mask(void)
{
    biref_spectral *sp = context();
    biref_scene sc;
    char msg[BIREF_MSG_SIZE];
    CHECK(biref_scene_parse(SCENE, strlen(SCENE), &sc, msg, sizeof msg) == BIREF_OK);
    CHECK(biref_light_sp((const double[2]){0.3, 0.7}, (const double[2]){0.25, 1.0}, &sc.light) == BIREF_OK);
    CHECK(biref_scene_validate(&sc, msg, sizeof msg) == BIREF_ERR_INVALID);
    CHECK(biref_light_sp((const double[2]){0.3, 0.7}, (const double[2]){0.0, 1.0}, &sc.light) == BIREF_OK);
    CHECK(biref_scene_validate(&sc, msg, sizeof msg) == BIREF_OK);
    uniforms u = {{-1, -1}, {-1, -1}, 0};
    biref_gl_scene_uniforms(&sc, sp, grab, &u);
    CHECK(u.seen == 3);
    CHECK(u.material[0] == 0.0f && u.material[1] == 1.0f);
    CHECK(u.mask[0] == 0.0f && u.mask[1] == 1.0f);
    biref_spectral_destroy(sp);
}

int main(int argc, char **argv)
{
    static const test_case cases[] = {
        {"subband_tables_sum_to_the_band_table", test_subband_tables_sum_to_the_band_table},
        {"material_rows_hold_the_indices", test_material_rows_hold_the_indices},
        {"scene_uniforms_flag_materials_and_pass_the_mask", test_scene_uniforms_flag_materials_and_pass_the_mask},
    };
    return test_run_cases("test_gl_data", cases, TEST_COUNT(cases), argc, argv);
}
