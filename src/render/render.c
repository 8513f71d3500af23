/* The renderer object and the parallel row loop. */
#include <float.h>
#include <math.h>
#include <stdint.h>
#include <omp.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "error.h"
#include "render/render_internal.h"
#include "render/render_tile.h"
#include "render/scene_fields.h"
#include "spectral/integrator_internal.h"
#include "shading/vec3.h"

void biref_render_options_default(biref_render_options *opt)
{
    opt->method = BIREF_METHOD_ANALYTIC;
    opt->samples = 64;
    opt->threads = 0;
    biref_expansion_opts_default(&opt->expansion);
    opt->antialias = BIREF_ANTIALIAS_NONE;
    opt->supersample = 1;
}

/* The options that are the renderer's own; the method's are the shader's (integrator.h). */
static biref_status check_render_options(const biref_render_options *opt, char *msg, size_t msg_len)
{
    if (opt->threads < 0 || opt->threads > 1024)
        return biref_fail(msg, msg_len, "threads must be between 0 and 1024");
    if (opt->antialias != BIREF_ANTIALIAS_NONE && opt->antialias != BIREF_ANTIALIAS_PREFILTER)
        return biref_fail(msg, msg_len, "unknown anti-aliasing mode");
    if (opt->antialias == BIREF_ANTIALIAS_PREFILTER && opt->method != BIREF_METHOD_ANALYTIC &&
        opt->method != BIREF_METHOD_ANALYTIC_PAIRS && opt->method != BIREF_METHOD_EXPANSION)
        return biref_fail(msg, msg_len,
                          "the prefilter anti-aliasing needs an analytic or the expansion method (numeric methods "
                          "have no phase table)");
    if (opt->supersample < 1 || opt->supersample > BIREF_MAX_SUPERSAMPLE)
        return biref_fail(msg, msg_len, "supersample must be between 1 and %d", BIREF_MAX_SUPERSAMPLE);
    return BIREF_OK;
}

/* Dispersive slabs and stack layers: physical over the spectral band (one line, "slabs[i].material: ..."). */
static biref_status check_materials(const biref_spectral *sp, const biref_scene *scene, char *msg, size_t msg_len)
{
    const biref_cmf_band *band = biref_spectral_band(sp);
    for (int i = 0; i < scene->n_slabs; i++) {
        const biref_material *m = scene->slabs[i].material;
        char why[BIREF_MSG_SIZE];
        if (m && biref_material_check_band(m, band->lmin_nm, band->lmax_nm, why, sizeof why) != BIREF_OK)
            return biref_fail(msg, msg_len, "slabs[%d].material: %s", i, why);
        for (int k = 0; k < scene->slabs[i].n_layers; k++) {
            const biref_material *lm = scene->slabs[i].layers[k].material;
            if (lm && biref_material_check_band(lm, band->lmin_nm, band->lmax_nm, why, sizeof why) != BIREF_OK)
                return biref_fail(msg, msg_len, "slabs[%d].layers[%d].material: %s", i, k, why);
        }
    }
    return BIREF_OK;
}

static void slabs_init(biref_renderer *r, const biref_scene *scene)
{
    r->n_slabs = scene->n_slabs;
    for (int i = 0; i < scene->n_slabs; i++) {
        const biref_scene_slab *in = &scene->slabs[i];
        render_slab *sl = &r->slabs[i];
        memcpy(sl->center, in->center, sizeof sl->center);
        memcpy(sl->normal, in->normal, sizeof sl->normal);
        memcpy(sl->tangent, in->tangent, sizeof sl->tangent);
        /* Local z = x cross y = tangent cross normal keeps (x, y, z) right-handed. */
        v3_cross(sl->tangent, sl->normal, sl->bitangent);
        sl->half_w = 0.5 * in->size[0];
        sl->half_h = 0.5 * in->size[1];
        v3_slab_axis_world(in->axis, sl->tangent, sl->normal, sl->axis_world);
        double rel[3];
        v3_sub(sl->center, r->cam.origin, rel);
        sl->center_n = v3_dot(rel, sl->normal);
        sl->is_stack = biref_scene_slab_stack(scene, in, &sl->stack) == BIREF_OK;
        /* A dispersive slab's hits are integrated with n(λ) (biref_shader_eval_material); its base
         * indices only stand in for the frames' and the kernel's set-up. */
        sl->material = in->material;
        sl->base.eta_o = in->material ? 1.5 : in->eta_o;
        sl->base.eta_e = in->material ? 1.5 : in->eta_e;
        sl->base.thickness_nm = in->thickness_nm;
        sl->base.eta_i = scene->eta_medium;
        memcpy(sl->base.axis, in->axis, sizeof sl->base.axis);
    }
}

static void panels_init(biref_renderer *r, const biref_scene *scene)
{
    r->n_panels = scene->n_panels;
    for (int i = 0; i < scene->n_panels; i++) {
        const biref_panel *in = &scene->panels[i];
        render_panel *p = &r->panels[i];
        memcpy(p->center, in->center, sizeof p->center);
        memcpy(p->normal, in->normal, sizeof p->normal);
        memcpy(p->tangent, in->tangent, sizeof p->tangent);
        v3_cross(p->tangent, p->normal, p->bitangent);
        p->half_w = 0.5 * in->size[0];
        p->half_h = 0.5 * in->size[1];
        biref_linear_srgb_to_xyz(in->radiance, p->radiance_xyz);
    }
}

/* The environment's radiances in XYZ and the ground plane's axes (a checker's tiles). */
static void env_init(render_env *e, const biref_environment *env)
{
    e->type = env->type;
    memcpy(e->up, env->up, sizeof e->up);
    double a[3] = {1, 0, 0};
    if (fabs(e->up[0]) > 0.9) v3_set(a, 0, 0, 1);
    v3_orthonormalize(a, e->up, e->e1);
    v3_cross(e->up, e->e1, e->e2);
    biref_linear_srgb_to_xyz(env->zenith, e->zenith);
    biref_linear_srgb_to_xyz(env->horizon, e->horizon);
    biref_linear_srgb_to_xyz(env->ground, e->ground);
    biref_linear_srgb_to_xyz(env->check_a, e->check_a);
    biref_linear_srgb_to_xyz(env->check_b, e->check_b);
    e->check_size = env->check_size;
}

biref_status biref_renderer_create(const biref_spectral *sp, const biref_scene *scene, const biref_render_options *opt,
                                   biref_renderer **out, char *msg, size_t msg_len)
{
    if (!out) return BIREF_ERR_INVALID;
    *out = NULL;
    if (!sp || !scene || !opt) return biref_fail(msg, msg_len, "no spectral context, scene or options");
    biref_status s = biref_scene_validate(scene, msg, msg_len);
    if (!s) s = check_render_options(opt, msg, msg_len);
    if (!s) s = check_materials(sp, scene, msg, msg_len);
    if (s) return s;

    biref_renderer *r = calloc(1, sizeof *r);
    if (!r) return biref_fail_status(BIREF_ERR_NOMEM, msg, msg_len, "out of memory");
    r->opt = *opt;
    biref_render_camera_init(&r->cam, &scene->camera);
    r->exposure = scene->camera.exposure;
    slabs_init(r, scene);
    panels_init(r, scene);
    env_init(&r->env, &scene->env);
    r->tile_isa = biref_render_tile_isa();
    r->centre_sx = malloc((size_t)r->cam.width * sizeof *r->centre_sx);
    if (!r->centre_sx) {
        biref_renderer_destroy(r);
        return biref_fail_status(BIREF_ERR_NOMEM, msg, msg_len, "out of memory");
    }
    biref_render_camera_columns(&r->cam, r->centre_sx);

    biref_integrator_options io;
    biref_integrator_options_default(&io);
    io.method = opt->method;
    io.samples = opt->samples;
    io.expansion = opt->expansion;
    s = biref_shader_create(sp, &io, &scene->light, &r->shader, msg, msg_len);
    if (!s && opt->antialias == BIREF_ANTIALIAS_PREFILTER) {
        s = biref_phase_prefilter_create(sp, &r->prefilter);
        if (s) biref_fail_status(s, msg, msg_len, "out of memory");
    }
    if (s) {
        biref_renderer_destroy(r);
        return s;
    }
    *out = r;
    return BIREF_OK;
}

void biref_renderer_destroy(biref_renderer *r)
{
    if (!r) return;
    biref_shader_destroy(r->shader);
    biref_phase_prefilter_destroy(r->prefilter);
    free(r->centre_sx);
    free(r);
}

int biref_renderer_width(const biref_renderer *r) { return r->cam.width; }
int biref_renderer_height(const biref_renderer *r) { return r->cam.height; }

/* A deterministic value in [0, 1) per pixel and sub-sample: the image does not depend on the
 * thread count or the row order. */
static double jitter(int x, int y, int s, uint32_t salt)
{
    uint32_t h = (uint32_t)x * 0x8da6b343u ^ (uint32_t)y * 0xd8163841u ^ (uint32_t)s * 0xcb1ab31fu ^ salt;
    h ^= h >> 16;
    h *= 0x7feb352du;
    h ^= h >> 15;
    h *= 0x846ca68bu;
    h ^= h >> 16;
    return (h >> 8) * (1.0 / 16777216.0);
}

/* A value that is not finite or beyond float range is stored as 0 and counted. */
static float stored(double v, long *nonfinite)
{
    const int ok = fabs(v) <= FLT_MAX; /* false for infinities and NaN */
    *nonfinite += !ok;
    return (float)(ok ? v : 0.0);
}

/* One sample per pixel, through the centres of pixels x0 .. x0 + n - 1 of row y (n <= RENDER_TILE),
 * stored from out (pixel x0): each sample's colour is its pixel's (the box filter of one sample). */
static void render_centres(const biref_renderer *r, render_tile *tile, int x0, int n, int y, float *out,
                           render_tile_counts *counts)
{
    tile->n = n;
    tile->h = 1.0;
    for (int j = 0; j < n; j++) {
        tile->fx[j] = x0 + j + 0.5;
        tile->fy[j] = y + 0.5;
    }
    tile->sx = r->centre_sx + x0;
    tile->sy = render_camera_sy(&r->cam, y + 0.5);
    tile->out = out;
    biref_render_tile(r, tile, counts);
}

/* Pixels x0 .. x0 + np - 1 of row y, stored from out, K x K stratified jittered samples each (K > 1),
 * box-filtered; with the prefilter each sample's footprint is its stratum
 * (steps of 1/K pixel to the neighbouring samples). The samples go through tiles in pixel order
 * (a pixel's may span several tiles), so each pixel sums its samples in one order. */
static void render_pixels(const biref_renderer *r, render_tile *tile, int x0, int np, int y, float *out,
                          render_tile_counts *counts)
{
    const int K = r->opt.supersample, KK = K * K;
    const double h = 1.0 / K;
    double acc[RENDER_TILE][3] = {{0}};
    int hit[RENDER_TILE] = {0};
    tile->h = h;
    tile->sx = NULL;
    tile->out = NULL;
    for (int done = 0, total = np * KK; done < total; done += tile->n) {
        tile->n = total - done < RENDER_TILE ? total - done : RENDER_TILE;
        for (int j = 0; j < tile->n; j++) {
            const int q = done + j, x = x0 + q / KK, s = q % KK;
            tile->fx[j] = x + (s % K + jitter(x, y, s, 0x9e3779b9u)) * h;
            tile->fy[j] = y + (s / K + jitter(x, y, s, 0x7f4a7c15u)) * h;
        }
        biref_render_tile(r, tile, counts);
        for (int j = 0; j < tile->n; j++) {
            const int p = (done + j) / KK;
            for (int c = 0; c < 3; c++) acc[p][c] += tile->xyz[c][j];
            hit[p] |= tile->slab[j] >= 0.0;
        }
    }
    const double e = r->exposure;
    for (int p = 0; p < np; p++) {
        counts->slab_pixels += hit[p];
        for (int c = 0; c < 3; c++)
            out[3 * (size_t)p + c] = stored(acc[p][c] / (double)KK * e, &counts->nonfinite);
    }
}

/* Pixels x_begin .. x_end - 1 of row y into out (pixel x_begin first), in groups of pixels whose
 * samples fill a tile (one pixel at a time when its samples need more than one). Every pixel's
 * value is the same whatever group it falls in (render_tile_lanes.inc), so a span of a row gives
 * the bits of the whole row. */
static void render_span(const biref_renderer *r, int y, int x_begin, int x_end, float *out, render_tile_counts *counts)
{
    const int KK = r->opt.supersample * r->opt.supersample;
    const int group = KK <= RENDER_TILE ? RENDER_TILE / KK : 1;
    render_tile tile;
    for (int x0 = x_begin; x0 < x_end; x0 += group) {
        const int n = x_end - x0 < group ? x_end - x0 : group;
        float *o = out + 3 * (size_t)(x0 - x_begin);
        if (KK == 1)
            render_centres(r, &tile, x0, n, y, o, counts);
        else
            render_pixels(r, &tile, x0, n, y, o, counts);
    }
}

/* Rows y_begin + k y_step (k < rows), pixels x_begin .. x_end - 1 of each, row k stored from
 * out + k stride: the parallel loop of every render entry. */
static biref_status render_rows(const biref_renderer *r, int x_begin, int x_end, int y_begin, int rows, int y_step,
                                float *out, size_t stride, biref_progress_fn progress, void *progress_user,
                                biref_render_stats *stats)
{
    const int threads = r->opt.threads > 0 ? r->opt.threads : omp_get_max_threads();
    long slab_pixels = 0, fallbacks = 0, nonfinite = 0;
    int done = 0;
    /* Rows are independent and every pixel is computed the same way on any thread, so the
     * image does not depend on the thread count; dynamic scheduling balances rows that miss
     * the slab (cheap) against rows that hit it (expensive). */
#pragma omp parallel for schedule(dynamic) num_threads(threads) reduction(+ : slab_pixels, fallbacks, nonfinite)
    for (int k = 0; k < rows; k++) {
        render_tile_counts c = {0, 0, 0};
        render_span(r, y_begin + k * y_step, x_begin, x_end, out + (size_t)k * stride, &c);
        slab_pixels += c.slab_pixels;
        fallbacks += c.fallbacks;
        nonfinite += c.nonfinite;
        if (progress) {
#pragma omp critical(biref_render_progress)
            {
                done++;
                progress(progress_user, done, rows);
            }
        }
    }
    if (stats) {
        stats->pixels = (long)rows * (x_end - x_begin);
        stats->slab_pixels = slab_pixels;
        stats->fallback_evals = fallbacks;
    }
    /* A non-finite colour is never an output: such pixels are stored as 0 and reported. */
    return nonfinite ? BIREF_ERR_ILLCOND : BIREF_OK;
}

biref_status biref_renderer_render(const biref_renderer *r, int y_begin, int y_end, int y_step, float *xyz,
                                   biref_progress_fn progress, void *progress_user, biref_render_stats *stats)
{
    if (!r || !xyz || y_step < 1 || y_begin < 0 || y_end > r->cam.height || y_begin > y_end) return BIREF_ERR_INVALID;
    const int W = r->cam.width;
    const int rows = (y_end - y_begin + y_step - 1) / y_step;
    return render_rows(r, 0, W, y_begin, rows, y_step, xyz + (size_t)y_begin * W * 3, (size_t)y_step * W * 3, progress,
                       progress_user, stats);
}

biref_status biref_renderer_render_rect(const biref_renderer *r, int x, int y, int width, int height, float *xyz,
                                        size_t row_stride, biref_render_stats *stats)
{
    if (!r || !xyz || x < 0 || y < 0 || width < 1 || height < 1 || width > r->cam.width - x ||
        height > r->cam.height - y || row_stride < 3 * (size_t)width)
        return BIREF_ERR_INVALID;
    return render_rows(r, x, x + width, y, height, 1, xyz, row_stride, NULL, NULL, stats);
}

biref_status biref_render_image(const biref_renderer *r, float *xyz, biref_progress_fn progress, void *progress_user,
                                biref_render_stats *stats)
{
    if (!r) return BIREF_ERR_INVALID;
    return biref_renderer_render(r, 0, r->cam.height, 1, xyz, progress, progress_user, stats);
}
