/* The renderer's tiles for any x86-64 (or other) CPU: generic code, SSE2 vectors on x86-64. Compiled without contracted multiply-adds
 * (CMakeLists.txt), so every instruction set gives the same bits; called only when the CPU has it
 * (render_tile.c). */
#define TILE_FN biref_render_tile_baseline
#include "render/render_tile_lanes.inc"
