/* The expansion's packet kernel per instruction set (expansion_packet.h). */
#include "spectral/expansion_packet.h"

biref_expansion_hits_kernel biref_simd_expansion_kernel(biref_simd_isa isa)
{
    switch (isa) {
    case BIREF_SIMD_BASELINE: return biref_expansion_hits_baseline;
    case BIREF_SIMD_AVX2: return biref_expansion_hits_avx2;
    case BIREF_SIMD_AVX512: return biref_expansion_hits_avx512;
    default: return NULL;
    }
}
