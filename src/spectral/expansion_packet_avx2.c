/* The expansion's packet kernel for AVX2 + FMA: 4 lanes of double, called only when the CPU has both (expansion_packet.h). */
#include "spectral/simd/avx2.h"
#define EXPANSION_HITS_FN biref_expansion_hits_avx2
#include "spectral/expansion_packet_kernel.inc"
