/* The renderer's tiles for AVX-512F: 8 lanes of double per vector. Compiled without contracted multiply-adds
 * (CMakeLists.txt), so every instruction set gives the same bits; called only when the CPU has it
 * (render_tile.c). */
#define TILE_FN biref_render_tile_avx512
#include "render/render_tile_lanes.inc"
