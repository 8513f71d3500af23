/* A tile: up to RENDER_TILE samples of one row of pixels (one per pixel, or the K x K samples of
 * supersampled pixels), shaded as structure of arrays. It is the renderer's one pixel path: camera
 * rays, the nearest-slab test, the slab hits' frames (ray_frame.h, shared with the shader's
 * biref_shading_frames), the radiance look-ups and the colours run in branch-free loops across the
 * samples (which the compiler vectorises); the hits go to the shader together (the analytic
 * method's packet kernel, each hit with its light resolved in its frames when the light is
 * world-fixed: packet_light.h), and the hits it declines to the shader one by one from the same
 * frames.
 *
 * The hits are compact (hit k belongs to sample px[k]; hits on the same slab are consecutive) so
 * that a per-hit input the kernel may need, such as a prefilter footprint from the neighbouring
 * rays, is one more array indexed by k. */
#ifndef BIREF_RENDER_TILE_H
#define BIREF_RENDER_TILE_H

#include "render/render_internal.h"
#include "spectral/integrator_internal.h"

/* Enough samples for several packets of the widest kernel, small enough for a thread's stack. */
#define RENDER_TILE 32

/* Rays of a tile, by component: from[c][k] + t dir[c][k]. */
typedef double render_lanes3[3][RENDER_TILE];

typedef struct {
    int n;                 /* samples 0 .. n - 1 */
    double fx[RENDER_TILE], fy[RENDER_TILE]; /* their image points, in pixels (pixel (x, y) spans [x, x + 1)) */
    double h;              /* the prefilter's step to the neighbouring samples, in pixels (1 / K) */
    /* A row of pixel centres, one sample per pixel (NULL otherwise): the samples' image-plane offsets
     * sx (the renderer's column table from the first sample's column) and the row's sy, so that the
     * rays need no division by the image size; fx and fy are still filled in for the footprints. */
    const double *sx;
    double sy;
    /* NULL, or one sample per pixel: sample j's colour times the exposure is stored as pixel j's
     * float XYZ from out (a value not finite or beyond float range as 0, counted as nonfinite). */
    float *out;
    render_lanes3 dir;     /* unit camera rays */
    double t[RENDER_TILE];    /* distance to the nearest slab */
    double slab[RENDER_TILE]; /* its index in the renderer, -1: none (a double to vectorise with t) */
    /* Background samples, compact: background sample k is sample bg[k]. */
    int n_bg, bg[RENDER_TILE];
    /* Slab hits, compact and grouped by slab: hit k is sample px[k]; the hits on slab run_slab[i]
     * are run_start[i] .. run_start[i + 1] - 1. */
    int n_hits, px[RENDER_TILE], n_runs, run_slab[RENDER_TILE], run_start[RENDER_TILE + 1];
    render_lanes3 from, hdir, mirror; /* background: camera origin and ray; hits: hit point, ray, mirror */
    render_lanes3 x;                  /* the transmission frame's x axis (s of both waves) */
    double c[RENDER_TILE];            /* cos(theta), clamped as the frames clamp theta */
    /* The kernel's input, field by field (biref_packet_hits): the slab's constants, the optic axis in
     * the hit's transmission frame and K. */
    double in[BIREF_PACKET_HIT_FIELDS][RENDER_TILE];
    biref_packet_hit_light light[RENDER_TILE]; /* each hit's light, when the shader's is resolved per hit */
    double T[RENDER_TILE][3], R[RENDER_TILE][3];
    unsigned char scalar[RENDER_TILE];
    biref_opl_footprint fp[RENDER_TILE]; /* with the prefilter: hit k's footprint (footprint_lanes.inc) */
    render_lanes3 Lb, Lf;             /* radiance from behind (or of the background) and from the mirror */
    render_lanes3 xyz;                /* the samples' colours */
} render_tile;

/* Counters of a tile's samples, summed by the row loop. */
typedef struct {
    long slab_pixels, fallbacks, nonfinite;
} render_tile_counts;

/* Shades the tile's samples (n, fx, fy, h, sx, sy and out filled in) into tile->xyz (and out), with point or prefiltered
 * look-ups, with the instruction set the renderer chose (r->tile_isa; every one gives the same
 * bits); a sample hit a slab when tile->slab[j] >= 0. counts->fallbacks counts the hits whose
 * evaluation failed (shown as a mirror). */
void biref_render_tile(const biref_renderer *r, render_tile *tile, render_tile_counts *counts);
/* The instruction set for the tiles: AVX-512 or AVX2 when biref_simd_isa_choose picks it (which
 * honours BIREF_SIMD), else the baseline. */
int biref_render_tile_isa(void);

void biref_render_tile_baseline(const biref_renderer *r, render_tile *tile, render_tile_counts *counts);
void biref_render_tile_avx2(const biref_renderer *r, render_tile *tile, render_tile_counts *counts);
void biref_render_tile_avx512(const biref_renderer *r, render_tile *tile, render_tile_counts *counts);

#endif
