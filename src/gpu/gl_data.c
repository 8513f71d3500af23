/* The shader's data from the C library: the look-up table and every scene uniform. Both
 * back-ends (native OpenGL and the browser page) load exactly these values. */
#include <complex.h>
#include <math.h>
#include <string.h>

#include "biref/gpu.h"
#include "shading/vec3.h"
#include "spectral/spectral_internal.h"
#include "spectral/subband.h"

extern const char biref_gl_shader_text[];

const char *biref_gl_shader_source(void) { return biref_gl_shader_text; }

void biref_gl_table(const biref_spectral *sp, biref_gl_table_info *info, float *texels)
{
    info->width = sp->nodes;
    info->height = 4;
    info->step_nm = sp->step;
    info->d_max_nm = sp->d_max;
    info->d_far_nm = sp->d_far;
    info->nu_c = sp->nu_c;
    info->lambda_min_nm = sp->cfg.lambda_min_nm;
    info->lambda_max_nm = sp->cfg.lambda_max_nm;
    for (int j = 0; j < 3; j++) {
        info->edge_lo[j] = sp->edge_lo[j];
        info->edge_hi[j] = sp->edge_hi[j];
        info->k_centroid[j] = sp->k_centroid[j];
    }
    if (!texels) return;
    const size_t W = (size_t)sp->nodes;
    for (size_t m = 0; m < W; m++) {
        const double *row = sp->table + m * 12;
        for (int j = 0; j < 3; j++)
            for (int k = 0; k < 4; k++) texels[((size_t)j * W + m) * 4 + k] = (float)row[4 * j + k];
        float *c = texels + (3 * W + m) * 4;
        c[0] = (float)sp->carrier[2 * m];
        c[1] = (float)sp->carrier[2 * m + 1];
        c[2] = c[3] = 0.0f;
    }
}

#define PLANS_WIDTH 2048

void biref_gl_coherent_plans(const biref_spectral *sp, biref_gl_plans_info *info, float *texels)
{
    size_t total = 0;
    for (int i = 0; i < sp->n_coherent; i++) total += (size_t)sp->coherent[i]->samples;
    info->width = PLANS_WIDTH;
    info->height = (int)((total + PLANS_WIDTH - 1) / PLANS_WIDTH);
    info->plans = sp->n_coherent;
    info->first_samples = sp->n_coherent ? sp->coherent[0]->samples : 0;
    if (!texels) return;
    memset(texels, 0, (size_t)info->width * info->height * 4 * sizeof *texels);
    size_t t = 0;
    for (int i = 0; i < sp->n_coherent; i++) {
        const biref_numeric_plan *p = sp->coherent[i];
        for (int n = 0; n < p->samples; n++, t++) {
            texels[4 * t] = (float)p->lambda[n];
            for (int j = 0; j < 3; j++) texels[4 * t + 1 + j] = (float)p->weight[n][j];
        }
    }
}

static void emit1(biref_gl_uniform_fn fn, void *user, const char *name, double v)
{
    float f = (float)v;
    fn(user, name, 1, 1, &f);
}

static void emitv(biref_gl_uniform_fn fn, void *user, const char *name, int comps, const double *v)
{
    float f[4];
    for (int i = 0; i < comps; i++) f[i] = (float)v[i];
    fn(user, name, comps, 1, f);
}

/* Array uniforms: n elements of comps components gathered by get(i, out). */
#define EMIT_ARRAY(NAME, COMPS, N, EXPR)                                                                               \
    do {                                                                                                               \
        float buf_[BIREF_SCENE_MAX_SLABS * 3];                                                                         \
        for (int i = 0; i < (N); i++) {                                                                                \
            double v_[3];                                                                                              \
            EXPR;                                                                                                      \
            for (int k = 0; k < (COMPS); k++) buf_[i * (COMPS) + k] = (float)v_[k];                                    \
        }                                                                                                              \
        if ((N) > 0) fn(user, NAME, COMPS, N, buf_);                                                                   \
    } while (0)

void biref_gl_scene_uniforms(const biref_scene *scene, const biref_spectral *sp, biref_gl_uniform_fn fn, void *user)
{
    /* Camera: as biref_render_camera_init. */
    const biref_camera *cam = &scene->camera;
    double f[3], r[3], u[3];
    v3_sub(cam->look_at, cam->position, f);
    v3_normalize(f, f);
    v3_cross(f, cam->up, r);
    v3_normalize(r, r);
    v3_cross(r, f, u);
    double res[2] = {cam->width, cam->height};
    double tv = tan(0.5 * cam->fov_deg * M_PI / 180.0);
    double tan_half[2] = {tv * (double)cam->width / (double)cam->height, tv};
    emitv(fn, user, "u_resolution", 2, res);
    emitv(fn, user, "u_cam_origin", 3, cam->position);
    emitv(fn, user, "u_cam_forward", 3, f);
    emitv(fn, user, "u_cam_right", 3, r);
    emitv(fn, user, "u_cam_up", 3, u);
    emitv(fn, user, "u_cam_tan_half", 2, tan_half);
    emit1(fn, user, "u_exposure", cam->exposure);
    emit1(fn, user, "u_eta_medium", scene->eta_medium);

    /* Slabs: local z = tangent x normal; optic axis to world, as the CPU renderer. */
    const int ns = scene->n_slabs;
    const biref_scene_slab *S = scene->slabs;
    emit1(fn, user, "u_n_slabs", ns);
    EMIT_ARRAY("u_slab_center", 3, ns, memcpy(v_, S[i].center, sizeof v_));
    EMIT_ARRAY("u_slab_normal", 3, ns, memcpy(v_, S[i].normal, sizeof v_));
    EMIT_ARRAY("u_slab_tangent", 3, ns, memcpy(v_, S[i].tangent, sizeof v_));
    EMIT_ARRAY("u_slab_bitangent", 3, ns, v3_cross(S[i].tangent, S[i].normal, v_));
    EMIT_ARRAY("u_slab_half", 2, ns, (v_[0] = 0.5 * S[i].size[0], v_[1] = 0.5 * S[i].size[1]));
    EMIT_ARRAY("u_slab_axis", 3, ns, v3_slab_axis_world(S[i].axis, S[i].tangent, S[i].normal, v_));
    EMIT_ARRAY("u_slab_optics", 3, ns, (v_[0] = S[i].eta_o, v_[1] = S[i].eta_e, v_[2] = S[i].thickness_nm));
    /* 1: a dispersive material, its indices in the texture of biref_gl_scene_materials. */
    EMIT_ARRAY("u_slab_material", 1, ns, v_[0] = S[i].material != NULL);

    const int np = scene->n_panels;
    const biref_panel *P = scene->panels;
    emit1(fn, user, "u_n_panels", np);
    EMIT_ARRAY("u_panel_center", 3, np, memcpy(v_, P[i].center, sizeof v_));
    EMIT_ARRAY("u_panel_normal", 3, np, memcpy(v_, P[i].normal, sizeof v_));
    EMIT_ARRAY("u_panel_tangent", 3, np, memcpy(v_, P[i].tangent, sizeof v_));
    EMIT_ARRAY("u_panel_bitangent", 3, np, v3_cross(P[i].tangent, P[i].normal, v_));
    EMIT_ARRAY("u_panel_half", 2, np, (v_[0] = 0.5 * P[i].size[0], v_[1] = 0.5 * P[i].size[1]));
    EMIT_ARRAY("u_panel_radiance", 3, np, biref_linear_srgb_to_xyz(P[i].radiance, v_));

    /* Environment: as biref_render_env_init. */
    const biref_environment *env = &scene->env;
    double e1[3] = {1, 0, 0}, e2[3], a[3] = {1, 0, 0}, xyz[3];
    if (fabs(env->up[0]) > 0.9) v3_set(a, 0, 0, 1);
    v3_orthonormalize(a, env->up, e1);
    v3_cross(env->up, e1, e2);
    emit1(fn, user, "u_env_checker", env->type == BIREF_ENV_CHECKER);
    emitv(fn, user, "u_env_up", 3, env->up);
    emitv(fn, user, "u_env_e1", 3, e1);
    emitv(fn, user, "u_env_e2", 3, e2);
    biref_linear_srgb_to_xyz(env->zenith, xyz);
    emitv(fn, user, "u_env_zenith", 3, xyz);
    biref_linear_srgb_to_xyz(env->horizon, xyz);
    emitv(fn, user, "u_env_horizon", 3, xyz);
    biref_linear_srgb_to_xyz(env->ground, xyz);
    emitv(fn, user, "u_env_ground", 3, xyz);
    biref_linear_srgb_to_xyz(env->check_a, xyz);
    emitv(fn, user, "u_env_check_a", 3, xyz);
    biref_linear_srgb_to_xyz(env->check_b, xyz);
    emitv(fn, user, "u_env_check_b", 3, xyz);
    emit1(fn, user, "u_env_check_size", env->check_size);

    /* Polarisation: the paper's s/p model as a diagonal coherency matrix and mask, world-fixed
     * polarizers as directions (docs/SCENES.md). */
    const biref_light *l = &scene->light;
    const int sp_mask = l->has_analyzer && !l->world_analyzer;
    double pv[4] = {l->world_polarizer, l->world_polarizer ? 0.5 : creal(l->C[0][0]),
                    l->world_polarizer ? 0.5 : creal(l->C[1][1]), l->world_analyzer};
    double mask[2] = {sp_mask ? l->mask[0] : 1.0, sp_mask ? l->mask[1] : 1.0}; /* power fractions */
    double zero[3] = {0, 0, 0};
    emitv(fn, user, "u_pol", 4, pv);
    emitv(fn, user, "u_mask", 2, mask);
    emitv(fn, user, "u_pol_dir", 3, l->world_polarizer ? l->polarizer_axis : zero);
    emitv(fn, user, "u_filter_dir", 3, l->world_analyzer ? l->analyzer_axis : zero);

    /* XYZ (white E) -> linear sRGB, row by row, from the library's own conversion. */
    float m[9];
    for (int c = 0; c < 3; c++) {
        double e[3] = {c == 0, c == 1, c == 2}, rgb[3];
        biref_xyz_to_linear_srgb(e, rgb);
        for (int row = 0; row < 3; row++) m[3 * row + c] = (float)rgb[row];
    }
    fn(user, "u_rgb_from_xyz", 3, 3, m);

    biref_gl_table_info t;
    biref_gl_table(sp, &t, NULL);
    double grid[4] = {t.step_nm, t.width, t.d_max_nm, t.d_far_nm};
    double band[4] = {t.nu_c, t.lambda_min_nm, t.lambda_max_nm, 0.0};
    emitv(fn, user, "u_lut_grid", 4, grid);
    emitv(fn, user, "u_lut_band", 4, band);
    emitv(fn, user, "u_lut_edge_lo", 3, t.edge_lo);
    emitv(fn, user, "u_lut_edge_hi", 3, t.edge_hi);
    emitv(fn, user, "u_k_centroid", 3, t.k_centroid);
    /* Dispersive materials: each band's two Gauss nodes and their masses (biref_band_nodes; the
     * sub-band tables are made for them only when a slab has a material). */
    float nodes_k[6] = {0}, nodes_mass[6] = {0};
    const biref_subbands *sb = NULL;
    for (int i = 0; i < ns && !sb; i++)
        if (S[i].material) sb = biref_spectral_subbands(sp);
    if (sb) {
        const biref_band_nodes *bn = biref_subband_nodes(sb);
        for (int i = 0; i < BIREF_BAND_NODES; i++)
            for (int j = 0; j < 3; j++) {
                nodes_k[3 * i + j] = (float)bn->k[j][i];
                nodes_mass[3 * i + j] = (float)bn->mass[j][i];
            }
    }
    fn(user, "u_band_node_k", 3, 2, nodes_k);
    fn(user, "u_band_node_mass", 3, 2, nodes_mass);
    biref_gl_plans_info pl;
    biref_gl_coherent_plans(sp, &pl, NULL);
    double plan_grid[4] = {pl.width, pl.plans, pl.first_samples, pl.height + 1};
    emitv(fn, user, "u_plan_grid", 4, plan_grid);
}
