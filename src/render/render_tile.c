/* The choice of the tiles' instruction set (render_tile.h). */
#include "render/render_tile.h"
#include "spectral/analytic_packet.h"

int biref_render_tile_isa(void)
{
    const biref_simd_isa isa = biref_simd_isa_choose();
    return isa == BIREF_SIMD_SCALAR ? BIREF_SIMD_BASELINE : isa;
}

void biref_render_tile(const biref_renderer *r, render_tile *tile, render_tile_counts *counts)
{
    switch (r->tile_isa) {
    case BIREF_SIMD_AVX512: biref_render_tile_avx512(r, tile, counts); break;
    case BIREF_SIMD_AVX2: biref_render_tile_avx2(r, tile, counts); break;
    default: biref_render_tile_baseline(r, tile, counts); break;
    }
}
