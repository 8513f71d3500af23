/* A row segment shaded as structure of arrays (render_tile.h). Each step below does, for every
 * pixel of the tile, the operations of the scalar per-pixel path (camera.c, shade.c,
 * hit_frames.c) in the same order, so the geometry and the radiance are the same to the bit and
 * the image does not depend on how pixels are grouped or on the thread count. */
#include <float.h>
#include <math.h>
#include <string.h>

#include "render/radiance.h"
#include "render/render_tile.h"
#include "render/vec3.h"

/* Unit rays through the pixel centres, as biref_render_camera_ray. */
static void tile_rays(const render_camera *c, render_tile *tl)
{
    const double sy = (1.0 - 2.0 * (tl->y + 0.5) / c->height) * c->tan_half_v;
    for (int j = 0; j < tl->n; j++) {
        const double sx = (2.0 * (tl->x0 + j + 0.5) / c->width - 1.0) * c->tan_half_h;
        double d[3];
        for (int i = 0; i < 3; i++) d[i] = c->forward[i] + sx * c->right[i] + sy * c->up[i];
        /* A camera ray is never zero: forward is a unit vector orthogonal to right and up. */
        const double inv = 1.0 / v3_len(d);
        for (int i = 0; i < 3; i++) tl->dir[i][j] = d[i] * inv;
    }
}

/* The nearest slab of every pixel, as biref_render_nearest_slab, branch-free across pixels. */
static void tile_nearest_slabs(const biref_renderer *r, render_tile *tl)
{
    const double *o = r->cam.origin;
    for (int j = 0; j < tl->n; j++) {
        tl->t[j] = INFINITY;
        tl->slab[j] = -1;
    }
    for (int i = 0; i < r->n_slabs; i++) {
        const render_slab *sl = &r->slabs[i];
        for (int j = 0; j < tl->n; j++) {
            const double d[3] = {tl->dir[0][j], tl->dir[1][j], tl->dir[2][j]};
            const double dn = v3_dot(d, sl->normal);
            const int facing = fabs(dn) >= 1e-12; /* edge-on: a thin slab is invisible */
            const double t = sl->center_n / (facing ? dn : 1.0);
            double q[3];
            v3_axpy(o, t, d, q);
            v3_sub(q, sl->center, q);
            const int in = facing & (t > BIREF_RENDER_RAY_EPS) & (t < tl->t[j]) &
                           (fabs(v3_dot(q, sl->tangent)) <= sl->half_w) & (fabs(v3_dot(q, sl->bitangent)) <= sl->half_h);
            tl->t[j] = in ? t : tl->t[j];
            tl->slab[j] = in ? i : tl->slab[j];
        }
    }
}

/* The prefilter's footprint of pixel j (footprint.c) from its neighbours' rays to the right and
 * below: the right one is the next pixel's ray, already in the tile (biref_render_camera_ray's
 * bits) except at the tile's end. */
static void tile_footprint(const biref_renderer *r, const render_tile *tl, const render_slab *sl, int j,
                           const double d[3], biref_opl_footprint *fp)
{
    double dx[3], dy[3];
    if (j + 1 < tl->n)
        for (int i = 0; i < 3; i++) dx[i] = tl->dir[i][j + 1];
    else
        biref_render_camera_ray_at(&r->cam, tl->x0 + j + 1.5, tl->y + 0.5, dx);
    biref_render_camera_ray_at(&r->cam, tl->x0 + j + 0.5, tl->y + 1.5, dy);
    biref_render_footprint_rays(r, sl, d, dx, dy, fp);
}

/* The kernel's input of every hit: the optic axis in the hit's transmission frame (the dot
 * products of biref_render_hit_frames, to the bit) and K = eta_i sin(theta) from
 * cos(theta) = |dir . normal|, clamped as the frames clamp theta (sin(acos(c)) = sqrt(1 - c^2)
 * without the two libm calls; the scalar path's K differs by a rounding). */
static void tile_hits(const biref_renderer *r, render_tile *tl)
{
    const double c_min = cos(BIREF_RENDER_THETA_MAX);
    int m = 0;
    for (int j = 0; j < tl->n; j++)
        if (tl->slab[j] >= 0) tl->px[m++] = j;
    tl->n_hits = m;
    for (int k = 0; k < m; k++) {
        const int j = tl->px[k];
        const render_slab *sl = &r->slabs[tl->slab[j]];
        const double d[3] = {tl->dir[0][j], tl->dir[1][j], tl->dir[2][j]};
        const double dn = v3_dot(d, sl->normal);
        double y[3], z[3], x[3];
        v3_scale(sl->normal, dn < 0 ? -1.0 : 1.0, y);
        v3_axpy(d, -dn, sl->normal, z);
        const double l = v3_len(z);
        if (l < 1e-9)
            memcpy(z, sl->tangent, sizeof z);
        else
            v3_scale(z, 1.0 / l, z);
        v3_cross(y, z, x);
        double c = fabs(dn);
        c = c < 1.0 ? c : 1.0;
        c = c > c_min ? c : c_min;
        const biref_slab *b = &sl->base;
        tl->in[k] = (biref_packet_hit){b->eta_o,
                                       b->eta_e,
                                       {v3_dot(sl->axis_world, x), v3_dot(sl->axis_world, y), v3_dot(sl->axis_world, z)},
                                       b->thickness_nm,
                                       b->eta_i,
                                       b->eta_i * sqrt((1.0 - c) * (1.0 + c))};
        tl->dn[k] = dn;
        if (r->prefilter) tile_footprint(r, tl, sl, j, d, &tl->fp[k]);
    }
}

static int finite3(const double v[3]) { return isfinite(v[0]) && isfinite(v[1]) && isfinite(v[2]); }

/* The slab's factors of every hit: the packet kernel, and the hits it declines one by one from
 * the frames of biref_render_hit_frames (theta through acos, as biref_render_shade_pixel). A
 * failed evaluation shows the slab as a mirror (biref_render_failed_hit). */
static void tile_integrate(const biref_renderer *r, render_tile *tl, render_tile_counts *counts)
{
    const biref_opl_footprint *fp = r->prefilter ? tl->fp : NULL;
    biref_integrate_packet_hits_footprint(r->integrator, tl->in, fp, (size_t)tl->n_hits, &r->light, tl->T, tl->R,
                                          tl->scalar);
    for (int k = 0; k < tl->n_hits; k++) {
        if (!tl->scalar[k] && finite3(tl->T[k]) && finite3(tl->R[k])) continue;
        const int j = tl->px[k];
        const render_slab *sl = &r->slabs[tl->slab[j]];
        const double d[3] = {tl->dir[0][j], tl->dir[1][j], tl->dir[2][j]};
        biref_hit_frames fr;
        biref_render_hit_frames(sl->normal, sl->tangent, sl->axis_world, &sl->base, d, &fr);
        if (tl->scalar[k] &&
            biref_integrate_hit_footprint(r->integrator, &(biref_slab_hit){fr.slab, fr.theta}, fp ? &fp[k] : NULL,
                                          &r->light, tl->T[k], tl->R[k]) == BIREF_OK)
            continue;
        biref_render_failed_hit(r, &fr, tl->T[k], tl->R[k]);
        counts->fallbacks++;
    }
}

/* Background pixels: the radiance along the camera ray through the filter (biref_render_background;
 * its factor is the same for every ray under the paper's light). Slab pixels: transmitted light
 * from behind along the ray and reflected light from the mirror direction, both from the hit
 * point (biref_render_hit_colour). */
static void tile_colours(const biref_renderer *r, render_tile *tl)
{
    const double *o = r->cam.origin;
    for (int j = 0; j < tl->n; j++) {
        if (tl->slab[j] >= 0) continue;
        const double d[3] = {tl->dir[0][j], tl->dir[1][j], tl->dir[2][j]};
        double L[3];
        render_radiance(r, o, d, L);
        for (int i = 0; i < 3; i++) tl->xyz[i][j] = L[i] * r->passthrough_sp;
    }
    for (int k = 0; k < tl->n_hits; k++) {
        const int j = tl->px[k];
        const render_slab *sl = &r->slabs[tl->slab[j]];
        const double d[3] = {tl->dir[0][j], tl->dir[1][j], tl->dir[2][j]};
        double hp[3], mirror[3], Lb[3], Lf[3];
        v3_axpy(o, tl->t[j], d, hp);
        v3_axpy(d, -2.0 * tl->dn[k], sl->normal, mirror);
        render_radiance(r, hp, d, Lb);
        render_radiance(r, hp, mirror, Lf);
        /* Band-wise products: exact for grey light, an approximation for coloured light. */
        for (int i = 0; i < 3; i++) tl->xyz[i][j] = tl->T[k][i] * Lb[i] + tl->R[k][i] * Lf[i];
    }
}

/* The colours into the float image; a value that is not finite or beyond float range is stored
 * as 0 and counted (as the scalar path's store). */
static void tile_store(const biref_renderer *r, const render_tile *tl, float *row, render_tile_counts *counts)
{
    float *px = row + 3 * (size_t)tl->x0;
    for (int j = 0; j < tl->n; j++)
        for (int i = 0; i < 3; i++) {
            const double v = tl->xyz[i][j] * r->exposure;
            const int ok = isfinite(v) && fabs(v) <= FLT_MAX;
            counts->nonfinite += !ok;
            px[3 * j + i] = (float)(ok ? v : 0.0);
        }
}

void biref_render_tile(const biref_renderer *r, render_tile *tl, int x0, int y, int n, float *row,
                       render_tile_counts *counts)
{
    tl->x0 = x0;
    tl->y = y;
    tl->n = n;
    tile_rays(&r->cam, tl);
    tile_nearest_slabs(r, tl);
    tile_hits(r, tl);
    counts->slab_pixels += tl->n_hits;
    tile_integrate(r, tl, counts);
    tile_colours(r, tl);
    tile_store(r, tl, row, counts);
}
