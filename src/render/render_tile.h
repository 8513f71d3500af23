/* A tile: a row segment of up to RENDER_TILE pixels with one sample each, shaded as structure of
 * arrays. Camera rays, the nearest-slab test, the slab hits' frames, the radiance look-ups and the
 * colours run in loops across the tile's pixels; the hits go to the analytic method's packet
 * kernel together. Every pixel's colour is biref_render_shade_pixel's (point look-ups, or with
 * the prefilter each phase integral averaged over the pixel's footprint): the
 * geometry to the bit, the kernel's input K = eta_i sin(theta) from cos(theta) instead of through
 * acos and sin (a rounding apart), and hits the kernel declines through the scalar path as before.
 *
 * The hits are compact (hit k belongs to pixel px[k]) so that a per-hit input the kernel may need,
 * such as a prefilter footprint from the neighbouring rays, is one more array indexed by k. */
#ifndef BIREF_RENDER_TILE_H
#define BIREF_RENDER_TILE_H

#include "render/render_internal.h"
#include "spectral/integrator_internal.h"

/* Enough hits for several packets of the widest kernel, small enough for a thread's stack. */
#define RENDER_TILE 32

typedef struct {
    int x0, y, n;                     /* pixels x0 .. x0 + n - 1 of row y */
    double dir[3][RENDER_TILE];       /* unit camera rays, by component */
    double t[RENDER_TILE];            /* distance to the nearest slab */
    int slab[RENDER_TILE];            /* its index in the renderer, -1: none */
    /* The slab hits, compact: hit k is pixel px[k]. */
    int n_hits, px[RENDER_TILE];
    double dn[RENDER_TILE];           /* camera ray . slab normal */
    biref_packet_hit in[RENDER_TILE]; /* the slab in the hit's transmission frame, K */
    double T[RENDER_TILE][3], R[RENDER_TILE][3];
    unsigned char scalar[RENDER_TILE];
    biref_opl_footprint fp[RENDER_TILE]; /* with the prefilter: hit k's footprint (footprint.c) */
    double xyz[3][RENDER_TILE]; /* the pixels' colours, by component */
} render_tile;

/* Counters of a tile's pixels, summed by the row loop. */
typedef struct {
    long slab_pixels, fallbacks, nonfinite;
} render_tile_counts;

/* Shades pixels x0 .. x0 + n - 1 (n <= RENDER_TILE) of row y into row (3 floats a pixel, row y's
 * start), one sample each with point or prefiltered look-ups under the paper's light (no
 * world-fixed polarizer). */
void biref_render_tile(const biref_renderer *r, render_tile *tile, int x0, int y, int n, float *row,
                       render_tile_counts *counts);

#endif
