/* A tile: a row segment of up to RENDER_TILE pixels with one sample each, shaded as structure of
 * arrays. Camera rays, the nearest-slab test, the slab hits' frames, the radiance look-ups and the
 * colours run in branch-free loops across the tile's pixels (which the compiler vectorises); the
 * hits go to the analytic method's packet kernel together. Every pixel's colour is
 * biref_render_shade_pixel's (point look-ups, or with the prefilter each phase integral averaged
 * over the pixel's footprint): the geometry and radiance to the bit, the kernel's input
 * K = eta_i sin(theta) from cos(theta) instead of through acos and sin (a rounding apart), and hits
 * the kernel declines through the scalar path as before.
 *
 * The hits are compact (hit k belongs to pixel px[k]; hits on the same slab are consecutive) so
 * that a per-hit input the kernel may need, such as a prefilter footprint from the neighbouring
 * rays, is one more array indexed by k. */
#ifndef BIREF_RENDER_TILE_H
#define BIREF_RENDER_TILE_H

#include "render/render_internal.h"
#include "spectral/integrator_internal.h"

/* Enough hits for several packets of the widest kernel, small enough for a thread's stack. */
#define RENDER_TILE 32

/* Rays of a tile, by component: from[c][k] + t dir[c][k]. */
typedef double render_lanes3[3][RENDER_TILE];

typedef struct {
    int x0, y, n;         /* pixels x0 .. x0 + n - 1 of row y */
    render_lanes3 dir;    /* unit camera rays */
    double t[RENDER_TILE];    /* distance to the nearest slab */
    double slab[RENDER_TILE]; /* its index in the renderer, -1: none (a double to vectorise with t) */
    /* Background pixels, compact: background pixel k is pixel bg[k]. */
    int n_bg, bg[RENDER_TILE];
    /* Slab hits, compact and grouped by slab: hit k is pixel px[k]; the hits on slab run_slab[i]
     * are run_start[i] .. run_start[i + 1] - 1. */
    int n_hits, px[RENDER_TILE], n_runs, run_slab[RENDER_TILE], run_start[RENDER_TILE + 1];
    render_lanes3 from, hdir, mirror; /* background: camera origin and ray; hits: hit point, ray, mirror */
    double dn[RENDER_TILE];           /* hit ray . slab normal */
    render_lanes3 axis;               /* optic axis in the hit's transmission frame */
    double K[RENDER_TILE];            /* eta_i sin(theta) */
    biref_packet_hit in[RENDER_TILE]; /* the kernel's input */
    double T[RENDER_TILE][3], R[RENDER_TILE][3];
    unsigned char scalar[RENDER_TILE];
    biref_opl_footprint fp[RENDER_TILE]; /* with the prefilter: hit k's footprint (footprint.c) */
    render_lanes3 Lb, Lf;             /* radiance from behind (or of the background) and from the mirror */
    render_lanes3 xyz;                /* the pixels' colours */
} render_tile;

/* Counters of a tile's pixels, summed by the row loop. */
typedef struct {
    long slab_pixels, fallbacks, nonfinite;
} render_tile_counts;

/* Shades pixels x0 .. x0 + n - 1 (n <= RENDER_TILE) of row y into row (3 floats a pixel, row y's
 * start), one sample each with point or prefiltered look-ups under the paper's light (no
 * world-fixed polarizer), with the instruction set the renderer chose (r->tile_isa; every one gives the same bits). */
void biref_render_tile(const biref_renderer *r, render_tile *tile, int x0, int y, int n, float *row,
                       render_tile_counts *counts);
/* The instruction set for the tiles: AVX-512 or AVX2 when biref_simd_isa_choose picks it (which
 * honours BIREF_SIMD), else the baseline. */
int biref_render_tile_isa(void);

void biref_render_tile_baseline(const biref_renderer *r, render_tile *tile, int x0, int y, int n, float *row,
                                render_tile_counts *counts);
void biref_render_tile_avx2(const biref_renderer *r, render_tile *tile, int x0, int y, int n, float *row,
                            render_tile_counts *counts);
void biref_render_tile_avx512(const biref_renderer *r, render_tile *tile, int x0, int y, int n, float *row,
                              render_tile_counts *counts);

#endif
