/* The expansion's packet kernel for AVX-512F: 8 lanes of double, called only when the CPU has it (expansion_packet.h). */
#include "spectral/simd/avx512.h"
#define EXPANSION_HITS_FN biref_expansion_hits_avx512
#include "spectral/expansion_packet_kernel.inc"
